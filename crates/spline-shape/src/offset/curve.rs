//! The offset of a curve computed on its projection to a plane: the planar frame, the exact
//! offsets of circular arcs, the cusps of rational offsets by sampling, the corners of space
//! curves and the approximation of space offsets.

use nalgebra::{SVector, Vector2, Vector3};
use spline_core::{Error, ErrorKind, Result, Scalar, cast, from_count, to_f64};
use spline_fit::AdaptiveApproximation;
use spline_geom::{BSpline, NurbsCurve, ParamCurve, PlanarCurve};

/// Grid steps per piece for the sign changes of `κ d − 1` on rational offsets and for
/// the search of tangents parallel to the direction.
const GRID: usize = 1024;

/// Relative distance from a circle under which every sample counts as on it.
const CIRCLE_CHECK: f64 = 1e-12;

/// `|T × V|` under which the direction counts as parallel to the tangent.
const PARALLEL: f64 = 1e-9;

/// An orthonormal pair `e1, e2` spanning the plane of the offset: the coordinate axes for
/// planar curves, the plane perpendicular to the direction `V` for space curves (with
/// `e1 × e2 = V`). The offset moves a point by `d′ (n_x e1 + n_y e2)`, `n` the unit normal
/// of the projected curve.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame<T: Scalar, const D: usize> {
    e1: SVector<T, D>,
    e2: SVector<T, D>,
}

impl<T: Scalar> Frame<T, 2> {
    /// The coordinate axes.
    pub(super) fn planar() -> Self {
        Self {
            e1: Vector2::x(),
            e2: Vector2::y(),
        }
    }
}

impl<T: Scalar> Frame<T, 3> {
    /// The plane perpendicular to `direction`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::DegenerateGeometry`] (zero length).
    pub(super) fn perpendicular_to(direction: &Vector3<T>) -> Result<Self> {
        if !direction.iter().all(nalgebra::ComplexField::is_finite) {
            return Err(Error::non_finite("the offset direction"));
        }
        let largest = direction.amax();
        if largest == T::zero() {
            return Err(Error::new(
                ErrorKind::DegenerateGeometry,
                "the offset direction has zero length",
            ));
        }
        let v = (direction / largest).normalize();
        // The axis least aligned with V, made perpendicular to it.
        let axis = if v.x.abs() <= v.y.abs() && v.x.abs() <= v.z.abs() {
            Vector3::x()
        } else if v.y.abs() <= v.z.abs() {
            Vector3::y()
        } else {
            Vector3::z()
        };
        let e1 = (axis - v * v.dot(&axis)).normalize();
        Ok(Self {
            e1,
            e2: v.cross(&e1),
        })
    }
}

impl<T: Scalar, const D: usize> Frame<T, D> {
    /// Coordinates in the plane.
    pub(super) fn project(&self, p: &SVector<T, D>) -> Vector2<T> {
        Vector2::new(p.dot(&self.e1), p.dot(&self.e2))
    }

    /// The vector of the space with plane coordinates `n`.
    pub(super) fn lift(&self, n: &Vector2<T>) -> SVector<T, D> {
        self.e1 * n.x + self.e2 * n.y
    }
}

/// A circle that a planar curve runs along: centre, radius and the sign of its curvature.
#[derive(Clone, Copy, Debug)]
pub(super) struct Circle<T> {
    pub(super) centre: Vector2<T>,
    pub(super) radius: T,
    pub(super) turn: T,
}

