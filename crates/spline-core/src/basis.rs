//! B-spline basis functions and their derivatives (The NURBS Book A2.2 and A2.3; the
//! recurrences (1)–(2) of seed 000), without heap allocation.

use crate::error::{Error, ErrorKind, Result};
use crate::knots::{KnotVector, MAX_ORDER};
use crate::scalar::{Scalar, from_count};

/// The `p + 1` basis functions that may be non-zero at a parameter: `N_{first + r, p}(u)` is
/// `values()[r]`. Lives on the stack.
#[derive(Clone, Copy, Debug)]
pub struct BasisValues<T> {
    span: usize,
    len: usize,
    values: [T; MAX_ORDER],
}

impl<T: Scalar> BasisValues<T> {
    /// The knot span `k` (`u_k ≤ u < u_{k+1}`).
    #[inline]
    #[must_use]
    pub fn span(&self) -> usize {
        self.span
    }

    /// Index of the first non-zero basis function, `k − p`.
    #[inline]
    #[must_use]
    pub fn first(&self) -> usize {
        self.span + 1 - self.len
    }

    /// The `p + 1` values.
    #[inline]
    #[must_use]
    pub fn values(&self) -> &[T] {
        &self.values[..self.len]
    }
}

impl<T: Scalar> KnotVector<T> {
    /// Writes the `p + 1` basis functions of degree `p` that may be non-zero in knot span
    /// `span` at `u` into `out[..p + 1]`: `out[r] = N_{span − p + r, p}(u)` (The NURBS Book
    /// A2.2, the triangular scheme of seed 000 Algorithm 1, stable and division-safe).
    ///
    /// # Panics
    /// If `out` is shorter than `p + 1` or `span` is not a valid span (`p ≤ span < n`).
    #[inline]
    pub fn basis_values(&self, span: usize, u: T, out: &mut [T]) {
        let p = self.degree();
        let knots = self.knots();
        assert!(span >= p && span < self.num_basis(), "invalid span {span}");
        let out = &mut out[..=p];
        let mut left = [T::zero(); MAX_ORDER];
        let mut right = [T::zero(); MAX_ORDER];
        out[0] = T::one();
        for j in 1..=p {
            left[j] = u - knots[span + 1 - j];
            right[j] = knots[span + j] - u;
            triangle_step(j, &left, &right, out);
        }
    }

    /// [`KnotVector::basis_values`] for a degree known at compile time (`N = p + 1`): the
    /// working arrays have exactly `N` entries, which makes the hot path of low-degree
    /// evaluation several times cheaper than the general routine.
    ///
    /// # Panics
    /// If `N != p + 1` or `span` is invalid.
    #[inline]
    #[must_use]
    pub fn basis_values_fixed<const N: usize>(&self, span: usize, u: T) -> [T; N] {
        assert!(
            N == self.degree() + 1,
            "basis_values_fixed::<{N}> for degree {}",
            self.degree()
        );
        let knots = &self.knots()[span + 1 - N..=span + N - 1];
        // knots[j] is u_{span - p + j}; span itself is at index p = N - 1.
        let mut out = [T::zero(); N];
        let mut left = [T::zero(); N];
        let mut right = [T::zero(); N];
        out[0] = T::one();
        for j in 1..N {
            left[j] = u - knots[N - j];
            right[j] = knots[N - 1 + j] - u;
            triangle_step(j, &left, &right, &mut out);
        }
        out
    }

    /// The triangular scheme of [`KnotVector::basis_values_fixed`], keeping every degree:
    /// row `d` holds the `d + 1` basis functions of degree `d` non-zero in `span`,
    /// $N_{span - d + r,\\,d}(u)$ at index `r` (the rest of the row is zero). Lower degrees
    /// give curve derivatives through the derivative control points (The NURBS Book A3.4).
    ///
    /// # Panics
    /// If `N != p + 1` or `span` is invalid.
    #[inline]
    #[must_use]
    pub fn basis_by_degree_fixed<const N: usize>(&self, span: usize, u: T) -> [[T; N]; N] {
        assert!(
            N == self.degree() + 1,
            "basis_by_degree_fixed::<{N}> for degree {}",
            self.degree()
        );
        let knots = &self.knots()[span + 1 - N..=span + N - 1];
        let mut rows = [[T::zero(); N]; N];
        let mut left = [T::zero(); N];
        let mut right = [T::zero(); N];
        rows[0][0] = T::one();
        for j in 1..N {
            left[j] = u - knots[N - j];
            right[j] = knots[N - 1 + j] - u;
            let mut row = rows[j - 1];
            triangle_step(j, &left, &right, &mut row);
            rows[j] = row;
        }
        rows
    }

