//! Knot vectors: validated once at construction, then trusted.

mod constructors;
mod rules;

use crate::error::{Error, ErrorKind, Result};
use crate::scalar::{Scalar, from_count, to_f64};

/// The highest degree the library supports.
///
/// Per-point algorithms keep their working arrays on the stack, sized `MAX_DEGREE + 1`.
/// Degrees this high are already numerically meaningless for B-splines in `f64`.
pub const MAX_DEGREE: usize = 32;

/// `MAX_DEGREE + 1`: the largest number of basis functions non-zero at a parameter.
pub const MAX_ORDER: usize = MAX_DEGREE + 1;

/// The highest derivative order that the functions returning all derivatives up to an order
/// (`dense_basis_derivatives`, curve, NURBS and surface `derivatives`) accept.
///
/// Derivatives of a polynomial piece above its degree (at most [`MAX_DEGREE`]) are zero and
/// cost nothing to compute, but the result holds one row per order; rational derivatives of
/// order `k` grow like `k!` and leave the range of `f64` near order 170. The limit keeps
/// the size of such results bounded by the input.
pub const MAX_DERIVATIVE_ORDER: usize = 1000;

/// Checks a derivative order against [`MAX_DERIVATIVE_ORDER`].
///
/// # Errors
/// [`ErrorKind::OrderTooHigh`] above the limit.
pub fn check_derivative_order(order: usize) -> Result<()> {
    if order > MAX_DERIVATIVE_ORDER {
        return Err(Error::new(
            ErrorKind::OrderTooHigh,
            format!(
                "derivative order {order} is above the supported maximum {MAX_DERIVATIVE_ORDER}"
            ),
        )
        .with_counts(MAX_DERIVATIVE_ORDER, order));
    }
    Ok(())
}

/// A knot vector together with the degree of the spline space it defines.
///
/// `n + p + 1` non-decreasing finite knots `u_0 ≤ … ≤ u_{n+p}` define `n` B-spline basis
/// functions of degree `p`; the parametric domain is $[u_p, u_n]$, clamped or not.
/// Construction checks every invariant (finite, sorted, multiplicity at most `p + 1`, at least
/// `p + 1` basis functions, non-empty domain); afterwards the type carries them.
///
/// Evaluation conventions (shared with scipy, The NURBS Book and the exchange format):
/// at an interior knot a parameter belongs to the span on its right (right limits); at the
/// last knot of the domain it belongs to the last non-empty span (left limit).
///
/// ```
/// use spline_core::KnotVector;
/// let knots = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0])?;
/// assert_eq!(knots.num_basis(), 6);
/// assert_eq!(knots.domain(), (0.0, 3.0));
/// assert_eq!(knots.find_span(1.0)?, 4); // right limit at an interior knot
/// assert_eq!(knots.find_span(3.0)?, 5); // left limit at the end of the domain
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector<T> {
    degree: usize,
    knots: Vec<T>,
}

