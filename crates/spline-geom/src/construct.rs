//! The classic constructions of seed 004 §5.2 and §6: cylindrical (extruded), ruled and
//! conical surfaces (5.14)–(5.17); conic arcs (6.6)–(6.7) with the classification of
//! Proposition 6.1; circular arcs (6.8) of any sweep; the full circle both ways of the notes
//! ((6.9)–(6.10) and the equilateral triangle); surfaces of revolution (6.11)–(6.12), the
//! sphere (6.13)–(6.14) and the torus.
//!
//! Every construction is exact: the rational constructions reproduce circles and conics
//! up to rounding only.

use crate::bspline::BSpline;
use crate::homogeneous::{Homogeneous, check_weight};
use crate::nurbs::{NurbsCurve, NurbsSurface};
use crate::surface::Surface;
use nalgebra::{SVector, Vector3};
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, from_count, to_f64,
};

fn degenerate(message: impl Into<String>) -> Error {
    Error::new(ErrorKind::DegenerateGeometry, message)
}

fn check_vector<T: Scalar, const D: usize>(v: &SVector<T, D>, what: &str) -> Result<()> {
    if v.iter().all(nalgebra::ComplexField::is_finite) {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::NonFinite,
            format!("{what} is not finite"),
        ))
    }
}

fn check_positive<T: Scalar>(value: T, what: &str) -> Result<()> {
    if !value.is_finite() {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("{what} is not finite"),
        ));
    }
    if !(value > T::zero()) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("{what} must be positive, got {}", to_f64(value)),
        ));
    }
    Ok(())
}

/// An orthonormal frame of a plane in $\mathbb{R}^D$ (`D ≥ 2`): an origin and two
/// perpendicular unit vectors. Circles and arcs are built in such a frame.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::Frame;
/// let f = Frame::with_normal(Vector3::new(0.0, 0.0, 1.0), Vector3::new(0.0, 0.0, 2.0))?;
/// assert_eq!(f.x_axis(), Vector3::new(1.0, 0.0, 0.0));
/// assert_eq!(f.y_axis(), Vector3::new(0.0, 1.0, 0.0));
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame<T, const D: usize> {
    origin: SVector<T, D>,
    x_axis: SVector<T, D>,
    y_axis: SVector<T, D>,
}

impl<T: Scalar, const D: usize> Frame<T, D> {
    /// The frame at `origin` whose x axis points along `x_direction` and whose y axis is the
    /// unit vector of `y_direction` made perpendicular to it (Gram–Schmidt).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] if `x_direction` is zero
    /// or `y_direction` is (numerically) parallel to it.
    pub fn new(
        origin: SVector<T, D>,
        x_direction: SVector<T, D>,
        y_direction: SVector<T, D>,
    ) -> Result<Self> {
        check_vector(&origin, "the origin")?;
        check_vector(&x_direction, "the x direction")?;
        check_vector(&y_direction, "the y direction")?;
        let xl = safe_norm(&x_direction);
        if !(xl > T::zero()) {
            return Err(degenerate("the x direction of a frame must not be zero"));
        }
        let x_axis = x_direction / xl;
        let y = y_direction - x_axis * x_axis.dot(&y_direction);
        let yl = safe_norm(&y);
        if !(yl > T::default_epsilon().sqrt() * safe_norm(&y_direction)) {
            return Err(degenerate(
                "the y direction of a frame must not be zero or parallel to the x direction",
            ));
        }
        Ok(Self {
            origin,
            x_axis,
            y_axis: y / yl,
        })
    }

    /// The origin.
    #[must_use]
    pub fn origin(&self) -> SVector<T, D> {
        self.origin
    }

    /// The unit x axis.
    #[must_use]
    pub fn x_axis(&self) -> SVector<T, D> {
        self.x_axis
    }

    /// The unit y axis.
    #[must_use]
    pub fn y_axis(&self) -> SVector<T, D> {
        self.y_axis
    }

    /// The point `origin + x X + y Y`.
    #[must_use]
    pub fn point(&self, x: T, y: T) -> SVector<T, D> {
        self.origin + self.x_axis * x + self.y_axis * y
    }
}

impl<T: Scalar> Frame<T, 2> {
    /// The standard frame of the plane moved to `origin`.
    #[must_use]
    pub fn planar(origin: nalgebra::Vector2<T>) -> Self {
        Self {
            origin,
            x_axis: nalgebra::Vector2::x(),
            y_axis: nalgebra::Vector2::y(),
        }
    }
}

