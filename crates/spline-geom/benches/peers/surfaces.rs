//! Surface workloads: a bicubic B-spline surface one point at a time, on a grid, its first
//! derivatives, and a NURBS sphere.

use crate::{report_check, uniform_samples};
use criterion::{Criterion, Throughput};
use curvo::prelude::NurbsSurface3D;
use nalgebra::{Point3, Point4, Vector3};
use spline_core::KnotVector;
use spline_geom::{NurbsSurface, Surface, Surface3};
use std::hint::black_box;
use truck_geometry::prelude::{
    BSplineSurface, KnotVec, NurbsSurface as TruckNurbs, ParametricSurface, Point3 as TPoint3,
    Vector4 as TVector4,
};

const SIDE: usize = 500;
const DERIV_POINTS: usize = 100_000;

fn gap(a: Vector3<f64>, x: f64, y: f64, z: f64) -> f64 {
    (a.x - x).abs().max((a.y - y).abs()).max((a.z - z).abs())
}

/// The bicubic with 50 × 50 control points over the unit square, random heights.
pub(crate) fn bicubic() -> Surface3 {
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

fn net_of(s: &Surface3) -> Vec<Vec<Vector3<f64>>> {
    s.control_net()
}

pub(crate) fn surfaces(c: &mut Criterion) {
    let ours = bicubic();
    let net = net_of(&ours);
    let curvo = NurbsSurface3D::new(
        3,
        3,
        ours.knots_u().knots().to_vec(),
        ours.knots_v().knots().to_vec(),
        net.iter()
            .map(|row| {
                row.iter()
                    .map(|p| Point4::new(p.x, p.y, p.z, 1.0))
                    .collect()
            })
            .collect(),
    );
    let truck = BSplineSurface::new(
        (
            KnotVec::from(ours.knots_u().knots().to_vec()),
            KnotVec::from(ours.knots_v().knots().to_vec()),
        ),
        net.iter()
            .map(|row| row.iter().map(|p| TPoint3::new(p.x, p.y, p.z)).collect())
            .collect(),
    );
    // One call per point: random (u, v) pairs, as many as the grid has points.
    let us = uniform_samples(SIDE * SIDE, 46);
    let vs = uniform_samples(SIDE * SIDE, 47);
    let grid: Vec<f64> = (0..SIDE).map(|i| i as f64 / (SIDE - 1) as f64).collect();
    let mut out = vec![Vector3::zeros(); SIDE * SIDE];
    ours.eval_grid_into(&grid, &grid, &mut out).unwrap();
    let (mut d_curvo, mut d_truck, mut d_grid) = (0.0f64, 0.0f64, 0.0f64);
    let mut evaluator = curvo.evaluator();
    let fast = ours.evaluator();
    assert!(
        fast.has_form(),
        "the bicubic has a piecewise polynomial form"
    );
    let mut d_fast = 0.0f64;
    for k in (0..SIDE * SIDE).step_by(101) {
        let p = ours.eval(us[k], vs[k]).unwrap();
        d_fast = d_fast.max((p - fast.eval(us[k], vs[k]).unwrap()).amax());
        let q = evaluator.point_at(us[k], vs[k]);
        d_curvo = d_curvo.max(gap(p, q.x, q.y, q.z));
        let q = truck.subs(us[k], vs[k]);
        d_truck = d_truck.max(gap(p, q.x, q.y, q.z));
        let (a, b) = (k / SIDE, k % SIDE);
        d_grid = d_grid.max((out[k] - ours.eval(grid[a], grid[b]).unwrap()).amax());
    }
    let sampled = curvo.regular_sample_points(SIDE - 1, SIDE - 1);
    let mut d_sampled = 0.0f64;
    for a in (0..SIDE).step_by(7) {
        for b in (0..SIDE).step_by(11) {
            let q = &sampled[a][b];
            d_sampled = d_sampled.max(gap(out[a * SIDE + b], q.x, q.y, q.z));
        }
    }
    report_check("surface/curvo_evaluator", d_curvo);
    report_check("surface/ours_evaluator", d_fast);
    report_check("surface/truck", d_truck);
    report_check("surface/ours_grid", d_grid);
    report_check("surface/curvo_grid", d_sampled);

    let mut group = c.benchmark_group("peers_surface_point");
    group.throughput(Throughput::Elements((SIDE * SIDE) as u64));
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
    group.bench_function("truck", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for (&u, &v) in us.iter().zip(&vs) {
                acc += truck.subs(black_box(u), black_box(v)).z;
            }
            acc
        });
    });
    group.finish();
    let mut group = c.benchmark_group("peers_surface_build");
    group.bench_function("ours_evaluator", |b| {
        b.iter(|| black_box(&ours).evaluator());
    });
    group.finish();

    let mut group = c.benchmark_group("peers_surface_grid");
    group.throughput(Throughput::Elements((SIDE * SIDE) as u64));
    group.bench_function("ours", |b| {
        b.iter(|| {
            ours.eval_grid_into(black_box(&grid), &grid, &mut out)
                .unwrap();
        });
    });
    group.bench_function("curvo", |b| {
        b.iter(|| curvo.regular_sample_points(black_box(SIDE - 1), SIDE - 1));
    });
    group.finish();

    derivatives(c, &ours, &curvo, &truck);
    nurbs_sphere(c);
}