impl<T: Scalar> KnotVector<T> {
    /// Validates `knots` for degree `degree`.
    ///
    /// # Errors
    /// [`ErrorKind::DegreeTooHigh`] above [`MAX_DEGREE`]; [`ErrorKind::InvalidLength`] with
    /// fewer than `2(p + 1)` knots; [`ErrorKind::NonFinite`] for NaN or infinite knots;
    /// [`ErrorKind::UnsortedKnots`]; [`ErrorKind::KnotMultiplicity`] when a knot appears more
    /// than `p + 1` times; [`ErrorKind::EmptyDomain`] when `u_p = u_n`.
    pub fn new(degree: usize, knots: Vec<T>) -> Result<Self> {
        if degree > MAX_DEGREE {
            return Err(Error::new(
                ErrorKind::DegreeTooHigh,
                format!("degree {degree} is above the supported maximum {MAX_DEGREE}"),
            ));
        }
        let order = degree + 1;
        if knots.len() < 2 * order {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "a degree-{degree} spline needs at least {} knots ({} control points + degree + 1), got {}",
                    2 * order,
                    order,
                    knots.len()
                ),
            ));
        }
        if let Some(i) = knots.iter().position(|k| !k.is_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("knot {i} is not finite ({})", to_f64(knots[i])),
            ));
        }
        if let Some(i) = (1..knots.len()).find(|&i| knots[i] < knots[i - 1]) {
            return Err(Error::new(
                ErrorKind::UnsortedKnots,
                format!(
                    "knots must be non-decreasing: knot {i} ({}) is smaller than knot {} ({})",
                    to_f64(knots[i]),
                    i - 1,
                    to_f64(knots[i - 1])
                ),
            ));
        }
        let mut start = 0;
        while start < knots.len() {
            let mut end = start + 1;
            while end < knots.len() && knots[end] == knots[start] {
                end += 1;
            }
            if end - start > order {
                return Err(Error::new(
                    ErrorKind::KnotMultiplicity,
                    format!(
                        "knot {} appears {} times; a degree-{degree} spline allows at most {order}",
                        to_f64(knots[start]),
                        end - start
                    ),
                ));
            }
            start = end;
        }
        let n = knots.len() - order;
        if knots[degree] >= knots[n] {
            return Err(Error::new(
                ErrorKind::EmptyDomain,
                format!(
                    "the domain [u_{degree}, u_{n}] = [{}, {}] is empty",
                    to_f64(knots[degree]),
                    to_f64(knots[n])
                ),
            ));
        }
        Ok(Self { degree, knots })
    }

    /// Wraps knots that the caller guarantees valid (the output of the library's own
    /// algorithms). The invariants are checked in debug builds.
    ///
    /// # Panics
    /// In debug builds, if the knots are invalid.
    #[must_use]
    pub fn new_unchecked(degree: usize, knots: Vec<T>) -> Self {
        #[cfg(debug_assertions)]
        if let Err(e) = Self::new(degree, knots.clone()) {
            panic!("invalid knot vector from a trusted caller: {e}");
        }
        Self { degree, knots }
    }

    /// Changes the knots in place through `f`, which must leave them valid (the library's
    /// own in-place algorithms: knot insertion and refinement grow the vector without a new
    /// allocation per call). The invariants are checked in debug builds.
    ///
    /// ```
    /// let mut k = spline_core::KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0])?;
    /// k.update_unchecked(|knots| knots.insert(2, 0.5));
    /// assert_eq!(k.knots(), &[0.0, 0.0, 0.5, 1.0, 1.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Panics
    /// In debug builds, if the knots are invalid afterwards.
    #[inline]
    pub fn update_unchecked<R>(&mut self, f: impl FnOnce(&mut Vec<T>) -> R) -> R {
        let out = f(&mut self.knots);
        #[cfg(debug_assertions)]
        if let Err(e) = Self::new(self.degree, self.knots.clone()) {
            panic!("invalid knot vector from a trusted caller: {e}");
        }
        out
    }

    /// The degree `p`.
    #[inline]
    #[must_use]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The order `p + 1`.
    #[inline]
    #[must_use]
    pub fn order(&self) -> usize {
        self.degree + 1
    }

    /// All knots.
    #[inline]
    #[must_use]
    pub fn knots(&self) -> &[T] {
        &self.knots
    }

    /// Consumes the vector, returning the knots.
    #[must_use]
    pub fn into_knots(self) -> Vec<T> {
        self.knots
    }

    /// Number of knots, `n + p + 1`.
    #[inline]
    #[must_use]
    #[allow(clippy::len_without_is_empty)]
    pub fn len(&self) -> usize {
        self.knots.len()
    }

    /// Number of basis functions (control points) `n`.
    #[inline]
    #[must_use]
    pub fn num_basis(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The parametric domain $[u_p, u_n]$.
    #[inline]
    #[must_use]
    pub fn domain(&self) -> (T, T) {
        (self.knots[self.degree], self.knots[self.num_basis()])
    }

    /// Whether the first and the last `p + 1` knots are equal (the curve interpolates its end
    /// control points).
    #[must_use]
    pub fn is_clamped(&self) -> bool {
        let p = self.degree;
        let (a, b) = self.domain();
        self.knots[..=p].iter().all(|&k| k == a)
            && self.knots[self.len() - p - 1..].iter().all(|&k| k == b)
    }

    /// Whether `u` lies in the domain (inclusive).
    #[inline]
    #[must_use]
    pub fn contains(&self, u: T) -> bool {
        let (a, b) = self.domain();
        u >= a && u <= b
    }

    /// Checks that `u` is finite and inside the domain.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn check_param(&self, u: T) -> Result<()> {
        if !u.is_finite() {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("parameter {} is not finite", to_f64(u)),
            )
            .with_value(to_f64(u)));
        }
        if !self.contains(u) {
            let (a, b) = self.domain();
            return Err(Error::out_of_domain(to_f64(u), (to_f64(a), to_f64(b))));
        }
        Ok(())
    }

    /// The knot span of `u`: the index `k`, `p ≤ k < n`, with $u_k \le u < u_{k+1}$ (right
    /// limit at interior knots), or the last non-empty span when `u = u_n`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    #[inline]
    pub fn find_span(&self, u: T) -> Result<usize> {
        self.check_param(u)?;
        Ok(self.span_in_domain(u))
    }

    /// [`KnotVector::find_span`] for a parameter already known to be in the domain; values
    /// outside are clamped to the first or last span.
    #[inline]
    #[must_use]
    pub fn span_in_domain(&self, u: T) -> usize {
        let p = self.degree;
        let n = self.num_basis();
        let end = self.knots[n];
        if u >= end {
            // Left limit: the last span [u_k, u_{k+1}) with u_k < u_n.
            return self.knots[..n].partition_point(|&k| k < end) - 1;
        }
        p + self.knots[p + 1..n].partition_point(|&k| k <= u)
    }

    /// [`KnotVector::span_in_domain`] starting from a previous span: constant time when
    /// parameters arrive in increasing order, a binary search otherwise.
    #[inline]
    #[must_use]
    pub fn span_in_domain_from(&self, u: T, hint: usize) -> usize {
        let n = self.num_basis();
        if hint >= self.degree() && hint < n && self.knots[hint] <= u {
            // Same span, or the next non-empty one; otherwise bisection.
            if u < self.knots[hint + 1] {
                return hint;
            }
            if hint + 2 <= n && u < self.knots[hint + 2] && u < self.knots[n] {
                return hint + 1;
            }
        }
        self.span_in_domain(u)
    }

    /// How many times `u` appears in the knot vector.
    #[must_use]
    pub fn multiplicity(&self, u: T) -> usize {
        let lo = self.knots.partition_point(|&k| k < u);
        let hi = self.knots.partition_point(|&k| k <= u);
        hi - lo
    }

    /// The distinct knots with their multiplicities, in increasing order.
    #[must_use]
    pub fn breakpoints(&self) -> Vec<(T, usize)> {
        let mut out: Vec<(T, usize)> = Vec::with_capacity(self.knots.len());
        for &k in &self.knots {
            match out.last_mut() {
                Some((last, m)) if *last == k => *m += 1,
                _ => out.push((k, 1)),
            }
        }
        out
    }

    /// The distinct knots inside the open domain, with multiplicities.
    #[must_use]
    pub fn interior_breakpoints(&self) -> Vec<(T, usize)> {
        let (a, b) = self.domain();
        self.breakpoints()
            .into_iter()
            .filter(|&(k, _)| k > a && k < b)
            .collect()
    }

    /// The ends of the polynomial pieces of a spline on `[a, b]`: `a`, the distinct knots
    /// strictly between `a` and `b` in increasing order, then `b` (only `a` when `a = b`).
    ///
    /// ```
    /// use spline_core::KnotVector;
    /// let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 3.0, 3.0, 3.0])?;
    /// assert_eq!(knots.breaks_between(0.5, 2.5), vec![0.5, 1.0, 2.0, 2.5]);
    /// assert_eq!(knots.breaks_between(1.0, 1.0), vec![1.0]);
    /// assert_eq!(knots.domain_breaks(), vec![0.0, 1.0, 2.0, 3.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    #[must_use]
    pub fn breaks_between(&self, a: T, b: T) -> Vec<T> {
        let mut breaks = Vec::with_capacity(self.knots.len() + 2);
        breaks.push(a);
        breaks.extend(self.knots.iter().copied().filter(|&k| k > a && k < b));
        breaks.push(b);
        breaks.dedup();
        breaks
    }

    /// The ends of the polynomial pieces on the whole domain $[u_p, u_n]$: its ends and the
    /// distinct interior knots ([`KnotVector::breaks_between`] on the domain).
    #[must_use]
    pub fn domain_breaks(&self) -> Vec<T> {
        let (a, b) = self.domain();
        self.breaks_between(a, b)
    }

    /// Greville abscissae $u^*_i = (u_{i+1} + … + u_{i+p})/p$, `i = 0 … n − 1`: the
    /// parameters at which the control polygon of a function is drawn. For degree 0, the
    /// midpoints of the supports.
    #[must_use]
    pub fn greville(&self) -> Vec<T> {
        let p = self.degree;
        (0..self.num_basis())
            .map(|i| {
                if p == 0 {
                    (self.knots[i] + self.knots[i + 1]) * crate::cast(0.5)
                } else {
                    self.knots[i + 1..=i + p]
                        .iter()
                        .fold(T::zero(), |s, &k| s + k)
                        / from_count(p)
                }
            })
            .collect()
    }
}

