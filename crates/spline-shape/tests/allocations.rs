//! The interior-point method allocates nothing inside its iterations: the number of
//! allocations of a solve does not depend on how many Newton steps it takes (setup and the
//! report allocate; the steps reuse the solver's workspace).
//!
//! The test binary counts every allocation with `stats_alloc` as its global allocator (a
//! counting allocator needs `unsafe impl GlobalAlloc`, which the workspace forbids: the crate
//! holds it). The counts are global, so the tests of this file run one at a time.

use nalgebra::DVector;
use spline_shape::{BarrierOptions, FunctionApproximation, Sign, find_feasible, minimize};
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, StatsAlloc};
use std::alloc::System;
use std::sync::Mutex;

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

/// One measurement at a time (the counters are global).
static SERIAL: Mutex<()> = Mutex::new(());

/// The allocations made while `f` runs.
fn allocations<R>(f: impl FnOnce() -> R) -> (usize, R) {
    let region = Region::new(GLOBAL);
    let out = f();
    (region.change().allocations, out)
}

/// A monotone fit of a wiggly function (the sign of the first derivative).
#[test]
fn barrier_method_on_a_constrained_approximation() {
    let _guard = SERIAL.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let approx = FunctionApproximation::uniform(3, 30, 0.0, 1.0)
        .expect("knots")
        .sign(1, Sign::NonNegative);
    let params: Vec<f64> = (0..=400).map(|j| f64::from(j) / 400.0).collect();
    let values: Vec<f64> = params
        .iter()
        .map(|u| (12.0 * u).sin() * 0.3 + u)
        .collect();
    let problem = &approx.problems(&params, &values).expect("problem")[0];
    let start = DVector::from_vec(approx.knots().greville());
    let x0 = find_feasible(problem, start, 1e-6, &BarrierOptions::default()).expect("phase I");
    let growth: f64 = std::env::var("G").map_or(2.0, |g| g.parse().unwrap());
    let run = |gap: f64| {
        let options = BarrierOptions {
            gap_tolerance: gap,
            t_growth: growth,
            max_outer_iterations: 1000,
            ..BarrierOptions::default()
        };
        allocations(|| minimize(problem, x0.clone(), &options).expect("solved"))
    };
    // Warm-up: the thread's solver workspace takes its sizes.
    let _ = run(1e-3);
    eprintln!("SHORT");
    let (few, short) = run(1e-3);
    eprintln!("LONG");
    let (many, long) = run(1e-9);
    eprintln!(
        "{few} allocations for {} Newton steps, {many} for {}",
        short.newton_iterations, long.newton_iterations
    );
    assert!(long.newton_iterations >= 2 * short.newton_iterations);
    assert_eq!(few, many);
}

#[test]
fn eraser_explore() {
    let _guard = SERIAL.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let text = std::fs::read_to_string(format!(
        "{}/../../data/airfoils/clarkv.dat",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let points: Vec<nalgebra::Vector2<f64>> = spline_geom::exchange::parse_points(&text)
        .unwrap()
        .into_iter()
        .map(|p| nalgebra::Vector2::new(p[0], p[1]))
        .collect();
    for gap in [1e-7, 1e-7, 1e-9, 1e-11] {
        let mut options = spline_shape::SmoothingOptions::new(20);
        options.barrier.gap_tolerance = gap;
        eprintln!("RUN");
        let (count, result) = allocations(|| spline_shape::smooth(&points, &options).unwrap());
        eprintln!("gap {gap}: {count} allocations, {} Newton steps", result.newton_steps);
    }
}
