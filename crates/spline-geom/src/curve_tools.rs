//! Tools on any [`ParamCurve`]: bounding boxes of the control hull and of the Bézier
//! pieces, adaptive tessellation by chord tolerance, the parameter at a given arc length;
//! and joining B-spline curves.

use crate::bezier::Bezier;
use crate::bspline::BSpline;
use crate::param::{ParamCurve, check_in_domain};
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, lerp, to_f64,
};

/// The most segments [`tessellate`] returns.
pub const MAX_TESSELLATION_SEGMENTS: usize = 1 << 22;

/// An axis-aligned box `[min, max]`, coordinate by coordinate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundingBox<P> {
    /// The smallest coordinates.
    pub min: P,
    /// The largest coordinates.
    pub max: P,
}

impl<P> BoundingBox<P> {
    /// The box of `points` (`None` without points).
    pub fn of_points<T: Scalar>(points: impl IntoIterator<Item = P>) -> Option<Self>
    where
        P: ControlPoint<T>,
    {
        let mut it = points.into_iter();
        let first = it.next()?;
        let mut b = Self {
            min: first,
            max: first,
        };
        for q in it {
            b.include(&q);
        }
        Some(b)
    }

    /// Grows the box to contain `q`.
    pub fn include<T: Scalar>(&mut self, q: &P)
    where
        P: ControlPoint<T>,
    {
        for c in 0..P::DIM {
            let v = q.coord(c);
            if v < self.min.coord(c) {
                self.min.set_coord(c, v);
            }
            if v > self.max.coord(c) {
                self.max.set_coord(c, v);
            }
        }
    }

    /// Whether the boxes overlap, each grown by `slack` on every side.
    pub fn overlaps<T: Scalar>(&self, other: &Self, slack: T) -> bool
    where
        P: ControlPoint<T>,
    {
        (0..P::DIM).all(|c| {
            self.min.coord(c) <= other.max.coord(c) + slack
                && other.min.coord(c) <= self.max.coord(c) + slack
        })
    }

    /// The length of the diagonal.
    pub fn diagonal<T: Scalar>(&self) -> T
    where
        P: ControlPoint<T>,
    {
        (self.max - self.min).length()
    }
}

/// The box of the control polygon (Cartesian control points): it contains the curve by the
/// convex hull property (positive weights for NURBS).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{BSpline, hull_box};
/// let c = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 2.0), Vector2::new(2.0, 0.0)])?;
/// let b = hull_box(&c);
/// assert_eq!((b.min, b.max), (Vector2::new(0.0, 0.0), Vector2::new(2.0, 2.0)));
/// # Ok::<(), spline_core::Error>(())
/// ```
pub fn hull_box<T: Scalar, C: ParamCurve<T> + ?Sized>(curve: &C) -> BoundingBox<C::Point> {
    BoundingBox::of_points(curve.control_polygon())
        .expect("a curve has at least one control point")
}

/// The box of the Bézier pieces' control points: inside [`hull_box`], still containing the
/// curve (it is the box of the refined control polygon).
pub fn pieces_box<T: Scalar, C: ParamCurve<T> + ?Sized>(curve: &C) -> BoundingBox<C::Point> {
    BoundingBox::of_points(
        curve
            .bezier_pieces()
            .iter()
            .flat_map(|(_, _, c)| c.iter().map(C::project)),
    )
    .expect("a curve has at least one piece")
}