impl<T: Scalar> Frame<T, 3> {
    /// A frame of the plane through `origin` perpendicular to `normal`, right-handed about
    /// it (`x × y = n / |n|`). The x axis is the coordinate axis least aligned with the
    /// normal, projected on the plane; for `n = z` the frame is `(x, y)`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] for a zero normal.
    pub fn with_normal(origin: Vector3<T>, normal: Vector3<T>) -> Result<Self> {
        check_vector(&origin, "the center")?;
        check_vector(&normal, "the normal")?;
        let len = safe_norm(&normal);
        if !(len > T::zero()) {
            return Err(degenerate("the normal of a plane must not be zero"));
        }
        let n = normal / len;
        let x = perpendicular(&n);
        Ok(Self {
            origin,
            x_axis: x,
            y_axis: n.cross(&x),
        })
    }
}

/// A unit vector perpendicular to the unit vector `n`: the coordinate axis least aligned
/// with `n` (the first on ties), projected on the plane `n⊥`.
fn perpendicular<T: Scalar>(n: &Vector3<T>) -> Vector3<T> {
    let mut best = 0;
    for i in 1..3 {
        if n[i].abs() < n[best].abs() {
            best = i;
        }
    }
    let e = Vector3::<T>::ith(best, T::one());
    let x = e - n * n.dot(&e);
    x / safe_norm(&x)
}

/// An axis of revolution: a point and a unit direction.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::{Axis, ErrorKind};
/// let axis = Axis::new(Vector3::new(1.0, 0.0, 0.0), Vector3::new(0.0, 0.0, 2.0))?;
/// assert_eq!(axis.direction(), Vector3::new(0.0, 0.0, 1.0));
/// let bad = Axis::new(Vector3::new(1.0, 0.0, 0.0), Vector3::zeros());
/// assert_eq!(bad.unwrap_err().kind(), ErrorKind::DegenerateGeometry);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axis<T> {
    point: Vector3<T>,
    direction: Vector3<T>,
}

impl<T: Scalar> Axis<T> {
    /// The axis through `point` along `direction` (normalised).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] for a zero direction.
    pub fn new(point: Vector3<T>, direction: Vector3<T>) -> Result<Self> {
        check_vector(&point, "the axis point")?;
        check_vector(&direction, "the axis direction")?;
        let len = safe_norm(&direction);
        if !(len > T::zero()) {
            return Err(degenerate("the direction of an axis must not be zero"));
        }
        Ok(Self {
            point,
            direction: direction / len,
        })
    }

    /// A point of the axis.
    #[must_use]
    pub fn point(&self) -> Vector3<T> {
        self.point
    }

    /// The unit direction.
    #[must_use]
    pub fn direction(&self) -> Vector3<T> {
        self.direction
    }

    /// The orthogonal projection of `p` on the axis.
    #[must_use]
    pub fn project(&self, p: &Vector3<T>) -> Vector3<T> {
        self.point + self.direction * self.direction.dot(&(p - self.point))
    }
}

/// The type of a conic arc (seed 004 Proposition 6.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ConicKind {
    /// $w_1 < 1$ (with $w_0 = w_2 = 1$).
    Ellipse,
    /// $w_1 = 1$: the arc is a polynomial (quadratic Bézier) curve.
    Parabola,
    /// $w_1 > 1$.
    Hyperbola,
}

impl ConicKind {
    /// The type of the rational quadratic Bézier arc with weights `w0, w1, w2`: by
    /// Proposition 6.1 applied to the normalised weights $(1, w_1/\sqrt{w_0 w_2}, 1)$, the
    /// sign of $w_1^2 - w_0 w_2$ decides (exact comparison: parabolas are exactly the
    /// polynomial arcs).
    #[must_use]
    pub fn from_weights<T: Scalar>(w0: T, w1: T, w2: T) -> Self {
        let d = w1 * w1 - w0 * w2;
        if d < T::zero() {
            Self::Ellipse
        } else if d > T::zero() {
            Self::Hyperbola
        } else {
            Self::Parabola
        }
    }
}

/// How a full circle is built from rational quadratic arcs (seed 004 §6, "Construction
/// d'un cercle").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum CircleConstruction {
    /// Four quarter circles: 9 control points on a square (corners and side midpoints),
    /// knots (6.9) `[0,0,0,¼,¼,½,½,¾,¾,1,1,1]`, weights (6.10) `[1, √2/2, 1, …, 1]`.
    #[default]
    Square,
    /// Three thirds of a circle: 7 control points on an equilateral triangle (vertices and
    /// side midpoints), knots `[0,0,0,⅓,⅓,⅔,⅔,1,1,1]`, weights `[1,½,1,½,1,½,1]`.
    Triangle,
}

