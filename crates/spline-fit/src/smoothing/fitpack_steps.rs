//! FITPACK's steps that the plain fit to a residual target ([`super::residual`]) and the
//! periodic one ([`super::periodic`]) share: how many knots to add next and where
//! (`fpknot`), the search for the smoothing factor (`root_rati` with `fprati`), and the
//! jumps of the `k`-th derivative at the interior knots (`fpdisc`).

use spline_core::{Error, ErrorKind, KnotVector, Result, Scalar, cast, from_count, to_f64};

/// FITPACK's iteration limit for the smoothing factor `p` (`maxit` of `curfit`).
pub const MAX_RESIDUAL_ITERATIONS: usize = 20;

/// How many knots FITPACK adds next (`nplus`), after `nplus` were added last time and the
/// residual fell by `delta` to `fpms` above the target: twice as many if it fell by at most
/// `acc`, else the estimate `nplus · fpms / delta` bounded to `[max(nplus / 2, 1), 2 nplus]`.
pub(super) fn knots_to_add<T: Scalar>(nplus: usize, delta: T, fpms: T, acc: T) -> usize {
    let npl1 = if delta > acc {
        // Python's int(): truncation, bounded before the cast.
        let ratio = (from_count::<T>(nplus) * fpms / delta).floor();
        let cap = from_count::<T>(2 * nplus);
        if ratio >= cap {
            2 * nplus
        } else {
            to_count(ratio)
        }
    } else {
        2 * nplus
    };
    (2 * nplus).min(npl1.max(nplus / 2).max(1))
}

/// FITPACK's search for the smoothing factor `p` with $f(p) = 0$ (scipy's `root_rati`):
/// `f(p)` returns the spline for `p` and its residual minus the target, decreasing in `p`;
/// `(f0, finf)` are its values at `p = 0` (the polynomial, or the constant when periodic) and
/// `p = ∞` (the least-squares spline); `p0` starts the search, `acc` is the accuracy.
/// Rational interpolation `r(p) = (u p + v) / (p + w)` through a bracket, at most
/// [`MAX_RESIDUAL_ITERATIONS`] steps. Returns the last spline, its `f`, its `p` and whether
/// $|f| <$ `acc` (otherwise FITPACK's `ier` 2 or 3: the last iterate is kept).
pub(super) fn root_rati<T: Scalar, S>(
    p0: T,
    (f0, finf): (T, T),
    acc: T,
    mut f: impl FnMut(T) -> Result<(S, T)>,
) -> Result<(S, T, T, bool)> {
    // (p1, f1) = (0, f0), (p3, f3) = (∞, finf); p3 = None is ∞.
    let (con1, con9, con4): (T, T, T) = (cast(0.1), cast(0.9), cast(0.04));
    let (mut p1, mut f1) = (T::zero(), f0);
    let (mut p3, mut f3): (Option<T>, T) = (None, finf);
    let (mut ich1, mut ich3) = (false, false);
    let mut p = p0;
    let mut last = None;
    for _ in 0..MAX_RESIDUAL_ITERATIONS {
        let (state, f2) = f(p)?;
        let p2 = p;
        if f2.abs() < acc {
            return Ok((state, f2, p2, true));
        }
        last = Some((state, f2, p2));
        if !ich3 {
            if f2 - f3 <= acc {
                p3 = Some(p2);
                f3 = f2;
                p *= con4;
                if p <= p1 {
                    p = p1 * con9 + p2 * con1;
                }
                continue;
            }
            if f2 < T::zero() {
                ich3 = true;
            }
        }
        if !ich1 {
            if f1 - f2 <= acc {
                p1 = p2;
                f1 = f2;
                p /= con4;
                // scipy's test (FITPACK's is p ≥ p3).
                if let Some(p3v) = p3
                    && p <= p3v
                {
                    p = p2 * con1 + p3v * con9;
                }
                continue;
            }
            if f2 > T::zero() {
                ich1 = true;
            }
        }
        if f1 <= f2 || f2 <= f3 {
            break;
        }
        p = fprati(p1, f1, p2, f2, p3, f3);
        if f2 < T::zero() {
            p3 = Some(p2);
            f3 = f2;
        } else {
            p1 = p2;
            f1 = f2;
        }
    }
    let (state, f2, p2) = last.expect("at least one iteration");
    Ok((state, f2, p2, false))
}

