//! Where the allowed extrema go, and the knot vectors of the coarse-to-fine continuation.

use super::{Extremum, ExtremumKind};
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_fit::{LeastSquares, project_ordered};
use spline_geom::{BSpline, Curve2};

/// `(u, oriented κ(u), arc-length weight)` of `curve` on a dense grid.
fn curvature_samples(curve: &Curve2<f64>, orientation: f64) -> Result<Vec<(f64, f64, f64)>> {
    let samples = 2000;
    let du = 1.0 / f64::from(samples);
    (0..=samples)
        .map(|k| {
            let u = f64::from(k) * du;
            let d = curve.derivatives(u, 1)?;
            Ok((
                u,
                orientation * curve.signed_curvature(u)?,
                d[1].norm() * du,
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

/// Parameters of the allowed extrema: given ones as they are; automatic ones, from left to
/// right, where the curvature of `fit` needs the least change to become monotone on both
/// sides (weighted isotonic regression along the arc length, between the neighbouring
/// extrema).
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] when an automatic extremum has no room between its
/// neighbours or the result is not in increasing order.
pub(crate) fn place_extrema(
    fit: &Curve2<f64>,
    extrema: &[Extremum],
    orientation: f64,
) -> Result<Vec<f64>> {
    let samples = curvature_samples(fit, orientation)?;
    let mut slots: Vec<Option<f64>> = extrema.iter().map(|e| e.at).collect();
    for i in 0..extrema.len() {
        if slots[i].is_some() {
            continue;
        }
        let lo = (0..i).rev().find_map(|j| slots[j]).unwrap_or(0.0);
        let hi = (i + 1..extrema.len()).find_map(|j| slots[j]).unwrap_or(1.0);
        let margin = 0.01;
        let left = samples.partition_point(|s| s.0 < lo);
        let right = samples.partition_point(|s| s.0 <= hi);
        let rising_before = extrema[i].kind == ExtremumKind::Maximum;
        let window = &samples[left..right];
        // Prefix costs of the rising part and suffix costs of the falling part (the suffix
        // read backwards is a prefix of the reversed samples, monotone the other way).
        let before = isotonic_prefix_costs(window, rising_before);
        let reversed: Vec<(f64, f64, f64)> = window.iter().rev().copied().collect();
        let after = isotonic_prefix_costs(&reversed, rising_before);
        let mut best: Option<(f64, f64)> = None;
        for (k, sample) in window.iter().enumerate() {
            let u = sample.0;
            if !(u > lo + margin && u < hi - margin) {
                continue;
            }
            let cost = before[k] + after[window.len() - 1 - k];
            if best.is_none_or(|(c, _)| cost < c) {
                best = Some((cost, u));
            }
        }
        let Some((_, u)) = best else {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "no room for curvature extremum {} between {lo} and {hi}: give its parameter",
                    i + 1
                ),
            ));
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

/// Least squares on `knots` with `rounds` of parameter correction (projection of each point
/// on the curve, in order, the end points staying at the ends); returns the last fit and the
/// corrected parameters.
///
/// # Errors
/// The errors of [`LeastSquares::control_points`] (Schoenberg–Whitney, singular systems).
pub(crate) fn fit_with_correction(
    points: &[Vector2<f64>],
    params: &[f64],
    knots: &KnotVector<f64>,
    rounds: usize,
) -> Result<(Curve2<f64>, Vec<f64>)> {
    let mut params = params.to_vec();
    let fit = |params: &[f64]| -> Result<Curve2<f64>> {
        BSpline::new(
            knots.clone(),
            LeastSquares::new(points, params, knots.clone()).control_points()?,
        )
    };
    let mut curve = fit(&params)?;
    for _ in 0..rounds {
        params = project_ordered(&curve, points, &params)?;
        pin_ends(&mut params);
        curve = fit(&params)?;
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

/// The knots of `fine` that `coarse` lacks (with multiplicity).
pub(crate) fn new_knots(coarse: &KnotVector<f64>, fine: &KnotVector<f64>) -> Vec<f64> {
    let mut out = Vec::new();
    let (c, f) = (coarse.knots(), fine.knots());
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
            let added = new_knots(&w[0], &w[1]);
            assert_eq!(w[0].knots().len() + added.len(), w[1].knots().len());
            assert!(w[1].knots().contains(&0.45));
        }
    }
}
