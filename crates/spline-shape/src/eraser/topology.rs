//! What differs between open and closed curves, behind one trait: the stages of the eraser
//! ([`super::smooth`], the continuation of [`super::driver`], the fits and placements of
//! [`super::placement`]) are written once over a [`Topology`].
//!
//! An open curve is a clamped B-spline on `[0, 1]` whose ends stay at the first and last data
//! points. A closed one is a periodic B-spline of period 1 held as its wrapped container
//! (`N + p` control points, the last `p` repeating the first `p`; its knots extend those of
//! one period by the period), so that the sign conditions of every segment and the foot
//! points of every data point see one curve without an end: the variables are the `N` free
//! control points, foot points cross the closing point, and the pieces between the allowed
//! extrema wrap around it (an even number of extrema, alternating around the curve).

use super::closed::closed_start;
use super::placement::{fit_with_correction, nested_levels, new_knots, pin_ends, place_extrema};
use super::types::{ExtremumKind, SmoothingOptions};
use nalgebra::Vector2;
use spline_algebra::{CurveFeatures, PlanarFeatures};
use spline_core::{KnotVector, Result};
use spline_fit::{
    LeastSquares, Parametrization, TwoSidedDeviation, least_squares_periodic, nurbs_book_knots,
    parametrize, project_ordered,
};
use spline_geom::{BSpline, Curve2, ParamCurve, PeriodicBSpline};

/// A closed planar curve.
pub(crate) type ClosedCurve2 = PeriodicBSpline<f64, Vector2<f64>>;

/// Where the smoothing starts: the least-squares shape of the data and the allowed extrema
/// placed on it.
pub(crate) struct Start {
    /// The data point that becomes the first (a closed contour's closing point moves into a
    /// monotone stretch of the curvature); `0` for open data.
    pub(crate) rotation: usize,
    /// The shape on `[0, 1]` (a closed one opened at its closing point).
    pub(crate) shape: Curve2<f64>,
    /// The parameters of the (rotated) data on it.
    pub(crate) params: Vec<f64>,
    /// The parameters of the allowed extrema.
    pub(crate) placed: Vec<f64>,
    /// `+1` where the curvature rises on the first piece, `−1` where it falls.
    pub(crate) first_sign: f64,
}

/// The sign of the first piece when the first allowed extremum is of kind `kind`: the
/// curvature rises towards a maximum of the oriented curvature.
fn sign_before(kind: ExtremumKind, orientation: f64) -> f64 {
    match kind {
        ExtremumKind::Maximum => orientation,
        ExtremumKind::Minimum => -orientation,
    }
}

/// Open or closed: the data, the start, the spaces of the continuation and the result.
pub(crate) trait Topology {
    /// The curve the continuation carries from level to level.
    type Curve: ParamCurve<f64, Point = Vector2<f64>>;
    /// The space of one level of the continuation.
    type Space;
    /// Whether the curve is closed (the problem's variables and foot points wrap).
    const CLOSED: bool;

    /// The data as the topology counts them (a closed contour's repeated first point at the
    /// end counts once).
    fn count_once(data: &mut Vec<Vector2<f64>>);

    /// The shape of the normalised data `unit` and the extrema placed on it.
    ///
    /// # Errors
    /// The errors of the fits and of the placement.
    fn start(unit: &[Vector2<f64>], options: &SmoothingOptions, orientation: f64) -> Result<Start>;

    /// The number of basis functions of the clamped knot vector whose interior knots the
    /// curve gets, for `n` control points of degree `p`.
    fn basis_count(n: usize, p: usize) -> usize;

    /// The polyline the deviations are measured against (a closed contour's closes).
    fn polyline(data: &[Vector2<f64>]) -> Vec<Vector2<f64>>;

    /// The spaces of the continuation, coarse to fine, ending on the clamped `knots`.
    ///
    /// # Errors
    /// As [`nested_levels`].
    fn levels(knots: &KnotVector<f64>, extrema: &[f64]) -> Result<Vec<Self::Space>>;

    /// The knots of the problem's container on `space`.
    fn knots(space: &Self::Space) -> &KnotVector<f64>;

    /// Least squares on `space`.
    ///
    /// # Errors
    /// As the fit (Schoenberg–Whitney, singular systems).
    fn least_squares(
        points: &[Vector2<f64>],
        params: &[f64],
        space: &Self::Space,
    ) -> Result<Self::Curve>;

    /// Parameters after a correction: an open curve's first and last data points stay at its
    /// ends.
    fn hold_ends(params: &mut [f64]);

    /// The control points the problem's variables hold (the wrapped ones of a closed curve).
    fn control_points(curve: &Self::Curve) -> Vec<Vector2<f64>>;

    /// The curve of the solution's `control` points on `space`, and the container the
    /// attempt returns (the wrapped one of a closed curve).
    ///
    /// # Errors
    /// As the containers' constructors.
    fn solution(
        space: &Self::Space,
        control: Vec<Vector2<f64>>,
    ) -> Result<(Self::Curve, Curve2<f64>)>;

