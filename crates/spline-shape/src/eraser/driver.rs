//! One attempt of the eraser on normalised data: coarse-to-fine continuation over nested knot
//! vectors, phase I where a level has no strictly feasible curve yet, path following with
//! refinement of active conditions on the finest level.

use super::placement::fit_with_correction;
use super::problem::EraserProblem;
use super::topology::Topology;
use super::{Objective, SmoothingOptions};
use crate::barrier::{BarrierProblem, StopRule, centre};
use nalgebra::{DVector, Vector2};
use spline_core::{ErrorKind, KnotVector, Result};
use spline_fit::project_ordered;
use spline_geom::Curve2;

/// Newton steps per centring step in phase I, at most.
const PHASE_ONE_NEWTON_STEPS: usize = 60;

/// Phase I gives up once `τ` stays above this many times the barrier's gap bound `m / t`:
/// were the centring exact and the pull on the fit gone, `τ − m/t` would bound the least
/// `τ` from below, so a `τ` far above `m / t` creeps towards a positive or zero limit (no
/// strictly feasible curve on this level) rather than through zero. The factor leaves room
/// for inexact centring and the pull, which the bound ignores. Measured on the 2,174 UIUC
/// airfoils (20 control points): at 10, 47 % of all Newton steps went to phases I that
/// failed; 3 gives the same curves on every airfoil (only the failing phases end sooner),
/// 92 s → 70 s for the database; 2 the same deviations' quantiles and refusals, 67 s →
/// 63 s (phases I that succeed have `τ` at most 2.3 times the bound before their last
/// round, in a sample of 100 airfoils, those that fail 1 to 3 times it, then 5 to 25 times);
/// 1.5 refuses an airfoil that succeeds, 1 three.
const PHASE_ONE_GAP_FACTOR: f64 = 2.0;

/// A warm start enters the path at `t = WARM_START_T · m` (the gap bound `m / t` at 1e-2;
/// a cold start at `10 m`, the end at
/// [`BarrierOptions::gap_tolerance`](crate::barrier::BarrierOptions)). Measured on clarkv
/// with a dragged point (six updates): at `10 m` as many steps again and no closer, at
/// `1e4 m` fewer steps but up to 45 % farther from the data (the path entered too near its
/// end keeps the earlier curve's active conditions); at `100 m` 34 ms a step against the
/// cold start's 180 ms, every deviation within 0.1 % of the cold start's or below it.
const WARM_START_T: f64 = 100.0;

/// What one attempt found.
pub(crate) struct Attempt {
    /// The curve on the final knots (normalised coordinates).
    pub(crate) curve: Curve2<f64>,
    pub(crate) refinements: usize,
    pub(crate) conditions: usize,
    pub(crate) newton_steps: usize,
    pub(crate) levels: usize,
}

/// The interior-point machinery of the eraser, with its step counts.
pub(super) struct Solver<'a> {
    pub(super) options: &'a SmoothingOptions,
    pub(super) newton_steps: usize,
}

