//! The barrier objective `t f0 − Σ log(−f_i)`: its value and its gradient at an iterate.

use super::problem::BarrierProblem;
use super::workspace::Workspace;
use nalgebra::DVector;
use spline_core::{Error, ErrorKind, Result};

/// Value of the barrier objective `t f0 − Σ log(−f_i)`, or `None` outside the domain; `c`
/// receives the constraint values.
pub(super) fn barrier_value(
    problem: &impl BarrierProblem,
    x: &DVector<f64>,
    t: f64,
    c: &mut DVector<f64>,
) -> Option<f64> {
    problem.constraints_into(x, c);
    if c.iter().any(|&ci| !(ci < 0.0)) {
        return None;
    }
    let f = t * problem.objective(x) - c.iter().map(|&ci| (-ci).ln()).sum::<f64>();
    f.is_finite().then_some(f)
}

/// [`barrier_value`] at an iterate, which must lie in the domain.
///
/// # Errors
/// [`ErrorKind::NonFinite`] when the iterate left it (or the value is not finite).
pub(super) fn iterate_value(
    problem: &impl BarrierProblem,
    x: &DVector<f64>,
    t: f64,
    c: &mut DVector<f64>,
) -> Result<f64> {
    barrier_value(problem, x, t, c)
        .ok_or_else(|| Error::new(ErrorKind::NonFinite, "iterate left the barrier domain"))
}

/// At an iterate, into the workspace: the constraints' Jacobian, the weights `1 / (−f_i)`
/// and the gradient of the barrier objective, `t ∇f0 + Σ ∇f_i / (−f_i)`.
pub(super) fn barrier_gradient(
    problem: &impl BarrierProblem,
    x: &DVector<f64>,
    t: f64,
    ws: &mut Workspace,
) -> Result<()> {
    problem.constraints_into(x, &mut ws.c);
    problem.constraint_jacobian_into(x, &mut ws.jac);
    for (w, &ci) in ws.inv.iter_mut().zip(ws.c.iter()) {
        *w = 1.0 / -ci;
    }
    problem.objective_gradient_into(x, &mut ws.g0);
    // Jᵀ w summed row after row (as the transposed CSR product did), then t ∇f0 added.
    ws.gradient.fill(0.0);
    ws.jac
        .transpose_mul_add(ws.inv.as_slice(), ws.gradient.as_mut_slice());
    for (g, &g0) in ws.gradient.iter_mut().zip(ws.g0.iter()) {
        *g += g0 * t;
    }
    if ws.gradient.iter().any(|g| !g.is_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            "the barrier gradient is not finite",
        ));
    }
    Ok(())
}
