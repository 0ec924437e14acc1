//! `cargo xtask bench peers`: ours against curvo 0.3 and truck-geometry 0.5 in one binary,
//! on the same data, each workload's libraries one after the other in one criterion group
//! (`peers_<workload>/<library>`), after checking that their results agree (printed as
//! `peers-check <workload>/<library> <max abs difference>` lines, which the xtask reads).
//!
//! This binary is also the downstream-style check of inlining: it is a separate crate that
//! calls only the public API of spline-geom, linked with two other geometry libraries.
//!
//! Workloads (random parameters from a fixed xorshift generator, so runs compare):
//! - `eval_point`, `eval_batch`, `eval_sorted`: a planar cubic with 100 control points at 10⁶
//!   parameters, one call per point (curvo: `point_at` and its span-caching evaluator; truck:
//!   `subs`) and in one batch call;
//! - `derivs`: C′ and C″ at 10⁵ random parameters;
//! - `insert`: 1,000 random knots inserted one at a time into the cubic; `refine`: the same
//!   knots at once; `elevate1` / `elevate3`: degree elevation by 1 and 3;
//! - `surface_point`, `surface_grid`, `surface_derivs`: a bicubic with 50 × 50 control
//!   points at 500² parameters (one call per point, random order, or one grid call), and
//!   S_u, S_v at 10⁵ random points;
//! - `nurbs_point`, `nurbs_batch`: the NURBS unit circle at 10⁶ random parameters;
//!   `nurbs_surface`: a NURBS sphere at 10⁵ random points;
//! - with the `parallel` feature, `peers_parallel`: the batch and a grid in rayon pools of 1
//!   and 2 threads.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

mod curves;
#[cfg(feature = "parallel")]
mod parallel;
mod surfaces;

use criterion::{Criterion, criterion_group, criterion_main};
use std::time::Duration;

/// A deterministic generator (xorshift64*) of uniform numbers in [0, 1).
pub(crate) fn uniform_samples(count: usize, seed: u64) -> Vec<f64> {
    let mut state = seed;
    (0..count)
        .map(|_| {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            let bits = state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11;
            bits as f64 / (1u64 << 53) as f64
        })
        .collect()
}

/// Prints the agreement line the xtask checks (and refuses to time disagreeing results).
pub(crate) fn report_check(id: &str, max_diff: f64) {
    println!("peers-check {id} {max_diff:e}");
    assert!(
        max_diff <= 1e-12,
        "{id}: results differ by {max_diff:e} — not timing disagreeing libraries"
    );
}

fn criterion() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
}

criterion_group! {
    name = benches;
    config = criterion();
    targets = curves::evaluation, curves::structural, surfaces::surfaces, curves::nurbs
}

#[cfg(feature = "parallel")]
criterion_group! {
    name = threads;
    config = criterion();
    targets = parallel::parallel
}

#[cfg(feature = "parallel")]
criterion_main!(benches, threads);
#[cfg(not(feature = "parallel"))]
criterion_main!(benches);
