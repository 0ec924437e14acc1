//! Cylindrical (extruded), ruled and conical surfaces (5.14)–(5.17), surfaces of revolution
//! (6.11)–(6.12), the sphere (6.13)–(6.14) and the torus.

use super::arcs::{
    CircleConstruction, arc_pieces, arc_template, full_circle_template, is_full_turn,
};
use super::checks::{check_positive, check_vector, degenerate};
use super::compatible::compatible_curves;
use super::placement::{Axis, Frame};
use super::vectors::{perpendicular, safe_norm};
use crate::bspline::BSpline;
use crate::homogeneous::Homogeneous;
use crate::nurbs::{NurbsCurve, NurbsSurface};
use crate::surface::Surface;
use nalgebra::{SVector, Vector3};
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, to_f64};

/// Two curves made compatible ([`compatible_curves`], The NURBS Book §8.4).
fn make_compatible<T: Scalar, Q: ControlPoint<T>>(
    a: &BSpline<T, Q>,
    b: &BSpline<T, Q>,
) -> Result<(BSpline<T, Q>, BSpline<T, Q>)> {
    let mut both = compatible_curves(&[a.clone(), b.clone()])?;
    let b = both.pop().expect("two curves");
    let a = both.pop().expect("two curves");
    Ok((a, b))
}

/// The surface with two rows in `v` (degree 1 on `[0, 1]`): `P_i0 = first_i`, `P_i1 = second_i`.
fn two_row_surface<T: Scalar, Q: ControlPoint<T>>(
    knots_u: KnotVector<T>,
    first: &[Q],
    second: &[Q],
) -> Surface<T, Q> {
    let points = first
        .iter()
        .zip(second)
        .flat_map(|(a, b)| [*a, *b])
        .collect();
    Surface::new_unchecked(
        knots_u,
        KnotVector::new_unchecked(1, vec![T::zero(), T::zero(), T::one(), T::one()]),
        points,
    )
}

