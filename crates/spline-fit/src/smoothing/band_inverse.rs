//! The band of the inverse of a symmetric positive definite band matrix (Takahashi's
//! recurrence, in the form of Hutchinson and de Hoog 1985): what the trace of a smoothing
//! spline's influence matrix needs, in `O(n b²)` without forming the inverse.

use crate::banded::BandCholesky;
use spline_core::Scalar;

/// The entries $Z_{ij}$, $|i - j| \le b$, of $Z = M^{-1}$ for the Cholesky factor
/// `M = L Lᵀ` (already factored, half-bandwidth `b`): row `i` of the result holds
/// $Z_{i, i-d}$ at `i (b + 1) + d`.
///
/// With $L = \tilde L D^{1/2}$, $\tilde L$ unit lower triangular,
/// $Z = D^{-1} \tilde L^{-1} + (I - \tilde L^T) Z$ gives, from the last row up,
/// $Z_{ij} = -\sum_{k = i+1}^{i+b} \tilde L_{ki} Z_{kj}$ for `j > i` and
/// $Z_{ii} = 1/d_i - \sum_{k} \tilde L_{ki} Z_{ki}$: every term stays inside the band.
pub(crate) fn inverse_band<T: Scalar>(factor: &BandCholesky<T>, n: usize) -> Vec<T> {
    let b = factor.bandwidth();
    let w = b + 1;
    let mut z = vec![T::zero(); n * w];
    let get = |z: &[T], i: usize, j: usize| -> T {
        let (i, j) = if j <= i { (i, j) } else { (j, i) };
        z[i * w + (i - j)]
    };
    for i in (0..n).rev() {
        let lii = factor.lower(i, i);
        let last = (i + b).min(n - 1);
        // Unit-lower entries L̃_ki = L_ki / L_ii for k = i + 1 … i + b.
        let mut scaled = [T::zero(); spline_core::MAX_ORDER + 1];
        for k in i + 1..=last {
            scaled[k - i] = factor.lower(k, i) / lii;
        }
        for j in (i + 1..=last).rev() {
            let mut acc = T::zero();
            for k in i + 1..=last {
                acc -= scaled[k - i] * get(&z, k, j);
            }
            z[j * w + (j - i)] = acc;
        }
        let mut diag = T::one() / (lii * lii);
        for k in i + 1..=last {
            diag -= scaled[k - i] * get(&z, k, i);
        }
        z[i * w] = diag;
    }
    z
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_dense_inverse() {
        // A symmetric positive definite band matrix of half-bandwidth 2.
        let n = 7;
        let b = 2;
        let entry = |i: usize, j: usize| -> f64 {
            let d = i.abs_diff(j);
            match d {
                0 => 6.0 + i as f64 * 0.3,
                1 => -1.0 + 0.1 * (i + j) as f64,
                2 => 0.5,
                _ => 0.0,
            }
        };
        let mut m = BandCholesky::zeros(n, b);
        for i in 0..n {
            for j in i.saturating_sub(b)..=i {
                m.add_lower(i, j, entry(i, j));
            }
        }
        let dense = nalgebra::DMatrix::from_fn(n, n, entry);
        let inverse = dense.try_inverse().unwrap();
        m.factor(&|i| format!("{i}")).unwrap();
        let z = inverse_band(&m, n);
        for i in 0..n {
            for j in i.saturating_sub(b)..=i {
                let got = z[i * (b + 1) + (i - j)];
                assert!((got - inverse[(i, j)]).abs() < 1e-14, "({i}, {j})");
            }
        }
    }
}
