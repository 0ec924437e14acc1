//! The ridge function of a parametric surface, written once over a small number trait so that
//! the same formula gives pointwise values (`f64`) and enclosures over a box (intervals whose
//! inputs are the Bernstein bounds of the curvature numerators), and the Bézier patches it
//! is evaluated on.
//!
//! With the scaled fundamental forms $\hat E \ldots \hat N$ of [`crate::CurvatureNumerators`]
//! ($\hat E = \omega E$, $\hat L = \omega \sqrt{A}\\, L$, $\omega = W^4$ the fourth power of the
//! weight function, 1 for polynomial surfaces, $A = EG - F^2$), the generalised eigenvalues
//! $\tilde\kappa$ of $(\hat{II}, \hat I)$ are $\mu / \hat A$ with
//! $\mu^2 - \hat H \mu + \hat A \hat K = 0$ ($\hat A = \hat E \hat G - \hat F^2$, $\hat H$ the
//! mean numerator, $\hat K$ the Gaussian one), and the principal curvatures are
//! $\kappa = \mu\\, \omega / \hat A^{3/2}$. Hence, with $\Delta = \hat H^2 - 4 \hat A \hat K$,
//! $s = \sqrt\Delta$ and $\mu_\sigma = (\hat H + \sigma s)/2$ ($\sigma = +1$: the larger
//! curvature $\kappa_1$, blue; $\sigma = -1$: $\kappa_2$, red), the derivative of
//! $\kappa_\sigma$ along a vector `t` is a positive multiple of
//! $$g = t \cdot \big(2 \hat A W \nu + 4 s \mu_\sigma (8 \hat A \nabla W - 3 W \nabla \hat A)\big),
//! \quad \nu = 4 s \nabla\mu_\sigma = 2 s \nabla \hat H + \sigma \nabla \Delta,$$
//! which has no division (it is continuous through the umbilics, where it vanishes). The
//! principal direction of $\kappa_\sigma$ is orthogonal to either row of the singular matrix
//! $\hat A \hat{II} - \mu_\sigma \hat I$: `t₁ = (ÂM̂ − μF̂, μÊ − ÂL̂)` or
//! `t₂ = (ÂN̂ − μĜ, μF̂ − ÂM̂)` (each vanishes where the other parameter line is principal).

use spline_geom::Surface;
use std::ops::{Add, Mul, Sub};

/// Arithmetic the ridge formula needs.
pub(crate) trait Num:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self>
{
    fn constant(x: f64) -> Self;
    /// The square root of a quantity that is non-negative in exact arithmetic.
    fn sqrt_nonneg(self) -> Self;
}

impl Num for f64 {
    fn constant(x: f64) -> Self {
        x
    }
    fn sqrt_nonneg(self) -> Self {
        self.max(0.0).sqrt()
    }
}

/// A closed interval (rounding is not directed: the enclosures hold up to rounding).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Interval {
    pub(crate) lo: f64,
    pub(crate) hi: f64,
}

impl Interval {
    pub(crate) fn contains_zero(self) -> bool {
        self.lo <= 0.0 && self.hi >= 0.0
    }
}

impl Add for Interval {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            lo: self.lo + o.lo,
            hi: self.hi + o.hi,
        }
    }
}

impl Sub for Interval {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self {
            lo: self.lo - o.hi,
            hi: self.hi - o.lo,
        }
    }
}

impl Mul for Interval {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let p = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        Self {
            lo: p.iter().copied().fold(f64::INFINITY, f64::min),
            hi: p.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        }
    }
}

impl Num for Interval {
    fn constant(x: f64) -> Self {
        Self { lo: x, hi: x }
    }
    fn sqrt_nonneg(self) -> Self {
        Self {
            lo: self.lo.max(0.0).sqrt(),
            hi: self.hi.max(0.0).sqrt(),
        }
    }
}

/// A value with its two partial derivatives.
pub(crate) type Jet<N> = [N; 3];

fn jet_mul<N: Num>(a: Jet<N>, b: Jet<N>) -> Jet<N> {
    [
        a[0] * b[0],
        a[1] * b[0] + a[0] * b[1],
        a[2] * b[0] + a[0] * b[2],
    ]
}