/// A non-negative whole number held in a scalar, as a count.
fn to_count<T: Scalar>(x: T) -> usize {
    let v = to_f64(x);
    if v <= 0.0 {
        0
    } else if v >= usize::MAX as f64 {
        usize::MAX
    } else {
        // Exact: `v` is a whole number below usize::MAX.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = v as usize;
        n
    }
}

/// FITPACK's `fprati`: the zero of the rational function $r(p) = (u p + v)/(p + w)$ through
/// three points (`p3 = None` for $p_3 = \infty$).
fn fprati<T: Scalar>(p1: T, f1: T, p2: T, f2: T, p3: Option<T>, f3: T) -> T {
    let h1 = f1 * (f2 - f3);
    let h2 = f2 * (f3 - f1);
    let h3 = f3 * (f1 - f2);
    match p3 {
        None => -(p2 * h1 + p1 * h2) / h3,
        Some(p3) => -(p1 * p2 * h3 + p2 * p3 * h1 + p1 * p3 * h2) / (p1 * h1 + p2 * h2 + p3 * h3),
    }
}

/// FITPACK's new knot (`fpknot`, as scipy's `_dierckx.fpknot`): the data are split into
/// runs between consecutive knots (a datum on a knot shares its residual between the two
/// runs); in the run with the largest residual sum among those with more than one interior
/// step, the datum in the middle becomes a knot.
pub(super) fn add_knot<T: Scalar>(
    x: &[T],
    t: &KnotVector<T>,
    residuals: &[T],
) -> Result<KnotVector<T>> {
    let k = t.degree();
    let knots = t.knots();
    let nc = t.num_basis();
    let mut interval = k + 1;
    let mut ix = vec![0usize];
    let mut parts = Vec::new();
    let mut part = T::zero();
    let half: T = cast(0.5);
    for (i, (&xv, &r)) in x.iter().zip(residuals).enumerate() {
        part += r;
        if interval < nc && xv >= knots[interval] {
            let carry = r * half;
            part -= carry;
            parts.push(part);
            part = carry;
            interval += 1;
            ix.push(i);
        }
    }
    ix.push(x.len() - 1);
    parts.push(part);
    let mut best: Option<(usize, T)> = None;
    for (i, &f) in parts.iter().enumerate() {
        if ix[i + 1] - ix[i] > 1 && best.is_none_or(|(_, b)| f > b) {
            best = Some((i, f));
        }
    }
    let Some((i, _)) = best else {
        return Err(Error::new(
            ErrorKind::NoConvergence,
            "no knot interval holds enough data for another knot",
        ));
    };
    let new = x[(ix[i] + ix[i + 1]).div_ceil(2)];
    let at = knots.partition_point(|&v| v < new);
    let mut all = Vec::with_capacity(knots.len() + 1);
    all.extend_from_slice(&knots[..at]);
    all.push(new);
    all.extend_from_slice(&knots[at..]);
    KnotVector::new(k, all)
}

/// The rows of FITPACK's discontinuity matrix (`fpdisc`, scipy's `disc`): for each interior
/// knot $t_j$ the jumps of the `k`-th derivatives of the `k + 2` B-splines around it, up to
/// FITPACK's normalisation $(\delta / \text{nrint})^k$ ($\delta$ the length of the domain,
/// `nrint` its number of knot intervals). Row `(first, values)` acts on coefficients
/// `first … first + k + 1`.
pub(super) fn jump_rows<T: Scalar>(t: &[T], k: usize) -> Vec<(usize, Vec<T>)> {
    let n = t.len();
    let delta = t[n - k - 1] - t[k];
    let nrint = n - 2 * k - 1;
    let factor = (delta / from_count::<T>(nrint)).powi(i32::try_from(k).unwrap_or(i32::MAX));
    (0..nrint - 1)
        .map(|jj| {
            let j = jj + k + 1;
            let row = (0..k + 2)
                .map(|ii| {
                    let i = jj + ii;
                    let prod = (0..k + 2)
                        .filter(|&s| i + s != j)
                        .fold(T::one(), |acc, s| acc * (t[j] - t[i + s]));
                    (t[i + k + 1] - t[i]) / prod * factor
                })
                .collect();
            (jj, row)
        })
        .collect()
}
