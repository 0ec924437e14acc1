//! The knot-vector rules of every structural operation, in one place: the target space of
//! knot insertion and refinement, knot removal, degree elevation, the derivative, clamping,
//! restriction to a sub-interval and splitting, Bézier extraction, merging, reversal and
//! reparametrisation. The algorithms of spline-geom (and the sparse maps of
//! spline-algebra, which run the same algorithms on symbolic points) take their target
//! knot vectors from here and nowhere else.

use super::{KnotVector, check_elevated_degree, check_interval};
use crate::Short;
use crate::error::{Error, ErrorKind, Result};
use crate::scalar::{Scalar, to_f64};

impl<T: Scalar> KnotVector<T> {
    /// The knot vector with `u` inserted `times` times.
    ///
    /// ```
    /// let k = spline_core::KnotVector::bezier(2, 0.0, 1.0)?;
    /// assert_eq!(k.with_inserted(0.5, 2)?.knots(), &[0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::OutOfDomain`] outside the domain; [`ErrorKind::KnotMultiplicity`] if the
    /// multiplicity would exceed `p + 1`.
    pub fn with_inserted(&self, u: T, times: usize) -> Result<Self> {
        self.check_insertion(u, times)?;
        let at = self.knots().partition_point(|&k| k <= u);
        let mut knots = Vec::with_capacity(self.len() + times);
        knots.extend_from_slice(&self.knots()[..at]);
        knots.extend(std::iter::repeat_n(u, times));
        knots.extend_from_slice(&self.knots()[at..]);
        Self::new(self.degree(), knots)
    }

    /// Checks that `u` can be inserted `times` times (the errors of
    /// [`KnotVector::with_inserted`]) without building the new knot vector: one binary
    /// search, no allocation.
    ///
    /// # Errors
    /// As [`KnotVector::with_inserted`].
    pub fn check_insertion(&self, u: T, times: usize) -> Result<()> {
        self.insertion_span(u, times).map(|_| ())
    }

