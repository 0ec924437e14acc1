//! The derivative spline and the design matrix of [`NdSpline`] (scipy's
//! `NdBSpline.derivative` and `NdBSpline.design_matrix`).

use super::NdSpline;
use super::work::{Dims, Work};
use nalgebra_sparse::CsrMatrix;
use spline_core::{Error, ErrorKind, KnotVector, Result};

impl NdSpline {
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
        self.check_orders(nu)?;
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
