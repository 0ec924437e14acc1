//! The piecewise polynomial form of a B-spline, cached in the curve: for every non-empty span
//! the Taylor coefficients about its left knot, and a [`SpanTable`] to find the span.
//!
//! $$ C(u) = \sum_{k=0}^{p} c_k\\,(u - u_s)^k, \qquad c_k = \frac{C^{(k)}(u_s^+)}{k!},
//! \qquad u_s \le u < u_{s+1}, $$
//!
//! so that a point costs a table lookup and `p` multiply-adds (Horner) instead of a search and
//! the triangular scheme with its divisions. The coefficients come from the curve's own
//! derivatives (derivative control points, The NURBS Book A3.3), `c_0` from its own point at
//! `u_s`, so at every knot the cached form returns exactly what the triangular scheme returns;
//! the domain's end, where the form would extrapolate a span to its right end, is left to the
//! triangular scheme.
//!
//! Batches use the form, eight parameters at a time across SIMD lanes where the CPU has
//! AVX2 and the scalar is `f64` (`lanes/`, the same values bit for bit), one at a time
//! otherwise; the one-point evaluation uses only the table (its values stay the
//! triangular scheme's, bit for bit: curve intersection in spline-algebra relies on their
//! rounding matching the derivatives').
//!
//! The cache is built on demand: by a batch of at least as many parameters as spans, or by the
//! one-point evaluation once it has been called as many times as there are spans since the
//! curve last changed (building costs a few evaluations per span, so it adds at most a small
//! multiple of the work of the calls already made).
//! Every mutation of the knots or control points drops it. It is not part of the curve's
//! value: equality, `Debug` and serialisation ignore it, clones share it until they change.

use crate::lanes::{self, LaneForm};
use spline_core::{ControlPoint, KnotVector, Scalar, SpanTable, from_count};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};

/// What the piecewise polynomial form needs of its curve: `BSpline` implements it (in
/// `bspline.rs`), so the form does not depend on the container that caches it.
pub(crate) trait PieceSource<T: Scalar, P: ControlPoint<T>> {
    /// The knot vector (degree, domain, spans).
    fn knots(&self) -> &KnotVector<T>;
    /// The control points.
    fn control_points(&self) -> &[P];
    /// The point at `u` in the span `span` (the triangular scheme).
    fn eval_in_span(&self, span: usize, u: T) -> P;
    /// The derivatives of orders `0 … out.len() − 1` at `u` in the span `span`.
    fn derivatives_in_span(&self, span: usize, u: T, out: &mut [P]);
}

/// Degrees up to this have a cached form (higher degrees keep the triangular scheme: the
/// power form loses accuracy as the degree grows).
const MAX_CACHED_DEGREE: usize = 5;

/// Whether degree `p` has a cached form (1 to [`MAX_CACHED_DEGREE`]).
fn has_form(p: usize) -> bool {
    (1..=MAX_CACHED_DEGREE).contains(&p)
}

/// The largest ratio of `Σ |c_k| h^k` to the largest control point of a span for which the
/// cached form is used: it bounds the loss of accuracy against the triangular scheme. Up to
/// degree 3 it always holds (the ratio is at most `3^p`).
const CONDITION: usize = 32;

/// Runs `$e` with the constant `$N` the order `p + 1` of a cached form (2 to 6).
macro_rules! by_order {
    ($order:expr, $N:ident => $e:expr) => {
        match $order {
            2 => {
                const $N: usize = 2;
                $e
            }
            3 => {
                const $N: usize = 3;
                $e
            }
            4 => {
                const $N: usize = 4;
                $e
            }
            5 => {
                const $N: usize = 5;
                $e
            }
            _ => {
                const $N: usize = 6;
                $e
            }
        }
    };
}

/// The Taylor coefficients of every span and the table finding the span.
pub(crate) struct Pieces<T, P> {
    table: SpanTable,
    order: usize,
    start: T,
    end: T,
    /// `p + 1` coefficients per span, `span − p` major (zero for empty spans).
    coefficients: Vec<P>,
    /// `falling[j][k]` $= k!/(k-j)!$ for `j ≤ k ≤ p`: the factor of `c_k` in the `j`-th
    /// derivative.
    falling: [[T; MAX_CACHED_DEGREE + 1]; MAX_CACHED_DEGREE + 1],
    /// The same form laid out for the batch across SIMD lanes (`f64` only).
    lanes: LaneForm,
}

