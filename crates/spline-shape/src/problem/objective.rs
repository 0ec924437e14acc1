//! The least-squares objective of the constrained approximations: spline-fit's normal
//! equations (functions: [`LeastSquares`]; grids: [`GridLeastSquares`]), as the sparse
//! Hessian, gradient and unconstrained solution a barrier method needs. Values come from
//! the residuals of the evaluated spline (no cancellation), not from the normal equations.

use nalgebra::DVector;
use nalgebra_sparse::ops::Op;
use nalgebra_sparse::ops::serial::spmm_csr_dense;
use nalgebra_sparse::{CooMatrix, CsrMatrix};
use spline_algebra::kron;
use spline_core::{Error, ErrorKind, KnotVector, MAX_ORDER, Result};
use spline_fit::{GridLeastSquares, LeastSquares, NormalEquations};
use std::cell::RefCell;

/// The samples of the objective.
#[derive(Clone, Debug)]
enum Samples {
    /// `values[j]` at `params[j]`.
    Function {
        knots: KnotVector<f64>,
        params: Vec<f64>,
        values: Vec<f64>,
    },
    /// `values[a · vs.len() + b]` at `(us[a], vs[b])`.
    Grid {
        knots: (KnotVector<f64>, KnotVector<f64>),
        us: Vec<f64>,
        vs: Vec<f64>,
        values: Vec<f64>,
        /// The original index of each sorted grid line.
        order: (Vec<usize>, Vec<usize>),
    },
}

/// $f_0(x) = \tfrac12 \sum_j (s_x(\bar u_j) - z_j)^2 = \tfrac12 x^T G x - r^T x + c$ with
/// the Gram matrix `G` and right-hand side `r` of spline-fit's normal equations.
#[derive(Clone, Debug)]
pub(crate) struct LeastSquaresObjective {
    gram: CsrMatrix<f64>,
    rhs: DVector<f64>,
    samples: Samples,
    /// The basis functions at the samples, computed once: the objective evaluates the spline
    /// of every `x` from them without allocating.
    design: Design,
}

/// The non-zero basis functions at sorted parameters: `first[j]` and `order` values each.
#[derive(Clone, Debug)]
struct BasisRows {
    order: usize,
    first: Vec<usize>,
    values: Vec<f64>,
}

impl BasisRows {
    fn new(knots: &KnotVector<f64>, params: &[f64]) -> Self {
        let p = knots.degree();
        let mut first = Vec::with_capacity(params.len());
        let mut values = Vec::with_capacity(params.len() * (p + 1));
        let mut span = p;
        let mut basis = [0.0; MAX_ORDER];
        for &u in params {
            span = knots.span_in_domain_from(u, span);
            knots.basis_values(span, u, &mut basis[..=p]);
            first.push(span - p);
            values.extend_from_slice(&basis[..=p]);
        }
        Self {
            order: p + 1,
            first,
            values,
        }
    }

    /// The rows `(first, values)`.
    fn rows(&self) -> impl Iterator<Item = (usize, &[f64])> + '_ {
        self.first
            .iter()
            .copied()
            .zip(self.values.chunks_exact(self.order))
    }
}

/// The basis rows of the samples, and for grids those of `v` and the coefficients of one
/// iso-curve `v ↦ s(u_a, v)` (reused).
#[derive(Clone, Debug)]
struct Design {
    u: BasisRows,
    v: Option<(BasisRows, RefCell<Vec<f64>>)>,
}

impl Design {
    fn new(samples: &Samples) -> Self {
        match samples {
            Samples::Function { knots, params, .. } => Self {
                u: BasisRows::new(knots, params),
                v: None,
            },
            Samples::Grid { knots, us, vs, .. } => Self {
                u: BasisRows::new(&knots.0, us),
                v: Some((
                    BasisRows::new(&knots.1, vs),
                    RefCell::new(vec![0.0; knots.1.num_basis()]),
                )),
            },
        }
    }

