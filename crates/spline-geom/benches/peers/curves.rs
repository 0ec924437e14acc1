//! Curve workloads: evaluation, derivatives, insertion, refinement, elevation, NURBS.

use crate::{report_check, uniform_samples};
use criterion::{BatchSize, Criterion, Throughput};
use curvo::prelude::NurbsCurve2D;
use nalgebra::{Point2, Point3, Vector2};
use spline_core::KnotVector;
use spline_geom::{BSpline, Curve2, NurbsCurve2};
use std::hint::black_box;
use truck_geometry::prelude::{
    BSplineCurve, KnotVec, NurbsCurve as TruckNurbs, ParametricCurve, Point2 as TPoint2,
    Vector3 as TVector3,
};

const POINTS: usize = 1_000_000;
const DERIV_POINTS: usize = 100_000;
const INSERTED: usize = 1000;

/// The planar cubic with 100 control points on clamped uniform knots of [0, 1].
pub(crate) fn cubic() -> Curve2 {
    let n = 100;
    let knots = KnotVector::clamped_uniform(3, n, 0.0, 1.0).unwrap();
    let ys = uniform_samples(n, 7);
    let points = (0..n)
        .map(|i| Vector2::new(i as f64 / n as f64, ys[i]))
        .collect();
    BSpline::new(knots, points).unwrap()
}

fn to_curvo(c: &Curve2) -> NurbsCurve2D<f64> {
    let points = c
        .control_points()
        .iter()
        .map(|p| Point3::new(p.x, p.y, 1.0))
        .collect();
    NurbsCurve2D::try_new(c.degree(), points, c.knots().knots().to_vec()).unwrap()
}

fn to_truck(c: &Curve2) -> BSplineCurve<TPoint2> {
    let points = c
        .control_points()
        .iter()
        .map(|p| TPoint2::new(p.x, p.y))
        .collect();
    BSplineCurve::new(KnotVec::from(c.knots().knots().to_vec()), points)
}

fn dist2(a: Vector2<f64>, x: f64, y: f64) -> f64 {
    (a.x - x).abs().max((a.y - y).abs())
}

pub(crate) fn evaluation(c: &mut Criterion) {
    let ours = cubic();
    let curvo = to_curvo(&ours);
    let truck = to_truck(&ours);
    let params = uniform_samples(POINTS, 42);
    let mut sorted = params.clone();
    sorted.sort_by(f64::total_cmp);
    let mut out = vec![Vector2::zeros(); POINTS];
    ours.eval_many_into(&params, &mut out).unwrap();
    let (mut d_curvo, mut d_eval, mut d_truck, mut d_one) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut d_ours_evaluator = 0.0f64;
    let mut evaluator = curvo.evaluator();
    let ours_evaluator = ours.evaluator();
    for (&u, p) in params.iter().zip(&out).step_by(97) {
        d_ours_evaluator = d_ours_evaluator.max((ours_evaluator.eval(u).unwrap() - p).amax());
        let q: Point2<f64> = curvo.point_at(u);
        d_curvo = d_curvo.max(dist2(*p, q.x, q.y));
        let q = evaluator.point_at(u);
        d_eval = d_eval.max(dist2(*p, q.x, q.y));
        let q = truck.subs(u);
        d_truck = d_truck.max(dist2(*p, q.x, q.y));
        d_one = d_one.max(dist2(*p, 0.0, 0.0) - dist2(ours.eval(u).unwrap(), 0.0, 0.0));
    }
    report_check("eval/curvo", d_curvo);
    report_check("eval/curvo_evaluator", d_eval);
    report_check("eval/truck", d_truck);
    report_check("eval/ours_batch", d_one.abs());
    report_check("eval/ours_evaluator", d_ours_evaluator);

    let mut group = c.benchmark_group("peers_eval_point");
    group.throughput(Throughput::Elements(POINTS as u64));
    group.bench_function("ours", |b| {
        b.iter(|| {
            let mut acc = Vector2::zeros();
            for &u in &params {
                acc += ours.eval(black_box(u)).unwrap();
            }
            acc
        });
    });
    group.bench_function("ours_evaluator", |b| {
        b.iter(|| {
            let evaluator = ours.evaluator();
            let mut acc = Vector2::zeros();
            for &u in &params {
                acc += evaluator.eval(black_box(u)).unwrap();
            }
            acc
        });
    });
    group.bench_function("curvo", |b| {
        b.iter(|| {
            let mut acc = Point2::origin();
            for &u in &params {
                acc.coords += curvo.point_at(black_box(u)).coords;
            }
            acc
        });
    });
    group.bench_function("curvo_evaluator", |b| {
        b.iter(|| {
            let mut evaluator = curvo.evaluator();
            let mut acc = Point2::origin();
            for &u in &params {
                acc.coords += evaluator.point_at(black_box(u)).coords;
            }
            acc
        });
    });
    group.bench_function("truck", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &u in &params {
                acc += truck.subs(black_box(u)).x;
            }
            acc
        });
    });
    group.finish();

    let mut group = c.benchmark_group("peers_eval_batch");
    group.throughput(Throughput::Elements(POINTS as u64));
    group.bench_function("ours", |b| {
        b.iter(|| ours.eval_many_into(black_box(&params), &mut out).unwrap());
    });
    group.bench_function("ours_sorted", |b| {
        b.iter(|| ours.eval_many_into(black_box(&sorted), &mut out).unwrap());
    });
    // The limits on this CPU: the cubic's arithmetic alone (span and Taylor coefficients
    // known, Horner's scheme, the store), and streaming the parameters in and the points out.
    let (spans, coefficients) = taylor_form(&ours, &params);
    let k = ours.knots().knots();
    group.bench_function("limit_arithmetic", |b| {
        b.iter(|| {
            for ((slot, &u), &s) in out.iter_mut().zip(black_box(&params)).zip(&spans) {
                let c: &[Vector2<f64>; 4] = coefficients[4 * s..4 * s + 4].try_into().unwrap();
                let t = u - k[s + 3];
                *slot = ((c[3] * t + c[2]) * t + c[1]) * t + c[0];
            }
        });
    });
    group.bench_function("limit_memory", |b| {
        b.iter(|| {
            for (slot, &u) in out.iter_mut().zip(black_box(&params)) {
                *slot = Vector2::new(u, u);
            }
        });
    });
    group.bench_function("curvo_evaluator_sorted", |b| {
        b.iter(|| {
            let mut evaluator = curvo.evaluator();
            let mut acc = Point2::origin();
            for &u in &sorted {
                acc.coords += evaluator.point_at(black_box(u)).coords;
            }
            acc
        });
    });
    group.finish();

    derivatives(c, &ours, &curvo, &truck);
}

