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
mod workspace;

use newton::{DENSE_LIMIT, SparseNewton};
pub use phase_one::{find_feasible, find_feasible_near};
use trust_region::centre_trust_region;
pub(crate) use workspace::Workspace;
use workspace::with_workspace;
pub use workspace::{SparseRows, trust_region_eigendecompositions};

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
        for (i, j, v) in self.objective_hessian(x).triplet_iter() {
            out[(i, j)] += scale * v;
        }
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
    /// A centring step also ends when [`STALL_STEPS`] accepted Newton steps in a row each
    /// lowered the barrier objective by less than this times `1 + |value|`: the iterate is
    /// crawling along a flat valley (non-convex problems, variables that barely change the
    /// objective), where more steps move the answer by less than the objective's rounding
    /// at this `t`. `0` turns the rule off (the default).
    pub stall_tolerance: f64,
}

/// Accepted Newton steps in a row that must each gain less than
/// [`BarrierOptions::stall_tolerance`] before a centring step ends as crawling.
pub const STALL_STEPS: usize = 4;

/// Counts consecutive accepted Newton steps of negligible gain (see
/// [`BarrierOptions::stall_tolerance`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct StallWatch {
    tolerance: f64,
    small: usize,
}

impl StallWatch {
    pub(super) fn new(options: &BarrierOptions) -> Self {
        Self {
            tolerance: options.stall_tolerance,
            small: 0,
        }
    }

    /// Records an accepted step from the value `before` to `after`; `true` once
    /// [`STALL_STEPS`] steps in a row gained less than the tolerance.
    pub(super) fn crawled(&mut self, before: f64, after: f64) -> bool {
        if before - after < self.tolerance * (1.0 + after.abs()) {
            self.small += 1;
        } else {
            self.small = 0;
        }
        self.small >= STALL_STEPS
    }
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
            stall_tolerance: 0.0,
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

/// A condition that ends a centring step early.
pub(crate) type StopRule<'a> = &'a dyn Fn(&DVector<f64>) -> bool;

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

#[cfg(test)]
mod stall_tests {
    use super::{BarrierOptions, STALL_STEPS, StallWatch};

    /// The watch fires after exactly `STALL_STEPS` negligible gains in a row, a real gain
    /// resets it, and a zero tolerance never fires.
    #[test]
    fn crawling_is_counted_in_a_row() {
        let options = BarrierOptions {
            stall_tolerance: 1e-5,
            ..BarrierOptions::default()
        };
        let mut watch = StallWatch::new(&options);
        // Gains of 1e-6 relative to a value of 1e3: negligible.
        let mut f = 1e3;
        for step in 1..STALL_STEPS {
            assert!(!watch.crawled(f, f - 1e-3), "step {step}");
            f -= 1e-3;
        }
        // A real gain resets the count.
        assert!(!watch.crawled(f, f - 1.0));
        f -= 1.0;
        for _ in 1..STALL_STEPS {
            assert!(!watch.crawled(f, f - 1e-3));
            f -= 1e-3;
        }
        assert!(watch.crawled(f, f - 1e-3));
        let mut off = StallWatch::new(&BarrierOptions::default());
        assert!((0..100).all(|_| !off.crawled(1.0, 1.0)));
    }
}
