//! Where the allowed extrema go, the least-squares fits they are placed on, and the knot
//! vectors of the coarse-to-fine continuation: each written once for open and closed curves
//! (what differs is the [`Topology`]).

use super::topology::Topology;
use super::{Extremum, ExtremumKind};
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_fit::project_ordered;
use spline_geom::{ParamCurve, PlanarCurve};

/// `(u, oriented κ(u), arc-length weight)` of `curve` at `count` parameters `k / count` of
/// `[0, 1]`, and at `1` too unless the curve is `closed` (where `1` is `0`).
///
/// # Errors
/// [`ErrorKind::DegenerateGeometry`] where the velocity vanishes; the errors of evaluation.
pub(crate) fn curvature_samples<C: PlanarCurve<f64>>(
    curve: &C,
    count: usize,
    closed: bool,
    orientation: f64,
) -> Result<Vec<(f64, f64, f64)>> {
    let du = 1.0 / count as f64;
    let mut first = [Vector2::zeros(); 2];
    (0..count + usize::from(!closed))
        .map(|k| {
            let u = k as f64 * du;
            curve.derivatives_into(u, &mut first)?;
            Ok((
                u,
                orientation * curve.signed_curvature(u)?,
                first[1].norm() * du,
            ))
        })
        .collect()
}

/// The weighted least-squares cost of making `values` monotone (pool adjacent violators),
/// for every prefix: entry `k` is the cost of `values[..=k]`. The pool is online, so all
/// prefixes cost one pass.
pub(super) fn isotonic_prefix_costs(values: &[(f64, f64, f64)], increasing: bool) -> Vec<f64> {
    // Blocks of (Σ w v, Σ w, Σ w v²) and the running cost Σ over blocks of (Σwv² − (Σwv)²/Σw).
    let mut blocks: Vec<(f64, f64, f64)> = Vec::with_capacity(values.len());
    let mut cost = 0.0;
    let block_cost = |(s, w, q): (f64, f64, f64)| q - s * s / w;
    let mut out = Vec::with_capacity(values.len());
    for &(_, v, w) in values {
        let v = if increasing { v } else { -v };
        let w = w.max(1e-300);
        blocks.push((w * v, w, w * v * v));
        while blocks.len() > 1 {
            let (s1, w1, q1) = blocks[blocks.len() - 2];
            let (s2, w2, q2) = blocks[blocks.len() - 1];
            if s1 / w1 > s2 / w2 {
                cost -= block_cost((s1, w1, q1));
                blocks.pop();
                let last = blocks.len() - 1;
                blocks[last] = (s1 + s2, w1 + w2, q1 + q2);
                cost += block_cost(blocks[last]);
            } else {
                break;
            }
        }
        out.push(cost.max(0.0));
    }
    out
}

/// The cost of making `values` monotone (the last prefix cost).
#[cfg(test)]
fn isotonic_cost(values: &[(f64, f64, f64)], increasing: bool) -> f64 {
    isotonic_prefix_costs(values, increasing)
        .last()
        .copied()
        .unwrap_or(0.0)
}

/// The sample of `window` (from [`curvature_samples`]) where an extremum needs the least
/// change of the curvature to make it monotone on both sides (rising before it when
/// `rising_before`, falling after; weighted isotonic regression along the arc length), among
/// the samples whose parameter is `admissible`; the first of equal costs.
fn cheapest_turn(
    window: &[(f64, f64, f64)],
    rising_before: bool,
    admissible: impl Fn(f64) -> bool,
) -> Option<f64> {
    // Prefix costs of the rising part and suffix costs of the falling part (the suffix read
    // backwards is a prefix of the reversed samples, monotone the other way).
    let before = isotonic_prefix_costs(window, rising_before);
    let reversed: Vec<(f64, f64, f64)> = window.iter().rev().copied().collect();
    let after = isotonic_prefix_costs(&reversed, rising_before);
    let mut best: Option<(f64, f64)> = None;
    for (k, sample) in window.iter().enumerate() {
        if !admissible(sample.0) {
            continue;
        }
        let cost = before[k] + after[window.len() - 1 - k];
        if best.is_none_or(|(c, _)| cost < c) {
            best = Some((cost, sample.0));
        }
    }
    best.map(|(_, u)| u)
}

