//! Fitting against curvo 0.3 (part of `cargo xtask bench peers`): global interpolation of
//! `m` planar points by a cubic with chord-length parameters and averaged knots (The NURBS
//! Book (9.8) — both libraries' default), after checking that the two curves agree at 1,000
//! parameters (printed as `peers-check interp_<m>/curvo <max difference>` lines). Ours solves
//! the banded, totally positive collocation system in `O(m p²)`; curvo assembles and solves
//! it dense.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use curvo::prelude::{Interpolation, NurbsCurve2D};
use nalgebra::{Point2, Vector2};
use spline_fit::{InterpolationOptions, interpolate};
use std::hint::black_box;
use std::time::Duration;

/// A wavy planar polyline of `m` points (deterministic).
fn points(m: usize) -> Vec<Vector2<f64>> {
    (0..m)
        .map(|i| {
            let t = i as f64 / (m - 1) as f64;
            Vector2::new(
                t + 0.01 * (37.0 * t).sin(),
                (6.0 * t).sin() + 0.2 * (23.0 * t).cos(),
            )
        })
        .collect()
}

fn interpolation(c: &mut Criterion) {
    for m in [100, 1000] {
        let data = points(m);
        let curvo_data: Vec<Point2<f64>> = data.iter().map(|p| Point2::new(p.x, p.y)).collect();
        let options = InterpolationOptions::default();
        let ours = interpolate(&data, 3, &options).unwrap();
        let theirs = NurbsCurve2D::<f64>::interpolate(&curvo_data, 3).unwrap();
        let mut max_diff = 0.0f64;
        for k in 0..=1000 {
            let u = f64::from(k) / 1000.0;
            let a = ours.curve.eval(u).unwrap();
            let b = theirs.point_at(u);
            max_diff = max_diff.max((a.x - b.x).abs()).max((a.y - b.y).abs());
        }
        let id = format!("interp_{m}");
        println!("peers-check {id}/curvo {max_diff:e}");
        assert!(
            max_diff <= 1e-9,
            "{id}: results differ by {max_diff:e} — not timing disagreeing libraries"
        );
        let mut group = c.benchmark_group(format!("peers_{id}"));
        group.bench_function(BenchmarkId::from_parameter("ours"), |b| {
            b.iter(|| interpolate(black_box(&data), 3, &options).unwrap());
        });
        group.bench_function(BenchmarkId::from_parameter("curvo"), |b| {
            b.iter(|| NurbsCurve2D::<f64>::interpolate(black_box(&curvo_data), 3).unwrap());
        });
        group.finish();
    }
}

fn criterion() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
}

criterion_group! {
    name = benches;
    config = criterion();
    targets = interpolation
}
criterion_main!(benches);
