//! The fewest control points within a tolerance.

use super::input::{check_max_deviation, distinct};
use super::smooth::smooth;
use super::types::{SmoothedCurve, SmoothingOptions, extrema_words};
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result};

/// [`smooth`](super::smooth) with the fewest control points that bring every data point within
/// `tolerance` of the curve (the thesis: "typically less than 2 mm" for a chord of 1 m). The
/// number of control points in `options` is ignored: counts are doubled from the smallest the
/// extrema allow until one reaches the tolerance, then bisected (deviations do not always
/// fall as control points are added, so this is the fewest such a search finds).
///
/// # Errors
/// [`ErrorKind::InvalidTolerance`] for a tolerance that is not positive and finite; the
/// errors of [`smooth`](super::smooth) for the other settings; [`ErrorKind::ToleranceExceeded`] when no
/// count up to one less than the number of data points reaches the tolerance (the message
/// gives the best deviation found).
pub fn smooth_to_tolerance(
    points: &[Vector2<f64>],
    tolerance: f64,
    options: &SmoothingOptions,
) -> Result<SmoothedCurve> {
    check_max_deviation(tolerance)?;
    let p = options.degree;
    let smallest = p + 1 + options.extrema.len() * p.saturating_sub(2);
    let largest = distinct(points)?.len().saturating_sub(1);
    if largest < smallest {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "{} need at least {} distinct data points, got {}",
                extrema_words(options.extrema.len()),
                smallest + 1,
                largest + 1
            ),
        ));
    }
    let mut best_seen = f64::INFINITY;
    let mut run = |n: usize| -> Result<Option<SmoothedCurve>> {
        let mut o = options.clone();
        o.control_points = n;
        let result = match smooth(points, &o) {
            Ok(r) => r,
            Err(e) if e.kind() == ErrorKind::NoConvergence => {
                return Ok(None);
            }
            Err(e) => return Err(e),
        };
        best_seen = best_seen.min(result.deviation.to_curve.max);
        let ok = result.deviation.to_curve.max <= tolerance;
        Ok(ok.then_some(result))
    };
    // Doubling, then bisection between the last failure and the first success.
    let mut lo = smallest - 1; // fails by convention
    let mut n = smallest;
    let mut found = loop {
        if let Some(r) = run(n)? {
            break (n, r);
        }
        if n >= largest {
            return Err(Error::new(
                ErrorKind::ToleranceExceeded,
                format!(
                    "no curve with {} within {tolerance} of the data was found with up to {largest} control points (best deviation {best_seen:.3e})",
                    extrema_words(options.extrema.len())
                ),
            ));
        }
        lo = n;
        n = (2 * n).min(largest);
    };
    while found.0 - lo > 1 {
        let mid = lo + (found.0 - lo) / 2;
        match run(mid)? {
            Some(r) => found = (mid, r),
            None => lo = mid,
        }
    }
    Ok(found.1)
}
