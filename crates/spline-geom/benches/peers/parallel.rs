//! The `parallel` feature: the cubic's batch of 10⁶ parameters and the bicubic's 500²
//! grid in rayon pools of 1 and 2 threads (`peers_parallel/<workload>_<threads>`), checked
//! equal bit for bit to the sequential results first; and the sequential kernels
//! (`<workload>_0`) for the cost of the parallel path on one thread.
//!
//! Wall-clock speed-up needs an idle second core. So that the split of the work can be judged
//! on a loaded machine too, each workload is also run ten times outside criterion while the
//! CPU time of all the process's threads is read from `/proc/self/task/*/schedstat`:
//! `peers-cpu parallel/<workload>_<threads>/{wall,cpu}` lines, seconds per run. Equal CPU
//! time at 1 and 2 threads means the work is split without overhead.

use crate::curves::cubic;
use crate::surfaces::bicubic;
use crate::uniform_samples;
use criterion::{Criterion, Throughput};
use nalgebra::{Vector2, Vector3};
use std::hint::black_box;
use std::time::Instant;

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
    group.throughput(Throughput::Elements(POINTS as u64));
    group.bench_function("batch_0", |b| {
        b.iter(|| curve.eval_many_into(black_box(&params), &mut out).unwrap());
    });
    group.throughput(Throughput::Elements((SIDE * SIDE) as u64));
    group.bench_function("grid_0", |b| {
        b.iter(|| {
            surface
                .eval_grid_into(black_box(&grid), &grid, &mut grid_out)
                .unwrap();
        });
    });
    cpu_report("batch_0", || {
        curve.eval_many_into(&params, &mut out).unwrap();
    });
    cpu_report("grid_0", || {
        surface.eval_grid_into(&grid, &grid, &mut grid_out).unwrap();
    });
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
        cpu_report(&format!("batch_{threads}"), || {
            pool.install(|| curve.par_eval_many_into(&params, &mut out))
                .unwrap();
        });
        cpu_report(&format!("grid_{threads}"), || {
            pool.install(|| surface.par_eval_grid_into(&grid, &grid, &mut grid_out))
                .unwrap();
        });
    }
    group.finish();
}

/// The CPU time of every thread of this process so far (Linux; `None` elsewhere).
fn cpu_seconds() -> Option<f64> {
    let mut total = 0u64;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let stat = std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok()?;
        total += stat.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(total as f64 * 1e-9)
}

/// Runs `work` ten times and prints its wall-clock and CPU time per run.
fn cpu_report(id: &str, mut work: impl FnMut()) {
    const RUNS: u32 = 10;
    work();
    let (start, cpu_start) = (Instant::now(), cpu_seconds());
    for _ in 0..RUNS {
        work();
    }
    let wall = start.elapsed().as_secs_f64() / f64::from(RUNS);
    println!("peers-cpu parallel/{id}/wall {wall:e}");
    if let (Some(before), Some(after)) = (cpu_start, cpu_seconds()) {
        println!(
            "peers-cpu parallel/{id}/cpu {:e}",
            (after - before) / f64::from(RUNS)
        );
    }
}
