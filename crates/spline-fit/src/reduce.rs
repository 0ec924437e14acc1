//! Degree reduction within a tolerance.

use crate::adaptive::{AdaptiveApproximation, AdaptiveFit};
use spline_core::{ControlPoint, Result, Scalar, cast};
use spline_geom::ParamCurve;

/// A B-spline of degree `degree` within `tolerance` of `curve` at every parameter, by least
/// squares on the curve's own breaks ([`AdaptiveApproximation`]; breaks where the derivative
/// jumps stay `C⁰` corners). With `refine`, spans that miss the tolerance are split (knots
/// are added); without, the knots stay those of the curve and a tolerance out of reach is
/// an error that gives the best deviation reached on them. The tolerance is absolute (in the
/// units of the points); the computation is scale-invariant (a curve scaled by 1e-300, with
/// its tolerance, gives the same reduction scaled and its true deviation, not 0).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{BSpline, ParamCurve};
/// // A parabola written as a cubic reduces to degree 2 exactly.
/// let cubic = BSpline::from_knots(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0], vec![
///     Vector2::new(0.0, 0.0), Vector2::new(1.0 / 3.0, 2.0 / 3.0),
///     Vector2::new(2.0 / 3.0, 2.0 / 3.0), Vector2::new(1.0, 0.0)])?;
/// let fit = spline_fit::reduce_degree(&cubic, 2, 1e-12, false)?;
/// assert_eq!(fit.curve.degree(), 2);
/// assert!((fit.curve.eval(0.3)? - cubic.eval(0.3)?).norm() < 1e-12);
/// // A cubic with an inflection is no parabola.
/// let s = BSpline::from_knots(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0], vec![
///     Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(2.0, -1.0), Vector2::new(3.0, 0.0)])?;
/// let e = spline_fit::reduce_degree(&s, 2, 1e-6, false).unwrap_err();
/// assert!(e.message().contains("best deviation"));
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`spline_core::ErrorKind::ToleranceExceeded`] when the tolerance is out of reach (on the
/// curve's knots without `refine`; with more than [`crate::MAX_ADAPTIVE_PIECES`] spans with
/// it), the message giving the best deviation reached; the errors of
/// [`AdaptiveApproximation::fit`] (degree, tolerance) and of the curve's evaluation.
pub fn reduce_degree<T: Scalar, C: ParamCurve<T> + ?Sized>(
    curve: &C,
    degree: usize,
    tolerance: T,
    refine: bool,
) -> Result<AdaptiveFit<T, C::Point>> {
    let (a, b) = curve.domain();
    let breaks = curve.breaks();
    let interior = &breaks[1..breaks.len() - 1];
    let delta = (b - a) * cast(1e-9);
    let (mut simple, mut corners) = (Vec::new(), Vec::new());
    for &k in interior {
        let left = curve.derivatives(k - delta, 1)?[1];
        let right = curve.derivatives(k + delta, 1)?[1];
        let scale = left.length().max(right.length());
        if (left - right).length() > scale * cast(1e-6) {
            corners.push(k);
        } else {
            simple.push(k);
        }
    }
    let mut approximation = AdaptiveApproximation::new(degree, tolerance)
        .breaks(&simple)
        .corners(&corners);
    if !refine {
        approximation = approximation.max_pieces(breaks.len() - 1);
    }
    approximation.fit((a, b), |u| curve.eval(u))
}
