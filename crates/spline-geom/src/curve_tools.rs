//! Tools on any [`ParamCurve`]: bounding boxes of the control hull and of the Bézier
//! pieces, adaptive tessellation by chord tolerance, the parameter at a given arc length;
//! and joining B-spline curves.

use crate::arclength::adaptive_length;
use crate::bezier::Bezier;
use crate::bspline::BSpline;
use crate::param::ParamCurve;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, lerp, to_f64};

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
///
/// # Panics
/// Never: every curve container has at least one control point.
pub fn hull_box<T: Scalar, C: ParamCurve<T> + ?Sized>(curve: &C) -> BoundingBox<C::Point> {
    BoundingBox::of_points(curve.control_polygon()).expect("a curve has at least one control point")
}

/// The box of the Bézier pieces' control points: inside [`hull_box`], still containing the
/// curve (it is the box of the refined control polygon).
///
/// # Panics
/// Never: every curve container has at least one piece.
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
                    )
                    .with_value(to_f64(tolerance)));
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
fn flat<T: Scalar, C: ParamCurve<T> + ?Sized>(
    coefficients: &[C::Coefficient],
    tolerance: T,
) -> bool {
    let points: Vec<C::Point> = coefficients.iter().map(C::project).collect();
    let (a, b) = (points[0], points[points.len() - 1]);
    points
        .iter()
        .all(|q| distance_to_segment(q, &a, &b) <= tolerance)
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
/// the relative accuracy `accuracy` (a fraction of the curve's length;
/// [`ArcLengthTable::param_at`]).
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
/// As [`ArcLengthTable::new`] and [`ArcLengthTable::param_at`].
pub fn param_at_length<T: Scalar, C: ParamCurve<T> + ?Sized>(
    curve: &C,
    length: T,
    accuracy: T,
) -> Result<T> {
    ArcLengthTable::new(curve, accuracy)?.param_at(length)
}

/// The arc length $s(u) = \int_a^u \lVert C' \rVert$ of a curve at its breaks, for fast
/// inversion: [`ArcLengthTable::param_at`] finds the piece by bisection of the table, then
/// solves $s(u) = s$ inside it by Newton's method safeguarded by bisection (the speed is
/// smooth inside a piece).
pub struct ArcLengthTable<'a, T, C: ?Sized> {
    curve: &'a C,
    breaks: Vec<T>,
    cumulative: Vec<T>,
    /// Where pieces are cut around near-stops of the speed (sorted).
    stops: Vec<T>,
    /// The relative accuracy given.
    accuracy: T,
    /// The absolute accuracy in length it means for this curve (`accuracy` times the
    /// length).
    absolute: T,
}

impl<'a, T: Scalar, C: ParamCurve<T> + ?Sized> ArcLengthTable<'a, T, C> {
    /// The table of `curve` for lengths to the relative `accuracy` (a fraction of the
    /// curve's length, [`crate::DEFAULT_ACCURACY`] a good choice: scale-invariant, and each
    /// piece's quadrature asks only its own fraction, whatever the number of pieces).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidTolerance`] unless the accuracy is positive and finite; the errors
    /// of [`ParamCurve::arc_length_between`].
    pub fn new(curve: &'a C, accuracy: T) -> Result<Self> {
        if !(accuracy > T::zero() && accuracy.is_finite()) {
            return Err(Error::invalid_tolerance(
                "accuracy",
                "positive and finite",
                to_f64(accuracy),
            ));
        }
        let breaks = curve.breaks();
        let quadrature = accuracy * cast(0.1);
        let mut cumulative = Vec::with_capacity(breaks.len());
        cumulative.push(T::zero());
        // Each piece's quadrature on its own bounds: `arc_length_between` would list the
        // curve's breaks again for every piece, quadratic in their number (issue 25: 10⁵
        // control points took minutes).
        let speed = |u: T| {
            let mut d = [C::Point::origin(); 2];
            curve
                .derivatives_into(u, &mut d)
                .map_or(T::zero(), |()| d[1].length())
        };
        // Each piece cut around its near-stops (the cuts kept for the lengths inside pieces
        // that `param_at` measures); a rational piece whose weights are far apart measured in
        // its own parameter. (The pieces are the intervals between the breaks.)
        let point_dim = <C::Point as ControlPoint<T>>::DIM;
        let pieces = curve.bezier_pieces();
        let aligned = pieces.len() + 1 == breaks.len();
        let mut stops = Vec::new();
        for (k, w) in breaks.windows(2).enumerate() {
            let last = cumulative[cumulative.len() - 1];
            let length = match aligned.then(|| &pieces[k]) {
                Some((_, _, q)) if crate::arclength::far_apart(q, point_dim) => {
                    crate::arclength::length_by_pieces(
                        &pieces[k..=k],
                        point_dim,
                        (w[0], w[1]),
                        quadrature,
                        speed,
                    )?
                }
                Some((lo, hi, q)) => {
                    let first = stops.len();
                    crate::arclength::stop_cuts(q, point_dim, (*lo, *hi), &mut stops);
                    let mut ends = vec![w[0]];
                    ends.extend(
                        stops[first..]
                            .iter()
                            .copied()
                            .filter(|&u| u > w[0] && u < w[1]),
                    );
                    ends.push(w[1]);
                    adaptive_length(&ends, quadrature, speed)?
                }
                None => adaptive_length(w, quadrature, speed)?,
            };
            cumulative.push(last + length);
        }
        let absolute = accuracy * cumulative[cumulative.len() - 1];
        Ok(Self {
            curve,
            breaks,
            cumulative,
            stops,
            accuracy,
            absolute,
        })
    }

    /// The length of the whole curve.
    #[must_use]
    pub fn total(&self) -> T {
        self.cumulative[self.cumulative.len() - 1]
    }

