//! Blossoms of B-spline basis functions: the one primitive behind every transfer between
//! spline spaces (knot insertion, refinement, Bézier extraction, restriction, exact knot
//! removal).
//!
//! The coefficient of the `i`-th B-spline of degree `p` on knots `w` of a spline `f` is the
//! blossom (polar form) of the polynomial piece of `f` on *any* non-empty knot span inside
//! the support of that B-spline, evaluated at `(w_{i+1}, …, w_{i+p})` (de Boor–Fix, Ramshaw).
//! So if `f` is given by its coefficients `c_j` in another space with knots `t`, the new
//! coefficient is `Σ_j c_j · β_j` where `β_j` is the blossom of `N_{j,p,t}` restricted to a
//! suitable span of `t`: one sparse row of `p + 1` entries. With all arguments equal this is
//! the usual basis evaluation; with the arguments of a finer knot vector it is the Oslo
//! algorithm (discrete B-splines).

use nalgebra_sparse::CsrMatrix;
use spline_core::{KnotVector, MAX_ORDER, Scalar, to_f64};

/// Writes into `out[r]`, `r = 0..=p`, the blossom at `args` (length `p`) of the basis function
/// `N_{mu − p + r, p}` restricted to the non-empty span `[t_mu, t_{mu+1})`.
///
/// Basis functions whose index falls outside the knot vector are treated as absent (their
/// entries are zero), so spans near the ends of unclamped knot vectors work too.
pub(crate) fn blossom_basis<T: Scalar>(t: &[T], p: usize, mu: usize, args: &[T], out: &mut [T]) {
    debug_assert!(args.len() >= p);
    debug_assert!(t[mu] < t[mu + 1]);
    let len = t.len();
    for v in out[..=p].iter_mut() {
        *v = T::zero();
    }
    out[p] = T::one();
    // The triangular scheme of The NURBS Book A2.2 with a different argument on each level:
    // one division per entry. Entry r holds the basis function of index mu − p + r.
    for k in 1..=p {
        let x = args[k - 1];
        let mut saved = T::zero();
        for r in p + 1 - k..=p {
            let j = mu as isize - p as isize + r as isize;
            let old = out[r];
            let temp = if j >= 0 && j as usize + k < len && old != T::zero() {
                let j = j as usize;
                let den = t[j + k] - t[j];
                if den > T::zero() {
                    let temp = old / den;
                    out[r - 1] = saved + (t[j + k] - x) * temp;
                    saved = (x - t[j]) * temp;
                    continue;
                }
                T::zero()
            } else {
                T::zero()
            };
            out[r - 1] = saved + temp;
            saved = T::zero();
        }
        out[p] = saved;
    }
}

/// How far the arguments lie outside the span `[s, e]`: the product over the arguments of
/// `(|x − s| + |x − e|) / (e − s)`, a bound on the amplification of rounding errors by the
/// blossom (1 when every argument lies inside the span). Compared in `f64`.
fn extrapolation(s: f64, e: f64, args: &[f64]) -> f64 {
    let h = e - s;
    args.iter()
        .map(|&x| (((x - s).abs() + (x - e).abs()) / h).min(1e9))
        .product()
}

/// How a transfer picks the source span of each row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SpanChoice {
    /// The target space contains the source space: the source span containing `w_i`
    /// (Lyche–Mørken's Oslo algorithm; exact on the whole line, all weights non-negative).
    Refine,
    /// The source space contains the target space (exact knot removal): the span of the
    /// target support where the blossom extrapolates least.
    Remove,
}

/// The length of the prefix of `t` whose knots satisfy `inside` (a predicate true on a
/// prefix), found by moving `cursor` from its previous position: rows are processed in
/// increasing order, so the queries are monotone and the total cost is linear.
fn prefix<T: Scalar>(t: &[T], cursor: &mut usize, inside: impl Fn(T) -> bool) -> usize {
    while *cursor > 0 && !inside(t[*cursor - 1]) {
        *cursor -= 1;
    }
    while *cursor < t.len() && inside(t[*cursor]) {
        *cursor += 1;
    }
    *cursor
}

