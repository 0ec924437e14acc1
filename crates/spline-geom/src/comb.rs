//! Curvature combs: the picture of a planar curve's curvature, a tooth along the normal at
//! each sample, of length proportional to the signed curvature (drawn by `spline plot
//! --comb`, the studio and the SVG pictures).

use crate::PlanarCurve;
use nalgebra::Vector2;
use spline_core::{Scalar, cast};

/// One tooth of a curvature comb ([`curvature_comb`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CombTooth<T: Scalar> {
    /// The parameter.
    pub u: T,
    /// The point `C(u)`.
    pub point: Vector2<T>,
    /// The unit normal ([`PlanarCurve::unit_normal`]).
    pub normal: Vector2<T>,
    /// The signed curvature ([`PlanarCurve::signed_curvature`]).
    pub curvature: T,
}

/// `intervals + 1` parameters evenly spaced over `(a, b)`, both ends included:
/// $u_j = a + (b - a)\, j / n$.
///
/// ```
/// assert_eq!(spline_geom::evenly_spaced_params((1.0, 3.0), 4), [1.0, 1.5, 2.0, 2.5, 3.0]);
/// ```
#[must_use]
pub fn evenly_spaced_params<T: Scalar>((a, b): (T, T), intervals: usize) -> Vec<T> {
    let n = intervals.max(1);
    (0..=n)
        .map(|j| a + (b - a) * cast::<T>(j as f64) / cast::<T>(n as f64))
        .collect()
}

/// The teeth of the curvature comb of a planar curve at `params`: point, unit normal and
/// signed curvature; a parameter where they are undefined (zero velocity, outside the
/// domain) has no tooth.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{CircleConstruction, Frame, NurbsCurve, ParamCurve};
/// use spline_geom::{curvature_comb, evenly_spaced_params};
/// let frame = Frame::planar(Vector2::new(0.0f64, 0.0));
/// let circle = NurbsCurve::circle(&frame, 2.0, CircleConstruction::Square)?;
/// let teeth = curvature_comb(&circle, &evenly_spaced_params(circle.domain(), 8));
/// assert_eq!(teeth.len(), 9);
/// assert!(teeth.iter().all(|t| (t.curvature - 0.5).abs() < 1e-12));
/// # Ok::<(), spline_core::Error>(())
/// ```
pub fn curvature_comb<T: Scalar, C: PlanarCurve<T> + ?Sized>(
    curve: &C,
    params: &[T],
) -> Vec<CombTooth<T>> {
    params
        .iter()
        .filter_map(|&u| {
            match (
                curve.eval(u),
                curve.unit_normal(u),
                curve.signed_curvature(u),
            ) {
                (Ok(point), Ok(normal), Ok(curvature)) => Some(CombTooth {
                    u,
                    point,
                    normal,
                    curvature,
                }),
                _ => None,
            }
        })
        .collect()
}

/// The teeth as segments from the curve to their tips, scaled so that the longest is
/// `length` long: $p - n \,(\kappa / \max|\kappa|)\, \ell$, pointing away from the centre of
/// curvature. Empty when every curvature is zero; a tooth whose tip is not finite is left
/// out.
#[must_use]
pub fn comb_segments<T: Scalar>(
    teeth: &[CombTooth<T>],
    length: T,
) -> Vec<(Vector2<T>, Vector2<T>)> {
    // |n κ| = |κ|: the curvature itself, not a norm that would underflow for tiny κ.
    let max = teeth
        .iter()
        .fold(T::zero(), |m, t| m.max(t.curvature.abs()));
    if max == T::zero() {
        return Vec::new();
    }
    teeth
        .iter()
        .map(|t| {
            let tip = t.point - t.normal * ((t.curvature / max) * length);
            (t.point, tip)
        })
        .filter(|(_, q)| q.x.is_finite() && q.y.is_finite())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{comb_segments, curvature_comb, evenly_spaced_params};
    use crate::BSpline;
    use nalgebra::Vector2;

    #[test]
    fn the_longest_tooth_has_the_length_and_teeth_point_away_from_the_centre() {
        // The parabola (u, u²) on [−1, 1]: curvature 2 at the vertex, the largest.
        let parabola = BSpline::from_knots(
            2,
            vec![-1.0f64, -1.0, -1.0, 1.0, 1.0, 1.0],
            vec![
                Vector2::new(-1.0, 1.0),
                Vector2::new(0.0, -1.0),
                Vector2::new(1.0, 1.0),
            ],
        )
        .unwrap();
        let teeth = curvature_comb(&parabola, &evenly_spaced_params(parabola.domain(), 4));
        assert_eq!(teeth.len(), 5);
        assert!((teeth[2].curvature - 2.0).abs() < 1e-12);
        let segments = comb_segments(&teeth, 0.5);
        let lengths: Vec<f64> = segments.iter().map(|(p, q)| (q - p).norm()).collect();
        assert!((lengths[2] - 0.5).abs() < 1e-15, "{lengths:?}");
        assert!(lengths.iter().all(|&l| l <= 0.5 + 1e-15));
        // The vertex's centre of curvature is above it: the tooth points down.
        assert!(segments[2].1.y < segments[2].0.y);
        // No curvature, no comb.
        let line = BSpline::from_knots(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0)],
        )
        .unwrap();
        let flat = curvature_comb(&line, &evenly_spaced_params(line.domain(), 3));
        assert!(comb_segments(&flat, 1.0).is_empty());
    }
}
