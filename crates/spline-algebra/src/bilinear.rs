//! Sparse bilinear maps (third-order tensors): products of splines, their constant second
//! derivatives, and Hessians.

use crate::sparse::{RowAccumulator, check_len};
use nalgebra_sparse::CsrMatrix;
use spline_core::{Error, ErrorKind, Result, Scalar};

/// A sparse bilinear map $B : \mathbb R^{m} \times \mathbb R^{n} \to \mathbb R^{r}$,
/// $B(x, y)_k = \sum_{(j, l)} b_{kjl}\\, x_j\\, y_l$, stored row by row (one row per output).
///
/// It is the structure of every product in this crate: the product of two splines is
/// `B(a, b)`, its Jacobians are `B(·, b)` and `B(a, ·)`, and `B` itself is the constant
/// second derivative (thesis (5.35)–(5.37)). A quadratic function `q(x) = B(x, x)` has the
/// constant Hessian [`SparseBilinear::symmetrized`]. The same type stores Hessians that depend
/// on the input (row `k` is the Hessian of output `k`).
///
/// ```
/// use spline_algebra::SparseBilinear;
/// // One output: x0·y1 + 2 x1·y0.
/// let b = SparseBilinear::from_rows(2, 2, vec![vec![(0, 1, 1.0), (1, 0, 2.0)]])?;
/// assert_eq!(b.apply(&[1.0, 3.0], &[5.0, 7.0])?, vec![7.0 + 30.0]);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SparseBilinear<T> {
    left_dim: usize,
    right_dim: usize,
    offsets: Vec<usize>,
    entries: Vec<(usize, usize, T)>,
}

/// Sorts `(j, l, v)` triplets and sums duplicates; drops exact zeros.
fn normalize<T: Scalar>(row: &mut Vec<(usize, usize, T)>) {
    row.sort_unstable_by_key(|&(j, l, _)| (j, l));
    let mut w = 0;
    for r in 0..row.len() {
        let (j, l, v) = row[r];
        if w > 0 && row[w - 1].0 == j && row[w - 1].1 == l {
            row[w - 1].2 += v;
        } else {
            row[w] = (j, l, v);
            w += 1;
        }
    }
    row.truncate(w);
    row.retain(|e| e.2 != T::zero());
}

impl<T: Scalar> SparseBilinear<T> {
    /// A bilinear map from its rows of `(j, l, b_kjl)` triplets (any order; duplicates are
    /// summed).
    ///
    /// # Errors
    /// [`ErrorKind::IndexOutOfRange`] if an index is out of range (the first offending
    /// index as [`spline_core::Error::index`]).
    pub fn from_rows(
        left_dim: usize,
        right_dim: usize,
        rows: Vec<Vec<(usize, usize, T)>>,
    ) -> Result<Self> {
        for (k, row) in rows.iter().enumerate() {
            if let Some(&(j, l, _)) = row
                .iter()
                .find(|&&(j, l, _)| j >= left_dim || l >= right_dim)
            {
                return Err(Error::new(
                    ErrorKind::IndexOutOfRange,
                    format!(
                        "row {k}: entry ({j}, {l}) outside the {left_dim}×{right_dim} argument range"
                    ),
                )
                .with_index(if j >= left_dim { j } else { l }));
            }
        }
        Ok(Self::from_rows_unchecked(left_dim, right_dim, rows))
    }

    pub(crate) fn from_rows_unchecked(
        left_dim: usize,
        right_dim: usize,
        rows: Vec<Vec<(usize, usize, T)>>,
    ) -> Self {
        let mut rows = rows.into_iter();
        let n = rows.len();
        Self::build(left_dim, right_dim, n, |_, row| {
            row.extend(rows.next().into_iter().flatten());
        })
    }

    /// Builds row by row into flat storage: `fill(k, row)` pushes the entries of output `k`
    /// (any order, duplicates summed) into a reused buffer.
    pub(crate) fn build(
        left_dim: usize,
        right_dim: usize,
        nrows: usize,
        mut fill: impl FnMut(usize, &mut Vec<(usize, usize, T)>),
    ) -> Self {
        let mut offsets = Vec::with_capacity(nrows + 1);
        let mut entries = Vec::new();
        let mut row = Vec::new();
        offsets.push(0);
        for k in 0..nrows {
            row.clear();
            fill(k, &mut row);
            normalize(&mut row);
            entries.extend_from_slice(&row);
            offsets.push(entries.len());
        }
        Self {
            left_dim,
            right_dim,
            offsets,
            entries,
        }
    }

    /// Flat storage whose rows are already sorted by `(j, l)` without duplicates.
    pub(crate) fn from_sorted_parts(
        left_dim: usize,
        right_dim: usize,
        offsets: Vec<usize>,
        entries: Vec<(usize, usize, T)>,
    ) -> Self {
        debug_assert_eq!(*offsets.last().expect("offsets"), entries.len());
        Self {
            left_dim,
            right_dim,
            offsets,
            entries,
        }
    }

