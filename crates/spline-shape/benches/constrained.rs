//! Constrained approximation benchmarks (thesis chapter 5):
//!
//! - `constrained/convex_200`: §5.1.4 bis, `cos 2u + 0.2(u − 2π)²` on `[0, 4π]` sampled
//!   every 0.01 (1257 samples), quartic with 200 coefficients, `s″ ≥ 0` (198 linear
//!   constraints): collocation, unconstrained solve, phase I and the barrier method;
//! - `constrained/nonnegative_20x20`: §5.5.2, `sin u sin v` on a 50 × 50 grid, bicubic
//!   20 × 20, `s ≥ 0` (400 constraints);
//! - `constrained/convex_10x10`: §5.6, bicubic 10 × 10 on a 40 × 40 grid, convexity
//!   (80 linear and 841 quadratic constraints, non-convex problem).
//!
//! Each benchmark also prints a line `constrained <id> cost <f0> newton <steps>`.

use criterion::{Criterion, criterion_main};
use spline_shape::{FunctionApproximation, Sign, SurfaceApproximation};
use std::f64::consts::PI;
use std::hint::black_box;

fn one_variable(c: &mut Criterion) {
    let params: Vec<f64> = (0..=1256).map(|j| 0.01 * f64::from(j)).collect();
    let values: Vec<f64> = params
        .iter()
        .map(|&u| (2.0 * u).cos() + 0.2 * (u - 2.0 * PI).powi(2))
        .collect();
    let approx = FunctionApproximation::uniform(4, 200, 0.0, 4.0 * PI)
        .expect("knots")
        .sign(2, Sign::NonNegative);
    let fit = approx.fit(&params, &values).expect("fit");
    println!(
        "constrained convex_200 cost {:.4} newton {}",
        fit.objective, fit.report.newton_iterations
    );
    c.bench_function("constrained/convex_200", |b| {
        b.iter(|| {
            approx
                .fit(black_box(&params), black_box(&values))
                .expect("fit")
        });
    });
}

fn two_variables(c: &mut Criterion) {
    let d = (0.0, 4.0 * PI);
    let nonnegative = SurfaceApproximation::uniform((3, 3), (20, 20), d, d)
        .expect("knots")
        .sign(0, 0, Sign::NonNegative);
    let convex = SurfaceApproximation::uniform((3, 3), (10, 10), d, d)
        .expect("knots")
        .convex();
    let target = |u: f64, v: f64| {
        u.sin() * v.sin() + 0.05 * ((u - 2.0 * PI).powi(2) + (v - 2.0 * PI).powi(2))
    };
    for (id, approx, samples, f) in [
        (
            "nonnegative_20x20",
            &nonnegative,
            50,
            (|u: f64, v: f64| u.sin() * v.sin()) as fn(f64, f64) -> f64,
        ),
        ("convex_10x10", &convex, 40, target as fn(f64, f64) -> f64),
    ] {
        let fit = approx.fit_function((samples, samples), f).expect("fit");
        println!(
            "constrained {id} cost {:.4} newton {}",
            fit.objective, fit.report.newton_iterations
        );
        c.bench_function(&format!("constrained/{id}"), |b| {
            b.iter(|| {
                approx
                    .fit_function(black_box((samples, samples)), f)
                    .expect("fit")
            });
        });
    }
}

/// Both groups, with few samples (one solve takes milliseconds to a second).
fn bench(c: &mut Criterion) {
    one_variable(c);
    two_variables(c);
}

mod harness {
    #![allow(missing_docs, unreachable_pub)]
    use super::bench;
    use criterion::{Criterion, criterion_group};
    use std::time::Duration;
    criterion_group! {
        name = benches;
        config = Criterion::default()
            .sample_size(10)
            .measurement_time(Duration::from_secs(5));
        targets = bench
    }
}

criterion_main!(harness::benches);
