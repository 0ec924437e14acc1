//! Pieces of the segments of a curve and the subdivision of Bernstein coefficients onto them.

/// A sub-interval `[lo, hi] ⊂ [0, 1]` of a segment (local parameter), on which the Bernstein
/// coefficients of `g` (from de Casteljau subdivision) must all have the sign of its piece.
#[derive(Clone, Debug)]
pub(super) struct Piece {
    pub(super) segment: usize,
    pub(super) lo: f64,
    pub(super) hi: f64,
    /// `+1` where the curvature must increase (`g > 0`), `−1` where it must decrease.
    pub(super) sign: f64,
    /// Coefficients on `[lo, hi]` = `subdivision · coefficients on [0, 1]`, `(q+1) × (q+1)`
    /// row-major.
    pub(super) subdivision: Vec<f64>,
    /// Positive scale of each condition (its magnitude at the start, floored).
    pub(super) scale: Vec<f64>,
    /// Homotopy shift of each condition: `σ_i ≥ 0`.
    pub(super) shift: Vec<f64>,
}

/// Coefficients of a Bernstein polynomial of degree `q` on `[lo, hi] ⊂ [0, 1]` as a matrix
/// applied to its coefficients on `[0, 1]` (de Casteljau on unit vectors).
pub(super) fn subdivision_matrix(q: usize, lo: f64, hi: f64) -> Vec<f64> {
    let size = q + 1;
    let mut out = vec![0.0; size * size];
    for k in 0..size {
        let mut c = vec![0.0; size];
        c[k] = 1.0;
        if hi < 1.0 {
            c = left_part(&c, hi);
        }
        if lo > 0.0 {
            c = right_part(&c, lo / hi);
        }
        for (r, v) in c.iter().enumerate() {
            out[r * size + k] = *v;
        }
    }
    out
}

/// Bernstein coefficients on `[0, s]`.
fn left_part(c: &[f64], s: f64) -> Vec<f64> {
    let mut work = c.to_vec();
    let mut out = Vec::with_capacity(c.len());
    out.push(work[0]);
    for r in 1..c.len() {
        for i in 0..c.len() - r {
            work[i] = (1.0 - s) * work[i] + s * work[i + 1];
        }
        out.push(work[0]);
    }
    out
}

/// Bernstein coefficients on `[s, 1]`.
fn right_part(c: &[f64], s: f64) -> Vec<f64> {
    let mut work = c.to_vec();
    let n = c.len();
    let mut out = vec![0.0; n];
    out[n - 1] = work[n - 1];
    for r in 1..n {
        for i in 0..n - r {
            work[i] = (1.0 - s) * work[i] + s * work[i + 1];
        }
        out[n - 1 - r] = work[n - 1 - r];
    }
    out
}
