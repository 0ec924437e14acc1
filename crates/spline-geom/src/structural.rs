//! Structural algorithms: knot insertion and refinement, exact knot removal, degree
//! elevation, the derivative, clamping, restriction and splitting, reversal and
//! reparametrisation. Each changes the representation, not the curve (the derivative
//! excepted), and each is written once, generic over the point type: on control points it
//! is the fast path, on [`spline_core::SymbolicPoint`]s it yields the operation's sparse
//! matrix (spline-algebra's `SplineMap` is built that way), so the two cannot disagree.
//! The target knot vectors come from the rules of [`KnotVector`] in spline-core.

use crate::bspline::BSpline;
use crate::transfer::reduce_points;
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, VectorSpace, binomial, from_count,
    to_f64,
};
use std::borrow::Cow;

/// The default relative tolerance of [`BSpline::remove_knot`]: `1e-9` times the size of the
/// control polygon.
pub const DEFAULT_REMOVAL_TOLERANCE: f64 = 1e-9;

/// The Bernstein degree elevation by `times` of segments of degree `p`:
/// $Q_i = \sum_j \binom{p}{j}\binom{t}{i-j} / \binom{p+t}{i}\ P_j$, weights computed once.
pub(crate) struct BernsteinElevation<T> {
    times: usize,
    /// The weights of row `i` (those of `P_j` for `j = max(0, i − t) … min(p, i)`) are
    /// `weights[starts[i]..starts[i + 1]]`.
    weights: Vec<T>,
    starts: Vec<usize>,
}

impl<T: Scalar> BernsteinElevation<T> {
    pub(crate) fn new(p: usize, times: usize) -> Self {
        let ph = p + times;
        let mut weights = Vec::new();
        let mut starts = Vec::with_capacity(ph + 2);
        for i in 0..=ph {
            starts.push(weights.len());
            let inv = T::one() / binomial::<T>(ph, i);
            weights.extend(
                (i.saturating_sub(times)..=p.min(i))
                    .map(|j| inv * binomial::<T>(p, j) * binomial::<T>(times, i - j)),
            );
        }
        starts.push(weights.len());
        Self {
            times,
            weights,
            starts,
        }
    }

    /// Writes the `p + t + 1` elevated control points of one segment into `out` (of that
    /// length).
    pub(crate) fn apply<V: VectorSpace<T>>(&self, points: &[V], out: &mut [V]) {
        for ((i, slot), range) in out.iter_mut().enumerate().zip(self.starts.windows(2)) {
            let first = i.saturating_sub(self.times);
            let mut acc = V::zero_vector();
            for (point, &w) in points[first..]
                .iter()
                .zip(&self.weights[range[0]..range[1]])
            {
                acc.add_scaled(point, w);
            }
            *slot = acc;
        }
    }
}

/// The differences $Q_i = \frac{p}{u_{i+p+1} - u_{i+1}} (P_{i+1} - P_i)$ of the first
/// derivative, for the rows that [`KnotVector::derivative_row_kept`] keeps.
fn differences<T: Scalar, V: VectorSpace<T>>(knots: &KnotVector<T>, points: &[V]) -> Vec<V> {
    let p = knots.degree();
    let t = knots.knots();
    let pt = from_count::<T>(p);
    (0..points.len() - 1)
        .filter(|&i| knots.derivative_row_kept(i))
        .map(|i| {
            let s = pt / (t[i + p + 1] - t[i + 1]);
            points[i + 1].combine(s, &points[i], -s)
        })
        .collect()
}

impl<T: Scalar, V: VectorSpace<T>> BSpline<T, V> {
    /// The spline with the sorted knots `x` inserted (A5.4), no checks.
    fn refined_unchecked(&self, x: &[T]) -> Self {
        // Room for the new knots and points from the start (no reallocation in the
        // refinement).
        let mut knots = Vec::with_capacity(self.knots().len() + x.len());
        knots.extend_from_slice(self.knots().knots());
        let mut points = Vec::with_capacity(self.len() + x.len());
        points.extend_from_slice(self.control_points());
        let mut curve =
            Self::new_unchecked(KnotVector::new_unchecked(self.degree(), knots), points);
        curve.refine_sorted_unchecked(x);
        curve
    }

