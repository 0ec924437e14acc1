//! The ridge function of a parametric surface, written once over a small number trait so that
//! the same formula gives pointwise values (`f64`) and enclosures over a box (intervals whose
//! inputs are the Bernstein bounds of the curvature numerators; the Bézier patches it is
//! evaluated on are [`crate::bezier_patch`]'s).
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

/// An upper bound of the magnitude of a quantity: the arithmetic of the rounding scale of
/// the ridge function, where every input is a symmetric interval `[−m, m]`. Sums and
/// differences add bounds, products multiply them, the square root of a non-negative
/// quantity takes the root of its bound: the `hi` ends of the same formula in [`Interval`]s
/// (the only interval that is not symmetric there, `√Δ ∈ [0, √m]`, and the quantities
/// built from it, enter the result only through products with symmetric ones), at a
/// quarter of the cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Magnitude(pub(crate) f64);

impl Add for Magnitude {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self(self.0 + o.0)
    }
}

impl Sub for Magnitude {
    type Output = Self;
    // The magnitude of a difference is bounded by the sum of the magnitudes.
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn sub(self, o: Self) -> Self {
        Self(self.0 + o.0)
    }
}

impl Mul for Magnitude {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self(self.0 * o.0)
    }
}

impl Num for Magnitude {
    fn constant(x: f64) -> Self {
        Self(x.abs())
    }
    fn sqrt_nonneg(self) -> Self {
        Self(self.0.sqrt())
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

/// `|g| ≤ VANISHING · (sum of the magnitudes of its terms)` at every probe of a patch: the
/// ridge condition of that colour vanishes identically there (rounding of the numerators is
/// about `1e-15` of the terms).
pub(crate) const VANISHING: f64 = 1e-10;

/// Crossings where `Δ ≤ NEAR_UMBILIC · Ĥ²` (the principal curvatures within about `10⁻³` of
/// each other, relatively) are not trusted: the direction forms vanish at the umbilics; the
/// box holding an umbilic joins the other crossings to it.
pub(crate) const NEAR_UMBILIC: f64 = 1e-6;

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
