//! Fitting benchmarks, the same workloads as `xtask/bench/fit_scipy.py` (run both with
//! `cargo xtask bench fit`):
//!
//! - `fit/interp/N`: cubic interpolation of `N` planar points (`N = 10⁴, 10⁵, 10⁶`) on the
//!   not-a-knot knots that scipy's `make_interp_spline` picks by default;
//! - `fit/lsq_normal/100000`, `fit/lsq_qr/100000`: cubic least squares of 10⁵ planar
//!   points with 200 coefficients on clamped uniform knots, by the normal equations and by
//!   Givens QR.
//!
//! Each benchmark also prints a line `fit-residual <id> <value>`: the largest interpolation
//! error `max_j ‖s(x_j) − y_j‖∞`, or the least-squares sum of squares `Σ_j ‖s(x_j) − y_j‖²`.

use criterion::{BenchmarkId, Criterion, criterion_main};
use nalgebra::Vector2;
use spline_core::KnotVector;
use spline_fit::{LeastSquares, LsqMethod, interpolate_with_knots};
use spline_geom::BSpline;
use std::hint::black_box;
use std::time::Duration;

/// Abscissae `x_j = (j + 0.3 sin j)/(N − 1)`: strictly increasing, unevenly spaced.
fn abscissae(n: usize) -> Vec<f64> {
    #[allow(clippy::cast_precision_loss)]
    let scale = 1.0 / (n - 1) as f64;
    (0..n)
        .map(|j| {
            #[allow(clippy::cast_precision_loss)]
            let jf = j as f64;
            if j == 0 {
                0.0
            } else if j == n - 1 {
                1.0
            } else {
                (jf + 0.3 * jf.sin()) * scale
            }
        })
        .collect()
}

/// The data `y_j`: a smooth planar curve plus a deterministic wiggle.
fn ordinates(x: &[f64]) -> Vec<Vector2<f64>> {
    x.iter()
        .enumerate()
        .map(|(j, &t)| {
            #[allow(clippy::cast_precision_loss)]
            let noise = 0.05 * (12_345.678 * j as f64).sin();
            Vector2::new(
                (6.0 * std::f64::consts::PI * t).sin() + 0.1 * (50.0 * t).cos() + noise,
                (4.0 * std::f64::consts::PI * t).cos() * t - noise,
            )
        })
        .collect()
}

/// scipy's default knots for odd degree: the data with the first and last `(k+1)/2`
/// interior abscissae dropped, clamped.
fn not_a_knot(x: &[f64], k: usize) -> Vec<f64> {
    let half = k.div_ceil(2);
    let n = x.len();
    let mut t = vec![x[0]; k + 1];
    t.extend_from_slice(&x[half..n - half]);
    t.extend(std::iter::repeat_n(x[n - 1], k + 1));
    t
}

fn max_error(curve: &BSpline<f64, Vector2<f64>>, x: &[f64], y: &[Vector2<f64>]) -> f64 {
    let values = curve.eval_many(x).expect("in domain");
    values
        .iter()
        .zip(y)
        .map(|(a, b)| (a - b).amax())
        .fold(0.0, f64::max)
}

fn sum_squares(curve: &BSpline<f64, Vector2<f64>>, x: &[f64], y: &[Vector2<f64>]) -> f64 {
    let values = curve.eval_many(x).expect("in domain");
    values
        .iter()
        .zip(y)
        .map(|(a, b)| (a - b).norm_squared())
        .sum()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("fit");
    group.sample_size(20);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(3));
    for n in [10_000usize, 100_000, 1_000_000] {
        let x = abscissae(n);
        let y = ordinates(&x);
        let t = not_a_knot(&x, 3);
        let run = || {
            let knots = KnotVector::new(3, t.clone()).expect("valid knots");
            interpolate_with_knots(&knots, &x, &y).expect("interpolation")
        };
        let curve = run();
        println!("fit-residual interp/{n} {:e}", max_error(&curve, &x, &y));
        if n == 1_000_000 {
            group.sample_size(10);
        }
        group.bench_with_input(BenchmarkId::new("interp", n), &n, |b, _| {
            b.iter(|| black_box(run()));
        });
    }
    group.sample_size(20);
    let m = 100_000;
    let x = abscissae(m);
    let y = ordinates(&x);
    let knots = KnotVector::clamped_uniform(3, 200, 0.0, 1.0).expect("valid knots");
    for (name, method) in [
        ("lsq_normal", LsqMethod::NormalEquations),
        ("lsq_qr", LsqMethod::Qr),
    ] {
        let run = || {
            LeastSquares::new(&y, &x, knots.clone())
                .method(method)
                .control_points()
                .expect("least squares")
        };
        let curve = BSpline::new(knots.clone(), run()).expect("curve");
        println!("fit-residual {name}/{m} {:e}", sum_squares(&curve, &x, &y));
        group.bench_with_input(BenchmarkId::new(name, m), &m, |b, _| {
            b.iter(|| black_box(run()));
        });
    }
    group.finish();
}

mod harness {
    #![allow(missing_docs, unreachable_pub)]
    use super::bench;
    use criterion::criterion_group;
    criterion_group!(benches, bench);
}

criterion_main!(harness::benches);
