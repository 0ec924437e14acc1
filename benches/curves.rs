//! Curve evaluation: a cubic planar B-spline with 100 control points at 10^6 random
//! parameters, one call per point and batched (random and sorted order).
//! `cargo bench --bench curves`; per-point cost = median / 10^6. The structural group
//! times knot insertion, refinement, degree elevation and Bézier extraction of the same
//! curve.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::Vector2;
use spline::geom::{BSpline, Curve2};
use std::hint::black_box;

const POINTS: usize = 1_000_000;

/// A deterministic generator (xorshift64*), so runs are comparable.
fn uniform_samples(count: usize, seed: u64) -> Vec<f64> {
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

fn cubic_curve() -> Curve2 {
    let n = 100;
    let knots = spline::core::KnotVector::clamped_uniform(3, n, 0.0, 1.0).unwrap();
    let ys = uniform_samples(n, 7);
    let points = (0..n)
        .map(|i| Vector2::new(i as f64 / n as f64, ys[i]))
        .collect();
    BSpline::new(knots, points).unwrap()
}

fn evaluation(c: &mut Criterion) {
    let curve = cubic_curve();
    let params = uniform_samples(POINTS, 42);
    let mut sorted = params.clone();
    sorted.sort_by(f64::total_cmp);
    let mut group = c.benchmark_group("cubic_100_ctrl_1e6_params");
    group.throughput(Throughput::Elements(POINTS as u64));
    group.sample_size(10);
    group.bench_function("one_at_a_time", |b| {
        b.iter(|| {
            let mut acc = Vector2::zeros();
            for &u in &params {
                acc += curve.eval(black_box(u)).unwrap();
            }
            acc
        });
    });
    group.bench_function("de_boor_one_at_a_time", |b| {
        b.iter(|| {
            let mut acc = Vector2::zeros();
            for &u in &params {
                acc += curve.de_boor(black_box(u)).unwrap();
            }
            acc
        });
    });
    let mut out = vec![Vector2::zeros(); POINTS];
    group.bench_function("batched_random_order", |b| {
        b.iter(|| curve.eval_many_into(black_box(&params), &mut out).unwrap());
    });
    group.bench_function("batched_sorted", |b| {
        b.iter(|| curve.eval_many_into(black_box(&sorted), &mut out).unwrap());
    });
    group.bench_function("first_derivative_batched_sorted", |b| {
        let mut ders = vec![Vector2::zeros(); 2 * POINTS];
        b.iter(|| {
            curve
                .derivatives_many_into(black_box(&sorted), 1, &mut ders)
                .unwrap();
        });
    });
    group.finish();
}

/// Structural operations on `f64` points: knot insertion, refinement, degree elevation and
/// Bézier extraction of the same cubic curve (the fast path of the generic algorithms).
fn structural(c: &mut Criterion) {
    let curve = cubic_curve();
    let knots = uniform_samples(100, 11);
    let mut group = c.benchmark_group("structural_cubic_100_ctrl");
    group.sample_size(20);
    group.bench_function("insert_knot_once", |b| {
        b.iter(|| curve.insert_knot(black_box(0.4321), 1).unwrap());
    });
    group.bench_function("insert_knot_three_times", |b| {
        b.iter(|| curve.insert_knot(black_box(0.4321), 3).unwrap());
    });
    group.bench_function("refine_100_knots", |b| {
        b.iter(|| curve.refine(black_box(&knots)).unwrap());
    });
    group.bench_function("elevate_by_1", |b| {
        b.iter(|| curve.elevate_degree(black_box(1)).unwrap());
    });
    group.bench_function("elevate_by_3", |b| {
        b.iter(|| curve.elevate_degree(black_box(3)).unwrap());
    });
    group.bench_function("bezier_segments", |b| {
        b.iter(|| black_box(&curve).bezier_segments());
    });
    group.finish();
}

criterion_group!(benches, evaluation, structural);
criterion_main!(benches);
