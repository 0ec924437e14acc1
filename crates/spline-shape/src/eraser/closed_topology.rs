//! The eraser's [`Topology`] of closed curves: nested periodic spaces with the closing point
//! `0` as a knot, held as periodic curves.

use super::closed::closed_start;
use super::placement::{nested_levels, new_knots, place_extrema};
use super::topology::{Closed, ClosedCurve2, FEATURE_ACCURACY, Start, Topology, sign_before};
use super::types::SmoothingOptions;
use nalgebra::Vector2;
use spline_algebra::{CurveFeatures, PlanarFeatures};
use spline_core::{KnotVector, Result};
use spline_fit::{TwoSidedDeviation, least_squares_periodic, project_ordered};
use spline_geom::{BSpline, Curve2, PeriodicBSpline};

/// The periodic space of period 1 whose knots of one period are those of the clamped knot
/// vector `clamped` on `[0, 1]` with `N + p` basis functions: `0` and its `N − 1` interior
/// knots.
pub(crate) fn periodic_space(clamped: &KnotVector<f64>) -> Result<ClosedCurve2> {
    let p = clamped.degree();
    let k = clamped.knots();
    let interior = &k[p + 1..k.len() - p - 1];
    let mut period_knots = Vec::with_capacity(interior.len() + 1);
    period_knots.push(0.0);
    period_knots.extend_from_slice(interior);
    let count = period_knots.len();
    PeriodicBSpline::new(p, period_knots, 1.0, vec![Vector2::zeros(); count])
}

/// Foot-point parameters as [`project_ordered`] takes them: in `[0, 1]` and not decreasing
/// (a foot point that crossed the closing point is moved back to its end of the period).
fn sorted_in_period(params: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = params.iter().map(|u| u.clamp(0.0, 1.0)).collect();
    for k in 1..out.len() {
        if out[k] < out[k - 1] {
            out[k] = out[k - 1];
        }
    }
    out
}

impl Topology for Closed {
    type Curve = ClosedCurve2;
    type Space = ClosedCurve2;
    const CLOSED: bool = true;

    fn count_once(data: &mut Vec<Vector2<f64>>) {
        if data.len() > 2 && data.last() == data.first() {
            data.pop();
        }
    }

    fn start(unit: &[Vector2<f64>], options: &SmoothingOptions, orientation: f64) -> Result<Start> {
        let automatic = options
            .extrema
            .iter()
            .all(|e| e.at.is_none())
            .then_some(options.extrema.len());
        let start = closed_start(
            unit,
            options.degree,
            options.control_points,
            automatic,
            orientation,
        )?;
        let (placed, first_sign) = match start.placed {
            Some((placed, rising)) => (placed, if rising { orientation } else { -orientation }),
            None => (
                place_extrema(&start.shape, &options.extrema, orientation)?,
                sign_before(options.extrema[0].kind, orientation),
            ),
        };
        Ok(Start {
            rotation: start.rotation,
            shape: start.shape,
            params: start.params,
            placed,
            first_sign,
        })
    }

    fn basis_count(n: usize, p: usize) -> usize {
        n + p
    }

    fn polyline(data: &[Vector2<f64>]) -> Vec<Vector2<f64>> {
        let mut polyline = data.to_vec();
        polyline.push(data[0]);
        polyline
    }

    fn levels(knots: &KnotVector<f64>, extrema: &[f64]) -> Result<Vec<Self::Space>> {
        // Levels with fewer knots than a periodic curve of degree p needs are skipped.
        Ok(nested_levels(knots, extrema)?
            .into_iter()
            .filter_map(|level| periodic_space(&level).ok())
            .collect())
    }

    fn knots(space: &Self::Space) -> &KnotVector<f64> {
        space.wrapped().knots()
    }

    fn least_squares(
        points: &[Vector2<f64>],
        params: &[f64],
        space: &Self::Space,
    ) -> Result<Self::Curve> {
        least_squares_periodic(points, params, space, None, 0.0)
    }

    fn hold_ends(_: &mut [f64]) {}

    fn control_points(curve: &Self::Curve) -> Vec<Vector2<f64>> {
        curve.wrapped().control_points().to_vec()
    }

    fn solution(
        space: &Self::Space,
        control: Vec<Vector2<f64>>,
    ) -> Result<(Self::Curve, Curve2<f64>)> {
        let wrapped = BSpline::new(Self::knots(space).clone(), control)?;
        Ok((PeriodicBSpline::from_wrapped(&wrapped)?, wrapped))
    }

    fn next(
        coarse: &Self::Space,
        fine: &Self::Space,
        curve: &Self::Curve,
        anchors: Vec<f64>,
        points: &[Vector2<f64>],
    ) -> Result<(Self::Curve, Vec<f64>)> {
        // One knot at a time, not [`PeriodicBSpline::refine`]: one refinement of all the
        // knots rounds differently, and the closed eraser's results (which the tool's outputs
        // pin byte for byte) follow those last bits.
        let mut refined = curve.clone();
        for u in new_knots(coarse.period_knots(), fine.period_knots()) {
            refined = refined.insert_knot(u, 1)?;
        }
        let params = project_ordered(&refined, points, &sorted_in_period(&anchors))?;
        Ok((refined, params))
    }

    fn result(world: Curve2<f64>) -> Result<(Curve2<f64>, Option<ClosedCurve2>)> {
        let periodic = PeriodicBSpline::from_wrapped(&world)?;
        Ok((periodic.open_at(0.0)?, Some(periodic)))
    }

    /// The deviations of closed data measured on the data rotated by `rotation` and closed
    /// by a repeated first point, put back in the order of the `count` data points.
    fn in_data_order(deviation: &mut TwoSidedDeviation<f64>, rotation: usize, count: usize) {
        let to_curve = &mut deviation.to_curve;
        to_curve.distances.truncate(count);
        to_curve.distances.rotate_right(rotation);
        deviation.params.truncate(count);
        deviation.params.rotate_right(rotation);
        to_curve.max_index = (to_curve.max_index % count + rotation) % count;
    }

    fn features(
        curve: &Curve2<f64>,
        periodic: Option<&ClosedCurve2>,
    ) -> Result<PlanarFeatures<f64>> {
        match periodic {
            Some(periodic) => periodic.features(FEATURE_ACCURACY),
            None => curve.features(FEATURE_ACCURACY),
        }
    }
}