/// Parameters `a = u_0 < … < u_k = b` such that the curve between consecutive parameters
/// stays within `tolerance` of the chord: every piece is subdivided (de Casteljau) until
/// the control points of its Bézier form lie within `tolerance` of the chord between its
/// ends, which bounds the curve by the convex hull property — a guarantee, not a sample.
/// Breaks are always among the parameters.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{BSpline, tessellate};
/// let c = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 2.0), Vector2::new(2.0, 0.0)])?;
/// let coarse = tessellate(&c, 0.1)?;
/// let fine = tessellate(&c, 0.001)?;
/// assert!(fine.len() > coarse.len());
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidTolerance`] unless the tolerance is positive and finite;
/// [`ErrorKind::InvalidArgument`] when more than [`MAX_TESSELLATION_SEGMENTS`] segments would be
/// needed (the tolerance is too small for the curve's size).
pub fn tessellate<T: Scalar, C: ParamCurve<T> + ?Sized>(curve: &C, tolerance: T) -> Result<Vec<T>> {
    if !(tolerance > T::zero() && tolerance.is_finite()) {
        return Err(Error::invalid_tolerance(
            "chord tolerance",
            "positive and finite",
            to_f64(tolerance),
        ));
    }
    let mut params = vec![curve.domain().0];
    let mut stack: Vec<Bezier<T, C::Coefficient>> = Vec::new();
    for (a, b, coefficients) in curve.bezier_pieces() {
        stack.push(Bezier::with_interval(coefficients, a, b)?);
        while let Some(piece) = stack.pop() {
            let (lo, hi) = piece.interval();
            if flat::<T, C>(piece.control_points(), tolerance) || !(lo < (lo + hi) * cast(0.5)) {
                params.push(hi);
                if params.len() > MAX_TESSELLATION_SEGMENTS {
                    return Err(Error::new(
                        ErrorKind::InvalidArgument,
                        format!(
                            "tessellation to {:.3e} needs more than {MAX_TESSELLATION_SEGMENTS} segments",
                            to_f64(tolerance)
                        ),
                    ));
                }
            } else {
                let (left, right) = piece.subdivide((lo + hi) * cast(0.5))?;
                stack.push(right);
                stack.push(left);
            }
        }
    }
    Ok(params)
}

/// Whether every projected control point is within `tolerance` of the chord.
fn flat<T: Scalar, C: ParamCurve<T> + ?Sized>(coefficients: &[C::Coefficient], tolerance: T) -> bool {
    let points: Vec<C::Point> = coefficients.iter().map(C::project).collect();
    let (a, b) = (points[0], points[points.len() - 1]);
    points.iter().all(|q| distance_to_segment(q, &a, &b) <= tolerance)
}

/// The distance from `q` to the segment `[a, b]`.
pub(crate) fn distance_to_segment<T: Scalar, P: ControlPoint<T>>(q: &P, a: &P, b: &P) -> T {
    let d = *b - *a;
    let dd = d.length_squared();
    let t = if dd > T::zero() {
        ((*q - *a).dot(&d) / dd).max(T::zero()).min(T::one())
    } else {
        T::zero()
    };
    (*q - lerp(*a, *b, t)).length()
}

/// The parameter `u` at which the arc length from the start of the domain is `length`, to
/// the absolute accuracy `accuracy` in length: Newton's method on
/// $s(u) = \int_a^u \lVert C' \rVert$ safeguarded by bisection.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{BSpline, param_at_length};
/// // A straight segment of length 2, parametrised non-uniformly.
/// let c = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(0.0, 0.0), Vector2::new(0.2, 0.0), Vector2::new(2.0, 0.0)])?;
/// let u: f64 = param_at_length(&c, 1.0, 1e-12)?;
/// assert!((c.eval(u)?.x - 1.0f64).abs() < 1e-11);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::OutOfDomain`] unless `0 ≤ length ≤` the curve's length;
/// [`ErrorKind::InvalidTolerance`] unless the accuracy is positive; the errors of
/// [`ParamCurve::arc_length_between`].
pub fn param_at_length<T: Scalar, C: ParamCurve<T> + ?Sized>(
    curve: &C,
    length: T,
    accuracy: T,
) -> Result<T> {
    if !(accuracy > T::zero() && accuracy.is_finite()) {
        return Err(Error::invalid_tolerance(
            "accuracy",
            "positive and finite",
            to_f64(accuracy),
        ));
    }
    let (a, b) = curve.domain();
    let quadrature = accuracy * cast(0.01);
    let total = curve.arc_length_between(a, b, quadrature)?;
    if !(length >= T::zero() && length <= total) {
        return Err(Error::out_of_domain(to_f64(length), (0.0, to_f64(total)))
            .context("arc length"));
    }
    let (mut lo, mut hi) = (a, b);
    let mut u = a + (b - a) * (length / total);
    for _ in 0..200 {
        check_in_domain((a, b), u)?;
        let f = curve.arc_length_between(a, u, quadrature)? - length;
        if f.abs() <= accuracy {
            return Ok(u);
        }
        if f > T::zero() {
            hi = u;
        } else {
            lo = u;
        }
        let speed = curve.speed(u)?;
        let newton = u - f / speed;
        u = if speed > T::zero() && newton > lo && newton < hi {
            newton
        } else {
            (lo + hi) * cast(0.5)
        };
        if !(hi > lo) || (hi - lo) <= (b - a) * cast(4.0 * f64::EPSILON) {
            return Ok(u);
        }
    }
    Err(Error::new(
        ErrorKind::NoConvergence,
        format!("no parameter found at arc length {}", to_f64(length)),
    ))
}

impl<T: Scalar, P: ControlPoint<T>> BSpline<T, P> {
    /// The curve followed by `other`, as one clamped B-spline of the higher degree, `C⁰` at
    /// the junction: `other` is shifted in parameter to start where `self` ends, and the
    /// junction point is `self`'s end point (`other`'s start moves by at most `tolerance`).
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use spline_geom::BSpline;
    /// let a = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
    ///     vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)])?;
    /// let b = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 2.0, 2.0, 2.0],
    ///     vec![Vector2::new(1.0, 0.0), Vector2::new(2.0, 1.0), Vector2::new(3.0, 0.0)])?;
    /// let j = a.join(&b, 1e-12)?;
    /// assert_eq!((j.degree(), j.domain()), (2, (0.0, 3.0)));
    /// assert!((j.eval(2.0)? - b.eval(1.0)?).norm() < 1e-14);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::ToleranceExceeded`] if the end of `self` and the start of `other` are
    /// farther apart than `tolerance`; [`ErrorKind::InvalidTolerance`] for a negative or
    /// non-finite tolerance.
    pub fn join(&self, other: &Self, tolerance: T) -> Result<Self>
    where
        P: spline_core::VectorSpace<T>,
    {
        if !(tolerance >= T::zero() && tolerance.is_finite()) {
            return Err(Error::invalid_tolerance(
                "join tolerance",
                "non-negative and finite",
                to_f64(tolerance),
            ));
        }
        let p = self.degree().max(other.degree());
        let first = self.clamped().elevate_degree(p - self.degree())?;
        let second = other.clamped().elevate_degree(p - other.degree())?;
        let end = first.control_points()[first.len() - 1];
        let gap = (second.control_points()[0] - end).length();
        if gap > tolerance {
            return Err(Error::new(
                ErrorKind::ToleranceExceeded,
                format!(
                    "the curves are {:.3e} apart at the junction (tolerance {:.3e})",
                    to_f64(gap),
                    to_f64(tolerance)
                ),
            ));
        }
        let (_, b) = first.domain();
        let (c, d) = second.domain();
        let shifted = second.reparametrized(b, b + (d - c))?;
        let k1 = first.knots().knots();
        let k2 = shifted.knots().knots();
        let mut knots = k1[..k1.len() - 1].to_vec();
        knots.extend_from_slice(&k2[p + 1..]);
        let mut points = first.control_points().to_vec();
        points.extend_from_slice(&shifted.control_points()[1..]);
        Self::new(KnotVector::new(p, knots)?, points)
    }
}