/// The degree `p + times` of a degree elevation, checked against [`MAX_DEGREE`] without
/// overflow.
///
/// # Errors
/// [`ErrorKind::DegreeTooHigh`] if `p + times` is above [`MAX_DEGREE`].
pub fn check_elevated_degree(degree: usize, times: usize) -> Result<usize> {
    match degree.checked_add(times) {
        Some(d) if d <= MAX_DEGREE => Ok(d),
        _ => Err(Error::new(
            ErrorKind::DegreeTooHigh,
            format!(
                "raising degree {degree} by {times} goes above the supported maximum degree {MAX_DEGREE} (at most {} more)",
                MAX_DEGREE.saturating_sub(degree)
            ),
        )),
    }
}

pub(crate) fn check_interval<T: Scalar>(a: T, b: T) -> Result<()> {
    if !(a.is_finite() && b.is_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("interval [{}, {}] is not finite", to_f64(a), to_f64(b)),
        ));
    }
    if a >= b {
        return Err(Error::new(
            ErrorKind::EmptyDomain,
            format!("interval [{}, {}] is empty", to_f64(a), to_f64(b)),
        ));
    }
    Ok(())
}

/// Checks that parameters are finite and non-decreasing.
///
/// # Errors
/// [`ErrorKind::NonFinite`] or [`ErrorKind::UnsortedKnots`].
pub fn check_params<T: Scalar>(params: &[T]) -> Result<()> {
    if let Some(i) = params.iter().position(|u| !u.is_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("parameter {i} is not finite"),
        ));
    }
    if let Some(i) = (1..params.len()).find(|&i| params[i] < params[i - 1]) {
        return Err(Error::new(
            ErrorKind::UnsortedKnots,
            format!(
                "parameters must be non-decreasing: parameter {i} ({}) < parameter {} ({})",
                to_f64(params[i]),
                i - 1,
                to_f64(params[i - 1])
            ),
        ));
    }
    Ok(())
}
