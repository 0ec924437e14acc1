//! Parameter correction allocates nothing per sweep: the refit writes the control points of
//! one curve through a reused least-squares workspace (the band of the normal equations and
//! its Cholesky factor), so a run of `2L` sweeps allocates as much as a run of `L` (before
//! the workspace: 10 allocations per sweep, 58 for 4 sweeps and 98 for 8 here).
//!
//! The test binary counts every allocation with `stats_alloc` as its global allocator (a
//! counting allocator needs `unsafe impl GlobalAlloc`, which the workspace forbids: the crate
//! holds it). The counts are global, so the tests of this file run one at a time.

use nalgebra::Vector2;
use spline_fit::{
    CorrectionOptions, LeastSquares, correct_parameters, correct_parameters_bezier,
    nurbs_book_knots,
};
use spline_testing::allocations::SERIAL;
use stats_alloc::{INSTRUMENTED_SYSTEM, StatsAlloc};
use std::alloc::System;

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

/// The allocations made while `f` runs (see [`spline_testing::allocations`]).
fn allocations<R>(f: impl Fn() -> R) -> (usize, R) {
    spline_testing::allocations::allocations(GLOBAL, f)
}

#[test]
fn parameter_correction_allocates_nothing_per_sweep() {
    let _guard = SERIAL
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let m = 300;
    let points: Vec<Vector2<f64>> = (0..=m)
        .map(|k| {
            let t = f64::from(k) / f64::from(m) * 6.0;
            Vector2::new(t.cos() * (1.0 + 0.2 * t), t.sin() * 0.5 + 0.1 * t)
        })
        .collect();
    // Uniform parameters: far from the foot points, so that every sweep corrects.
    let params: Vec<f64> = (0..=m).map(|k| f64::from(k) / f64::from(m)).collect();
    let knots = nurbs_book_knots(3, 25, &params).expect("knots");
    let problem = LeastSquares::new(&points, &params, knots);
    let run = |sweeps: usize| {
        let options = CorrectionOptions {
            max_iterations: sweeps,
            angle_tolerance: 1e-14,
            max_halvings: 30,
        };
        allocations(|| correct_parameters(&problem, &options).expect("corrected"))
    };
    let (few, (_, short)) = run(4);
    let (many, (_, long)) = run(8);
    assert_eq!((short.iterations, long.iterations), (4, 8));
    assert!(!long.converged);
    // The sweeps improve the fit (they do run).
    assert!(long.errors[8] < long.errors[4] && long.errors[4] < long.errors[0]);
    eprintln!("parameter correction: {few} allocations for 4 sweeps, {many} for 8");
    assert_eq!(few, many, "{few} allocations for 4 sweeps, {many} for 8");
}

/// The Bézier form of parameter correction refits through the same reused least-squares
/// workspace and writes the curve and its hodograph in place (`Bezier::control_points_mut`,
/// `Bezier::derivative_into`): nothing is allocated per sweep. Before: a new least-squares
/// problem per refit and a new hodograph per evaluation, 1,616 allocations for 4 sweeps and
/// 3,100 for 8 here; then 18 and 26 with a new curve and hodograph per refit.
#[test]
fn bezier_parameter_correction_allocates_nothing_per_sweep() {
    let _guard = SERIAL
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let m = 120;
    let points: Vec<Vector2<f64>> = (0..=m)
        .map(|k| {
            let t = f64::from(k) / f64::from(m) * 3.0;
            Vector2::new(t + 0.3 * t.sin(), (1.5 * t).cos())
        })
        .collect();
    let params: Vec<f64> = (0..=m).map(|k| f64::from(k) / f64::from(m)).collect();
    let run = |sweeps: usize| {
        let options = CorrectionOptions {
            max_iterations: sweeps,
            angle_tolerance: 1e-14,
            max_halvings: 30,
        };
        allocations(|| {
            correct_parameters_bezier(&points, &params, 5, (0.0, 1.0), &options).expect("corrected")
        })
    };
    let (few, (_, short)) = run(4);
    let (many, (_, long)) = run(8);
    assert_eq!((short.iterations, long.iterations), (4, 8));
    assert!(long.errors[8] < long.errors[4] && long.errors[4] < long.errors[0]);
    eprintln!("Bézier parameter correction: {few} allocations for 4 sweeps, {many} for 8");
    assert_eq!(few, many, "{few} allocations for 4 sweeps, {many} for 8");
}