fn derivatives(
    c: &mut Criterion,
    ours: &Surface3,
    curvo: &NurbsSurface3D<f64>,
    truck: &BSplineSurface<TPoint3>,
) {
    let us = uniform_samples(DERIV_POINTS, 48);
    let vs = uniform_samples(DERIV_POINTS, 49);
    let (mut d_curvo, mut d_truck, mut d_fast) = (0.0f64, 0.0f64, 0.0f64);
    let mut evaluator = curvo.evaluator();
    let fast = ours.evaluator();
    for k in (0..DERIV_POINTS).step_by(13) {
        let (u, v) = (us[k], vs[k]);
        let mut d = [Vector3::zeros(); 4];
        ours.derivatives_into(u, v, 1, &mut d).unwrap();
        let mut e = [Vector3::zeros(); 4];
        fast.derivatives_into(u, v, 1, &mut e).unwrap();
        d_fast = d_fast.max(
            (d[1] - e[1]).amax().max((d[2] - e[2]).amax()) / d[1].amax().max(d[2].amax()).max(1.0),
        );
        // derivatives_into writes [S, S_v, S_u, S_uv].
        let theirs = evaluator.rational_derivatives(u, v, 1);
        let scale = d[1].amax().max(d[2].amax()).max(1.0);
        let (su, sv) = (&theirs[1][0], &theirs[0][1]);
        d_curvo = d_curvo.max(gap(d[2], su.x, su.y, su.z).max(gap(d[1], sv.x, sv.y, sv.z)) / scale);
        let (tu, tv) = (truck.uder(u, v), truck.vder(u, v));
        d_truck = d_truck.max(gap(d[2], tu.x, tu.y, tu.z).max(gap(d[1], tv.x, tv.y, tv.z)) / scale);
    }
    report_check("surface_derivs/curvo_evaluator", d_curvo);
    report_check("surface_derivs/truck", d_truck);
    report_check("surface_derivs/ours_evaluator", d_fast);
    let mut group = c.benchmark_group("peers_surface_derivs");
    group.throughput(Throughput::Elements(DERIV_POINTS as u64));
    group.bench_function("ours", |b| {
        b.iter(|| {
            let mut acc = Vector3::zeros();
            let mut d = [Vector3::zeros(); 4];
            for (&u, &v) in us.iter().zip(&vs) {
                ours.derivatives_into(black_box(u), black_box(v), 1, &mut d)
                    .unwrap();
                acc += d[1] + d[2];
            }
            acc
        });
    });
    group.bench_function("ours_evaluator", |b| {
        b.iter(|| {
            let mut acc = Vector3::zeros();
            let mut d = [Vector3::zeros(); 4];
            for (&u, &v) in us.iter().zip(&vs) {
                fast.derivatives_into(black_box(u), black_box(v), 1, &mut d)
                    .unwrap();
                acc += d[1] + d[2];
            }
            acc
        });
    });
    group.bench_function("curvo_evaluator", |b| {
        b.iter(|| {
            let mut evaluator = curvo.evaluator();
            let mut acc = Vector3::zeros();
            for (&u, &v) in us.iter().zip(&vs) {
                let d = evaluator.rational_derivatives(black_box(u), black_box(v), 1);
                acc += d[1][0] + d[0][1];
            }
            acc
        });
    });
    group.bench_function("truck", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for (&u, &v) in us.iter().zip(&vs) {
                acc += truck.uder(black_box(u), black_box(v)).z + truck.vder(u, v).z;
            }
            acc
        });
    });
    group.finish();
}