    /// The spline on a space contained in this one (see [`BSpline::reduced`]), no checks.
    fn reduced_unchecked(&self, target: &KnotVector<T>) -> Self {
        Self::new_unchecked(
            target.clone(),
            reduce_points(self.knots(), target, self.control_points()),
        )
    }

    /// Inserts every value of `breaks` (sorted, in the domain) up to multiplicity `p + 1`
    /// and returns the refined spline with, for each break, the index of the first of its
    /// `p + 1` knots: the pieces between breaks are then slices.
    fn cut_at(&self, breaks: &[T]) -> (Self, Vec<usize>) {
        let p = self.degree();
        let mut x = Vec::with_capacity(breaks.len() * (p + 1));
        for &u in breaks {
            let missing = (p + 1).saturating_sub(self.knots().multiplicity(u));
            x.extend(std::iter::repeat_n(u, missing));
        }
        let full = self.refined_unchecked(&x);
        let firsts = breaks
            .iter()
            .map(|&u| full.knots().knots().partition_point(|&k| k < u))
            .collect();
        (full, firsts)
    }

    /// The piece between the breaks whose first knots are at `from` and `to` of a spline
    /// cut there ([`BSpline::cut_at`]), clamped at both ends.
    fn slice(&self, from: usize, to: usize) -> Self {
        let p = self.degree();
        Self::new_unchecked(
            KnotVector::new_unchecked(p, self.knots().knots()[from..=to + p].to_vec()),
            self.control_points()[from..to].to_vec(),
        )
    }

    /// The same spline on another knot vector of the same degree that contains this space
    /// on its domain (a refinement, the clamped form, a restriction, a finer Bernstein
    /// space, an unclamped form): restriction to the target domain, refinement, and for
    /// unclamped targets the exact transfer of [`BSpline::reduced`].
    ///
    /// # Errors
    /// [`ErrorKind::SpaceMismatch`] unless `target` contains the space on its domain
    /// ([`KnotVector::check_contained_in`]).
    pub fn transferred(&self, target: &KnotVector<T>) -> Result<Self> {
        self.knots().check_contained_in(target, "transfer")?;
        if target == self.knots() {
            return Ok(self.clone());
        }
        let (a, b) = target.domain();
        let (cut, firsts) = self.cut_at(&[a, b]);
        let restricted = cut.slice(firsts[0], firsts[1]);
        let clamped = target.to_clamped();
        let mut missing = Vec::new();
        for (k, m) in clamped.interior_breakpoints() {
            let have = restricted.knots().multiplicity(k);
            missing.extend(std::iter::repeat_n(k, m.saturating_sub(have)));
        }
        let refined = restricted.refined_unchecked(&missing);
        debug_assert_eq!(refined.knots(), &clamped);
        Ok(if &clamped == target {
            refined
        } else {
            refined.reduced_unchecked(target)
        })
    }

    /// Inserts the knot `u` `times` times without changing the curve (seed 000 Algorithm 3,
    /// seed 004 (8.4)–(8.5); a refinement by `times` copies of `u`).
    ///
    /// ```
    /// use spline_geom::BSpline;
    /// let f = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 1.0, 0.0])?;
    /// let g = f.insert_knot(0.5, 1)?;
    /// assert_eq!(g.control_points(), &[0.0, 0.5, 0.5, 0.0]);
    /// let (a, b): (f64, f64) = (g.eval(0.3)?, f.eval(0.3)?);
    /// assert!((a - b).abs() < 1e-15);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]/[`ErrorKind::OutOfDomain`] for `u`;
    /// [`ErrorKind::KnotMultiplicity`] if `u` would appear more than `p + 1` times.
    pub fn insert_knot(&self, u: T, times: usize) -> Result<Self> {
        let mut curve = self.clone();
        curve.insert_knot_mut(u, times)?;
        Ok(curve)
    }

