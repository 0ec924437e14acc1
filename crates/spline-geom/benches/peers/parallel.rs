//! The `parallel` feature: the cubic's batch of 10⁶ parameters and the bicubic's 500²
//! grid in rayon pools of 1 and 2 threads (`peers_parallel/<workload>_<threads>`), checked
//! equal bit for bit to the sequential results first.

use crate::curves::cubic;
use crate::surfaces::bicubic;
use crate::uniform_samples;
use criterion::{Criterion, Throughput};
use nalgebra::{Vector2, Vector3};
use std::hint::black_box;

const POINTS: usize = 1_000_000;
const SIDE: usize = 500;

pub(crate) fn parallel(c: &mut Criterion) {
    let curve = cubic();
    let surface = bicubic();
    let params = uniform_samples(POINTS, 52);
    let grid: Vec<f64> = (0..SIDE).map(|i| i as f64 / (SIDE - 1) as f64).collect();
    let mut out = vec![Vector2::zeros(); POINTS];
    let mut sequential = out.clone();
    curve.eval_many_into(&params, &mut sequential).unwrap();
    let mut grid_out = vec![Vector3::zeros(); SIDE * SIDE];
    let mut grid_sequential = grid_out.clone();
    surface
        .eval_grid_into(&grid, &grid, &mut grid_sequential)
        .unwrap();
    let mut group = c.benchmark_group("peers_parallel");
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            curve.par_eval_many_into(&params, &mut out).unwrap();
            surface
                .par_eval_grid_into(&grid, &grid, &mut grid_out)
                .unwrap();
        });
        assert!(out == sequential && grid_out == grid_sequential);
        println!("peers-check parallel/{threads} 0");
        group.throughput(Throughput::Elements(POINTS as u64));
        group.bench_function(format!("batch_{threads}"), |b| {
            b.iter(|| {
                pool.install(|| curve.par_eval_many_into(black_box(&params), &mut out))
                    .unwrap();
            });
        });
        group.throughput(Throughput::Elements((SIDE * SIDE) as u64));
        group.bench_function(format!("grid_{threads}"), |b| {
            b.iter(|| {
                pool.install(|| surface.par_eval_grid_into(black_box(&grid), &grid, &mut grid_out))
                    .unwrap();
            });
        });
    }
    group.finish();
}
