//! The derivatives of [`ApproximationProblem`] written into the solver's buffers: the
//! patterns of the Jacobian of the quadratic constraints and of their weighted Hessian are
//! fixed, so each evaluation rewrites values only (the same sums as the owned forms).

use super::{ApproximationProblem, HessianPattern};
use crate::barrier::{BarrierProblem, SparseRows};
use nalgebra::DVector;
use nalgebra_sparse::CsrMatrix;
use spline_algebra::SparseBilinear;

/// The pattern of `∂B(x, x)/∂x` (first argument) of the quadratic forms: per form, its
/// sorted columns, and per entry `(j, l, v)` its slot.
#[derive(Clone, Debug)]
pub(super) struct JacobianPattern {
    offsets: Vec<usize>,
    columns: Vec<usize>,
    /// `(slot, l, v)` in the order of the forms' entries, `entries[k]..entries[k + 1]` of
    /// form `k`.
    scatter: Vec<(usize, usize, f64)>,
    entries: Vec<usize>,
}

impl JacobianPattern {
    pub(super) fn new(forms: &SparseBilinear<f64>) -> Self {
        let mut offsets = vec![0];
        let mut columns = Vec::new();
        let mut scatter = Vec::with_capacity(forms.nnz());
        let mut entries = vec![0];
        for k in 0..forms.nrows() {
            let start = columns.len();
            columns.extend(forms.row(k).iter().map(|&(j, _, _)| j));
            columns[start..].sort_unstable();
            let mut kept = start;
            for r in start..columns.len() {
                if kept == start || columns[kept - 1] != columns[r] {
                    columns[kept] = columns[r];
                    kept += 1;
                }
            }
            columns.truncate(kept);
            let row = &columns[start..];
            for &(j, l, v) in forms.row(k) {
                scatter.push((row.partition_point(|&c| c < j), l, v));
            }
            offsets.push(columns.len());
            entries.push(scatter.len());
        }
        Self {
            offsets,
            columns,
            scatter,
            entries,
        }
    }
}

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
