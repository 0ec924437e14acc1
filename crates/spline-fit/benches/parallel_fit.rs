//! The normal equations of a large least-squares fit assembled in chunks (`parallel`
//! feature) on rayon pools of 1 and 2 threads: cubic, 200 control points, `N = 10⁵` and
//! `10⁶` planar points. `assemble` is `LeastSquares::normal_equations` (no
//! Schoenberg–Whitney check), `solve` the whole fit (the check runs beside the chunks).
//!
//! Run: `cargo bench -p spline-fit --features parallel --bench parallel_fit`. On a machine
//! shared with other work, compare task-clock (`perf stat`) rather than the wall clock.

use criterion::{BenchmarkId, Criterion, criterion_main};
use nalgebra::Vector2;
use spline_core::KnotVector;
use spline_fit::LeastSquares;
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

fn benches() {
    let mut c = Criterion::default().configure_from_args();
    parallel_assembly(&mut c);
}

criterion_main!(benches);
