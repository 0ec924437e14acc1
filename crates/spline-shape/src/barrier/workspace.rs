//! The solver's reused memory: the constraint Jacobian as sparse rows written in place, the
//! vectors and matrices of one Newton step, kept between steps and between centring steps so
//! that an iteration allocates nothing once the buffers have their sizes.

use nalgebra::{DMatrix, DVector};
use nalgebra_sparse::CsrMatrix;
use std::cell::RefCell;

use super::newton::SparseNewton;

/// A sparse matrix stored by rows, filled one row at a time into buffers that keep their
/// capacity: the form in which [`BarrierProblem::constraint_jacobian_into`] writes the
/// constraints' Jacobian without allocating (its pattern may change between calls).
///
/// [`BarrierProblem::constraint_jacobian_into`]: super::BarrierProblem::constraint_jacobian_into
///
/// ```
/// use spline_shape::barrier::SparseRows;
/// let mut rows = SparseRows::new(3);
/// rows.push(0, 1.0);
/// rows.push(2, -1.0);
/// rows.end_row();
/// rows.end_row(); // an empty row
/// assert_eq!(rows.nrows(), 2);
/// assert_eq!(rows.row(0), (&[0, 2][..], &[1.0, -1.0][..]));
/// let mut out = [0.0; 3];
/// rows.transpose_mul_add(&[2.0, 5.0], &mut out);
/// assert_eq!(out, [2.0, 0.0, -2.0]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SparseRows {
    ncols: usize,
    offsets: Vec<usize>,
    cols: Vec<usize>,
    vals: Vec<f64>,
}

impl Default for SparseRows {
    fn default() -> Self {
        Self::new(0)
    }
}

impl SparseRows {
    /// No rows, `ncols` columns.
    #[must_use]
    pub fn new(ncols: usize) -> Self {
        Self {
            ncols,
            offsets: vec![0],
            cols: Vec::new(),
            vals: Vec::new(),
        }
    }

    /// Removes every row (the buffers keep their capacity) and sets the number of columns.
    pub fn clear(&mut self, ncols: usize) {
        self.ncols = ncols;
        self.offsets.clear();
        self.offsets.push(0);
        self.cols.clear();
        self.vals.clear();
    }

    /// Appends the entry `(col, value)` to the current row.
    ///
    /// # Panics
    /// In debug builds, if `col` is not below the number of columns.
    pub fn push(&mut self, col: usize, value: f64) {
        debug_assert!(col < self.ncols, "column {col} of {}", self.ncols);
        self.cols.push(col);
        self.vals.push(value);
    }

    /// Appends a row with the columns `cols`, its values zero, and returns the values to be
    /// filled.
    ///
    /// # Panics
    /// In debug builds, if a column is not below the number of columns.
    pub fn push_row(&mut self, cols: &[usize]) -> &mut [f64] {
        debug_assert!(cols.iter().all(|&c| c < self.ncols));
        let start = self.vals.len();
        self.cols.extend_from_slice(cols);
        self.vals.resize(start + cols.len(), 0.0);
        self.end_row();
        &mut self.vals[start..]
    }

    /// Ends the current row.
    pub fn end_row(&mut self) {
        self.offsets.push(self.cols.len());
    }

    /// Appends the rows of `m` (whose number of columns must be this one's).
    ///
    /// # Panics
    /// In debug builds, if the numbers of columns differ.
    pub fn extend_from_csr(&mut self, m: &CsrMatrix<f64>) {
        debug_assert_eq!(m.ncols(), self.ncols);
        for row in m.row_iter() {
            self.cols.extend_from_slice(row.col_indices());
            self.vals.extend_from_slice(row.values());
            self.end_row();
        }
    }

    /// The number of complete rows.
    #[must_use]
    pub fn nrows(&self) -> usize {
        self.offsets.len() - 1
    }

    /// The number of columns.
    #[must_use]
    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// The columns and values of row `i`.
    ///
    /// # Panics
    /// If `i` is not below [`SparseRows::nrows`].
    #[must_use]
    pub fn row(&self, i: usize) -> (&[usize], &[f64]) {
        let (a, b) = (self.offsets[i], self.offsets[i + 1]);
        (&self.cols[a..b], &self.vals[a..b])
    }