    /// The arc lengths at the breaks of the curve (the first is 0).
    #[must_use]
    pub fn at_breaks(&self) -> &[T] {
        &self.cumulative
    }

    /// The parameters at the non-decreasing arc lengths `lengths`: each one solved from the
    /// previous one inside the same piece (short integrals), far cheaper than
    /// [`Self::param_at`] for many values.
    ///
    /// # Errors
    /// As [`Self::param_at`]; [`ErrorKind::UnsortedKnots`] for decreasing lengths.
    pub fn params_at(&self, lengths: &[T]) -> Result<Vec<T>> {
        let mut out = Vec::with_capacity(lengths.len());
        // (piece, length, parameter) of the previous solution.
        // (piece, asked length, measured length, parameter) of the previous solution.
        let mut previous: Option<(usize, T, T, T)> = None;
        for (j, &s) in lengths.iter().enumerate() {
            let s = self.clamp_length(s)?;
            let k = self.piece_of(s);
            let (s0, u0) = match previous {
                Some((_, asked, _, _)) if s < asked => {
                    return Err(Error::new(
                        ErrorKind::UnsortedKnots,
                        format!("arc lengths must not decrease (entry {j})"),
                    ));
                }
                Some((pk, _, measured, pu)) if pk == k && s >= measured => (measured, pu),
                _ => (self.cumulative[k], self.breaks[k]),
            };
            let (u, measured) = self.solve_in_piece(k, s0, u0, s)?;
            previous = Some((k, s, measured, u));
            out.push(u);
        }
        Ok(out)
    }

    /// The length itself, or the end it is within the accuracy of.
    fn clamp_length(&self, s: T) -> Result<T> {
        let total = self.total();
        // Lengths within the accuracy of an end are that end (two quadratures of the same
        // length differ by rounding).
        let s = if s > total && s <= total + self.absolute {
            total
        } else if s < T::zero() && s >= -self.absolute {
            T::zero()
        } else {
            s
        };
        if s >= T::zero() && s <= total {
            Ok(s)
        } else {
            Err(Error::out_of_domain(to_f64(s), (0.0, to_f64(total))).context("arc length"))
        }
    }

    /// The piece `k` with `cumulative[k] ≤ s ≤ cumulative[k + 1]`.
    fn piece_of(&self, s: T) -> usize {
        self.cumulative
            .partition_point(|&c| c <= s)
            .clamp(1, self.breaks.len() - 1)
            - 1
    }

    /// $\int_x^y \lVert C' \rVert$ for `x ≤ y` inside one piece (no break between them).
    fn length_inside(&self, x: T, y: T) -> Result<T> {
        let from = self.stops.partition_point(|&u| u <= x);
        let to = self.stops.partition_point(|&u| u < y);
        let mut ends = vec![x];
        ends.extend_from_slice(&self.stops[from..to.max(from)]);
        ends.push(y);
        adaptive_length(&ends, self.accuracy * cast(0.1), |u| {
            let mut d = [C::Point::origin(); 2];
            self.curve
                .derivatives_into(u, &mut d)
                .map_or(T::zero(), |()| d[1].length())
        })
    }

    /// Solves $s(u) = s$ in piece `k` from a known point $(u_0, s_0)$ of it (`s ≥ s_0`):
    /// Newton's method safeguarded by bisection, every length measured from $u_0$ (one
    /// integral each, no accumulation). Returns `u` and its measured length.
    fn solve_in_piece(&self, k: usize, s0: T, u0: T, s: T) -> Result<(T, T)> {
        let (mut lo, mut hi) = (u0, self.breaks[k + 1]);
        let s1 = self.cumulative[k + 1];
        if !(s1 > s0) || s <= s0 {
            return Ok((u0, s0));
        }
        // The first guess: one Newton step from u0 (close when u0 is the previous solution).
        let speed0 = self.curve.speed(u0)?;
        let step = (s - s0) / speed0;
        let mut u = if speed0 > T::zero() && u0 + step < hi {
            u0 + step
        } else {
            lo + (hi - lo) * ((s - s0) / (s1 - s0)).min(T::one())
        };
        let mut best = (u0, s0);
        for _ in 0..200 {
            let su = s0 + self.length_inside(u0, u)?;
            let f = su - s;
            if f.abs() < (best.1 - s).abs() {
                best = (u, su);
            }
            if f.abs() <= self.absolute {
                return Ok((u, su));
            }
            if f > T::zero() {
                hi = u;
            } else {
                lo = u;
            }
            let speed = self.curve.speed(u)?;
            let newton = u - f / speed;
            u = if speed > T::zero() && newton > lo && newton < hi {
                newton
            } else {
                (lo + hi) * cast(0.5)
            };
            if !(hi > lo) || (hi - lo) <= hi.abs().max(lo.abs()) * cast(4.0 * f64::EPSILON) {
                // The bracket is at the resolution of the parameter: the best there is.
                return Ok(best);
            }
        }
        Err(Error::new(
            ErrorKind::NoConvergence,
            format!("no parameter found at arc length {}", to_f64(s)),
        ))
    }

    /// The parameter at arc length `s` from the start, to the table's accuracy.
    ///
    /// # Errors
    /// [`ErrorKind::OutOfDomain`] unless `0 ≤ s ≤` [`Self::total`] (to the accuracy);
    /// [`ErrorKind::NoConvergence`] if the inversion fails.
    pub fn param_at(&self, s: T) -> Result<T> {
        let s = self.clamp_length(s)?;
        let k = self.piece_of(s);
        Ok(self
            .solve_in_piece(k, self.cumulative[k], self.breaks[k], s)?
            .0)
    }
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
