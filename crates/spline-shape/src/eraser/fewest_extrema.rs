//! The fewest curvature extrema within a tolerance (`spline smooth --curvature-extrema auto`).

use super::input::{check_max_deviation, distinct, frame};
use super::smooth::smooth;
use super::types::{Extremum, SmoothedCurve, SmoothingOptions, extrema_words};
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result};

/// The tolerance of [`smooth_fewest_extrema`] when the caller gives none, as a fraction of
/// the diagonal of the data's bounding box: `0.002`, about 2 mm on an airfoil of chord 1 m
/// (the thesis: "typically less than 2 mm").
pub const AUTO_EXTREMA_TOLERANCE: f64 = 2e-3;

/// The most extrema [`smooth_fewest_extrema`] tries.
const MOST_AUTO_EXTREMA: usize = 8;

/// [`smooth`](super::smooth) with the fewest curvature extrema that bring every data point
/// within `tolerance` of the curve (`None`: [`AUTO_EXTREMA_TOLERANCE`] times the diagonal
/// of the data's bounding box). The extrema in `options` are ignored: `k = 1, 2, …` (a
/// closed contour: `2, 4, …`) alternating maximum, minimum, … placed automatically, up to 8
/// or as many as the control points allow; the first `k` whose curve is within the
/// tolerance is the answer.
///
/// # Errors
/// [`ErrorKind::InvalidTolerance`] for a tolerance that is not positive and finite; the
/// errors of [`smooth`](super::smooth) for unusable data or settings;
/// [`ErrorKind::ToleranceExceeded`] when no count reaches the tolerance (the message gives
/// the best deviation found and its count).
pub fn smooth_fewest_extrema(
    points: &[Vector2<f64>],
    tolerance: Option<f64>,
    options: &SmoothingOptions,
) -> Result<SmoothedCurve> {
    let tolerance = match tolerance {
        Some(t) => check_max_deviation(t)?,
        None => AUTO_EXTREMA_TOLERANCE * frame(&distinct(points)?).1,
    };
    let p = options.degree;
    if p < 3 {
        // The error of `smooth` for such a degree.
        return smooth(points, options);
    }
    // Room for the extremum knots of multiplicity p − 2 (as `smooth` checks).
    let room = options
        .control_points
        .saturating_sub(p + 1)
        .checked_div(p.saturating_sub(2))
        .unwrap_or(0);
    let step = if options.closed { 2 } else { 1 };
    let mut best: Option<(usize, f64)> = None;
    let mut k = step;
    while k <= MOST_AUTO_EXTREMA.min(room) {
        let mut o = options.clone();
        o.extrema = Extremum::alternating(k);
        match smooth(points, &o) {
            Ok(result) => {
                let max = result.deviation.to_curve.max;
                if max <= tolerance {
                    return Ok(result);
                }
                if best.is_none_or(|(_, b)| max < b) {
                    best = Some((k, max));
                }
            }
            // No curve with k extrema (or no room to place them): try more.
            Err(e)
                if matches!(
                    e.kind(),
                    ErrorKind::NoConvergence | ErrorKind::InvalidArgument
                ) => {}
            Err(e) => return Err(e),
        }
        k += step;
    }
    Err(Error::new(
        ErrorKind::ToleranceExceeded,
        match best {
            Some((k, max)) => format!(
                "no curve with up to {} and {} control points is within {tolerance:.3e} of the data (best: {max:.3e} with {})",
                extrema_words(k.max(MOST_AUTO_EXTREMA.min(room))),
                options.control_points,
                extrema_words(k)
            ),
            None => format!(
                "no curve with up to {} and {} control points was found near the data",
                extrema_words(MOST_AUTO_EXTREMA.min(room)),
                options.control_points
            ),
        },
    ))
}
