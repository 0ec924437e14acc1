//! Tensor-product splines in any number of dimensions with the semantics of scipy's
//! `scipy.interpolate.NdBSpline(t, c, k, extrapolate=True)` (scipy 1.17).
//!
//! An [`NdSpline`] in `d ≥ 1` dimensions holds one knot vector $t^{(e)}$ and one degree
//! $k_e$ per dimension and a coefficient array of shape $n_1 \times \dots \times n_d$
//! (flattened row-major, the last dimension fastest) with `m ≥ 1` trailing value columns:
//!
//! $$ s_j(x) = \sum_{i_1, …, i_d} c_{i_1 … i_d, j} \prod_{e=1}^{d} B_{i_e, k_e}(x_e; t^{(e)}). $$
//!
//! Evaluation computes, per point, one span and one row of basis values (or derivatives)
//! per dimension, then the $\prod_e (k_e + 1)$ products for all columns in one pass, with
//! no allocation per point. [`NdSpline::design_matrix`] gives scipy's
//! `NdBSpline.design_matrix` as a CSR matrix.
//!
//! ```
//! use spline_geom::NdSpline;
//! // s(x, y) = x·y on [0, 1]², bilinear: coefficients at the corners.
//! let t = vec![vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]];
//! let s = NdSpline::new(t, vec![0.0, 0.0, 0.0, 1.0], &[1, 1], 1, true)?;
//! let mut out = [0.0; 2];
//! let nan = s.eval_into(&[0.5, 0.25, 2.0, 3.0], &[0, 0], true, &mut out)?;
//! assert_eq!((nan, out), (0, [0.125, 6.0]));
//! # Ok::<(), spline_core::Error>(())
//! ```

use crate::columns::{check_knots, check_rows, check_scipy_knots, without_empty_basis};
use spline_core::{Error, ErrorKind, KnotVector, Result};
use work::{Dims, Work};

mod design;
mod work;

/// A tensor-product spline in `d ≥ 1` dimensions with `m ≥ 1` value columns: the
/// container behind scipy's `NdBSpline` with the trailing dimensions of `c` flattened.
///
/// **Knot vectors accepted** (per dimension, as [`crate::ColumnSpline`]): at least
/// `2k + 2` finite knots in non-decreasing order with $t_k < t_n$ and `k ≤ 32`. A knot
/// repeated more than `k + 1` times is accepted by [`NdSpline::new`] as scipy accepts it: the
/// basis functions of a single point's support are dropped with their coefficients (the
/// same function), so [`NdSpline::knot_vectors`] and [`NdSpline::coefficients`] are those of
/// the reduced form. Unlike [`crate::ColumnSpline`], an empty end span is not given scipy's
/// zero beyond it (points there take the last non-empty span's polynomial).
///
/// **Evaluation conventions** (scipy's): right limits at interior knots, the left limit at
/// $t_n$; with extrapolation, points below $t_k$ (above $t_n$) use the polynomial of the
/// first (last) non-empty span of their dimension; without it, a point with any coordinate
/// outside $[t_k, t_n]$ gives a row of NaN. Points with a NaN or infinite coordinate give
/// a row of NaN in both modes. Partial derivatives of an order above the degree in some
/// dimension are zero (inside the domain), as scipy's.
#[derive(Clone, Debug)]
pub struct NdSpline {
    dims: Dims,
    coefficients: Vec<f64>,
    columns: usize,
    extrapolate: bool,
}

