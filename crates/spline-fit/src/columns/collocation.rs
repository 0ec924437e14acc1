//! The interpolation systems of [`super::make_interp_spline`] for degrees 1 to 5, solved by
//! elimination without pivoting with rows of a width fixed at compile time and all columns
//! of the right-hand side at once.
//!
//! The rows are ordered so that the matrix is a staircase (row `i` non-zero from column
//! `first_i ≤ i`, `first` non-decreasing) with its diagonal inside each row: at the left end
//! the value at $x_0$ first, then the given derivatives in increasing order; at the right end
//! the given derivatives in decreasing order, then the value at $x_{n-1}$. Collocation with
//! Hermite data at the ends is the limit of collocation at coalescing points, so the
//! matrix stays totally positive for the usual conditions (`'clamped'`, several consecutive
//! orders) and needs no pivoting (de Boor and Pinkus 1977). A pivot that is zero or
//! negligible relative to its row (conditions like `'natural'` alone, data that violate
//! Schoenberg–Whitney) returns `None`, and the caller solves the system with the pivoting band
//! LU instead.

use spline_core::KnotVector;

/// Rows of width `N` reduced one at a time against the previous ones (the unit upper factor
/// kept), with `m` right-hand-side columns.
struct FixedStaircase<const N: usize> {
    first: Vec<usize>,
    upper: Vec<[f64; N]>,
    rhs: Vec<f64>,
    m: usize,
}

impl<const N: usize> FixedStaircase<N> {
    fn with_capacity(n: usize, m: usize) -> Self {
        Self {
            first: Vec::with_capacity(n),
            upper: Vec::with_capacity(n),
            rhs: Vec::with_capacity(n * m),
            m,
        }
    }

    /// Appends row `row` at columns `first …` with right-hand side `b`; `None` on a pivot that
    /// is not finite or not above `4 N ε` times the row's largest entry.
    #[inline]
    fn push(&mut self, first: usize, mut row: [f64; N], b: &[f64]) -> Option<()> {
        let m = self.m;
        let i = self.first.len();
        if first > i || i >= first + N {
            return None;
        }
        let scale = row.iter().fold(0.0_f64, |s, v| s.max(v.abs()));
        if m == 1 {
            self.rhs.push(b[0]);
        } else {
            self.rhs.extend_from_slice(b);
        }
        let (done, current) = self.rhs.split_at_mut(i * m);
        for k in first..i {
            let l = row[k - first];
            if l == 0.0 {
                continue;
            }
            // Row k of U (unit diagonal) covers columns k .. first_k + N: in this row's
            // window, from offset k + 1 − first, the entries of U's row from k + 1 − first_k.
            let fk = self.first[k];
            let upper = &self.upper[k][k + 1 - fk..];
            for (r, &u) in row[k + 1 - first..].iter_mut().zip(upper) {
                *r -= l * u;
            }
            if m == 1 {
                current[0] -= l * done[k];
            } else {
                let bk = &done[k * m..(k + 1) * m];
                for (o, &v) in current.iter_mut().zip(bk) {
                    *o -= l * v;
                }
            }
        }
        let pivot = row[i - first];
        #[allow(clippy::cast_precision_loss)]
        let tiny = f64::EPSILON * (4 * N) as f64 * scale;
        if !(pivot.abs() > tiny) || !pivot.is_finite() {
            return None;
        }
        let inverse = 1.0 / pivot;
        for v in &mut row[i + 1 - first..] {
            *v *= inverse;
        }
        for o in current.iter_mut() {
            *o *= inverse;
        }
        self.first.push(first);
        self.upper.push(row);
        Some(())
    }