    /// [`BSpline::insert_knot`] in place: the knots and control points grow by `times`
    /// entries (amortised, no new allocation per call) and `p` points change. Inserting many
    /// knots one at a time this way costs a shift of the tail per knot.
    ///
    /// ```
    /// use spline_geom::BSpline;
    /// let mut f = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 1.0, 0.0])?;
    /// f.insert_knot_mut(0.5, 1)?;
    /// assert_eq!(f.control_points(), &[0.0, 0.5, 0.5, 0.0]);
    /// assert!(f.insert_knot_mut(0.5, 3).is_err()); // multiplicity 4 > p + 1: unchanged
    /// assert_eq!(f.len(), 4);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSpline::insert_knot`]; the curve is unchanged on error.
    pub fn insert_knot_mut(&mut self, u: T, times: usize) -> Result<()> {
        let span = self.knots().insertion_span(u, times)?;
        let x = [u; spline_core::MAX_ORDER];
        self.insert_unchecked(span, &x[..times]);
        Ok(())
    }

    /// Inserts many knots at once (knot refinement, The NURBS Book A5.4), in `O(n + r p)`.
    /// The knots may come in any order and repeat.
    ///
    /// # Errors
    /// As [`BSpline::insert_knot`] for each knot, checked before anything is computed.
    pub fn refine(&self, new_knots: &[T]) -> Result<Self> {
        let x = self.checked_refinement(new_knots)?;
        Ok(self.refined_unchecked(&x))
    }

    /// [`BSpline::refine`] in place (sorted knots need no copy of them).
    ///
    /// # Errors
    /// As [`BSpline::refine`]; the curve is unchanged on error.
    pub fn refine_mut(&mut self, new_knots: &[T]) -> Result<()> {
        let x = self.checked_refinement(new_knots)?;
        self.refine_sorted_unchecked(&x);
        Ok(())
    }

