//! Shared helpers of the algebra tests (the strategies and comparisons are in
//! spline-testing).

#![allow(dead_code, unreachable_pub, clippy::cast_lossless)]

use nalgebra_sparse::CsrMatrix;

/// Dense copy of a sparse matrix.
pub fn dense(m: &CsrMatrix<f64>) -> Vec<Vec<f64>> {
    let mut d = vec![vec![0.0; m.ncols()]; m.nrows()];
    for (i, j, v) in m.triplet_iter() {
        d[i][j] += *v;
    }
    d
}
