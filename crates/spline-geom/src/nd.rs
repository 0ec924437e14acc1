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

use crate::columns::{check_knots, check_scipy_knots, without_empty_basis};
use nalgebra_sparse::CsrMatrix;
use spline_core::{BatchBasis, Error, ErrorKind, KnotVector, Result};

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

/// The knot vectors of the dimensions with their batch tables and the row strides of the
/// coefficient array.
#[derive(Clone, Debug)]
struct Dims {
    knots: Vec<KnotVector<f64>>,
    batches: Vec<BatchBasis<f64>>,
    /// `n_e`, the number of basis functions of each dimension.
    shape: Vec<usize>,
    /// Row-major strides of the coefficient array in rows (the last is 1).
    strides: Vec<usize>,
    /// The product of the shape (the number of coefficient rows).
    rows: usize,
}

impl Dims {
    fn new(knots: Vec<KnotVector<f64>>) -> Result<Self> {
        if knots.is_empty() {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "a tensor-product spline needs at least one dimension",
            ));
        }
        let shape: Vec<usize> = knots.iter().map(KnotVector::num_basis).collect();
        let mut strides = vec![1usize; shape.len()];
        let mut rows = 1usize;
        for e in (0..shape.len()).rev() {
            strides[e] = rows;
            rows = rows.checked_mul(shape[e]).ok_or_else(|| {
                Error::new(
                    ErrorKind::InvalidLength,
                    "the coefficient array of the tensor product has too many entries",
                )
            })?;
        }
        let batches = knots.iter().map(BatchBasis::new).collect();
        Ok(Self {
            knots,
            batches,
            shape,
            strides,
            rows,
        })
    }

    fn ndim(&self) -> usize {
        self.knots.len()
    }

    fn widths(&self) -> impl Iterator<Item = usize> + '_ {
        self.knots.iter().map(|k| k.degree() + 1)
    }

    /// The number of products per point, $\prod_e (k_e + 1)$, checked.
    fn terms(&self) -> Result<usize> {
        self.widths()
            .try_fold(1usize, usize::checked_mul)
            .ok_or_else(|| {
                Error::new(
                    ErrorKind::InvalidLength,
                    "the tensor product has too many basis functions per point",
                )
            })
    }

    /// Checks `xi` (points × d) and returns the number of points.
    fn points(&self, xi: &[f64]) -> Result<usize> {
        let d = self.ndim();
        if xi.len() % d != 0 {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "{} coordinates do not make points of {d} coordinates (ndim = {d})",
                    xi.len()
                ),
            ));
        }
        Ok(xi.len() / d)
    }
}

/// The working memory of one batch of evaluations (allocated once per call).
struct Work {
    /// The basis rows of every dimension, concatenated (`k_e + 1` each).
    basis: Vec<f64>,
    /// Where each dimension's row starts in `basis`.
    offsets: Vec<usize>,
    widths: Vec<usize>,
    /// Room for one table of basis derivatives.
    scratch: Vec<f64>,
    hints: Vec<usize>,
    /// The odometer over the multi-index of the tensor sum, the partial products of the
    /// basis values and the partial row offsets of the levels above the innermost.
    index: Vec<usize>,
    partial: Vec<f64>,
    base: Vec<usize>,
}

impl Work {
    fn new(dims: &Dims, nu: &[usize]) -> Self {
        let widths: Vec<usize> = dims.widths().collect();
        let mut offsets = Vec::with_capacity(widths.len());
        let mut total = 0;
        for &w in &widths {
            offsets.push(total);
            total += w;
        }
        let scratch = widths
            .iter()
            .zip(nu)
            .map(|(&w, &n)| (n + 1) * w)
            .max()
            .unwrap_or(0);
        let d = widths.len();
        Self {
            basis: vec![0.0; total],
            offsets,
            widths,
            scratch: vec![0.0; scratch],
            hints: vec![usize::MAX; d],
            index: vec![0; d],
            partial: vec![0.0; d],
            base: vec![0; d],
        }
    }

