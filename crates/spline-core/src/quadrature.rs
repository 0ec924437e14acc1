//! Gauss–Legendre quadrature on `[-1, 1]`.

use crate::{Scalar, cast};

/// The `count` Gauss–Legendre nodes and weights `(x, w)` on `[-1, 1]` (exact for polynomials
/// of degree `2 count − 1`), computed in `f64` by Newton's method on the Legendre polynomial
/// from the usual asymptotic first guesses.
///
/// ```
/// let rule = spline_core::gauss_legendre::<f64>(3);
/// let integral: f64 = rule.iter().map(|&(x, w)| w * x.powi(4)).sum();
/// assert!((integral - 0.4).abs() < 1e-15); // ∫ x⁴ over [−1, 1] = 2/5
/// ```
#[must_use]
pub fn gauss_legendre<T: Scalar>(count: usize) -> Vec<(T, T)> {
    let mut out = Vec::with_capacity(count);
    #[allow(clippy::cast_precision_loss)]
    let nf = count as f64;
    for i in 0..count {
        #[allow(clippy::cast_precision_loss)]
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // P_n(x) and P_n'(x) by the three-term recurrence.
            let (mut p0, mut p1) = (1.0f64, x);
            for k in 2..=count {
                #[allow(clippy::cast_precision_loss)]
                let kf = k as f64;
                let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
                p0 = p1;
                p1 = p2;
            }
            let pn = if count == 0 { 1.0 } else { p1 };
            let pm = if count <= 1 { 1.0 } else { p0 };
            dp = nf * (x * pn - pm) / (x * x - 1.0);
            let dx = pn / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        out.push((cast(x), cast(w)));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::gauss_legendre;

    #[test]
    fn integrates_polynomials_exactly() {
        for count in 1..12 {
            let rule = gauss_legendre::<f64>(count);
            for degree in 0..2 * count {
                let got: f64 = rule.iter().map(|&(x, w)| w * x.powi(degree as i32)).sum();
                let exact = if degree % 2 == 1 {
                    0.0
                } else {
                    2.0 / (degree as f64 + 1.0)
                };
                assert!(
                    (got - exact).abs() < 1e-13,
                    "n={count} degree={degree}: {got}"
                );
            }
        }
    }
}