impl<T: Scalar, P: ControlPoint<T>> Surface<T, P> {
    /// The cylindrical surface (extrusion) (5.14)–(5.15) of `curve` along `offset`:
    /// $P_{i0} = P_i$, $P_{i1} = P_i + V$, linear in `v ∈ [0, 1]`; every iso-curve at fixed
    /// `u` is the segment from `C(u)` to `C(u) + V`.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use spline_geom::{BSpline, Surface};
    /// let c = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
    ///     vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 0.0, 0.0)])?;
    /// let s = Surface::extrusion(&c, Vector3::new(0.0, 0.0, 2.0))?;
    /// assert_eq!(s.eval(0.5, 0.5)?, Vector3::new(0.5, 0.0, 1.0));
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::DegenerateGeometry`] for a zero offset; [`ErrorKind::NonFinite`].
    pub fn extrusion(curve: &BSpline<T, P>, offset: P) -> Result<Self> {
        if !offset.all_finite() {
            return Err(Error::new(
                ErrorKind::NonFinite,
                "the extrusion vector is not finite",
            ));
        }
        if !(offset.length() > T::zero()) {
            return Err(degenerate("the extrusion vector must not be zero"));
        }
        let moved: Vec<P> = curve.control_points().iter().map(|p| *p + offset).collect();
        Ok(two_row_surface(
            curve.knots().clone(),
            curve.control_points(),
            &moved,
        ))
    }

    /// The ruled surface (5.16) joining `first` (at `v = 0`) to `second` (at `v = 1`) by
    /// segments: `S(u, v) = (1 − v) C_1(u) + v C_2(u)`. The curves are first made compatible
    /// (same degree by elevation, `second` mapped onto the domain of `first`, same knots
    /// by refinement), so any two curves are accepted.
    ///
    /// # Errors
    /// The errors of degree elevation and refinement (e.g. [`ErrorKind::DegreeTooHigh`]).
    pub fn ruled(first: &BSpline<T, P>, second: &BSpline<T, P>) -> Result<Self> {
        let (a, b) = make_compatible(first, second)?;
        Ok(two_row_surface(
            a.knots().clone(),
            a.control_points(),
            b.control_points(),
        ))
    }

    /// The translation surface of two curves (thesis ch. 7):
    /// $S(u, v) = A(u) + B(v) - B(v_0)$, the curve `A` moved along `B` without turning
    /// ($S(u, v_0) = A(u)$; if the curves meet at $A(u_0) = B(v_0)$, both are on the
    /// surface). Exact: control points $P_{ij} = A_i + B_j - B(v_0)$, since each basis sums to
    /// one. $S_{uv} = 0$, so the second fundamental form has no mixed term and the parabolic
    /// lines are where $\det(A'', A', B')$ or $\det(B'', A', B')$ vanish: for curves in
    /// perpendicular planes, the parameter lines through the inflections of either curve.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use spline_geom::{BSpline, Surface};
    /// let a = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    ///     vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 0.0, 1.0), Vector3::new(2.0, 0.0, 0.0)])?;
    /// let b = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
    ///     vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 3.0, 0.5)])?;
    /// let s = Surface::translation(&a, &b)?;
    /// let expected = a.eval(0.3)? + b.eval(0.6)?;
    /// assert!((s.eval(0.3, 0.6)? - expected).norm() < 1e-14);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] if the grid of control points would exceed the
    /// container's limits; the errors of [`Surface::new`].
    pub fn translation(first: &BSpline<T, P>, second: &BSpline<T, P>) -> Result<Self> {
        let (na, nb) = (first.control_points().len(), second.control_points().len());
        let count = na.checked_mul(nb).ok_or_else(|| {
            Error::new(
                ErrorKind::InvalidLength,
                format!("{na} × {nb} control points are too many"),
            )
        })?;
        let start = second.eval(second.domain().0)?;
        let mut points = Vec::with_capacity(count);
        for a in first.control_points() {
            for b in second.control_points() {
                points.push(*a + (*b - start));
            }
        }
        Surface::new(first.knots().clone(), second.knots().clone(), points)
    }

    /// The conical surface (5.17) joining `curve` (at `v = 0`) to the apex `Q` (at `v = 1`):
    /// $P_{i0} = P_i$, $P_{i1} = Q$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] if the apex is not finite.
    pub fn cone(curve: &BSpline<T, P>, apex: P) -> Result<Self> {
        if !apex.all_finite() {
            return Err(Error::new(ErrorKind::NonFinite, "the apex is not finite"));
        }
        let apexes = vec![apex; curve.control_points().len()];
        Ok(two_row_surface(
            curve.knots().clone(),
            curve.control_points(),
            &apexes,
        ))
    }
}

impl<T: Scalar, const D: usize> NurbsSurface<T, D> {
    /// The extrusion (5.14) of a NURBS curve along `offset`: in homogeneous space
    /// $P^w_{i1} = (w_i (P_i + V), w_i)$, so every iso-curve at fixed `u` is the segment
    /// from `R(u)` to `R(u) + V`.
    ///
    /// # Errors
    /// [`ErrorKind::DegenerateGeometry`] for a zero offset; [`ErrorKind::NonFinite`].
    pub fn extrusion(curve: &NurbsCurve<T, D>, offset: SVector<T, D>) -> Result<Self> {
        check_vector(&offset, "the extrusion vector")?;
        if !(safe_norm(&offset) > T::zero()) {
            return Err(degenerate("the extrusion vector must not be zero"));
        }
        let hom = curve.homogeneous();
        let moved: Vec<_> = hom
            .control_points()
            .iter()
            .map(|h| Homogeneous::new(h.point + offset * h.weight, h.weight))
            .collect();
        Ok(Self::new_unchecked(two_row_surface(
            hom.knots().clone(),
            hom.control_points(),
            &moved,
        )))
    }

    /// The ruled surface (5.16) of two NURBS curves, made compatible in homogeneous space:
    /// each iso-curve at fixed `u` is the straight segment from `R_1(u)` to `R_2(u)` (its
    /// parametrisation in `v` is rational unless the weights agree).
    ///
    /// # Errors
    /// As [`Surface::ruled`].
    pub fn ruled(first: &NurbsCurve<T, D>, second: &NurbsCurve<T, D>) -> Result<Self> {
        Ok(Self::new_unchecked(Surface::ruled(
            first.homogeneous(),
            second.homogeneous(),
        )?))
    }

    /// The cone (5.17) over a NURBS curve with apex `Q`: $P^w_{i1} = (w_i Q, w_i)$, so each
    /// iso-curve at fixed `u` is the segment from `R(u)` to `Q`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] if the apex is not finite.
    pub fn cone(curve: &NurbsCurve<T, D>, apex: SVector<T, D>) -> Result<Self> {
        check_vector(&apex, "the apex")?;
        let hom = curve.homogeneous();
        let apexes: Vec<_> = hom
            .control_points()
            .iter()
            .map(|h| Homogeneous::new(apex * h.weight, h.weight))
            .collect();
        Ok(Self::new_unchecked(two_row_surface(
            hom.knots().clone(),
            hom.control_points(),
            &apexes,
        )))
    }
}

impl<T: Scalar> NurbsSurface<T, 3> {
    /// The surface of revolution (6.11)–(6.12) of `profile` about `axis`, through the
    /// angle `angle` (radians, right-handed about the axis direction, `0 < |angle| ≤ 2π`).
    ///
    /// `u` runs along the profile (its knots and degree), `v ∈ [0, 1]` along the circles.
    /// Each control point $P_i$ (weight $w_i$) generates the control points of an arc
    /// centred at its projection $O_i$ on the axis, of radius $r_i = |P_i - O_i|$, in the
    /// frame $X_i = (P_i - O_i)/r_i$, $Y_i = a \times X_i$: for a full turn the 9 points of
    /// the square (6.9)–(6.10), otherwise rational quadratic pieces of at most 90°. The
    /// weights are $w_i \omega_j$. Since every row of the net is the same arc scaled and
    /// rotated, $S(u, v)$ is exactly the profile point $R(u)$ rotated by the angle of `v`,
    /// for any profile, planar or not, rational or not. Control points on the axis stay
    /// where they are (the poles of a sphere).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::InvalidArgument`] for an angle that is zero or
    /// larger than 2π in magnitude.
    pub fn revolution(profile: &NurbsCurve<T, 3>, axis: &Axis<T>, angle: T) -> Result<Self> {
        let pieces = arc_pieces(angle, T::frac_pi_2())?;
        let full = is_full_turn(angle);
        let template = if full {
            let mut t = full_circle_template::<T>(CircleConstruction::Square);
            if angle < T::zero() {
                t.points.iter_mut().for_each(|p| p.1 = -p.1);
            }
            t
        } else {
            arc_template(T::zero(), angle, pieces)
        };
        let hom = profile.homogeneous();
        let nv = template.points.len();
        let mut points = Vec::with_capacity(hom.control_points().len() * nv);
        for h in hom.control_points() {
            let p = h.project();
            let o = axis.project(&p);
            let d = p - o;
            let r = safe_norm(&d);
            let (x, y) = if r > T::zero() {
                let x = d / r;
                (x, axis.direction().cross(&x))
            } else {
                (Vector3::zeros(), Vector3::zeros())
            };
            for (j, &(a, b, w)) in template.points.iter().enumerate() {
                let q = if j == 0 || (full && j == nv - 1) || r == T::zero() {
                    p
                } else {
                    o + x * (a * r) + y * (b * r)
                };
                let weight = h.weight * w;
                points.push(Homogeneous::new(q * weight, weight));
            }
        }
        Ok(Self::new_unchecked(Surface::new_unchecked(
            hom.knots().clone(),
            template.knots.clone(),
            points,
        )))
    }

    /// The sphere (6.13)–(6.14) of center `c` and radius `r`: the half circle from the north
    /// pole `c + r z` to the south pole `c − r z` through `c + r x` (5 control points,
    /// knots `[0,0,0,½,½,1,1,1]`, weights `[1, √2/2, 1, √2/2, 1]`) revolved about the
    /// axis `(c, z)` with the 9-point circle: a 5 × 9 net of degrees (2, 2). The normal
    /// $S_u \times S_v$ points outwards.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::InvalidArgument`] unless `r > 0`.
    pub fn sphere(center: Vector3<T>, radius: T) -> Result<Self> {
        Self::sphere_about(center, radius, Vector3::z())
    }

    /// The sphere of center `c` and radius `r` with its poles on the axis `(c, a)`: as
    /// [`Self::sphere`] with `z` replaced by the unit axis $\hat a$ and `x` by the unit
    /// vector perpendicular to it along the coordinate axis least aligned with it (for
    /// $\hat a = z$: `x`, and the same surface as [`Self::sphere`]). The poles are
    /// $S(0, v) = c + r \hat a$ and $S(1, v) = c - r \hat a$ (Open CASCADE's
    /// `Geom_SphericalSurface` on a placement).
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use spline_geom::NurbsSurface;
    /// let sphere = NurbsSurface::sphere_about(Vector3::zeros(), 2.0, Vector3::new(1.0, 1.0, 0.0))?;
    /// let pole = sphere.eval(0.0, 0.3)?;
    /// assert!((pole - Vector3::new(1.0, 1.0, 0.0) * 2f64.sqrt()).norm() < 1e-14);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::InvalidArgument`] unless `r > 0`;
    /// [`ErrorKind::DegenerateGeometry`] for a zero axis.
    pub fn sphere_about(center: Vector3<T>, radius: T, axis: Vector3<T>) -> Result<Self> {
        check_vector(&center, "the center")?;
        check_positive(radius, "the radius")?;
        let axis = Axis::new(center, axis)?;
        let (pole, across) = (axis.direction(), perpendicular(&axis.direction()));
        let (one, zero, s) = (T::one(), T::zero(), cast::<T>(0.5).sqrt());
        let half = cast::<T>(0.5);
        let pts = [
            (zero, one),
            (one, one),
            (one, zero),
            (one, -one),
            (zero, -one),
        ];
        let profile = NurbsCurve::from_knots(
            2,
            vec![zero, zero, zero, half, half, one, one, one],
            pts.iter()
                .map(|&(x, z)| center + (across * x + pole * z) * radius)
                .collect(),
            vec![one, s, one, s, one],
        )?;
        Self::revolution(&profile, &axis, T::two_pi())
    }

    /// The torus of center `c` about the axis `(c, axis_direction)`: the circle of radius
    /// `minor` centred at distance `major` from the axis, in a plane containing the axis
    /// (9-point circle), revolved about it (9-point circle): a 9 × 9 net of degrees (2, 2).
    /// The normal $S_u \times S_v$ points outwards.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] for a zero axis;
    /// [`ErrorKind::InvalidArgument`] unless `major > minor > 0` (the axis must not meet
    /// the circle).
    pub fn torus(
        center: Vector3<T>,
        axis_direction: Vector3<T>,
        major: T,
        minor: T,
    ) -> Result<Self> {
        let axis = Axis::new(center, axis_direction)?;
        check_positive(minor, "the minor radius")?;
        check_positive(major, "the major radius")?;
        if !(major > minor) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "the major radius ({}) must exceed the minor radius ({}) so that the axis does not meet the circle",
                    to_f64(major),
                    to_f64(minor)
                ),
            )
            .with_value(to_f64(major))
            .with_interval(to_f64(minor), f64::INFINITY));
        }
        let x = perpendicular(&axis.direction());
        let frame = Frame::new(center + x * major, x, -axis.direction())?;
        let profile = NurbsCurve::circle(&frame, minor, CircleConstruction::Square)?;
        Self::revolution(&profile, &axis, T::two_pi())
    }
}
