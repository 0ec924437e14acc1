//! Smoothing-spline benchmarks, the same workloads as `xtask/bench/smoothing_scipy.py` (run
//! both with `cargo xtask bench smoothing`), on `N = 10⁵` data
//! $x_j = j + 0.3 \sin j$, $y_j = \sin(x_j/3000) + 0.5 \cos(x_j/700) + 0.1 \sin(12345.678\\,j)$:
//!
//! - `smoothing/lambda/N`: `make_smoothing_spline(x, y, lam=1)`;
//! - `smoothing/gcv/N`: `make_smoothing_spline(x, y)` (λ by generalised cross-validation);
//! - `smoothing/residual/N`: `splrep(x, y, s=N/200)` (FITPACK's residual target, cubic).
//!
//! Each prints a line `smoothing-check <id> <value>`: λ for the GCV search, the weighted
//! residual for the others, to compare with scipy's.

use criterion::{Criterion, criterion_main};
use spline_fit::{SmoothingParameter, smoothing_spline, smoothing_to_residual};
use std::hint::black_box;
use std::time::Duration;

/// The benchmark data (also written by `xtask/bench/smoothing_scipy.py`).
fn data(n: usize) -> (Vec<f64>, Vec<f64>) {
    (0..n)
        .map(|j| {
            #[allow(clippy::cast_precision_loss)]
            let jf = j as f64;
            let x = jf + 0.3 * jf.sin();
            let y = (x / 3000.0).sin() + 0.5 * (x / 700.0).cos() + 0.1 * (12_345.678 * jf).sin();
            (x, y)
        })
        .unzip()
}

fn smoothing(c: &mut Criterion) {
    let n = 100_000;
    let (x, y) = data(n);
    let mut group = c.benchmark_group("smoothing");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(8));
    let fixed = smoothing_spline(&x, &y, None, SmoothingParameter::Lambda(1.0)).expect("fixed λ");
    println!("smoothing-check lambda/{n} {:e}", fixed.residual);
    group.bench_function(format!("lambda/{n}"), |b| {
        b.iter(|| {
            smoothing_spline(
                black_box(&x),
                black_box(&y),
                None,
                SmoothingParameter::Lambda(1.0),
            )
        });
    });
    let gcv = smoothing_spline(&x, &y, None, SmoothingParameter::Gcv).expect("GCV");
    println!("smoothing-check gcv/{n} {:e}", gcv.lambda);
    group.bench_function(format!("gcv/{n}"), |b| {
        b.iter(|| smoothing_spline(black_box(&x), black_box(&y), None, SmoothingParameter::Gcv));
    });
    #[allow(clippy::cast_precision_loss)]
    let s = n as f64 / 200.0;
    let fit = smoothing_to_residual(&x, &y, None, 3, s).expect("residual target");
    println!(
        "smoothing-check residual/{n} {:e} ({} knots)",
        fit.residual,
        fit.spline.knots().len()
    );
    group.bench_function(format!("residual/{n}"), |b| {
        b.iter(|| smoothing_to_residual(black_box(&x), black_box(&y), None, 3, s));
    });
    group.finish();
}

fn benches() {
    let mut c = Criterion::default().configure_from_args();
    smoothing(&mut c);
}

criterion_main!(benches);
