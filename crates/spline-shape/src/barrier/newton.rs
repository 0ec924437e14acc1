//! The Newton matrix of one barrier step, dense or sparse.

use nalgebra::{DMatrix, DVector};
use nalgebra_sparse::factorization::CscCholesky;
use nalgebra_sparse::{CooMatrix, CscMatrix, CsrMatrix};
use spline_core::{Error, ErrorKind, Result};

/// The Newton matrix of one step: dense for small problems (the eraser's curves, the
/// functions of thesis ch. 5), sparse (COO, then a sparse Cholesky factorisation) above
/// [`DENSE_LIMIT`] unknowns.
#[derive(Clone)]
pub(super) enum NewtonSystem {
    Dense(DMatrix<f64>),
    Sparse(CooMatrix<f64>),
}

/// Problems with at most this many unknowns use dense matrices.
pub(super) const DENSE_LIMIT: usize = 400;

impl NewtonSystem {
    pub(super) fn new(n: usize) -> Self {
        if n <= DENSE_LIMIT {
            Self::Dense(DMatrix::zeros(n, n))
        } else {
            Self::Sparse(CooMatrix::new(n, n))
        }
    }

    pub(super) fn add(&mut self, i: usize, j: usize, v: f64) {
        match self {
            Self::Dense(m) => m[(i, j)] += v,
            Self::Sparse(m) => m.push(i, j, v),
        }
    }

    /// Adds `w · a aᵀ` for a sparse vector `a`.
    pub(super) fn add_outer(&mut self, cols: &[usize], vals: &[f64], w: f64) {
        for (&ca, &va) in cols.iter().zip(vals) {
            let wa = w * va;
            for (&cb, &vb) in cols.iter().zip(vals) {
                self.add(ca, cb, wa * vb);
            }
        }
    }

    /// This matrix plus `h`.
    pub(super) fn with(&self, h: &CsrMatrix<f64>) -> Self {
        let mut out = self.clone();
        for (i, j, v) in h.triplet_iter() {
            out.add(i, j, *v);
        }
        out
    }

    /// Solves `H d = −g` if `H` is positive definite.
    pub(super) fn solve_definite(&self, gradient: &DVector<f64>) -> Option<DVector<f64>> {
        let d = match self {
            Self::Dense(m) => m.clone().cholesky()?.solve(&(-gradient)),
            Self::Sparse(m) => {
                let factor = CscCholesky::factor(&CscMatrix::from(m)).ok()?;
                let d = factor.solve(&(-gradient));
                DVector::from_column_slice(d.as_slice())
            }
        };
        d.iter().all(|v| v.is_finite()).then_some(d)
    }

    /// Solves `H d = −g`, adding `δ I` with growing `δ` while `H` is not positive definite.
    pub(super) fn solve_shifted(&self, gradient: &DVector<f64>) -> Result<DVector<f64>> {
        let n = gradient.len();
        let scale = match self {
            Self::Dense(m) => (0..n).map(|i| m[(i, i)].abs()).fold(0.0, f64::max),
            Self::Sparse(m) => {
                let csc = CscMatrix::from(m);
                (0..n)
                    .map(|i| csc.get_entry(i, i).map_or(0.0, |e| e.into_value().abs()))
                    .fold(0.0, f64::max)
            }
        }
        .max(1e-300);
        let mut shift = 0.0;
        for _ in 0..40 {
            let mut shifted = self.clone();
            if shift > 0.0 {
                for i in 0..n {
                    shifted.add(i, i, shift);
                }
            }
            if let Some(d) = shifted.solve_definite(gradient) {
                return Ok(d);
            }
            shift = if shift == 0.0 {
                1e-10 * scale
            } else {
                shift * 10.0
            };
        }
        Err(Error::new(
            ErrorKind::SingularSystem,
            "the Newton matrix could not be made positive definite",
        ))
    }
}