/// The circle the curve lies on, if it does: centre and radius from the curvature at the
/// middle of the domain, then every one of `4 (p + 1)` samples per piece (more than the
/// `2p` points where a rational curve of degree `p` not on the circle can meet it) within
/// [`CIRCLE_CHECK`] of the radius, with the curvature of the same sign.
pub(super) fn circle_of<T: Scalar, C: PlanarCurve<T>>(
    curve: &C,
    degree: usize,
) -> Option<Circle<T>> {
    let (a, b) = curve.domain();
    let mid = (a + b) * cast(0.5);
    let kappa = curve.signed_curvature(mid).ok()?;
    if !(kappa != T::zero() && kappa.is_finite()) {
        return None;
    }
    let radius = T::one() / kappa.abs();
    let centre = curve.eval(mid).ok()? + curve.unit_normal(mid).ok()? * (T::one() / kappa);
    let check = cast::<T>(CIRCLE_CHECK) * radius;
    for u in curve.sample_params(4 * (degree + 1)) {
        let on = ((curve.eval(u).ok()? - centre).norm() - radius).abs() <= check;
        let same_turn = curve.signed_curvature(u).ok()? * kappa > T::zero();
        if !(on && same_turn) {
            return None;
        }
    }
    Some(Circle {
        centre,
        radius,
        turn: kappa.signum(),
    })
}

/// The factor by which the offset at planar distance `distance` scales a circle about its
/// centre: `(r − d s) / r` (`s` the sign of the curvature: the normal points to the centre
/// where the curve turns left).
///
/// # Errors
/// [`ErrorKind::DegenerateGeometry`] when the offset collapses to the centre.
pub(super) fn circle_factor<T: Scalar>(circle: &Circle<T>, distance: T) -> Result<T> {
    let factor = (circle.radius - distance * circle.turn) / circle.radius;
    if factor.abs() <= cast::<T>(CIRCLE_CHECK) {
        return Err(Error::new(
            ErrorKind::DegenerateGeometry,
            format!(
                "the offset at distance {} of a circular arc of radius {} collapses to its centre",
                to_f64(distance),
                to_f64(circle.radius)
            ),
        )
        .with_value(to_f64(distance)));
    }
    Ok(factor)
}

/// The parameters of the cusps of the offset of any planar curve (rational ones): where
/// `κ d − 1` changes sign on a grid of [`GRID`] steps per piece, bisected to `accuracy`.
/// (Touches without a sign change are not found; for B-splines
/// `spline_algebra::offset_cusps` finds them exactly.)
///
/// # Errors
/// The errors of [`PlanarCurve::signed_curvature`] (where the curve stops).
pub(super) fn sampled_cusps<T: Scalar, C: PlanarCurve<T>>(
    curve: &C,
    distance: T,
    accuracy: T,
) -> Result<Vec<T>> {
    if distance == T::zero() {
        return Ok(Vec::new());
    }
    let g = |u: T| -> Result<T> { Ok(curve.signed_curvature(u)? * distance - T::one()) };
    let mut out = Vec::new();
    for w in curve.breaks().windows(2) {
        let (lo, hi) = (w[0], w[1]);
        let mut previous = (lo, g(lo)?);
        for k in 1..=GRID {
            // The last point is `hi` itself: `lo + (hi − lo)` can round one step past it.
            let u = if k == GRID {
                hi
            } else {
                lo + (hi - lo) * from_count::<T>(k) / from_count::<T>(GRID)
            };
            let value = g(u)?;
            if previous.1 * value < T::zero() {
                let (mut left, mut right, at_left) = (previous.0, u, previous.1);
                while right - left > accuracy {
                    let mid = (left + right) * cast(0.5);
                    if !(mid > left && mid < right) {
                        break;
                    }
                    if g(mid)? * at_left > T::zero() {
                        left = mid;
                    } else {
                        right = mid;
                    }
                }
                out.push((left + right) * cast(0.5));
            }
            previous = (u, value);
        }
    }
    Ok(out)
}

