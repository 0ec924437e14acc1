//! scipy's class methods of `BSpline` that build matrices and splines from other data:
//! `design_matrix` and `from_power_basis`.

use super::{ColumnSpline, Extrapolate, check_scipy_knots, without_empty_basis};
use nalgebra_sparse::CsrMatrix;
use spline_core::{Error, ErrorKind, KnotVector, MAX_ORDER, Result};

impl ColumnSpline {
    /// The collocation ("design") matrix of scipy's `BSpline.design_matrix(x, t, k,
    /// extrapolate)`: row `i` holds the `k + 1` B-splines of degree `k` on `t` that may be
    /// non-zero at `x_i`, $B_{j,k}(x_i)$ at column `j`, in a CSR matrix of
    /// `len(x) × (len(t) − k − 1)` with exactly `k + 1` stored entries per row (zeros at knots
    /// included, as scipy stores them).
    ///
    /// With [`Extrapolate::On`] points outside $[t_k, t_n]$ use the end pieces' polynomials,
    /// with [`Extrapolate::Periodic`] they are mapped into it first, with [`Extrapolate::Off`]
    /// they are an error.
    ///
    /// # Errors
    /// [`ErrorKind::UnsortedKnots`] ("Expect t to be a 1-D sorted array_like");
    /// [`ErrorKind::InvalidLength`] for fewer than `2k + 2` knots ("Length t is not enough for
    /// k=…"); [`ErrorKind::NonFinite`] for NaN or infinite `x` or knots ("Array must not
    /// contain infs or nans"); [`ErrorKind::OutOfDomain`] ("Out of bounds w/ x = …") with
    /// [`Extrapolate::Off`]; the errors of [`ColumnSpline::new`] for the knots otherwise.
    pub fn design_matrix(
        x: &[f64],
        t: &[f64],
        k: usize,
        mode: Extrapolate,
    ) -> Result<CsrMatrix<f64>> {
        if let Some(v) = x.iter().chain(t).find(|v| !v.is_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("Array must not contain infs or nans (found {v})"),
            ));
        }
        if let Some(i) = (1..t.len()).find(|&i| t[i] < t[i - 1]) {
            return Err(Error::new(
                ErrorKind::UnsortedKnots,
                format!(
                    "Expect t to be a 1-D sorted array_like, but knot {i} = {} follows {}",
                    t[i],
                    t[i - 1]
                ),
            ));
        }
        if t.len() < 2 * k + 2 {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "Length t is not enough for k={k}: {} knots, at least {} needed",
                    t.len(),
                    2 * k + 2
                ),
            ));
        }
        check_scipy_knots(t, k)?;
        // Evaluation on the knots without empty basis functions; `kept` maps their columns
        // back to the columns of `t`'s basis.
        let (knots, kept) = match without_empty_basis(t, k) {
            None => (KnotVector::new(k, t.to_vec())?, None),
            Some((reduced, kept)) => (KnotVector::new(k, reduced)?, Some(kept)),
        };
        let n = t.len() - k - 1;
        let (a, b) = knots.domain();
        if mode == Extrapolate::Off
            && let Some(&v) = x.iter().find(|&&v| v < a || v > b)
        {
            return Err(Error::new(
                ErrorKind::OutOfDomain,
                format!("Out of bounds w/ x = {v}: the base interval is [{a}, {b}]"),
            )
            .with_value(v)
            .with_interval(a, b));
        }
        let width = k + 1;
        let mut values = Vec::with_capacity(x.len() * width);
        let mut columns = Vec::with_capacity(x.len() * width);
        let mut basis = [0.0; MAX_ORDER];
        let mut hint = usize::MAX;
        for &x0 in x {
            let u = if mode == Extrapolate::Periodic {
                a + (x0 - a).rem_euclid(b - a)
            } else {
                x0
            };
            let span = span_outside(&knots, u, hint);
            hint = span;
            knots.basis_values(span, u, &mut basis);
            values.extend_from_slice(&basis[..width]);
            match &kept {
                None => columns.extend(span - k..=span),
                Some(kept) => columns.extend(kept[span - k..=span].iter().copied()),
            }
        }
        let offsets: Vec<usize> = (0..=x.len()).map(|i| i * width).collect();
        CsrMatrix::try_from_csr_data(x.len(), n, offsets, columns, values).map_err(|e| {
            Error::new(
                ErrorKind::InvalidArgument,
                format!("the design matrix is malformed: {e}"),
            )
        })
    }
}

/// The span whose polynomial gives the spline at `u`: the span of `u` inside the base
/// interval, the first or last non-empty one outside.
fn span_outside(knots: &KnotVector<f64>, u: f64, hint: usize) -> usize {
    let (a, b) = knots.domain();
    knots.span_in_domain_from(u.clamp(a, b), hint)
}

/// The knots that scipy's `BSpline.from_power_basis` chooses, by CubicSpline's boundary
/// condition (`bc_type`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PowerBasisKnots {
    /// `'not-a-knot'`: the not-a-knot knots of the breakpoints ([`KnotVector::not_a_knot`]).
    NotAKnot,
    /// `'natural'` or `'clamped'`: every breakpoint a knot, the ends `k + 1` times.
    Augmented,
    /// `'periodic'`: every breakpoint a knot, `k` knots at each end continued periodically
    /// (for even `k` the interior breakpoints moved half a step back first).
    Periodic,
}