/// The samples with parameters in `[lo, hi]`.
fn window(samples: &[(f64, f64, f64)], lo: f64, hi: f64) -> &[(f64, f64, f64)] {
    let left = samples.partition_point(|s| s.0 < lo);
    let right = samples.partition_point(|s| s.0 <= hi);
    &samples[left..right]
}

/// Samples of the curvature of an open curve for the placement of its extrema.
const OPEN_PLACEMENT_SAMPLES: usize = 2000;

/// Parameters of the allowed extrema: given ones as they are; automatic ones, from left to
/// right, at the [`cheapest_turn`] of the curvature of `fit` between the neighbouring
/// extrema (a margin of `0.01` from them).
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] when an automatic extremum has no room between its
/// neighbours or the result is not in increasing order.
pub(crate) fn place_extrema<C: PlanarCurve<f64>>(
    fit: &C,
    extrema: &[Extremum],
    orientation: f64,
) -> Result<Vec<f64>> {
    let samples = curvature_samples(fit, OPEN_PLACEMENT_SAMPLES, false, orientation)?;
    let mut slots: Vec<Option<f64>> = extrema.iter().map(|e| e.at).collect();
    for i in 0..extrema.len() {
        if slots[i].is_some() {
            continue;
        }
        let lo = (0..i).rev().find_map(|j| slots[j]).unwrap_or(0.0);
        let hi = (i + 1..extrema.len()).find_map(|j| slots[j]).unwrap_or(1.0);
        let margin = 0.01;
        let rising_before = extrema[i].kind == ExtremumKind::Maximum;
        let admissible = |u: f64| u > lo + margin && u < hi - margin;
        let Some(u) = cheapest_turn(window(&samples, lo, hi), rising_before, admissible) else {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "no room for curvature extremum {} between {lo} and {hi}: give its parameter",
                    i + 1
                ),
            )
            .with_index(i)
            .with_interval(lo, hi));
        };
        slots[i] = Some(u);
    }
    let placed: Vec<f64> = slots.into_iter().flatten().collect();
    if placed.windows(2).any(|w| !(w[1] > w[0])) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "the automatic extrema do not come in the order given: give their parameters",
        ));
    }
    Ok(placed)
}

/// Moves each extremum of `placed` (placed on a coarse fit) to the [`cheapest_turn`] of the
/// curvature `samples` of a finer fit, within a quarter of the distance to its neighbours
/// (the first piece rising when `first_rising`): the coarse fit finds the large turns, the
/// fine one their exact place.
pub(crate) fn refine_extrema(samples: &[(f64, f64, f64)], placed: &mut [f64], first_rising: bool) {
    let k = placed.len();
    for i in 0..k {
        let lo = if i == 0 { 0.0 } else { placed[i - 1] };
        let hi = if i + 1 == k { 1.0 } else { placed[i + 1] };
        let here = placed[i];
        let reach = 0.25 * (here - lo).min(hi - here);
        let rising_before = (i % 2 == 0) == first_rising;
        let admissible = |u: f64| (u - here).abs() <= reach;
        if let Some(u) = cheapest_turn(window(samples, lo, hi), rising_before, admissible) {
            placed[i] = u;
        }
    }
}