fn jet_sub<N: Num>(a: Jet<N>, b: Jet<N>) -> Jet<N> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn jet_add<N: Num>(a: Jet<N>, b: Jet<N>) -> Jet<N> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// The ridge function of one colour at a point (or over a box).
#[derive(Clone, Copy, Debug)]
pub(crate) struct RidgeValue<N> {
    /// `g` with the two direction forms `t₁`, `t₂`.
    pub(crate) g: [N; 2],
    /// The squared lengths of `t₁`, `t₂`.
    pub(crate) t2: [N; 2],
    /// The direction forms `t₁`, `t₂` themselves.
    pub(crate) t: [[N; 2]; 2],
    /// Sum of the magnitudes of the terms of `g` (pointwise only meaningful for `f64`).
    pub(crate) scale: [N; 2],
    /// $\Delta$ and $\hat H^2$: `Δ` small against `Ĥ²` means an umbilic.
    pub(crate) delta: N,
    pub(crate) h2: N,
    /// The gradient vector `G` with `g = G · t` (pointwise: `|G|²`).
    pub(crate) grad2: N,
}

/// The ridge function of colour `sigma` (±1) from the jets of `[Ê, F̂, Ĝ, L̂, M̂, N̂, W]`.
pub(crate) fn ridge_value<N: Num>(
    x: &[Jet<N>; 7],
    sigma: f64,
    abs: impl Fn(N) -> N,
) -> RidgeValue<N> {
    let [e, f, g, l, m, n, w] = *x;
    let two = N::constant(2.0);
    let a = jet_sub(jet_mul(e, g), jet_mul(f, f));
    let fm = jet_mul(f, m);
    let h = jet_add(jet_sub(jet_mul(e, n), jet_add(fm, fm)), jet_mul(g, l));
    let k = jet_sub(jet_mul(l, n), jet_mul(m, m));
    let hh = jet_mul(h, h);
    let ak = jet_mul(a, k);
    let four = N::constant(4.0);
    let delta = [
        hh[0] - four * ak[0],
        hh[1] - four * ak[1],
        hh[2] - four * ak[2],
    ];
    let s = delta[0].sqrt_nonneg();
    let sg = N::constant(sigma);
    let mu = N::constant(0.5) * (h[0] + sg * s);
    let nu = [
        two * s * h[1] + sg * delta[1],
        two * s * h[2] + sg * delta[2],
    ];
    // The gradient of κ (up to a positive factor), term by term.
    let c1 = two * a[0] * w[0];
    let c2 = four * s * mu;
    let grad = |i: usize| {
        let t1 = c1 * nu[i - 1];
        let t2 = c2 * N::constant(8.0) * a[0] * w[i];
        let t3 = c2 * N::constant(3.0) * w[0] * a[i];
        (t1 + t2 - t3, abs(t1) + abs(t2) + abs(t3))
    };
    let (gu, su) = grad(1);
    let (gv, sv) = grad(2);
    let rl = a[0] * l[0] - mu * e[0];
    let rm = a[0] * m[0] - mu * f[0];
    let rn = a[0] * n[0] - mu * g[0];
    // t₁ = (rm, −rl), t₂ = (rn, −rm).
    let forms = [(rm, rl), (rn, rm)];
    let mut out = RidgeValue {
        g: [N::constant(0.0); 2],
        t2: [N::constant(0.0); 2],
        t: [[N::constant(0.0); 2]; 2],
        scale: [N::constant(0.0); 2],
        delta: delta[0],
        h2: hh[0],
        grad2: gu * gu + gv * gv,
    };
    for (i, (tu, tv)) in forms.into_iter().enumerate() {
        out.g[i] = gu * tu - gv * tv;
        out.t2[i] = tu * tu + tv * tv;
        out.t[i] = [tu, N::constant(0.0) - tv];
        out.scale[i] = su * abs(tu) + sv * abs(tv);
    }
    out
}

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
/// (at least `p + 1` long).
fn bernstein_into(p: usize, t: f64, b: &mut [f64], db: &mut [f64]) {
    // Degree p − 1 first (for the derivative), then one more step.
    b[..=p].fill(0.0);
    db[..=p].fill(0.0);
    b[0] = 1.0;
    for d in 1..p {
        for i in (0..=d).rev() {
            let left = if i > 0 { b[i - 1] * t } else { 0.0 };
            b[i] = left + b[i] * (1.0 - t);
        }
    }
    if p > 0 {
        for i in 0..=p {
            let left = if i > 0 { b[i - 1] } else { 0.0 };
            let right = if i < p { b[i] } else { 0.0 };
            db[i] = p as f64 * (left - right);
        }
        for i in (0..=p).rev() {
            let left = if i > 0 { b[i - 1] * t } else { 0.0 };
            let own = if i < p { b[i] * (1.0 - t) } else { 0.0 };
            b[i] = left + own;
        }
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
        let range = |it: &mut dyn Iterator<Item = f64>| {
            let mut r = Interval {
                lo: f64::INFINITY,
                hi: f64::NEG_INFINITY,
            };
            for x in it {
                r.lo = r.lo.min(x);
                r.hi = r.hi.max(x);
            }
            if r.lo > r.hi {
                Interval::constant(0.0)
            } else {
                r
            }
        };
        let nv = self.q + 1;
        let c = &self.c;
        let (p, q) = (self.p, self.q);
        let su = p as f64 / (self.u.1 - self.u.0);
        let sv = q as f64 / (self.v.1 - self.v.0);
        [
            range(&mut c.iter().copied()),
            range(
                &mut (0..p)
                    .flat_map(|i| (0..=q).map(move |j| su * (c[(i + 1) * nv + j] - c[i * nv + j]))),
            ),
            range(
                &mut (0..=p)
                    .flat_map(|i| (0..q).map(move |j| sv * (c[i * nv + j + 1] - c[i * nv + j]))),
            ),
        ]
    }

    /// De Casteljau halving along `u` (`along_u`) or `v`.
    pub(crate) fn halves(&self, along_u: bool) -> (Self, Self) {
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
        let (mut left, mut right) = (self.c.clone(), self.c.clone());
        let mut work = vec![0.0; n + 1];
        for line in 0..=m {
            for (k, w) in work.iter_mut().enumerate() {
                *w = self.c[at(line, k)];
            }
            for r in 0..=n {
                left[at(line, r)] = work[0];
                right[at(line, n - r)] = work[n - r];
                for k in 0..n - r {
                    work[k] = 0.5 * (work[k] + work[k + 1]);
                }
            }
        }
        let (mut a, mut b) = (Self { c: left, ..*self }, Self { c: right, ..*self });
        if along_u {
            let mid = 0.5 * (self.u.0 + self.u.1);
            a.u.1 = mid;
            b.u.0 = mid;
        } else {
            let mid = 0.5 * (self.v.0 + self.v.1);
            a.v.1 = mid;
            b.v.0 = mid;
        }
        (a, b)
    }
}

