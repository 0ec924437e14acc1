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

/// Rows of width `N` reduced one at a time against the previous ones, with `m`
/// right-hand-side columns. Row `i` of the unit upper factor is stored aligned on its
/// diagonal: `upper[i][c]` is the entry at column `i + c` (its non-zeros end before column
/// `first_i + N ≤ i + N`), so elimination and back substitution are fixed-length loops.
struct FixedStaircase<const N: usize> {
    /// Rows pushed so far.
    rows: usize,
    upper: Vec<[f64; N]>,
    /// The reduced right-hand sides, then the solution; `N` zero rows of padding at the end.
    rhs: Vec<f64>,
    m: usize,
}

impl<const N: usize> FixedStaircase<N> {
    fn with_capacity(n: usize, m: usize) -> Self {
        Self {
            rows: 0,
            upper: vec![[0.0; N]; n],
            rhs: vec![0.0; (n + N) * m],
            m,
        }
    }

    /// Appends row `row` at columns `first …` with right-hand side `b`; `None` on a pivot that
    /// is not finite or not above `4 N ε` times the row's largest entry, or more rows than
    /// allocated.
    #[inline]
    fn push(&mut self, first: usize, row: [f64; N], b: &[f64]) -> Option<()> {
        let m = self.m;
        let i = self.rows;
        if first > i || i >= first + N || i >= self.upper.len() {
            return None;
        }
        let scale = row.iter().fold(0.0_f64, |s, v| s.max(v.abs()));
        // The row at columns first …, with room for the tail of an upper row.
        let mut w = [0.0; 16];
        w[..N].copy_from_slice(&row);
        let (done, current) = self.rhs.split_at_mut(i * m);
        let current = &mut current[..m];
        if m == 1 {
            current[0] = b[0];
        } else {
            current.copy_from_slice(b);
        }
        for k in first..i {
            let j = k - first;
            let l = w[j];
            if l == 0.0 {
                continue;
            }
            let upper = &self.upper[k];
            for c in 1..N {
                w[j + c] -= l * upper[c];
            }
            if m == 1 {
                current[0] -= l * done[k];
            } else {
                for (o, &v) in current.iter_mut().zip(&done[k * m..(k + 1) * m]) {
                    *o -= l * v;
                }
            }
        }
        let d = i - first;
        let pivot = w[d];
        #[allow(clippy::cast_precision_loss)]
        let tiny = f64::EPSILON * (4 * N) as f64 * scale;
        if !(pivot.abs() > tiny) || !pivot.is_finite() {
            return None;
        }
        let inverse = 1.0 / pivot;
        let upper = &mut self.upper[i];
        upper[0] = 1.0;
        for c in 1..N {
            upper[c] = w[d + c] * inverse;
        }
        for o in current.iter_mut() {
            *o *= inverse;
        }
        self.rows += 1;
        Some(())
    }

    /// Back substitution: the solution, row-major with `m` columns.
    fn solve(mut self) -> Vec<f64> {
        let n = self.rows;
        let m = self.m;
        if m == 1 {
            let x = &mut self.rhs;
            for i in (0..n).rev() {
                let u = &self.upper[i];
                let mut acc = x[i];
                for c in 1..N {
                    acc -= u[c] * x[i + c];
                }
                x[i] = acc;
            }
        } else {
            for i in (0..n).rev() {
                let u = self.upper[i];
                let (head, tail) = self.rhs.split_at_mut((i + 1) * m);
                let target = &mut head[i * m..];
                for c in 1..N {
                    for (o, &v) in target.iter_mut().zip(&tail[(c - 1) * m..c * m]) {
                        *o -= u[c] * v;
                    }
                }
            }
        }
        self.rhs.truncate(n * m);
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
    (system.rows == nt).then(|| system.solve())
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