    /// Back substitution: the solution, row-major with `m` columns.
    fn solve(mut self) -> Vec<f64> {
        let n = self.first.len();
        let m = self.m;
        for i in (0..n).rev() {
            let fi = self.first[i];
            let end = (fi + N).min(n);
            let row = self.upper[i];
            let (head, tail) = self.rhs.split_at_mut((i + 1) * m);
            let target = &mut head[i * m..];
            if m == 1 {
                let mut acc = target[0];
                for (&u, &v) in row[i + 1 - fi..end - fi].iter().zip(tail.iter()) {
                    acc -= u * v;
                }
                target[0] = acc;
                continue;
            }
            for j in i + 1..end {
                let u = row[j - fi];
                for (o, &v) in target.iter_mut().zip(&tail[(j - i - 1) * m..(j - i) * m]) {
                    *o -= u * v;
                }
            }
        }
        self.rhs
    }
}

/// One condition of the system: the derivative `order` at `at` equals `values`.
type Condition<'a> = (usize, f64, &'a [f64]);

/// The coefficients (row-major, `m` columns) of the spline on `knots` (degree `N − 1`) with
/// value `y_i` at `x_i` and the end conditions `left` at `x[0]`, `right` at `x[n-1]` (each
/// `(order, values)`), or `None` where elimination without pivoting does not apply.
fn solve_fixed<const N: usize>(
    knots: &KnotVector<f64>,
    x: &[f64],
    y: &[f64],
    m: usize,
    left: &[(usize, Vec<f64>)],
    right: &[(usize, Vec<f64>)],
) -> Option<Vec<f64>> {
    let n = x.len();
    let nt = knots.num_basis();
    let k = N - 1;
    let (a, b) = knots.domain();
    let mut system = FixedStaircase::<N>::with_capacity(nt, m);
    let mut span = k;
    let derivative_row = |order: usize, at: f64| -> (usize, [f64; N]) {
        let span = knots.span_in_domain(at.clamp(a, b));
        let mut table = [0.0; 64];
        let table = &mut table[..(order + 1) * N];
        knots.basis_derivatives(span, at, order, table);
        let mut row = [0.0; N];
        row.copy_from_slice(&table[order * N..(order + 1) * N]);
        (span - k, row)
    };
    let mut left_sorted: Vec<Condition<'_>> =
        left.iter().map(|(o, v)| (*o, x[0], &v[..])).collect();
    left_sorted.sort_by_key(|c| c.0);
    let mut right_sorted: Vec<Condition<'_>> =
        right.iter().map(|(o, v)| (*o, x[n - 1], &v[..])).collect();
    right_sorted.sort_by_key(|c| std::cmp::Reverse(c.0));
    for (i, &u) in x.iter().enumerate() {
        if i == n - 1 {
            for &(order, at, values) in &right_sorted {
                let (first, row) = derivative_row(order, at);
                system.push(first, row, values)?;
            }
        }
        span = knots.span_in_domain_from(u.clamp(a, b), span);
        let row = knots.basis_values_fixed::<N>(span, u);
        system.push(span - k, row, &y[i * m..(i + 1) * m])?;
        if i == 0 {
            for &(order, at, values) in &left_sorted {
                let (first, row) = derivative_row(order, at);
                system.push(first, row, values)?;
            }
        }
    }
    (system.first.len() == nt).then(|| system.solve())
}

/// [`solve_fixed`] for degrees 1 to 5 (`None` for other degrees, derivative orders above 9,
/// or where elimination without pivoting does not apply).
pub(super) fn solve(
    knots: &KnotVector<f64>,
    x: &[f64],
    y: &[f64],
    m: usize,
    left: &[(usize, Vec<f64>)],
    right: &[(usize, Vec<f64>)],
) -> Option<Vec<f64>> {
    let k = knots.degree();
    if left
        .iter()
        .chain(right)
        .any(|(order, _)| (order + 1) * (k + 1) > 64)
    {
        return None;
    }
    match k {
        1 => solve_fixed::<2>(knots, x, y, m, left, right),
        2 => solve_fixed::<3>(knots, x, y, m, left, right),
        3 => solve_fixed::<4>(knots, x, y, m, left, right),
        4 => solve_fixed::<5>(knots, x, y, m, left, right),
        5 => solve_fixed::<6>(knots, x, y, m, left, right),
        _ => None,
    }
}
