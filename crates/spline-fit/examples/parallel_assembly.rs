//! Assembles the normal equations of a cubic fit of 10⁶ planar points (200 control points)
//! `REPS` times on a rayon pool of `THREADS` threads and prints the median wall time per
//! assembly; with `perf stat -e task-clock` around it, the CPU time too (the wall clock
//! alone means little on a machine shared with other work).
//!
//! `cargo run --release -p spline-fit --features parallel --example parallel_assembly -- THREADS REPS`

use nalgebra::Vector2;
use spline_core::KnotVector;
use spline_fit::LeastSquares;
use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let threads: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let reps: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(20);
    let n: usize = 1_000_000;
    #[allow(clippy::cast_precision_loss)]
    let params: Vec<f64> = (0..n).map(|j| j as f64 / (n - 1) as f64).collect();
    let points: Vec<Vector2<f64>> = params
        .iter()
        .map(|&u| Vector2::new((9.0 * u).sin() + u, (4.0 * u).cos() * (1.0 + u)))
        .collect();
    let knots = KnotVector::uniform(3, 200, 0.0, 1.0).expect("knots");
    let problem = LeastSquares::new(&points, &params, knots);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let start = Instant::now();
            let normal = pool
                .install(|| problem.normal_equations())
                .expect("assembled");
            std::hint::black_box(normal);
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    println!(
        "{threads} thread(s): median {:.2} ms, min {:.2} ms per assembly of {n} points",
        times[reps / 2],
        times[0]
    );
}
