//! The two kernels behind every structural operation, generic over the point type:
//!
//! - [`refine_in_place`]: knot refinement (The NURBS Book A5.4), which also serves insertion,
//!   clamping, restriction, splitting and Bézier extraction (refine, then slice);
//! - [`reduce_points`]: the transfer onto a space contained in the source space (exact knot
//!   removal, the last step of degree elevation, unclamping), where every target
//!   coefficient is a blossom of one polynomial piece (de Boor–Fix, Ramshaw).
//!
//! The coefficient of the `i`-th B-spline of degree `p` on knots `w` of a spline `f` is the
//! blossom of the polynomial piece of `f` on *any* non-empty knot span inside the support of
//! that B-spline, evaluated at `(w_{i+1}, …, w_{i+p})`. With `f` given by coefficients `c_j`
//! on knots `t`, that is `Σ_j c_j β_j` with `β_j` the blossom of `N_{j,p,t}` restricted to
//! the chosen span: one row of `p + 1` weights. The span is the one of the target support
//! where the blossom extrapolates least, so no difference of close knots is ever divided
//! by. A target B-spline equal to a source one (same `p + 2` knots) takes its coefficient
//! unchanged.

use spline_core::{KnotVector, MAX_ORDER, Scalar, VectorSpace, to_f64};

/// Inserts the sorted knots `x` (inside the domain, multiplicities checked by the caller)
/// into the spline with coefficients `points` on `knot_vector` (The NURBS Book A5.4, in
/// `O(n + r p)`), in the vectors themselves: both grow by `x.len()` and are updated from
/// the back, so that every old value is read before its slot is written. No allocation
/// beyond the growth of the two vectors.
// The indices mirror A5.4 so that the code can be checked against the book: `old(i)` is
// the old knot `i`, still in place whenever it is read (every write lands above it).
#[allow(clippy::many_single_char_names)]
pub(crate) fn refine_in_place<T: Scalar, V: VectorSpace<T>>(
    knot_vector: &mut KnotVector<T>,
    points: &mut Vec<V>,
    x: &[T],
) {
    if x.is_empty() {
        return;
    }
    let first = knot_vector.span_in_domain(x[0]);
    let last = knot_vector.span_in_domain(x[x.len() - 1]);
    refine_in_spans(knot_vector, points, x, first, last);
}

/// [`refine_in_place`] with the spans of the first and last new knot known.
pub(crate) fn refine_in_spans<T: Scalar, V: VectorSpace<T>>(
    knot_vector: &mut KnotVector<T>,
    points: &mut Vec<V>,
    x: &[T],
    first: usize,
    last: usize,
) {
    if x.is_empty() {
        return;
    }
    let p = knot_vector.degree();
    knot_vector.update_unchecked(|knots| refine_vectors(p, (first, last + 1), knots, points, x));
}

#[allow(clippy::many_single_char_names)]
fn refine_vectors<T: Scalar, V: VectorSpace<T>>(
    p: usize,
    (a, b): (usize, usize),
    knots: &mut Vec<T>,
    points: &mut Vec<V>,
    x: &[T],
) {
    let n = points.len() - 1; // index of the last control point
    let m = n + p + 1; // index of the last knot
    let r = x.len() - 1;
    // Shift the unchanged tails right by r + 1 (one memmove each; old values below b − 1
    // and b + p stay put).
    points.resize(n + r + 2, V::zero_vector());
    points[b - 1..].rotate_right(r + 1);
    knots.resize(m + r + 2, T::zero());
    knots[b + p..].rotate_right(r + 1);
    let mut i = b + p - 1;
    let mut k = b + p + r;
    for j in (0..=r).rev() {
        while x[j] <= knots[i] && i > a {
            points[k - p - 1] = points[i - p - 1].clone();
            knots[k] = knots[i];
            k -= 1;
            i -= 1;
        }
        points[k - p - 1] = points[k - p].clone();
        // Slices of exactly the lengths the loop reads (no bounds checks inside it):
        // points k − p … k, knots k + 1 … k + p and i + 1 − p … i.
        let window = &mut points[k - p..=k];
        let (right, left) = (&knots[k + 1..=k + p], &knots[i + 1 - p..=i]);
        for l in 0..p {
            let alpha = right[l] - x[j];
            window[l] = if alpha == T::zero() {
                window[l + 1].clone()
            } else {
                let alpha = alpha / (right[l] - left[l]);
                window[l].combine(alpha, &window[l + 1], T::one() - alpha)
            };
        }
        knots[k] = x[j];
        k -= 1;
    }
}

