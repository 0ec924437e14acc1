//! The bilinearly blended Coons patch (The NURBS Book §10.5) of four boundary curves.

use super::compatible::{compatible_curves, compatible_surfaces};
use crate::bspline::BSpline;
use crate::surface::Surface;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, to_f64};

/// The largest coordinate magnitude of the control points (the scale of corner checks).
fn magnitude<T: Scalar, P: ControlPoint<T>>(curves: &[&BSpline<T, P>]) -> T {
    let mut m = T::zero();
    for c in curves {
        for p in c.control_points() {
            for k in 0..P::DIM {
                m = m.max(p.coord(k).abs());
            }
        }
    }
    m
}

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
    /// and `right`, minus the bilinear patch of the four corners; the three are made
    /// compatible ([`crate::compatible_surfaces`]) and their control points combined, so the
    /// patch is a B-spline surface of degrees `(max(p_bottom, p_top, 1), max(p_left,
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
        let ends = |c: &BSpline<T, P>| {
            let cp = c.control_points();
            (cp[0], cp[cp.len() - 1])
        };
        let ((b0, b1), (t0, t1), (l0, l1), (r0, r1)) = (ends(&c0), ends(&c1), ends(&d0), ends(&d1));
        let tolerance = cast::<T>(1e-9) * (T::one() + magnitude(&[&c0, &c1, &d0, &d1]));
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
        let parts = compatible_surfaces(&[rc, rd, corners])?;
        let points = parts[0]
            .control_points()
            .iter()
            .zip(parts[1].control_points())
            .zip(parts[2].control_points())
            .map(|((a, b), c)| *a + *b - *c)
            .collect();
        let (ku, kv, _) = parts[0].clone().into_parts();
        Ok(Self::new_unchecked(ku, kv, points))
    }
}