/// The control polygon of a circle of radius 1 in frame coordinates, with weights and knots.
struct ArcTemplate<T> {
    /// `(x, y, w)`: the control point `x X + y Y` (radius 1) and its weight.
    points: Vec<(T, T, T)>,
    knots: KnotVector<T>,
}

fn full_circle_template<T: Scalar>(construction: CircleConstruction) -> ArcTemplate<T> {
    let (one, zero) = (T::one(), T::zero());
    match construction {
        CircleConstruction::Square => {
            let s: T = cast::<T>(0.5).sqrt();
            let corners = [
                (one, zero, one),
                (one, one, s),
                (zero, one, one),
                (-one, one, s),
                (-one, zero, one),
                (-one, -one, s),
                (zero, -one, one),
                (one, -one, s),
                (one, zero, one),
            ];
            let q = |x: f64| cast::<T>(x);
            ArcTemplate {
                points: corners.to_vec(),
                knots: KnotVector::new_unchecked(
                    2,
                    vec![
                        zero,
                        zero,
                        zero,
                        q(0.25),
                        q(0.25),
                        q(0.5),
                        q(0.5),
                        q(0.75),
                        q(0.75),
                        one,
                        one,
                        one,
                    ],
                ),
            }
        }
        CircleConstruction::Triangle => {
            let h: T = cast(0.5);
            let r3: T = cast::<T>(3.0).sqrt();
            let two: T = cast(2.0);
            let third = one / cast::<T>(3.0);
            let two_thirds = two / cast::<T>(3.0);
            ArcTemplate {
                points: vec![
                    (one, zero, one),
                    (one, r3, h),
                    (-h, r3 * h, one),
                    (-two, zero, h),
                    (-h, -r3 * h, one),
                    (one, -r3, h),
                    (one, zero, one),
                ],
                knots: KnotVector::new_unchecked(
                    2,
                    vec![
                        zero, zero, zero, third, third, two_thirds, two_thirds, one, one, one,
                    ],
                ),
            }
        }
    }
}

/// A circular arc of radius 1 from angle `start` sweeping `sweep` (radians, sign gives the
/// sense) in `pieces` rational quadratic pieces: each piece of angle Δ has its middle
/// control point where the end tangents meet, at distance `1 / cos(Δ/2)`, with weight
/// `cos(Δ/2)` (6.8). Knots are double at the joints, the domain is `[0, 1]`.
fn arc_template<T: Scalar>(start: T, sweep: T, pieces: usize) -> ArcTemplate<T> {
    let n = from_count::<T>(pieces);
    let delta = sweep / n;
    let half = delta * cast(0.5);
    let w = half.cos();
    let mut points = Vec::with_capacity(2 * pieces + 1);
    for k in 0..pieces {
        let a = start + delta * from_count::<T>(k);
        points.push((a.cos(), a.sin(), T::one()));
        let m = a + half;
        points.push((m.cos() / w, m.sin() / w, w));
    }
    let end = start + sweep;
    points.push((end.cos(), end.sin(), T::one()));
    let mut knots = vec![T::zero(); 3];
    for k in 1..pieces {
        let t = from_count::<T>(k) / n;
        knots.push(t);
        knots.push(t);
    }
    knots.extend([T::one(); 3]);
    ArcTemplate {
        points,
        knots: KnotVector::new_unchecked(2, knots),
    }
}

/// The largest number of rational quadratic pieces of an arc (`NurbsCurve::arc_with_max_piece`):
/// a full circle in pieces of at least 0.36°.
pub const MAX_ARC_PIECES: usize = 1000;

