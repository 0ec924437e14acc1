//! Offsets of planar curves approximated within a tolerance.

use crate::adaptive::{AdaptiveApproximation, AdaptiveFit};
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result, Scalar, cast, to_f64};
use spline_geom::PlanarCurve;

/// The point $O(u) = C(u) + d\,N(u)$ of the offset at signed distance `distance` ($N$ the
/// unit normal, [`PlanarCurve::unit_normal`]: to the left of the tangent).
///
/// # Errors
/// As [`PlanarCurve::unit_normal`] (where the curve stops there is no normal).
pub fn offset_point<T: Scalar, C: PlanarCurve<T> + ?Sized>(
    curve: &C,
    distance: T,
    u: T,
) -> Result<Vector2<T>> {
    Ok(curve.eval(u)? + curve.unit_normal(u)? * distance)
}

/// The unit tangents of `curve` on either side of the interior break `k`: the directions of
/// the last leg of the Bézier piece ending at `k` and of the first leg of the piece starting
/// there (exact); where a leg has zero length (repeated control points), the tangents just
/// off the break, `delta` away.
fn one_sided_tangents<T: Scalar, C: PlanarCurve<T> + ?Sized>(
    curve: &C,
    pieces: &[(T, T, Vec<C::Coefficient>)],
    k: T,
    delta: T,
) -> Result<(Vector2<T>, Vector2<T>)> {
    let leg = |from: &C::Coefficient, to: &C::Coefficient| C::project(to) - C::project(from);
    let ending = pieces.iter().find(|(_, end, _)| *end == k);
    let starting = pieces.iter().find(|(start, _, _)| *start == k);
    if let (Some((_, _, left)), Some((_, _, right))) = (ending, starting) {
        if left.len() >= 2 && right.len() >= 2 {
            let l = leg(&left[left.len() - 2], &left[left.len() - 1]);
            let r = leg(&right[0], &right[1]);
            let size = left
                .iter()
                .chain(right)
                .map(|c| C::project(c).amax())
                .fold(T::zero(), nalgebra::RealField::max);
            let degenerate = cast::<T>(1e-12) * size;
            if l.amax() > degenerate && r.amax() > degenerate {
                return Ok((unit(l), unit(r)));
            }
        }
    }
    let mut left = [Vector2::zeros(); 2];
    let mut right = [Vector2::zeros(); 2];
    curve.derivatives_into(k - delta, &mut left)?;
    curve.derivatives_into(k + delta, &mut right)?;
    Ok((unit(left[1]), unit(right[1])))
}

/// `v / |v|` without underflow or overflow of the squares (`v` divided by its largest
/// coordinate first: legs of 1e-300 have directions too).
fn unit<T: Scalar>(v: Vector2<T>) -> Vector2<T> {
    (v / v.amax()).normalize()
}

/// A B-spline of degree `degree` (3 is a good choice) on the curve's domain within `tolerance` of the offset
/// $O(u) = C(u) + d\,N(u)$ at every parameter (the same parameter: the error bounds the
/// distance between the point sets too), by [`AdaptiveApproximation`] with the curve's
/// breaks as initial knots and the offset's `cusps` (where $\kappa d = 1$, from
/// `spline_algebra::offset_cusps`) as `C⁰` corners, since the offset turns back there.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{BSpline, ParamCurve};
/// let parabola = BSpline::from_knots(2, vec![-1.0, -1.0, -1.0, 1.0, 1.0, 1.0], vec![
///     Vector2::new(-1.0, 1.0), Vector2::new(0.0, -1.0), Vector2::new(1.0, 1.0)])?;
/// // Offset by 0.2 to the convex side (no cusps).
/// let fit = spline_fit::offset_curve(&parabola, -0.2, 3, 1e-6, &[])?;
/// let q = fit.curve.eval(0.5)?;
/// let exact = spline_fit::offset_point(&parabola, -0.2, 0.5)?;
/// assert!((q - exact).norm() <= 1e-6);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::NonFinite`] for a non-finite distance; the errors of
/// [`PlanarCurve::unit_normal`] where the curve stops; [`ErrorKind::InvalidArgument`] where
/// the curve turns at a break (a corner: the offset is not continuous there); the
/// errors of [`AdaptiveApproximation::fit`] (cusps outside the domain, a tolerance that
/// cannot be met).
pub fn offset_curve<T: Scalar, C: PlanarCurve<T> + ?Sized>(
    curve: &C,
    distance: T,
    degree: usize,
    tolerance: T,
    cusps: &[T],
) -> Result<AdaptiveFit<T, Vector2<T>>> {
    if !distance.is_finite() {
        return Err(Error::non_finite("the offset distance"));
    }
    let (a, b) = curve.domain();
    let breaks = curve.breaks();
    let interior = &breaks[1..breaks.len() - 1];
    // A corner at a break (the unit tangent jumps) tears the offset apart. The one-sided
    // tangents at a break are read off the Bézier pieces on either side (the directions of
    // their end legs: exact, however fast the tangent turns next to the break).
    let pieces = curve.bezier_pieces();
    let delta = (b - a) * cast(1e-9);
    for &k in interior {
        let (l, r) = one_sided_tangents(curve, &pieces, k, delta)?;
        if !((l - r).norm() <= cast(1e-6)) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "the curve has a corner at u = {} (the tangent turns by {:.3e} rad): its offset is not continuous there",
                    to_f64(k),
                    to_f64(spline_geom::wedge(&l, &r).abs().asin())
                ),
            )
            .with_value(to_f64(k)));
        }
    }
    let corners: Vec<T> = cusps
        .iter()
        .copied()
        .filter(|c| !interior.contains(c))
        .collect();
    let simple: Vec<T> = interior
        .iter()
        .copied()
        .filter(|k| !cusps.contains(k))
        .collect();
    AdaptiveApproximation::new(degree, tolerance)
        .breaks(&simple)
        .corners(&corners)
        .fit((a, b), |u| offset_point(curve, distance, u))
}
