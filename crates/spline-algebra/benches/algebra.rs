//! Linear cost of the algebra: the product of two cubic functions with 10³–10⁵ coefficients
//! (unshared knots), and `g` with its Jacobian for curves with 10²–10⁴ control points; the
//! curvature features of the ellipsoid 1.5 × 2 × 1 (8 rational biquadratic patches):
//! parabolic lines, umbilics and ridges side by side.

#![allow(missing_docs)]

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::Vector2;
use spline_algebra::{Form, PlanarInvariants, ProductMap, product};
use spline_core::KnotVector;
use spline_geom::BSpline;
use std::hint::black_box;
use std::time::Duration;

fn function(n: usize, shift: f64) -> BSpline<f64, f64> {
    let segments = n - 3;
    let interior: Vec<f64> = (1..segments)
        .map(|j| (j as f64 + shift) / segments as f64)
        .collect();
    let knots = KnotVector::clamped(3, 0.0, 1.0, &interior).unwrap();
    let values = (0..n)
        .map(|i| ((i * 7919) % 1000) as f64 / 500.0 - 1.0)
        .collect();
    BSpline::new(knots, values).unwrap()
}

fn curve(n: usize) -> BSpline<f64, Vector2<f64>> {
    let knots = KnotVector::clamped_uniform(3, n, 0.0, 1.0).unwrap();
    let points = (0..n)
        .map(|i| {
            let t = i as f64 / n as f64 * 20.0;
            Vector2::new(t + 0.3 * t.sin(), (1.7 * t).cos())
        })
        .collect();
    BSpline::new(knots, points).unwrap()
}

fn products(c: &mut Criterion) {
    let mut group = c.benchmark_group("product_cubic");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(2));
    for n in [1_000usize, 10_000, 100_000] {
        let a = function(n, 0.0);
        let b = function(n, 0.5);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("value", n), &n, |bench, _| {
            bench.iter(|| product(black_box(&a), black_box(&b)).unwrap());
        });
        group.bench_with_input(
            BenchmarkId::new("value_and_jacobians", n),
            &n,
            |bench, _| {
                bench.iter(|| {
                    let map = ProductMap::new(a.knots(), b.knots()).unwrap();
                    let c = map.apply(a.control_points(), b.control_points()).unwrap();
                    let ja = map.jacobian_left(b.control_points()).unwrap();
                    let jb = map.jacobian_right(a.control_points()).unwrap();
                    (c, ja, jb)
                });
            },
        );
    }
    group.finish();
}

fn curvature_numerator(c: &mut Criterion) {
    let mut group = c.benchmark_group("g_cubic_curve");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(2));
    for n in [100usize, 1_000, 10_000] {
        let curve = curve(n);
        let algebra = PlanarInvariants::new(curve.knots()).unwrap();
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("with_jacobian", n), &n, |bench, _| {
            bench.iter(|| {
                algebra
                    .g(black_box(curve.control_points()), Form::BSpline)
                    .unwrap()
            });
        });
        group.bench_with_input(
            BenchmarkId::new("setup_and_with_jacobian", n),
            &n,
            |bench, _| {
                bench.iter(|| {
                    PlanarInvariants::new(curve.knots())
                        .unwrap()
                        .g(black_box(curve.control_points()), Form::BSpline)
                        .unwrap()
                });
            },
        );
    }
    group.finish();
}

fn surface_features(c: &mut Criterion) {
    let mut group = c.benchmark_group("ellipsoid_features");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(2));
    let sphere = spline_geom::NurbsSurface::sphere(nalgebra::Vector3::zeros(), 1.0).unwrap();
    let e = sphere.map_control_points(|p| nalgebra::Vector3::new(1.5 * p.x, 2.0 * p.y, p.z));
    group.bench_function("parabolic_lines_8", |bench| {
        bench.iter(|| spline_algebra::parabolic_lines(black_box(&e), 8).unwrap());
    });
    group.bench_function("umbilics", |bench| {
        bench.iter(|| spline_algebra::umbilics(black_box(&e)).unwrap());
    });
    for samples in [8usize, 32] {
        group.bench_with_input(
            BenchmarkId::new("surface_ridges", samples),
            &samples,
            |bench, &n| {
                bench.iter(|| spline_algebra::surface_ridges(black_box(&e), n).unwrap());
            },
        );
    }
    group.finish();
}

/// All the features of a random bicubic (`n × n` control points over the unit square,
/// heights from a fixed sequence): the workload of `spline surface-features` on the
/// reproducers' 60×60 random bicubic, at a size a benchmark can repeat.
fn random_bicubic_features(c: &mut Criterion) {
    let mut group = c.benchmark_group("random_bicubic_features");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(5));
    let n = 16usize;
    let knots = {
        let mut k = vec![0.0; 3];
        k.extend((0..=n - 3).map(|i| i as f64 / (n - 3) as f64));
        k.extend([1.0; 3]);
        spline_core::KnotVector::new(3, k).unwrap()
    };
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut height = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 0.1 - 0.05
    };
    let mut points = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let (x, y) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
            points.push(nalgebra::Vector3::new(x, y, height()));
        }
    }
    let surface = spline_geom::Surface::new(knots.clone(), knots, points).unwrap();
    let surface = spline_geom::NurbsSurface::from_surface(&surface);
    group.bench_function(BenchmarkId::new("surface_features_8", n), |bench| {
        bench.iter(|| spline_algebra::surface_features(black_box(&surface), 8).unwrap());
    });
    group.finish();
}

criterion_group!(
    benches,
    products,
    curvature_numerator,
    surface_features,
    random_bicubic_features
);
criterion_main!(benches);
