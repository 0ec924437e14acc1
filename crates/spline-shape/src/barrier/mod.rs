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

use nalgebra::{DMatrix, DVector};
use nalgebra_sparse::CsrMatrix;
use spline_core::{Error, ErrorKind, Result};

mod newton;
mod phase_one;
mod trust_region;

use newton::{DENSE_LIMIT, NewtonSystem};
pub use phase_one::{find_feasible, find_feasible_near};
use trust_region::centre_trust_region;

/// A smooth problem `min f0(x) s.t. f_i(x) < 0` with first and second derivatives.
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
    /// `false` and the solver uses [`BarrierProblem::weighted_constraint_hessian`].
    fn add_weighted_constraint_hessian(
        &self,
        _x: &DVector<f64>,
        _weights: &DVector<f64>,
        _out: &mut DMatrix<f64>,
    ) -> bool {
        false
    }
}

/// Settings of [`minimize`].
#[derive(Clone, Debug)]
pub struct BarrierOptions {
    /// Stop when the duality-gap bound `m / t` is below this.
    pub gap_tolerance: f64,
    /// Stop Newton's method when half the squared Newton decrement is below this times
    /// `1 + |barrier value|`.
    pub newton_tolerance: f64,
    /// Factor by which `t` grows between centring steps (μ).
    pub t_growth: f64,
    /// Initial `t`; `None` chooses `t` so that both terms of the first gradient balance.
    pub t_initial: Option<f64>,
    /// Armijo parameter α ∈ (0, ½).
    pub armijo: f64,
    /// Backtracking factor β ∈ (0, 1).
    pub backtracking: f64,
    /// Newton iterations per centring step.
    pub max_newton_iterations: usize,
    /// Centring steps.
    pub max_outer_iterations: usize,
}

impl Default for BarrierOptions {
    fn default() -> Self {
        Self {
            gap_tolerance: 1e-8,
            newton_tolerance: 1e-10,
            t_growth: 10.0,
            t_initial: None,
            armijo: 0.01,
            backtracking: 0.5,
            max_newton_iterations: 200,
            max_outer_iterations: 60,
        }
    }
}

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
/// [`ErrorKind::InvalidArgument`] if `x0` has the wrong size or is not strictly feasible
/// (see [`find_feasible`]); [`ErrorKind::NonFinite`] if the problem produces NaN;
/// [`ErrorKind::NoConvergence`] if the iteration limits are reached;
/// [`ErrorKind::SingularSystem`] if no shift makes the Newton matrix positive definite.
pub fn minimize(
    problem: &impl BarrierProblem,
    x0: DVector<f64>,
    options: &BarrierOptions,
) -> Result<BarrierReport> {
    let n = problem.dimension();
    let m = problem.num_constraints();
    if x0.len() != n {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "starting point has {} entries, the problem {n} unknowns",
                x0.len()
            ),
        ));
    }
    let c0 = problem.constraints(&x0);
    if let Some(i) = c0.iter().position(|&c| !(c < 0.0)) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the starting point is not strictly feasible: constraint {i} = {:.3e} ≥ 0",
                c0[i]
            ),
        ));
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
        match centre(problem, &mut x, t, options, None) {
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

/// Value of the barrier objective `t f0 − Σ log(−f_i)`, or `None` outside the domain.
pub(super) fn barrier_value(
    problem: &impl BarrierProblem,
    x: &DVector<f64>,
    t: f64,
) -> Option<f64> {
    let c = problem.constraints(x);
    if c.iter().any(|&ci| !(ci < 0.0)) {
        return None;
    }
    let f = t * problem.objective(x) - c.iter().map(|&ci| (-ci).ln()).sum::<f64>();
    f.is_finite().then_some(f)
}

/// At an iterate: the constraints' Jacobian, the weights `1 / (−f_i)` and the gradient of
/// the barrier objective.
pub(super) struct Gradient {
    jac: CsrMatrix<f64>,
    inv: DVector<f64>,
    gradient: DVector<f64>,
}

/// The gradient of the barrier objective, `t ∇f0 + Σ ∇f_i / (−f_i)`.
pub(super) fn barrier_gradient(
    problem: &impl BarrierProblem,
    x: &DVector<f64>,
    t: f64,
) -> Result<Gradient> {
    let c = problem.constraints(x);
    let jac = problem.constraint_jacobian(x);
    let inv = c.map(|ci| 1.0 / -ci);
    let gradient = problem.objective_gradient(x) * t + jac.transpose() * &inv;
    if gradient.iter().any(|g| !g.is_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            "the barrier gradient is not finite",
        ));
    }
    Ok(Gradient { jac, inv, gradient })
}

/// A condition that ends a centring step early.
pub(crate) type StopRule<'a> = &'a dyn Fn(&DVector<f64>) -> bool;

/// Newton's method on the barrier objective for fixed `t`; returns the number of steps.
/// `stop` ends the centring early once an iterate satisfies it.
pub(crate) fn centre(
    problem: &impl BarrierProblem,
    x: &mut DVector<f64>,
    t: f64,
    options: &BarrierOptions,
    stop: Option<StopRule<'_>>,
) -> Result<usize> {
    let n = problem.dimension();
    if n <= DENSE_LIMIT {
        return centre_trust_region(problem, x, t, options, stop);
    }
    for step in 0..options.max_newton_iterations {
        let Gradient { jac, inv, gradient } = barrier_gradient(problem, x, t)?;
        // Hessian: t ∇²f0 + Σ ∇f_i ∇f_iᵀ / f_i² + Σ ∇²f_i / (−f_i). With the curvature of
        // the constraints when that keeps the Newton matrix positive definite; otherwise the
        // Gauss–Newton matrix t∇²f0 + Σ ∇f_i∇f_iᵀ/f_i² (positive semi-definite) with a small
        // shift — the standard remedy for non-convex constraints.
        let mut system = NewtonSystem::new(n);
        for (i, j, v) in problem.objective_hessian(x).triplet_iter() {
            system.add(i, j, t * v);
        }
        for (row, &w) in jac.row_iter().zip(inv.iter()) {
            system.add_outer(row.col_indices(), row.values(), w * w);
        }
        let curvature = problem.weighted_constraint_hessian(x, &inv);
        let direction = match curvature {
            Some(h) => {
                let full = system.with(&h);
                match full.solve_definite(&gradient) {
                    Some(d) => d,
                    None => system.solve_shifted(&gradient)?,
                }
            }
            None => system.solve_shifted(&gradient)?,
        };
        let decrement = -gradient.dot(&direction);
        let f = barrier_value(problem, x, t)
            .ok_or_else(|| Error::new(ErrorKind::NonFinite, "iterate left the barrier domain"))?;
        // Relative to the barrier value: at large t the gradient is a difference of large terms.
        if decrement / 2.0 <= options.newton_tolerance * (1.0 + f.abs()) {
            return Ok(step);
        }
        // Backtracking: stay strictly feasible, then Armijo.
        let slope = gradient.dot(&direction);
        let mut s = 1.0;
        loop {
            let candidate = &*x + &direction * s;
            if let Some(fc) = barrier_value(problem, &candidate, t) {
                if fc <= f + options.armijo * s * slope {
                    *x = candidate;
                    if stop.is_some_and(|stop| stop(x)) {
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
