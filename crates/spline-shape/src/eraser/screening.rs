//! Many data points: the eraser on a working set of them, grown where the others lie farther
//! from the curve (an active set on the deviation constraints).
//!
//! With [`Objective::MaxDeviation`] the problem bounds every data point's distance by one
//! variable, and the points that decide the answer are the few where the bound is reached.
//! Data with more than [`SCREENING_POINTS`] points are solved on every `k`-th point (the
//! ends always among them); the curve found is measured against all points, and every run
//! of consecutive points farther from it than the working set's largest distance gives its
//! farthest point to the working set, which is solved again from the last round's curve
//! (the continuation enters at the finest level, its sign conditions unchanged, only the
//! distance bounds new: [`attempt_from`]), until no point lies farther or after
//! [`SCREENING_ROUNDS`] rounds. The curve of the round closest to all points is the answer:
//! at the end, the curve of the whole problem's bound, with the working set's mean of
//! squared distances for the tie-break term. A round the continuation cannot solve leaves
//! the previous one's. Its deviations are measured on all points by the caller.
//!
//! Measured (release, 2 cores): 10⁵ noisy points of `0.1 sin 3t`, 20 control points, one
//! maximum: 79 s on all points, 2.7 s on the working set at the same largest distance; on
//! 3,000–20,000 noisy points of NACA sections the working set ended as close or closer in
//! every case (the solve on all points stopped early, its Newton steps crawling).
//!
//! [`Objective::LeastSquares`] has no such few points: every point counts in the sum, and
//! the problem is solved on all of them.

use super::driver::{Attempt, Task, attempt, attempt_from};
use super::topology::Topology;
use super::types::Objective;
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result};
use spline_fit::two_sided_deviation;
use spline_geom::Curve2;

/// Data with more points than this are solved on a working set (max deviation objective).
pub(crate) const SCREENING_POINTS: usize = 4096;

/// The largest number of times the working set grows.
pub(crate) const SCREENING_ROUNDS: usize = 8;

/// At most this many points join the working set in one round (the farthest runs first).
const JOINING_PER_ROUND: usize = 512;

/// [`attempt`] on the normalised data `points` with their parameters, on a working set of
/// the points when they are many (module documentation); the Newton steps of every round
/// are counted.
pub(super) fn attempt_screened<T: Topology>(task: Task<'_>) -> Result<Option<Attempt>> {
    let Task { points, params, .. } = task;
    let m = points.len();
    if m <= SCREENING_POINTS || task.options.objective != Objective::MaxDeviation {
        return attempt::<T>(task);
    }
    let stride = m.div_ceil(SCREENING_POINTS / 2);
    let mut working: Vec<usize> = (0..m).step_by(stride).collect();
    if working.last() != Some(&(m - 1)) {
        working.push(m - 1);
    }
    let mut newton_steps = 0;
    let mut best: Option<(Attempt, f64)> = None;
    let mut last: Option<Curve2<f64>> = None;
    for _ in 0..=SCREENING_ROUNDS {
        let subset: Vec<Vector2<f64>> = working.iter().map(|&i| points[i]).collect();
        let subset_params: Vec<f64> = working.iter().map(|&i| params[i]).collect();
        // From the last round's curve (entering at the finest level, its sign conditions
        // unchanged, only the distance bounds new), or afresh where that fails.
        let round = Task {
            points: &subset,
            params: &subset_params,
            ..task
        };
        let warm = match &last {
            Some(start) => attempt_from::<T>(round, start, false),
            None => Ok(None),
        };
        let warm = match warm {
            Ok(found) => found,
            Err(e) if recoverable(&e) => None,
            Err(e) => return Err(e),
        };
        let cold = || attempt::<T>(round);
        let found = match warm.map_or_else(cold, |found| Ok(Some(found))) {
            Ok(Some(found)) => found,
            // A grown working set that the continuation cannot solve (its path moves with
            // the data) leaves the curve of the last round.
            Ok(None) if best.is_some() => break,
            Err(e) if best.is_some() && recoverable(&e) => break,
            other => return other,
        };
        newton_steps += found.newton_steps;
        let (curve, _) = T::result(found.curve.clone())?;
        let distances = two_sided_deviation(&curve, points)?.to_curve.distances;
        let largest = distances.iter().copied().fold(0.0, f64::max);
        let bound = working.iter().map(|&i| distances[i]).fold(0.0, f64::max) * (1.0 + 1e-6);
        let joining = farthest_of_runs(&distances, bound);
        last = Some(found.curve.clone());
        if best.as_ref().is_none_or(|(_, b)| largest < *b) {
            best = Some((found, largest));
        }
        if joining.is_empty() {
            break;
        }
        working.extend(joining);
        working.sort_unstable();
        working.dedup();
    }
    Ok(best.map(|(mut found, _)| {
        found.newton_steps = newton_steps;
        found
    }))
}

/// The failures of an attempt that leave the previous round's curve standing (those the
/// caller treats as "no curve on these knots").
pub(super) fn recoverable(e: &Error) -> bool {
    matches!(
        e.kind(),
        ErrorKind::SchoenbergWhitney
            | ErrorKind::SingularSystem
            | ErrorKind::NonFinite
            | ErrorKind::NoConvergence
    )
}

/// The farthest point of every run of consecutive points farther than `bound`, at most
/// [`JOINING_PER_ROUND`] of them (the farthest first).
fn farthest_of_runs(distances: &[f64], bound: f64) -> Vec<usize> {
    let mut peaks: Vec<usize> = Vec::new();
    let mut run: Option<usize> = None;
    for (i, &d) in distances.iter().enumerate() {
        if d > bound {
            run = match run {
                Some(best) if distances[best] >= d => Some(best),
                _ => Some(i),
            };
        } else if let Some(best) = run.take() {
            peaks.push(best);
        }
    }
    peaks.extend(run);
    peaks.sort_by(|&a, &b| distances[b].total_cmp(&distances[a]));
    peaks.truncate(JOINING_PER_ROUND);
    peaks
}

#[cfg(test)]
mod tests {
    use super::farthest_of_runs;

    #[test]
    fn each_run_gives_its_farthest_point() {
        let d = [0.0, 2.0, 3.0, 1.0, 0.5, 4.0, 0.0, 2.5];
        assert_eq!(farthest_of_runs(&d, 1.0), vec![5, 2, 7]);
        assert!(farthest_of_runs(&d, 4.0).is_empty());
    }
}
