//! Splines with many coefficient columns on one knot vector, with the semantics of
//! `scipy.interpolate.BSpline` (scipy 1.17): the Rust side of a drop-in replacement.
//!
//! A [`ColumnSpline`] holds a knot vector `t`, a degree `k` and an `rows × m` row-major
//! coefficient matrix: `m ≥ 1` columns share the knots (scipy's trailing dimensions
//! flattened; a complex spline is two real columns per complex one). Every per-point kernel
//! computes the basis once and combines the coefficient rows for all columns in one pass.
//!
//! ```
//! use spline_geom::{ColumnSpline, Extrapolate};
//! // Two columns: x ↦ x and x ↦ 1 as linear splines on [0, 2].
//! let s = ColumnSpline::new(vec![0.0, 0.0, 1.0, 2.0, 2.0], vec![0.0, 1.0, 1.0, 1.0, 2.0, 1.0], 1, 2)?;
//! let mut out = [0.0; 4];
//! s.eval_into(&[0.5, 3.0], 0, Extrapolate::On, &mut out)?;
//! assert_eq!(out, [0.5, 1.0, 3.0, 1.0]);
//! # Ok::<(), spline_core::Error>(())
//! ```

mod container;
mod design;
mod ops;
mod roots;

pub use container::{ColumnSpline, Extrapolate};
use container::{EmptyEnd, invalid};
pub(crate) use container::{check_knots, check_rows, check_scipy_knots, without_empty_basis};
pub use design::PowerBasisKnots;

use std::sync::OnceLock;

use spline_core::{BatchBasis, Error, ErrorKind, KnotVector, Result};

impl ColumnSpline {
    /// A spline from knots `t`, row-major coefficients `c` (`rows × columns`, `rows ≥ n`)
    /// and degree `k`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] for `columns == 0` or non-finite coefficients;
    /// [`ErrorKind::InvalidLength`] when `c.len()` is not a multiple of `columns` or the
    /// rows are fewer than `n = len(t) − k − 1` ("Knots, coefficients and degree are
    /// inconsistent"), or with fewer than `2k + 2` knots ("Need at least … knots");
    /// [`ErrorKind::NonFinite`] ("Knots should not have nans or infs"),
    /// [`ErrorKind::UnsortedKnots`] ("Knots must be in a non-decreasing order"),
    /// [`ErrorKind::EmptyDomain`] ("Need at least two internal knots"),
    /// [`ErrorKind::DegreeTooHigh`] above [`spline_core::MAX_DEGREE`].
    pub fn new(t: Vec<f64>, c: Vec<f64>, k: usize, columns: usize) -> Result<Self> {
        check_scipy_knots(&t, k)?;
        match without_empty_basis(&t, k) {
            None => {
                let knots = KnotVector::new(k, t)?;
                Self::from_knot_vector(knots, c, columns)
            }
            Some((reduced, kept)) => {
                let knots = KnotVector::new(k, reduced)?;
                let mut spline = Self::assemble(t, knots, c, columns)?;
                let m = columns;
                let rows = kept
                    .iter()
                    .flat_map(|&i| spline.coefficients[i * m..(i + 1) * m].iter().copied())
                    .collect();
                spline.reduced = Some(rows);
                Ok(spline)
            }
        }
    }

    /// [`ColumnSpline::new`] with a validated knot vector.
    ///
    /// # Errors
    /// As [`ColumnSpline::new`] for the coefficients.
    pub fn from_knot_vector(knots: KnotVector<f64>, c: Vec<f64>, columns: usize) -> Result<Self> {
        let t = knots.knots().to_vec();
        Self::assemble(t, knots, c, columns)
    }