    /// [`KnotVector::check_insertion`], returning the span of `u`
    /// ([`KnotVector::span_in_domain`]) that the insertion changes: one binary search, the
    /// multiplicity of `u` counted next to it.
    ///
    /// ```
    /// let k = spline_core::KnotVector::new(2, vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0])?;
    /// assert_eq!(k.insertion_span(0.25, 1)?, 2);
    /// assert_eq!(k.insertion_span(0.5, 1)?, 4);
    /// assert!(k.insertion_span(0.5, 2).is_err()); // multiplicity 4 > p + 1
    /// assert!(k.insertion_span(1.5, 1).is_err());
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`KnotVector::with_inserted`].
    pub fn insertion_span(&self, u: T, times: usize) -> Result<usize> {
        self.check_param(u)?;
        let span = self.span_in_domain(u);
        let knots = self.knots();
        // Copies of u end at the span's left knot (u inside the domain) or start right
        // after the span (u at the domain's end).
        let below = knots[..=span].iter().rev().take_while(|&&k| k == u).count();
        let above = knots[span + 1..].iter().take_while(|&&k| k == u).count();
        let present = below + above;
        let room = self.order() - present.min(self.order());
        if times > room {
            return Err(Error::new(
                ErrorKind::KnotMultiplicity,
                format!(
                    "knot {} appears {present} time(s) and a degree-{} spline allows at most {}: it can be inserted at most {room} more times, not {times}",
                    to_f64(u),
                    self.degree(),
                    self.order(),
                ),
            )
            .with_value(to_f64(u))
            .with_counts(room, times));
        }
        Ok(span)
    }

    /// The knot vector with all of `new_knots` inserted (knot refinement; any order,
    /// repetitions allowed).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for a knot (named by its index);
    /// [`ErrorKind::KnotMultiplicity`] if a multiplicity would exceed `p + 1`.
    pub fn refined(&self, new_knots: &[T]) -> Result<Self> {
        self.check_new_knots(new_knots)?;
        let mut sorted = new_knots.to_vec();
        sorted.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        self.check_refinement(&sorted)?;
        let mut all = Vec::with_capacity(self.len() + new_knots.len());
        all.extend_from_slice(self.knots());
        all.extend_from_slice(&sorted);
        all.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        Ok(Self::new_unchecked(self.degree(), all))
    }

    /// Checks that every one of `new_knots` is a finite parameter of the domain (the first
    /// error of [`KnotVector::refined`], naming the knot by its index).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn check_new_knots(&self, new_knots: &[T]) -> Result<()> {
        // One comparison pair per knot (false for NaN); the messages come from the slow path.
        let (a, b) = self.domain();
        // Branch-free over chunks (it vectorises).
        let inside = |chunk: &[T]| chunk.iter().fold(true, |ok, &u| ok & (u >= a) & (u <= b));
        if new_knots.chunks(256).all(inside) {
            return Ok(());
        }
        for (j, &u) in new_knots.iter().enumerate() {
            self.check_param(u)
                .map_err(|e| e.with_index(j).context(format_args!("knot {j}")))?;
        }
        Ok(())
    }

    /// Checks that inserting the *sorted* knots `sorted` (already checked to lie in the
    /// domain) leaves every multiplicity at most `p + 1`: one merge, no allocation.
    ///
    /// # Errors
    /// [`ErrorKind::KnotMultiplicity`] naming the first knot that would appear too often.
    pub fn check_refinement(&self, sorted: &[T]) -> Result<()> {
        let order = self.order();
        let old = self.knots();
        // The usual case without a walk: distinct new knots, and no old knot of full
        // multiplicity p + 1 between the first and the last of them.
        if let (Some(&first), Some(&last)) = (sorted.first(), sorted.last()) {
            let distinct = sorted
                .windows(2)
                .fold(true, |ok, pair| ok & (pair[0] != pair[1]));
            let full_inside = old
                .windows(order)
                .any(|run| run[0] == run[order - 1] && run[0] >= first && run[0] <= last);
            if distinct && !full_inside {
                return Ok(());
            }
        }
        // Walks both sorted sequences once: `i` is the first old knot not below `u`.
        let mut i = 0;
        let mut j = 0;
        while j < sorted.len() {
            let u = sorted[j];
            let mut end = j + 1;
            while end < sorted.len() && sorted[end] == u {
                end += 1;
            }
            while i < old.len() && old[i] < u {
                i += 1;
            }
            let present = old[i..].iter().take_while(|&&k| k == u).count();
            let count = end - j + present;
            if count > order {
                return Err(Error::new(
                    ErrorKind::KnotMultiplicity,
                    format!(
                        "knot {} appears {count} times; a degree-{} spline allows at most {order}",
                        to_f64(u),
                        self.degree()
                    ),
                )
                .with_value(to_f64(u)));
            }
            j = end;
        }
        Ok(())
    }

    /// The knot vector with the interior knot `u` removed `times` times.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] if `u` is not an interior knot or appears fewer than
    /// `times` times.
    pub fn removed(&self, u: T, times: usize) -> Result<Self> {
        let (a, b) = self.domain();
        let mult = self.multiplicity(u);
        if !(u > a && u < b) || mult == 0 {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!("{} is not an interior knot of the curve", to_f64(u)),
            )
            .with_value(to_f64(u)));
        }
        if times > mult {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "knot {} appears {mult} times and cannot be removed {times} times",
                    to_f64(u)
                ),
            )
            .with_value(to_f64(u))
            .with_counts(mult, times));
        }
        let first = self.knots().partition_point(|&k| k < u);
        let mut knots = self.knots().to_vec();
        knots.drain(first..first + times);
        Ok(Self::new_unchecked(self.degree(), knots))
    }

    /// The clamped knot vector of the same space on the domain: `p + 1` copies of each end,
    /// the interior knots with their multiplicities (the knots of a clamped curve).
    #[must_use]
    pub fn to_clamped(&self) -> Self {
        if self.is_clamped() {
            return self.clone();
        }
        let (a, b) = self.domain();
        let p = self.degree();
        let mut out = Vec::with_capacity(self.len() + 2);
        out.extend(std::iter::repeat_n(a, p + 1));
        out.extend(self.knots().iter().copied().filter(|&k| k > a && k < b));
        out.extend(std::iter::repeat_n(b, p + 1));
        Self::new_unchecked(p, out)
    }

    /// The knot vector of the restriction to `[a, b]` inside the domain: clamped on
    /// `[a, b]` (`p + 1` copies of each end), with the knots strictly between `a` and `b`.
    /// Splitting at `u` gives the restrictions to `[u_p, u]` and `[u, u_n]`.
    ///
    /// ```
    /// let k = spline_core::KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0])?;
    /// assert_eq!(k.restricted(0.5, 2.0)?.knots(), &[0.5, 0.5, 0.5, 1.0, 2.0, 2.0, 2.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::OutOfDomain`] unless `a < b` both lie in the
    /// domain.
    pub fn restricted(&self, a: T, b: T) -> Result<Self> {
        self.check_param(a)?;
        self.check_param(b)?;
        if !(a < b) {
            return Err(Error::new(
                ErrorKind::OutOfDomain,
                format!(
                    "restriction to an empty interval [{}, {}]",
                    to_f64(a),
                    to_f64(b)
                ),
            )
            .with_interval(to_f64(a), to_f64(b)));
        }
        let p = self.degree();
        let mut out = Vec::with_capacity(self.len() + 2 * p + 2);
        out.extend(std::iter::repeat_n(a, p + 1));
        out.extend(self.knots().iter().copied().filter(|&k| k > a && k < b));
        out.extend(std::iter::repeat_n(b, p + 1));
        Self::new(p, out)
    }

    /// The knot vectors of the two halves of a split at `u`, strictly inside the domain:
    /// the restrictions to `[u_p, u]` and `[u, u_n]`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::OutOfDomain`] unless `u` lies strictly inside
    /// the domain.
    pub fn split_at(&self, u: T) -> Result<(Self, Self)> {
        self.check_param(u)?;
        let (a, b) = self.domain();
        if !(u > a && u < b) {
            return Err(Error::new(
                ErrorKind::OutOfDomain,
                format!(
                    "split parameter {} must lie strictly inside the domain [{}, {}]",
                    Short(to_f64(u)),
                    Short(to_f64(a)),
                    Short(to_f64(b))
                ),
            )
            .with_value(to_f64(u))
            .with_interval(to_f64(a), to_f64(b)));
        }
        Ok((self.restricted(a, u)?, self.restricted(u, b)?))
    }

    /// The per-segment Bernstein space of degree `p` on the given breakpoints: every
    /// breakpoint repeated `p + 1` times, so that segment `k` owns coefficients
    /// `(p + 1) k … (p + 1) k + p` (the target of Bézier extraction).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] with fewer than two breakpoints;
    /// [`ErrorKind::UnsortedKnots`] unless they increase strictly; the errors of
    /// [`KnotVector::new`].
    pub fn bernstein(degree: usize, breakpoints: &[T]) -> Result<Self> {
        if breakpoints.len() < 2 {
            return Err(Error::invalid_length(
                "a piecewise Bernstein space needs at least two breakpoints",
                2,
                breakpoints.len(),
            ));
        }
        if let Some(i) = (1..breakpoints.len()).find(|&i| !(breakpoints[i] > breakpoints[i - 1])) {
            return Err(Error::new(
                ErrorKind::UnsortedKnots,
                format!("breakpoints must increase strictly (breakpoint {i})"),
            )
            .with_index(i));
        }
        let mut knots = Vec::with_capacity(breakpoints.len() * (degree + 1));
        for &x in breakpoints {
            knots.extend(std::iter::repeat_n(x, degree + 1));
        }
        Self::new(degree, knots)
    }

    /// The target of Bézier extraction: the per-segment Bernstein space
    /// ([`KnotVector::bernstein`]) on the breakpoints of the domain
    /// ([`KnotVector::domain_breaks`]), one segment per non-empty knot span.
    #[must_use]
    pub fn bezier_space(&self) -> Self {
        let breaks = self.domain_breaks();
        let p = self.degree();
        let mut knots = Vec::with_capacity(breaks.len() * (p + 1));
        for &x in &breaks {
            knots.extend(std::iter::repeat_n(x, p + 1));
        }
        Self::new_unchecked(p, knots)
    }

    /// A per-segment Bernstein space ([`KnotVector::bernstein`]) with the same breakpoints
    /// and another degree (each breakpoint repeated `degree + 1` times).
    ///
    /// # Panics
    /// In debug builds, unless this is a per-segment Bernstein space and `degree` is at most
    /// [`crate::MAX_DEGREE`].
    #[must_use]
    pub fn with_degree_of_pieces(&self, degree: usize) -> Self {
        let p = self.degree();
        let mut knots = Vec::with_capacity(self.len() / (p + 1) * (degree + 1));
        for chunk in self.knots().chunks_exact(p + 1) {
            knots.extend(std::iter::repeat_n(chunk[0], degree + 1));
        }
        Self::new_unchecked(degree, knots)
    }

    /// The union of two knot vectors of the same degree: every distinct knot with the larger
    /// of its two multiplicities.
    ///
    /// # Errors
    /// [`ErrorKind::SpaceMismatch`] if the degrees differ; the errors of
    /// [`KnotVector::new`].
    pub fn merged(&self, other: &Self) -> Result<Self> {
        if self.degree() != other.degree() {
            return Err(Error::new(
                ErrorKind::SpaceMismatch,
                format!(
                    "cannot merge knot vectors of degrees {} and {}",
                    self.degree(),
                    other.degree()
                ),
            ));
        }
        Self::new(self.degree(), merge_sorted_max(self.knots(), other.knots()))
    }

    /// The knot vector of the degree-elevated space: degree `p + times`, clamped at the
    /// domain ends ([`KnotVector::to_clamped`]), every distinct knot repeated `times` more
    /// times.
    ///
    /// ```
    /// let k = spline_core::KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0])?;
    /// assert_eq!(
    ///     k.elevated(1)?.knots(),
    ///     &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0]
    /// );
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::DegreeTooHigh`] above [`crate::MAX_DEGREE`] (checked before anything is
    /// allocated, without overflow for any `times`).
    pub fn elevated(&self, times: usize) -> Result<Self> {
        let degree = check_elevated_degree(self.degree(), times)?;
        let clamped = self.to_clamped();
        let mut knots = Vec::with_capacity(clamped.len() + times * clamped.len());
        for (k, m) in clamped.breakpoints() {
            knots.extend(std::iter::repeat_n(k, m + times));
        }
        // Valid by construction: sorted, finite, every multiplicity m + times ≤ degree + 1.
        Ok(Self::new_unchecked(degree, knots))
    }

    /// Whether basis function `i` has an empty support `[u_i, u_{i+p+1}]` (a knot of
    /// multiplicity `p + 1` inside it): it is identically zero.
    #[inline]
    #[must_use]
    pub fn is_empty_support(&self, i: usize) -> bool {
        let t = self.knots();
        !(t[i + self.degree() + 1] > t[i])
    }

    /// The knots of the derivative space (degree `p − 1`): the first and last knots
    /// dropped, and one copy of every knot of multiplicity `p + 1` inside (the derivative
    /// basis function $N_{i+1,p-1}$ of the difference $P_{i+1} - P_i$ has an empty support
    /// there and is dropped, so the derivative of a discontinuous spline is the piecewise
    /// derivative on a valid knot vector).
    ///
    /// ```
    /// let k = spline_core::KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0, 2.0, 2.0])?;
    /// assert_eq!(k.derivative_knots()?.knots(), &[0.0, 1.0, 2.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] for degree 0.
    pub fn derivative_knots(&self) -> Result<Self> {
        let p = self.degree();
        if p == 0 {
            return Err(Error::order_too_high(1, 0, "the degree"));
        }
        let t = self.knots();
        let n = self.num_basis();
        let knots = t[1..t.len() - 1]
            .iter()
            .enumerate()
            .filter(|&(i, _)| i + 1 >= n || self.derivative_row_kept(i))
            .map(|(_, &k)| k)
            .collect();
        Ok(Self::new_unchecked(p - 1, knots))
    }

    /// Whether the difference $P_{i+1} - P_i$ (`i < n − 1`) is a coefficient of the
    /// derivative ([`KnotVector::derivative_knots`]): its basis function has a non-empty
    /// support, $u_{i+p+1} > u_{i+1}$.
    #[inline]
    #[must_use]
    pub fn derivative_row_kept(&self, i: usize) -> bool {
        let t = self.knots();
        t[i + self.degree() + 1] > t[i + 1]
    }

    /// The knots of the derivative of order `order` ([`KnotVector::derivative_knots`]
    /// applied `order` times).
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] if `order` exceeds the degree.
    pub fn derivative_knots_of_order(&self, order: usize) -> Result<Self> {
        if order > self.degree() {
            return Err(Error::order_too_high(order, self.degree(), "the degree"));
        }
        let mut knots = self.clone();
        for _ in 0..order {
            knots = knots.derivative_knots()?;
        }
        Ok(knots)
    }

    /// The reversed knot vector `u ↦ a + b − u` (same domain `[a, b]`).
    #[must_use]
    pub fn reversed(&self) -> Self {
        let (a, b) = self.domain();
        let knots = self.knots().iter().rev().map(|&k| a + b - k).collect();
        Self::new_unchecked(self.degree(), knots)
    }

    /// The knot vector mapped affinely so that the domain becomes `[a, b]`.
    ///
    /// # Errors
    /// [`ErrorKind::EmptyDomain`] unless `a < b`; [`ErrorKind::NonFinite`].
    pub fn reparametrized(&self, a: T, b: T) -> Result<Self> {
        check_interval(a, b)?;
        let (c, d) = self.domain();
        let scale = (b - a) / (d - c);
        let knots = self.knots().iter().map(|&k| a + (k - c) * scale).collect();
        Self::new(self.degree(), knots)
    }

    /// Whether `fine` contains this space on `fine`'s domain: same degree, `fine`'s domain
    /// inside this one, and every knot of this vector strictly inside `fine`'s domain at
    /// least as often in `fine` (the condition for an exact transfer by blossoming).
    ///
    /// # Errors
    /// [`ErrorKind::SpaceMismatch`] naming the first violated condition; `what` names the
    /// operation in the message.
    pub fn check_contained_in(&self, fine: &Self, what: &str) -> Result<()> {
        if self.degree() != fine.degree() {
            return Err(Error::new(
                ErrorKind::SpaceMismatch,
                format!(
                    "{what} between degrees {} and {}: elevate the degree first",
                    self.degree(),
                    fine.degree()
                ),
            ));
        }
        let (sa, sb) = self.domain();
        let (fa, fb) = fine.domain();
        if fa < sa || fb > sb {
            return Err(Error::new(
                ErrorKind::SpaceMismatch,
                format!(
                    "{what}: the domain [{}, {}] is not inside the domain [{}, {}]",
                    to_f64(fa),
                    to_f64(fb),
                    to_f64(sa),
                    to_f64(sb)
                ),
            ));
        }
        for (k, m) in self.breakpoints() {
            if k > fa && k < fb && fine.multiplicity(k) < m {
                return Err(Error::new(
                    ErrorKind::SpaceMismatch,
                    format!(
                        "{what}: knot {} appears {m} times in the coarser space but only {} times in the finer one",
                        to_f64(k),
                        fine.multiplicity(k)
                    ),
                )
                .with_value(to_f64(k)));
            }
        }
        Ok(())
    }
}

/// Sorted union keeping, for each value, the larger multiplicity.
fn merge_sorted_max<T: Scalar>(a: &[T], b: &[T]) -> Vec<T> {
    let mut out = Vec::with_capacity(a.len().max(b.len()));
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        if j >= b.len() || (i < a.len() && a[i] < b[j]) {
            out.push(a[i]);
            i += 1;
        } else if i >= a.len() || b[j] < a[i] {
            out.push(b[j]);
            j += 1;
        } else {
            out.push(a[i]);
            i += 1;
            j += 1;
        }
    }
    out
}