    /// Basis values (`nu == 0`) or derivatives of order `nu ≤ k` of dimension `e` at `u`
    /// into `out[..k + 1]`, with the span, or `None` where the point gives NaN (`u` not
    /// finite, or outside the base interval without extrapolation). `scratch` holds at least
    /// `(nu + 1)(k + 1)` values. Writes the row into `self.basis`.
    #[inline(always)]
    fn basis(
        &mut self,
        dims: &Dims,
        e: usize,
        u: f64,
        nu: usize,
        extrapolate: bool,
    ) -> Option<usize> {
        let hint = self.hints[e];
        let o = self.offsets[e];
        let out = &mut self.basis[o..o + self.widths[e]];
        let scratch = &mut self.scratch;
        let kv = &dims.knots[e];
        let (a, b) = kv.domain();
        let inside = u >= a && u <= b;
        if !u.is_finite() || (!extrapolate && !inside) {
            return None;
        }
        let k = kv.degree();
        let w = k + 1;
        if nu > 0 {
            let span = if inside {
                dims.batches[e].span_from(kv, u, hint)
            } else {
                kv.span_in_domain(u)
            };
            kv.basis_derivatives(span, u, nu, scratch);
            out[..w].copy_from_slice(&scratch[nu * w..(nu + 1) * w]);
            return Some(span);
        }
        if !inside {
            let span = kv.span_in_domain(u);
            kv.basis_values(span, u, out);
            return Some(span);
        }
        let batch = &dims.batches[e];
        macro_rules! fixed {
            ($n:literal) => {{
                let (span, v) = batch.eval_fixed_from::<$n>(kv, u, hint);
                out[..$n].copy_from_slice(&v);
                span
            }};
        }
        Some(match k {
            1 => fixed!(2),
            2 => fixed!(3),
            3 => fixed!(4),
            4 => fixed!(5),
            5 => fixed!(6),
            _ => {
                let span = batch.span_from(kv, u, hint);
                kv.basis_values(span, u, out);
                span
            }
        })
    }

    /// Fills the basis rows for point `x`; returns the first coefficient row of the
    /// tensor sum, or `None` for a NaN row.
    #[inline(always)]
    fn prepare(
        &mut self,
        dims: &Dims,
        x: &[f64],
        nu: &[usize],
        extrapolate: bool,
    ) -> Option<usize> {
        let mut first = 0;
        for (e, &u) in x.iter().enumerate() {
            let w = self.widths[e];
            let span = self.basis(dims, e, u, nu[e], extrapolate)?;
            self.hints[e] = span;
            first += (span + 1 - w) * dims.strides[e];
        }
        Some(first)
    }

    /// Calls `f(row, weight, inner)` for every line of the tensor sum at the prepared point
    /// along the last dimension: the coefficient rows `row ..` (as many as `inner`, the
    /// last dimension's basis row) enter with the weights `weight · inner[i]`, `weight`
    /// the product of the other dimensions' basis values (rows in increasing order).
    #[inline(always)]
    fn for_each_line(&mut self, dims: &Dims, first: usize, mut f: impl FnMut(usize, f64, &[f64])) {
        let d = self.widths.len();
        // One, two and three dimensions as plain loops (the same products in the same
        // order as the odometer below).
        match d {
            1 => {
                f(first, 1.0, &self.basis[..self.widths[0]]);
                return;
            }
            2 => {
                let (b0, b1) = self.basis.split_at(self.widths[0]);
                let s0 = dims.strides[0];
                for (i0, &v0) in b0.iter().enumerate() {
                    f(first + i0 * s0, v0, b1);
                }
                return;
            }
            3 => {
                let (b0, rest) = self.basis.split_at(self.widths[0]);
                let (b1, b2) = rest.split_at(self.widths[1]);
                let (s0, s1) = (dims.strides[0], dims.strides[1]);
                for (i0, &v0) in b0.iter().enumerate() {
                    let r0 = first + i0 * s0;
                    for (i1, &v1) in b1.iter().enumerate() {
                        f(r0 + i1 * s1, v0 * v1, b2);
                    }
                }
                return;
            }
            _ => {}
        }
        let last = d - 1;
        for l in 0..last {
            self.index[l] = 0;
            let (p, b) = if l == 0 {
                (1.0, first)
            } else {
                (self.partial[l - 1], self.base[l - 1])
            };
            self.partial[l] = p * self.basis[self.offsets[l]];
            self.base[l] = b;
        }
        let inner = &self.basis[self.offsets[last]..self.offsets[last] + self.widths[last]];
        loop {
            let (p, b) = if last == 0 {
                (1.0, first)
            } else {
                (self.partial[last - 1], self.base[last - 1])
            };
            f(b, p, inner);
            // Advance the odometer over the outer levels.
            let mut l = last;
            loop {
                if l == 0 {
                    return;
                }
                l -= 1;
                self.index[l] += 1;
                if self.index[l] < self.widths[l] {
                    break;
                }
                self.index[l] = 0;
            }
            for j in l..last {
                let (p, b) = if j == 0 {
                    (1.0, first)
                } else {
                    (self.partial[j - 1], self.base[j - 1])
                };
                let i = self.index[j];
                self.partial[j] = p * self.basis[self.offsets[j] + i];
                self.base[j] = b + i * dims.strides[j];
            }
        }
    }
}