    /// The new knots in increasing order (borrowed when they already are), after the checks
    /// of [`BSpline::refine`].
    fn checked_refinement<'a>(&self, new_knots: &'a [T]) -> Result<Cow<'a, [T]>> {
        self.knots().check_new_knots(new_knots)?;
        let x = if new_knots.is_sorted_by(|a, b| a <= b) {
            Cow::Borrowed(new_knots)
        } else {
            // Finite after the checks: no NaN to order.
            let mut x = new_knots.to_vec();
            x.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
            Cow::Owned(x)
        };
        self.knots().check_refinement(&x)?;
        Ok(x)
    }

    /// The spline on a *subspace* (same degree and domain, every knot at most as often as
    /// here): exact for splines that lie in it, a local quasi-interpolant otherwise. Each
    /// coefficient is the blossom of one polynomial piece at the target knots, on the piece
    /// where the blossom extrapolates least — no tolerance, no sequential removal.
    ///
    /// ```
    /// use spline_core::KnotVector;
    /// use spline_geom::BSpline;
    /// let coarse = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 2.0])?;
    /// let f = BSpline::new(coarse.clone(), vec![1.0, -2.0, 0.5, 3.0, 1.0])?;
    /// let back = f.refine(&[0.5, 1.0, 1.5])?.reduced(&coarse)?;
    /// assert!(back.control_points().iter().zip(f.control_points()).all(|(a, b): (&f64, &f64)| (a - b).abs() < 1e-14));
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::SpaceMismatch`] unless `target` is such a subspace.
    pub fn reduced(&self, target: &KnotVector<T>) -> Result<Self> {
        target.check_contained_in(self.knots(), "knot removal")?;
        if target.domain() != self.domain() {
            return Err(Error::new(
                ErrorKind::SpaceMismatch,
                "knot removal needs the same domain",
            ));
        }
        Ok(self.reduced_unchecked(target))
    }

    /// The coefficients of the Bézier segments one after the other: the same spline on the
    /// per-segment Bernstein space [`KnotVector::bezier_space`] (Bézier extraction by
    /// refinement, segment `k` owning coefficients `(p + 1) k … (p + 1) k + p`).
    #[must_use]
    pub fn to_bernstein(&self) -> Self {
        let p = self.degree();
        let (a, b) = self.domain();
        let breaks = self.knots().domain_breaks();
        let mut x = Vec::with_capacity(breaks.len() * (p + 1));
        for (u, m) in self.knots().breakpoints() {
            // Ends up to p + 1 copies, interior breaks up to p: neighbours share a point.
            let wanted = if u == a || u == b {
                p + 1
            } else if u > a && u < b {
                p
            } else {
                0
            };
            x.extend(std::iter::repeat_n(u, wanted.saturating_sub(m)));
        }
        let full = self.refined_unchecked(&x);
        let knots = full.knots().knots();
        let mut points = Vec::with_capacity((breaks.len() - 1) * (p + 1));
        // The segment starting at a break begins p before the last copy of the break.
        let mut last = 0;
        for &u in &breaks[..breaks.len() - 1] {
            while knots[last + 1] <= u {
                last += 1;
            }
            let first = last - p;
            points.extend_from_slice(&full.control_points()[first..=first + p]);
        }
        Self::new_unchecked(self.knots().bezier_space(), points)
    }

    /// Raises the degree by `times` (every distinct knot's multiplicity rises by exactly
    /// `times`), exactly: Bézier extraction ([`BSpline::to_bernstein`]), Bernstein
    /// elevation of each segment, then the blossoms of the elevated pieces at the knots of
    /// the elevated space ([`BSpline::reduced`]). Unlike The NURBS Book A5.9 it never
    /// divides by differences of close knots, so high degrees with nearly equal knots stay
    /// exact. An unclamped curve comes back clamped at its domain ends.
    ///
    /// ```
    /// use spline_geom::BSpline;
    /// let f = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 1.0, 0.0])?;
    /// let g = f.elevate_degree(1)?;
    /// assert_eq!(g.knots().knots(), &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]);
    /// let (a, b): (f64, f64) = (g.eval(0.3)?, f.eval(0.3)?);
    /// assert!((a - b).abs() < 1e-15);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::DegreeTooHigh`] if `p + times` exceeds [`spline_core::MAX_DEGREE`].
    pub fn elevate_degree(&self, times: usize) -> Result<Self> {
        if times == 0 {
            return Ok(self.clone());
        }
        let target = self.knots().elevated(times)?;
        let p = self.degree();
        let pieces = self.to_bernstein();
        let weights = BernsteinElevation::new(p, times);
        let mut elevated = vec![V::zero_vector(); pieces.len() / (p + 1) * (p + times + 1)];
        for (segment, out) in pieces
            .control_points()
            .chunks_exact(p + 1)
            .zip(elevated.chunks_exact_mut(p + times + 1))
        {
            weights.apply(segment, out);
        }
        let elevated_pieces = pieces.knots().with_degree_of_pieces(p + times);
        Ok(Self::new_unchecked(
            target.clone(),
            reduce_points(&elevated_pieces, &target, &elevated),
        ))
    }

    /// The derivative of order `order` as a B-spline of degree `p − order` on the knots of
    /// [`KnotVector::derivative_knots_of_order`] (seed 000 (6)):
    /// $Q_i = \frac{p}{u_{i+p+1} - u_{i+1}} (P_{i+1} - P_i)$, applied `order` times. Where a
    /// knot of multiplicity `p + 1` (a discontinuity) makes the denominator vanish, the
    /// coefficient multiplies an identically zero basis function and is dropped with one
    /// copy of the knot, so the result is the piecewise derivative.
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] if `order > p`; [`ErrorKind::NonFinite`] when a
    /// coefficient is too large for the scalar type.
    pub fn derivative(&self, order: usize) -> Result<Self> {
        if order > self.degree() {
            return Err(Error::order_too_high(order, self.degree(), "the degree")
                .context("higher derivatives are zero"));
        }
        let mut knots = self.knots().clone();
        let mut points = self.control_points().to_vec();
        for _ in 0..order {
            points = differences(&knots, &points);
            knots = knots.derivative_knots()?;
        }
        if !points.iter().all(VectorSpace::is_finite_vector) {
            return Err(spline_core::overflow(format_args!(
                "a control point of the derivative of order {order}"
            )));
        }
        Ok(Self::new_unchecked(knots, points))
    }

    /// The curve on the same domain with clamped knots (`p + 1` copies of each domain end),
    /// so that it interpolates its first and last control points. Clamped curves are
    /// returned unchanged.
    #[must_use]
    pub fn clamped(&self) -> Self {
        if self.knots().is_clamped() {
            return self.clone();
        }
        let (a, b) = self.domain();
        let (cut, firsts) = self.cut_at(&[a, b]);
        cut.slice(firsts[0], firsts[1])
    }

    /// The curve restricted to `[a, b]` inside the domain, clamped there.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::OutOfDomain`] unless `a < b` lie in the domain.
    pub fn restricted(&self, a: T, b: T) -> Result<Self> {
        let target = self.knots().restricted(a, b)?;
        let (cut, firsts) = self.cut_at(&[a, b]);
        let piece = cut.slice(firsts[0], firsts[1]);
        debug_assert_eq!(piece.knots(), &target);
        Ok(piece)
    }

    /// Splits the curve at `u` (seed 000 FIG. 5; seed 004 (8.6)–(8.7)) into two curves, both
    /// clamped at `u` (`p + 1` copies of `u`), whose domains are `[a, u]` and `[u, b]`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::OutOfDomain`] unless `a < u < b`.
    pub fn split(&self, u: T) -> Result<(Self, Self)> {
        self.knots().split_at(u)?;
        let (a, b) = self.domain();
        let (cut, firsts) = self.cut_at(&[a, u, b]);
        Ok((
            cut.slice(firsts[0], firsts[1]),
            cut.slice(firsts[1], firsts[2]),
        ))
    }

    /// The same curve traversed backwards on the same domain: $\tilde C(u) = C(a + b - u)$.
    #[must_use]
    pub fn reversed(&self) -> Self {
        let mut points = self.control_points().to_vec();
        points.reverse();
        Self::new_unchecked(self.knots().reversed(), points)
    }

    /// The same curve on the domain `[a, b]` (affine change of parameter).
    ///
    /// # Errors
    /// [`ErrorKind::EmptyDomain`] unless `a < b`; [`ErrorKind::NonFinite`].
    pub fn reparametrized(&self, a: T, b: T) -> Result<Self> {
        Ok(Self::new_unchecked(
            self.knots().reparametrized(a, b)?,
            self.control_points().to_vec(),
        ))
    }
}

