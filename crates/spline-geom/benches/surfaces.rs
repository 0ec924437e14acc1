//! Surface and NURBS evaluation.
//!
//! - A bicubic surface with 50 × 50 control points on a 1000 × 1000 grid of parameters: the
//!   tensor fast path ([`Surface::eval_grid_into`]) against one call per point (basis form
//!   and seed 000 Algorithm 4).
//! - A cubic NURBS curve with 100 control points at 10^5 parameters (points, batched points,
//!   first and second rational derivatives) and the 9-point circle.
//! - A NURBS sphere on a 300 × 300 grid.
//!
//! `cargo bench -p spline-geom --bench surfaces`; per-point cost = median / elements.

// `criterion_group!` defines an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{Vector2, Vector3};
use spline_geom::{CircleConstruction, Frame, KnotVector, NurbsCurve, NurbsSurface, Surface};
use std::hint::black_box;

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

fn bicubic_surface(n: usize) -> Surface<f64, Vector3<f64>> {
    let knots = KnotVector::clamped_uniform(3, n, 0.0, 1.0).unwrap();
    let heights = uniform_samples(n * n, 11);
    let points = (0..n * n)
        .map(|k| {
            Vector3::new(
                (k / n) as f64 / n as f64,
                (k % n) as f64 / n as f64,
                heights[k],
            )
        })
        .collect();
    Surface::new(knots.clone(), knots, points).unwrap()
}

fn grid(count: usize) -> Vec<f64> {
    (0..count).map(|i| i as f64 / (count - 1) as f64).collect()
}

fn surface_grid(c: &mut Criterion) {
    let surface = bicubic_surface(50);
    let (us, vs) = (grid(1000), grid(1000));
    let mut group = c.benchmark_group("bicubic_50x50_ctrl_1000x1000_grid");
    group.throughput(Throughput::Elements((us.len() * vs.len()) as u64));
    group.sample_size(10);
    let mut out = vec![Vector3::zeros(); us.len() * vs.len()];
    group.bench_function("tensor_fast_path", |b| {
        b.iter(|| {
            surface
                .eval_grid_into(black_box(&us), black_box(&vs), &mut out)
                .unwrap();
        });
    });
    group.bench_function("point_by_point", |b| {
        b.iter(|| {
            for (row, &u) in out.chunks_exact_mut(vs.len()).zip(&us) {
                for (slot, &v) in row.iter_mut().zip(&vs) {
                    *slot = surface.eval(black_box(u), black_box(v)).unwrap();
                }
            }
        });
    });
    group.bench_function("de_boor_point_by_point", |b| {
        b.iter(|| {
            for (row, &u) in out.chunks_exact_mut(vs.len()).zip(&us) {
                for (slot, &v) in row.iter_mut().zip(&vs) {
                    *slot = surface.de_boor(black_box(u), black_box(v)).unwrap();
                }
            }
        });
    });
    group.finish();
}

fn nurbs_curve(c: &mut Criterion) {
    let n = 100;
    let knots = KnotVector::clamped_uniform(3, n, 0.0, 1.0).unwrap();
    let ys = uniform_samples(n, 7);
    let ws = uniform_samples(n, 9);
    let curve = NurbsCurve::new(
        knots,
        (0..n)
            .map(|i| Vector2::new(i as f64 / n as f64, ys[i]))
            .collect(),
        ws.iter().map(|w| 0.2 + 2.0 * w).collect(),
    )
    .unwrap();
    let count = 100_000;
    let mut params = uniform_samples(count, 42);
    params.sort_by(f64::total_cmp);
    let mut group = c.benchmark_group("nurbs_cubic_100_ctrl_1e5_params");
    group.throughput(Throughput::Elements(count as u64));
    group.bench_function("eval_one_at_a_time", |b| {
        b.iter(|| {
            let mut acc = Vector2::zeros();
            for &u in &params {
                acc += curve.eval(black_box(u)).unwrap();
            }
            acc
        });
    });
    group.bench_function("eval_many_sorted", |b| {
        b.iter(|| curve.eval_many(black_box(&params)).unwrap());
    });
    group.bench_function("first_derivative", |b| {
        let mut d = [Vector2::zeros(); 2];
        b.iter(|| {
            let mut acc = Vector2::zeros();
            for &u in &params {
                curve.derivatives_into(black_box(u), &mut d).unwrap();
                acc += d[1];
            }
            acc
        });
    });
    group.bench_function("second_derivative", |b| {
        let mut d = [Vector2::zeros(); 3];
        b.iter(|| {
            let mut acc = Vector2::zeros();
            for &u in &params {
                curve.derivatives_into(black_box(u), &mut d).unwrap();
                acc += d[2];
            }
            acc
        });
    });
    let circle = NurbsCurve::circle(
        &Frame::planar(Vector2::zeros()),
        1.0,
        CircleConstruction::Square,
    )
    .unwrap();
    group.bench_function("circle_9_eval", |b| {
        b.iter(|| {
            let mut acc = Vector2::zeros();
            for &u in &params {
                acc += circle.eval(black_box(u)).unwrap();
            }
            acc
        });
    });
    group.finish();
}

fn nurbs_sphere(c: &mut Criterion) {
    let sphere = NurbsSurface::sphere(Vector3::zeros(), 1.0).unwrap();
    let (us, vs) = (grid(300), grid(300));
    let mut group = c.benchmark_group("nurbs_sphere_300x300_grid");
    group.throughput(Throughput::Elements((us.len() * vs.len()) as u64));
    group.bench_function("tensor_fast_path", |b| {
        b.iter(|| sphere.eval_grid(black_box(&us), black_box(&vs)).unwrap());
    });
    group.bench_function("point_by_point", |b| {
        b.iter(|| {
            let mut acc = Vector3::zeros();
            for &u in &us {
                for &v in &vs {
                    acc += sphere.eval(black_box(u), black_box(v)).unwrap();
                }
            }
            acc
        });
    });
    group.finish();
}

criterion_group!(benches, surface_grid, nurbs_curve, nurbs_sphere);
criterion_main!(benches);