impl Solver<'_> {
    /// One centring step at `t` (an unfinished one still improves the iterate), then the
    /// anchors of the foot points follow the curve.
    fn centre(
        &mut self,
        problem: &EraserProblem,
        x: &mut DVector<f64>,
        t: f64,
        stop: Option<StopRule<'_>>,
    ) -> Result<()> {
        self.centre_with(problem, x, t, stop, &self.options.barrier.clone())
    }

    /// [`Solver::centre`] with other barrier settings.
    fn centre_with(
        &mut self,
        problem: &EraserProblem,
        x: &mut DVector<f64>,
        t: f64,
        stop: Option<StopRule<'_>>,
        barrier: &crate::barrier::BarrierOptions,
    ) -> Result<()> {
        let steps = match centre(problem, x, t, barrier, stop) {
            Ok(steps) => steps,
            Err(e) if e.kind() == ErrorKind::NoConvergence => {
                self.options.barrier.max_newton_iterations
            }
            Err(e) => return Err(e),
        };
        self.newton_steps += steps;
        problem.commit(x);
        Ok(())
    }

    /// Phase I from `control`: `τ` as a variable, `min τ + pull · fit` until `τ < 0`, the
    /// pull weakening as `t` grows (so that the fit keeps its hold while the conditions are
    /// driven to feasibility), each condition shifted by its own violation. `None` if
    /// no strictly feasible curve is found, or `τ` creeps towards zero from above (a
    /// degenerate configuration, `g ≡ 0` on a piece, not a way to feasibility): `τ` that
    /// stops halving, or stays far above the gap bound ([`PHASE_ONE_GAP_FACTOR`]).
    pub(super) fn phase_one(
        &mut self,
        problem: &mut EraserProblem,
        control: &[Vector2<f64>],
        z: f64,
    ) -> Option<DVector<f64>> {
        let x = problem.variables(control, z);
        problem.start_homotopy(&x, 0.1);
        problem.set_relaxed(true, 1.0);
        let mut y = problem.variables(control, z);
        let index = problem.tau_index();
        let mut t = problem.num_constraints() as f64;
        let mut found = false;
        let mut best_tau = f64::INFINITY;
        let mut stalled = 0;
        // Phase I needs no accurate centring: a few Newton steps per value of t.
        let quick = crate::barrier::BarrierOptions {
            max_newton_iterations: PHASE_ONE_NEWTON_STEPS,
            ..self.options.barrier.clone()
        };
        for _ in 0..self.options.max_rounds {
            let feasible = |v: &DVector<f64>| v[index] < 0.0;
            if self
                .centre_with(problem, &mut y, t, Some(&feasible), &quick)
                .is_err()
            {
                break;
            }
            if y[index] < 0.0 {
                found = true;
                break;
            }
            if y[index] > PHASE_ONE_GAP_FACTOR * problem.num_constraints() as f64 / t {
                break;
            }
            if y[index] > 0.5 * best_tau {
                stalled += 1;
                if stalled >= 2 {
                    break;
                }
            } else {
                stalled = 0;
            }
            best_tau = best_tau.min(y[index]);
            t *= self.options.barrier.t_growth;
            let pull = problem.pull() / self.options.barrier.t_growth;
            problem.set_relaxed(true, pull);
        }
        problem.set_relaxed(false, 1.0);
        problem.set_tau(0.0);
        found.then(|| y.rows(0, index).into_owned())
    }

    /// Phase II from a strictly feasible `x`: path following from `t = start · m` until the
    /// gap bound `m/t` is below `gap`, refining active conditions after each centring step (at most
    /// `max_refinements` passes). Returns the number of passes that split something.
    pub(super) fn phase_two(
        &mut self,
        problem: &mut EraserProblem,
        x: &mut DVector<f64>,
        start: f64,
        gap: f64,
        max_refinements: usize,
    ) -> Result<usize> {
        let mut t = start * problem.num_constraints() as f64;
        let mut refinements = 0;
        // Intermediate centring steps need not be accurate (the next t moves the centre
        // anyway); the last one is.
        let loose = crate::barrier::BarrierOptions {
            newton_tolerance: 1e-6,
            ..self.options.barrier.clone()
        };
        loop {
            let last = problem.num_constraints() as f64 / t < gap;
            if last {
                self.centre(problem, x, t, None)?;
            } else {
                self.centre_with(problem, x, t, None, &loose)?;
            }
            if refinements < max_refinements && problem.refine_active(x, 1e-3, 1.0 / 64.0) > 0 {
                refinements += 1;
            }
            if last {
                return Ok(refinements);
            }
            t *= self.options.barrier.t_growth;
        }
    }
}

