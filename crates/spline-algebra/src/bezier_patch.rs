//! Scalar Bézier patches on their domains, as the surface features evaluate them: values
//! and first partial derivatives from the Bernstein bases (`O(p)` each, binomials from a
//! table), enclosures from the convex hull of the coefficients, de Casteljau halving, and
//! the restriction to a grid line, along which each value then costs `O(degree)`.

use crate::ridge_function::{Interval, Jet, Num};
use spline_geom::Surface;

/// A scalar Bézier patch (Bernstein coefficients, row-major, `i` along `u`) on its domain.
#[derive(Clone, Debug)]
pub(crate) struct Patch {
    pub(crate) c: Vec<f64>,
    pub(crate) p: usize,
    pub(crate) q: usize,
    pub(crate) u: (f64, f64),
    pub(crate) v: (f64, f64),
}

/// The Bernstein basis of degree `p` at `t ∈ [0, 1]` and its derivative, into `b` and `db`
/// (at least `p + 1` long), in `O(p)`: $B^p_i = \binom{p}{i} t^i (1 - t)^{p - i}$ from the
/// powers of `t` and `1 − t`, and $B^{p\prime}_i = p\,(B^{p-1}_{i-1} - B^{p-1}_i)$.
fn bernstein_into(p: usize, t: f64, b: &mut [f64], db: &mut [f64]) {
    if p == 0 {
        b[0] = 1.0;
        db[0] = 0.0;
        return;
    }
    let s = 1.0 - t;
    // b[i] ← tⁱ, db[i] ← (1 − t)ⁱ for i ≤ p (the powers, replaced below).
    b[0] = 1.0;
    db[0] = 1.0;
    for i in 1..=p {
        b[i] = b[i - 1] * t;
        db[i] = db[i - 1] * s;
    }
    // Degree p − 1 first: lower[i] = C(p − 1, i) tⁱ (1 − t)^(p − 1 − i), kept for the
    // derivative; then degree p.
    let mut lower = [0.0; STACK_DEGREE + 1];
    let mut lower_heap = Vec::new();
    let lower: &mut [f64] = if p <= STACK_DEGREE {
        &mut lower[..p]
    } else {
        lower_heap.resize(p, 0.0);
        &mut lower_heap
    };
    for (i, x) in lower.iter_mut().enumerate() {
        *x = binomial(p - 1, i) * b[i] * db[p - 1 - i];
    }
    for i in 0..=p {
        b[i] *= binomial(p, i) * db[p - i];
    }
    let pf = p as f64;
    for i in 0..=p {
        let left = if i > 0 { lower[i - 1] } else { 0.0 };
        let right = if i < p { lower[i] } else { 0.0 };
        db[i] = pf * (left - right);
    }
}

/// The binomial coefficients `C(n, k)` for `n ≤ STACK_DEGREE`, exact (below 2⁵³).
static BINOMIALS: [[f64; STACK_DEGREE + 1]; STACK_DEGREE + 1] = {
    let mut whole = [[0u64; STACK_DEGREE + 1]; STACK_DEGREE + 1];
    let mut out = [[0.0; STACK_DEGREE + 1]; STACK_DEGREE + 1];
    let mut n = 0;
    while n <= STACK_DEGREE {
        let mut k = 0;
        while k <= n {
            whole[n][k] = if k == 0 || k == n {
                1
            } else {
                whole[n - 1][k - 1] + whole[n - 1][k]
            };
            // Exact: every coefficient up to C(47, 23) ≈ 1.6·10¹³ is below 2⁵³.
            #[allow(clippy::cast_precision_loss)]
            let x = whole[n][k] as f64;
            out[n][k] = x;
            k += 1;
        }
        n += 1;
    }
    out
};

