//! Capability traits in the style of kurbo: what a consumer needs of a curve or a surface,
//! implemented by every kind (B-spline, Bézier and NURBS curves; B-spline and NURBS
//! surfaces), so that closest points, curvature, curvature combs, features, arc length,
//! plotting and meshing are written once and take any kind.

use crate::planar::{magnitude_formula, scaled_curvature, signed_formula, unit, zero_velocity};
use crate::surface::Surface;
use crate::surface_geometry::LocalProperties;
use nalgebra::{Vector2, Vector3};
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, from_count, to_f64};

/// A parametric curve $C : [a, b] \to \mathbb{R}^D$, piecewise polynomial or rational.
///
/// Required: the domain, evaluation with derivatives into a buffer, the breakpoints of the
/// pieces, and the Bézier pieces of the B-spline container behind the curve (Cartesian
/// points for polynomial curves, homogeneous ones for rational curves), whose Cartesian
/// control points bound each piece (convex hull property). Everything else — speed, unit
/// tangent, curvature, arc length, sampling — is provided.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{BSpline, NurbsCurve, ParamCurve, PlanarCurve};
/// fn turning<C: PlanarCurve<f64>>(c: &C) -> f64 {
///     let (a, b) = c.domain();
///     c.signed_curvature(0.5 * (a + b)).unwrap()
/// }
/// let quarter = NurbsCurve::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(1.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(0.0, 1.0)],
///     vec![1.0, 1.0, 2.0])?;
/// assert!((turning(&quarter) - 1.0).abs() < 1e-14); // the unit circle
/// let parabola = BSpline::from_knots(2, vec![-1.0, -1.0, -1.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(-1.0, 1.0), Vector2::new(0.0, -1.0), Vector2::new(1.0, 1.0)])?;
/// assert!((turning(&parabola) - 2.0).abs() < 1e-14); // y = x² at its vertex
/// # Ok::<(), spline_core::Error>(())
/// ```
pub trait ParamCurve<T: Scalar> {
    /// The points of the curve.
    type Point: ControlPoint<T>;
    /// The control points of the B-spline container behind the curve: [`Self::Point`] for
    /// polynomial curves, [`crate::Homogeneous`] points for rational ones.
    type Coefficient: ControlPoint<T>;

    /// The parametric domain `[a, b]`.
    fn domain(&self) -> (T, T);

    /// The point $C(u)$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    fn eval(&self, u: T) -> Result<Self::Point>;

    /// $C(u), C'(u), …, C^{(k)}(u)$ with `k = out.len() − 1`, written into `out`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for `u`;
    /// [`ErrorKind::NonFinite`] when a derivative is too large for the scalar type.
    fn derivatives_into(&self, u: T, out: &mut [Self::Point]) -> Result<()>;

    /// The ends of the pieces on the domain: `a`, the distinct interior knots, `b`.
    fn breaks(&self) -> Vec<T>;

    /// The Bézier pieces of the container, one per non-empty knot span: each interval with
    /// the `p + 1` control points of the piece on it.
    fn bezier_pieces(&self) -> Vec<(T, T, Vec<Self::Coefficient>)>;

    /// The point of the curve that a container coefficient stands for (itself, or the
    /// central projection of a homogeneous point).
    fn project(coefficient: &Self::Coefficient) -> Self::Point;

    /// The control polygon, as points of the curve's space.
    fn control_polygon(&self) -> Vec<Self::Point>;

    /// The points at many parameters.
    ///
    /// # Errors
    /// As [`ParamCurve::eval`], naming the parameter.
    fn eval_many(&self, params: &[T]) -> Result<Vec<Self::Point>> {
        params
            .iter()
            .enumerate()
            .map(|(i, &u)| {
                self.eval(u)
                    .map_err(|e| e.context(format_args!("parameter {i}")))
            })
            .collect()
    }

