//! gnuplot `.dat` files (seed 000's `drawCurve` and `drawPoly`): one point per line,
//! coordinates separated by spaces.

use spline_core::{ControlPoint, Scalar, to_f64};
use spline_geom::ParamCurve;

fn row<T: Scalar, P: ControlPoint<T>>(p: &P) -> String {
    (0..P::DIM)
        .map(|i| format!("{}", to_f64(p.coord(i))))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The curve sampled for gnuplot: one point per line, coordinates separated by spaces
/// (`per_span` samples per knot span, [`ParamCurve::sample_params`]).
///
/// # Panics
/// Never: the samples lie in the domain.
#[must_use]
pub fn gnuplot_curve<T: Scalar, C: ParamCurve<T>>(curve: &C, per_span: usize) -> String {
    let params = curve.sample_params(per_span);
    let points = curve.eval_many(&params).expect("samples lie in the domain");
    points.iter().map(|p| row(p) + "\n").collect()
}

/// The control polygon for gnuplot: one control point per line.
#[must_use]
pub fn gnuplot_polygon<T: Scalar, C: ParamCurve<T>>(curve: &C) -> String {
    curve
        .control_polygon()
        .iter()
        .map(|p| row(p) + "\n")
        .collect()
}
