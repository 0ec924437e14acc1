//! Rotation-minimising frames along a space curve by the double reflection method (Wang,
//! Jüttler, Zheng and Liu, *Computation of rotation minimizing frames*, ACM TOG 27, 2008):
//! the frames that sweeps carry along their path.

use super::checks::degenerate;
use super::vectors::{perpendicular, safe_norm};
use crate::param::ParamCurve;
use nalgebra::Vector3;
use spline_core::{Error, ErrorKind, Result, Scalar, from_count, to_f64};

/// Reflection steps per interval between consecutive requested parameters: the method is of
/// fourth order, so 64 steps per interval keep the rotation error near rounding for every
/// reasonable curve.
const STEPS_PER_INTERVAL: usize = 64;

/// An orthonormal frame moving along a curve: the point, the unit tangent, and two unit
/// vectors spanning the normal plane (`tangent × normal = binormal`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MovingFrame<T> {
    /// The point of the curve.
    pub origin: Vector3<T>,
    /// The unit tangent.
    pub tangent: Vector3<T>,
    /// The first vector of the normal plane (rotation-minimising: it does not turn about
    /// the tangent).
    pub normal: Vector3<T>,
    /// `tangent × normal`.
    pub binormal: Vector3<T>,
}

impl<T: Scalar> MovingFrame<T> {
    /// The frame as the columns `(tangent, normal, binormal)` of a rotation matrix.
    #[must_use]
    pub fn rotation(&self) -> nalgebra::Matrix3<T> {
        nalgebra::Matrix3::from_columns(&[self.tangent, self.normal, self.binormal])
    }
}

/// The rotation-minimising frames of a space curve at increasing parameters `params`: the
/// frame at `params[0]` has the given `normal` (projected onto the normal plane; by default
/// the coordinate axis least aligned with the tangent), and each next frame follows from
/// the previous one by the double reflection method on 64 sub-steps per interval,
/// so the normal vector never turns about the tangent (its angular velocity has no tangent
/// component: along a helix it turns against the Frenet frame at the rate of the torsion).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::{BSpline, rotation_minimizing_frames};
/// // A planar path: the frames keep the plane's normal as their binormal.
/// let path = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![
///     Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 1.0, 0.0), Vector3::new(2.0, 0.0, 0.0)])?;
/// let frames = rotation_minimizing_frames(&path, &[0.0, 0.5, 1.0], Some(Vector3::new(0.0, 1.0, 0.0)))?;
/// for f in &frames {
///     assert!((f.binormal - Vector3::new(0.0, 0.0, 1.0)).norm() < 1e-12);
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] without parameters; [`ErrorKind::UnsortedKnots`] for
/// decreasing parameters; [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for a
/// parameter; [`ErrorKind::DegenerateGeometry`] where the curve has no tangent (zero
/// velocity) or the given normal is parallel to the first tangent.
pub fn rotation_minimizing_frames<T: Scalar, C: ParamCurve<T, Point = Vector3<T>>>(
    curve: &C,
    params: &[T],
    normal: Option<Vector3<T>>,
) -> Result<Vec<MovingFrame<T>>> {
    if params.is_empty() {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            "rotation-minimising frames need at least one parameter",
        ));
    }
    spline_core::check_params(params)?;
    let tangent_at = |u: T| -> Result<(Vector3<T>, Vector3<T>)> {
        let mut d = [Vector3::zeros(); 2];
        curve.derivatives_into(u, &mut d)?;
        let len = safe_norm(&d[1]);
        if !(len > T::zero()) {
            return Err(degenerate(format!(
                "the path has no tangent at parameter {} (zero velocity)",
                to_f64(u)
            )));
        }
        Ok((d[0], d[1] / len))
    };
    let (x0, t0) = tangent_at(params[0])?;
    let r0 = match normal {
        Some(n) => {
            super::checks::check_vector(&n, "the initial normal")?;
            let r = n - t0 * t0.dot(&n);
            let len = safe_norm(&r);
            if !(len > safe_norm(&n) * spline_core::cast::<T>(1e-12)) {
                return Err(degenerate(
                    "the initial normal is parallel to the tangent of the path",
                ));
            }
            r / len
        }
        None => perpendicular(&t0),
    };
    let frame = |origin: Vector3<T>, tangent: Vector3<T>, normal: Vector3<T>| MovingFrame {
        origin,
        tangent,
        normal,
        binormal: tangent.cross(&normal),
    };
    let mut frames = Vec::with_capacity(params.len());
    frames.push(frame(x0, t0, r0));
    let (mut x, mut t, mut r) = (x0, t0, r0);
    let two: T = spline_core::cast(2.0);
    let steps: T = from_count(STEPS_PER_INTERVAL);
    for w in params.windows(2) {
        for k in 1..=STEPS_PER_INTERVAL {
            let u = if k == STEPS_PER_INTERVAL {
                w[1]
            } else {
                w[0] + (w[1] - w[0]) * from_count::<T>(k) / steps
            };
            let (x1, t1) = tangent_at(u)?;
            // First reflection in the bisecting plane of x and x1, second in the plane
            // that brings the reflected tangent onto t1.
            let v1 = x1 - x;
            let c1 = v1.dot(&v1);
            let (r_l, t_l) = if c1 > T::zero() {
                (
                    r - v1 * (two / c1 * v1.dot(&r)),
                    t - v1 * (two / c1 * v1.dot(&t)),
                )
            } else {
                (r, t)
            };
            let v2 = t1 - t_l;
            let c2 = v2.dot(&v2);
            let mut r1 = if c2 > T::zero() {
                r_l - v2 * (two / c2 * v2.dot(&r_l))
            } else {
                r_l
            };
            // Keep the frame orthonormal against rounding.
            r1 -= t1 * t1.dot(&r1);
            r1 /= safe_norm(&r1);
            (x, t, r) = (x1, t1, r1);
        }
        frames.push(frame(x, t, r));
    }
    Ok(frames)
}