    /// The non-zero basis functions at `u`, with their span.
    ///
    /// ```
    /// use spline_core::KnotVector;
    /// let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0])?;
    /// let basis = knots.eval_basis(0.5)?;
    /// assert_eq!(basis.first(), 0);
    /// assert_eq!(basis.values(), &[0.25, 0.625, 0.125]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    #[inline]
    pub fn eval_basis(&self, u: T) -> Result<BasisValues<T>> {
        let span = self.find_span(u)?;
        let mut values = [T::zero(); MAX_ORDER];
        self.basis_values(span, u, &mut values);
        Ok(BasisValues {
            span,
            len: self.degree() + 1,
            values,
        })
    }

    /// Writes the basis functions of degree `p` non-zero in span `span` and their derivatives
    /// of orders `0 … order` into `out`, row-major with rows of length `p + 1`:
    /// `out[k (p + 1) + r]` $= N^{(k)}_{span − p + r, p}(u)$. Orders above `p` give zero rows.
    ///
    /// The NURBS Book A2.3, reorganised so that no table beyond `out` is needed: the rows
    /// first receive the basis values of degrees `p − k` from the triangular scheme, then are
    /// turned into derivatives in place (right to left) with the coefficients
    /// $a_{k,j}$ of (2).
    ///
    /// Only the orders up to `p` are computed; the rows above are set to zero.
    ///
    /// # Panics
    /// If `out.len() < (order + 1)(p + 1)` (a buffer of that size cannot exist when the
    /// product overflows) or `span` is invalid.
    pub fn basis_derivatives(&self, span: usize, u: T, order: usize, out: &mut [T]) {
        // Small degrees as constants (the loops unroll; the same operations in the same
        // order, so the same values).
        match self.degree() {
            1 => self.basis_derivatives_of_degree::<2>(1, span, u, order, out),
            2 => self.basis_derivatives_of_degree::<3>(2, span, u, order, out),
            3 => self.basis_derivatives_of_degree::<4>(3, span, u, order, out),
            4 => self.basis_derivatives_of_degree::<5>(4, span, u, order, out),
            5 => self.basis_derivatives_of_degree::<6>(5, span, u, order, out),
            p => self.basis_derivatives_of_degree::<MAX_ORDER>(p, span, u, order, out),
        }
    }

    /// [`KnotVector::basis_derivatives`] for `p = self.degree()`, passed in so that a
    /// constant degree specialises the code, with working arrays of `L ≥ p + 1` entries.
    #[inline(always)]
    fn basis_derivatives_of_degree<const L: usize>(
        &self,
        p: usize,
        span: usize,
        u: T,
        order: usize,
        out: &mut [T],
    ) {
        let knots = self.knots();
        let width = p + 1;
        assert!(span >= p && span < self.num_basis(), "invalid span {span}");
        let needed = order
            .checked_add(1)
            .and_then(|rows| rows.checked_mul(width));
        assert!(
            needed.is_some_and(|needed| out.len() >= needed),
            "output buffer too short"
        );
        let top = order.min(p);
        for v in out[(top + 1) * width..(order + 1) * width].iter_mut() {
            *v = T::zero();
        }
        // Triangular scheme, capturing the degree p − k values in row k.
        let mut left = [T::zero(); L];
        let mut right = [T::zero(); L];
        let mut n = [T::zero(); L];
        n[0] = T::one();
        if p <= top {
            out[p * width] = T::one();
        }
        for j in 1..=p {
            left[j] = u - knots[span + 1 - j];
            right[j] = knots[span + j] - u;
            triangle_step(j, &left, &right, &mut n);
            if p - j <= top {
                let row = p - j;
                out[row * width..row * width + j + 1].copy_from_slice(&n[..=j]);
            }
        }
        if top == 0 {
            return;
        }
        // ndu[pk + 1][x] of A2.3: the knot difference u_{span+x+1} − u_{span+x−pk}.
        let diff = |pk: usize, x: usize| knots[span + x + 1] - knots[span + x - pk];
        let mut a = [[T::zero(); L]; 2];
        // Right to left: computing column r reads columns ≤ r of the degree-(p − k) rows.
        for r in (0..=p).rev() {
            let (mut s1, mut s2) = (0usize, 1usize);
            a[0][0] = T::one();
            for k in 1..=top {
                let pk = p - k;
                let row = k * width;
                let mut d = T::zero();
                if r >= k {
                    let rk = r - k;
                    a[s2][0] = a[s1][0] / diff(pk, rk);
                    d = a[s2][0] * out[row + rk];
                }
                let j1 = if r >= k { 1 } else { k - r };
                let j2 = if r < pk + 1 { k - 1 } else { p - r };
                for j in j1..=j2 {
                    let x = r + j - k;
                    a[s2][j] = (a[s1][j] - a[s1][j - 1]) / diff(pk, x);
                    d += a[s2][j] * out[row + x];
                }
                if r <= pk {
                    a[s2][k] = -a[s1][k - 1] / diff(pk, r);
                    d += a[s2][k] * out[row + r];
                }
                out[row + r] = d;
                std::mem::swap(&mut s1, &mut s2);
            }
        }
        // Multiply row k by p! / (p − k)!.
        let mut factor = from_count::<T>(p);
        for k in 1..=top {
            for v in &mut out[k * width..(k + 1) * width] {
                *v *= factor;
            }
            factor *= from_count::<T>(p - k);
        }
    }