/// For each parameter its span index (from 0), and the Taylor coefficients of the cubic about
/// every span's left knot (from the public derivatives), for the arithmetic-only limit.
fn taylor_form(curve: &Curve2, params: &[f64]) -> (Vec<usize>, Vec<Vector2<f64>>) {
    let k = curve.knots().knots();
    let spans: Vec<usize> = params
        .iter()
        .map(|&u| curve.knots().find_span(u).unwrap() - 3)
        .collect();
    let mut coefficients = Vec::new();
    for &left in &k[3..curve.len()] {
        let mut d = [Vector2::zeros(); 4];
        // Right derivatives at the span's left knot (find_span picks this span there).
        curve.derivatives_into(left, &mut d).unwrap();
        coefficients.extend([d[0], d[1], d[2] / 2.0, d[3] / 6.0]);
    }
    let check = params
        .iter()
        .zip(&spans)
        .step_by(101)
        .map(|(&u, &s)| {
            let c = &coefficients[4 * s..4 * s + 4];
            let t = u - k[s + 3];
            let p = ((c[3] * t + c[2]) * t + c[1]) * t + c[0];
            (p - curve.eval(u).unwrap()).amax()
        })
        .fold(0.0, f64::max);
    report_check("eval/limit_arithmetic", check);
    (spans, coefficients)
}

fn derivatives(
    c: &mut Criterion,
    ours: &Curve2,
    curvo: &NurbsCurve2D<f64>,
    truck: &BSplineCurve<TPoint2>,
) {
    let params = uniform_samples(DERIV_POINTS, 43);
    let (mut d_curvo, mut d_truck, mut d_evaluator) = (0.0f64, 0.0f64, 0.0f64);
    let evaluator = ours.evaluator();
    for &u in params.iter().step_by(7) {
        let mut d = [Vector2::zeros(); 3];
        ours.derivatives_into(u, &mut d).unwrap();
        let mut e = [Vector2::zeros(); 3];
        evaluator.derivatives_into(u, &mut e).unwrap();
        d_evaluator =
            d_evaluator.max((d[1] - e[1]).amax().max((d[2] - e[2]).amax()) / d[2].norm().max(1.0));
        let theirs = curvo.rational_derivatives(u, 2);
        let scale = d[2].norm().max(1.0);
        d_curvo = d_curvo.max(
            (dist2(d[1], theirs[1].x, theirs[1].y)).max(dist2(d[2], theirs[2].x, theirs[2].y))
                / scale,
        );
        let (t1, t2) = (truck.der(u), truck.der2(u));
        d_truck = d_truck.max((dist2(d[1], t1.x, t1.y)).max(dist2(d[2], t2.x, t2.y)) / scale);
    }
    report_check("derivs/curvo", d_curvo);
    report_check("derivs/truck", d_truck);
    report_check("derivs/ours_evaluator", d_evaluator);
    let mut group = c.benchmark_group("peers_derivs");
    group.throughput(Throughput::Elements(DERIV_POINTS as u64));
    group.bench_function("ours", |b| {
        b.iter(|| {
            let mut acc = Vector2::zeros();
            let mut d = [Vector2::zeros(); 3];
            for &u in &params {
                ours.derivatives_into(black_box(u), &mut d).unwrap();
                acc += d[1] + d[2];
            }
            acc
        });
    });
    group.bench_function("ours_evaluator", |b| {
        b.iter(|| {
            let evaluator = ours.evaluator();
            let mut acc = Vector2::zeros();
            let mut d = [Vector2::zeros(); 3];
            for &u in &params {
                evaluator.derivatives_into(black_box(u), &mut d).unwrap();
                acc += d[1] + d[2];
            }
            acc
        });
    });
    group.bench_function("curvo", |b| {
        b.iter(|| {
            let mut acc = Vector2::zeros();
            for &u in &params {
                let d = curvo.rational_derivatives(black_box(u), 2);
                acc += d[1] + d[2];
            }
            acc
        });
    });
    group.bench_function("truck", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &u in &params {
                acc += truck.der(black_box(u)).x + truck.der2(black_box(u)).x;
            }
            acc
        });
    });
    group.finish();
}

