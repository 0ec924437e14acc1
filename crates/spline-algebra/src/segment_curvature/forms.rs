//! The quadratic and quartic forms of a segment's curvature numerator: Bernstein product
//! weights, the dot and wedge pairs of derivative coefficients with their constant Hessians,
//! and the product rule for the quartic `g = h1 h2 − 3 h3 h4`.

use spline_core::{Scalar, binomial};

/// `w[i][j] = C(m,i) C(n,j) / C(m+n,i+j)`: the weight of `f_i g_j` in coefficient `i + j` of
/// the Bernstein product of degrees `m` and `n` (thesis (5.38)).
pub(super) fn product_weights<T: Scalar>(m: usize, n: usize) -> Vec<Vec<T>> {
    (0..=m)
        .map(|i| {
            (0..=n)
                .map(|j| binomial::<T>(m, i) * binomial::<T>(n, j) / binomial::<T>(m + n, i + j))
                .collect()
        })
        .collect()
}

/// A quadratic form in the local variables: value and gradient (its Hessian is constant and
/// kept with the segment).
#[derive(Clone, Debug)]
pub(super) struct Quadratic<T> {
    pub(super) value: T,
    pub(super) gradient: Vec<T>,
}

impl<T: Scalar> Quadratic<T> {
    pub(super) fn zeros(n: usize) -> Self {
        Self {
            value: T::zero(),
            gradient: vec![T::zero(); n],
        }
    }

    pub(super) fn clear(&mut self) {
        self.value = T::zero();
        self.gradient.iter_mut().for_each(|g| *g = T::zero());
    }
}

/// Which product of two derivative coefficients.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Pairing {
    Dot,
    Wedge,
}

/// Adds `w · (a ∘ b)` to `out` (value and gradient), where `a` and `b` are the local
/// coefficient vectors of two derivative coefficients (`a·X`, `a·Y` their coordinates) and
/// `∘` is `·` or `∧`. `ax = a·X` etc. are their current coordinates. Variables are
/// interleaved `[x_0, y_0, …]`. The gradient only `with_gradient`.
pub(super) fn add_pair<T: Scalar>(
    out: &mut Quadratic<T>,
    w: T,
    (a, b): (&[T], &[T]),
    (ax, ay): (T, T),
    (bx, by): (T, T),
    (pairing, with_gradient): (Pairing, bool),
) {
    match pairing {
        Pairing::Dot => {
            out.value += w * (ax * bx + ay * by);
            for j in 0..if with_gradient { a.len() } else { 0 } {
                out.gradient[2 * j] += w * (a[j] * bx + b[j] * ax);
                out.gradient[2 * j + 1] += w * (a[j] * by + b[j] * ay);
            }
        }
        Pairing::Wedge => {
            // a ∧ b = (a·X)(b·Y) − (a·Y)(b·X)
            out.value += w * (ax * by - ay * bx);
            for j in 0..if with_gradient { a.len() } else { 0 } {
                out.gradient[2 * j] += w * (a[j] * by - b[j] * ay);
                out.gradient[2 * j + 1] += w * (b[j] * ax - a[j] * bx);
            }
        }
    }
}

/// Adds the (constant) Hessian of `w · (a ∘ b)` to `hessian` (row-major `n × n`).
pub(super) fn add_pair_hessian<T: Scalar>(
    hessian: &mut [T],
    n: usize,
    w: T,
    (a, b): (&[T], &[T]),
    pairing: Pairing,
) {
    for j in 0..a.len() {
        for l in 0..a.len() {
            match pairing {
                Pairing::Dot => {
                    let v = w * (a[j] * b[l] + b[j] * a[l]);
                    hessian[(2 * j) * n + 2 * l] += v;
                    hessian[(2 * j + 1) * n + 2 * l + 1] += v;
                }
                Pairing::Wedge => {
                    // ∂²/∂X_j∂Y_l = a_j b_l − b_j a_l
                    let v = w * (a[j] * b[l] - b[j] * a[l]);
                    hessian[(2 * j) * n + 2 * l + 1] += v;
                    hessian[(2 * l + 1) * n + 2 * j] += v;
                }
            }
        }
    }
}

/// The Hessians of the Bernstein product `d1 ∘ right` (coefficient after coefficient, each
/// row-major `n × n`), appended to `out`.
pub(super) fn product_hessians<T: Scalar>(
    out: &mut Vec<T>,
    n: usize,
    d1: &[Vec<T>],
    right: &[Vec<T>],
    weights: &[Vec<T>],
    pairing: Pairing,
) {
    let start = out.len();
    out.resize(start + (d1.len() + right.len() - 1) * n * n, T::zero());
    for (i, a) in d1.iter().enumerate() {
        for (j, b) in right.iter().enumerate() {
            let k = i + j;
            add_pair_hessian(
                &mut out[start + k * n * n..start + (k + 1) * n * n],
                n,
                weights[i][j],
                (a, b),
                pairing,
            );
        }
    }
}