/// Validates a sweep angle and returns the number of pieces of at most `max_piece`.
fn arc_pieces<T: Scalar>(sweep: T, max_piece: T) -> Result<usize> {
    if !(sweep.is_finite() && max_piece.is_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            "arc angles must be finite",
        ));
    }
    let two_pi = T::two_pi();
    let full = two_pi * (T::one() + cast(1e-12));
    if !(sweep != T::zero() && sweep.abs() <= full) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the sweep angle must be non-zero and at most 2π in magnitude, got {} rad",
                to_f64(sweep)
            ),
        ));
    }
    if !(max_piece > T::zero() && max_piece < T::pi()) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the largest piece of an arc must lie strictly between 0 and π, got {} rad",
                to_f64(max_piece)
            ),
        ));
    }
    // Sweeps that are whole multiples of the piece angle (360° / 90°) up to rounding.
    let ratio = (to_f64(sweep.abs() / max_piece) * (1.0 - 1e-12))
        .ceil()
        .max(1.0);
    #[allow(clippy::cast_precision_loss)]
    if !(ratio <= MAX_ARC_PIECES as f64) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "an arc of {} rad in pieces of at most {} rad needs {} pieces, more than the supported maximum {MAX_ARC_PIECES}; allow larger pieces",
                to_f64(sweep.abs()),
                to_f64(max_piece),
                spline_core::Short(ratio)
            ),
        ));
    }
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let pieces = ratio as usize;
    Ok(pieces)
}

fn is_full_turn<T: Scalar>(sweep: T) -> bool {
    (sweep.abs() - T::two_pi()).abs() <= T::two_pi() * cast(1e-12)
}

/// Rational quadratic pieces of a circle of radius `radius` in `frame`.
fn arc_in_frame<T: Scalar, const D: usize>(
    frame: &Frame<T, D>,
    radius: T,
    template: &ArcTemplate<T>,
) -> NurbsCurve<T, D> {
    let points = template
        .points
        .iter()
        .map(|&(x, y, w)| Homogeneous::new(frame.point(x * radius, y * radius) * w, w))
        .collect();
    NurbsCurve::new_unchecked(BSpline::new_unchecked(template.knots.clone(), points))
}

