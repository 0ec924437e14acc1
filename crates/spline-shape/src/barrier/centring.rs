//! A centring step: Newton's method on the barrier objective for fixed `t`, by trust-region
//! steps on small problems and by the sparse Newton matrix with a line search on large ones.

use super::newton::{DENSE_LIMIT, SparseNewton};
use super::objective::{barrier_gradient, barrier_value, iterate_value};
use super::options::{BarrierOptions, StallWatch, StopRule};
use super::problem::BarrierProblem;
use super::trust_region::centre_trust_region;
use super::workspace::{Workspace, with_workspace};
use nalgebra::DVector;
use spline_core::{Error, ErrorKind, Result};

/// Newton's method on the barrier objective for fixed `t`; returns the number of steps.
/// `stop` ends the centring early once an iterate satisfies it. The memory of the steps is
/// this thread's solver workspace, reused from one call to the next.
pub(crate) fn centre(
    problem: &impl BarrierProblem,
    x: &mut DVector<f64>,
    t: f64,
    options: &BarrierOptions,
    stop: Option<StopRule<'_>>,
) -> Result<usize> {
    with_workspace(|ws| centre_in(problem, x, t, options, stop, ws))
}

/// [`centre`] with the given workspace.
pub(super) fn centre_in(
    problem: &impl BarrierProblem,
    x: &mut DVector<f64>,
    t: f64,
    options: &BarrierOptions,
    stop: Option<StopRule<'_>>,
    ws: &mut Workspace,
) -> Result<usize> {
    let n = problem.dimension();
    ws.prepare(n, problem.num_constraints(), n <= DENSE_LIMIT);
    if n <= DENSE_LIMIT {
        return centre_trust_region(problem, x, t, options, stop, ws);
    }
    let mut watch = StallWatch::new(options);
    for step in 0..options.max_newton_iterations {
        barrier_gradient(problem, x, t, ws)?;
        // Hessian: t ∇²f0 + Σ ∇f_i ∇f_iᵀ / f_i² + Σ ∇²f_i / (−f_i). With the curvature of
        // the constraints when that keeps the Newton matrix positive definite; otherwise the
        // Gauss–Newton matrix t∇²f0 + Σ ∇f_i∇f_iᵀ/f_i² (positive semi-definite) with a small
        // shift — the standard remedy for non-convex constraints.
        problem.objective_hessian_into(x, &mut ws.objective_hessian);
        let curved = problem.weighted_constraint_hessian_into(x, &ws.inv, &mut ws.curvature);
        fill_newton(ws, t, curved);
        let newton = ws.newton.as_mut().expect("filled");
        let solved = if curved {
            newton.solve_definite(&ws.gradient, &mut ws.direction)
        } else {
            false
        };
        if !solved {
            newton.solve_shifted(&ws.gradient, &mut ws.direction)?;
        }
        let direction = &ws.direction;
        let decrement = -ws.gradient.dot(direction);
        let f = iterate_value(problem, x, t, &mut ws.c_trial)?;
        // Relative to the barrier value: at large t the gradient is a difference of large terms.
        if decrement / 2.0 <= options.newton_tolerance * (1.0 + f.abs()) {
            return Ok(step);
        }
        // Backtracking: stay strictly feasible, then Armijo.
        let slope = ws.gradient.dot(direction);
        let mut s = 1.0;
        loop {
            ws.candidate.copy_from(x);
            ws.candidate.axpy(s, &ws.direction, 1.0);
            if let Some(fc) = barrier_value(problem, &ws.candidate, t, &mut ws.c_trial) {
                if fc <= f + options.armijo * s * slope {
                    x.copy_from(&ws.candidate);
                    if stop.is_some_and(|stop| stop(x)) || watch.crawled(f, fc) {
                        return Ok(step + 1);
                    }
                    break;
                }
            }
            s *= options.backtracking;
            if s < 1e-16 {
                // No progress possible at this t: the point is as central as rounding allows.
                return Ok(step);
            }
        }
    }
    Err(Error::new(
        ErrorKind::NoConvergence,
        format!(
            "Newton's method did not converge in {} steps (t = {t:.3e})",
            options.max_newton_iterations
        ),
    ))
}

/// Fills the sparse Newton matrix of the workspace: base values `t ∇²f0 + Σ ∇f_i ∇f_iᵀ /
/// f_i²`, and working values with the curvature added when `curved`. The pattern is made
/// (again) when an entry falls outside it: at the first step, or when the problem's
/// patterns change.
fn fill_newton(ws: &mut Workspace, t: f64, curved: bool) {
    for attempt in 0..2 {
        if ws.newton.is_none() || attempt == 1 {
            let old = ws.newton.take();
            let mut entries: Vec<(usize, usize)> = old
                .as_ref()
                .map(|o| o.entries().collect())
                .unwrap_or_default();
            if let Some(h) = &ws.objective_hessian {
                entries.extend(h.triplet_iter().map(|(i, j, _)| (i, j)));
            }
            for (cols, _) in ws.jac.rows() {
                for &a in cols {
                    entries.extend(cols.iter().map(|&b| (a, b)));
                }
            }
            if curved {
                if let Some(h) = &ws.curvature {
                    entries.extend(h.triplet_iter().map(|(i, j, _)| (i, j)));
                }
            }
            ws.newton = Some(SparseNewton::new(ws.n, entries.into_iter()));
        }
        let newton = ws.newton.as_mut().expect("made above");
        newton.clear();
        if let Some(h) = &ws.objective_hessian {
            for (i, j, v) in h.triplet_iter() {
                newton.add(i, j, t * v);
            }
        }
        for ((cols, vals), &w) in ws.jac.rows().zip(ws.inv.iter()) {
            newton.add_outer(cols, vals, w * w);
        }
        newton.reset_work();
        if curved {
            if let Some(h) = &ws.curvature {
                for (i, j, v) in h.triplet_iter() {
                    newton.add_work(i, j, *v);
                }
            }
        }
        if !newton.missed {
            break;
        }
    }
}
