//! [`ParamCurve`] and [`ParamSurface`] for every kind of curve and surface, and the
//! inherent shortcuts that call them (so that `curve.signed_curvature(u)` works without
//! importing the traits).

use crate::bezier::Bezier;
use crate::bspline::BSpline;
use crate::homogeneous::Homogeneous;
use crate::nurbs::{NurbsCurve, NurbsSurface};
use crate::param::{ParamCurve, ParamSurface, PlanarCurve, SpatialSurface};
use crate::surface::Surface;
use crate::surface_geometry::LocalProperties;
use nalgebra::{SVector, Vector2, Vector3};
use spline_core::{ControlPoint, Result, Scalar};

impl<T: Scalar, P: ControlPoint<T>> ParamCurve<T> for BSpline<T, P> {
    type Point = P;
    type Coefficient = P;

    fn domain(&self) -> (T, T) {
        self.knots().domain()
    }

    fn eval(&self, u: T) -> Result<P> {
        BSpline::eval(self, u)
    }

    fn derivatives_into(&self, u: T, out: &mut [P]) -> Result<()> {
        BSpline::derivatives_into(self, u, out)
    }

    fn breaks(&self) -> Vec<T> {
        self.knots().domain_breaks()
    }

    fn bezier_pieces(&self) -> Vec<(T, T, Vec<P>)> {
        pieces_of(self)
    }

    fn project(coefficient: &P) -> P {
        *coefficient
    }

    fn control_polygon(&self) -> Vec<P> {
        self.control_points().to_vec()
    }

    fn eval_many(&self, params: &[T]) -> Result<Vec<P>> {
        BSpline::eval_many(self, params)
    }
}

/// The Bézier pieces of a container as intervals with control points.
fn pieces_of<T: Scalar, P: ControlPoint<T>>(curve: &BSpline<T, P>) -> Vec<(T, T, Vec<P>)> {
    curve
        .bezier_segments()
        .into_iter()
        .map(|b| {
            let (lo, hi) = b.interval();
            (lo, hi, b.control_points().to_vec())
        })
        .collect()
}

impl<T: Scalar, P: ControlPoint<T>> ParamCurve<T> for Bezier<T, P> {
    type Point = P;
    type Coefficient = P;

    fn domain(&self) -> (T, T) {
        self.interval()
    }

    fn eval(&self, u: T) -> Result<P> {
        Bezier::eval(self, u)
    }

    /// Derivatives by repeated hodographs (any degree, also above
    /// [`spline_core::MAX_DEGREE`]).
    fn derivatives_into(&self, u: T, out: &mut [P]) -> Result<()> {
        let mut curve = self.clone();
        for (k, slot) in out.iter_mut().enumerate() {
            if k > 0 {
                curve = curve.derivative();
            }
            *slot = curve.eval(u)?;
        }
        Ok(())
    }

    fn breaks(&self) -> Vec<T> {
        let (a, b) = self.interval();
        vec![a, b]
    }

    fn bezier_pieces(&self) -> Vec<(T, T, Vec<P>)> {
        let (a, b) = self.interval();
        vec![(a, b, self.control_points().to_vec())]
    }

    fn project(coefficient: &P) -> P {
        *coefficient
    }

    fn control_polygon(&self) -> Vec<P> {
        self.control_points().to_vec()
    }
}

impl<T: Scalar, const D: usize> ParamCurve<T> for NurbsCurve<T, D> {
    type Point = SVector<T, D>;
    type Coefficient = Homogeneous<T, D>;

    fn domain(&self) -> (T, T) {
        self.knots().domain()
    }

    fn eval(&self, u: T) -> Result<SVector<T, D>> {
        NurbsCurve::eval(self, u)
    }

    fn derivatives_into(&self, u: T, out: &mut [SVector<T, D>]) -> Result<()> {
        NurbsCurve::derivatives_into(self, u, out)
    }

    fn breaks(&self) -> Vec<T> {
        self.knots().domain_breaks()
    }

    fn bezier_pieces(&self) -> Vec<(T, T, Vec<Homogeneous<T, D>>)> {
        pieces_of(self.homogeneous())
    }

    fn project(coefficient: &Homogeneous<T, D>) -> SVector<T, D> {
        coefficient.project()
    }