/// `|g| ≤ VANISHING · (sum of the magnitudes of its terms)` at every probe of a patch: the
/// ridge condition of that colour vanishes identically there (rounding of the numerators is
/// about `1e-15` of the terms).
pub(crate) const VANISHING: f64 = 1e-10;

/// Crossings where `Δ ≤ NEAR_UMBILIC · Ĥ²` (the principal curvatures within about `10⁻³` of
/// each other, relatively) are not trusted: the direction forms vanish at the umbilics; the
/// box holding an umbilic joins the other crossings to it.
pub(crate) const NEAR_UMBILIC: f64 = 1e-6;

/// The edges `[u = u₀, u = u₁, v = v₀, v = v₁]` of a patch along which `Â = ÊĜ − F̂²`
/// vanishes (below `floor` at five points).
pub(crate) fn singular_edges(factors: &[Patch; 7], floor: f64) -> [bool; 4] {
    let (u, v) = (factors[0].u, factors[0].v);
    let area = |p: [f64; 2]| {
        let [e, f, g] = [0, 1, 2].map(|i| factors[i].jet(p[0], p[1])[0]);
        e * g - f * f
    };
    let along = |k: usize, t: f64| match k {
        0 => [u.0, v.0 + t * (v.1 - v.0)],
        1 => [u.1, v.0 + t * (v.1 - v.0)],
        2 => [u.0 + t * (u.1 - u.0), v.0],
        _ => [u.0 + t * (u.1 - u.0), v.1],
    };
    std::array::from_fn(|k| {
        [0.0, 0.25, 0.5, 0.75, 1.0]
            .iter()
            .all(|&t| area(along(k, t)).abs() <= floor)
    })
}

/// `g` with the chosen direction form, zero where it is below [`VANISHING`] of its terms
/// (rounding: a ridge along a grid line, or a condition vanishing identically, must not
/// produce crossings from the signs of rounding errors).
pub(crate) fn snapped(r: &RidgeValue<f64>, form: usize) -> f64 {
    if r.g[form].abs() <= VANISHING * r.scale[form] {
        0.0
    } else {
        r.g[form]
    }
}

/// Whether the ridge condition of the colour vanishes at the point (or it is an umbilic).
pub(crate) fn degenerate(r: &RidgeValue<f64>) -> bool {
    let best = usize::from(r.t2[1] > r.t2[0]);
    r.delta <= 1e-10 * r.h2 || r.g[best].abs() <= VANISHING * r.scale[best]
}

/// Whether the point is (nearly) an umbilic.
pub(crate) fn degenerate_umbilic(r: &RidgeValue<f64>) -> bool {
    r.delta <= NEAR_UMBILIC * r.h2
}

/// The direction form with the larger length.
pub(crate) fn best_form(r: &RidgeValue<f64>) -> usize {
    usize::from(r.t2[1] > r.t2[0])
}