/// `C(n, k)`: from the table up to [`STACK_DEGREE`], by the product formula above.
fn binomial(n: usize, k: usize) -> f64 {
    if n <= STACK_DEGREE {
        BINOMIALS[n][k]
    } else {
        (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
    }
}

/// Degrees up to this use a basis on the stack in [`Patch::jet`].
const STACK_DEGREE: usize = 47;

/// A Bernstein basis and its derivative at one parameter, for one degree and interval.
struct Basis {
    key: (usize, f64, f64),
    b: [f64; STACK_DEGREE + 1],
    db: [f64; STACK_DEGREE + 1],
}

impl Basis {
    fn new() -> Self {
        Self {
            key: (usize::MAX, 0.0, 0.0),
            b: [0.0; STACK_DEGREE + 1],
            db: [0.0; STACK_DEGREE + 1],
        }
    }

    /// Recomputes the basis unless it is already that of degree `p` at `x` on `(a, b)`.
    fn at(&mut self, p: usize, x: f64, (a, b): (f64, f64)) {
        let key = (p, a, b);
        if self.key != key {
            bernstein_into(p, (x - a) / (b - a), &mut self.b, &mut self.db);
            self.key = key;
        }
    }
}

/// A patch on a line of constant `v` or `u` ([`Patch::restricted`]): its jets along the
/// line cost `O(degree)` instead of `O(p q)`.
pub(crate) struct LineRestriction {
    /// Whether the line runs along `u` (constant `v`).
    along_u: bool,
    /// The degree along the line.
    degree: usize,
    /// The patch's interval along the line.
    interval: (f64, f64),
    /// The widths of the patch's intervals in `u` and `v`.
    widths: (f64, f64),
    /// Bernstein coefficients of the value along the line.
    value: Vec<f64>,
    /// Bernstein coefficients of the derivative across the line (per unit of the
    /// patch's own parameter across it).
    across: Vec<f64>,
}

impl LineRestriction {
    /// The Bernstein coefficients of the value along the line.
    pub(crate) fn into_values(self) -> Vec<f64> {
        self.value
    }

    /// Value and partial derivatives `[f, ∂f/∂u, ∂f/∂v]` from the basis along the line and
    /// its derivative.
    fn combine(&self, b: &[f64], db: &[f64]) -> Jet<f64> {
        let (mut f, mut along, mut across) = (0.0, 0.0, 0.0);
        for k in 0..=self.degree {
            f += b[k] * self.value[k];
            along += db[k] * self.value[k];
            across += b[k] * self.across[k];
        }
        let (wu, wv) = self.widths;
        if self.along_u {
            [f, along / wu, across / wv]
        } else {
            [f, across / wu, along / wv]
        }
    }

    /// The jets of several restrictions to one line at the parameter `x` along it, each
    /// basis computed once per degree and interval.
    pub(crate) fn jets<const N: usize>(lines: &[Self; N], x: f64) -> [Jet<f64>; N] {
        let mut basis = Basis::new();
        std::array::from_fn(|i| {
            let line = &lines[i];
            if line.degree > STACK_DEGREE {
                let mut b = vec![0.0; line.degree + 1];
                let mut db = vec![0.0; line.degree + 1];
                let (a, c) = line.interval;
                bernstein_into(line.degree, (x - a) / (c - a), &mut b, &mut db);
                return line.combine(&b, &db);
            }
            basis.at(line.degree, x, line.interval);
            line.combine(&basis.b, &basis.db)
        })
    }
}

impl Patch {
    /// The patch of a scalar spline already in single-patch Bernstein form.
    pub(crate) fn of(s: &Surface<f64, f64>) -> Self {
        let (p, q) = s.degrees();
        let (u, v) = s.domain();
        Self {
            c: s.control_points().to_vec(),
            p,
            q,
            u,
            v,
        }
    }

    /// The constant 1 on a domain.
    pub(crate) fn one(u: (f64, f64), v: (f64, f64)) -> Self {
        Self {
            c: vec![1.0],
            p: 0,
            q: 0,
            u,
            v,
        }
    }

    /// Value and partial derivatives at `(u, v)`.
    pub(crate) fn jet(&self, u: f64, v: f64) -> Jet<f64> {
        if self.p > STACK_DEGREE || self.q > STACK_DEGREE {
            let (mut bu, mut dbu) = (vec![0.0; self.p + 1], vec![0.0; self.p + 1]);
            let (mut bv, mut dbv) = (vec![0.0; self.q + 1], vec![0.0; self.q + 1]);
            bernstein_into(
                self.p,
                (u - self.u.0) / (self.u.1 - self.u.0),
                &mut bu,
                &mut dbu,
            );
            bernstein_into(
                self.q,
                (v - self.v.0) / (self.v.1 - self.v.0),
                &mut bv,
                &mut dbv,
            );
            return self.combine(&bu, &dbu, &bv, &dbv);
        }
        let (mut bu, mut bv) = (Basis::new(), Basis::new());
        bu.at(self.p, u, self.u);
        bv.at(self.q, v, self.v);
        self.combine(&bu.b, &bu.db, &bv.b, &bv.db)
    }

    /// The jets of several patches at one point, each basis computed once per degree and
    /// interval (equal to [`Patch::jet`] of each, bit for bit).
    pub(crate) fn jets<const N: usize>(patches: &[Patch; N], u: f64, v: f64) -> [Jet<f64>; N] {
        let (mut bu, mut bv) = (Basis::new(), Basis::new());
        std::array::from_fn(|i| {
            let f = &patches[i];
            if f.p > STACK_DEGREE || f.q > STACK_DEGREE {
                return f.jet(u, v);
            }
            bu.at(f.p, u, f.u);
            bv.at(f.q, v, f.v);
            f.combine(&bu.b, &bu.db, &bv.b, &bv.db)
        })
    }

    /// Value and partial derivatives from the bases in `u` and `v` and their derivatives.
    fn combine(&self, bu: &[f64], dbu: &[f64], bv: &[f64], dbv: &[f64]) -> Jet<f64> {
        let (wu, wv) = (self.u.1 - self.u.0, self.v.1 - self.v.0);
        let nv = self.q + 1;
        let mut out = [0.0; 3];
        for (i, row) in self.c.chunks_exact(nv).enumerate().take(self.p + 1) {
            let (mut r0, mut r1) = (0.0, 0.0);
            for (j, &c) in row.iter().enumerate() {
                r0 += c * bv[j];
                r1 += c * dbv[j];
            }
            out[0] += bu[i] * r0;
            out[1] += dbu[i] * r0;
            out[2] += bu[i] * r1;
        }
        out[1] /= wu;
        out[2] /= wv;
        out
    }

    /// Enclosures of the value and the partial derivatives on the whole patch (convex hull
    /// of the Bernstein coefficients and of their differences).
    pub(crate) fn bounds(&self) -> Jet<Interval> {
        let empty = Interval {
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
        };
        let widen = |r: &mut Interval, x: f64| {
            r.lo = r.lo.min(x);
            r.hi = r.hi.max(x);
        };
        let nv = self.q + 1;
        let c = &self.c;
        let (p, q) = (self.p, self.q);
        let su = p as f64 / (self.u.1 - self.u.0);
        let sv = q as f64 / (self.v.1 - self.v.0);
        let mut out = [empty; 3];
        for (i, row) in c.chunks_exact(nv).enumerate().take(p + 1) {
            for (j, &x) in row.iter().enumerate() {
                widen(&mut out[0], x);
                if i < p {
                    widen(&mut out[1], su * (c[(i + 1) * nv + j] - x));
                }
                if j < q {
                    widen(&mut out[2], sv * (row[j + 1] - x));
                }
            }
        }
        out.map(|r| {
            if r.lo > r.hi {
                Interval::constant(0.0)
            } else {
                r
            }
        })
    }

    /// The patch on the line `v = fixed` (`along_u`) or `u = fixed`: per Bernstein
    /// coefficient along the line, the value of the patch and its derivative across it.
    pub(crate) fn restricted(&self, along_u: bool, fixed: f64) -> LineRestriction {
        let (p, q) = (self.p, self.q);
        let nv = q + 1;
        let (degree, across_degree, across_interval) = if along_u {
            (p, q, self.v)
        } else {
            (q, p, self.u)
        };
        let mut b = vec![0.0; across_degree + 1];
        let mut db = vec![0.0; across_degree + 1];
        bernstein_into(
            across_degree,
            (fixed - across_interval.0) / (across_interval.1 - across_interval.0),
            &mut b,
            &mut db,
        );
        let (mut value, mut across) = (vec![0.0; degree + 1], vec![0.0; degree + 1]);
        for (i, row) in self.c.chunks_exact(nv).enumerate().take(p + 1) {
            for (j, &c) in row.iter().enumerate() {
                if along_u {
                    value[i] += c * b[j];
                    across[i] += c * db[j];
                } else {
                    value[j] += b[i] * c;
                    across[j] += db[i] * c;
                }
            }
        }
        LineRestriction {
            along_u,
            degree,
            interval: if along_u { self.u } else { self.v },
            widths: (self.u.1 - self.u.0, self.v.1 - self.v.0),
            value,
            across,
        }
    }

    /// De Casteljau halving along `u` (`along_u`) or `v`.
    pub(crate) fn halves(&self, along_u: bool) -> (Self, Self) {
        let (mut left, mut right) = (self.clone(), self.clone());
        self.halves_into(along_u, &mut left, &mut right);
        (left, right)
    }

    /// [`Patch::halves`] into `left` and `right` (their buffers reused: no allocation once
    /// they have the size of this patch's coefficients).
    pub(crate) fn halves_into(&self, along_u: bool, left: &mut Self, right: &mut Self) {
        let (n, m) = if along_u {
            (self.p, self.q)
        } else {
            (self.q, self.p)
        };
        let nv = self.q + 1;
        let at = |line: usize, k: usize| {
            if along_u {
                line + k * nv
            } else {
                line * nv + k
            }
        };
        for half in [&mut *left, &mut *right] {
            half.c.resize(self.c.len(), 0.0);
            (half.p, half.q, half.u, half.v) = (self.p, self.q, self.u, self.v);
        }
        let mut stack = [0.0; STACK_DEGREE + 1];
        let mut heap = Vec::new();
        let work: &mut [f64] = if n <= STACK_DEGREE {
            &mut stack[..=n]
        } else {
            heap.resize(n + 1, 0.0);
            &mut heap
        };
        for line in 0..=m {
            for (k, w) in work.iter_mut().enumerate() {
                *w = self.c[at(line, k)];
            }
            for r in 0..=n {
                left.c[at(line, r)] = work[0];
                right.c[at(line, n - r)] = work[n - r];
                for k in 0..n - r {
                    work[k] = 0.5 * (work[k] + work[k + 1]);
                }
            }
        }
        if along_u {
            let mid = 0.5 * (self.u.0 + self.u.1);
            left.u.1 = mid;
            right.u.0 = mid;
        } else {
            let mid = 0.5 * (self.v.0 + self.v.1);
            left.v.1 = mid;
            right.v.0 = mid;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::bernstein_into;

    /// The basis and its derivative against the definition (binomials and powers computed
    /// independently, the derivative by central differences), for degrees 0 to 60 (past the
    /// stack buffer).
    #[test]
    fn bernstein_basis_against_the_definition() {
        for p in 0..=60usize {
            for &t in &[0.0, 1e-3, 0.25, 0.5, 0.713, 0.999, 1.0] {
                let (mut b, mut db) = (vec![0.0; p + 1], vec![0.0; p + 1]);
                bernstein_into(p, t, &mut b, &mut db);
                let exact = |i: usize, t: f64| {
                    let c: f64 = (0..i).map(|k| (p - k) as f64 / (k + 1) as f64).product();
                    c * t.powi(i as i32) * (1.0 - t).powi((p - i) as i32)
                };
                assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-13, "p {p} t {t}");
                let h = 1e-6;
                for i in 0..=p {
                    assert!(
                        (b[i] - exact(i, t)).abs() <= 1e-14 * (1.0 + exact(i, t)),
                        "p {p} i {i} t {t}"
                    );
                    if t > h && t < 1.0 - h {
                        let fd = (exact(i, t + h) - exact(i, t - h)) / (2.0 * h);
                        assert!(
                            (db[i] - fd).abs() <= 1e-6 * (1.0 + fd.abs()) * p as f64,
                            "p {p} i {i} t {t}: {} {fd}",
                            db[i]
                        );
                    }
                }
                assert!(
                    db.iter().sum::<f64>().abs() < 1e-10 * (1.0 + p as f64),
                    "p {p} t {t}"
                );
            }
        }
    }
}
