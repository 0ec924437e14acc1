//! Sparse rows of linear constraints: normalised to unit length, and stacked.

use nalgebra_sparse::{CooMatrix, CsrMatrix};

/// Scales every row of `m` by `factor / ‖row‖₂` (empty rows are dropped): a constraint
/// `(G x)_i < 0` then measures the distance of `x` to its hyperplane, so that constraints of
/// different derivative orders live on one scale (the barrier itself is scale-invariant; the
/// phase-I search is not).
pub(crate) fn normalized_rows(m: &CsrMatrix<f64>, factor: f64) -> CsrMatrix<f64> {
    let kept: Vec<_> = m
        .row_iter()
        .filter_map(|row| {
            let norm = row.values().iter().map(|v| v * v).sum::<f64>().sqrt();
            (norm > 0.0).then(|| {
                row.col_indices()
                    .iter()
                    .zip(row.values())
                    .map(|(&j, &v)| (j, factor * v / norm))
                    .collect::<Vec<_>>()
            })
        })
        .collect();
    let mut coo = CooMatrix::new(kept.len(), m.ncols());
    for (i, row) in kept.into_iter().enumerate() {
        for (j, v) in row {
            coo.push(i, j, v);
        }
    }
    CsrMatrix::from(&coo)
}

/// Stacks sparse matrices with the same number of columns.
pub(crate) fn vstack(ncols: usize, blocks: &[CsrMatrix<f64>]) -> CsrMatrix<f64> {
    let nrows = blocks.iter().map(CsrMatrix::nrows).sum();
    let mut coo = CooMatrix::new(nrows, ncols);
    let mut offset = 0;
    for b in blocks {
        debug_assert_eq!(b.ncols(), ncols);
        for (i, j, v) in b.triplet_iter() {
            coo.push(offset + i, j, *v);
        }
        offset += b.nrows();
    }
    CsrMatrix::from(&coo)
}