/// Largest distance between two planar curves at 1000 parameters.
fn curve_gap(ours: &Curve2, truck: &BSplineCurve<TPoint2>) -> f64 {
    (0..=1000)
        .map(|i| {
            let u = f64::from(i) / 1000.0;
            let q = truck.subs(u);
            dist2(ours.eval(u).unwrap(), q.x, q.y)
        })
        .fold(0.0, f64::max)
}

fn curvo_gap(ours: &Curve2, curvo: &NurbsCurve2D<f64>) -> f64 {
    (0..=1000)
        .map(|i| {
            let u = f64::from(i) / 1000.0;
            let q = curvo.point_at(u);
            dist2(ours.eval(u).unwrap(), q.x, q.y)
        })
        .fold(0.0, f64::max)
}

pub(crate) fn structural(c: &mut Criterion) {
    let ours = cubic();
    let curvo = to_curvo(&ours);
    let truck = to_truck(&ours);
    // Distinct knots away from the existing ones (multiplicity never exceeds 1).
    let knots: Vec<f64> = uniform_samples(INSERTED, 44)
        .into_iter()
        .map(|u| 0.0005 + 0.999 * u)
        .collect();
    let mut sorted = knots.clone();
    sorted.sort_by(f64::total_cmp);

    // Agreement: the inserted curves equal each other and the original.
    let mut o = ours.clone();
    let mut cv = curvo.clone();
    let mut tr = truck.clone();
    for &u in &knots {
        o.insert_knot_mut(u, 1).unwrap();
        cv.try_add_knot(u).unwrap();
        tr.add_knot(u);
    }
    assert_eq!(o.len(), ours.len() + INSERTED);
    report_check("insert/ours", curve_gap(&o, &truck));
    report_check("insert/curvo", curvo_gap(&o, &cv));
    report_check("insert/truck", curve_gap(&o, &tr));
    let refined = ours.refine(&sorted).unwrap();
    let mut cv = curvo.clone();
    cv.try_refine_knot(sorted.clone()).unwrap();
    report_check("refine/ours", curve_gap(&refined, &truck));
    report_check("refine/curvo", curvo_gap(&refined, &cv));
    for times in [1, 3] {
        let elevated = ours.elevate_degree(times).unwrap();
        let mut tr = truck.clone();
        for _ in 0..times {
            tr.elevate_degree();
        }
        report_check(
            &format!("elevate{times}/ours"),
            curve_gap(&elevated, &truck),
        );
        report_check(&format!("elevate{times}/truck"), curve_gap(&elevated, &tr));
        let curvo_ok = std::panic::catch_unwind(|| curvo.try_elevate_degree(3 + times).is_ok());
        println!(
            "peers-note elevate{times}/curvo {}",
            match curvo_ok {
                Ok(true) => "ok",
                Ok(false) => "error",
                Err(_) => "panics",
            }
        );
    }

    let mut group = c.benchmark_group("peers_insert");
    group.bench_function("ours", |b| {
        b.iter_batched(
            || ours.clone(),
            |mut curve| {
                for &u in &knots {
                    curve.insert_knot_mut(black_box(u), 1).unwrap();
                }
                curve
            },
            BatchSize::LargeInput,
        );
    });
    group.bench_function("curvo", |b| {
        b.iter_batched(
            || curvo.clone(),
            |mut curve| {
                for &u in &knots {
                    curve.try_add_knot(black_box(u)).unwrap();
                }
                curve
            },
            BatchSize::LargeInput,
        );
    });
    group.bench_function("truck", |b| {
        b.iter_batched(
            || truck.clone(),
            |mut curve| {
                for &u in &knots {
                    curve.add_knot(black_box(u));
                }
                curve
            },
            BatchSize::LargeInput,
        );
    });
    group.finish();

    let mut group = c.benchmark_group("peers_refine");
    group.bench_function("ours", |b| {
        b.iter(|| ours.refine(black_box(&sorted)).unwrap());
    });
    group.bench_function("curvo", |b| {
        b.iter_batched(
            || (curvo.clone(), sorted.clone()),
            |(mut curve, x)| {
                curve.try_refine_knot(x).unwrap();
                curve
            },
            BatchSize::LargeInput,
        );
    });
    group.finish();

    for times in [1, 3] {
        let mut group = c.benchmark_group(format!("peers_elevate{times}"));
        group.bench_function("ours", |b| {
            b.iter(|| ours.elevate_degree(black_box(times)).unwrap());
        });
        group.bench_function("truck", |b| {
            b.iter_batched(
                || truck.clone(),
                |mut curve| {
                    for _ in 0..times {
                        curve.elevate_degree();
                    }
                    curve
                },
                BatchSize::LargeInput,
            );
        });
        group.finish();
    }
}

