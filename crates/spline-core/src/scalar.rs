//! The scalar trait and conversions from and to `f64`.

use nalgebra::RealField;

/// The numbers a spline is built over: `f32`, `f64`, and automatic-differentiation numbers
/// such as `num_dual::Dual64` or `num_dual::HyperDual64`.
///
/// One trait with a blanket implementation over [`nalgebra::RealField`] `+ Copy`, so every
/// real field that nalgebra knows works without further impls. Comparisons (`<`, `==`) on
/// dual numbers compare real parts, which is what span searches need.
pub trait Scalar: RealField + Copy {}

impl<T: RealField + Copy> Scalar for T {}

/// Converts an `f64` constant to any scalar type (rounding for `f32`; a constant with zero
/// derivative part for dual numbers).
///
/// ```
/// let half: f32 = spline_core::cast(0.5);
/// assert_eq!(half, 0.5f32);
/// ```
#[inline]
#[must_use]
pub fn cast<T: Scalar>(value: f64) -> T {
    nalgebra::convert(value)
}

/// The real part of a scalar as an `f64` (the value itself for `f32`/`f64`, the real part of a
/// dual number).
///
/// ```
/// assert_eq!(spline_core::to_f64(0.25f32), 0.25);
/// ```
#[inline]
#[must_use]
pub fn to_f64<T: Scalar>(value: T) -> f64 {
    value.to_subset_unchecked()
}

/// `n` as a scalar.
#[inline]
#[must_use]
pub fn from_count<T: Scalar>(n: usize) -> T {
    // Counts in this library are small (degrees, orders): exact in f64.
    #[allow(clippy::cast_precision_loss)]
    cast(n as f64)
}
