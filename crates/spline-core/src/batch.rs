//! Basis functions for batches of parameters in any order: a bucket table finds the span in
//! constant time and a table of reciprocal knot differences removes every division.

use crate::knots::KnotVector;
use crate::scalar::{Scalar, to_f64};

/// A bucket table over the domain that finds the knot span of a parameter in constant time
/// for any knot vector (uniform or not, clamped or not, repeated knots): the domain is cut
/// into `4 (n − p)` equal buckets; each bucket stores the span of its left edge and, when it
/// holds one distinct knot value (of any multiplicity), the span that starts there — one
/// more comparison and a select, no branch. Buckets holding several distinct knots
/// (clustered knots) walk them.
///
/// The bucket of a knot is computed by the same floating-point formula as the bucket of a
/// parameter, and that formula is monotone, so the table is exact — no rounding can land
/// a parameter in the wrong span.
///
/// ```
/// use spline_core::{KnotVector, SpanTable};
/// let knots = KnotVector::new(2, vec![0.0f64, 0.0, 0.0, 0.1, 0.1, 0.15, 1.0, 1.0, 1.0])?;
/// let table = SpanTable::new(&knots);
/// for u in [0.0, 0.05, 0.1, 0.12, 0.15, 0.6, 1.0] {
///     assert_eq!(table.span(&knots, u), knots.find_span(u)?);
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct SpanTable {
    degree: usize,
    start: f64,
    buckets_per_unit: f64,
    /// Per bucket: the span at its left edge, and the span starting at the one distinct knot
    /// value inside it (the left span again if there is none, [`SEVERAL`] if there are more).
    buckets: Vec<[usize; 2]>,
    /// The last non-empty span (the span of the domain's end).
    last: usize,
}

/// Marks a bucket holding several distinct knot values.
const SEVERAL: usize = usize::MAX;

impl SpanTable {
    /// Builds the table in `O(n)`.
    #[must_use]
    pub fn new<T: Scalar>(knots: &KnotVector<T>) -> Self {
        let mut table = Self {
            degree: 0,
            start: 0.0,
            buckets_per_unit: 0.0,
            buckets: Vec::new(),
            last: 0,
        };
        table.rebuild(knots);
        table
    }

    /// Rebuilds the table for `knots` in `O(n)`, reusing its storage (no allocation when
    /// the new table is no larger).
    pub fn rebuild<T: Scalar>(&mut self, knots: &KnotVector<T>) {
        let p = knots.degree();
        let n = knots.num_basis();
        let k = knots.knots();
        let (a, b) = knots.domain();
        let (start, end) = (to_f64(a), to_f64(b));
        let count = 4 * (n - p);
        self.buckets.clear();
        self.buckets.resize(count, [p, p]);
        let per_unit = count as f64 / (end - start);
        self.degree = p;
        self.start = start;
        self.buckets_per_unit = per_unit;
        self.last = knots.span_in_domain(b);
        // The knots u_{p+1} … u_{n−1} bucket by bucket, in increasing order: the span at a
        // bucket's left edge is the span of the last knot before it.
        let mut span = p;
        let mut j = p + 1;
        for (i, slot) in self.buckets.iter_mut().enumerate() {
            let left = span;
            let mut distinct = 0;
            while j < n && Self::bucket_of(start, per_unit, count, k[j]) == i {
                if k[j] != k[j - 1] || j == p + 1 {
                    distinct += 1;
                }
                span = j;
                j += 1;
            }
            *slot = [left, if distinct > 1 { SEVERAL } else { span }];
        }
    }

    #[inline(always)]
    fn bucket_of<T: Scalar>(start: f64, buckets_per_unit: f64, count: usize, u: T) -> usize {
        // Saturating conversion: below the domain (and NaN) gives bucket 0.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let bucket = ((to_f64(u) - start) * buckets_per_unit).max(0.0) as i64 as usize;
        bucket.min(count - 1)
    }

    /// The bucket formula's origin and scale: the bucket of `u` is
    /// $\min(\lfloor \max(0, (u - \text{start}) \cdot \text{scale}) \rfloor, \text{count} - 1)$
    /// with `(start, scale)` these and `count` the length of [`SpanTable::buckets`]. For
    /// kernels that look spans up lane by lane (spline-geom's batch across SIMD lanes).
    #[must_use]
    pub fn bucket_scale(&self) -> (f64, f64) {
        (self.start, self.buckets_per_unit)
    }

    /// The bucket of `u` by the formula of [`SpanTable::bucket_scale`].
    #[must_use]
    pub fn bucket<T: Scalar>(&self, u: T) -> usize {
        Self::bucket_of(self.start, self.buckets_per_unit, self.buckets.len(), u)
    }

    /// Per bucket: the span at its left edge and the span starting at the one distinct knot
    /// value inside it (the left span again when it holds none), or `None` for a bucket
    /// holding several distinct knot values (where [`SpanTable::span`] walks the knots). A
    /// parameter `u` below the domain's end in a bucket `[left, next]` lies in span `next`
    /// if `u ≥ u_next`, in span `left` otherwise.
    pub fn buckets(&self) -> impl ExactSizeIterator<Item = Option<[usize; 2]>> + '_ {
        self.buckets
            .iter()
            .map(|&[left, next]| (next != SEVERAL).then_some([left, next]))
    }

    /// The span of `u` (right limits inside the domain, the last non-empty span at its end),
    /// as [`KnotVector::span_in_domain`] finds it; parameters outside the domain get the first
    /// or last span.
    ///
    /// # Panics
    /// If `knots` is not the knot vector the table was built from, the span is meaningless
    /// or an index is out of bounds.
    #[inline(always)]
    #[must_use]
    pub fn span<T: Scalar>(&self, knots: &KnotVector<T>, u: T) -> usize {
        let k = knots.knots();
        let n = k.len() - self.degree - 1;
        if u >= k[n] {
            return self.last;
        }
        let bucket = Self::bucket_of(self.start, self.buckets_per_unit, self.buckets.len(), u);
        let [left, next] = self.buckets[bucket];
        if next != SEVERAL {
            return if u >= k[next] { next } else { left };
        }
        // u < u_n: the walk stops before n.
        let mut span = left;
        while u >= k[span + 1] {
            span += 1;
        }
        span
    }
}

