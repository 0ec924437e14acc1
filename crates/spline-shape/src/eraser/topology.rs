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
//!
//! The trait and the two topologies are declared here; their implementations live in
//! `open_topology.rs` and `closed_topology.rs`, above the stages they call.

use super::types::{ExtremumKind, SmoothingOptions};
use nalgebra::Vector2;
use spline_algebra::PlanarFeatures;
use spline_core::{KnotVector, Result};
use spline_fit::TwoSidedDeviation;
use spline_geom::{Curve2, ParamCurve, PeriodicBSpline};

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

/// Open or closed: the data, the start, the spaces of the continuation and the result.
/// The sign of the first piece when the first allowed extremum is of kind `kind`: the
/// curvature rises towards a maximum of the oriented curvature.
pub(super) fn sign_before(kind: ExtremumKind, orientation: f64) -> f64 {
    match kind {
        ExtremumKind::Maximum => orientation,
        ExtremumKind::Minimum => -orientation,
    }
}

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
    /// As [`super::placement::nested_levels`].
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
pub(super) const FEATURE_ACCURACY: f64 = 1e-10;

/// Open curves: nested clamped knot vectors, the ends pinned to the first and last points.
pub(crate) struct Open;

/// Closed curves: nested periodic spaces (those of [`super::placement::nested_levels`], each with the closing
/// point `0` as a knot), held as periodic curves with zero control points.
pub(crate) struct Closed;
