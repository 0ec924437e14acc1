//! The bilinearly blended Coons patch (The NURBS Book §10.5) of four boundary curves.

use super::compatible::{boolean_sum, compatible_curves};
use crate::bspline::BSpline;
use crate::homogeneous::Homogeneous;
use crate::nurbs::{NurbsCurve, NurbsSurface};
use crate::surface::Surface;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, to_f64};

/// The curve on `[0, 1]` (the end knots exactly 0 and 1).
fn on_unit<T: Scalar, P: ControlPoint<T>>(c: &BSpline<T, P>) -> Result<BSpline<T, P>> {
    c.clamped().reparametrized(T::zero(), T::one())
}

impl<T: Scalar, P: ControlPoint<T>> Surface<T, P> {
    /// The bilinearly blended Coons patch (The NURBS Book (10.22)–(10.24)) bounded by four
    /// curves: `bottom` $= S(u, 0)$, `top` $= S(u, 1)$, `left` $= S(0, v)$ and `right`
    /// $= S(1, v)$, each mapped onto `[0, 1]`:
    ///
    /// $$ S = R_c + R_d - T, $$
    ///
    /// the ruled surface between `bottom` and `top`, plus the ruled surface between `left`
    /// and `right`, minus the bilinear patch of the four corners (their
    /// [`crate::boolean_sum`]: the three made compatible, their control points combined), so
    /// the patch is a B-spline surface of degrees `(max(p_bottom, p_top, 1), max(p_left,
    /// p_right, 1))` that reproduces all four curves exactly (up to rounding).
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use spline_geom::{BSpline, Surface};
    /// let line = |a: [f64; 3], b: [f64; 3]| BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
    ///     vec![Vector3::from(a), Vector3::from(b)]);
    /// let arch = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![
    ///     Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.5, 0.0, 1.0), Vector3::new(1.0, 0.0, 0.0)])?;
    /// let top = line([0.0, 1.0, 0.0], [1.0, 1.0, 0.0])?;
    /// let left = line([0.0, 0.0, 0.0], [0.0, 1.0, 0.0])?;
    /// let right = line([1.0, 0.0, 0.0], [1.0, 1.0, 0.0])?;
    /// let s = Surface::coons(&arch, &top, &left, &right)?;
    /// assert!((s.eval(0.5, 0.0)? - arch.eval(0.5)?).norm() < 1e-15);
    /// assert!((s.eval(0.5, 0.5)? - Vector3::new(0.5, 0.5, 0.25)).norm() < 1e-15);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::DegenerateGeometry`] if the curves do not meet at the four corners
    /// (within `1e-9` of the largest coordinate); the errors of elevation.
    pub fn coons(
        bottom: &BSpline<T, P>,
        top: &BSpline<T, P>,
        left: &BSpline<T, P>,
        right: &BSpline<T, P>,
    ) -> Result<Self> {
        let [c0, c1, d0, d1] = [bottom, top, left, right].map(on_unit);
        let (c0, c1, d0, d1) = (c0?, c1?, d0?, d1?);
        check_corners([&c0, &c1, &d0, &d1].map(BSpline::control_points))?;
        let ends = |c: &BSpline<T, P>| {
            let cp = c.control_points();
            (cp[0], cp[cp.len() - 1])
        };
        let ((b0, b1), (t0, t1)) = (ends(&c0), ends(&c1));
        let linear =
            || KnotVector::new_unchecked(1, vec![T::zero(), T::zero(), T::one(), T::one()]);
        let ruled = |a: &BSpline<T, P>, b: &BSpline<T, P>| -> Result<Self> {
            let pair = compatible_curves(&[a.clone(), b.clone()])?;
            let points = pair[0]
                .control_points()
                .iter()
                .zip(pair[1].control_points())
                .flat_map(|(p, q)| [*p, *q])
                .collect();
            Ok(Self::new_unchecked(
                pair[0].knots().clone(),
                linear(),
                points,
            ))
        };
        let rc = ruled(&c0, &c1)?;
        let rd = ruled(&d0, &d1)?.transposed();
        let corners = Self::new_unchecked(linear(), linear(), vec![b0, t0, b1, t1]);
        boolean_sum(rc, rd, corners)
    }
}

