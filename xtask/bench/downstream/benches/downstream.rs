//! One-point evaluation of a bicubic 50 × 50 surface at 1000² random parameters, timed from a
//! crate that only depends on the library (thin LTO): `Surface::eval`, `Surface::evaluator`
//! and curvo's evaluator, interleaved in one criterion group (`downstream_surface_point/…`),
//! after checking that their results agree (`peers-check` lines, at most 1e-12 apart); also
//! the NURBS sphere through `NurbsSurface::eval` and its evaluator.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use curvo::prelude::NurbsSurface3D;
use nalgebra::{Point3, Point4, Vector3};
use spline_core::KnotVector;
use spline_geom::{NurbsSurface, Surface, Surface3};
use std::hint::black_box;
use std::time::Duration;

const POINTS: usize = 1_000_000;

/// Uniform numbers in [0, 1) from xorshift64*, as the in-tree peers benchmark draws them.
fn uniform_samples(count: usize, seed: u64) -> Vec<f64> {
    let mut state = seed;
    (0..count)
        .map(|_| {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            let bits = state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11;
            bits as f64 / (1u64 << 53) as f64
        })
        .collect()
}

fn report_check(id: &str, max_diff: f64) {
    println!("peers-check downstream/{id} {max_diff:e}");
    assert!(max_diff <= 1e-12, "{id}: results differ by {max_diff:e}");
}

fn gap(a: Vector3<f64>, q: Point3<f64>) -> f64 {
    (a - q.coords).amax()
}

/// The in-tree benchmark's bicubic: 50 × 50 control points over the unit square, random
/// heights.
fn bicubic() -> Surface3 {
    let n = 50;
    let knots = KnotVector::clamped_uniform(3, n, 0.0, 1.0).unwrap();
    let zs = uniform_samples(n * n, 9);
    let net = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| Vector3::new(i as f64 / n as f64, j as f64 / n as f64, zs[i * n + j]))
                .collect()
        })
        .collect();
    Surface::from_net(knots.clone(), knots, net).unwrap()
}

fn surfaces(c: &mut Criterion) {
    let ours = bicubic();
    let curvo = NurbsSurface3D::new(
        3,
        3,
        ours.knots_u().knots().to_vec(),
        ours.knots_v().knots().to_vec(),
        ours.control_net()
            .iter()
            .map(|row| {
                row.iter()
                    .map(|p| Point4::new(p.x, p.y, p.z, 1.0))
                    .collect()
            })
            .collect(),
    );
    let us = uniform_samples(POINTS, 46);
    let vs = uniform_samples(POINTS, 47);
    let fast = ours.evaluator();
    let mut theirs = curvo.evaluator();
    let (mut d_fast, mut d_curvo) = (0.0f64, 0.0f64);
    for k in (0..POINTS).step_by(97) {
        let p = ours.eval(us[k], vs[k]).unwrap();
        d_fast = d_fast.max((p - fast.eval(us[k], vs[k]).unwrap()).amax());
        d_curvo = d_curvo.max(gap(p, theirs.point_at(us[k], vs[k])));
    }
    report_check("surface/ours_evaluator", d_fast);
    report_check("surface/curvo_evaluator", d_curvo);

    let mut group = c.benchmark_group("downstream_surface_point");
    group.throughput(Throughput::Elements(POINTS as u64));
    group.bench_function("ours", |b| {
        b.iter(|| {
            let mut acc = Vector3::zeros();
            for (&u, &v) in us.iter().zip(&vs) {
                acc += ours.eval(black_box(u), black_box(v)).unwrap();
            }
            acc
        });
    });
    group.bench_function("ours_evaluator", |b| {
        b.iter(|| {
            let mut acc = Vector3::zeros();
            for (&u, &v) in us.iter().zip(&vs) {
                acc += fast.eval(black_box(u), black_box(v)).unwrap();
            }
            acc
        });
    });
    group.bench_function("curvo_evaluator", |b| {
        b.iter(|| {
            let mut evaluator = curvo.evaluator();
            let mut acc = Point3::origin();
            for (&u, &v) in us.iter().zip(&vs) {
                acc.coords += evaluator.point_at(black_box(u), black_box(v)).coords;
            }
            acc
        });
    });
    group.finish();

    let sphere = NurbsSurface::sphere(Vector3::new(0.0, 0.0, 0.0), 1.0).unwrap();
    let ((ua, ub), (va, vb)) = sphere.domain();
    let count = POINTS / 10;
    let su: Vec<f64> = us[..count].iter().map(|t| ua + (ub - ua) * t).collect();
    let sv: Vec<f64> = vs[..count].iter().map(|t| va + (vb - va) * t).collect();
    let fast = sphere.evaluator();
    let mut d_sphere = 0.0f64;
    for k in (0..count).step_by(13) {
        let p = sphere.eval(su[k], sv[k]).unwrap();
        d_sphere = d_sphere.max((p - fast.eval(su[k], sv[k]).unwrap()).amax());
    }
    report_check("nurbs_surface/ours_evaluator", d_sphere);
    let mut group = c.benchmark_group("downstream_nurbs_surface");
    group.throughput(Throughput::Elements(count as u64));
    group.bench_function("ours", |b| {
        b.iter(|| {
            let mut acc = Vector3::zeros();
            for (&u, &v) in su.iter().zip(&sv) {
                acc += sphere.eval(black_box(u), black_box(v)).unwrap();
            }
            acc
        });
    });
    group.bench_function("ours_evaluator", |b| {
        b.iter(|| {
            let mut acc = Vector3::zeros();
            for (&u, &v) in su.iter().zip(&sv) {
                acc += fast.eval(black_box(u), black_box(v)).unwrap();
            }
            acc
        });
    });
    group.finish();
}

fn criterion() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
}

criterion_group! {
    name = benches;
    config = criterion();
    targets = surfaces
}
criterion_main!(benches);