/// Scratch sums of [`ProductSums::add_weighted_hessian`].
pub(super) struct ProductSums<'a, T> {
    pub(super) right: &'a mut [T],
    pub(super) left: &'a mut [T],
    pub(super) gradients: &'a mut [T],
}

impl<T: Scalar> ProductSums<'_, T> {
    /// Adds $\sum_k \omega_k \nabla^2 \big(f \sum_{i+j=k} w_{ij} a_i b_j\big)$ to `out`
    /// for quadratic forms `a_i`, `b_j` (values and gradients, and their constant Hessians
    /// `ha`, `hb`). With $s_{ij} = f w_{ij} \omega_{i+j}$ the product rule gives
    /// $\sum_j \alpha_j \nabla^2 b_j + \sum_i \beta_i \nabla^2 a_i + \sum_i (\nabla a_i
    /// v_i^T + v_i \nabla a_i^T)$ with $\alpha_j = \sum_i s_{ij} a_i$,
    /// $\beta_i = \sum_j s_{ij} b_j$ and $v_i = \sum_j s_{ij} \nabla b_j$: one pass over the
    /// Hessians per factor instead of one per pair.
    pub(super) fn add_weighted_hessian(
        &mut self,
        (left, ha): (&[Quadratic<T>], &[T]),
        (right, hb): (&[Quadratic<T>], &[T]),
        weights: &[Vec<T>],
        factor: T,
        hw: &[T],
        out: &mut [T],
    ) {
        let n = left[0].gradient.len();
        let nn = n * n;
        let alpha = &mut self.right[..right.len()];
        let beta = &mut self.left[..left.len()];
        let v = &mut self.gradients[..left.len() * n];
        alpha.iter_mut().for_each(|x| *x = T::zero());
        beta.iter_mut().for_each(|x| *x = T::zero());
        v.iter_mut().for_each(|x| *x = T::zero());
        for (i, a) in left.iter().enumerate() {
            let vi = &mut v[i * n..(i + 1) * n];
            for (j, b) in right.iter().enumerate() {
                let s = weights[i][j] * factor * hw[i + j];
                if s == T::zero() {
                    continue;
                }
                alpha[j] += s * a.value;
                beta[i] += s * b.value;
                for (vr, gb) in vi.iter_mut().zip(&b.gradient) {
                    *vr += s * *gb;
                }
            }
        }
        for (coefficient, h) in alpha.iter().zip(hb.chunks_exact(nn)) {
            if *coefficient != T::zero() {
                for (o, hv) in out.iter_mut().zip(h) {
                    *o += *coefficient * *hv;
                }
            }
        }
        for (coefficient, h) in beta.iter().zip(ha.chunks_exact(nn)) {
            if *coefficient != T::zero() {
                for (o, hv) in out.iter_mut().zip(h) {
                    *o += *coefficient * *hv;
                }
            }
        }
        for (a, vi) in left.iter().zip(v.chunks_exact(n)) {
            for r in 0..n {
                let (gar, vr) = (a.gradient[r], vi[r]);
                let row = &mut out[r * n..(r + 1) * n];
                for ((o, gc), vc) in row.iter_mut().zip(&a.gradient).zip(vi) {
                    *o += gar * *vc + vr * *gc;
                }
            }
        }
    }
}

/// Adds `factor · Σ_{i+j=k} w_ij a_i b_j` to coefficient `k` of `values`, with gradients
/// into `jacobian`.
pub(super) fn quartic_products<T: Scalar>(
    left: &[Quadratic<T>],
    right: &[Quadratic<T>],
    weights: &[Vec<T>],
    factor: T,
    n: usize,
    values: &mut [T],
    mut jacobian: Option<&mut [T]>,
) {
    for (i, a) in left.iter().enumerate() {
        for (j, b) in right.iter().enumerate() {
            let k = i + j;
            let c = weights[i][j] * factor;
            values[k] += c * a.value * b.value;
            if let Some(jac) = jacobian.as_deref_mut() {
                let row = &mut jac[k * n..(k + 1) * n];
                for ((r, ga), gb) in row.iter_mut().zip(&a.gradient).zip(&b.gradient) {
                    *r += c * (a.value * *gb + b.value * *ga);
                }
            }
        }
    }
}