    /// The derivatives $C^{(j)}(u)$ for `j = 0 … order`.
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] above [`spline_core::MAX_DERIVATIVE_ORDER`]; the errors
    /// of [`ParamCurve::derivatives_into`].
    fn derivatives(&self, u: T, order: usize) -> Result<Vec<Self::Point>> {
        spline_core::check_derivative_order(order)?;
        let mut out = vec![Self::Point::origin(); order + 1];
        self.derivatives_into(u, &mut out)?;
        Ok(out)
    }

    /// The speed $\lVert C'(u) \rVert$.
    ///
    /// # Errors
    /// As [`ParamCurve::derivatives_into`].
    fn speed(&self, u: T) -> Result<T> {
        let mut d = [Self::Point::origin(); 2];
        self.derivatives_into(u, &mut d)?;
        Ok(d[1].length())
    }

    /// The unit tangent $C'(u) / \lVert C'(u) \rVert$ (computed without overflow).
    ///
    /// # Errors
    /// [`ErrorKind::DegenerateGeometry`] where the velocity vanishes; the errors of
    /// [`ParamCurve::derivatives_into`].
    fn unit_tangent(&self, u: T) -> Result<Self::Point> {
        let mut d = [Self::Point::origin(); 2];
        self.derivatives_into(u, &mut d)?;
        unit(d[1]).ok_or_else(|| zero_velocity(u))
    }

    /// The unsigned curvature in any dimension,
    /// $\kappa = \sqrt{\lVert C'\rVert^2 \lVert C''\rVert^2 - (C'\cdot C'')^2} / \lVert C'\rVert^3$,
    /// computed on the derivatives divided by their largest coordinates (scale-invariant,
    /// no overflow or underflow of the powers).
    ///
    /// # Errors
    /// As [`ParamCurve::unit_tangent`]; [`ErrorKind::NonFinite`] when the curvature is out
    /// of the range of the scalar type.
    fn curvature_magnitude(&self, u: T) -> Result<T> {
        let mut d = [Self::Point::origin(); 3];
        self.derivatives_into(u, &mut d)?;
        scaled_curvature(&d[1], &d[2], u, magnitude_formula)
    }

    /// Parameters covering the domain: `per_span` equal steps in every piece, so that every
    /// break is a sample.
    fn sample_params(&self, per_span: usize) -> Vec<T> {
        let per_span = per_span.max(1);
        let breaks = self.breaks();
        let mut params = Vec::with_capacity((breaks.len() - 1) * per_span + 1);
        for w in breaks.windows(2) {
            for j in 0..per_span {
                params.push(w[0] + (w[1] - w[0]) * from_count::<T>(j) / from_count::<T>(per_span));
            }
        }
        params.push(self.domain().1);
        params
    }

    /// The arc length of the whole curve to the relative `accuracy`
    /// ([`ParamCurve::arc_length_between`]; [`crate::DEFAULT_ACCURACY`] is a good choice).
    ///
    /// # Errors
    /// As [`ParamCurve::arc_length_between`].
    fn arc_length(&self, accuracy: T) -> Result<T> {
        let (a, b) = self.domain();
        self.arc_length_between(a, b, accuracy)
    }

    /// The arc length between parameters `a ≤ b` to the relative `accuracy` (a fraction
    /// of the length: the same digits at every scale of the coordinates):
    /// $\int_a^b \lVert C'(u) \rVert\\,du$ by adaptive Gauss–Legendre quadrature on each
    /// piece (the speed is smooth inside a piece), bisecting where two estimates differ by
    /// more than `accuracy` times the piece's length. A piece is first cut around its
    /// near-stops (where the speed dips far below its size, narrower than the nodes'
    /// spacing: the velocity's Bézier coefficients are halved until they lie on one side
    /// of the origin). A rational piece whose weights lie
    /// more than 16 apart (the curve then rushes through parts of it in parameter intervals
    /// as narrow as their ratio, down to widths no parameter resolves) is halved by de
    /// Casteljau in its own parameter until every part's weights come within that ratio,
    /// and each part measured in its own parameter: weights `[1, 1e300, 1]` give the length
    /// of the two legs.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]/[`ErrorKind::OutOfDomain`] for the bounds;
    /// [`ErrorKind::InvalidArgument`] if `a > b`; [`ErrorKind::InvalidTolerance`] unless the
    /// accuracy is positive; [`ErrorKind::NoConvergence`] if the quadrature does not converge
    /// (an accuracy below what the rounding of the speed allows is not refused: no interval
    /// is asked for less than its rounding, and the length is then as accurate as the speed
    /// can be evaluated).
    fn arc_length_between(&self, a: T, b: T, accuracy: T) -> Result<T> {
        check_in_domain(self.domain(), a)?;
        check_in_domain(self.domain(), b)?;
        if a > b {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "arc length from {} to {}: bounds in decreasing order",
                    to_f64(a),
                    to_f64(b)
                ),
            )
            .with_interval(to_f64(a), to_f64(b)));
        }
        if !(accuracy > T::zero()) {
            return Err(Error::invalid_tolerance(
                "accuracy",
                "positive",
                to_f64(accuracy),
            ));
        }
        let speed = |u: T| {
            let mut d = [Self::Point::origin(); 2];
            // The quadrature nodes lie inside the domain.
            self.derivatives_into(u, &mut d)
                .map_or(T::zero(), |()| d[1].length())
        };
        // Piece by piece: near-stops cut out, a rational piece whose weights are far apart
        // measured in its own parameter.
        crate::arclength::length_by_pieces(
            &self.bezier_pieces(),
            <Self::Point as ControlPoint<T>>::DIM,
            (a, b),
            accuracy,
            speed,
        )
    }
}

/// Checks that `u` is finite and in `[a, b]`.
///
/// # Errors
/// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
pub(crate) fn check_in_domain<T: Scalar>((a, b): (T, T), u: T) -> Result<()> {
    if !u.is_finite() {
        return Err(
            Error::non_finite(format_args!("parameter {}", to_f64(u))).with_value(to_f64(u))
        );
    }
    if u < a || u > b {
        return Err(Error::out_of_domain(to_f64(u), (to_f64(a), to_f64(b))));
    }
    Ok(())
}

