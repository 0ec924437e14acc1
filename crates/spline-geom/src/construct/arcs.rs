//! Conic arcs (6.6)–(6.7) with the classification of Proposition 6.1, circular arcs (6.8) of
//! any sweep, and the full circle both ways of the notes ((6.9)–(6.10) and the equilateral
//! triangle).

use super::checks::{check_positive, check_vector, degenerate};
use super::placement::Frame;
use super::vectors::safe_norm;
use crate::bspline::BSpline;
use crate::homogeneous::{Homogeneous, check_weight};
use crate::nurbs::NurbsCurve;
use nalgebra::SVector;
use spline_core::{Error, ErrorKind, KnotVector, Result, Scalar, cast, from_count, to_f64};

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
pub(super) struct ArcTemplate<T> {
    /// `(x, y, w)`: the control point `x X + y Y` (radius 1) and its weight.
    pub(super) points: Vec<(T, T, T)>,
    pub(super) knots: KnotVector<T>,
}

pub(super) fn full_circle_template<T: Scalar>(construction: CircleConstruction) -> ArcTemplate<T> {
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
pub(super) fn arc_template<T: Scalar>(start: T, sweep: T, pieces: usize) -> ArcTemplate<T> {
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
pub(super) fn arc_pieces<T: Scalar>(sweep: T, max_piece: T) -> Result<usize> {
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
        )
        .with_value(to_f64(sweep))
        .with_interval(-std::f64::consts::TAU, std::f64::consts::TAU));
    }
    if !(max_piece > T::zero() && max_piece < T::pi()) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the largest piece of an arc must lie strictly between 0 and π, got {} rad",
                to_f64(max_piece)
            ),
        )
        .with_value(to_f64(max_piece))
        .with_interval(0.0, std::f64::consts::PI));
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
        )
        .with_value(ratio)
        .with_interval(1.0, MAX_ARC_PIECES as f64));
    }
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let pieces = ratio as usize;
    Ok(pieces)
}

pub(super) fn is_full_turn<T: Scalar>(sweep: T) -> bool {
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