impl<T: Scalar, const D: usize> NurbsCurve<T, D> {
    /// The conic arc (6.6): the rational quadratic Bézier curve on `[0, 1]` with control
    /// points `P0, P1, P2` and weights `[1, w1, 1]`. By Proposition 6.1 it is an arc of an
    /// ellipse for `w1 < 1`, of a parabola for `w1 = 1`, of a hyperbola for `w1 > 1` (see
    /// [`NurbsCurve::conic_kind`]); it is tangent to `P0P1` at `P0` and to `P1P2` at `P2`.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use spline_geom::{ConicKind, NurbsCurve};
    /// let arc = NurbsCurve::conic_arc(Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 1.0),
    ///     Vector2::new(2.0, 0.0), 2.0)?;
    /// assert_eq!(arc.conic_kind(), Some(ConicKind::Hyperbola));
    /// // (6.7): S = R(½), M the midpoint of P0P2: w1 = |SM| / |SP1|.
    /// let s = arc.eval(0.5)?;
    /// assert!(((s - Vector2::new(1.0, 0.0)).norm() / (s - Vector2::new(1.0, 1.0)).norm() - 2.0).abs() < 1e-14);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::InvalidWeight`] unless `w1` is positive and finite;
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] if the three points are
    /// collinear (the "conic" would be a segment).
    pub fn conic_arc(
        p0: SVector<T, D>,
        p1: SVector<T, D>,
        p2: SVector<T, D>,
        w1: T,
    ) -> Result<Self> {
        check_weight(w1).map_err(|e| e.context("w1"))?;
        for (p, name) in [(&p0, "P0"), (&p1, "P1"), (&p2, "P2")] {
            check_vector(p, name)?;
        }
        let (a, b) = (p1 - p0, p2 - p0);
        let area2 = a.norm_squared() * b.norm_squared() - a.dot(&b).powi(2);
        let scale = a.norm_squared() * b.norm_squared();
        if !(area2 > T::default_epsilon() * scale) {
            return Err(degenerate(
                "the control points of a conic arc must not be collinear",
            ));
        }
        let knots = KnotVector::bezier(2, T::zero(), T::one())?;
        Self::new(knots, vec![p0, p1, p2], vec![T::one(), w1, T::one()])
    }

    /// The weight (6.7) of the conic arc through the shoulder point `S`:
    /// $w_1 = \lVert SM \rVert / \lVert SP_1 \rVert$ where `M` is the midpoint of `P0P2`.
    /// `S` must lie strictly between `M` and `P1`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] if `S` is not on the open
    /// segment `]M, P1[` (relative tolerance `√ε`).
    pub fn conic_shoulder_weight(
        p0: SVector<T, D>,
        p1: SVector<T, D>,
        p2: SVector<T, D>,
        shoulder: SVector<T, D>,
    ) -> Result<T> {
        for (p, name) in [(&p0, "P0"), (&p1, "P1"), (&p2, "P2"), (&shoulder, "S")] {
            check_vector(p, name)?;
        }
        let m = (p0 + p2) * cast::<T>(0.5);
        let axis = p1 - m;
        let len2 = axis.norm_squared();
        if !(len2 > T::zero()) {
            return Err(degenerate("P1 must differ from the midpoint of P0P2"));
        }
        let t = (shoulder - m).dot(&axis) / len2;
        let off = safe_norm(&(shoulder - m - axis * t));
        if !(t > T::zero() && t < T::one() && off <= T::default_epsilon().sqrt() * len2.sqrt()) {
            return Err(degenerate(
                "the shoulder point must lie strictly between the midpoint of P0P2 and P1",
            ));
        }
        Ok(safe_norm(&(shoulder - m)) / safe_norm(&(p1 - shoulder)))
    }

    /// The conic arc through the shoulder point `S` (its point at `u = ½`), with the weight
    /// (6.7).
    ///
    /// # Errors
    /// As [`NurbsCurve::conic_shoulder_weight`] and [`NurbsCurve::conic_arc`].
    pub fn conic_arc_through(
        p0: SVector<T, D>,
        p1: SVector<T, D>,
        p2: SVector<T, D>,
        shoulder: SVector<T, D>,
    ) -> Result<Self> {
        let w1 = Self::conic_shoulder_weight(p0, p1, p2, shoulder)?;
        Self::conic_arc(p0, p1, p2, w1)
    }

    /// The type of a single rational quadratic arc (degree 2, three control points), by
    /// Proposition 6.1 ([`ConicKind::from_weights`]); `None` for other curves.
    #[must_use]
    pub fn conic_kind(&self) -> Option<ConicKind> {
        let w = self.weights();
        (self.degree() == 2 && w.len() == 3).then(|| ConicKind::from_weights(w[0], w[1], w[2]))
    }

    /// The circular arc of the isosceles control polygon `P0, P1, P2`
    /// (`|P1P0| = |P1P2|`) with the weight (6.8) $w_1 = \cos\theta$,
    /// $\theta = \widehat{P_1 P_0 P_2}$: e.g. `θ = π/4` gives the quarter circle with
    /// `w1 = √2/2`, `θ = π/3` the third of a circle with `w1 = ½`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] if the polygon is not
    /// isosceles at `P1` (relative tolerance `√ε`) or is flat.
    pub fn circular_arc_from_polygon(
        p0: SVector<T, D>,
        p1: SVector<T, D>,
        p2: SVector<T, D>,
    ) -> Result<Self> {
        for (p, name) in [(&p0, "P0"), (&p1, "P1"), (&p2, "P2")] {
            check_vector(p, name)?;
        }
        let (l0, l2) = (safe_norm(&(p1 - p0)), safe_norm(&(p1 - p2)));
        if !((l0 - l2).abs() <= T::default_epsilon().sqrt() * (l0 + l2)) {
            return Err(degenerate(
                "a circular arc needs |P1P0| = |P1P2| (an isosceles control polygon)",
            ));
        }
        let (a, b) = (p1 - p0, p2 - p0);
        let cos = a.dot(&b) / (safe_norm(&a) * safe_norm(&b));
        if !(cos > T::zero() && cos < T::one()) {
            return Err(degenerate("the control polygon of a circular arc is flat"));
        }
        Self::conic_arc(p0, p1, p2, cos)
    }

    /// The arc of the circle of radius `radius` centred at the frame's origin, from angle
    /// `start` (radians, measured from the frame's x axis towards its y axis) sweeping
    /// `sweep` (negative: clockwise), `0 < |sweep| ≤ 2π`, made of rational quadratic
    /// pieces of at most 90° (each with the weight (6.8) `cos(Δ/2)`). The domain is
    /// `[0, 1]`; a sweep of 2π gives the 9-point circle of (6.9)–(6.10) up to rounding.
    ///
    /// # Errors
    /// As [`NurbsCurve::arc_with_max_piece`].
    pub fn arc(frame: &Frame<T, D>, radius: T, start: T, sweep: T) -> Result<Self> {
        Self::arc_with_max_piece(frame, radius, start, sweep, T::frac_pi_2())
    }

    /// [`NurbsCurve::arc`] with pieces of at most `max_piece` radians (e.g. `2π/3` for
    /// the 120° pieces of the triangle construction), `0 < max_piece < π`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::InvalidArgument`] for a radius that is not
    /// positive, a sweep that is zero or above 2π in magnitude, or `max_piece` outside
    /// `(0, π)`.
    pub fn arc_with_max_piece(
        frame: &Frame<T, D>,
        radius: T,
        start: T,
        sweep: T,
        max_piece: T,
    ) -> Result<Self> {
        check_positive(radius, "the radius")?;
        if !start.is_finite() {
            return Err(Error::new(
                ErrorKind::NonFinite,
                "the start angle is not finite",
            ));
        }
        let pieces = arc_pieces(sweep, max_piece)?;
        let mut template = arc_template(start, sweep, pieces);
        if is_full_turn(sweep) {
            // Close the circle exactly.
            let first = template.points[0];
            if let Some(last) = template.points.last_mut() {
                *last = first;
            }
        }
        Ok(arc_in_frame(frame, radius, &template))
    }

    /// The full circle of radius `radius` centred at the frame's origin, starting at
    /// `origin + radius · X` and turning towards `Y`, built either way of the notes (see
    /// [`CircleConstruction`]).
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use spline_geom::{CircleConstruction, Frame, NurbsCurve};
    /// let c = NurbsCurve::circle(&Frame::planar(Vector2::new(0.0f64, 0.0)), 1.0, CircleConstruction::Square)?;
    /// assert_eq!(c.control_points()[1], Vector2::new(1.0, 1.0));
    /// assert!((c.eval(0.1)?.norm() - 1.0).abs() < 1e-15);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::InvalidArgument`] unless the radius is
    /// positive and finite.
    pub fn circle(
        frame: &Frame<T, D>,
        radius: T,
        construction: CircleConstruction,
    ) -> Result<Self> {
        check_positive(radius, "the radius")?;
        Ok(arc_in_frame(
            frame,
            radius,
            &full_circle_template(construction),
        ))
    }
}

