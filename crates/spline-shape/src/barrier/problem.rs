//! What the barrier method solves: a smooth problem with inequality constraints, its
//! derivatives written into the solver's buffers.

use super::workspace::{SparseRows, add_sparse};
use nalgebra::{DMatrix, DVector};
use nalgebra_sparse::CsrMatrix;

/// A smooth problem `min f0(x) s.t. f_i(x) < 0` with first and second derivatives.
///
/// The solver calls the `_into` forms (and [`BarrierProblem::add_objective_hessian`]),
/// which write into its reused buffers; their defaults call the owned forms, so an
/// implementor needs only the owned ones, and overrides the others to keep the solver's
/// iterations free of allocation.
pub trait BarrierProblem {
    /// The number of unknowns `n`.
    fn dimension(&self) -> usize;
    /// The number of constraints `m`.
    fn num_constraints(&self) -> usize;
    /// $f_0(x)$.
    fn objective(&self, x: &DVector<f64>) -> f64;
    /// $\nabla f_0(x)$.
    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64>;
    /// $\nabla^2 f_0(x)$ (`n × n`, symmetric; both triangles stored).
    fn objective_hessian(&self, x: &DVector<f64>) -> CsrMatrix<f64>;
    /// The constraint values $f_i(x)$; the point is strictly feasible when all are negative.
    fn constraints(&self, x: &DVector<f64>) -> DVector<f64>;
    /// The Jacobian of the constraints (`m × n`): row `i` is $\nabla f_i(x)^T$.
    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64>;
    /// $\sum_i w_i \nabla^2 f_i(x)$, or `None` when every constraint is linear.
    fn weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>>;
    /// Adds $\sum_i w_i \nabla^2 f_i(x)$ to the dense matrix `out` and returns `true`, for
    /// problems that assemble their Hessian blocks faster that way; the default returns
    /// `false` and the solver uses [`BarrierProblem::weighted_constraint_hessian_into`].
    fn add_weighted_constraint_hessian(
        &self,
        _x: &DVector<f64>,
        _weights: &DVector<f64>,
        _out: &mut DMatrix<f64>,
    ) -> bool {
        false
    }

    /// [`BarrierProblem::objective_gradient`] written into `out` (`n` entries). The solver
    /// calls this form; the default calls the owned one, so implementors that care about
    /// allocations override it.
    fn objective_gradient_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        out.copy_from(&self.objective_gradient(x));
    }

    /// [`BarrierProblem::constraints`] written into `out` (`m` entries).
    fn constraints_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        out.copy_from(&self.constraints(x));
    }

    /// [`BarrierProblem::constraint_jacobian`] written into `out`: cleared, then one row per
    /// constraint (columns in increasing order), `n` columns.
    fn constraint_jacobian_into(&self, x: &DVector<f64>, out: &mut SparseRows) {
        out.clear(self.dimension());
        out.extend_from_csr(&self.constraint_jacobian(x));
    }

    /// Adds `scale · ∇²f0(x)` to the dense `n × n` matrix `out`.
    fn add_objective_hessian(&self, x: &DVector<f64>, scale: f64, out: &mut DMatrix<f64>) {
        add_sparse(out, &self.objective_hessian(x), scale);
    }

    /// [`BarrierProblem::objective_hessian`] written into `out`. Implementors whose pattern
    /// does not change rewrite the values of `out` in place when it already has that
    /// pattern (`out` is `None` at the first call).
    fn objective_hessian_into(&self, x: &DVector<f64>, out: &mut Option<CsrMatrix<f64>>) {
        *out = Some(self.objective_hessian(x));
    }

    /// [`BarrierProblem::weighted_constraint_hessian`] written into `out`; returns `false`
    /// (leaving `out` alone) when every constraint is linear.
    fn weighted_constraint_hessian_into(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
        out: &mut Option<CsrMatrix<f64>>,
    ) -> bool {
        match self.weighted_constraint_hessian(x, weights) {
            Some(h) => {
                *out = Some(h);
                true
            }
            None => false,
        }
    }
}
