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

/// A power of four at most `magnitude` and above a sixteenth of it (1 for zero or
/// non-finite magnitudes): dividing by it is exact in binary floating point and commutes
/// with square roots, so it brings coordinates near 1 without changing a single digit of the
/// results of scale-invariant computations (barring underflow).
///
/// ```
/// assert_eq!(spline_core::power_of_two_scale(3.0), 1.0);
/// assert_eq!(spline_core::power_of_two_scale(5.0), 4.0);
/// assert_eq!(spline_core::power_of_two_scale(1e-300), 2f64.powi(-998));
/// assert_eq!(spline_core::power_of_two_scale(0.0), 1.0);
/// ```
#[must_use]
pub fn power_of_two_scale(magnitude: f64) -> f64 {
    if !(magnitude > 0.0 && magnitude.is_finite()) {
        return 1.0;
    }
    // The exponent of a finite positive double lies in −1074 … 1023.
    #[allow(clippy::cast_possible_truncation)]
    let mut exponent = magnitude.log2().floor() as i32;
    // log2 may round up to the next integer just below a power of two.
    if 2f64.powi(exponent) > magnitude {
        exponent -= 1;
    }
    let even = exponent.clamp(-1022, 1022).div_euclid(2) * 2;
    2f64.powi(even)
}