    /// The rows in order, as `(columns, values)`.
    pub fn rows(&self) -> impl Iterator<Item = (&[usize], &[f64])> + '_ {
        self.offsets
            .windows(2)
            .map(|w| (&self.cols[w[0]..w[1]], &self.vals[w[0]..w[1]]))
    }

    /// The columns and values of all rows, and the row offsets, mutably: for sorting the
    /// entries of a row in place.
    pub fn parts_mut(&mut self) -> (&[usize], &mut [usize], &mut [f64]) {
        (&self.offsets, &mut self.cols, &mut self.vals)
    }

    /// `out += Aᵀ w`, summed row after row (the order of a transposed CSR product).
    ///
    /// # Panics
    /// If `w` is shorter than the number of rows or `out` than the number of columns.
    pub fn transpose_mul_add(&self, w: &[f64], out: &mut [f64]) {
        for ((cols, vals), &wi) in self.rows().zip(w) {
            for (&j, &v) in cols.iter().zip(vals) {
                out[j] += v * wi;
            }
        }
    }

    /// As a CSR matrix (allocates; for tests and conversions). Rows must have increasing
    /// column indices.
    ///
    /// # Panics
    /// If a row's columns are not increasing.
    #[must_use]
    pub fn to_csr(&self) -> CsrMatrix<f64> {
        CsrMatrix::try_from_csr_data(
            self.nrows(),
            self.ncols,
            self.offsets.clone(),
            self.cols.clone(),
            self.vals.clone(),
        )
        .expect("rows of increasing columns")
    }
}

/// Everything one centring step needs, sized once per problem shape.
#[derive(Default)]
pub(crate) struct Workspace {
    pub(super) n: usize,
    pub(super) m: usize,
    /// Constraint values at the iterate, and at a trial point.
    pub(super) c: DVector<f64>,
    pub(super) c_trial: DVector<f64>,
    /// `1 / (−f_i)`.
    pub(super) inv: DVector<f64>,
    /// `∇f0` and the barrier gradient.
    pub(super) g0: DVector<f64>,
    pub(super) gradient: DVector<f64>,
    pub(super) jac: SparseRows,
    pub(super) candidate: DVector<f64>,
    pub(super) direction: DVector<f64>,
    /// Sparse forms of `∇²f0` and `Σ wᵢ ∇²fᵢ` ([`super::BarrierProblem::objective_hessian_into`]).
    pub(super) objective_hessian: Option<CsrMatrix<f64>>,
    pub(super) curvature: Option<CsrMatrix<f64>>,
    /// Dense path: the local metric, the Hessian, `L` of the metric (lower triangle, zeros
    /// above) and its transpose, and the storage of the two Cholesky factorisations.
    pub(super) metric: DMatrix<f64>,
    pub(super) hessian: DMatrix<f64>,
    pub(super) l: DMatrix<f64>,
    pub(super) lt: DMatrix<f64>,
    pub(super) factor_storage: Option<DMatrix<f64>>,
    pub(super) hessian_storage: Option<DMatrix<f64>>,
    pub(super) scaled_gradient: DVector<f64>,
    pub(super) y: DVector<f64>,
    /// The trust-region step: `L⁻¹ H`, `L⁻¹ H L⁻ᵀ` before and after symmetrisation, the
    /// transposed eigenvectors, the storage handed to the eigendecomposition, `Qᵀ g`, `Λ Qᵀ y`
    /// and `H̃ y`.
    pub(super) left: DMatrix<f64>,
    pub(super) scaled: DMatrix<f64>,
    pub(super) symmetric: DMatrix<f64>,
    pub(super) qt: DMatrix<f64>,
    pub(super) eigen_storage: Option<DMatrix<f64>>,
    pub(super) gamma: DVector<f64>,
    pub(super) weighted: DVector<f64>,
    pub(super) hy: DVector<f64>,
    /// Sparse path: the Newton matrix on a fixed pattern and its factorisation.
    pub(super) newton: Option<SparseNewton>,
}

/// Resizes `v` to `len` entries (reallocating only when the size changes).
fn fit_vector(v: &mut DVector<f64>, len: usize) {
    if v.len() != len {
        *v = DVector::zeros(len);
    }
}