/// The span of the source knots `t` used for target row `i` (target knots `w`, degree `p`).
/// For removal: among the non-empty source spans that overlap the support
/// `[w_i, w_{i+p+1}]` inside both domains, the one where the blossom extrapolates least.
/// Otherwise (and when the support does not meet the domains) the span containing `w_i`.
fn choose_span<T: Scalar>(
    t: &[T],
    w: &[T],
    p: usize,
    i: usize,
    (lo, hi): (T, T),
    choice: SpanChoice,
    cursors: &mut [usize; 3],
) -> usize {
    let left = if w[i] > lo { w[i] } else { lo };
    let right = if w[i + p + 1] < hi { w[i + p + 1] } else { hi };
    if choice == SpanChoice::Remove && left < right {
        let first = prefix(t, &mut cursors[0], |k| k <= left).saturating_sub(1);
        let last = prefix(t, &mut cursors[1], |k| k < right).saturating_sub(1);
        let mut args = [0.0f64; MAX_ORDER];
        for (a, &x) in args.iter_mut().zip(&w[i + 1..=i + p]) {
            *a = to_f64(x);
        }
        let args = &args[..p];
        let mut best = None;
        let mut best_score = f64::INFINITY;
        for mu in first..=last.min(t.len() - 2) {
            if t[mu] < t[mu + 1] {
                let score = extrapolation(to_f64(t[mu]), to_f64(t[mu + 1]), args);
                if score < best_score || best.is_none() {
                    best_score = score;
                    best = Some(mu);
                }
            }
        }
        if let Some(mu) = best {
            return mu;
        }
    }
    // Outside the domains: the span containing w_i (Lyche–Mørken's choice for the Oslo
    // algorithm), or the last non-empty span.
    let mut mu = prefix(t, &mut cursors[2], |k| k <= w[i]).saturating_sub(1);
    if mu >= t.len() - 1 {
        mu = t.len() - 2;
    }
    while mu > 0 && !(t[mu] < t[mu + 1]) {
        mu -= 1;
    }
    mu
}

/// The matrix taking coefficients on `source` to coefficients on `target` (same degree) by
/// blossoming: exact whenever the function restricted to the target domain lies in the
/// target space (refinement, extraction, restriction; exact knot removal of functions that
/// lie in the coarser space).
pub(crate) fn transfer_matrix<T: Scalar>(
    source: &KnotVector<T>,
    target: &KnotVector<T>,
    choice: SpanChoice,
) -> CsrMatrix<T> {
    let p = source.degree();
    debug_assert_eq!(p, target.degree());
    let t = source.knots();
    let w = target.knots();
    let n_src = source.num_basis();
    let n_dst = target.num_basis();
    let (sa, sb) = source.domain();
    let (ta, tb) = target.domain();
    let lo = if sa > ta { sa } else { ta };
    let hi = if sb < tb { sb } else { tb };
    let mut offsets = Vec::with_capacity(n_dst + 1);
    let mut cols = Vec::with_capacity(n_dst * (p + 1));
    let mut values = Vec::with_capacity(n_dst * (p + 1));
    offsets.push(0);
    let mut beta = [T::zero(); MAX_ORDER];
    let mut cursors = [0usize; 3];
    for i in 0..n_dst {
        let mu = choose_span(t, w, p, i, (lo, hi), choice, &mut cursors);
        blossom_basis(t, p, mu, &w[i + 1..=i + p], &mut beta);
        for (r, &b) in beta[..=p].iter().enumerate() {
            let j = mu as isize - p as isize + r as isize;
            if j >= 0 && (j as usize) < n_src && b != T::zero() {
                cols.push(j as usize);
                values.push(b);
            }
        }
        offsets.push(cols.len());
    }
    CsrMatrix::try_from_csr_data(n_dst, n_src, offsets, cols, values)
        .expect("blossom rows are sorted")
}
