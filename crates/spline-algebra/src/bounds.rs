//! The tight bounding box of a B-spline curve: the exact extremes of every coordinate.

use crate::roots::zeros;
use nalgebra::SVector;
use spline_core::{Error, Result, Scalar, to_f64};
use spline_geom::{BSpline, BoundingBox, ParamCurve};

/// The smallest axis-aligned box containing a polynomial B-spline curve in `D` dimensions:
/// every coordinate's extremes are at the ends, at the breaks (where the derivative may
/// jump) or at the zeros of that coordinate of the derivative, isolated by [`zeros`] to the
/// parameter accuracy `accuracy` (each extreme value is then exact to rounding, since the
/// coordinate is stationary there). Compare `spline_geom::hull_box` (the control points:
/// larger, no root finding).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{BSpline, hull_box};
/// // (u, u²) on [−1, 1]: the box is [−1, 1] × [0, 1]; the control points reach y = −1.
/// let c = BSpline::from_knots(2, vec![-1.0f64, -1.0, -1.0, 1.0, 1.0, 1.0], vec![
///     Vector2::new(-1.0, 1.0), Vector2::new(0.0, -1.0), Vector2::new(1.0, 1.0)])?;
/// let b = spline_algebra::tight_box(&c, 1e-12)?;
/// assert!(b.min.y.abs() < 1e-15 && b.max.y == 1.0 && b.min.x == -1.0);
/// assert_eq!(hull_box(&c).min.y, -1.0);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`spline_core::ErrorKind::InvalidTolerance`] unless `accuracy` is positive and finite;
/// the evaluation errors of the curve.
///
/// # Panics
/// Never: the ends of the domain are always evaluated.
pub fn tight_box<T: Scalar, const D: usize>(
    curve: &BSpline<T, SVector<T, D>>,
    accuracy: T,
) -> Result<BoundingBox<SVector<T, D>>> {
    if !(accuracy > T::zero() && accuracy.is_finite()) {
        return Err(Error::invalid_tolerance(
            "box accuracy",
            "positive and finite",
            to_f64(accuracy),
        ));
    }
    // Breaks: the ends, and where the derivative may jump (all the values of a piecewise
    // constant curve).
    let mut params = curve.breaks();
    if curve.degree() >= 1 {
        let derivative = curve.derivative(1)?;
        for c in 0..D {
            let coordinate = derivative.map_control_points(|p| p[c]);
            for zero in zeros(&coordinate, accuracy)? {
                params.push(zero.start);
                params.push(zero.end);
            }
        }
    }
    let points = curve.eval_many(&params)?;
    Ok(BoundingBox::of_points(points).expect("the ends are among the parameters"))
}