fn fit_matrix(a: &mut DMatrix<f64>, n: usize) {
    if a.nrows() != n || a.ncols() != n {
        *a = DMatrix::zeros(n, n);
    }
}

impl Workspace {
    /// Sizes the vectors for `n` unknowns and `m` constraints, and the dense matrices when
    /// `dense`.
    pub(super) fn prepare(&mut self, n: usize, m: usize, dense: bool) {
        for v in [
            &mut self.g0,
            &mut self.gradient,
            &mut self.candidate,
            &mut self.direction,
            &mut self.scaled_gradient,
            &mut self.y,
            &mut self.gamma,
            &mut self.weighted,
            &mut self.hy,
        ] {
            fit_vector(v, n);
        }
        for v in [&mut self.c, &mut self.c_trial, &mut self.inv] {
            fit_vector(v, m);
        }
        if dense {
            for a in [
                &mut self.metric,
                &mut self.hessian,
                &mut self.l,
                &mut self.lt,
                &mut self.left,
                &mut self.scaled,
                &mut self.symmetric,
                &mut self.qt,
            ] {
                fit_matrix(a, n);
            }
            for a in [
                &mut self.factor_storage,
                &mut self.hessian_storage,
                &mut self.eigen_storage,
            ] {
                if a.as_ref().is_some_and(|a| a.nrows() != n) {
                    *a = None;
                }
            }
        }
        if self.n != n || self.m != m {
            self.newton = None;
            self.objective_hessian = None;
            self.curvature = None;
        }
        self.n = n;
        self.m = m;
    }
}

thread_local! {
    /// The trust-region subproblems solved by an eigendecomposition on this thread.
    static EIGENDECOMPOSITIONS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Counts one eigendecomposition of the trust-region subproblem on this thread.
pub(super) fn count_eigendecomposition() {
    EIGENDECOMPOSITIONS.with(|c| c.set(c.get() + 1));
}

/// The number of trust-region subproblems the dense solver has solved by an
/// eigendecomposition on this thread so far (a diagnostic). Every other part of a Newton
/// step reuses the solver's workspace; nalgebra's symmetric eigendecomposition has no
/// in-place form and allocates its own work vectors and eigenvectors (5 blocks in nalgebra
/// 0.35), so the allocations of a solve grow only by 5 per such step.
///
/// ```
/// use spline_shape::barrier::trust_region_eigendecompositions;
/// let before = trust_region_eigendecompositions();
/// // … solve …
/// assert!(trust_region_eigendecompositions() >= before);
/// ```
#[must_use]
pub fn trust_region_eigendecompositions() -> usize {
    EIGENDECOMPOSITIONS.with(std::cell::Cell::get)
}

thread_local! {
    /// The workspace of the solver on this thread: kept between calls, so that the centring
    /// steps of one solve (and the solves of one eraser run) reuse the same memory.
    static WORKSPACE: RefCell<Workspace> = RefCell::new(Workspace::default());
}

/// The largest sparse Newton matrix (entries) the thread's workspace keeps after a solve;
/// larger ones are released (the dense matrices have at most 400² entries).
const KEEP_ENTRIES: usize = 1 << 20;

/// Runs `f` with this thread's workspace (a fresh one if it is in use, e.g. when a problem's
/// methods call the solver themselves).
pub(crate) fn with_workspace<R>(f: impl FnOnce(&mut Workspace) -> R) -> R {
    WORKSPACE.with(|cell| match cell.try_borrow_mut() {
        Ok(mut ws) => {
            let out = f(&mut ws);
            if ws
                .newton
                .as_ref()
                .is_some_and(|m| m.base.len() > KEEP_ENTRIES)
            {
                *ws = Workspace::default();
            }
            out
        }
        Err(_) => f(&mut Workspace::default()),
    })
}

/// Adds `scale · h` to the dense matrix `out` (the same shape).
pub(crate) fn add_sparse(out: &mut DMatrix<f64>, h: &CsrMatrix<f64>, scale: f64) {
    for (i, j, v) in h.triplet_iter() {
        out[(i, j)] += scale * v;
    }
}