impl<T: Scalar, P: ControlPoint<T>> BSpline<T, P> {
    /// Removes the interior knot `u` `times` times if the curve moves by at most
    /// `tolerance` (absolute; see [`BSpline::remove_knot`] for the relative default).
    ///
    /// The new control points are those of the exact removal ([`BSpline::reduced`]); the
    /// result is then checked exactly: re-inserting the knots gives control points whose
    /// largest distance to the original ones bounds the change of the curve (partition of
    /// unity).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] if `u` is not an interior knot or is repeated fewer
    /// than `times` times; [`ErrorKind::InvalidTolerance`] if `tolerance` is negative or
    /// NaN; [`ErrorKind::ToleranceExceeded`] (the message gives the deviation) if the curve
    /// would move more than `tolerance`.
    pub fn remove_knot_within(&self, u: T, times: usize, tolerance: T) -> Result<Self> {
        checked_removal(self, u, times, tolerance, |a: &P, b: &P| (*a - *b).length())
    }

    /// Removes the interior knot `u` `times` times if the curve moves by at most
    /// `relative_tolerance` times the size of the control polygon (its largest coordinate
    /// magnitude, or 1 if that is smaller). [`DEFAULT_REMOVAL_TOLERANCE`] is the usual choice.
    ///
    /// ```
    /// use spline_geom::BSpline;
    /// let f = BSpline::from_knots(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
    ///     vec![0.0, 2.0, -1.0, 1.0])?;
    /// let g = f.insert_knot(0.25, 2)?;
    /// let back = g.remove_knot(0.25, 2, 1e-9)?;
    /// assert!(back.control_points().iter().zip(f.control_points()).all(|(a, b): (&f64, &f64)| (a - b).abs() < 1e-12));
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSpline::remove_knot_within`].
    pub fn remove_knot(&self, u: T, times: usize, relative_tolerance: T) -> Result<Self> {
        let scale = relative_scale(self.control_points().iter().map(ControlPoint::max_abs));
        self.remove_knot_within(u, times, relative_tolerance * scale)
    }
}

/// Knot removal within an absolute tolerance, for any point type with a `distance`: the
/// exact removal ([`BSpline::reduced`]), checked by re-inserting the knots — the largest
/// distance between the original and the re-inserted control points bounds the change of
/// the curve (partition of unity).
///
/// # Errors
/// As [`BSpline::remove_knot_within`].
pub(crate) fn checked_removal<T: Scalar, V: VectorSpace<T>>(
    curve: &BSpline<T, V>,
    u: T,
    times: usize,
    tolerance: T,
    distance: impl Fn(&V, &V) -> T,
) -> Result<BSpline<T, V>> {
    check_tolerance(tolerance)?;
    let target = curve.knots().removed(u, times)?;
    let removed = curve.reduced(&target)?;
    let back = removed.insert_knot(u, times)?;
    let deviation = back
        .control_points()
        .iter()
        .zip(curve.control_points())
        .fold(T::zero(), |m, (x, y)| m.max(distance(x, y)));
    if deviation <= tolerance {
        Ok(removed)
    } else {
        Err(tolerance_exceeded(u, times, Some(deviation), tolerance))
    }
}

/// The scale that turns a relative removal tolerance into an absolute one: the largest of
/// the control points' coordinate magnitudes, or 1 if that is smaller.
pub(crate) fn relative_scale<T: Scalar>(magnitudes: impl IntoIterator<Item = T>) -> T {
    magnitudes.into_iter().fold(T::one(), T::max)
}

/// [`ErrorKind::InvalidTolerance`] unless the tolerance is non-negative.
pub(crate) fn check_tolerance<T: Scalar>(tolerance: T) -> Result<()> {
    if tolerance >= T::zero() {
        Ok(())
    } else {
        Err(Error::invalid_tolerance(
            "tolerance",
            "non-negative",
            to_f64(tolerance),
        ))
    }
}

/// [`ErrorKind::ToleranceExceeded`] for a removal that moves the shape by `bound` (`None`:
/// it would make a weight non-positive).
pub(crate) fn tolerance_exceeded<T: Scalar>(
    u: T,
    times: usize,
    bound: Option<T>,
    tolerance: T,
) -> Error {
    let what = match bound {
        Some(b) => format!("by up to {:.3e}", to_f64(b)),
        None => "and make a weight non-positive".to_owned(),
    };
    let mut e = Error::new(
        ErrorKind::ToleranceExceeded,
        format!(
            "removing knot {} {times} time(s) would move the shape {what}, more than the tolerance {:.3e}",
            to_f64(u),
            to_f64(tolerance)
        ),
    );
    if let Some(b) = bound {
        e = e.with_value(to_f64(b));
    }
    e
}
