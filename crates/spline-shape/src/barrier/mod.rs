//! A log-barrier interior-point method for smooth inequality-constrained problems on sparse
//! matrices (Boyd & Vandenberghe ch. 11; thesis §5.2).
//!
//! Minimise $f_0(x)$ subject to $f_i(x) < 0$, `i = 1 … m`, by following the central path:
//! for increasing `t`, minimise $t f_0(x) - \sum_i \log(-f_i(x))$ with Newton's method,
//! every iterate strictly feasible. Small problems (at most 400 unknowns: the eraser's curves,
//! the functions of thesis ch. 5) take trust-region steps with the exact Hessian in the
//! barrier's local metric (`trust_region`); larger ones a sparse Newton matrix, shifted by a
//! multiple of the identity until its Cholesky factorisation succeeds, and a backtracking line
//! search (`newton`). A phase-I problem finds a strictly feasible start when the given one is
//! not (`phase_one`).

use nalgebra::DVector;
use spline_core::{Error, ErrorKind, Result};

mod centring;
mod newton;
mod objective;
mod options;
mod phase_one;
mod problem;
mod trust_region;
mod workspace;

pub(crate) use centring::centre;
use centring::centre_in;
pub(crate) use options::StopRule;
pub use options::{BarrierOptions, STALL_STEPS};
pub use phase_one::{find_feasible, find_feasible_near};
pub use problem::BarrierProblem;
use workspace::with_workspace;
pub use workspace::{SparseRows, trust_region_eigendecompositions};
pub(crate) use workspace::{Workspace, add_sparse};

/// The outcome of [`minimize`].
#[derive(Clone, Debug)]
pub struct BarrierReport {
    /// The solution (strictly feasible).
    pub x: DVector<f64>,
    /// $f_0$ at the solution.
    pub objective: f64,
    /// The final barrier parameter.
    pub t: f64,
    /// The bound `m / t` on the gap to the optimum (for convex problems).
    pub duality_gap: f64,
    /// Centring steps taken.
    pub outer_iterations: usize,
    /// Newton steps taken in total.
    pub newton_iterations: usize,
    /// Centring steps that ended at the Newton iteration limit (then the method went on with
    /// a larger `t` from the improved, strictly feasible iterate). Zero for well-behaved
    /// convex problems.
    pub unfinished_centring_steps: usize,
    /// The largest constraint value at the solution (negative).
    pub max_constraint: f64,
}

/// Minimises `problem` from a strictly feasible `x0`.
///
/// # Errors
/// [`ErrorKind::InvalidLength`] if `x0` has the wrong size (`(unknowns, entries)` as
/// [`Error::counts`]); [`ErrorKind::InvalidArgument`] if it is not strictly feasible (see
/// [`find_feasible`]; the first constraint that is not negative as [`Error::index`], its
/// value as [`Error::value`]); [`ErrorKind::NonFinite`] if the problem produces NaN;
/// [`ErrorKind::NoConvergence`] if the iteration limits are reached;
/// [`ErrorKind::SingularSystem`] if no shift makes the Newton matrix positive definite.
pub fn minimize(
    problem: &impl BarrierProblem,
    x0: DVector<f64>,
    options: &BarrierOptions,
) -> Result<BarrierReport> {
    with_workspace(|ws| minimize_in(problem, x0, options, ws))
}

/// [`minimize`] with the given workspace.
fn minimize_in(
    problem: &impl BarrierProblem,
    x0: DVector<f64>,
    options: &BarrierOptions,
    ws: &mut Workspace,
) -> Result<BarrierReport> {
    let n = problem.dimension();
    let m = problem.num_constraints();
    if x0.len() != n {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "starting point has {} entries, the problem {n} unknowns",
                x0.len()
            ),
        )
        .with_counts(n, x0.len()));
    }
    let c0 = problem.constraints(&x0);
    if let Some(i) = c0.iter().position(|&c| !(c < 0.0)) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the starting point is not strictly feasible: constraint {i} = {:.3e} ≥ 0",
                c0[i]
            ),
        )
        .with_index(i)
        .with_value(c0[i])
        .with_interval(f64::NEG_INFINITY, 0.0));
    }
    let mut x = x0;
    let mut t = match options.t_initial {
        Some(t) => t,
        None => initial_t(problem, &x),
    };
    let mut newton_total = 0;
    let mut unfinished = 0;
    for outer in 1..=options.max_outer_iterations {
        // A centring step that runs out of Newton iterations (non-convex problems can crawl)
        // still leaves a strictly feasible, improved iterate: go on with a larger t.
        match centre_in(problem, &mut x, t, options, None, ws) {
            Ok(steps) => newton_total += steps,
            Err(e) if e.kind() == ErrorKind::NoConvergence => {
                newton_total += options.max_newton_iterations;
                unfinished += 1;
            }
            Err(e) => return Err(e),
        }
        let gap = if m == 0 { 0.0 } else { m as f64 / t };
        if gap < options.gap_tolerance {
            let c = problem.constraints(&x);
            return Ok(BarrierReport {
                objective: problem.objective(&x),
                x,
                t,
                duality_gap: gap,
                outer_iterations: outer,
                newton_iterations: newton_total,
                unfinished_centring_steps: unfinished,
                max_constraint: c.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            });
        }
        t *= options.t_growth;
    }
    Err(Error::new(
        ErrorKind::NoConvergence,
        format!(
            "the barrier method did not reach the gap {:.1e} in {} centring steps",
            options.gap_tolerance, options.max_outer_iterations
        ),
    ))
}

/// Balances `t ∇f0` against `∇φ` at the start: `t = ‖∇φ‖ / ‖∇f0‖` (clamped to a sane range).
fn initial_t(problem: &impl BarrierProblem, x: &DVector<f64>) -> f64 {
    let g0 = problem.objective_gradient(x);
    let c = problem.constraints(x);
    let jac = problem.constraint_jacobian(x);
    let w = c.map(|ci| 1.0 / -ci);
    let gphi = jac.transpose() * &w;
    let (a, b) = (g0.norm(), gphi.norm());
    if a > 0.0 && b > 0.0 {
        (b / a).clamp(1e-6, 1e6)
    } else {
        1.0
    }
}