impl NdSpline {
    /// A tensor-product spline from one knot vector and one degree per dimension, the
    /// coefficients `c` flattened row-major from shape $n_1 \times \dots \times n_d \times m$
    /// ($n_e = \mathrm{len}(t_e) - k_e - 1$, `m = columns`), and the default of
    /// `extrapolate` (scipy's attribute; every evaluation takes the mode explicitly).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] without dimensions or for `columns == 0`;
    /// [`ErrorKind::InvalidLength`] for a different number of degrees and knot vectors;
    /// per dimension (the message names it) the knot errors of [`crate::ColumnSpline::new`];
    /// [`ErrorKind::InvalidLength`] unless `c.len()` $= m \prod_e n_e$; [`ErrorKind::NonFinite`] for a non-finite coefficient.
    pub fn new(
        t: Vec<Vec<f64>>,
        c: Vec<f64>,
        k: &[usize],
        columns: usize,
        extrapolate: bool,
    ) -> Result<Self> {
        if t.len() == k.len() && columns > 0 {
            for (e, (te, &ke)) in t.iter().zip(k).enumerate() {
                check_scipy_knots(te, ke)
                    .map_err(|err| err.context(format_args!("dimension {e}")))?;
            }
            // Knots repeated more than k + 1 times (scipy accepts them): the basis functions
            // of a single point's support are identically zero; evaluation works on the knots
            // without them and on the coefficients of the others (see `ColumnSpline`).
            let reduced: Vec<_> = t
                .iter()
                .zip(k)
                .map(|(te, &ke)| without_empty_basis(te, ke))
                .collect();
            if reduced.iter().any(Option::is_some) {
                let full: Vec<usize> = t.iter().zip(k).map(|(te, &ke)| te.len() - ke - 1).collect();
                let rows = full.iter().try_fold(1usize, |a, &n| a.checked_mul(n));
                if rows.and_then(|r| r.checked_mul(columns)) != Some(c.len()) {
                    let shape: Vec<String> = full.iter().map(ToString::to_string).collect();
                    return Err(Error::new(
                        ErrorKind::InvalidLength,
                        format!(
                            "Knots, coefficients and degree are inconsistent: the knots need coefficients of shape ({}) with {columns} columns, got {} values",
                            shape.join(", "),
                            c.len()
                        ),
                    ));
                }
                let mut kept_rows = vec![0usize];
                for (n, r) in full.iter().zip(&reduced) {
                    let indices: Vec<usize> = match r {
                        Some((_, kept)) => kept.clone(),
                        None => (0..*n).collect(),
                    };
                    kept_rows = kept_rows
                        .iter()
                        .flat_map(|&row| indices.iter().map(move |&i| row * n + i))
                        .collect();
                }
                let gathered = kept_rows
                    .iter()
                    .flat_map(|&row| c[row * columns..(row + 1) * columns].iter().copied())
                    .collect();
                let t = t
                    .into_iter()
                    .zip(reduced)
                    .map(|(te, r)| r.map_or(te, |(knots, _)| knots))
                    .collect();
                let knots = knot_vectors(t, k)?;
                return Self::from_knot_vectors(knots, gathered, columns, extrapolate);
            }
        }
        let knots = knot_vectors(t, k)?;
        Self::from_knot_vectors(knots, c, columns, extrapolate)
    }