/// Writes into `out[r]`, `r = 0..=p`, the blossom at `args` (length `p`) of the basis
/// function `N_{mu − p + r, p}` restricted to the non-empty span `[t_mu, t_{mu+1})`.
///
/// Basis functions whose index falls outside the knot vector are treated as absent (their
/// entries are zero), so spans near the ends of unclamped knot vectors work too.
fn blossom_basis<T: Scalar>(t: &[T], p: usize, mu: usize, args: &[T], out: &mut [T]) {
    debug_assert!(args.len() >= p);
    debug_assert!(t[mu] < t[mu + 1]);
    let len = t.len();
    for v in &mut out[..=p] {
        *v = T::zero();
    }
    out[p] = T::one();
    // The triangular scheme of The NURBS Book A2.2 with a different argument on each level:
    // one division per entry. Entry r holds the basis function of index mu − p + r.
    for k in 1..=p {
        let x = args[k - 1];
        let mut saved = T::zero();
        for r in p + 1 - k..=p {
            let j = mu + r;
            let old = out[r];
            // Index of the basis function: mu − p + r (absent when negative).
            if j >= p && j - p + k < len && old != T::zero() {
                let j = j - p;
                let den = t[j + k] - t[j];
                if den > T::zero() {
                    let temp = old / den;
                    out[r - 1] = saved + (t[j + k] - x) * temp;
                    saved = (x - t[j]) * temp;
                    continue;
                }
            }
            out[r - 1] = saved;
            saved = T::zero();
        }
        out[p] = saved;
    }
}

/// How far the arguments lie outside the span `[s, e]`: the product over the arguments of
/// `(|x − s| + |x − e|) / (e − s)`, a bound on the amplification of rounding errors by the
/// blossom (1 when every argument lies inside the span).
fn extrapolation<T: Scalar>(s: f64, e: f64, args: &[T]) -> f64 {
    let h = e - s;
    let mut score = 1.0;
    for &x in args {
        let x = to_f64(x);
        if x < s || x > e {
            score *= (((x - s).abs() + (x - e).abs()) / h).min(1e9);
        }
    }
    score
}

/// The span of the source used for target row `i` (target knots `w`, degree `p`, `lo < hi`
/// the intersection of the domains): among the non-empty source spans (`spans`, indices
/// with their ends) that overlap the support `[w_i, w_{i+p+1}]` inside the domains, the
/// one where the blossom extrapolates least; the span containing `w_i` if the support does
/// not meet the domains. `cursor` is the first candidate of the previous row (rows come in
/// increasing order, so the total cost of moving it is linear).
fn choose_span<T: Scalar>(
    spans: &[(usize, f64, f64)],
    w: &[T],
    p: usize,
    i: usize,
    (lo, hi): (T, T),
    cursor: &mut usize,
) -> usize {
    let left = to_f64(if w[i] > lo { w[i] } else { lo });
    let right = to_f64(if w[i + p + 1] < hi { w[i + p + 1] } else { hi });
    // The first span ending after `left`.
    while *cursor + 1 < spans.len() && spans[*cursor].2 <= left {
        *cursor += 1;
    }
    if left < right {
        let args = &w[i + 1..=i + p];
        let mut best = spans[*cursor].0;
        let mut best_score = f64::INFINITY;
        for &(mu, s, e) in &spans[*cursor..] {
            if s >= right {
                break;
            }
            let score = extrapolation(s, e, args);
            if score < best_score {
                best_score = score;
                best = mu;
                if score == 1.0 {
                    break;
                }
            }
        }
        return best;
    }
    // The span containing w_i, or the last one before it.
    let x = to_f64(w[i]);
    let k = spans.partition_point(|&(_, s, _)| s <= x).saturating_sub(1);
    spans[k].0
}