/// Refuses a direction parallel to the tangent somewhere: `|T × V|` (the speed of the
/// projection over the speed of the curve) below [`PARALLEL`] on a grid of [`GRID`] steps per
/// piece (there the offset direction `T × V / |T × V|` is undefined).
///
/// # Errors
/// [`ErrorKind::DegenerateGeometry`] with the parameter; the evaluation errors.
pub(super) fn check_not_parallel<T: Scalar, C: ParamCurve<T, Point = Vector3<T>> + ?Sized>(
    curve: &C,
    frame: &Frame<T, 3>,
) -> Result<()> {
    let mut d = [Vector3::zeros(); 2];
    for w in curve.breaks().windows(2) {
        for k in 0..=GRID {
            let u = if k == GRID {
                w[1]
            } else {
                w[0] + (w[1] - w[0]) * from_count::<T>(k) / from_count::<T>(GRID)
            };
            curve.derivatives_into(u, &mut d)?;
            let largest = d[1].amax();
            let across = if largest > T::zero() {
                frame.project(&(d[1] / largest)).norm() / (d[1] / largest).norm()
            } else {
                T::zero()
            };
            if !(across > cast(PARALLEL)) {
                return Err(Error::new(
                    ErrorKind::DegenerateGeometry,
                    format!(
                        "the offset direction is parallel to the tangent at u = {} (|T × V| = {:.1e}): the offset direction T × V is undefined there",
                        to_f64(u),
                        to_f64(across)
                    ),
                )
                .with_value(to_f64(u)));
            }
        }
    }
    Ok(())
}

/// Refuses a corner of the projected curve at an interior break (the offset tears apart
/// there): the turn of the unit tangent across the break over `±δ` for `δ = 10⁻⁶` and
/// `10⁻⁹` of the domain; a smooth curve's turn shrinks with `δ`, a corner's does not.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] at a corner; the errors of the unit tangent.
pub(super) fn check_no_corner<T: Scalar, C: PlanarCurve<T>>(curve: &C) -> Result<()> {
    let (a, b) = curve.domain();
    let breaks = curve.breaks();
    let turn = |k: T, delta: T| -> Result<T> {
        let left = curve.unit_tangent(k - delta)?;
        let right = curve.unit_tangent(k + delta)?;
        Ok((left - right).norm())
    };
    for &k in &breaks[1..breaks.len() - 1] {
        let wide = turn(k, (b - a) * cast(1e-6))?;
        let narrow = turn(k, (b - a) * cast(1e-9))?;
        if narrow > cast(1e-6) && narrow >= wide * cast(0.5) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "the curve has a corner at u = {} (seen across the offset direction): its offset is not continuous there",
                    to_f64(k)
                ),
            )
            .with_value(to_f64(k)));
        }
    }
    Ok(())
}

/// The approximation of the space offset $C(u) + d′ E\,n(u)$ (`n` the unit normal of the
/// projection `planar`, `E` the frame) by [`AdaptiveApproximation`], with the breaks of the
/// curve as knots and `corners` as `C⁰` corners.
///
/// # Errors
/// As [`AdaptiveApproximation::fit`] and the unit normal.
pub(super) fn fit_space_offset<T: Scalar, const D: usize, C, P>(
    curve: &C,
    planar: &P,
    frame: &Frame<T, D>,
    distance: T,
    corners: &[T],
    (degree, tolerance): (usize, T),
) -> Result<(BSpline<T, SVector<T, D>>, T)>
where
    C: ParamCurve<T, Point = SVector<T, D>>,
    P: PlanarCurve<T>,
{
    check_no_corner(planar)?;
    let breaks = curve.breaks();
    let simple: Vec<T> = breaks[1..breaks.len() - 1]
        .iter()
        .copied()
        .filter(|k| !corners.contains(k))
        .collect();
    let fit = AdaptiveApproximation::new(degree, tolerance)
        .breaks(&simple)
        .corners(corners)
        .fit(curve.domain(), |u| {
            Ok(curve.eval(u)? + frame.lift(&planar.unit_normal(u)?) * distance)
        })?;
    Ok((fit.curve, fit.max_error))
}

/// The NURBS curve whose Cartesian control points are moved by `(f − 1)` times their offset
/// from the circle's axis in the plane: the image of the curve under the affine map that
/// scales the plane coordinates about the centre by `f` (exact by affine invariance).
pub(super) fn scaled_about<T: Scalar, const D: usize>(
    curve: &NurbsCurve<T, D>,
    frame: &Frame<T, D>,
    circle: &Circle<T>,
    factor: T,
) -> NurbsCurve<T, D> {
    curve.map_control_points(|p| {
        *p + frame.lift(&((frame.project(p) - circle.centre) * (factor - T::one())))
    })
}
