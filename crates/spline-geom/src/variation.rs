//! The variation-diminishing property (seed 004 §8.2): sign changes of a control polygon bound
//! those of the function, and crossings of a control polygon with a line bound those of the
//! curve.

use crate::bspline::BSpline;
use nalgebra::Vector2;
use spline_core::Scalar;

/// The number of sign changes $V(\alpha)$ of a sequence (seed 004 Definition 8.1): zeros are
/// skipped, so `[1, 0, -1]` has one change and `[1, 0, 1]` none.
///
/// ```
/// assert_eq!(spline_geom::sign_changes(&[1.0, 0.0, -2.0, -1.0, 3.0]), 2);
/// ```
#[must_use]
pub fn sign_changes<T: Scalar>(values: &[T]) -> usize {
    let mut count = 0;
    let mut last: Option<bool> = None;
    for &v in values {
        if v == T::zero() {
            continue;
        }
        let positive = v > T::zero();
        if last.is_some_and(|l| l != positive) {
            count += 1;
        }
        last = Some(positive);
    }
    count
}

impl<T: Scalar> BSpline<T, T> {
    /// $V(\alpha)$ of the coefficients: an upper bound on the number of sign changes (zeros
    /// crossed) of the function on its domain (seed 004 Proposition 8.2).
    #[must_use]
    pub fn coefficient_sign_changes(&self) -> usize {
        sign_changes(self.control_points())
    }
}

impl<T: Scalar> BSpline<T, Vector2<T>> {
    /// The number of crossings of the control polygon with the line `r x + s y + t = 0`: an
    /// upper bound on the number of crossings of the curve with that line.
    #[must_use]
    pub fn polygon_line_crossings(&self, r: T, s: T, t: T) -> usize {
        let values: Vec<T> = self
            .control_points()
            .iter()
            .map(|p| r * p.x + s * p.y + t)
            .collect();
        sign_changes(&values)
    }
}