pub(crate) fn nurbs(c: &mut Criterion) {
    let curvo =
        NurbsCurve2D::<f64>::try_circle(&Point2::origin(), &Vector2::x(), &Vector2::y(), 1.0)
            .unwrap();
    let knots = curvo.knots().to_vec();
    let (points, weights): (Vec<_>, Vec<_>) = curvo
        .control_points()
        .iter()
        .map(|h| (Vector2::new(h.x / h.z, h.y / h.z), h.z))
        .unzip();
    let ours = NurbsCurve2::from_knots(
        curvo.degree(),
        knots.clone(),
        points.clone(),
        weights.clone(),
    )
    .unwrap();
    let homogeneous = curvo
        .control_points()
        .iter()
        .map(|h| TVector3::new(h.x, h.y, h.z))
        .collect();
    let truck = TruckNurbs::new(BSplineCurve::new(KnotVec::from(knots), homogeneous));
    let (a, b) = ours.domain();
    let params: Vec<f64> = uniform_samples(POINTS, 45)
        .into_iter()
        .map(|t| a + (b - a) * t)
        .collect();
    let mut out = vec![Vector2::zeros(); POINTS];
    ours.eval_many_into(&params, &mut out).unwrap();
    let (mut d_curvo, mut d_truck, mut d_one, mut radius) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut evaluator = curvo.evaluator();
    for (&u, p) in params.iter().zip(&out).step_by(97) {
        let q = evaluator.point_at(u);
        d_curvo = d_curvo.max(dist2(*p, q.x, q.y));
        let q = truck.subs(u);
        d_truck = d_truck.max(dist2(*p, q.x, q.y));
        d_one = d_one.max((ours.eval(u).unwrap() - p).amax());
        d_one = d_one.max((ours.evaluator().eval(u).unwrap() - p).amax());
        radius = radius.max((p.norm() - 1.0).abs());
    }
    report_check("nurbs/curvo", d_curvo);
    report_check("nurbs/truck", d_truck);
    report_check("nurbs/ours_batch", d_one);
    report_check("nurbs/radius", radius);

    let mut group = c.benchmark_group("peers_nurbs");
    group.throughput(Throughput::Elements(POINTS as u64));
    group.bench_function("ours", |b| {
        b.iter(|| {
            let mut acc = Vector2::zeros();
            for &u in &params {
                acc += ours.eval(black_box(u)).unwrap();
            }
            acc
        });
    });
    group.bench_function("ours_evaluator", |b| {
        b.iter(|| {
            let evaluator = ours.evaluator();
            let mut acc = Vector2::zeros();
            for &u in &params {
                acc += evaluator.eval(black_box(u)).unwrap();
            }
            acc
        });
    });
    group.bench_function("ours_batch", |b| {
        b.iter(|| ours.eval_many_into(black_box(&params), &mut out).unwrap());
    });
    group.bench_function("curvo", |b| {
        b.iter(|| {
            let mut acc = Point2::origin();
            for &u in &params {
                acc.coords += curvo.point_at(black_box(u)).coords;
            }
            acc
        });
    });
    group.bench_function("curvo_evaluator", |b| {
        b.iter(|| {
            let mut evaluator = curvo.evaluator();
            let mut acc = Point2::origin();
            for &u in &params {
                acc.coords += evaluator.point_at(black_box(u)).coords;
            }
            acc
        });
    });
    group.bench_function("truck", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &u in &params {
                acc += truck.subs(black_box(u)).x;
            }
            acc
        });
    });
    group.finish();
}