    fn control_polygon(&self) -> Vec<SVector<T, D>> {
        self.control_points().to_vec()
    }

    fn eval_many(&self, params: &[T]) -> Result<Vec<SVector<T, D>>> {
        NurbsCurve::eval_many(self, params)
    }
}

impl<T: Scalar, P: ControlPoint<T>> ParamSurface<T> for Surface<T, P> {
    type Point = P;
    type Coefficient = P;

    fn domain(&self) -> ((T, T), (T, T)) {
        Surface::domain(self)
    }

    fn eval(&self, u: T, v: T) -> Result<P> {
        Surface::eval(self, u, v)
    }

    fn derivatives_into(&self, u: T, v: T, order: usize, out: &mut [P]) -> Result<()> {
        Surface::derivatives_into(self, u, v, order, out)
    }

    fn breaks(&self) -> (Vec<T>, Vec<T>) {
        (
            self.knots_u().domain_breaks(),
            self.knots_v().domain_breaks(),
        )
    }

    fn eval_grid(&self, us: &[T], vs: &[T]) -> Result<Vec<P>> {
        Surface::eval_grid(self, us, vs)
    }

    fn bezier_patches(&self) -> Vec<Vec<Surface<T, P>>> {
        Surface::bezier_patches(self)
    }

    fn project(coefficient: &P) -> P {
        *coefficient
    }
}

impl<T: Scalar, const D: usize> ParamSurface<T> for NurbsSurface<T, D> {
    type Point = SVector<T, D>;
    type Coefficient = Homogeneous<T, D>;

    fn domain(&self) -> ((T, T), (T, T)) {
        NurbsSurface::domain(self)
    }

    fn eval(&self, u: T, v: T) -> Result<SVector<T, D>> {
        NurbsSurface::eval(self, u, v)
    }

    fn derivatives_into(&self, u: T, v: T, order: usize, out: &mut [SVector<T, D>]) -> Result<()> {
        NurbsSurface::derivatives_into(self, u, v, order, out)
    }

    fn breaks(&self) -> (Vec<T>, Vec<T>) {
        (
            self.knots_u().domain_breaks(),
            self.knots_v().domain_breaks(),
        )
    }

    fn eval_grid(&self, us: &[T], vs: &[T]) -> Result<Vec<SVector<T, D>>> {
        NurbsSurface::eval_grid(self, us, vs)
    }

    fn bezier_patches(&self) -> Vec<Vec<Surface<T, Homogeneous<T, D>>>> {
        self.homogeneous().bezier_patches()
    }

    fn project(coefficient: &Homogeneous<T, D>) -> SVector<T, D> {
        coefficient.project()
    }
}

