//! Surface benchmarks, run with their peers by `cargo xtask bench surfaces`:
//!
//! - `surface_closest/*`: closest points on a wavy bicubic surface with 10 × 10 control
//!   points, 1000 query points around it (a third of them nearest to the boundary).
//!   `setup` builds the [`SurfaceProjector`] (box hierarchy over the Bézier patches);
//!   `ours_global` answers the 1000 queries with it; `truck_global` asks truck-geometry's
//!   `SearchNearestParameter` with no hint (its presearch on a 50 × 50 grid, then Newton);
//!   `ours_local` / `truck_local` start Newton from a hint 0.02 off the answer.
//!   Throughput is per query.
//! - `surface_fit/lsq/N`: least squares of `N` scattered heights `z(x, y)` (`N = 10⁴, 10⁵`)
//!   by a bicubic with 20 × 20 coefficients on clamped uniform knots — the workload of
//!   scipy's `LSQBivariateSpline` in `xtask/bench/surfaces_scipy.py` (the same data: a
//!   Kronecker sequence, a deterministic wiggle as noise).
//! - `surface_fit/scattered/10000`: the whole [`fit_scattered`] pipeline on 10⁴ noisy
//!   points of a tilted analytic surface in 3-D (plane parametrisation, 12 × 12 control
//!   points, parameter correction, deviations both ways); no peer has it.
//!
//! Lines printed besides criterion's: `closest-check <what> <count>` (queries where one
//! library's distance exceeds the other's by more than 1e-9, truck's failures and answers
//! outside the domain, which count as failures) and
//! `fit-residual <id> <sum of squares>`.

// `criterion_group!` defines an undocumented public function.
#![allow(missing_docs)]
// Counts become coordinates: small integers, exact as f64.
#![allow(clippy::cast_precision_loss)]

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::Vector3;
use spline_core::KnotVector;
use spline_fit::{
    ScatteredOptions, SurfaceProjector, approximate_surface_scattered, closest_local, fit_scattered,
};
use spline_geom::Surface;
use std::hint::black_box;
use std::time::Duration;
use truck_geometry::prelude::{
    BSplineSurface, KnotVec, ParametricSurface, Point3, SPHint2D, SearchNearestParameter,
};

type V3 = Vector3<f64>;

/// A deterministic generator (xorshift64*), so runs are comparable.
fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        let bits = state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11;
        bits as f64 / (1u64 << 53) as f64
    }
}

/// A wavy bicubic over `[0, 1]²` with `n × n` control points.
fn wavy_surface(n: usize) -> Surface<f64, V3> {
    let knots = KnotVector::clamped_uniform(3, n, 0.0, 1.0).unwrap();
    let mut rand = uniform(7);
    let points = (0..n * n)
        .map(|k| {
            let (i, j) = ((k / n) as f64, (k % n) as f64);
            let m = (n - 1) as f64;
            V3::new(i / m, j / m, 0.3 * rand())
        })
        .collect();
    Surface::new(knots.clone(), knots, points).unwrap()
}

/// The same surface in truck-geometry.
fn to_truck(surface: &Surface<f64, V3>) -> BSplineSurface<Point3> {
    let nv = surface.knots_v().num_basis();
    let rows = surface
        .control_points()
        .chunks_exact(nv)
        .map(|row| row.iter().map(|p| Point3::new(p.x, p.y, p.z)).collect())
        .collect();
    BSplineSurface::new(
        (
            KnotVec::from(surface.knots_u().knots().to_vec()),
            KnotVec::from(surface.knots_v().knots().to_vec()),
        ),
        rows,
    )
}

/// 1000 points in `[-0.2, 1.2]² × [-0.3, 0.6]`: about a third project onto the boundary.
fn queries() -> Vec<V3> {
    let mut rand = uniform(99);
    (0..1000)
        .map(|_| V3::new(1.4 * rand() - 0.2, 1.4 * rand() - 0.2, 0.9 * rand() - 0.3))
        .collect()
}

/// Points off the surface along its normal, with a start 0.02 off their parameters.
fn local_queries(surface: &Surface<f64, V3>) -> Vec<(V3, (f64, f64))> {
    let mut rand = uniform(5);
    (0..1000)
        .map(|_| {
            let (u, v) = (0.1 + 0.8 * rand(), 0.1 + 0.8 * rand());
            let point = surface.eval(u, v).unwrap();
            let normal = surface.normal(u, v).unwrap();
            (point + normal * 0.02 * (rand() - 0.5), (u + 0.02, v - 0.02))
        })
        .collect()
}

fn truck_distance(surface: &BSplineSurface<Point3>, q: &V3, uv: Option<(f64, f64)>) -> f64 {
    uv.map_or(f64::INFINITY, |(u, v)| {
        let p = surface.subs(u, v);
        ((p.x - q.x).powi(2) + (p.y - q.y).powi(2) + (p.z - q.z).powi(2)).sqrt()
    })
}

