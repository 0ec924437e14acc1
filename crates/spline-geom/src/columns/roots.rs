//! Real roots of one column, piece by piece (scipy's `PPoly.roots(discontinuity=True,
//! extrapolate=False)` on `PPoly.from_spline`; for cubics the roots `sproot` finds).

use super::ColumnSpline;
use nalgebra::DMatrix;
use spline_core::{Error, ErrorKind, MAX_ORDER, Result};

impl ColumnSpline {
    /// The real roots of column `column` in the base interval $[t_k, t_n]$, increasing, each
    /// once.
    ///
    /// Each polynomial piece is written in powers of $(x - t_i)/(t_{i+1} - t_i)$ and its
    /// roots in the piece found (closed forms up to degree 2, the eigenvalues of the
    /// companion matrix above, polished by Newton's method). As in scipy's `PPoly.roots`
    /// with `discontinuity=True`, a sign change across a breakpoint where the spline jumps
    /// is a root at the breakpoint. A piece that is identically zero contributes its left
    /// end (scipy's `PPoly.roots` reports it followed by NaN; `sproot` does not report it).
    ///
    /// # Errors
    /// [`ErrorKind::IndexOutOfRange`] for a column that does not exist.
    pub fn roots(&self, column: usize) -> Result<Vec<f64>> {
        if column >= self.columns {
            return Err(Error::new(
                ErrorKind::IndexOutOfRange,
                format!(
                    "column {column} does not exist: the spline has {} columns",
                    self.columns
                ),
            )
            .with_index(column));
        }
        let k = self.degree();
        // The knots and coefficients evaluation works on (no empty basis functions).
        let knots = self.knot_vector();
        let coefficients = self.evaluation_coefficients();
        let t = knots.knots();
        let n = knots.num_basis();
        let m = self.columns;
        let scale = (0..n)
            .map(|i| coefficients[i * m + column].abs())
            .fold(0.0, f64::max);
        let tiny = scale * f64::EPSILON * 16.0;
        let width = k + 1;
        let mut scratch = vec![0.0; width * width];
        let mut roots: Vec<f64> = Vec::new();
        let push = |x: f64, roots: &mut Vec<f64>| {
            if roots.last().is_none_or(|&r| x > r) {
                roots.push(x);
            }
        };
        let mut previous_end: Option<f64> = None;
        for span in k..n {
            let (x0, x1) = (t[span], t[span + 1]);
            if x1 <= x0 {
                continue;
            }
            let h = x1 - x0;
            // Power coefficients in s = (x − x0)/h: q_d = s^{(d)}(x0) h^d / d!.
            knots.basis_derivatives(span, x0, k, &mut scratch);
            let mut q = [0.0; MAX_ORDER];
            let mut factor = 1.0;
            for d in 0..=k {
                let row = &scratch[d * width..(d + 1) * width];
                let value: f64 = row
                    .iter()
                    .enumerate()
                    .map(|(r, b)| b * coefficients[(span - k + r) * m + column])
                    .sum();
                q[d] = value * factor;
                factor *= h / (d + 1) as f64;
            }
            let q = &q[..=k];
            let end = q.iter().sum::<f64>();
            if q.iter().all(|v| v.abs() <= tiny) {
                push(x0, &mut roots);
                previous_end = Some(0.0);
                continue;
            }
            if let Some(prev) = previous_end
                && prev * q[0] < 0.0
            {
                push(x0, &mut roots);
            }
            let mut local = [0.0; MAX_ORDER];
            let count = unit_interval_roots(q, tiny, &mut local);
            for &s in &local[..count] {
                push(if s == 1.0 { x1 } else { x0 + s * h }, &mut roots);
            }
            previous_end = Some(end);
        }
        Ok(roots)
    }
}

/// The real roots in `[0, 1]` of $\sum_d q_d s^d$ (not identically zero), increasing, into
/// `out`; returns their number.
fn unit_interval_roots(q: &[f64], tiny: f64, out: &mut [f64]) -> usize {
    let mut degree = q.len() - 1;
    while degree > 0 && q[degree].abs() <= tiny {
        degree -= 1;
    }
    let q = &q[..=degree];
    let mut candidates: Vec<f64> = Vec::with_capacity(degree);
    match degree {
        0 => {}
        1 => candidates.push(-q[0] / q[1]),
        2 => {
            let (a, b, c) = (q[2], q[1], q[0]);
            let disc = b * b - 4.0 * a * c;
            if disc >= 0.0 {
                let r = -0.5 * (b + b.signum() * disc.sqrt());
                if r != 0.0 {
                    candidates.push(c / r);
                    candidates.push(r / a);
                } else {
                    // b = 0 and c = 0: a double root at 0.
                    candidates.push(0.0);
                }
            } else if disc > -16.0 * f64::EPSILON * b * b {
                candidates.push(-b / (2.0 * a));
            }
        }
        _ => {
            // Companion matrix of the monic polynomial.
            let lead = q[degree];
            let companion = DMatrix::from_fn(degree, degree, |i, j| {
                if i == 0 {
                    -q[degree - 1 - j] / lead
                } else if i == j + 1 {
                    1.0
                } else {
                    0.0
                }
            });
            for z in companion.complex_eigenvalues().iter() {
                if z.im.abs() <= 1e-7 * (1.0 + z.re.abs()) {
                    candidates.push(z.re);
                }
            }
        }
    }
    let eval = |s: f64| {
        let mut v = 0.0;
        let mut d = 0.0;
        for &c in q.iter().rev() {
            d = d * s + v;
            v = v * s + c;
        }
        (v, d)
    };
    let mut count = 0;
    for mut s in candidates {
        // Newton polish (kept only when it improves the residual).
        for _ in 0..3 {
            let (v, d) = eval(s);
            if d == 0.0 || v == 0.0 {
                break;
            }
            let next = s - v / d;
            if next.is_finite() && eval(next).0.abs() < v.abs() {
                s = next;
            } else {
                break;
            }
        }
        let eps = 1e-12;
        if s.is_finite() && s >= -eps && s <= 1.0 + eps {
            out[count] = s.clamp(0.0, 1.0);
            count += 1;
        }
    }
    out[..count].sort_by(f64::total_cmp);
    count
}