    /// $\tfrac12 \sum_j (s_x(\bar u_j) - z_j)^2$.
    fn half_squared_residual(&self, x: &[f64], values: &[f64]) -> f64 {
        let mut sum = 0.0;
        match &self.v {
            None => {
                for ((first, basis), z) in self.u.rows().zip(values) {
                    let s: f64 = basis.iter().zip(&x[first..]).map(|(b, c)| b * c).sum();
                    sum += (s - z) * (s - z);
                }
            }
            Some((v_rows, curve)) => {
                let mut curve = curve.borrow_mut();
                let nv = curve.len();
                let mut z = values.iter();
                for (first, bu) in self.u.rows() {
                    curve.iter_mut().for_each(|c| *c = 0.0);
                    for (r, &b) in bu.iter().enumerate() {
                        let row = &x[(first + r) * nv..(first + r + 1) * nv];
                        for (c, &p) in curve.iter_mut().zip(row) {
                            *c += b * p;
                        }
                    }
                    for (fv, bv) in v_rows.rows() {
                        let s: f64 = bv.iter().zip(&curve[fv..]).map(|(b, c)| b * c).sum();
                        let zj = z.next().copied().unwrap_or(f64::NAN);
                        sum += (s - zj) * (s - zj);
                    }
                }
            }
        }
        0.5 * sum
    }
}

/// The banded Gram matrix of normal equations as a sparse matrix.
fn gram_matrix(normal: &NormalEquations<f64, f64>) -> CsrMatrix<f64> {
    let n = normal.len();
    let w = normal.bandwidth();
    let mut coo = CooMatrix::new(n, n);
    for i in 0..n {
        for j in i.saturating_sub(w)..(i + w + 1).min(n) {
            let g = normal.gram(i, j);
            if g != 0.0 {
                coo.push(i, j, g);
            }
        }
    }
    CsrMatrix::from(&coo)
}

impl LeastSquaresObjective {
    /// The objective of a function fit to `values` at `params` (inside the domain).
    ///
    /// # Errors
    /// The errors of [`LeastSquares::normal_equations`].
    pub(crate) fn function(
        knots: &KnotVector<f64>,
        params: &[f64],
        values: &[f64],
    ) -> Result<Self> {
        // The objective does not depend on the order of the samples; spline-fit takes them
        // by increasing parameter.
        let (params, order) = sorted(params, "parameter")?;
        let values: Vec<f64> = order.iter().map(|&i| values[i]).collect();
        let normal = LeastSquares::new(&values, &params, knots.clone()).normal_equations()?;
        let samples = Samples::Function {
            knots: knots.clone(),
            params,
            values,
        };
        Ok(Self {
            gram: gram_matrix(&normal),
            rhs: DVector::from_column_slice(normal.rhs()),
            design: Design::new(&samples),
            samples,
        })
    }

    /// The objective of a tensor-product fit to grid `values`.
    ///
    /// # Errors
    /// The errors of [`GridLeastSquares::normal_equations`].
    pub(crate) fn grid(
        knots: (&KnotVector<f64>, &KnotVector<f64>),
        us: &[f64],
        vs: &[f64],
        values: &[f64],
    ) -> Result<Self> {
        // The objective does not depend on the order of the grid lines; spline-fit takes
        // them by increasing parameter.
        let (us, pu) = sorted(us, "u parameter")?;
        let (vs, pv) = sorted(vs, "v parameter")?;
        let values = if values.len() == us.len() * vs.len() {
            permuted(values, &pu, &pv)
        } else {
            values.to_vec()
        };
        let normal = GridLeastSquares::new(&us, &vs, &values, knots.0.clone(), knots.1.clone())
            .normal_equations()?;
        let samples = Samples::Grid {
            knots: (knots.0.clone(), knots.1.clone()),
            us,
            vs,
            values,
            order: (pu, pv),
        };
        Ok(Self {
            gram: kron(&gram_matrix(normal.gram_u()), &gram_matrix(normal.gram_v())),
            rhs: DVector::from_column_slice(normal.rhs()),
            design: Design::new(&samples),
            samples,
        })
    }

