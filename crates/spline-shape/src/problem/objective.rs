//! The least-squares objective of the constrained approximations: spline-fit's normal
//! equations (functions: [`LeastSquares`]; grids: [`GridLeastSquares`]), as the sparse
//! Hessian, gradient and unconstrained solution a barrier method needs. Values come from
//! the residuals of the evaluated spline (no cancellation), not from the normal equations.

use nalgebra::DVector;
use nalgebra_sparse::ops::Op;
use nalgebra_sparse::ops::serial::spmm_csr_dense;
use nalgebra_sparse::{CooMatrix, CsrMatrix};
use std::cell::RefCell;
use spline_algebra::kron;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_fit::{GridLeastSquares, LeastSquares, NormalEquations};
use spline_geom::{BSpline, Surface};

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
    /// The spline of the last `x` evaluated and its values at the samples, reused by every
    /// evaluation of the objective (no allocation inside the solver's iterations).
    fitted: RefCell<Fitted>,
}

/// A spline with the samples' knots whose coefficients are overwritten, and its values.
#[derive(Clone, Debug)]
struct Fitted {
    spline: FittedSpline,
    values: Vec<f64>,
}

#[derive(Clone, Debug)]
enum FittedSpline {
    Function(BSpline<f64, f64>),
    Grid(Surface<f64, f64>),
}

impl Fitted {
    fn new(samples: &Samples, n: usize) -> Self {
        match samples {
            Samples::Function { knots, params, .. } => Self {
                spline: FittedSpline::Function(BSpline::new_unchecked(knots.clone(), vec![0.0; n])),
                values: vec![0.0; params.len()],
            },
            Samples::Grid { knots, us, vs, .. } => Self {
                spline: FittedSpline::Grid(Surface::new_unchecked(
                    knots.0.clone(),
                    knots.1.clone(),
                    vec![0.0; n],
                )),
                values: vec![0.0; us.len() * vs.len()],
            },
        }
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
            fitted: RefCell::new(Fitted::new(&samples, normal.rhs().len())),
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
            fitted: RefCell::new(Fitted::new(&samples, normal.rhs().len())),
            samples,
        })
    }

    pub(crate) fn dimension(&self) -> usize {
        self.rhs.len()
    }

    /// $\tfrac12 \sum_j (s_x(\bar u_j) - z_j)^2$ from the evaluated spline (infinite if it
    /// cannot be evaluated).
    pub(crate) fn value(&self, x: &DVector<f64>) -> f64 {
        let mut fitted = self.fitted.borrow_mut();
        let Fitted { spline, values: out } = &mut *fitted;
        let evaluated = match (spline, &self.samples) {
            (FittedSpline::Function(curve), Samples::Function { params, .. }) => {
                curve.control_points_mut().copy_from_slice(x.as_slice());
                curve.eval_many_into(params, out)
            }
            (FittedSpline::Grid(surface), Samples::Grid { us, vs, .. }) => {
                surface.control_points_mut().copy_from_slice(x.as_slice());
                surface.eval_grid_into(us, vs, out)
            }
            _ => unreachable!("the spline is made from the samples"),
        };
        let values = match &self.samples {
            Samples::Function { values, .. } | Samples::Grid { values, .. } => values,
        };
        evaluated.map_or(f64::INFINITY, |()| {
            0.5 * out
                .iter()
                .zip(values)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
        })
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