/// Elevates, clamps, reparametrises and refines two curves until they have the same degree
/// and knot vector (the compatibility The NURBS Book §8.4 requires of ruled surfaces).
fn make_compatible<T: Scalar, Q: ControlPoint<T>>(
    a: &BSpline<T, Q>,
    b: &BSpline<T, Q>,
) -> Result<(BSpline<T, Q>, BSpline<T, Q>)> {
    let p = a.degree().max(b.degree());
    let a = a.clamped().elevate_degree(p - a.degree())?;
    let b = b.clamped().elevate_degree(p - b.degree())?;
    // b on the domain of a, with the end knots exactly equal.
    let (s, e) = a.domain();
    let (c, d) = b.domain();
    let scale = (e - s) / (d - c);
    let kb = b.knots().knots();
    let mut knots = kb.to_vec();
    for (k, &x) in knots.iter_mut().zip(kb) {
        *k = if x == c {
            s
        } else if x == d {
            e
        } else {
            s + (x - c) * scale
        };
    }
    let b = BSpline::new(KnotVector::new(p, knots)?, b.control_points().to_vec())?;
    let target = a.knots().merged(b.knots())?;
    let missing = |curve: &BSpline<T, Q>| -> Vec<T> {
        let mut extra = Vec::new();
        for (k, m) in target.interior_breakpoints() {
            extra.extend(std::iter::repeat_n(k, m - curve.knots().multiplicity(k)));
        }
        extra
    };
    let (ma, mb) = (missing(&a), missing(&b));
    Ok((a.refine(&ma)?, b.refine(&mb)?))
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
        check_vector(&center, "the center")?;
        check_positive(radius, "the radius")?;
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
                .map(|&(x, z)| center + Vector3::new(x, zero, z) * radius)
                .collect(),
            vec![one, s, one, s, one],
        )?;
        Self::revolution(&profile, &Axis::new(center, Vector3::z())?, T::two_pi())
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
            ));
        }
        let x = perpendicular(&axis.direction());
        let frame = Frame::new(center + x * major, x, -axis.direction())?;
        let profile = NurbsCurve::circle(&frame, minor, CircleConstruction::Square)?;
        Self::revolution(&profile, &axis, T::two_pi())
    }
}

/// The Euclidean length computed on the vector divided by its largest coordinate, so that it
/// neither overflows (coordinates above 1e154) nor underflows (below 1e-154).
fn safe_norm<T: Scalar, const D: usize>(v: &nalgebra::SVector<T, D>) -> T {
    let m = v.amax();
    if m > T::zero() && m.is_finite() {
        (v / m).norm() * m
    } else {
        v.norm()
    }
}
