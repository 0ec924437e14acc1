//! Offsets: the one home that front ends call. A curve's offset is its approximation within a
//! tolerance (`spline_fit::offset_curve`, on `spline_fit::AdaptiveApproximation`) with the
//! cusps of the offset (`spline_algebra::offset_cusps`) as `C⁰` corners, returned with the
//! cusps and the error bound in one record ([`CurveOffset`]).
//!
//! The offset lives here, not in spline-fit or spline-algebra, because it needs both: the
//! cusps come from algebra's root isolation, the curve from fit's adaptive approximation, and
//! spline-fit does not depend on spline-algebra (nor the other way round).

use nalgebra::Vector2;
use spline_algebra::{OffsetCusp, offset_cusps};
use spline_core::{Result, Scalar, cast};
use spline_geom::{BSpline, PlanarCurve};

/// Parameter accuracy of the cusps, relative to the length of the domain.
pub const CUSP_ACCURACY: f64 = 1e-12;

/// The settings of an offset: degree of the approximation and the largest distance allowed
/// between it and the exact offset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OffsetOptions<T> {
    /// Degree of the approximating B-spline (3 is a good choice).
    pub degree: usize,
    /// The largest distance between the result and the exact offset at the same parameter.
    pub tolerance: T,
}

impl<T: Scalar> Default for OffsetOptions<T> {
    fn default() -> Self {
        Self {
            degree: 3,
            tolerance: cast(1e-6),
        }
    }
}

/// The offset of a curve: the approximating curve, the cusps of the exact offset and the
/// largest deviation between the two measured at the check points.
#[derive(Clone, Debug)]
pub struct CurveOffset<T, P> {
    /// The offset curve (on the domain of the original; the same parameter).
    pub curve: BSpline<T, P>,
    /// The parameters where the offset has a cusp or stops (`κ d = 1`), increasing, with the
    /// points there.
    pub cusps: Vec<OffsetCusp<T>>,
    /// The largest distance between `curve` and the exact offset at the check points.
    pub max_error: T,
}

/// Planar curves whose offsets this module computes: the cusps of their offsets.
pub trait OffsetCusps<T: Scalar>: PlanarCurve<T> {
    /// The cusps of the offset at signed distance `distance` (positive to the left of the
    /// direction of travel), located to `accuracy` in the parameter.
    ///
    /// # Errors
    /// As `spline_algebra::offset_cusps`.
    fn offset_cusps(&self, distance: T, accuracy: T) -> Result<Vec<OffsetCusp<T>>>;
}

impl<T: Scalar> OffsetCusps<T> for BSpline<T, Vector2<T>> {
    fn offset_cusps(&self, distance: T, accuracy: T) -> Result<Vec<OffsetCusp<T>>> {
        offset_cusps(self, distance, accuracy)
    }
}

/// The offset $O(u) = C(u) + d\,N(u)$ of a planar curve at signed distance `distance`
/// ($N$ the unit normal to the left of the tangent) within `options.tolerance`: the cusps
/// (located to [`CUSP_ACCURACY`] of the domain), then the approximation with the cusps where
/// $\kappa d - 1$ changes sign as `C⁰` corners.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{BSpline, ParamCurve};
/// use spline_shape::{OffsetOptions, offset_planar_curve};
/// // y = x² on [−1, 1], offset by 1 toward the concave side: two cusps.
/// let parabola = BSpline::from_knots(2, vec![-1.0, -1.0, -1.0, 1.0, 1.0, 1.0], vec![
///     Vector2::new(-1.0, 1.0), Vector2::new(0.0, -1.0), Vector2::new(1.0, 1.0)])?;
/// let offset = offset_planar_curve(&parabola, 1.0, &OffsetOptions::default())?;
/// assert_eq!(offset.cusps.len(), 2);
/// assert!(offset.max_error <= 1e-6);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`OffsetCusps::offset_cusps`] and `spline_fit::offset_curve` (a non-finite distance,
/// a corner of the curve, a tolerance that cannot be met).
pub fn offset_planar_curve<T: Scalar, C: OffsetCusps<T>>(
    curve: &C,
    distance: T,
    options: &OffsetOptions<T>,
) -> Result<CurveOffset<T, Vector2<T>>> {
    let (a, b) = curve.domain();
    let cusps = curve.offset_cusps(distance, cast::<T>(CUSP_ACCURACY) * (b - a))?;
    let corners: Vec<T> = cusps
        .iter()
        .filter(|c| c.sign_change)
        .map(|c| c.u)
        .collect();
    let fit =
        spline_fit::offset_curve(curve, distance, options.degree, options.tolerance, &corners)?;
    Ok(CurveOffset {
        curve: fit.curve,
        cusps,
        max_error: fit.max_error,
    })
}
