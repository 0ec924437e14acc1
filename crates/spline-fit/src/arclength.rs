//! Reparametrisation by arc length within a tolerance.

use crate::adaptive::{AdaptiveApproximation, AdaptiveFit};
use spline_core::{ControlPoint, Result, Scalar, cast};
use spline_geom::{ArcLengthTable, ParamCurve};

/// A B-spline curve $G$ of degree `p` on $[0, L]$ ($L$ the length of `curve`) with
/// $\lVert G(s) - C(u(s)) \rVert \le$ `tolerance`, where $u(s)$ is the exact arc-length
/// parameter ([`ArcLengthTable`]): the curve parametrised by arc length, so that
/// $\lVert G'(s) \rVert \approx 1$. The breaks of `curve` map to initial knots; spans are
/// refined until the tolerance is met ([`AdaptiveApproximation`]). Any kind of curve
/// (B-spline, NURBS, periodic) in any dimension.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::NurbsCurve;
/// use spline_fit::reparametrize_by_arc_length;
/// // A quarter of the unit circle (rational, not arc-length parametrised).
/// let quarter = NurbsCurve::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(1.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(0.0, 1.0)],
///     vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0])?;
/// let fit = reparametrize_by_arc_length(&quarter, 3, 1e-7)?;
/// let (_, length) = fit.curve.domain();
/// assert!((length - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
/// let q = fit.curve.eval(0.5)?;
/// assert!((q - Vector2::new(0.5f64.cos(), 0.5f64.sin())).norm() < 1e-7);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`spline_core::ErrorKind::InvalidTolerance`] unless the tolerance is positive and finite;
/// [`spline_core::ErrorKind::EmptyDomain`] for a curve of zero length; the errors of
/// [`ArcLengthTable`] and [`AdaptiveApproximation::fit`].
pub fn reparametrize_by_arc_length<T: Scalar, C: ParamCurve<T> + ?Sized>(
    curve: &C,
    degree: usize,
    tolerance: T,
) -> Result<AdaptiveFit<T, C::Point>> {
    if !(tolerance > T::zero() && tolerance.is_finite()) {
        return Err(spline_core::Error::invalid_tolerance(
            "tolerance",
            "positive and finite",
            spline_core::to_f64(tolerance),
        ));
    }
    // Lengths far more accurate than the positions asked for (a length error δ moves the
    // point by δ along the curve): a thousandth of the tolerance, relative to the length of
    // the control polygon (at least the curve's for B-splines), at least 8 ε.
    let polygon = curve.control_polygon();
    let size = polygon
        .windows(2)
        .fold(T::zero(), |s, w| s + (w[1] - w[0]).length());
    let relative = if size > T::zero() {
        (tolerance * cast(1e-3) / size)
            .min(cast(1e-3))
            .max(cast(8.0 * f64::EPSILON))
    } else {
        cast(1e-3)
    };
    let table = ArcLengthTable::new(curve, relative)?;
    let total = table.total();
    let at = table.at_breaks();
    let breaks: Vec<T> = at[1..at.len() - 1]
        .iter()
        .copied()
        .filter(|&s| s > T::zero() && s < total)
        .collect();
    AdaptiveApproximation::new(degree, tolerance)
        .breaks(&breaks)
        .fit_many((T::zero(), total), |lengths| {
            table
                .params_at(lengths)?
                .into_iter()
                .map(|u| curve.eval(u))
                .collect()
        })
}