/// Inherent shortcuts of [`ParamCurve`] methods for the curve kinds.
macro_rules! curve_shortcuts {
    ($(#[$doc:meta])* impl [$($g:tt)*] $ty:ty, $point:ty) => {
        $(#[$doc])*
        impl<$($g)*> $ty {
            /// The speed $\lVert C'(u) \rVert$ ([`ParamCurve::speed`]).
            ///
            /// # Errors
            /// As [`ParamCurve::speed`].
            pub fn speed(&self, u: T) -> Result<T> {
                ParamCurve::speed(self, u)
            }

            /// The unit tangent ([`ParamCurve::unit_tangent`]).
            ///
            /// # Errors
            /// As [`ParamCurve::unit_tangent`].
            pub fn unit_tangent(&self, u: T) -> Result<$point> {
                ParamCurve::unit_tangent(self, u)
            }

            /// The unsigned curvature in any dimension
            /// ([`ParamCurve::curvature_magnitude`]).
            ///
            /// # Errors
            /// As [`ParamCurve::curvature_magnitude`].
            pub fn curvature_magnitude(&self, u: T) -> Result<T> {
                ParamCurve::curvature_magnitude(self, u)
            }

            /// The arc length of the whole curve to the relative `accuracy`
            /// ([`ParamCurve::arc_length`]).
            ///
            /// # Errors
            /// As [`ParamCurve::arc_length_between`].
            pub fn arc_length(&self, accuracy: T) -> Result<T> {
                ParamCurve::arc_length(self, accuracy)
            }

            /// The arc length between parameters `a ≤ b`
            /// ([`ParamCurve::arc_length_between`]).
            ///
            /// # Errors
            /// As [`ParamCurve::arc_length_between`].
            pub fn arc_length_between(&self, a: T, b: T, accuracy: T) -> Result<T> {
                ParamCurve::arc_length_between(self, a, b, accuracy)
            }
        }
    };
}

curve_shortcuts!(
    /// Differential geometry ([`ParamCurve`]).
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use spline_geom::BSpline;
    /// // The parabola y = x², 0 ≤ x ≤ 1: length √5/2 + asinh(2)/4.
    /// let c = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    ///     vec![Vector2::new(0.0, 0.0), Vector2::new(0.5, 0.0), Vector2::new(1.0, 1.0)])?;
    /// let exact = 5f64.sqrt() / 2.0 + 2f64.asinh() / 4.0;
    /// assert!((c.arc_length(1e-12)? - exact).abs() < 1e-12);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    impl [T: Scalar, P: ControlPoint<T>] BSpline<T, P>, P
);
curve_shortcuts!(
    /// Differential geometry ([`ParamCurve`]).
    impl [T: Scalar, const D: usize] NurbsCurve<T, D>, SVector<T, D>
);

/// Inherent shortcuts of [`PlanarCurve`] methods for the planar curve kinds.
macro_rules! planar_shortcuts {
    ($(#[$doc:meta])* impl [$($g:tt)*] $ty:ty) => {
        $(#[$doc])*
        impl<$($g)*> $ty {
            /// The signed curvature $\kappa = \frac{C' \wedge C''}{\lVert C' \rVert^3}$
            /// ([`PlanarCurve::signed_curvature`]).
            ///
            /// # Errors
            /// As [`PlanarCurve::signed_curvature`].
            pub fn signed_curvature(&self, u: T) -> Result<T> {
                PlanarCurve::signed_curvature(self, u)
            }

            /// The unit normal, the unit tangent turned by +90°
            /// ([`PlanarCurve::unit_normal`]).
            ///
            /// # Errors
            /// As [`ParamCurve::unit_tangent`].
            pub fn unit_normal(&self, u: T) -> Result<Vector2<T>> {
                PlanarCurve::unit_normal(self, u)
            }
        }
    };
}

planar_shortcuts!(
    /// Planar differential geometry ([`PlanarCurve`]).
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
    impl [T: Scalar] BSpline<T, Vector2<T>>
);
planar_shortcuts!(
    /// Planar differential geometry ([`PlanarCurve`]).
    impl [T: Scalar] NurbsCurve<T, 2>
);

/// Inherent shortcuts of [`SpatialSurface`] methods for the surface kinds.
macro_rules! surface_shortcuts {
    ($(#[$doc:meta])* impl [$($g:tt)*] $ty:ty) => {
        $(#[$doc])*
        impl<$($g)*> $ty {
            /// The unit normal $S_u \times S_v / \lVert S_u \times S_v \rVert$
            /// ([`SpatialSurface::normal`]).
            ///
            /// # Errors
            /// As [`SpatialSurface::local_properties`].
            pub fn normal(&self, u: T, v: T) -> Result<Vector3<T>> {
                SpatialSurface::normal(self, u, v)
            }

            /// Normal, fundamental forms and curvatures at `(u, v)`
            /// ([`SpatialSurface::local_properties`]).
            ///
            /// # Errors
            /// As [`SpatialSurface::local_properties`].
            pub fn local_properties(&self, u: T, v: T) -> Result<LocalProperties<T>> {
                SpatialSurface::local_properties(self, u, v)
            }
        }
    };
}

surface_shortcuts!(
    /// Differential geometry of surfaces in space ([`SpatialSurface`]).
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use spline_geom::Surface;
    /// // z = u v: K = −1/(1 + u² + v²)².
    /// let s = Surface::bezier(vec![
    ///     vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 1.0, 0.0)],
    ///     vec![Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 1.0, 1.0)],
    /// ])?;
    /// let props = s.local_properties(0.5, 0.5)?;
    /// assert!((props.gaussian_curvature + 1.0 / 1.5f64.powi(2)).abs() < 1e-15);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    impl [T: Scalar] Surface<T, Vector3<T>>
);
surface_shortcuts!(
    /// Differential geometry of surfaces in space ([`SpatialSurface`]).
    impl [T: Scalar] NurbsSurface<T, 3>
);