fn closest(c: &mut Criterion) {
    let surface = wavy_surface(10);
    let truck = to_truck(&surface);
    let targets = queries();
    let projector = SurfaceProjector::new(&surface).unwrap();

    // Agreement, printed once.
    let (mut truck_worse, mut ours_worse, mut truck_none, mut truck_outside, mut boundary) =
        (0, 0, 0, 0, 0);
    for q in &targets {
        let ours = projector.closest(*q).unwrap();
        let mut found = truck.search_nearest_parameter(Point3::new(q.x, q.y, q.z), None, 100);
        truck_none += usize::from(found.is_none());
        // Newton without bounds may leave the domain (the polynomial continued): no answer.
        if found.is_some_and(|(u, v)| !(0.0..=1.0).contains(&u) || !(0.0..=1.0).contains(&v)) {
            truck_outside += 1;
            found = None;
        }
        let theirs = truck_distance(&truck, q, found);
        truck_worse += usize::from(theirs > ours.distance + 1e-9);
        ours_worse += usize::from(ours.distance > theirs + 1e-9);
        boundary += usize::from(
            [ours.u, ours.v]
                .iter()
                .any(|&x| x.abs() < 1e-12 || (x - 1.0).abs() < 1e-12),
        );
    }
    println!("closest-check boundary_answers {boundary}");
    println!("closest-check truck_farther {truck_worse}");
    println!("closest-check ours_farther {ours_worse}");
    println!("closest-check truck_none {truck_none}");
    println!("closest-check truck_outside {truck_outside}");

    let mut group = c.benchmark_group("surface_closest");
    group.measurement_time(Duration::from_secs(4));
    group.bench_function("setup", |b| {
        b.iter(|| SurfaceProjector::new(black_box(&surface)).unwrap());
    });
    group.throughput(Throughput::Elements(targets.len() as u64));
    group.bench_function("ours_global", |b| {
        b.iter(|| {
            for q in &targets {
                black_box(projector.closest(black_box(*q)).unwrap());
            }
        });
    });
    group.sample_size(10);
    group.bench_function("truck_global", |b| {
        b.iter(|| {
            for q in &targets {
                let p = Point3::new(q.x, q.y, q.z);
                black_box(truck.search_nearest_parameter(black_box(p), None, 100));
            }
        });
    });
    group.sample_size(100);
    let local = local_queries(&surface);
    group.bench_function("ours_local", |b| {
        b.iter(|| {
            for (q, uv) in &local {
                black_box(closest_local(&surface, black_box(*q), *uv).unwrap());
            }
        });
    });
    group.bench_function("truck_local", |b| {
        b.iter(|| {
            for (q, uv) in &local {
                let p = Point3::new(q.x, q.y, q.z);
                black_box(truck.search_nearest_parameter(
                    black_box(p),
                    SPHint2D::Parameter(uv.0, uv.1),
                    100,
                ));
            }
        });
    });
    group.finish();
}

/// The heights of `xtask/bench/surfaces_scipy.py`: points of the Kronecker sequence with
/// the plastic number, `z = sin 3x cos 2y + 0.2 x y` and a deterministic wiggle.
fn height_data(count: usize) -> (Vec<(f64, f64)>, Vec<f64>) {
    let g = 1.324_717_957_244_746_f64;
    let (a1, a2) = (1.0 / g, 1.0 / (g * g));
    let mut params = Vec::with_capacity(count);
    let mut heights = Vec::with_capacity(count);
    for j in 0..count {
        let jf = j as f64;
        let (x, y) = ((0.5 + a1 * jf).fract(), (0.5 + a2 * jf).fract());
        params.push((x, y));
        heights
            .push((3.0 * x).sin() * (2.0 * y).cos() + 0.2 * x * y + 0.01 * (12_345.678 * jf).sin());
    }
    (params, heights)
}

/// Noisy samples of a tilted graph in 3-D (as in the scattered-fitting tests).
fn noisy_cloud(count: usize) -> Vec<V3> {
    let mut rand = uniform(2024);
    let (c, s) = (0.6f64.cos(), 0.6f64.sin());
    (0..count)
        .map(|_| {
            let (x, y) = (2.0 * rand(), 2.0 * rand());
            let z = 0.3 * (1.5 * x).sin() * (1.2 * y).cos();
            let noise = V3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 2e-3;
            V3::new(c * x - s * z, y, s * x + c * z) + noise
        })
        .collect()
}

fn fitting(c: &mut Criterion) {
    let knots = KnotVector::clamped_uniform(3, 20, 0.0, 1.0).unwrap();
    let mut group = c.benchmark_group("surface_fit");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(5));
    for count in [10_000usize, 100_000] {
        let (params, heights) = height_data(count);
        let fit = approximate_surface_scattered(&params, &heights, &knots, &knots, 0.0).unwrap();
        let residual: f64 = params
            .iter()
            .zip(&heights)
            .map(|(&(u, v), z)| (fit.surface.eval(u, v).unwrap() - z).powi(2))
            .sum();
        println!("fit-residual lsq/{count} {residual:.12e}");
        group.bench_with_input(BenchmarkId::new("lsq", count), &count, |b, _| {
            b.iter(|| {
                approximate_surface_scattered(black_box(&params), &heights, &knots, &knots, 0.0)
                    .unwrap()
            });
        });
    }
    let cloud = noisy_cloud(10_000);
    let options = ScatteredOptions {
        control_points: (12, 12),
        corrections: 5,
        ..ScatteredOptions::default()
    };
    let fit = fit_scattered::<f64, Surface<f64, V3>>(&cloud, None, None, &options).unwrap();
    println!(
        "fit-deviation scattered/10000 rms {:.3e} max {:.3e} to_data {:.3e} corrections {}",
        fit.to_surface.rms, fit.to_surface.max, fit.to_data, fit.corrections
    );
    group.bench_function(BenchmarkId::new("scattered", 10_000), |b| {
        b.iter(|| {
            fit_scattered::<f64, Surface<f64, V3>>(black_box(&cloud), None, None, &options).unwrap()
        });
    });
    group.finish();
}

criterion_group!(benches, closest, fitting);
criterion_main!(benches);