/// A planar parametric curve: signed curvature and the unit normal, for every
/// [`ParamCurve`] with planar points.
pub trait PlanarCurve<T: Scalar>: ParamCurve<T, Point = Vector2<T>> {
    /// The signed curvature $\kappa = \frac{C' \wedge C''}{\lVert C' \rVert^3}$ (positive
    /// when the curve turns left), scale-invariant (computed on the derivatives divided by
    /// their largest coordinates).
    ///
    /// # Errors
    /// [`ErrorKind::DegenerateGeometry`] where the velocity vanishes; the errors of
    /// [`ParamCurve::derivatives_into`]; [`ErrorKind::NonFinite`] when the curvature is out
    /// of the range of the scalar type.
    fn signed_curvature(&self, u: T) -> Result<T> {
        let mut d = [Vector2::zeros(); 3];
        self.derivatives_into(u, &mut d)?;
        scaled_curvature(&d[1], &d[2], u, signed_formula)
    }

    /// The unit normal: the unit tangent turned by +90°, pointing to the centre of
    /// curvature where the signed curvature is positive.
    ///
    /// # Errors
    /// As [`ParamCurve::unit_tangent`].
    fn unit_normal(&self, u: T) -> Result<Vector2<T>> {
        let t = self.unit_tangent(u)?;
        Ok(Vector2::new(-t.y, t.x))
    }
}

impl<T: Scalar, C: ParamCurve<T, Point = Vector2<T>> + ?Sized> PlanarCurve<T> for C {}

/// A parametric tensor-product surface $S : [a, b] \times [c, d] \to \mathbb{R}^D$,
/// piecewise polynomial or rational.
pub trait ParamSurface<T: Scalar> {
    /// The points of the surface.
    type Point: ControlPoint<T>;
    /// The control points of the tensor-product container behind the surface:
    /// [`Self::Point`] for polynomial surfaces, [`crate::Homogeneous`] points for rational
    /// ones.
    type Coefficient: ControlPoint<T>;

    /// The parametric domain `((u_min, u_max), (v_min, v_max))`.
    fn domain(&self) -> ((T, T), (T, T));

    /// The point $S(u, v)$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    fn eval(&self, u: T, v: T) -> Result<Self::Point>;

    /// The partial derivatives $\partial^{k+l} S / \partial u^k \partial v^l$ for
    /// `0 ≤ k, l ≤ order` into `out[k (order + 1) + l]`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless `out.len() = (order + 1)²`;
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    fn derivatives_into(&self, u: T, v: T, order: usize, out: &mut [Self::Point]) -> Result<()>;

    /// The ends of the pieces in `u` and in `v` (domain ends and distinct interior knots).
    fn breaks(&self) -> (Vec<T>, Vec<T>);

    /// The Bézier patches of the container (`[a][b]` over the `a`-th non-empty span in `u`
    /// and the `b`-th in `v`, see [`Surface::bezier_patches`]), whose Cartesian control
    /// points ([`ParamSurface::project`]) bound each patch (convex hull property).
    fn bezier_patches(&self) -> Vec<Vec<Surface<T, Self::Coefficient>>>;

    /// The point of the surface that a container coefficient stands for (itself, or the
    /// central projection of a homogeneous point).
    fn project(coefficient: &Self::Coefficient) -> Self::Point;

    /// The points on the grid `us × vs`, row-major (`[a · vs.len() + b]` $= S(u_a, v_b)$).
    ///
    /// # Errors
    /// As [`ParamSurface::eval`] for the first bad parameter.
    fn eval_grid(&self, us: &[T], vs: &[T]) -> Result<Vec<Self::Point>> {
        let mut out = Vec::with_capacity(us.len() * vs.len());
        for &u in us {
            for &v in vs {
                out.push(self.eval(u, v)?);
            }
        }
        Ok(out)
    }
}

/// A surface in space: normals, fundamental forms and curvatures, for every
/// [`ParamSurface`] with points in $\mathbb{R}^3$.
pub trait SpatialSurface<T: Scalar>: ParamSurface<T, Point = Vector3<T>> {
    /// Normal, fundamental forms and curvatures at `(u, v)` (see [`LocalProperties`]).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`];
    /// [`ErrorKind::DegenerateGeometry`] at a singular point.
    fn local_properties(&self, u: T, v: T) -> Result<LocalProperties<T>> {
        let mut d = [Vector3::zeros(); 9];
        self.derivatives_into(u, v, 2, &mut d)?;
        LocalProperties::from_partials(d[0], d[3], d[1], d[6], d[4], d[2])
    }

    /// The unit normal $S_u \times S_v / \lVert S_u \times S_v \rVert$.
    ///
    /// # Errors
    /// As [`SpatialSurface::local_properties`].
    fn normal(&self, u: T, v: T) -> Result<Vector3<T>> {
        Ok(self.local_properties(u, v)?.normal)
    }
}

impl<T: Scalar, S: ParamSurface<T, Point = Vector3<T>> + ?Sized> SpatialSurface<T> for S {}
