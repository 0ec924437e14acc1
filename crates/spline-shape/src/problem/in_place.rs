//! The derivatives of [`ApproximationProblem`] written into the solver's buffers: the
//! patterns of the Jacobian of the quadratic constraints and of their weighted Hessian are
//! fixed, so each evaluation rewrites values only (the same sums as the owned forms).

use super::approximation::ApproximationProblem;
use super::patterns::HessianPattern;
use crate::barrier::{BarrierProblem, SparseRows};
use nalgebra::DVector;
use nalgebra_sparse::CsrMatrix;

impl HessianPattern {
    /// [`HessianPattern::weighted`] into `out`, in place when `out` has this pattern.
    pub(super) fn weighted_into(&self, weights: &[f64], out: &mut Option<CsrMatrix<f64>>) {
        match out {
            Some(m)
                if m.row_offsets() == self.offsets.as_slice()
                    && m.col_indices() == self.columns.as_slice() =>
            {
                let values = m.values_mut();
                values.iter_mut().for_each(|v| *v = 0.0);
                for &(k, slot, v) in &self.scatter {
                    values[slot] += weights[k] * v;
                }
            }
            _ => *out = Some(self.weighted(weights)),
        }
    }
}

impl ApproximationProblem {
    /// `G x` then the quadratic constraints `½ xᵀ H_k x`, into `out`.
    pub(super) fn constraints_in_place(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        let ml = self.linear.nrows();
        for (o, row) in out.iter_mut().zip(self.linear.row_iter()) {
            let mut dot = 0.0;
            for (&j, v) in row.col_indices().iter().zip(row.values()) {
                dot += v * x[j];
            }
            *o = dot;
        }
        if let Some(h) = &self.quadratic {
            for k in 0..h.nrows() {
                let q = h
                    .row(k)
                    .iter()
                    .fold(0.0, |acc, &(j, l, v)| acc + v * x[j] * x[l]);
                out[ml + k] = 0.5 * q;
            }
        }
    }

    /// $\sum_k w_k H_k$ for the weights `weights` of the constraints (linear ones first)
    /// into `out` (in place when it has the pattern already); `false` (`out` untouched)
    /// without quadratic constraints.
    pub(super) fn weighted_hessian_in_place(
        &self,
        weights: &[f64],
        out: &mut Option<CsrMatrix<f64>>,
    ) -> bool {
        let Some(pattern) = &self.pattern else {
            return false;
        };
        pattern.weighted_into(&weights[self.linear.nrows()..], out);
        true
    }

    /// The Jacobian of the constraints into `out`.
    pub(super) fn jacobian_in_place(&self, x: &DVector<f64>, out: &mut SparseRows) {
        out.clear(self.dimension());
        out.extend_from_csr(&self.linear);
        if let Some(pattern) = &self.jacobian_pattern {
            for k in 0..pattern.offsets.len() - 1 {
                let (a, b) = (pattern.offsets[k], pattern.offsets[k + 1]);
                let values = out.push_row(&pattern.columns[a..b]);
                let scatter = &pattern.scatter[pattern.entries[k]..pattern.entries[k + 1]];
                for &(slot, l, v) in scatter {
                    values[slot] += v * x[l];
                }
            }
        }
    }
}