/// Tables prepared once for a knot vector, so that the basis functions of degree `N − 1` at
/// any parameter of the domain cost a table lookup, a short walk and `p(p + 1)` multiplications
/// ([`BatchBasis::eval_fixed`]). Worth it for more parameters than knots.
///
/// ```
/// use spline_core::{BatchBasis, KnotVector};
/// let knots = KnotVector::new(2, vec![0.0f64, 0.0, 0.0, 0.3, 0.5, 1.0, 1.0, 1.0])?;
/// let batch = BatchBasis::new(&knots);
/// for u in [0.7, 0.1, 0.5, 1.0, 0.0] {
///     let (span, values) = batch.eval_fixed::<3>(&knots, u);
///     assert_eq!(span, knots.find_span(u)?);
///     let exact = knots.eval_basis(u)?;
///     for (a, b) in values.iter().zip(exact.values()) {
///         let (a, b): (&f64, &f64) = (a, b);
///         assert!((a - b).abs() < 1e-15);
///     }
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct BatchBasis<T> {
    degree: usize,
    table: SpanTable,
    /// `p(p + 1)/2` reciprocal knot differences per span (`span − p` major).
    reciprocals: Vec<T>,
}

impl<T: Scalar> BatchBasis<T> {
    /// Prepares the tables: a [`SpanTable`] and the reciprocals of every span.
    #[must_use]
    pub fn new(knots: &KnotVector<T>) -> Self {
        let p = knots.degree();
        let n = knots.num_basis();
        let k = knots.knots();
        let per_span = p * (p + 1) / 2;
        let mut reciprocals = vec![T::zero(); (n - p) * per_span];
        for s in p..n {
            if k[s] == k[s + 1] {
                continue;
            }
            let row = &mut reciprocals[(s - p) * per_span..(s - p + 1) * per_span];
            let mut idx = 0;
            for j in 1..=p {
                for r in 0..j {
                    row[idx] = T::one() / (k[s + r + 1] - k[s + 1 + r - j]);
                    idx += 1;
                }
            }
        }
        Self {
            degree: p,
            table: SpanTable::new(knots),
            reciprocals,
        }
    }

    /// The span of a parameter of the domain (right limits inside, left limit at the end),
    /// as [`KnotVector::span_in_domain`] finds it.
    #[inline(always)]
    #[must_use]
    pub fn span(&self, knots: &KnotVector<T>, u: T) -> usize {
        self.span_from(knots, u, usize::MAX)
    }

    /// [`BatchBasis::span`] trying `hint` (the previous span) first: one comparison when
    /// parameters come in increasing order.
    #[inline(always)]
    #[must_use]
    pub fn span_from(&self, knots: &KnotVector<T>, u: T, hint: usize) -> usize {
        let k = knots.knots();
        let n = knots.num_basis();
        // Both comparisons are evaluated (`&`, not `&&`): for parameters in random order the
        // first alone would be a coin toss for the branch predictor, the pair is nearly always
        // false.
        if hint < n && ((k[hint] <= u) & (u < k[hint + 1])) {
            return hint;
        }
        self.table.span(knots, u)
    }

    /// The span of `u` and the `N = p + 1` basis functions non-zero there. Parameters exactly
    /// on a knot use the exact routine (clamped ends are exact).
    ///
    /// # Panics
    /// If `N != p + 1` or the tables belong to another knot vector.
    #[inline(always)]
    #[must_use]
    pub fn eval_fixed<const N: usize>(&self, knots: &KnotVector<T>, u: T) -> (usize, [T; N]) {
        self.eval_fixed_from(knots, u, usize::MAX)
    }

    /// [`BatchBasis::eval_fixed`] trying the span `hint` first (see [`BatchBasis::span_from`]).
    ///
    /// # Panics
    /// As [`BatchBasis::eval_fixed`].
    #[inline(always)]
    #[must_use]
    pub fn eval_fixed_from<const N: usize>(
        &self,
        knots: &KnotVector<T>,
        u: T,
        hint: usize,
    ) -> (usize, [T; N]) {
        assert!(
            N == self.degree + 1,
            "eval_fixed::<{N}> for degree {}",
            self.degree
        );
        let span = self.span_from(knots, u, hint);
        let k = knots.knots();
        if u == k[span] || u == k[span + 1] {
            return (span, knots.basis_values_fixed::<N>(span, u));
        }
        let p = N - 1;
        let per_span = p * (p + 1) / 2;
        let recips = &self.reciprocals[(span - p) * per_span..(span - p + 1) * per_span];
        let window = &k[span + 1 - N..=span + N - 1];
        let mut out = [T::zero(); N];
        let mut left = [T::zero(); N];
        let mut right = [T::zero(); N];
        out[0] = T::one();
        let mut idx = 0;
        for j in 1..N {
            left[j] = u - window[N - j];
            right[j] = window[N - 1 + j] - u;
            let mut saved = T::zero();
            for r in 0..j {
                let alpha = right[r + 1] * recips[idx + r];
                let temp = out[r];
                out[r] = saved + alpha * temp;
                saved = temp - alpha * temp;
            }
            out[j] = saved;
            idx += j;
        }
        (span, out)
    }
}