/// What one attempt fits: `points` (normalised) at `params`, on the clamped `knots` (a
/// closed curve's periodic knots are its `0` and its interior knots) with the allowed
/// extrema at the knots `extrema` and the sign of the first piece `first_sign`.
#[derive(Clone, Copy)]
pub(crate) struct Task<'a> {
    pub(crate) points: &'a [Vector2<f64>],
    pub(crate) params: &'a [f64],
    pub(crate) knots: &'a KnotVector<f64>,
    pub(crate) extrema: &'a [f64],
    pub(crate) first_sign: f64,
    pub(crate) options: &'a SmoothingOptions,
}

/// The constrained fit of a [`Task`]: the continuation over the topology's nested spaces.
/// The attempt's curve is the container (the wrapped one of a closed curve). `None` when
/// no strictly feasible curve was found on any level.
pub(crate) fn attempt<T: Topology>(task: Task<'_>) -> Result<Option<Attempt>> {
    attempt_entering::<T>(task, None)
}

/// [`attempt`] from the container `start` of an earlier attempt on the same knots (its
/// curve solved for other data points): the continuation enters at the finest level from
/// that curve, the data's parameters its closest points (`params` the guesses), after
/// phase I where the curve is not strictly feasible for the fresh problem's conditions;
/// the path is entered late ([`WARM_START_T`]) when the data moved little (`near`: a
/// dragged point), where a cold start would be otherwise (a working set that grew by its
/// farthest points). `None` when phase I finds no strictly feasible curve from there.
pub(crate) fn attempt_from<T: Topology>(
    task: Task<'_>,
    start: &Curve2<f64>,
    near: bool,
) -> Result<Option<Attempt>> {
    let entry_t = if near { WARM_START_T } else { 10.0 };
    attempt_entering::<T>(task, Some((start.control_points(), entry_t)))
}

/// [`attempt`] or [`attempt_from`]: the levels of the task's knots, then the continuation.
fn attempt_entering<T: Topology>(
    task: Task<'_>,
    warm: Option<(&[Vector2<f64>], f64)>,
) -> Result<Option<Attempt>> {
    let levels = T::levels(task.knots, task.extrema)?;
    if levels.is_empty() {
        return Ok(None);
    }
    continuation::<T>(
        &levels,
        task.points,
        task.params,
        task.extrema,
        task.first_sign,
        task.options,
        warm,
    )
}

