//! The eraser's [`Topology`] of open curves: nested clamped knot vectors, the ends pinned to
//! the first and last data points.

use super::placement::{fit_with_correction, nested_levels, new_knots, pin_ends, place_extrema};
use super::topology::{ClosedCurve2, FEATURE_ACCURACY, Open, Start, Topology, sign_before};
use super::types::SmoothingOptions;
use nalgebra::Vector2;
use spline_algebra::{CurveFeatures, PlanarFeatures};
use spline_core::{KnotVector, Result};
use spline_fit::{
    LeastSquares, Parametrization, TwoSidedDeviation, nurbs_book_knots, parametrize_above_noise,
    project_ordered,
};
use spline_geom::{BSpline, Curve2};

impl Topology for Open {
    type Curve = Curve2<f64>;
    type Space = KnotVector<f64>;
    const CLOSED: bool = false;

    fn count_once(_: &mut Vec<Vector2<f64>>) {}

    fn start(unit: &[Vector2<f64>], options: &SmoothingOptions, orientation: f64) -> Result<Start> {
        // Centripetal, measured above the data's noise (dense scans).
        let params = parametrize_above_noise(unit, &Parametrization::Centripetal)?;
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
