//! Differential geometry of curves: unit tangent, normal, signed curvature (planar), curvature
//! magnitude (any dimension), speed.

use crate::bspline::BSpline;
use nalgebra::Vector2;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, to_f64};

fn degenerate(u: f64) -> Error {
    Error::new(
        ErrorKind::DegenerateGeometry,
        format!(
            "the curve has zero velocity at u = {u}: tangent and curvature are undefined there"
        ),
    )
}

impl<T: Scalar, P: ControlPoint<T>> BSpline<T, P> {
    /// The speed $\lVert C'(u) \rVert$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn speed(&self, u: T) -> Result<T> {
        let mut d = [P::origin(); 2];
        self.derivatives_into(u, &mut d)?;
        Ok(d[1].length())
    }

    /// The unit tangent $C'(u) / \lVert C'(u) \rVert$.
    ///
    /// # Errors
    /// [`ErrorKind::DegenerateGeometry`] where the velocity vanishes; the errors of
    /// [`BSpline::eval`].
    pub fn unit_tangent(&self, u: T) -> Result<P> {
        let mut d = [P::origin(); 2];
        self.derivatives_into(u, &mut d)?;
        let speed = d[1].length();
        if !(speed > T::zero()) {
            return Err(degenerate(to_f64(u)));
        }
        Ok(d[1] * (T::one() / speed))
    }

    /// The unsigned curvature in any dimension,
    /// $\kappa = \frac{\sqrt{\lVert C'\rVert^2 \lVert C''\rVert^2 - (C'\cdot C'')^2}}{\lVert C'\rVert^3}$.
    ///
    /// # Errors
    /// As [`BSpline::unit_tangent`].
    pub fn curvature_magnitude(&self, u: T) -> Result<T> {
        let mut d = [P::origin(); 3];
        self.derivatives_into(u, &mut d)?;
        let s2 = d[1].length_squared();
        if !(s2 > T::zero()) {
            return Err(degenerate(to_f64(u)));
        }
        let cross2 = (s2 * d[2].length_squared() - d[1].dot(&d[2]).powi(2)).max(T::zero());
        Ok(cross2.sqrt() / (s2 * s2.sqrt()))
    }
}

/// The wedge product $a \wedge b = a_x b_y - a_y b_x$ of planar vectors.
#[inline]
pub fn wedge<T: Scalar>(a: &Vector2<T>, b: &Vector2<T>) -> T {
    a.x * b.y - a.y * b.x
}

impl<T: Scalar> BSpline<T, Vector2<T>> {
    /// The unit normal: the unit tangent turned by +90°, so that it points to the centre of
    /// curvature where the signed curvature is positive.
    ///
    /// # Errors
    /// As [`BSpline::unit_tangent`].
    pub fn unit_normal(&self, u: T) -> Result<Vector2<T>> {
        let t = self.unit_tangent(u)?;
        Ok(Vector2::new(-t.y, t.x))
    }

    /// The signed curvature $\kappa = \frac{C' \wedge C''}{\lVert C' \rVert^3}$ (positive
    /// when the curve turns left).
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use spline_geom::BSpline;
    /// // y = x² at x = 0 has curvature 2.
    /// let parabola = BSpline::from_knots(2, vec![-1.0, -1.0, -1.0, 1.0, 1.0, 1.0],
    ///     vec![Vector2::new(-1.0, 1.0), Vector2::new(0.0, -1.0), Vector2::new(1.0, 1.0)])?;
    /// assert!((parabola.signed_curvature(0.0)? - 2.0f64).abs() < 1e-14);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSpline::unit_tangent`].
    pub fn signed_curvature(&self, u: T) -> Result<T> {
        let mut d = [Vector2::zeros(); 3];
        self.derivatives_into(u, &mut d)?;
        let s2 = d[1].norm_squared();
        if !(s2 > T::zero()) {
            return Err(degenerate(to_f64(u)));
        }
        Ok(wedge(&d[1], &d[2]) / (s2 * s2.sqrt()))
    }
}