impl<T: Scalar, const D: usize> NurbsSurface<T, D> {
    /// The Coons patch of four NURBS boundary curves: `bottom` $= S(u, 0)$, `top`
    /// $= S(u, 1)$, `left` $= S(0, v)$, `right` $= S(1, v)$, each mapped onto `[0, 1]`.
    ///
    /// The curves are made compatible in pairs (bottom and top, left and right) in
    /// homogeneous space; the control points of the patch are the bilinearly blended Coons
    /// net of the boundaries' control points ([`Surface::coons`] on them), and its weights
    /// the blend of the logarithms of the boundaries' weights, so they are positive whatever
    /// the boundaries' weights are. The rows and columns at the border of both nets are the
    /// boundary curves' own, so the patch reproduces each boundary exactly once the weights
    /// agree at the corners. A curve's weights can be multiplied by a constant without
    /// changing it, which makes three corners agree; the fourth needs the ratio of the end
    /// weights of one curve changed, which a Möbius reparametrization
    /// ([`NurbsCurve::mobius_reparametrized`]) of `top` does without changing its points:
    /// $S(u, 1)$ then runs through `top` at those rational linear parameters (at its own
    /// when the weights already agreed). Boundaries with unit weights give the patch of
    /// [`Surface::coons`] with unit weights; degrees `(max(p_bottom, p_top, 1),
    /// max(p_left, p_right, 1))`.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use spline_geom::{NurbsCurve3, NurbsSurface3};
    /// // A quarter of a cylinder of radius 1 and height 2: two arcs and two lines.
    /// let h = 0.5f64.sqrt();
    /// let arc = |z: f64| NurbsCurve3::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    ///     vec![Vector3::new(1.0, 0.0, z), Vector3::new(1.0, 1.0, z), Vector3::new(0.0, 1.0, z)],
    ///     vec![1.0, h, 1.0]);
    /// let line = |a: Vector3<f64>, b: Vector3<f64>| NurbsCurve3::from_knots(1,
    ///     vec![0.0, 0.0, 1.0, 1.0], vec![a, b], vec![1.0, 1.0]);
    /// let patch = NurbsSurface3::coons(
    ///     &arc(0.0)?, &arc(2.0)?,
    ///     &line(Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 0.0, 2.0))?,
    ///     &line(Vector3::new(0.0, 1.0, 0.0), Vector3::new(0.0, 1.0, 2.0))?,
    /// )?;
    /// let p = patch.eval(0.3, 0.7)?;
    /// assert!((p.x.hypot(p.y) - 1.0).abs() < 1e-14 && (p.z - 1.4).abs() < 1e-14);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::DegenerateGeometry`] if the curves do not meet at the four corners
    /// (within `1e-9` of the largest coordinate); [`ErrorKind::InvalidWeight`] when a
    /// weight overflows; the errors of elevation.
    pub fn coons(
        bottom: &NurbsCurve<T, D>,
        top: &NurbsCurve<T, D>,
        left: &NurbsCurve<T, D>,
        right: &NurbsCurve<T, D>,
    ) -> Result<Self> {
        let unit = |c: &NurbsCurve<T, D>| c.clamped().reparametrized(T::zero(), T::one());
        let (c0, c1, d0, d1) = (unit(bottom)?, unit(top)?, unit(left)?, unit(right)?);
        check_corners([&c0, &c1, &d0, &d1].map(NurbsCurve::control_points))?;
        let end_weights = |c: &NurbsCurve<T, D>| (c.weights()[0], c.weights()[c.len() - 1]);
        let ((wb0, wb1), (wl0, wl1), (wr0, wr1)) =
            (end_weights(&c0), end_weights(&d0), end_weights(&d1));
        // Bottom as it is; left and right scaled to its corner weights; top reparametrized
        // so that its end weights have the ratio the scaled sides ask for, then scaled.
        let left_scale = wb0 / wl0;
        let right_scale = wb1 / wr0;
        let (want0, want1) = (left_scale * wl1, right_scale * wr1);
        let (wt0, wt1) = end_weights(&c1);
        let (have, want) = (wt1 / wt0, want1 / want0);
        let c1 = if (have - want).abs() <= cast::<T>(1e-14) * want {
            c1
        } else {
            let power = T::one() / cast::<T>(c1.degree() as f64);
            c1.mobius_reparametrized((have / want).powf(power))?
        };
        let top_scale = want0 / c1.weights()[0];
        let scaled = |c: &NurbsCurve<T, D>, s: T| {
            c.homogeneous()
                .map_control_points(|h| Homogeneous::new(h.point * s, h.weight * s))
        };
        let across = compatible_curves(&[c0.into_homogeneous(), scaled(&c1, top_scale)])?;
        let along = compatible_curves(&[scaled(&d0, left_scale), scaled(&d1, right_scale)])?;
        // The Cartesian control points and the logarithms of the weights, each a B-spline
        // curve on the compatible knots.
        let points = |c: &BSpline<T, Homogeneous<T, D>>| c.map_control_points(Homogeneous::project);
        let logs = |c: &BSpline<T, Homogeneous<T, D>>| {
            c.map_control_points(|h| nalgebra::Vector1::new(h.weight.ln()))
        };
        let net = Surface::coons(
            &points(&across[0]),
            &points(&across[1]),
            &points(&along[0]),
            &points(&along[1]),
        )?;
        let log_weights = Surface::coons(
            &logs(&across[0]),
            &logs(&across[1]),
            &logs(&along[0]),
            &logs(&along[1]),
        )?;
        let (knots_u, knots_v, points) = net.into_parts();
        let weights = log_weights
            .control_points()
            .iter()
            .map(|l| l.x.exp())
            .collect();
        Self::new(knots_u, knots_v, points, weights)
    }
}

/// The four corners of the Coons patch of curves on `[0, 1]` meet: the end control points of
/// `[bottom, top, left, right]` agree within `1e-9` of the largest coordinate magnitude.
fn check_corners<T: Scalar, P: ControlPoint<T>>(nets: [&[P]; 4]) -> Result<()> {
    let ends = |net: &[P]| (net[0], net[net.len() - 1]);
    let [(b0, b1), (t0, t1), (l0, l1), (r0, r1)] = nets.map(ends);
    let mut largest = T::zero();
    for p in nets.iter().flat_map(|net| net.iter()) {
        for k in 0..P::DIM {
            largest = largest.max(p.coord(k).abs());
        }
    }
    let tolerance = cast::<T>(1e-9) * (T::one() + largest);
    for (name, a, b) in [
        ("bottom and left", b0, l0),
        ("bottom and right", b1, r0),
        ("top and left", t0, l1),
        ("top and right", t1, r1),
    ] {
        let gap = (a - b).length();
        if !(gap <= tolerance) {
            return Err(Error::new(
                ErrorKind::DegenerateGeometry,
                format!(
                    "the {name} curves do not meet at their common corner (gap {})",
                    to_f64(gap)
                ),
            )
            .with_value(to_f64(gap)));
        }
    }
    Ok(())
}