/// The coefficients on `target` of the spline with coefficients `points` on `source`, for
/// a target space contained in the source space on the target's domain (same degree):
/// exact for splines that lie in the target space, a local quasi-interpolant otherwise.
pub(crate) fn reduce_points<T: Scalar, V: VectorSpace<T>>(
    source: &KnotVector<T>,
    target: &KnotVector<T>,
    points: &[V],
) -> Vec<V> {
    if source == target {
        return points.to_vec();
    }
    let p = source.degree();
    debug_assert_eq!(p, target.degree());
    let t = source.knots();
    let w = target.knots();
    let (sa, sb) = source.domain();
    let (ta, tb) = target.domain();
    let lo = if sa > ta { sa } else { ta };
    let hi = if sb < tb { sb } else { tb };
    let spans: Vec<(usize, f64, f64)> = (0..t.len() - 1)
        .filter(|&mu| t[mu] < t[mu + 1])
        .map(|mu| (mu, to_f64(t[mu]), to_f64(t[mu + 1])))
        .collect();
    let mut beta = [T::zero(); MAX_ORDER];
    let mut cursor = 0;
    let mut out = Vec::with_capacity(target.num_basis());
    // Ends of the runs of equal knots containing w_i, in w and in t.
    let (mut run_w, mut run_t) = (0usize, 0usize);
    for i in 0..target.num_basis() {
        if i == 0 || w[i] != w[i - 1] {
            while run_w < w.len() && w[run_w] <= w[i] {
                run_w += 1;
            }
            while run_t < t.len() && t[run_t] <= w[i] {
                run_t += 1;
            }
        }
        // The source B-spline with the same knots, aligned on the ends of the runs.
        if let Some(j) = (run_t + i).checked_sub(run_w) {
            // (The ends first: most rows differ there, and the slice comparison is slower.)
            if j + p + 1 < t.len()
                && t[j + p + 1] == w[i + p + 1]
                && t[j] == w[i]
                && t[j..=j + p + 1] == w[i..=i + p + 1]
            {
                out.push(points[j].clone());
                continue;
            }
        }
        let mu = choose_span(&spans, w, p, i, (lo, hi), &mut cursor);
        let args = &w[i + 1..=i + p];
        let mut acc = V::zero_vector();
        if mu >= p && mu + p < t.len() && mu < points.len() {
            // Every basis function of the span exists: no checks in the inner loop; a
            // Bézier piece (both ends of multiplicity p + 1) needs no division at all.
            if t[mu - p] == t[mu] && t[mu + 1] == t[mu + p + 1] {
                // Arguments all at the piece's ends: the blossom is the Bézier point with
                // as many arguments at the right end (the triangular scheme would compute
                // exactly that, with weights 0 and 1).
                let (a, b) = (t[mu], t[mu + 1]);
                if args.iter().all(|&x| x == a || x == b) {
                    let right = args.iter().filter(|&&x| x == b).count();
                    out.push(points[mu - p + right].clone());
                    continue;
                }
                let piece = &points[mu - p..=mu];
                let fixed = match p {
                    1 => Some(bezier_blossom::<T, V, 2>(a, b, args, piece)),
                    2 => Some(bezier_blossom::<T, V, 3>(a, b, args, piece)),
                    3 => Some(bezier_blossom::<T, V, 4>(a, b, args, piece)),
                    4 => Some(bezier_blossom::<T, V, 5>(a, b, args, piece)),
                    5 => Some(bezier_blossom::<T, V, 6>(a, b, args, piece)),
                    _ => None,
                };
                if let Some(point) = fixed {
                    out.push(point);
                    continue;
                }
                blossom_bernstein(a, b, p, args, &mut beta);
            } else {
                blossom_basis_inside(t, p, mu, args, &mut beta);
            }
            for (point, &b) in points[mu - p..=mu].iter().zip(&beta[..=p]) {
                acc.add_scaled(point, b);
            }
        } else {
            blossom_basis(t, p, mu, args, &mut beta);
            for (r, &b) in beta[..=p].iter().enumerate() {
                // The basis function of index mu − p + r, absent below 0 and above n − 1.
                if b != T::zero() && mu + r >= p && mu + r - p < points.len() {
                    acc.add_scaled(&points[mu + r - p], b);
                }
            }
        }
        out.push(acc);
    }
    out
}

/// [`blossom_basis`] for a span whose `p + 1` basis functions all exist
/// (`p ≤ mu` and `mu + p < t.len()`): every denominator is positive.
fn blossom_basis_inside<T: Scalar>(t: &[T], p: usize, mu: usize, args: &[T], out: &mut [T]) {
    out[p] = T::one();
    for k in 1..=p {
        let x = args[k - 1];
        let mut saved = T::zero();
        for r in p + 1 - k..=p {
            let j = mu + r - p;
            let temp = out[r] / (t[j + k] - t[j]);
            out[r - 1] = saved + (t[j + k] - x) * temp;
            saved = (x - t[j]) * temp;
        }
        out[p] = saved;
    }
}

/// The blossom at `args` of the Bézier piece on `[a, b]` with control points `points`, for
/// `N = p + 1` (arrays of exactly `N` entries, so that the constant degree unrolls
/// [`blossom_bernstein`]).
#[inline(always)]
fn bezier_blossom<T: Scalar, V: VectorSpace<T>, const N: usize>(
    a: T,
    b: T,
    args: &[T],
    points: &[V],
) -> V {
    let mut beta = [T::zero(); N];
    blossom_bernstein(a, b, N - 1, args, &mut beta);
    let mut acc = V::zero_vector();
    for (point, &weight) in points[..N].iter().zip(&beta) {
        acc.add_scaled(point, weight);
    }
    acc
}

/// [`blossom_basis`] for a Bézier piece on `[a, b]` (both ends of multiplicity `p + 1`):
/// the blossom of the Bernstein polynomials, with the local parameters
/// $\lambda_k = (x_k - a)/(b - a)$ of the arguments.
#[inline(always)]
fn blossom_bernstein<T: Scalar>(a: T, b: T, p: usize, args: &[T], out: &mut [T]) {
    let inv = T::one() / (b - a);
    out[p] = T::one();
    for k in 1..=p {
        let lambda = (args[k - 1] - a) * inv;
        let mu = T::one() - lambda;
        let mut saved = T::zero();
        for r in p + 1 - k..=p {
            let old = out[r];
            out[r - 1] = saved + mu * old;
            saved = lambda * old;
        }
        out[p] = saved;
    }
}