    pub(crate) fn dimension(&self) -> usize {
        self.rhs.len()
    }

    /// $\tfrac12 \sum_j (s_x(\bar u_j) - z_j)^2$ from the evaluated spline (the basis
    /// functions at the samples computed once).
    pub(crate) fn value(&self, x: &DVector<f64>) -> f64 {
        let values = match &self.samples {
            Samples::Function { values, .. } | Samples::Grid { values, .. } => values,
        };
        self.design.half_squared_residual(x.as_slice(), values)
    }

    /// $G x - r$.
    pub(crate) fn gradient(&self, x: &DVector<f64>) -> DVector<f64> {
        &self.gram * x - &self.rhs
    }

    /// [`LeastSquaresObjective::gradient`] into `out`, with the same sums.
    pub(crate) fn gradient_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        out.fill(0.0);
        spmm_csr_dense(0.0, &mut *out, 1.0, Op::NoOp(&self.gram), Op::NoOp(x));
        *out -= &self.rhs;
    }

    /// `G`.
    pub(crate) fn hessian(&self) -> &CsrMatrix<f64> {
        &self.gram
    }

    /// The unconstrained minimiser.
    ///
    /// # Errors
    /// [`ErrorKind::SchoenbergWhitney`] if the samples do not determine every coefficient.
    pub(crate) fn solve(&self) -> Result<DVector<f64>> {
        let x = match &self.samples {
            Samples::Function {
                knots,
                params,
                values,
            } => LeastSquares::new(values, params, knots.clone()).control_points()?,
            Samples::Grid {
                knots,
                us,
                vs,
                values,
                ..
            } => GridLeastSquares::new(us, vs, values, knots.0.clone(), knots.1.clone())
                .normal_equations()?
                .solve()?,
        };
        finite(x)
    }

    /// The least-squares coefficients for other grid values on the same samples.
    ///
    /// # Errors
    /// As [`LeastSquaresObjective::solve`]; [`ErrorKind::InvalidArgument`] for a function
    /// objective.
    pub(crate) fn solve_for(&self, other: &[f64]) -> Result<DVector<f64>> {
        match &self.samples {
            Samples::Grid {
                knots,
                us,
                vs,
                order: (pu, pv),
                ..
            } => {
                let other = permuted(other, pu, pv);
                finite(
                    GridLeastSquares::new(us, vs, &other, knots.0.clone(), knots.1.clone())
                        .normal_equations()?
                        .solve()?,
                )
            }
            Samples::Function { .. } => Err(Error::new(
                ErrorKind::InvalidArgument,
                "other values are solved for on grids only",
            )),
        }
    }
}

/// The parameters in increasing order with the original index of each.
fn sorted(params: &[f64], what: &str) -> Result<(Vec<f64>, Vec<usize>)> {
    if let Some(j) = params.iter().position(|u| !u.is_finite()) {
        return Err(Error::non_finite(format_args!("{what} {j}")).with_index(j));
    }
    let mut order: Vec<usize> = (0..params.len()).collect();
    order.sort_by(|&i, &j| params[i].total_cmp(&params[j]));
    Ok((order.iter().map(|&i| params[i]).collect(), order))
}

/// Grid values with their rows and columns in the order of the sorted grid lines.
fn permuted(values: &[f64], rows: &[usize], columns: &[usize]) -> Vec<f64> {
    let mut out = Vec::with_capacity(values.len());
    for &a in rows {
        out.extend(columns.iter().map(|&b| values[a * columns.len() + b]));
    }
    out
}

fn finite(x: Vec<f64>) -> Result<DVector<f64>> {
    if x.iter().all(|v| v.is_finite()) {
        Ok(DVector::from_vec(x))
    } else {
        Err(Error::new(
            ErrorKind::SingularSystem,
            "the normal equations are too ill-conditioned to solve",
        ))
    }
}
