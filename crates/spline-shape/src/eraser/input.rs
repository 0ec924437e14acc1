//! The checks of the options and the data, and the data's frame.

use super::types::{ExtremumKind, MAX_CURVATURE_EXTREMA, SmoothingOptions, extrema_words};
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result};

/// The options' errors, as [`super::smooth`] documents them.
pub(crate) fn check_options(options: &SmoothingOptions) -> Result<()> {
    let p = options.degree;
    if p < 3 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "smoothing needs degree 3 or more (the curvature's derivative involves c‴), got {p}"
            ),
        )
        .with_value(p as f64)
        .with_interval(3.0, f64::INFINITY));
    }
    if options.extrema.is_empty() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "allow at least one curvature extremum",
        )
        .with_counts(1, 0));
    }
    if options.extrema.len() > MAX_CURVATURE_EXTREMA {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "at most {MAX_CURVATURE_EXTREMA} curvature extrema can be allowed, got {}",
                options.extrema.len()
            ),
        )
        .with_counts(MAX_CURVATURE_EXTREMA, options.extrema.len()));
    }
    if options.knot_exponents.is_empty() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "knot density exponents must be given, finite and not negative",
        )
        .with_counts(1, 0));
    }
    if let Some((i, &e)) = options
        .knot_exponents
        .iter()
        .enumerate()
        .find(|(_, e)| !(**e >= 0.0 && e.is_finite()))
    {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("knot density exponent {i} must be finite and not negative, got {e}"),
        )
        .with_index(i)
        .with_value(e)
        .with_interval(0.0, f64::INFINITY));
    }
    for (i, w) in options.extrema.windows(2).enumerate() {
        if w[0].kind == w[1].kind {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "curvature extrema alternate: a {} must be followed by a {}",
                    w[0].kind,
                    match w[0].kind {
                        ExtremumKind::Maximum => ExtremumKind::Minimum,
                        ExtremumKind::Minimum => ExtremumKind::Maximum,
                    }
                ),
            )
            .with_index(i + 1));
        }
    }
    if options.closed && options.extrema.len() % 2 != 0 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the curvature of a closed curve has as many maxima as minima: allow an even number of extrema, got {}",
                options.extrema.len()
            ),
        )
        .with_value(options.extrema.len() as f64));
    }
    let mut last = 0.0;
    for (i, e) in options.extrema.iter().enumerate() {
        if let Some(u) = e.at {
            if !(u > last && u < 1.0) {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!("extremum parameter {u} must lie in (0, 1), after the previous one"),
                )
                .with_index(i)
                .with_value(u)
                .with_interval(last, 1.0));
            }
            last = u;
        }
    }
    let k = options.extrema.len();
    let n = options.control_points;
    // One span per piece at least, and room for the extremum knots of multiplicity p − 2.
    let needed = p + 1 + k * (p - 2);
    if n < needed {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{} need at least {needed} control points of degree {p}, got {n}",
                extrema_words(k)
            ),
        )
        .with_counts(needed, n));
    }
    Ok(())
}

/// The points without consecutive repetitions; all finite, at least two distinct.
pub(crate) fn distinct(points: &[Vector2<f64>]) -> Result<Vec<Vector2<f64>>> {
    if let Some(k) = points
        .iter()
        .position(|q| !(q.x.is_finite() && q.y.is_finite()))
    {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("data point {k} is not finite"),
        ));
    }
    let mut out: Vec<Vector2<f64>> = Vec::with_capacity(points.len());
    for q in points {
        if out.last() != Some(q) {
            out.push(*q);
        }
    }
    if out.len() < 2 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            "smoothing needs at least two distinct data points",
        ));
    }
    Ok(out)
}

/// Centre and diagonal of the bounding box, without underflow or overflow at any scale the
/// numbers hold (data at 1e-300 or 1e300 have a diagonal too).
pub(crate) fn frame(points: &[Vector2<f64>]) -> (Vector2<f64>, f64) {
    let mut lo = points[0];
    let mut hi = points[0];
    for q in points {
        lo = lo.inf(q);
        hi = hi.sup(q);
    }
    (
        lo * 0.5 + hi * 0.5,
        spline_core::ControlPoint::length(&(hi * 0.5 - lo * 0.5)) * 2.0,
    )
}

/// Twice the signed area of the polygon closed by its chord (positive counter-clockwise).
pub(crate) fn polygon_area(points: &[Vector2<f64>]) -> f64 {
    let mut sum = 0.0;
    for k in 0..points.len() {
        let a = points[k];
        let b = points[(k + 1) % points.len()];
        sum += a.x * b.y - a.y * b.x;
    }
    sum
}

/// The maximum deviation `tolerance` itself, or [`ErrorKind::InvalidTolerance`] unless it is
/// positive and finite.
pub(crate) fn check_max_deviation(tolerance: f64) -> Result<f64> {
    if tolerance > 0.0 && tolerance.is_finite() {
        Ok(tolerance)
    } else {
        Err(Error::new(
            ErrorKind::InvalidTolerance,
            format!("the maximum deviation must be positive and finite, got {tolerance}"),
        )
        .with_value(tolerance)
        .with_interval(0.0, f64::INFINITY))
    }
}
