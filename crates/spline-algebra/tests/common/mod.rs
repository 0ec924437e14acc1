//! Shared helpers: a small deterministic random generator and random spline spaces.

#![allow(dead_code, unreachable_pub, clippy::cast_lossless)]

use nalgebra_sparse::CsrMatrix;
use spline_core::KnotVector;

/// A 64-bit linear congruential generator (deterministic, no dependency).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15).wrapping_add(1))
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 11
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.next_u64() as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }

    /// Uniform integer in lo..=hi.
    pub fn int(&mut self, lo: usize, hi: usize) -> usize {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as usize
    }

    pub fn values(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.range(-1.0, 1.0)).collect()
    }
}

/// A random knot vector of degree `p` on `[0, 1]` whose interior knots are drawn from
/// `pool` (so that two such vectors share some knots and not others), with random
/// multiplicities up to `p + 1` (or `p` unless `discontinuous`), clamped or not.
pub fn random_knots(rng: &mut Rng, p: usize, pool: &[f64], discontinuous: bool) -> KnotVector<f64> {
    let max_mult = if discontinuous { p + 1 } else { p.max(1) };
    let mut interior = Vec::new();
    for &x in pool {
        if rng.uniform() < 0.5 {
            let m = rng.int(1, max_mult);
            interior.extend(std::iter::repeat_n(x, m));
        }
    }
    let clamped = rng.uniform() < 0.6;
    let mut knots = Vec::new();
    if clamped {
        knots.extend(std::iter::repeat_n(0.0, p + 1));
    } else {
        for j in (1..=p).rev() {
            knots.push(-0.13 * j as f64);
        }
        knots.push(0.0);
    }
    knots.extend(interior);
    if clamped {
        knots.extend(std::iter::repeat_n(1.0, p + 1));
    } else {
        knots.push(1.0);
        for j in 1..=p {
            knots.push(1.0 + 0.11 * j as f64);
        }
    }
    KnotVector::new(p, knots).expect("valid random knots")
}

/// A pool of breakpoints: some on a coarse grid, some random, some very close together.
pub fn random_pool(rng: &mut Rng) -> Vec<f64> {
    let mut pool: Vec<f64> = (1..8).map(|k| k as f64 / 8.0).collect();
    for _ in 0..4 {
        pool.push((rng.range(0.01, 0.99) * 1e6).round() / 1e6);
    }
    let near = (rng.range(0.05, 0.95) * 1e6).round() / 1e6;
    pool.push(near + 1e-4);
    pool.sort_by(f64::total_cmp);
    pool.dedup();
    pool
}

/// Parameters in the domain: uniform samples, every knot, and points just beside knots.
pub fn parameters(rng: &mut Rng, knots: &KnotVector<f64>, count: usize) -> Vec<f64> {
    let (a, b) = knots.domain();
    let mut out: Vec<f64> = (0..count).map(|_| rng.range(a, b)).collect();
    for &k in knots.knots() {
        if k >= a && k <= b {
            out.push(k);
            out.push((k - 1e-9).max(a));
            out.push((k + 1e-9).min(b));
        }
    }
    out.push(a);
    out.push(b);
    out
}

/// Dense copy of a sparse matrix.
pub fn dense(m: &CsrMatrix<f64>) -> Vec<Vec<f64>> {
    let mut d = vec![vec![0.0; m.ncols()]; m.nrows()];
    for (i, j, v) in m.triplet_iter() {
        d[i][j] += *v;
    }
    d
}

/// Asserts `|got − expected| ≤ tol · max(scale, |expected|)` entry-wise.
pub fn assert_close_rel(got: f64, expected: f64, tol: f64, scale: f64, what: &str) {
    let s = scale.max(expected.abs());
    assert!(
        (got - expected).abs() <= tol * s,
        "{what}: got {got}, expected {expected} (relative difference {:.3e})",
        (got - expected).abs() / s
    );
}