    /// [`NdSpline::new`] with validated knot vectors (each with its degree).
    ///
    /// # Errors
    /// As [`NdSpline::new`] for the dimensions and the coefficients.
    pub fn from_knot_vectors(
        knots: Vec<KnotVector<f64>>,
        c: Vec<f64>,
        columns: usize,
        extrapolate: bool,
    ) -> Result<Self> {
        if columns == 0 {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "a spline needs at least one column of coefficients",
            )
            .with_counts(1, 0));
        }
        let dims = Dims::new(knots)?;
        let expected = dims.rows.checked_mul(columns);
        if expected != Some(c.len()) {
            let shape: Vec<String> = dims.shape.iter().map(ToString::to_string).collect();
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "Knots, coefficients and degree are inconsistent: the knots need coefficients of shape ({}) with {columns} columns ({} values), got {}",
                    shape.join(", "),
                    dims.rows.saturating_mul(columns),
                    c.len()
                ),
            ));
        }
        if let Some(i) = c.iter().position(|v| !v.is_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!(
                    "coefficient {i} (row {}, column {}) is not finite ({})",
                    i / columns,
                    i % columns,
                    c[i]
                ),
            )
            .with_index(i));
        }
        Ok(Self {
            dims,
            coefficients: c,
            columns,
            extrapolate,
        })
    }

    /// The number of dimensions `d`.
    #[must_use]
    pub fn ndim(&self) -> usize {
        self.dims.ndim()
    }

    /// The knot vectors, one per dimension, each with its degree.
    #[must_use]
    pub fn knot_vectors(&self) -> &[KnotVector<f64>] {
        &self.dims.knots
    }

    /// The degrees $k_e$.
    #[must_use]
    pub fn degrees(&self) -> Vec<usize> {
        self.dims.knots.iter().map(KnotVector::degree).collect()
    }

    /// The shape $n_1, …, n_d$ of the coefficient array (without the columns).
    #[must_use]
    pub fn shape(&self) -> &[usize] {
        &self.dims.shape
    }

    /// The number of value columns `m`.
    #[must_use]
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// The coefficients, flattened row-major ($n_1 \times \dots \times n_d \times m$).
    #[must_use]
    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// The default extrapolation mode (scipy's `extrapolate` attribute).
    #[must_use]
    pub fn extrapolate(&self) -> bool {
        self.extrapolate
    }

    /// [`ErrorKind::InvalidLength`] unless `nu` holds one derivative order per dimension.
    fn check_orders(&self, nu: &[usize]) -> Result<()> {
        let d = self.ndim();
        if nu.len() == d {
            return Ok(());
        }
        Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "invalid number of derivative orders: {} for ndim = {d}",
                nu.len()
            ),
        ))
    }

    /// Consumes the spline, returning the knot vectors and the coefficients.
    #[must_use]
    pub fn into_parts(self) -> (Vec<KnotVector<f64>>, Vec<f64>) {
        (self.dims.knots, self.coefficients)
    }

    /// Evaluates the partial derivative of orders `nu` (one per dimension; an empty slice
    /// for values) of every column at the points `xi` (row-major, `N × d`) into `out`
    /// (row-major, `N × m`): `out[i m + j]` $= \partial^{\nu} s_j(x_i)$.
    ///
    /// Rows that scipy fills with NaN are NaN here too, and their number is returned: points
    /// with a NaN or infinite coordinate, and with `extrapolate == false` points with a
    /// coordinate outside its base interval $[t_k, t_n]$. Every other row is finite. Orders
    /// above the degree give zero rows.
    ///
    /// One span search and one basis row per dimension and point, then
    /// $\prod_e (k_e + 1)$ products for all columns; no allocation per point.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless `xi.len()` is a multiple of `d`, `nu` is empty or
    /// has `d` entries, and `out.len()` $= N m$.
    pub fn eval_into(
        &self,
        xi: &[f64],
        nu: &[usize],
        extrapolate: bool,
        out: &mut [f64],
    ) -> Result<usize> {
        let d = self.ndim();
        let npts = self.dims.points(xi)?;
        let zeros;
        let nu = if nu.is_empty() {
            zeros = vec![0; d];
            &zeros[..]
        } else {
            nu
        };
        self.check_orders(nu)?;
        let m = self.columns;
        check_rows(npts, m, out.len())?;
        let vanishes = self
            .dims
            .knots
            .iter()
            .zip(nu)
            .any(|(kv, &n)| n > kv.degree());
        // Values in two or three dimensions of one degree from 1 to 5: the kernel with the
        // sizes as constants (the same operations, every array on the stack).
        let degrees_equal = self
            .dims
            .knots
            .iter()
            .all(|kv| kv.degree() == self.dims.knots[0].degree());
        if !vanishes && degrees_equal {
            macro_rules! fixed {
                ($d:literal) => {
                    match self.dims.knots[0].degree() {
                        1 => return Ok(self.eval_fixed::<$d, 2>(xi, nu, extrapolate, out)),
                        2 => return Ok(self.eval_fixed::<$d, 3>(xi, nu, extrapolate, out)),
                        3 => return Ok(self.eval_fixed::<$d, 4>(xi, nu, extrapolate, out)),
                        4 => return Ok(self.eval_fixed::<$d, 5>(xi, nu, extrapolate, out)),
                        5 => return Ok(self.eval_fixed::<$d, 6>(xi, nu, extrapolate, out)),
                        _ => {}
                    }
                };
            }
            match d {
                2 => fixed!(2),
                3 => fixed!(3),
                _ => {}
            }
        }
        // Orders above the degree: zero, only the NaN rows are computed.
        let nu_used: Vec<usize> = if vanishes { vec![0; d] } else { nu.to_vec() };
        let mut work = Work::new(&self.dims, &nu_used);
        let mut nan = 0;
        for (x, row) in xi.chunks_exact(d).zip(out.chunks_exact_mut(m)) {
            let Some(first) = work.prepare(&self.dims, x, &nu_used, extrapolate) else {
                row.fill(f64::NAN);
                nan += 1;
                continue;
            };
            if vanishes {
                row.fill(0.0);
                continue;
            }
            let c = &self.coefficients;
            if m == 1 {
                let mut acc = 0.0;
                work.for_each_line(&self.dims, first, |r, p, inner| {
                    let dot: f64 = inner
                        .iter()
                        .zip(&c[r..r + inner.len()])
                        .map(|(b, c)| b * c)
                        .sum();
                    acc += p * dot;
                });
                row[0] = acc;
            } else {
                row.fill(0.0);
                work.for_each_line(&self.dims, first, |r, p, inner| {
                    for (i, &b) in inner.iter().enumerate() {
                        let w = p * b;
                        for (o, &cv) in row.iter_mut().zip(&c[(r + i) * m..(r + i + 1) * m]) {
                            *o += w * cv;
                        }
                    }
                });
            }
        }
        Ok(nan)
    }

    /// Values or partial derivatives of orders `nu` (each at most `N − 1`) in `D` dimensions
    /// of degree `N − 1` in every dimension (see [`NdSpline::eval_into`]): basis rows and
    /// spans on the stack, the tensor sum as `N` or `N²` dot products of `N` coefficients.
    /// Returns the number of NaN rows.
    fn eval_fixed<const D: usize, const N: usize>(
        &self,
        xi: &[f64],
        nu: &[usize],
        extrapolate: bool,
        out: &mut [f64],
    ) -> usize {
        let dims = &self.dims;
        let m = self.columns;
        let c = &self.coefficients;
        let domains: [(f64, f64); D] = std::array::from_fn(|e| dims.knots[e].domain());
        let strides: [usize; D] = std::array::from_fn(|e| dims.strides[e]);
        let orders: [usize; D] = std::array::from_fn(|e| nu[e]);
        let mut hints = [usize::MAX; D];
        let mut scratch = [[0.0; N]; N];
        let mut nan = 0;
        for (x, row) in xi.chunks_exact(D).zip(out.chunks_exact_mut(m)) {
            let mut basis = [[0.0; N]; D];
            let mut first = 0;
            let mut outside = false;
            for e in 0..D {
                let u = x[e];
                let (a, b) = domains[e];
                let kv = &dims.knots[e];
                let inside = u >= a && u <= b;
                let order = orders[e];
                let span = if order > 0 && (inside || (extrapolate && u.is_finite())) {
                    let span = if inside {
                        dims.batches[e].span_from(kv, u, hints[e])
                    } else {
                        kv.span_in_domain(u)
                    };
                    let table = scratch.as_flattened_mut();
                    kv.basis_derivatives(span, u, order, &mut table[..(order + 1) * N]);
                    basis[e] = scratch[order];
                    span
                } else if inside {
                    let (span, v) = dims.batches[e].eval_fixed_from::<N>(kv, u, hints[e]);
                    basis[e] = v;
                    span
                } else if extrapolate && u.is_finite() {
                    let span = kv.span_in_domain(u);
                    basis[e] = kv.basis_values_fixed::<N>(span, u);
                    span
                } else {
                    outside = true;
                    break;
                };
                hints[e] = span;
                first += (span + 1 - N) * strides[e];
            }
            if outside {
                row.fill(f64::NAN);
                nan += 1;
                continue;
            }
            let inner = &basis[D - 1];
            let line = |r: usize, p: f64, row: &mut [f64]| {
                if m == 1 {
                    let cs = &c[r..r + N];
                    let dot: f64 = inner.iter().zip(cs).map(|(b, c)| b * c).sum();
                    row[0] += p * dot;
                } else {
                    for (i, &bv) in inner.iter().enumerate() {
                        let w = p * bv;
                        for (o, &cv) in row.iter_mut().zip(&c[(r + i) * m..(r + i + 1) * m]) {
                            *o += w * cv;
                        }
                    }
                }
            };
            row.fill(0.0);
            if D == 2 {
                for (i0, &v0) in basis[0].iter().enumerate() {
                    line(first + i0 * strides[0], v0, row);
                }
            } else {
                for (i0, &v0) in basis[0].iter().enumerate() {
                    let r0 = first + i0 * strides[0];
                    for (i1, &v1) in basis[1].iter().enumerate() {
                        line(r0 + i1 * strides[1], v0 * v1, row);
                    }
                }
            }
        }
        nan
    }

    /// Evaluates into a new vector (see [`NdSpline::eval_into`]), with the spline's own
    /// extrapolation mode.
    ///
    /// # Errors
    /// As [`NdSpline::eval_into`].
    pub fn eval(&self, xi: &[f64], nu: &[usize]) -> Result<Vec<f64>> {
        let npts = self.dims.points(xi)?;
        let mut out = vec![0.0; npts.saturating_mul(self.columns)];
        self.eval_into(xi, nu, self.extrapolate, &mut out)?;
        Ok(out)
    }
}

/// Validates one knot vector per dimension with scipy's rules (see [`NdSpline`]); the
/// error names the dimension.
///
/// # Errors
/// [`ErrorKind::InvalidLength`] unless there are as many degrees as knot vectors (with
/// `(len(t), len(k))` as [`Error::counts`]); [`ErrorKind::InvalidArgument`] without knot
/// vectors; the knot errors of [`crate::ColumnSpline::new`].
pub fn knot_vectors(t: Vec<Vec<f64>>, k: &[usize]) -> Result<Vec<KnotVector<f64>>> {
    if t.len() != k.len() {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("len(t) = {} != len(k) = {}", t.len(), k.len()),
        )
        .with_counts(t.len(), k.len()));
    }
    if t.is_empty() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "a tensor-product spline needs at least one dimension",
        )
        .with_counts(1, 0));
    }
    t.into_iter()
        .zip(k)
        .enumerate()
        .map(|(e, (te, &ke))| {
            check_knots(te, ke).map_err(|err| err.context(format_args!("dimension {e}")))
        })
        .collect()
}

#[cfg(test)]
mod tests;