impl<T: Scalar, P: ControlPoint<T>> Pieces<T, P> {
    /// The Taylor coefficients of every non-empty span of `curve`, or `None` above
    /// [`MAX_CACHED_DEGREE`], for degree 0, or when a span's form would lose accuracy
    /// (see [`CONDITION`]).
    fn new(curve: &impl PieceSource<T, P>) -> Option<Self> {
        if !has_form(curve.knots().degree()) {
            return None;
        }
        let (start, end) = curve.knots().domain();
        let mut pieces = Self {
            table: SpanTable::new(curve.knots()),
            order: 0,
            start,
            end,
            coefficients: Vec::new(),
            falling: [[T::zero(); MAX_CACHED_DEGREE + 1]; MAX_CACHED_DEGREE + 1],
            lanes: LaneForm::default(),
        };
        if !pieces.fill_coefficients(curve) {
            return None;
        }
        pieces.fill_lanes(curve);
        Some(pieces)
    }

    /// Makes these the pieces of `curve`, reusing the storage (no allocation when the curve
    /// has no more spans than the one they were built for); `false` where
    /// [`Pieces::new`] gives `None`.
    fn refill(&mut self, curve: &impl PieceSource<T, P>) -> bool {
        if !self.fill_coefficients(curve) {
            return false;
        }
        self.table.rebuild(curve.knots());
        self.fill_lanes(curve);
        true
    }

    /// The form laid out for the lanes (inactive where they do not apply).
    #[cfg(test)]
    pub(crate) fn lanes(&self) -> &LaneForm {
        &self.lanes
    }

    /// The form for the lanes, once the coefficients and the table are built.
    fn fill_lanes(&mut self, curve: &impl PieceSource<T, P>) {
        self.lanes
            .fill(&self.table, curve.knots(), &self.coefficients, self.order);
    }

    /// Everything but the span table: the Taylor coefficients, the degree and the domain;
    /// `false` where the form is refused.
    fn fill_coefficients(&mut self, curve: &impl PieceSource<T, P>) -> bool {
        let p = curve.knots().degree();
        if !has_form(p) {
            return false;
        }
        let knots = curve.knots();
        let k = knots.knots();
        let n = knots.num_basis();
        let order = p + 1;
        self.coefficients.clear();
        self.coefficients.resize((n - p) * order, P::origin());
        let mut factorial = T::one();
        let mut inverse_factorials = [T::one(); MAX_CACHED_DEGREE + 1];
        for (i, slot) in inverse_factorials
            .iter_mut()
            .enumerate()
            .take(order)
            .skip(1)
        {
            factorial *= from_count::<T>(i);
            *slot = T::one() / factorial;
        }
        for (s, row) in (p..n).zip(self.coefficients.chunks_exact_mut(order)) {
            if k[s] == k[s + 1] {
                continue;
            }
            curve.derivatives_in_span(s, k[s], row);
            row[0] = curve.eval_in_span(s, k[s]);
            for (c, &scale) in row.iter_mut().zip(&inverse_factorials).skip(2) {
                *c = *c * scale;
            }
            // Horner's rounding grows with Σ |c_k| h^k, the triangular scheme's with the
            // largest control point of the span: beyond a factor CONDITION (oscillating
            // control points of degree 4 or 5, where it can reach 3^p) the curve keeps the
            // triangular scheme.
            let h = k[s + 1] - k[s];
            let mut spread = T::zero();
            let mut power = T::one();
            for c in row.iter() {
                spread += c.max_abs() * power;
                power *= h;
            }
            let largest = curve.control_points()[s - p..=s]
                .iter()
                .fold(T::zero(), |m, q| m.max(q.max_abs()));
            if !row.iter().all(ControlPoint::all_finite)
                || !(spread <= from_count::<T>(CONDITION) * largest)
            {
                return false;
            }
        }
        for (j, row) in self.falling.iter_mut().enumerate() {
            for (k, slot) in row.iter_mut().enumerate() {
                *slot = if j < order && k >= j && k < order {
                    from_count::<T>(((k - j + 1)..=k).product::<usize>())
                } else {
                    T::zero()
                };
            }
        }
        let (start, end) = knots.domain();
        self.order = order;
        self.start = start;
        self.end = end;
        true
    }