    /// All `n` basis functions at `u` (zeros included): a dense row of the collocation matrix.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn dense_basis(&self, u: T) -> Result<Vec<T>> {
        let basis = self.eval_basis(u)?;
        let mut row = vec![T::zero(); self.num_basis()];
        row[basis.first()..=basis.span()].copy_from_slice(basis.values());
        Ok(row)
    }

    /// All `n` basis functions at `u` and their derivatives up to `order`: `[k][i]`
    /// $= N^{(k)}_{i,p}(u)$.
    ///
    /// ```
    /// use spline_core::KnotVector;
    /// let knots = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0])?;
    /// let rows = knots.dense_basis_derivatives(0.0, 1)?;
    /// assert_eq!(rows[0], vec![1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    /// assert_eq!(rows[1], vec![-3.0, 3.0, 0.0, 0.0, 0.0, 0.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] if `order` is above [`crate::MAX_DERIVATIVE_ORDER`];
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn dense_basis_derivatives(&self, u: T, order: usize) -> Result<Vec<Vec<T>>> {
        crate::check_derivative_order(order)?;
        let span = self.find_span(u)?;
        let p = self.degree();
        // Orders above the degree are zero rows: only the others are computed.
        let top = order.min(p);
        let mut local = [T::zero(); MAX_ORDER * MAX_ORDER];
        self.basis_derivatives(span, u, top, &mut local[..(top + 1) * (p + 1)]);
        Ok((0..=order)
            .map(|k| {
                let mut row = vec![T::zero(); self.num_basis()];
                if k <= top {
                    row[span - p..=span].copy_from_slice(&local[k * (p + 1)..(k + 1) * (p + 1)]);
                }
                row
            })
            .collect())
    }

    /// The single basis function $N_{i,p}(u)$ (zero outside its support).
    ///
    /// # Errors
    /// [`ErrorKind::IndexOutOfRange`] if `i ≥ n` (with `i` as [`Error::index`]); the errors
    /// of [`KnotVector::find_span`].
    pub fn basis_function(&self, i: usize, u: T) -> Result<T> {
        if i >= self.num_basis() {
            return Err(Error::new(
                ErrorKind::IndexOutOfRange,
                format!(
                    "basis function {i} does not exist (n = {})",
                    self.num_basis()
                ),
            )
            .with_index(i));
        }
        let basis = self.eval_basis(u)?;
        Ok(if i >= basis.first() && i <= basis.span() {
            basis.values()[i - basis.first()]
        } else {
            T::zero()
        })
    }
}

/// One degree of the triangular scheme (seed 000 (1), The NURBS Book A2.2): turns the `j`
/// basis functions of degree `j − 1` in `out[..j]` into the `j + 1` of degree `j`, written
/// with the weight $\alpha = \frac{u_{k+r+1} - u}{u_{k+r+1} - u_{k+r+1-j}}$ so that at a
/// knot one weight is exactly 1 and the other exactly 0: a clamped curve returns exactly its
/// end control points, and values stay a partition of unity to rounding.
#[inline(always)]
fn triangle_step<T: Scalar>(j: usize, left: &[T], right: &[T], out: &mut [T]) {
    let mut saved = T::zero();
    for r in 0..j {
        let alpha = right[r + 1] / (right[r + 1] + left[j - r]);
        let temp = out[r];
        out[r] = saved + alpha * temp;
        saved = temp - alpha * temp;
    }
    out[j] = saved;
}

/// The largest degree whose reciprocal knot differences [`SpanBasis`] keeps.
const SPAN_CACHE_DEGREE: usize = 7;

/// An evaluator of basis functions for many parameters that visit spans in order (batches of
/// sorted parameters, collocation and least-squares matrices). It keeps the reciprocals of the
/// knot differences of its current span, updated incrementally when the span moves one step
/// right, so that a parameter costs a few multiplications instead of `p(p + 1)/2` divisions.
/// Parameters exactly on a knot take the exact division-based route, so clamped ends are
/// exact. Degrees above 7 always take that route.
///
/// ```
/// use spline_core::{KnotVector, SpanBasis};
/// let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0])?;
/// let mut basis = SpanBasis::new();
/// let mut values = [0.0; 3];
/// for u in [0.1, 0.2, 0.6, 1.0] {
///     let span = knots.find_span(u)?;
///     basis.eval(&knots, span, u, &mut values);
///     assert!((values.iter().sum::<f64>() - 1.0).abs() < 1e-15);
/// }
/// assert_eq!(values, [0.0, 0.0, 1.0]); // exactly the last function at the end
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct SpanBasis<T> {
    span: usize,
    /// `inverse[j (j − 1)/2 + r]` $= 1/(u_{s+r+1} - u_{s+1-j+r})$, `j = 1 … p`, `r < j`.
    inverse: [T; SPAN_CACHE_DEGREE * (SPAN_CACHE_DEGREE + 1) / 2],
}