/// The coarse-to-fine continuation of one attempt, for open and closed curves alike: entry at
/// the finest level whose least-squares fit leads to a strictly feasible curve (at once or by
/// phase I), so that it starts as close to the data as it can; path following on each level
/// (loosely on the coarse ones), the solution carried to the next level's knots (phase I
/// mends what rounding breaks there); refinement of active conditions on the finest.
fn continuation<T: Topology>(
    spaces: &[T::Space],
    points: &[Vector2<f64>],
    params: &[f64],
    extrema: &[f64],
    first_sign: f64,
    options: &SmoothingOptions,
    warm: Option<(&[Vector2<f64>], f64)>,
) -> Result<Option<Attempt>> {
    let levels = spaces.len();
    let mut solver = Solver {
        options,
        newton_steps: 0,
    };
    let setup = |level: usize,
                 control: &[Vector2<f64>],
                 params: &[f64],
                 unit: Option<f64>|
     -> Result<(EraserProblem, DVector<f64>, f64)> {
        let finest = level + 1 == levels;
        let mut problem = EraserProblem::new(
            T::knots(&spaces[level]),
            T::CLOSED,
            points,
            params,
            options.objective,
            extrema.to_vec(),
            first_sign,
        )?;
        // Fixed parameters on the coarse levels (a coarse curve could otherwise fit the data
        // degenerately, all of them near one end); they follow the curve on the finest one.
        problem.set_projection(finest);
        let largest = problem
            .squared_distances(&problem.variables(control, 0.0))
            .iter()
            .copied()
            .fold(0.0, f64::max)
            .max(1e-24);
        let unit = unit.unwrap_or(largest);
        problem.set_unit(unit);
        let x = problem.variables(control, 1.25 * largest / unit);
        if finest {
            problem.set_excursions(&x, 2.0 * largest.sqrt());
        }
        problem.rescale(&x);
        Ok((problem, x, unit))
    };
    // The maximum deviation's bound: the variable after the control points' coordinates
    // (just before phase I's τ).
    let z_of = |x: &DVector<f64>, problem: &EraserProblem| {
        if options.objective == Objective::MaxDeviation {
            x[problem.tau_index() - 1]
        } else {
            0.0
        }
    };
    let mut entry = None;
    if let Some((control, _)) = warm {
        let level = levels - 1;
        let (curve, _) = T::solution(&spaces[level], control.to_vec())?;
        let mut corrected = project_ordered(&curve, points, params)?;
        T::hold_ends(&mut corrected);
        let (mut problem, x, unit) = setup(level, control, &corrected, None)?;
        // The earlier curve met conditions on pieces refined where they were active: the
        // same refinement brings the fresh, unrefined conditions back to it.
        let feasible = |problem: &EraserProblem| problem.constraints(&x).iter().all(|&c| c < 0.0);
        for _ in 0..options.max_refinements {
            if feasible(&problem) || problem.refine_active(&x, 0.0, 1.0 / 64.0) == 0 {
                break;
            }
        }
        if feasible(&problem) {
            entry = Some((level, problem, x, unit));
        } else {
            let z = z_of(&x, &problem);
            if let Some(found) = solver.phase_one(&mut problem, control, z) {
                entry = Some((level, problem, found, unit));
            }
        }
    }
    // Without a warm start, the finest level whose least-squares fit leads to a strictly
    // feasible curve.
    let cold_levels = if warm.is_some() { 0 } else { levels };
    for level in (0..cold_levels).rev() {
        let (fit, corrected) = match fit_with_correction::<T>(points, params, &spaces[level], 12) {
            Ok(found) => found,
            Err(e)
                if matches!(
                    e.kind(),
                    ErrorKind::SchoenbergWhitney | ErrorKind::SingularSystem
                ) =>
            {
                continue;
            }
            Err(e) => return Err(e),
        };
        let control = T::control_points(&fit);
        let (mut problem, x, unit) = setup(level, &control, &corrected, None)?;
        if problem.constraints(&x).iter().all(|&c| c < 0.0) {
            entry = Some((level, problem, x, unit));
            break;
        }
        let z = z_of(&x, &problem);
        if let Some(found) = solver.phase_one(&mut problem, &control, z) {
            entry = Some((level, problem, found, unit));
            break;
        }
    }
    let Some((first, mut problem, mut x, unit)) = entry else {
        return Ok(None);
    };
    let mut level = first;
    loop {
        let finest = level + 1 == levels;
        let (gap, max_refinements) = if finest {
            (options.barrier.gap_tolerance, options.max_refinements)
        } else {
            (1e-4, 0)
        };
        // A warm start near the end of the path already is entered late.
        let start = warm.map_or(10.0, |(_, entry_t)| entry_t);
        let refinements = solver.phase_two(&mut problem, &mut x, start, gap, max_refinements)?;
        let (curve, container) = T::solution(&spaces[level], problem.control_points(&x))?;
        if finest {
            return Ok(Some(Attempt {
                curve: container,
                refinements,
                conditions: problem.num_conditions(),
                newton_steps: solver.newton_steps,
                levels: levels - first,
            }));
        }
        let (refined, params) = T::next(
            &spaces[level],
            &spaces[level + 1],
            &curve,
            problem.anchors(),
            points,
        )?;
        level += 1;
        let control = T::control_points(&refined);
        let (mut next_problem, mut next_x, _) = setup(level, &control, &params, Some(unit))?;
        // Rounding can leave a condition at zero after the insertion: phase I mends it.
        if !next_problem.constraints(&next_x).iter().all(|&c| c < 0.0) {
            let z = z_of(&next_x, &next_problem);
            match solver.phase_one(&mut next_problem, &control, z) {
                Some(found) => next_x = found,
                None => return Ok(None),
            }
        }
        problem = next_problem;
        x = next_x;
    }
}