    /// $C(u)$ from the cached form for `start ≤ u < end`; `None` otherwise (the domain's
    /// end, outside, NaN), where the caller uses the triangular scheme.
    #[inline(always)]
    pub(crate) fn eval_inside(&self, knots: &KnotVector<T>, u: T) -> Option<P> {
        if !(u >= self.start && u < self.end) {
            return None;
        }
        let span = self.table.span(knots, u);
        Some(by_order!(self.order, N => self.horner_in::<N>(knots, span, u)))
    }

    /// $C^{(j)}(u)$, `j = 0 … out.len() − 1`, from the cached form for `start ≤ u < end`
    /// (orders above the degree are zero); `false` otherwise, with `out` untouched.
    #[inline(always)]
    pub(crate) fn derivatives_inside(&self, knots: &KnotVector<T>, u: T, out: &mut [P]) -> bool {
        if !(u >= self.start && u < self.end) {
            return false;
        }
        let span = self.table.span(knots, u);
        by_order!(self.order, N => self.derivatives_in::<N>(knots, span, u, out));
        true
    }

    /// The derivatives of the Taylor form in a known span:
    /// $C^{(j)} = \sum_{k \ge j} \frac{k!}{(k-j)!} c_k t^{k-j}$, each by Horner's scheme.
    #[inline(always)]
    fn derivatives_in<const N: usize>(
        &self,
        knots: &KnotVector<T>,
        span: usize,
        u: T,
        out: &mut [P],
    ) {
        let first = (span - (N - 1)) * N;
        let c: &[P; N] = self.coefficients[first..first + N]
            .try_into()
            .expect("N coefficients per span");
        let t = u - knots.knots()[span];
        for (j, slot) in out.iter_mut().enumerate() {
            if j >= N {
                *slot = P::origin();
                continue;
            }
            let factors = &self.falling[j];
            let mut acc = c[N - 1] * factors[N - 1];
            for k in (j..N - 1).rev() {
                acc = acc * t + c[k] * factors[k];
            }
            *slot = acc;
        }
    }

    /// The span of `u` for `start ≤ u ≤ end`, `None` otherwise (outside, NaN).
    #[inline(always)]
    pub(crate) fn span_inside(&self, knots: &KnotVector<T>, u: T) -> Option<usize> {
        (u >= self.start && u <= self.end).then(|| self.table.span(knots, u))
    }

    /// Writes `map(C(u))` for every parameter (all in the domain); the domain's end goes
    /// through `exact`.
    #[inline]
    pub(crate) fn eval_many_map<Q>(
        &self,
        knots: &KnotVector<T>,
        params: &[T],
        out: &mut [Q],
        map: impl Fn(P) -> Q,
        exact: impl Fn(T) -> P,
    ) {
        if lanes::eval_many_map(&self.lanes, params, out, &map, &exact) {
            return;
        }
        self.eval_many_scalar(knots, params, out, map, exact);
    }

    /// [`Pieces::eval_many_map`] without the lanes: the scalar batch, the reference of the
    /// lanes' tests.
    #[inline]
    pub(crate) fn eval_many_scalar<Q>(
        &self,
        knots: &KnotVector<T>,
        params: &[T],
        out: &mut [Q],
        map: impl Fn(P) -> Q,
        exact: impl Fn(T) -> P,
    ) {
        by_order!(self.order, N => self.many::<N, Q>(knots, params, out, map, exact));
    }

    /// The batch for `N = p + 1`: groups of four points, spans first, so that the four
    /// independent lookups and Horner chains overlap. Points at the domain's end (where the
    /// last span's form would extrapolate) go through `exact`, out of line.
    #[inline(always)]
    fn many<const N: usize, Q>(
        &self,
        knots: &KnotVector<T>,
        params: &[T],
        out: &mut [Q],
        map: impl Fn(P) -> Q,
        exact: impl Fn(T) -> P,
    ) {
        const GROUP: usize = 4;
        let mut groups = out.chunks_exact_mut(GROUP);
        let mut inputs = params.chunks_exact(GROUP);
        for (slots, us) in (&mut groups).zip(&mut inputs) {
            let mut spans = [0; GROUP];
            for (span, &u) in spans.iter_mut().zip(us) {
                *span = self.table.span(knots, u);
            }
            for ((slot, &u), &span) in slots.iter_mut().zip(us).zip(&spans) {
                *slot = map(if u < self.end {
                    self.horner_in::<N>(knots, span, u)
                } else {
                    at_end(&exact, u)
                });
            }
        }
        for (slot, &u) in groups.into_remainder().iter_mut().zip(inputs.remainder()) {
            *slot = map(if u < self.end {
                self.horner::<N>(knots, u)
            } else {
                at_end(&exact, u)
            });
        }
    }