impl<T: Scalar> Default for SpanBasis<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Scalar> SpanBasis<T> {
    /// An evaluator with no span cached yet.
    #[must_use]
    pub fn new() -> Self {
        Self {
            span: usize::MAX,
            inverse: [T::zero(); SPAN_CACHE_DEGREE * (SPAN_CACHE_DEGREE + 1) / 2],
        }
    }

    /// The `p + 1` basis functions non-zero in `span` at `u` into `out[..p + 1]`, as
    /// [`KnotVector::basis_values`] computes them.
    ///
    /// # Panics
    /// If `out` is shorter than `p + 1` or `span` is not a valid span of `knots`.
    #[inline]
    pub fn eval(&mut self, knots: &KnotVector<T>, span: usize, u: T, out: &mut [T]) {
        let p = knots.degree();
        let k = knots.knots();
        if p > SPAN_CACHE_DEGREE || u == k[span] || u == k[span + 1] {
            knots.basis_values(span, u, out);
            return;
        }
        if span != self.span {
            if span == self.span.wrapping_add(1) {
                // One span to the right: every row shifts by one and gains one reciprocal.
                let mut idx = 0;
                for j in 1..=p {
                    self.inverse.copy_within(idx + 1..idx + j, idx);
                    self.inverse[idx + j - 1] = T::one() / (k[span + j] - k[span]);
                    idx += j;
                }
            } else {
                let mut idx = 0;
                for j in 1..=p {
                    for r in 0..j {
                        self.inverse[idx] = T::one() / (k[span + r + 1] - k[span + 1 + r - j]);
                        idx += 1;
                    }
                }
            }
            self.span = span;
        }
        let mut left = [T::zero(); SPAN_CACHE_DEGREE + 1];
        let mut right = [T::zero(); SPAN_CACHE_DEGREE + 1];
        let out = &mut out[..=p];
        out[0] = T::one();
        let mut idx = 0;
        for j in 1..=p {
            left[j] = u - k[span + 1 - j];
            right[j] = k[span + j] - u;
            let mut saved = T::zero();
            for r in 0..j {
                let alpha = right[r + 1] * self.inverse[idx + r];
                let temp = out[r];
                out[r] = saved + alpha * temp;
                saved = temp - alpha * temp;
            }
            out[j] = saved;
            idx += j;
        }
    }
}

/// The binomial coefficient $\binom{n}{k}$ as a scalar (exact in `f64` up to `n = 56`).
#[must_use]
pub fn binomial<T: Scalar>(n: usize, k: usize) -> T {
    if k > n {
        return T::zero();
    }
    let k = k.min(n - k);
    let mut c = 1.0f64;
    for i in 0..k {
        #[allow(clippy::cast_precision_loss)]
        {
            c = c * (n - i) as f64 / (i + 1) as f64;
        }
    }
    crate::cast(c.round())
}

/// The Bernstein polynomial $B_i^n(t) = \binom{n}{i} t^i (1-t)^{n-i}$.
///
/// ```
/// assert!((spline_core::bernstein(3, 1, 0.5) - 0.375f64).abs() < 1e-15);
/// ```
#[must_use]
pub fn bernstein<T: Scalar>(n: usize, i: usize, t: T) -> T {
    if i > n {
        return T::zero();
    }
    let mut value = binomial::<T>(n, i);
    let s = T::one() - t;
    for _ in 0..i {
        value *= t;
    }
    for _ in 0..n - i {
        value *= s;
    }
    value
}

/// All Bernstein polynomials of degree `n` at `t` into `out[..n + 1]` by the stable
/// recurrence $B_i^n = (1-t) B_i^{n-1} + t B_{i-1}^{n-1}$ (The NURBS Book A1.3).
///
/// # Panics
/// If `out.len() < n + 1`.
pub fn bernstein_all<T: Scalar>(n: usize, t: T, out: &mut [T]) {
    let out = &mut out[..=n];
    out[0] = T::one();
    let s = T::one() - t;
    for j in 1..=n {
        let mut saved = T::zero();
        for value in out.iter_mut().take(j) {
            let temp = *value;
            *value = saved + s * temp;
            saved = t * temp;
        }
        out[j] = saved;
    }
}
