//! The values every endpoint reads and answers, checked against the studio's limits:
//! planar points, counts, curves as exchange-format records, drawn samples. [`crate::api`]
//! re-exports them; the labs build on them.

use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result};
use spline_geom::{BSpline, ParamCurve};
use spline_io::exchange::CurveRecord;

/// A planar point of the studio.
pub type Point = Vector2<f64>;

/// The largest number of points (data or control points) a request may carry.
pub const MAX_POINTS: usize = 100_000;
/// The largest number of samples a drawn curve may ask for (per span, or in all for Bézier
/// curves).
pub const MAX_SAMPLES: usize = 10_000;
/// The largest degree the studio accepts (Bézier curves of many points included).
pub const MAX_DEGREE: usize = 60;

/// Checks a list of `[x, y]` points: at most [`MAX_POINTS`], at least `min`, all finite.
///
/// # Errors
/// [`ErrorKind::TooFewPoints`], [`ErrorKind::InvalidLength`] or [`ErrorKind::NonFinite`].
pub fn points(raw: &[[f64; 2]], min: usize, what: &str) -> Result<Vec<Point>> {
    if raw.len() > MAX_POINTS {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("{what}: {} points, at most {MAX_POINTS}", raw.len()),
        ));
    }
    if raw.len() < min {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!("{what}: {} point(s), at least {min} needed", raw.len()),
        ));
    }
    if let Some(k) = raw.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("{what}: point {k} is not finite"),
        ));
    }
    Ok(raw.iter().map(|p| Vector2::new(p[0], p[1])).collect())
}

/// Checks a count given by the user against `1..=max`.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`].
pub fn count(value: usize, max: usize, what: &str) -> Result<usize> {
    if value == 0 || value > max {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("{what} must be between 1 and {max}, got {value}"),
        )
        .with_value(value as f64)
        .with_interval(1.0, max as f64));
    }
    Ok(value)
}

/// `[x, y]` for JSON.
#[must_use]
pub fn xy(p: &Point) -> [f64; 2] {
    [p.x, p.y]
}

/// `[x, y]` of each point.
#[must_use]
pub fn xys(points: &[Point]) -> Vec<[f64; 2]> {
    points.iter().map(xy).collect()
}

/// The exchange-format record of a planar B-spline curve.
#[must_use]
pub fn record(curve: &BSpline<f64, Point>) -> CurveRecord {
    CurveRecord::from_bspline(curve)
}

/// A planar B-spline curve from its exchange-format record.
///
/// # Errors
/// [`ErrorKind::DimensionMismatch`] unless the points are 2-D; [`ErrorKind::InvalidLength`]
/// beyond [`MAX_POINTS`]; the errors of [`CurveRecord::to_bspline`].
pub fn planar(record: &CurveRecord) -> Result<BSpline<f64, Point>> {
    if record.control_points.len() > MAX_POINTS || record.knots.len() > MAX_POINTS + MAX_DEGREE {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("curve: more than {MAX_POINTS} control points"),
        ));
    }
    if record.weights.is_some() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "curve: the studio draws B-spline curves (no weights)",
        ));
    }
    let d = record.dimension()?;
    if d != 2 {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("curve: the studio draws planar curves, this one has dimension {d}"),
        ));
    }
    record.to_bspline()
}

/// The points of the drawn polyline of a B-spline curve: `per_span` equal parameter steps
/// in every knot span ([`ParamCurve::sample_params`]), as `[x, y]`.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for `per_span` outside `1..=MAX_SAMPLES`; evaluation
/// errors.
pub fn samples(curve: &BSpline<f64, Point>, per_span: usize) -> Result<Vec<[f64; 2]>> {
    count(per_span, MAX_SAMPLES, "samples per span")?;
    let params = curve.sample_params(per_span);
    if params.len() > MAX_POINTS {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "{} samples asked for, at most {MAX_POINTS}: fewer per span",
                params.len()
            ),
        ));
    }
    Ok(xys(&curve.eval_many(&params)?))
}