impl ColumnSpline {
    /// The B-spline of the piecewise polynomial with breakpoints `x` and power coefficients
    /// `c` (scipy's `BSpline.from_power_basis(pp, bc_type)`, `pp` a `CubicSpline`): `c` is
    /// row-major of shape `(k + 1) × (len(x) − 1) × columns`, `c[m][i][j]` the coefficient of
    /// $(x - x_i)^{k-m}$ on piece `i` of column `j`. The knots follow `bc`; the coefficients
    /// come from Marsden's identity (Lyche and Mørken §3.1.2), as scipy computes them:
    ///
    /// $$ c_j = \sum_{m=0}^{k} \frac{(k-m)!}{k!}\, c_{m,i}\, (-1)^{k-m}\, D^m p_{j,k}(x_i),
    /// \qquad p_{j,k}(y) = \prod_{r=1}^{k} (y - t_{j+r}), $$
    ///
    /// with $i = j$ for the first `len(x) − 2` coefficients and $i = \mathrm{len}(x) - 2$ for
    /// the rest. Exact when the pieces join as smoothly as the knots allow (a `CubicSpline`
    /// with the same `bc_type`).
    ///
    /// # Errors
    /// [`ErrorKind::TooFewPoints`] for fewer than 2 breakpoints; [`ErrorKind::InvalidLength`]
    /// when `c` does not have `(k + 1)(len(x) − 1) · columns` entries or `order` is 0;
    /// [`ErrorKind::UnsortedKnots`] unless the breakpoints increase strictly; the errors of
    /// [`ColumnSpline::new`].
    pub fn from_power_basis(
        x: &[f64],
        c: &[f64],
        order: usize,
        columns: usize,
        bc: PowerBasisKnots,
    ) -> Result<Self> {
        let n = x.len();
        if n < 2 {
            return Err(Error::new(
                ErrorKind::TooFewPoints,
                format!("a piecewise polynomial needs at least 2 breakpoints, got {n}"),
            ));
        }
        if order == 0 || Some(c.len()) != order.checked_mul((n - 1) * columns) || columns == 0 {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "{} power coefficients do not fill order {order} × {} intervals × {columns} columns",
                    c.len(),
                    n - 1
                ),
            ));
        }
        if let Some(i) = (1..n).find(|&i| !(x[i] > x[i - 1])) {
            return Err(Error::new(
                ErrorKind::UnsortedKnots,
                format!(
                    "the breakpoints must increase strictly: x[{i}] = {} follows {}",
                    x[i],
                    x[i - 1]
                ),
            ));
        }
        let k = order - 1;
        let t: Vec<f64> = match bc {
            PowerBasisKnots::NotAKnot if n > k => KnotVector::not_a_knot(k, x)?.into_knots(),
            PowerBasisKnots::NotAKnot => KnotVector::bezier(k, x[0], x[n - 1])?.into_knots(),
            PowerBasisKnots::Augmented => {
                let mut t = Vec::with_capacity(n + 2 * k);
                t.extend(std::iter::repeat_n(x[0], k));
                t.extend_from_slice(x);
                t.extend(std::iter::repeat_n(x[n - 1], k));
                t
            }
            PowerBasisKnots::Periodic => periodic_knots(x, k),
        };
        let count = t.len() - k - 1;
        let mut coefficients = vec![0.0; count * columns];
        let mut factorial_k = 1.0;
        for i in 1..=k {
            factorial_k *= i as f64;
        }
        let mut dual = [0.0; MAX_ORDER];
        for j in 0..count {
            let i = j.min(n - 2);
            // Taylor coefficients of p_{j,k} at x_i: dual[d] = D^d p(x_i) / d!.
            dual.fill(0.0);
            dual[0] = 1.0;
            for r in 1..=k {
                let shift = x[i] - t[j + r];
                for d in (0..=r).rev() {
                    let lower = if d > 0 { dual[d - 1] } else { 0.0 };
                    dual[d] = dual[d] * shift + lower;
                }
            }
            let mut factorial_m = 1.0; // m!
            let mut falling = factorial_k; // (k − m)!
            for m in 0..=k {
                if m > 0 {
                    factorial_m *= m as f64;
                    falling /= (k + 1 - m) as f64;
                }
                let weight = falling / factorial_k
                    * if (k - m) % 2 == 0 { 1.0 } else { -1.0 }
                    * dual[m]
                    * factorial_m;
                for col in 0..columns {
                    coefficients[j * columns + col] +=
                        weight * c[(m * (n - 1) + i) * columns + col];
                }
            }
        }
        ColumnSpline::new(t, coefficients, k, columns)
    }
}

impl ColumnSpline {
    /// The knots of scipy's periodic interpolation (`_periodic_knots(x, k)`, used by
    /// `make_interp_spline(…, bc_type='periodic')` and `from_power_basis`): the abscissae
    /// (for even `k` the interior ones moved back by half a step), extended on each side by
    /// `k` knots continued with the period's steps; `len(x) + 2k` knots.
    ///
    /// # Panics
    /// If `x` has fewer than 2 entries.
    #[must_use]
    pub fn periodic_knots(x: &[f64], k: usize) -> Vec<f64> {
        periodic_knots(x, k)
    }
}

/// scipy's `_periodic_knots(x, k)`.
fn periodic_knots(x: &[f64], k: usize) -> Vec<f64> {
    let n = x.len();
    let mut xc = x.to_vec();
    if k % 2 == 0 {
        for i in 1..n - 1 {
            xc[i] -= (x[i] - x[i - 1]) / 2.0;
        }
    }
    let dx: Vec<f64> = xc.windows(2).map(|w| w[1] - w[0]).collect();
    let mut t = vec![0.0; n + 2 * k];
    t[k..k + n].copy_from_slice(&xc);
    let len = t.len();
    for i in 0..k {
        t[k - i - 1] = t[k - i] - dx[dx.len() - 1 - (i % (n - 1))];
        t[len - k + i] = t[len - k + i - 1] + dx[i % (n - 1)];
    }
    t
}