    /// The spline of knots `t` evaluated on `knots` (the same, or `t` without the knots of
    /// empty basis functions), without reduced coefficients yet.
    fn assemble(t: Vec<f64>, knots: KnotVector<f64>, c: Vec<f64>, columns: usize) -> Result<Self> {
        if columns == 0 {
            return Err(
                invalid("a spline needs at least one column of coefficients").with_counts(1, 0),
            );
        }
        if c.len() % columns != 0 {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "{} coefficients do not fill rows of {columns} columns",
                    c.len()
                ),
            ));
        }
        let rows = c.len() / columns;
        let k = knots.degree();
        let n = t.len() - k - 1;
        if rows < n {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "Knots, coefficients and degree are inconsistent: {} knots of degree {k} need {n} coefficient rows, got {rows}",
                    t.len(),
                ),
            )
            .with_counts(n, rows));
        }
        if let Some(i) = c.iter().position(|v| !v.is_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!(
                    "coefficient ({}, {}) is not finite ({})",
                    i / columns,
                    i % columns,
                    c[i]
                ),
            )
            .with_index(i));
        }
        let empty_end = |span: usize| {
            (t[span] == t[span + 1]).then_some(if k == 0 {
                EmptyEnd::Row(span)
            } else {
                EmptyEnd::Zero
            })
        };
        let empty_ends = [empty_end(k), empty_end(n - 1)];
        Ok(Self {
            t,
            knots,
            coefficients: c,
            reduced: None,
            empty_ends,
            rows,
            columns,
            batch: OnceLock::new(),
        })
    }

    /// The knots `t`, as given.
    #[must_use]
    pub fn knots(&self) -> &[f64] {
        &self.t
    }

    /// The knot vector evaluation works on, with its degree: [`ColumnSpline::knots`] without
    /// the knots of identically zero basis functions (the same knots unless some value repeats
    /// more than `k + 1` times); its coefficient rows are
    /// [`ColumnSpline::evaluation_coefficients`].
    #[must_use]
    pub fn knot_vector(&self) -> &KnotVector<f64> {
        &self.knots
    }

    /// The coefficient rows of the basis functions of [`ColumnSpline::knot_vector`]
    /// (row-major, `columns` per row): [`ColumnSpline::coefficients`] without the rows of
    /// identically zero basis functions.
    #[must_use]
    pub fn evaluation_coefficients(&self) -> &[f64] {
        self.reduced.as_deref().unwrap_or(&self.coefficients)
    }

    /// The degree `k`.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// The coefficients, row-major (`rows × columns`).
    #[must_use]
    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// Consumes the spline, returning knots and coefficients.
    #[must_use]
    pub fn into_parts(self) -> (Vec<f64>, Vec<f64>) {
        (self.t, self.coefficients)
    }

    /// The number of coefficient rows (at least [`ColumnSpline::num_basis`]).
    #[must_use]
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// The number of columns `m`.
    #[must_use]
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// The number of basis functions `n = len(t) − k − 1`.
    #[must_use]
    pub fn num_basis(&self) -> usize {
        self.t.len() - self.degree() - 1
    }

    /// The base interval $[t_k, t_n]$.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        self.knots.domain()
    }

    /// Where `x` is evaluated under `mode`, or `None` for a NaN row.
    #[inline(always)]
    fn mapped(&self, x: f64, mode: Extrapolate, (a, b): (f64, f64)) -> Option<f64> {
        match mode {
            Extrapolate::On => x.is_finite().then_some(x),
            Extrapolate::Off => (x >= a && x <= b).then_some(x),
            Extrapolate::Periodic => {
                let u = a + (x - a).rem_euclid(b - a);
                u.is_finite().then_some(u)
            }
        }
    }

    /// Evaluates the derivative of order `nu` (0 for values) of every column at every `x`
    /// into `out`, row-major: `out[i m + j]` $= s_j^{(\nu)}(x_i)$. Derivatives above the
    /// degree are zero (as scipy's).
    ///
    /// Rows that scipy fills with NaN are NaN here too, and their number is returned: NaN
    /// (or infinite) `x` in every mode, and `x` outside $[t_k, t_n]$ with
    /// [`Extrapolate::Off`]. Every other row is finite. At interior knots the right limit
    /// is taken, at $t_n$ the left one.
    ///
    /// One span search and one basis evaluation per point, no allocation per point. For
    /// derivatives at many points (at least as many as basis functions) the derivative
    /// spline is built once and its values evaluated with the fixed-size kernels.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless `out.len() == x.len() · columns`.
    pub fn eval_into(
        &self,
        x: &[f64],
        nu: usize,
        mode: Extrapolate,
        out: &mut [f64],
    ) -> Result<usize> {
        check_rows(x.len(), self.columns, out.len())?;
        let k = self.degree();
        if nu > k {
            let domain = self.domain();
            let mut nan = 0;
            for (&xi, row) in x.iter().zip(out.chunks_exact_mut(self.columns)) {
                if self.mapped(xi, mode, domain).is_some() {
                    row.fill(0.0);
                } else {
                    row.fill(f64::NAN);
                    nan += 1;
                }
            }
            return Ok(nan);
        }
        if nu > 0 && x.len() >= self.num_basis() {
            // Many points: evaluate the derivative spline (built once, O(n m)) with the
            // fixed-size value kernels. Its end pieces are the derivatives of the end pieces,
            // so extrapolation agrees. Knots of multiplicity k + 1 inside have no derivative
            // spline: the general path below handles them.
            if let Ok(derivative) = self.derivative(nu) {
                return derivative.eval_into(x, 0, mode, out);
            }
        }
        Ok(if nu == 0 {
            match k {
                0 => self.eval_fixed::<1>(x, mode, out),
                1 => self.eval_fixed::<2>(x, mode, out),
                2 => self.eval_fixed::<3>(x, mode, out),
                3 => self.eval_fixed::<4>(x, mode, out),
                4 => self.eval_fixed::<5>(x, mode, out),
                5 => self.eval_fixed::<6>(x, mode, out),
                _ => self.eval_general(x, 0, mode, out),
            }
        } else {
            self.eval_general(x, nu, mode, out)
        })
    }

    /// Evaluates at many points into a new vector (see [`ColumnSpline::eval_into`]).
    ///
    /// # Errors
    /// As [`ColumnSpline::eval_into`] (never for a correct size).
    pub fn eval(&self, x: &[f64], nu: usize, mode: Extrapolate) -> Result<Vec<f64>> {
        let mut out = vec![0.0; x.len().saturating_mul(self.columns)];
        self.eval_into(x, nu, mode, &mut out)?;
        Ok(out)
    }

    /// The batch tables, built on first use.
    fn batch(&self) -> &BatchBasis<f64> {
        self.batch.get_or_init(|| BatchBasis::new(&self.knots))
    }

    /// The knot vector of degree `k` that [`ColumnSpline::new`] accepts (the same checks
    /// and messages), for callers that build the coefficients afterwards.
    ///
    /// # Errors
    /// As [`ColumnSpline::new`] for the knots.
    pub fn check_knots(t: Vec<f64>, k: usize) -> Result<KnotVector<f64>> {
        check_knots(t, k)
    }

    /// The span for a point `u` that is finite: inside the base interval by the batch
    /// tables, outside the first or last non-empty span.
    #[inline(always)]
    fn span_of(&self, u: f64, (a, b): (f64, f64), hint: usize) -> usize {
        if u < a {
            self.knots.span_in_domain(a)
        } else if u > b {
            self.knots.span_in_domain(b)
        } else {
            self.batch().span_from(&self.knots, u, hint)
        }
    }

    /// What scipy gives at `u` when `u` is beyond an end whose span is empty.
    #[inline(always)]
    fn beyond_empty_end(&self, u: f64, (a, b): (f64, f64)) -> Option<EmptyEnd> {
        match self.empty_ends {
            [None, None] => None,
            [low, high] => {
                if u < a {
                    low
                } else if u >= b {
                    high
                } else {
                    None
                }
            }
        }
    }

    /// Fills `row` with the derivative of order `nu` beyond an empty end span.
    fn fill_empty_end(&self, end: EmptyEnd, nu: usize, row: &mut [f64]) {
        let m = self.columns;
        match end {
            EmptyEnd::Row(r) if nu == 0 => {
                row.copy_from_slice(&self.coefficients[r * m..(r + 1) * m]);
            }
            _ => row.fill(0.0),
        }
    }

    /// Combines rows `first ..= first + width − 1` of the coefficients with `basis` into
    /// `row` (all columns in one pass).
    #[inline(always)]
    fn combine(&self, first: usize, basis: &[f64], row: &mut [f64]) {
        let m = self.columns;
        let c = &self.evaluation_coefficients()[first * m..(first + basis.len()) * m];
        if m == 1 {
            row[0] = basis.iter().zip(c).map(|(b, c)| b * c).sum();
            return;
        }
        row.fill(0.0);
        for (&b, crow) in basis.iter().zip(c.chunks_exact(m)) {
            for (o, &cv) in row.iter_mut().zip(crow) {
                *o += b * cv;
            }
        }
    }

    /// Values for degree `N − 1` with the fixed-size basis kernels.
    fn eval_fixed<const N: usize>(&self, x: &[f64], mode: Extrapolate, out: &mut [f64]) -> usize {
        let domain = self.domain();
        let (a, b) = domain;
        let m = self.columns;
        let coefficients = self.evaluation_coefficients();
        let batch = self.batch();
        let mut hint = usize::MAX;
        let mut nan = 0;
        for (&xi, row) in x.iter().zip(out.chunks_exact_mut(m)) {
            let Some(u) = self.mapped(xi, mode, domain) else {
                row.fill(f64::NAN);
                nan += 1;
                continue;
            };
            if let Some(end) = self.beyond_empty_end(u, domain) {
                self.fill_empty_end(end, 0, row);
                continue;
            }
            let (span, basis) = if u >= a && u <= b {
                batch.eval_fixed_from::<N>(&self.knots, u, hint)
            } else {
                let span = self.span_of(u, domain, hint);
                (span, self.knots.basis_values_fixed::<N>(span, u))
            };
            hint = span;
            // All columns from the N rows starting at span + 1 − N; the sum over the basis
            // unrolls.
            let c = &coefficients[(span + 1 - N) * m..(span + 1) * m];
            for (j, o) in row.iter_mut().enumerate() {
                let mut acc = 0.0;
                for r in 0..N {
                    acc += basis[r] * c[r * m + j];
                }
                *o = acc;
            }
        }
        nan
    }

    /// Values or derivatives of order `nu ≤ k` for any degree.
    fn eval_general(&self, x: &[f64], nu: usize, mode: Extrapolate, out: &mut [f64]) -> usize {
        let domain = self.domain();
        let k = self.degree();
        let width = k + 1;
        let mut scratch = vec![0.0; (nu + 1) * width];
        let mut hint = usize::MAX;
        let mut nan = 0;
        for (&xi, row) in x.iter().zip(out.chunks_exact_mut(self.columns)) {
            let Some(u) = self.mapped(xi, mode, domain) else {
                row.fill(f64::NAN);
                nan += 1;
                continue;
            };
            if let Some(end) = self.beyond_empty_end(u, domain) {
                self.fill_empty_end(end, nu, row);
                continue;
            }
            let span = self.span_of(u, domain, hint);
            hint = span;
            if nu == 0 {
                self.knots.basis_values(span, u, &mut scratch);
            } else {
                self.knots.basis_derivatives(span, u, nu, &mut scratch);
            }
            self.combine(span - k, &scratch[nu * width..(nu + 1) * width], row);
        }
        nan
    }
}

#[cfg(test)]
mod tests;