/// Least squares on `space` with `rounds` of parameter correction (each data point moves
/// to its closest point on the fit, in order; an open curve's end points stay at its ends);
/// returns the last fit and the corrected parameters.
///
/// # Errors
/// The errors of the topology's least squares (Schoenberg–Whitney, singular systems) and of
/// projection.
pub(crate) fn fit_with_correction<T: Topology>(
    points: &[Vector2<f64>],
    params: &[f64],
    space: &T::Space,
    rounds: usize,
) -> Result<(T::Curve, Vec<f64>)>
where
    T::Curve: ParamCurve<f64, Point = Vector2<f64>>,
{
    let mut params = params.to_vec();
    let mut curve = T::least_squares(points, &params, space)?;
    for _ in 0..rounds {
        params = project_ordered(&curve, points, &params)?;
        T::hold_ends(&mut params);
        curve = T::least_squares(points, &params, space)?;
    }
    Ok((curve, params))
}

/// The first and last data points at the ends of the domain `[0, 1]`.
pub(crate) fn pin_ends(params: &mut [f64]) {
    if let Some(first) = params.first_mut() {
        *first = 0.0;
    }
    if let Some(last) = params.last_mut() {
        *last = 1.0;
    }
}

/// The knots of `fine` that `coarse` lacks (with multiplicity; both sorted).
pub(crate) fn new_knots(coarse: &[f64], fine: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    let (c, f) = (coarse, fine);
    let mut i = 0;
    for &u in f {
        if i < c.len() && c[i] == u {
            i += 1;
        } else {
            out.push(u);
        }
    }
    out
}

/// Nested knot vectors from coarse to `knots`: each coarser level drops every other interior
/// knot that is not an extremum knot, down to the extremum knots alone.
///
/// # Errors
/// None for a valid clamped knot vector (the errors of [`KnotVector::clamped`]).
pub(crate) fn nested_levels(
    knots: &KnotVector<f64>,
    extrema: &[f64],
) -> Result<Vec<KnotVector<f64>>> {
    let p = knots.degree();
    let (a, b) = knots.domain();
    let interior = &knots.knots()[p + 1..knots.num_basis()];
    let fixed: Vec<f64> = interior
        .iter()
        .copied()
        .filter(|u| extrema.contains(u))
        .collect();
    let mut free: Vec<f64> = interior
        .iter()
        .copied()
        .filter(|u| !extrema.contains(u))
        .collect();
    let mut levels = Vec::new();
    loop {
        let mut all = fixed.clone();
        all.extend(&free);
        all.sort_by(f64::total_cmp);
        levels.push(KnotVector::clamped(p, a, b, &all)?);
        if free.is_empty() {
            break;
        }
        free = free.iter().skip(1).step_by(2).copied().collect();
    }
    levels.reverse();
    Ok(levels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isotonic_cost_of_monotone_data_is_zero() {
        let rising: Vec<(f64, f64, f64)> = (0..10).map(|k| (0.0, f64::from(k), 1.0)).collect();
        assert!(isotonic_cost(&rising, true).abs() < 1e-12);
        // Decreasing data made increasing: the best fit is the mean, cost = Σ (v − mean)².
        let cost = isotonic_cost(&rising, false);
        let mean = 4.5;
        let expected: f64 = (0..10).map(|k| (f64::from(k) - mean).powi(2)).sum();
        assert!((cost - expected).abs() < 1e-9, "{cost} {expected}");
    }

    #[test]
    fn levels_are_nested_and_keep_the_extremum_knots() {
        let knots =
            KnotVector::clamped(3, 0.0, 1.0, &[0.1, 0.2, 0.3, 0.45, 0.6, 0.7, 0.8, 0.9]).unwrap();
        let levels = nested_levels(&knots, &[0.45]).unwrap();
        assert_eq!(levels.last().unwrap(), &knots);
        assert_eq!(levels[0].knots().len(), 9); // 0.45 alone inside
        for w in levels.windows(2) {
            let added = new_knots(w[0].knots(), w[1].knots());
            assert_eq!(w[0].knots().len() + added.len(), w[1].knots().len());
            assert!(w[1].knots().contains(&0.45));
        }
    }
}
