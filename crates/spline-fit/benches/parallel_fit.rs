//! The normal equations of a large least-squares fit assembled in chunks (`parallel`
//! feature) on rayon pools of 1 and 2 threads: cubic, 200 control points, `N = 10⁵` and
//! `10⁶` planar points. `assemble` is `LeastSquares::normal_equations` (no
//! Schoenberg–Whitney check), `solve` the whole fit (the check runs beside the chunks).
//!
//! `parallel_surface_fit`: surface fits, scattered (normal equations in chunks) and grid
//! (grid lines on every core), at 1 and 2 threads.
//!
//! Run: `cargo bench -p spline-fit --features parallel --bench parallel_fit`
//! (`-- parallel_surface_fit` for the surfaces only). On a machine
//! shared with other work, compare task-clock (`perf stat`) rather than the wall clock.

use criterion::{BenchmarkId, Criterion, criterion_main};
use nalgebra::{Vector2, Vector3};
use spline_core::KnotVector;
use spline_fit::{
    LeastSquares, Parametrization, approximate_surface_grid, approximate_surface_scattered,
};
use std::hint::black_box;
use std::time::Duration;

fn data(n: usize) -> (Vec<f64>, Vec<Vector2<f64>>) {
    #[allow(clippy::cast_precision_loss)]
    let params: Vec<f64> = (0..n).map(|j| j as f64 / (n - 1) as f64).collect();
    let points = params
        .iter()
        .map(|&u| Vector2::new((9.0 * u).sin() + u, (4.0 * u).cos() * (1.0 + u)))
        .collect();
    (params, points)
}

fn parallel_assembly(c: &mut Criterion) {
    let mut group = c.benchmark_group("parallel_fit");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(4));
    let knots = KnotVector::uniform(3, 200, 0.0, 1.0).expect("knots");
    for n in [100_000, 1_000_000] {
        let (params, points) = data(n);
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("thread pool");
            let problem = LeastSquares::new(&points, &params, knots.clone());
            group.bench_with_input(
                BenchmarkId::new(format!("assemble/{threads}t"), n),
                &n,
                |b, _| b.iter(|| pool.install(|| black_box(problem.normal_equations()))),
            );
            group.bench_with_input(
                BenchmarkId::new(format!("solve/{threads}t"), n),
                &n,
                |b, _| b.iter(|| pool.install(|| black_box(problem.control_points()))),
            );
        }
    }
    group.finish();
}

/// Surfaces: a scattered least-squares fit (bicubic, 40 × 40 control points, 2·10⁵ points:
/// the normal equations assembled in one chunk per thread) and a grid fit (400 × 400 points,
/// 50 × 50 control points: the grid lines solved on every core).
fn parallel_surfaces(c: &mut Criterion) {
    let mut group = c.benchmark_group("parallel_surface_fit");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(4));
    let m = 200_000_u32;
    let params: Vec<(f64, f64)> = (0..m)
        .map(|k| {
            let k = f64::from(k);
            (
                (k * 0.618_033_988_749_895).fract(),
                (k * 0.754_877_666_246_693).fract(),
            )
        })
        .collect();
    let points: Vec<Vector3<f64>> = params
        .iter()
        .map(|&(u, v)| Vector3::new(u, v, (5.0 * u).sin() * (3.0 * v).cos()))
        .collect();
    let knots = KnotVector::uniform(3, 40, 0.0, 1.0).expect("knots");
    let side = 400;
    #[allow(clippy::cast_precision_loss)]
    let grid: Vec<Vector3<f64>> = (0..side * side)
        .map(|k| {
            let (u, v) = ((k / side) as f64 / 399.0, (k % side) as f64 / 399.0);
            Vector3::new(u, v, (4.0 * u).sin() * v + (2.0 * v).cos())
        })
        .collect();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        group.bench_function(format!("scattered/{threads}t"), |b| {
            b.iter(|| {
                pool.install(|| {
                    black_box(approximate_surface_scattered(
                        &params, &points, &knots, &knots, 0.0,
                    ))
                })
            });
        });
        group.bench_function(format!("grid/{threads}t"), |b| {
            b.iter(|| {
                pool.install(|| {
                    black_box(approximate_surface_grid(
                        &grid,
                        side,
                        side,
                        3,
                        3,
                        50,
                        50,
                        &Parametrization::Uniform,
                        &Parametrization::Uniform,
                    ))
                })
            });
        });
    }
    group.finish();
}

fn benches() {
    let mut c = Criterion::default().configure_from_args();
    parallel_assembly(&mut c);
    parallel_surfaces(&mut c);
}

criterion_main!(benches);