    /// Horner's scheme in the span of `u` (`N = p + 1`).
    #[inline(always)]
    fn horner<const N: usize>(&self, knots: &KnotVector<T>, u: T) -> P {
        self.horner_in::<N>(knots, self.table.span(knots, u), u)
    }

    /// Horner's scheme in a known span.
    #[inline(always)]
    fn horner_in<const N: usize>(&self, knots: &KnotVector<T>, span: usize, u: T) -> P {
        let first = (span - (N - 1)) * N;
        let c: &[P; N] = self.coefficients[first..first + N]
            .try_into()
            .expect("N coefficients per span");
        let t = u - knots.knots()[span];
        let mut acc = c[N - 1];
        for k in (0..N - 1).rev() {
            acc = acc * t + c[k];
        }
        acc
    }
}

/// The exact evaluation at the domain's end, kept out of the batch loop.
#[cold]
#[inline(never)]
fn at_end<T, P>(exact: &impl Fn(T) -> P, u: T) -> P {
    exact(u)
}

/// The cache slot in a `BSpline`: empty, or the pieces (`None` where the degree has no
/// cached form), the number of one-point evaluations since the curve last changed, and the
/// pieces dropped by the last change (their storage is reused by the next build, so that a
/// curve changed and evaluated in a loop — parameter correction — allocates nothing).
pub(crate) struct PieceCache<T, P> {
    pieces: OnceLock<Option<Arc<Pieces<T, P>>>>,
    calls: AtomicUsize,
    spare: Mutex<Option<Arc<Pieces<T, P>>>>,
}

impl<T, P> Default for PieceCache<T, P> {
    fn default() -> Self {
        Self {
            pieces: OnceLock::new(),
            calls: AtomicUsize::new(0),
            spare: Mutex::new(None),
        }
    }
}

impl<T, P> Clone for PieceCache<T, P> {
    /// Clones share the pieces (an `Arc`), not the spare storage.
    fn clone(&self) -> Self {
        Self {
            pieces: self.pieces.clone(),
            calls: AtomicUsize::new(self.calls.load(Ordering::Relaxed)),
            spare: Mutex::new(None),
        }
    }
}

impl<T, P> PieceCache<T, P> {
    /// Drops the pieces: the knots or control points change. Pieces no clone shares are
    /// kept as storage for the next build.
    pub(crate) fn invalidate(&mut self) {
        if let Some(Some(pieces)) = self.pieces.take()
            && Arc::strong_count(&pieces) == 1
        {
            *self.spare.get_mut().unwrap_or_else(PoisonError::into_inner) = Some(pieces);
        }
        *self.calls.get_mut() = 0;
    }
}

impl<T: Scalar, P: ControlPoint<T>> PieceCache<T, P> {
    /// The pieces if they are built.
    #[inline(always)]
    pub(crate) fn get(&self) -> Option<Option<&Pieces<T, P>>> {
        self.pieces.get().map(Option::as_deref)
    }

    /// The pieces, built now if needed.
    pub(crate) fn get_or_build(&self, curve: &impl PieceSource<T, P>) -> Option<&Pieces<T, P>> {
        self.pieces
            .get_or_init(|| {
                let spare = self
                    .spare
                    .lock()
                    .unwrap_or_else(PoisonError::into_inner)
                    .take();
                match spare {
                    Some(mut pieces) => Arc::get_mut(&mut pieces)
                        .is_some_and(|storage| storage.refill(curve))
                        .then_some(pieces),
                    None => Pieces::new(curve).map(Arc::new),
                }
            })
            .as_deref()
    }

    /// Counts a one-point evaluation of a curve with `spans` spans; builds the pieces at the
    /// `spans`-th (a racy count between threads only moves that moment).
    #[inline(always)]
    pub(crate) fn count_call(&self, curve: &impl PieceSource<T, P>, spans: usize) {
        let calls = self.calls.load(Ordering::Relaxed);
        if calls >= spans {
            self.build(curve);
        } else {
            self.calls.store(calls + 1, Ordering::Relaxed);
        }
    }

    #[cold]
    #[inline(never)]
    fn build(&self, curve: &impl PieceSource<T, P>) {
        self.get_or_build(curve);
    }
}
