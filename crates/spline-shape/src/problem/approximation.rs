//! The constrained least-squares problem: its data, its sparsity patterns, and its
//! derivatives as a [`BarrierProblem`].

use super::objective::LeastSquaresObjective;
use super::patterns::{HessianPattern, JacobianPattern};
use super::rows::vstack;
use crate::barrier::{BarrierProblem, SparseRows, add_sparse};
use nalgebra::{DMatrix, DVector};
use nalgebra_sparse::CsrMatrix;
use spline_algebra::SparseBilinear;
#[cfg(doc)]
use spline_core::ErrorKind;
use spline_core::Result;

/// A constrained least-squares problem, ready for [`crate::minimize`]: minimise
/// $f_0(x) = \tfrac12\\|Ax - b\\|^2$ over the coefficients `x` subject to linear constraints
/// `G x < 0` (sign conditions on the control points of derivatives, each row scaled to unit
/// length so that its value is the signed distance of `x` to the hyperplane) and quadratic
/// ones $\tfrac12 x^T H_k x < 0$ with constant Hessians `H_k` (the control points of
/// $s_{uu}s_{vv} - s_{uv}^2$, thesis §5.6).
///
/// The builders [`crate::FunctionApproximation`] and [`crate::SurfaceApproximation`] make
/// these and solve them; they are public so that the derivatives can be checked and the
/// solver driven by hand.
///
/// # Panics
/// The [`BarrierProblem`] methods panic if `x` does not have [`BarrierProblem::dimension`]
/// entries (the trait has no error channel; [`crate::minimize`] checks the start).
///
/// ```
/// use spline_shape::{BarrierOptions, BarrierProblem, FunctionApproximation, Sign};
/// use spline_shape::{find_feasible, minimize};
/// let approx = FunctionApproximation::uniform(3, 8, 0.0, 1.0)?.sign(1, Sign::NonNegative);
/// let params: Vec<f64> = (0..=50).map(|j| f64::from(j) / 50.0).collect();
/// let values: Vec<f64> = params.iter().map(|u| (6.0 * u).sin() + u).collect();
/// let problem = &approx.problems(&params, &values)?[0];
/// assert_eq!(problem.num_constraints(), 7); // the 7 control points of s′
/// // A strictly increasing start: the Greville abscissae (s(u) = u).
/// let start = nalgebra::DVector::from_vec(approx.knots().greville());
/// let options = BarrierOptions::default();
/// let x0 = find_feasible(problem, start, 1e-6, &options)?;
/// let report = minimize(problem, x0, &options)?;
/// let fit = approx.fit(&params, &values)?;
/// assert!((report.objective - fit.objective).abs() < 1e-6);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct ApproximationProblem {
    pub(super) lsq: LeastSquaresObjective,
    pub(super) linear: CsrMatrix<f64>,
    pub(super) quadratic: Option<SparseBilinear<f64>>,
    pub(super) pattern: Option<HessianPattern>,
    pub(super) jacobian_pattern: Option<JacobianPattern>,
}

impl ApproximationProblem {
    pub(crate) fn new(
        lsq: LeastSquaresObjective,
        linear: CsrMatrix<f64>,
        quadratic: Option<SparseBilinear<f64>>,
    ) -> Self {
        let pattern = quadratic
            .as_ref()
            .map(|q| HessianPattern::new(lsq.dimension(), q));
        let jacobian_pattern = quadratic.as_ref().map(JacobianPattern::new);
        Self {
            lsq,
            linear,
            quadratic,
            pattern,
            jacobian_pattern,
        }
    }

    pub(crate) fn least_squares(&self) -> &LeastSquaresObjective {
        &self.lsq
    }

    /// The number of linear constraints (they come first).
    #[must_use]
    pub fn num_linear_constraints(&self) -> usize {
        self.linear.nrows()
    }

    /// The number of quadratic constraints (they come after the linear ones).
    #[must_use]
    pub fn num_quadratic_constraints(&self) -> usize {
        self.quadratic.as_ref().map_or(0, SparseBilinear::nrows)
    }

    /// The minimiser of $f_0$ without constraints, $x = (A^TA)^{-1}A^Tb$.
    ///
    /// # Errors
    /// [`ErrorKind::SchoenbergWhitney`] if the samples leave a coefficient undetermined;
    /// [`ErrorKind::SingularSystem`] if the normal equations cannot be solved accurately.
    pub fn unconstrained_solution(&self) -> Result<DVector<f64>> {
        self.lsq.solve()
    }
}

impl BarrierProblem for ApproximationProblem {
    fn dimension(&self) -> usize {
        self.lsq.dimension()
    }

    fn num_constraints(&self) -> usize {
        self.linear.nrows() + self.num_quadratic_constraints()
    }

    fn objective(&self, x: &DVector<f64>) -> f64 {
        self.lsq.value(x)
    }

    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64> {
        self.lsq.gradient(x)
    }

    fn objective_hessian(&self, _: &DVector<f64>) -> CsrMatrix<f64> {
        self.lsq.hessian().clone()
    }

    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        let lin = &self.linear * x;
        match &self.quadratic {
            None => lin,
            Some(h) => {
                let q = h
                    .apply(x.as_slice(), x.as_slice())
                    .expect("x has `dimension()` entries");
                DVector::from_iterator(
                    lin.len() + q.len(),
                    lin.iter().copied().chain(q.iter().map(|v| 0.5 * v)),
                )
            }
        }
    }

    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        match &self.quadratic {
            None => self.linear.clone(),
            Some(h) => {
                let jac = h
                    .jacobian_left(x.as_slice())
                    .expect("x has `dimension()` entries");
                vstack(self.dimension(), &[self.linear.clone(), jac])
            }
        }
    }

    fn weighted_constraint_hessian(
        &self,
        _: &DVector<f64>,
        weights: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        let pattern = self.pattern.as_ref()?;
        Some(pattern.weighted(&weights.as_slice()[self.linear.nrows()..]))
    }

    fn objective_gradient_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        self.lsq.gradient_into(x, out);
    }

    fn constraints_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        self.constraints_in_place(x, out);
    }

    fn constraint_jacobian_into(&self, x: &DVector<f64>, out: &mut SparseRows) {
        self.jacobian_in_place(x, out);
    }

    fn add_objective_hessian(&self, _: &DVector<f64>, scale: f64, out: &mut DMatrix<f64>) {
        add_sparse(out, self.lsq.hessian(), scale);
    }

    fn objective_hessian_into(&self, _: &DVector<f64>, out: &mut Option<CsrMatrix<f64>>) {
        let h = self.lsq.hessian();
        match out {
            Some(m) if m.pattern() == h.pattern() => m.values_mut().copy_from_slice(h.values()),
            _ => *out = Some(h.clone()),
        }
    }

    fn weighted_constraint_hessian_into(
        &self,
        _: &DVector<f64>,
        weights: &DVector<f64>,
        out: &mut Option<CsrMatrix<f64>>,
    ) -> bool {
        self.weighted_hessian_in_place(weights.as_slice(), out)
    }
}