    /// The zero map with `rows` outputs.
    #[must_use]
    pub fn zeros(rows: usize, left_dim: usize, right_dim: usize) -> Self {
        Self {
            left_dim,
            right_dim,
            offsets: vec![0; rows + 1],
            entries: Vec::new(),
        }
    }

    /// Number of outputs.
    #[must_use]
    pub fn nrows(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Dimension of the first argument.
    #[must_use]
    pub fn left_dim(&self) -> usize {
        self.left_dim
    }

    /// Dimension of the second argument.
    #[must_use]
    pub fn right_dim(&self) -> usize {
        self.right_dim
    }

    /// Number of stored entries.
    #[must_use]
    pub fn nnz(&self) -> usize {
        self.entries.len()
    }

    /// The entries `(j, l, b_kjl)` of output `k`, sorted by `(j, l)`.
    ///
    /// # Panics
    /// If `k >= nrows()`.
    #[must_use]
    pub fn row(&self, k: usize) -> &[(usize, usize, T)] {
        &self.entries[self.offsets[k]..self.offsets[k + 1]]
    }

    /// The slice of output `k` as a `left_dim × right_dim` sparse matrix (for a Hessian: the
    /// Hessian matrix of output `k`).
    ///
    /// # Panics
    /// If `k >= nrows()`.
    #[must_use]
    pub fn matrix(&self, k: usize) -> CsrMatrix<T> {
        let mut rows = vec![Vec::new(); self.left_dim];
        for &(j, l, v) in self.row(k) {
            rows[j].push((l, v));
        }
        crate::sparse::csr_from_rows(self.right_dim, rows)
    }

    /// $B(x, y)$.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] if the argument lengths are wrong.
    pub fn apply(&self, x: &[T], y: &[T]) -> Result<Vec<T>> {
        check_len("first argument", self.left_dim, x.len())?;
        check_len("second argument", self.right_dim, y.len())?;
        Ok(self.apply_unchecked(x, y))
    }

    pub(crate) fn apply_unchecked(&self, x: &[T], y: &[T]) -> Vec<T> {
        (0..self.nrows())
            .map(|k| {
                self.row(k)
                    .iter()
                    .fold(T::zero(), |acc, &(j, l, v)| acc + v * x[j] * y[l])
            })
            .collect()
    }

    /// The Jacobian with respect to the first argument, $\partial B(x, y)/\partial x =
    /// B(\cdot, y)$: an `nrows × left_dim` sparse matrix.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless `y` has `right_dim` entries.
    pub fn jacobian_left(&self, y: &[T]) -> Result<CsrMatrix<T>> {
        check_len("second argument", self.right_dim, y.len())?;
        Ok(self.contract(y, true))
    }

    /// The Jacobian with respect to the second argument, $B(x, \cdot)$: `nrows × right_dim`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless `x` has `left_dim` entries.
    pub fn jacobian_right(&self, x: &[T]) -> Result<CsrMatrix<T>> {
        check_len("first argument", self.left_dim, x.len())?;
        Ok(self.contract(x, false))
    }

    pub(crate) fn contract(&self, fixed: &[T], keep_left: bool) -> CsrMatrix<T> {
        let ncols = if keep_left {
            self.left_dim
        } else {
            self.right_dim
        };
        let mut acc = RowAccumulator::new(ncols);
        let mut offsets = Vec::with_capacity(self.nrows() + 1);
        let mut cols = Vec::new();
        let mut values = Vec::new();
        offsets.push(0);
        for k in 0..self.nrows() {
            for &(j, l, v) in self.row(k) {
                if keep_left {
                    acc.add(j, v * fixed[l]);
                } else {
                    acc.add(l, v * fixed[j]);
                }
            }
            acc.flush(&mut cols, &mut values);
            offsets.push(cols.len());
        }
        CsrMatrix::try_from_csr_data(self.nrows(), ncols, offsets, cols, values)
            .expect("valid contraction")
    }

    /// The map with its arguments swapped, $(x, y) \mapsto B(y, x)$.
    #[must_use]
    pub fn swapped(&self) -> Self {
        Self::build(self.right_dim, self.left_dim, self.nrows(), |k, row| {
            row.extend(self.row(k).iter().map(|&(j, l, v)| (l, j, v)));
        })
    }

    /// $B + B^{\mathsf T}$ (arguments swapped): the constant Hessian of the quadratic function
    /// $x \mapsto B(x, x)$.
    ///
    /// # Errors
    /// [`ErrorKind::DimensionMismatch`] unless both arguments have the same dimension.
    pub fn symmetrized(&self) -> Result<Self> {
        self.check_square()?;
        Ok(Self::build(
            self.left_dim,
            self.right_dim,
            self.nrows(),
            |k, row| {
                row.extend(
                    self.row(k)
                        .iter()
                        .flat_map(|&(j, l, v)| [(j, l, v), (l, j, v)]),
                );
            },
        ))
    }

    fn check_square(&self) -> Result<()> {
        if self.left_dim == self.right_dim {
            Ok(())
        } else {
            Err(Error::new(
                ErrorKind::DimensionMismatch,
                format!(
                    "a quadratic form needs arguments of equal dimension, got {} and {}",
                    self.left_dim, self.right_dim
                ),
            ))
        }
    }

    /// For the quadratic function $q(x) = B(x, x)$: its value and its Jacobian
    /// $B(\cdot, x) + B(x, \cdot)$.
    ///
    /// # Errors
    /// [`ErrorKind::DimensionMismatch`] unless the arguments have equal dimension;
    /// [`ErrorKind::InvalidLength`] for a wrong `x`.
    pub fn quadratic(&self, x: &[T]) -> Result<(Vec<T>, CsrMatrix<T>)> {
        self.check_square()?;
        check_len("argument", self.left_dim, x.len())?;
        let value = self.apply_unchecked(x, x);
        let jac = crate::sparse::add_scaled(
            T::one(),
            &self.contract(x, true),
            T::one(),
            &self.contract(x, false),
        );
        Ok((value, jac))
    }

    /// The bilinear map $(x, y) \mapsto B(L x, R y)$ for sparse matrices `L` (`left_dim`
    /// rows) and `R` (`right_dim` rows): the chain rule on both arguments.
    ///
    /// # Errors
    /// [`ErrorKind::DimensionMismatch`] if the matrices do not match the arguments.
    pub fn compose(&self, left: &CsrMatrix<T>, right: &CsrMatrix<T>) -> Result<Self> {
        if left.nrows() != self.left_dim || right.nrows() != self.right_dim {
            return Err(Error::new(
                ErrorKind::DimensionMismatch,
                format!(
                    "cannot feed {}- and {}-row matrices into a {}×{} bilinear map",
                    left.nrows(),
                    right.nrows(),
                    self.left_dim,
                    self.right_dim
                ),
            ));
        }
        Ok(Self::build(
            left.ncols(),
            right.ncols(),
            self.nrows(),
            |k, row| {
                for &(a, b, v) in self.row(k) {
                    let la = left.row(a);
                    let rb = right.row(b);
                    for (&j, &x) in la.col_indices().iter().zip(la.values()) {
                        for (&l, &y) in rb.col_indices().iter().zip(rb.values()) {
                            row.push((j, l, v * x * y));
                        }
                    }
                }
            },
        ))
    }

    /// The bilinear map $O \cdot B$ for a sparse matrix `O` with `nrows()` columns: a linear
    /// map applied to the outputs.
    ///
    /// # Errors
    /// [`ErrorKind::DimensionMismatch`] unless `output.ncols() == nrows()`.
    pub fn then(&self, output: &CsrMatrix<T>) -> Result<Self> {
        if output.ncols() != self.nrows() {
            return Err(Error::new(
                ErrorKind::DimensionMismatch,
                format!(
                    "cannot apply a matrix with {} columns to {} outputs",
                    output.ncols(),
                    self.nrows()
                ),
            ));
        }
        Ok(Self::build(
            self.left_dim,
            self.right_dim,
            output.nrows(),
            |r, row| {
                let orow = output.row(r);
                for (&k, &w) in orow.col_indices().iter().zip(orow.values()) {
                    row.extend(self.row(k).iter().map(|&(j, l, v)| (j, l, w * v)));
                }
            },
        ))
    }

    /// $\alpha B + \beta C$.
    ///
    /// # Errors
    /// [`ErrorKind::DimensionMismatch`] if the shapes differ.
    pub fn combine(&self, alpha: T, other: &Self, beta: T) -> Result<Self> {
        if (self.nrows(), self.left_dim, self.right_dim)
            != (other.nrows(), other.left_dim, other.right_dim)
        {
            return Err(Error::new(
                ErrorKind::DimensionMismatch,
                "cannot combine bilinear maps of different shapes",
            ));
        }
        Ok(Self::build(
            self.left_dim,
            self.right_dim,
            self.nrows(),
            |k, row| {
                row.extend(self.row(k).iter().map(|&(j, l, v)| (j, l, alpha * v)));
                row.extend(other.row(k).iter().map(|&(j, l, v)| (j, l, beta * v)));
            },
        ))
    }

    /// The Kronecker product of two bilinear maps on row-major grids: output
    /// `(r, s) ↦ r · other.nrows() + s`, arguments `(j, j') ↦ j · other.left_dim() + j'`
    /// (and likewise on the right). Tensor-product splines multiply this way.
    #[must_use]
    pub fn kron(&self, other: &Self) -> Self {
        let mut rows = Vec::with_capacity(self.nrows() * other.nrows());
        for r in 0..self.nrows() {
            for s in 0..other.nrows() {
                let mut row = Vec::with_capacity(self.row(r).len() * other.row(s).len());
                for &(j, l, v) in self.row(r) {
                    for &(j2, l2, w) in other.row(s) {
                        row.push((j * other.left_dim + j2, l * other.right_dim + l2, v * w));
                    }
                }
                rows.push(row);
            }
        }
        Self::from_rows_unchecked(
            self.left_dim * other.left_dim,
            self.right_dim * other.right_dim,
            rows,
        )
    }
}