    /// The same curve on the `fine` space (unchanged, so still strictly feasible) and the
    /// data's parameters on it, from the solution's anchors.
    ///
    /// # Errors
    /// As refinement and projection.
    fn next(
        coarse: &Self::Space,
        fine: &Self::Space,
        curve: &Self::Curve,
        anchors: Vec<f64>,
        points: &[Vector2<f64>],
    ) -> Result<(Self::Curve, Vec<f64>)>;

    /// The result on `[0, 1]` from the attempt's container in data coordinates, and the
    /// periodic curve of a closed one.
    ///
    /// # Errors
    /// As the containers' constructors.
    fn result(world: Curve2<f64>) -> Result<(Curve2<f64>, Option<ClosedCurve2>)>;

    /// The deviations, measured on the rotated data, in the order of the `count` data points.
    fn in_data_order(deviation: &mut TwoSidedDeviation<f64>, rotation: usize, count: usize);

    /// The inflections and curvature extrema of the result: those strictly inside `[0, 1]`
    /// of an open curve (its ends are not extrema of a curve that stops there); those of one
    /// period of a closed one, its closing point `0` included.
    ///
    /// # Errors
    /// As [`CurveFeatures::features`] (a velocity that vanishes somewhere).
    fn features(
        curve: &Curve2<f64>,
        periodic: Option<&ClosedCurve2>,
    ) -> Result<PlanarFeatures<f64>>;
}

/// Accuracy of the features of the result.
const FEATURE_ACCURACY: f64 = 1e-10;

/// Open curves: nested clamped knot vectors, the ends pinned to the first and last points.
pub(crate) struct Open;

impl Topology for Open {
    type Curve = Curve2<f64>;
    type Space = KnotVector<f64>;
    const CLOSED: bool = false;

    fn count_once(_: &mut Vec<Vector2<f64>>) {}

    fn start(unit: &[Vector2<f64>], options: &SmoothingOptions, orientation: f64) -> Result<Start> {
        let params = parametrize(unit, &Parametrization::Centripetal)?;
        let base = nurbs_book_knots(options.degree, options.control_points, &params)?;
        let (shape, params) = fit_with_correction::<Self>(unit, &params, &base, 8)?;
        let placed = place_extrema(&shape, &options.extrema, orientation)?;
        Ok(Start {
            rotation: 0,
            shape,
            params,
            placed,
            first_sign: sign_before(options.extrema[0].kind, orientation),
        })
    }

    fn basis_count(n: usize, _: usize) -> usize {
        n
    }

    fn polyline(data: &[Vector2<f64>]) -> Vec<Vector2<f64>> {
        data.to_vec()
    }

    fn levels(knots: &KnotVector<f64>, extrema: &[f64]) -> Result<Vec<Self::Space>> {
        nested_levels(knots, extrema)
    }

    fn knots(space: &Self::Space) -> &KnotVector<f64> {
        space
    }

    fn least_squares(
        points: &[Vector2<f64>],
        params: &[f64],
        space: &Self::Space,
    ) -> Result<Self::Curve> {
        BSpline::new(
            space.clone(),
            LeastSquares::new(points, params, space.clone()).control_points()?,
        )
    }

    fn hold_ends(params: &mut [f64]) {
        pin_ends(params);
    }

    fn control_points(curve: &Self::Curve) -> Vec<Vector2<f64>> {
        curve.control_points().to_vec()
    }

    fn solution(
        space: &Self::Space,
        control: Vec<Vector2<f64>>,
    ) -> Result<(Self::Curve, Curve2<f64>)> {
        let curve = BSpline::new(space.clone(), control)?;
        Ok((curve.clone(), curve))
    }

    fn next(
        _: &Self::Space,
        fine: &Self::Space,
        curve: &Self::Curve,
        mut anchors: Vec<f64>,
        points: &[Vector2<f64>],
    ) -> Result<(Self::Curve, Vec<f64>)> {
        pin_ends(&mut anchors);
        let refined = curve.refine(&new_knots(curve.knots().knots(), fine.knots()))?;
        let mut params = project_ordered(&refined, points, &anchors)?;
        pin_ends(&mut params);
        Ok((refined, params))
    }

    fn result(world: Curve2<f64>) -> Result<(Curve2<f64>, Option<ClosedCurve2>)> {
        Ok((world, None))
    }

    fn in_data_order(_: &mut TwoSidedDeviation<f64>, _: usize, _: usize) {}

    fn features(curve: &Curve2<f64>, _: Option<&ClosedCurve2>) -> Result<PlanarFeatures<f64>> {
        let mut features = curve.features(FEATURE_ACCURACY)?;
        features
            .curvature_extrema
            .retain(|&u| u > 1e-9 && u < 1.0 - 1e-9);
        Ok(features)
    }
}

/// Closed curves: nested periodic spaces (those of [`nested_levels`], each with the closing
/// point `0` as a knot), held as periodic curves with zero control points.
pub(crate) struct Closed;

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