fn nurbs_sphere(c: &mut Criterion) {
    let curvo =
        NurbsSurface3D::<f64>::try_sphere(&Point3::origin(), &Vector3::z(), &Vector3::x(), 1.0)
            .unwrap();
    let hom = curvo.control_points();
    let ku = curvo.u_knots().to_vec();
    let kv = curvo.v_knots().to_vec();
    let net = hom
        .iter()
        .map(|row| {
            row.iter()
                .map(|h| Vector3::new(h.x / h.w, h.y / h.w, h.z / h.w))
                .collect()
        })
        .collect();
    let weights = hom
        .iter()
        .map(|row| row.iter().map(|h| h.w).collect())
        .collect();
    let ours = NurbsSurface::from_net(
        KnotVector::new(curvo.u_degree(), ku.clone()).unwrap(),
        KnotVector::new(curvo.v_degree(), kv.clone()).unwrap(),
        net,
        weights,
    )
    .unwrap();
    let truck = TruckNurbs::new(BSplineSurface::new(
        (KnotVec::from(ku), KnotVec::from(kv)),
        hom.iter()
            .map(|row| {
                row.iter()
                    .map(|h| TVector4::new(h.x, h.y, h.z, h.w))
                    .collect()
            })
            .collect(),
    ));
    let ((ua, ub), (va, vb)) = ours.domain();
    let us: Vec<f64> = uniform_samples(DERIV_POINTS, 50)
        .into_iter()
        .map(|t| ua + (ub - ua) * t)
        .collect();
    let vs: Vec<f64> = uniform_samples(DERIV_POINTS, 51)
        .into_iter()
        .map(|t| va + (vb - va) * t)
        .collect();
    let (mut d_curvo, mut d_truck, mut radius) = (0.0f64, 0.0f64, 0.0f64);
    let mut evaluator = curvo.evaluator();
    let fast = ours.evaluator();
    assert!(
        fast.has_form(),
        "the sphere has a piecewise polynomial form"
    );
    let mut d_fast = 0.0f64;
    for k in (0..DERIV_POINTS).step_by(13) {
        let p = ours.eval(us[k], vs[k]).unwrap();
        d_fast = d_fast.max((p - fast.eval(us[k], vs[k]).unwrap()).amax());
        let q = evaluator.point_at(us[k], vs[k]);
        d_curvo = d_curvo.max(gap(p, q.x, q.y, q.z));
        let q = truck.subs(us[k], vs[k]);
        d_truck = d_truck.max(gap(p, q.x, q.y, q.z));
        radius = radius.max((p.norm() - 1.0).abs());
    }
    report_check("nurbs_surface/curvo_evaluator", d_curvo);
    report_check("nurbs_surface/truck", d_truck);
    report_check("nurbs_surface/radius", radius);
    report_check("nurbs_surface/ours_evaluator", d_fast);
    let mut group = c.benchmark_group("peers_nurbs_surface");
    group.throughput(Throughput::Elements(DERIV_POINTS as u64));
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
    group.bench_function("truck", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for (&u, &v) in us.iter().zip(&vs) {
                acc += truck.subs(black_box(u), black_box(v)).z;
            }
            acc
        });
    });
    group.finish();
}
