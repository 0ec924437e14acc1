//! The fixed sparsity patterns of the quadratic constraints: of their weighted Hessian
//! `Σ w_k H_k` and of their Jacobian, each entry of each form with its slot.

use nalgebra_sparse::CsrMatrix;
use spline_algebra::SparseBilinear;

/// The union of the sparsity patterns of the `H_k` (CSR) and, for every entry of every
/// `H_k`, its slot there: `Σ w_k H_k` is then a scatter-add, without sorting.
#[derive(Clone, Debug)]
pub(super) struct HessianPattern {
    pub(super) n: usize,
    pub(super) offsets: Vec<usize>,
    pub(super) columns: Vec<usize>,
    /// `(k, slot, value)`.
    pub(super) scatter: Vec<(usize, usize, f64)>,
}

impl HessianPattern {
    pub(super) fn new(n: usize, forms: &SparseBilinear<f64>) -> Self {
        let mut rows: Vec<Vec<usize>> = vec![Vec::new(); n];
        for k in 0..forms.nrows() {
            for &(j, l, _) in forms.row(k) {
                rows[j].push(l);
            }
        }
        let mut offsets = Vec::with_capacity(n + 1);
        let mut columns = Vec::new();
        offsets.push(0);
        for row in &mut rows {
            row.sort_unstable();
            row.dedup();
            columns.extend_from_slice(row);
            offsets.push(columns.len());
        }
        let mut scatter = Vec::with_capacity(forms.nnz());
        for k in 0..forms.nrows() {
            for &(j, l, v) in forms.row(k) {
                let row = &columns[offsets[j]..offsets[j + 1]];
                let slot = offsets[j] + row.partition_point(|&c| c < l);
                scatter.push((k, slot, v));
            }
        }
        Self {
            n,
            offsets,
            columns,
            scatter,
        }
    }

    pub(super) fn weighted(&self, weights: &[f64]) -> CsrMatrix<f64> {
        let mut values = vec![0.0; self.columns.len()];
        for &(k, slot, v) in &self.scatter {
            values[slot] += weights[k] * v;
        }
        CsrMatrix::try_from_csr_data(
            self.n,
            self.n,
            self.offsets.clone(),
            self.columns.clone(),
            values,
        )
        .unwrap_or_else(|_| CsrMatrix::zeros(self.n, self.n))
    }
}

/// The pattern of `∂B(x, x)/∂x` (first argument) of the quadratic forms: per form, its
/// sorted columns, and per entry `(j, l, v)` its slot.
#[derive(Clone, Debug)]
pub(super) struct JacobianPattern {
    pub(super) offsets: Vec<usize>,
    pub(super) columns: Vec<usize>,
    /// `(slot, l, v)` in the order of the forms' entries, `entries[k]..entries[k + 1]` of
    /// form `k`.
    pub(super) scatter: Vec<(usize, usize, f64)>,
    pub(super) entries: Vec<usize>,
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