impl NdSpline {
    /// A tensor-product spline from one knot vector and one degree per dimension, the
    /// coefficients `c` flattened row-major from shape $n_1 \times \dots \times n_d \times m$
    /// ($n_e = \mathrm{len}(t_e) - k_e - 1$, `m = columns`), and the default of
    /// `extrapolate` (scipy's attribute; every evaluation takes the mode explicitly).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] without dimensions, for `columns == 0` or a different
    /// number of degrees and knot vectors; per dimension (the message names it) the knot
    /// errors of [`crate::ColumnSpline::new`]; [`ErrorKind::InvalidLength`] unless
    /// `c.len()` $= m \prod_e n_e$; [`ErrorKind::NonFinite`] for a non-finite coefficient.
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
            ));
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
        if nu.len() != d {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "invalid number of derivative orders: {} for ndim = {d}",
                    nu.len()
                ),
            ));
        }
        let m = self.columns;
        if npts.checked_mul(m) != Some(out.len()) {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "the output holds {} values; {npts} points of {m} columns need {}",
                    out.len(),
                    npts.saturating_mul(m)
                ),
            ));
        }
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

    /// The partial derivative of orders `nu` (one per dimension) as a spline, scipy's
    /// `NdBSpline.derivative(nu)`: along each dimension with $\nu_e > 0$ the coefficient
    /// lines are differentiated as one-dimensional splines ([`crate::ColumnSpline::derivative`],
    /// FITPACK's `splder`: the first and last knot dropped, the degree lowered by $\nu_e$),
    /// the other dimensions untouched. The extrapolation mode is kept.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless `nu` has `d` entries;
    /// [`ErrorKind::KnotMultiplicity`] when interior knots repeated $k_e + 1$ times make the
    /// spline non-differentiable.
    ///
    /// Along a dimension with $\nu_e > k_e$ the derivative is zero: scipy returns the zero
    /// spline of degree 0 on the same knots; this one is the zero spline of degree 0 on the
    /// distinct knots (the same function on the same base interval; the repeated knots of
    /// scipy's only add basis functions of empty support).
    pub fn derivative(&self, nu: &[usize]) -> Result<Self> {
        let d = self.ndim();
        if nu.len() != d {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "invalid number of derivative orders: {} for ndim = {d}",
                    nu.len()
                ),
            ));
        }
        let m = self.columns;
        let mut knots = self.dims.knots.clone();
        let mut shape = self.dims.shape.clone();
        let mut c = self.coefficients.clone();
        for (e, &order) in nu.iter().enumerate() {
            if order == 0 {
                continue;
            }
            if order > knots[e].degree() {
                // Identically zero along this dimension: scipy's zero spline of degree 0 on the
                // same knots, whose repeated knots only add empty basis functions, is the zero
                // spline of degree 0 on the distinct knots (the same base interval).
                let mut distinct = knots[e].knots().to_vec();
                distinct.dedup();
                let new_n = distinct.len() - 1;
                let before: usize = shape[..e].iter().product();
                let after: usize = shape[e + 1..].iter().product::<usize>() * m;
                c = vec![0.0; before * new_n * after];
                shape[e] = new_n;
                knots[e] = KnotVector::new(0, distinct)?;
                continue;
            }
            // The array as (before, n, after): move the axis to the front, so that the
            // lines along it are the columns of a one-dimensional spline.
            let n = shape[e];
            let before: usize = shape[..e].iter().product();
            let after: usize = shape[e + 1..].iter().product::<usize>() * m;
            let cols = before * after;
            let mut front = vec![0.0; c.len()];
            for b in 0..before {
                for i in 0..n {
                    let src = &c[(b * n + i) * after..(b * n + i + 1) * after];
                    front[i * cols + b * after..i * cols + (b + 1) * after].copy_from_slice(src);
                }
            }
            let line = crate::ColumnSpline::from_knot_vector(knots[e].clone(), front, cols)?
                .derivative(order)
                .map_err(|err| err.context(format_args!("dimension {e}")))?;
            let new_n = line.num_basis();
            let moved = &line.coefficients()[..new_n * cols];
            let mut back = vec![0.0; before * new_n * after];
            for b in 0..before {
                for i in 0..new_n {
                    back[(b * new_n + i) * after..(b * new_n + i + 1) * after]
                        .copy_from_slice(&moved[i * cols + b * after..i * cols + (b + 1) * after]);
                }
            }
            c = back;
            shape[e] = new_n;
            knots[e] = line.knot_vector().clone();
        }
        Self::from_knot_vectors(knots, c, m, self.extrapolate)
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

    /// The design matrix of the tensor-product basis at the points `xi` (row-major,
    /// `N × d`), scipy's `NdBSpline.design_matrix(xi, t, k)`, as CSR parts
    /// `(indptr, indices, data)` of an `N × ∏ n_e` matrix: row `i` holds the
    /// $\prod_e (k_e + 1)$ products of basis values non-zero at $x_i$ (explicit zeros
    /// kept, as scipy keeps them), columns increasing (row-major flat indices of the
    /// coefficient array).
    ///
    /// Points outside the base interval are extrapolated when `extrapolate` is true
    /// (scipy 1.17 extrapolates whatever the flag); with `false` they are an error, as
    /// scipy's documentation describes.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] without knot vectors; [`ErrorKind::InvalidLength`]
    /// unless `xi.len()` is a multiple of `d`, or when the matrix would be too large;
    /// [`ErrorKind::NonFinite`] for a NaN or infinite coordinate;
    /// [`ErrorKind::OutOfDomain`] for a coordinate outside its base interval when
    /// `extrapolate` is false (the message names the point and the dimension).
    pub fn design_matrix_parts(
        xi: &[f64],
        knots: &[KnotVector<f64>],
        extrapolate: bool,
    ) -> Result<(Vec<usize>, Vec<usize>, Vec<f64>)> {
        let dims = Dims::new(knots.to_vec())?;
        let d = dims.ndim();
        let npts = dims.points(xi)?;
        let terms = dims.terms()?;
        let nnz = npts.checked_mul(terms).ok_or_else(|| {
            Error::new(
                ErrorKind::InvalidLength,
                "the design matrix has too many entries",
            )
        })?;
        let nu = vec![0; d];
        let mut work = Work::new(&dims, &nu);
        let mut indptr = Vec::with_capacity(npts + 1);
        let mut indices = Vec::with_capacity(nnz);
        let mut data = Vec::with_capacity(nnz);
        indptr.push(0);
        for (p, x) in xi.chunks_exact(d).enumerate() {
            let Some(first) = work.prepare(&dims, x, &nu, extrapolate) else {
                let e = x
                    .iter()
                    .zip(&dims.knots)
                    .position(|(u, kv)| {
                        let (a, b) = kv.domain();
                        !(u.is_finite() && (extrapolate || (*u >= a && *u <= b)))
                    })
                    .unwrap_or(0);
                let u = x[e];
                let err = if u.is_finite() {
                    Error::out_of_domain(u, dims.knots[e].domain())
                } else {
                    Error::non_finite(format_args!("coordinate {e} of point {p} ({u})"))
                };
                return Err(err.context(format_args!("point {p}, dimension {e}")));
            };
            work.for_each_line(&dims, first, |r, p, inner| {
                for (i, &b) in inner.iter().enumerate() {
                    indices.push(r + i);
                    data.push(p * b);
                }
            });
            indptr.push(indices.len());
        }
        Ok((indptr, indices, data))
    }

    /// [`NdSpline::design_matrix_parts`] as an `nalgebra-sparse` CSR matrix with
    /// $\prod_e n_e$ columns.
    ///
    /// # Errors
    /// As [`NdSpline::design_matrix_parts`].
    pub fn design_matrix(
        xi: &[f64],
        knots: &[KnotVector<f64>],
        extrapolate: bool,
    ) -> Result<CsrMatrix<f64>> {
        let (indptr, indices, data) = Self::design_matrix_parts(xi, knots, extrapolate)?;
        let rows = indptr.len() - 1;
        let cols = knots.iter().map(KnotVector::num_basis).product();
        CsrMatrix::try_from_csr_data(rows, cols, indptr, indices, data).map_err(|e| {
            Error::new(
                ErrorKind::InvalidArgument,
                format!("the design matrix is not a valid CSR matrix: {e}"),
            )
        })
    }
}

/// Validates one knot vector per dimension with scipy's rules (see [`NdSpline`]); the
/// error names the dimension.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] unless there are as many degrees as knot vectors (and at
/// least one); the knot errors of [`crate::ColumnSpline::new`].
pub fn knot_vectors(t: Vec<Vec<f64>>, k: &[usize]) -> Result<Vec<KnotVector<f64>>> {
    if t.len() != k.len() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("len(t) = {} != len(k) = {}", t.len(), k.len()),
        ));
    }
    if t.is_empty() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "a tensor-product spline needs at least one dimension",
        ));
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
