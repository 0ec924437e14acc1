//! Curve intersections against dense sampling plus Newton's method (none missed, none
//! invented) on random pairs, constructed tangencies, closed forms (circles and lines) and
//! self-intersections.

use nalgebra::Vector2;
use proptest::prelude::*;
use spline_algebra::{
    CurveIntersection, intersect_curves, intersect_curves_relative, self_intersections,
    self_intersections_relative,
};
use spline_core::ErrorKind;
use spline_geom::{BSpline, NurbsCurve, ParamCurve, PlanarCurve};
use spline_testing::strategies::{planar_curve, two_planar_curves};

type Curve = BSpline<f64, Vector2<f64>>;

fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// About `n` parameters: equal steps in every piece (short pieces too), every break.
fn samples<C: ParamCurve<f64>>(c: &C, n: usize) -> Vec<f64> {
    let spans = c.breaks().len() - 1;
    c.sample_params(n.div_ceil(spans).max(16))
}

/// Newton's method on A(u) = B(v) from (u, v) (the test's own, plain).
fn newton<A: PlanarCurve<f64>, B: PlanarCurve<f64>>(
    a: &A,
    b: &B,
    mut u: f64,
    mut v: f64,
) -> Option<(f64, f64)> {
    let (a0, a1) = a.domain();
    let (b0, b1) = b.domain();
    for _ in 0..50 {
        let da = a.derivatives(u, 1).ok()?;
        let db = b.derivatives(v, 1).ok()?;
        let f = da[0] - db[0];
        let det = cross(da[1], -db[1]);
        if det.abs() < 1e-300 {
            return None;
        }
        let du = cross(-f, -db[1]) / det;
        let dv = cross(da[1], -f) / det;
        u = (u + du).clamp(a0, a1);
        v = (v + dv).clamp(b0, b1);
        if du.abs() < 1e-15 && dv.abs() < 1e-15 {
            break;
        }
    }
    let d = (a.eval(u).ok()? - b.eval(v).ok()?).norm();
    (d < 1e-11).then_some((u, v))
}

/// The crossings of the two sampled polylines, refined by Newton's method: the reference.
fn sampled_crossings<A: PlanarCurve<f64>, B: PlanarCurve<f64>>(
    a: &A,
    b: &B,
    n: usize,
    same: bool,
) -> Vec<(f64, f64)> {
    crossings(a, b, &samples(a, n), &samples(b, n), same)
}

/// Parameters in a window of 2e-3 (of the domain) around `t`: 200 steps in every piece
/// that meets it (short pieces too).
fn window<C: ParamCurve<f64>>(c: &C, t: f64) -> Vec<f64> {
    let (a, b) = c.domain();
    let (lo, hi) = ((t - 1e-3 * (b - a)).max(a), (t + 1e-3 * (b - a)).min(b));
    let mut out = Vec::new();
    for w in c.breaks().windows(2) {
        let (x, y) = (w[0].max(lo), w[1].min(hi));
        if x < y {
            out.extend((0..200).map(|k| x + (y - x) * f64::from(k) / 200.0));
        }
    }
    out.push(hi);
    out
}

/// The crossings of the polylines through the points at `ua` and `va`, refined by
/// Newton's method.
fn crossings<A: PlanarCurve<f64>, B: PlanarCurve<f64>>(
    a: &A,
    b: &B,
    ua: &[f64],
    va: &[f64],
    same: bool,
) -> Vec<(f64, f64)> {
    let (pa, pb) = (a.eval_many(ua).unwrap(), b.eval_many(va).unwrap());
    let mut out: Vec<(f64, f64)> = Vec::new();
    for i in 0..ua.len() - 1 {
        let (p0, p1) = (pa[i], pa[i + 1]);
        let (lo, hi) = (p0.inf(&p1), p0.sup(&p1));
        for j in 0..va.len() - 1 {
            if same && j <= i + 1 {
                continue;
            }
            let (q0, q1) = (pb[j], pb[j + 1]);
            if q0.x.max(q1.x) < lo.x
                || q0.x.min(q1.x) > hi.x
                || q0.y.max(q1.y) < lo.y
                || q0.y.min(q1.y) > hi.y
            {
                continue;
            }
            let d1 = cross(p1 - p0, q0 - p0);
            let d2 = cross(p1 - p0, q1 - p0);
            let d3 = cross(q1 - q0, p0 - q0);
            let d4 = cross(q1 - q0, p1 - q0);
            if d1 * d2 <= 0.0 && d3 * d4 <= 0.0 && (d1 != d2) && (d3 != d4) {
                let s = d3 / (d3 - d4);
                let t = d1 / (d1 - d2);
                let u = ua[i] + (ua[i + 1] - ua[i]) * s;
                let v = va[j] + (va[j + 1] - va[j]) * t;
                if let Some((u, v)) = newton(a, b, u, v) {
                    let (u, v) = if same && u > v { (v, u) } else { (u, v) };
                    if !out
                        .iter()
                        .any(|&(x, y)| (x - u).abs() < 1e-9 && (y - v).abs() < 1e-9)
                    {
                        out.push((u, v));
                    }
                }
            }
        }
    }
    out
}

fn sine<A: PlanarCurve<f64>, B: PlanarCurve<f64>>(a: &A, b: &B, u: f64, v: f64) -> f64 {
    let (ta, tb) = (
        a.derivatives(u, 1).unwrap()[1],
        b.derivatives(v, 1).unwrap()[1],
    );
    cross(ta, tb).abs() / (ta.norm() * tb.norm())
}

/// Checks `found` against the sampled reference: every reported point is an intersection
/// to 1e-12; every sampled crossing is reported; every reported crossing at an angle is
/// sampled.
fn check<A: PlanarCurve<f64>, B: PlanarCurve<f64>>(
    a: &A,
    b: &B,
    found: &[CurveIntersection<f64>],
    reference: &[(f64, f64)],
    min_loop: f64,
) -> Result<(), TestCaseError> {
    for hit in found {
        // 1e-12, or the resolution of the parameters where the curves are fast (a tiny
        // piece between nearly coincident knots): one rounding of u and v moves the points
        // by |A'| eps |u| and |B'| eps |v|.
        let (ta, tb) = (
            a.derivatives(hit.u, 1).unwrap()[1],
            b.derivatives(hit.v, 1).unwrap()[1],
        );
        let resolution = 4.0 * f64::EPSILON * (hit.u.abs() * ta.norm() + hit.v.abs() * tb.norm());
        let d = (a.eval(hit.u).unwrap() - b.eval(hit.v).unwrap()).norm();
        prop_assert!((d - hit.gap).abs() < 1e-15, "{:?}: gap {:e}", hit, d);
        if hit.tangential {
            // A contact: the curves come within the tolerance of each other, with parallel
            // tangents, and the gap is smallest there.
            prop_assert!(d <= 1e-9, "{:?}", hit);
            let nearby = [(1e-7, 0.0), (-1e-7, 0.0), (0.0, 1e-7), (0.0, -1e-7)]
                .iter()
                .all(|&(du, dv)| {
                    let (u, v) = (hit.u + du, hit.v + dv);
                    let inside = a.domain().0 <= u
                        && u <= a.domain().1
                        && b.domain().0 <= v
                        && v <= b.domain().1;
                    !inside || (a.eval(u).unwrap() - b.eval(v).unwrap()).norm() >= d
                });
            prop_assert!(nearby, "{:?} is not the smallest gap nearby", hit);
        } else {
            prop_assert!(
                d < 1e-12 + resolution,
                "reported ({}, {}) is {:e} apart",
                hit.u,
                hit.v,
                d
            );
        }
        prop_assert!((hit.point - a.eval(hit.u).unwrap()).norm() <= 0.5 * d + 1e-15);
    }
    for (i, x) in found.iter().enumerate() {
        for y in &found[i + 1..] {
            prop_assert!(
                (x.u - y.u).abs() + (x.v - y.v).abs() > 1e-9,
                "reported twice: {:?} and {:?}",
                x,
                y
            );
        }
    }
    for &(u, v) in reference {
        prop_assert!(
            found
                .iter()
                .any(|h| (h.u - u).abs() < 1e-8 && (h.v - v).abs() < 1e-8),
            "missed the sampled crossing ({}, {}); found {:?}",
            u,
            v,
            found
        );
    }
    // Every reported point is an intersection (above); those at a clear angle, away from
    // other intersections and from the breaks (where a sampled polyline has a corner, and
    // nearly coincident knots make pieces too short and fast for the sampling: the reference
    // can miss a crossing within 1e-4 of them), are in the sampled reference too.
    let near_break = |c: &[f64], t: f64| c.iter().any(|k| (k - t).abs() < 1e-4);
    let (breaks_a, breaks_b) = (a.breaks(), b.breaks());
    // Near a point where a curve almost stops (a near-cusp: the speed below a hundredth of
    // the mean), arcs of tiny size cross there and no polyline resolves them.
    let fast = |c: &dyn Fn(f64) -> f64, mean: f64, t: f64| c(t) >= 1e-2 * mean;
    let speed_a = |t: f64| a.derivatives(t, 1).unwrap()[1].norm();
    let speed_b = |t: f64| b.derivatives(t, 1).unwrap()[1].norm();
    let mean = |speed: &dyn Fn(f64) -> f64, (lo, hi): (f64, f64)| {
        (0..=200)
            .map(|k| speed(lo + (hi - lo) * f64::from(k) / 200.0))
            .sum::<f64>()
            / 201.0
    };
    let (mean_a, mean_b) = (mean(&speed_a, a.domain()), mean(&speed_b, b.domain()));
    let fast_a = |t: f64| fast(&speed_a, mean_a, t);
    let fast_b = |t: f64| fast(&speed_b, mean_b, t);
    for hit in found {
        let isolated = found
            .iter()
            .all(|h| h == hit || (h.u - hit.u).abs() + (h.v - hit.v).abs() > 1e-3);
        let clear = !near_break(&breaks_a, hit.u)
            && !near_break(&breaks_b, hit.v)
            && (hit.v - hit.u).abs() > min_loop;
        if !hit.tangential
            && isolated
            && clear
            && fast_a(hit.u)
            && fast_b(hit.v)
            && sine(a, b, hit.u, hit.v) > 1e-2
        {
            // Not in the reference: the polylines sampled densely near the point must cross
            // there (the whole-curve sampling can be too coarse for the geometry there).
            let seen = |r: &[(f64, f64)]| {
                r.iter()
                    .any(|&(u, v)| (hit.u - u).abs() < 1e-8 && (hit.v - v).abs() < 1e-8)
            };
            prop_assert!(
                seen(reference)
                    || seen(&crossings(
                        a,
                        b,
                        &window(a, hit.u),
                        &window(b, hit.v),
                        false
                    )),
                "invented ({}, {}) (not in the sampled reference {:?})",
                hit.u,
                hit.v,
                reference
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_pairs_agree_with_dense_sampling((a, b) in two_planar_curves(4, 4)) {
        let found = intersect_curves(&a, &b, 1e-9).unwrap().points;
        let reference = sampled_crossings(&a, &b, 1500, false);
        check(&a, &b, &found, &reference, 0.0)?;
    }

    #[test]
    fn constructed_tangencies_are_found_and_flagged(
        a in planar_curve(3, 3, true),
        t0 in 0.1f64..0.9,
        angle in 0.0f64..std::f64::consts::TAU,
        size in 0.05f64..0.5,
    ) {
        // B = A + (t − t0)² n: B touches A at t0 from one side (B − A vanishes to second
        // order there, nowhere else at equal parameters).
        let n = Vector2::new(angle.cos(), angle.sin()) * size;
        let k = a.knots().knots();
        let control: Vec<Vector2<f64>> = a.control_points().iter().enumerate().map(|(i, p)| {
            // Blossom of (t − t0)² in cubic form at (t_{i+1}, t_{i+2}, t_{i+3}).
            let (x, y, z) = (k[i + 1] - t0, k[i + 2] - t0, k[i + 3] - t0);
            p + n * ((x * y + x * z + y * z) / 3.0)
        }).collect();
        let b = BSpline::new(a.knots().clone(), control).unwrap();
        prop_assert!(((b.eval(0.37).unwrap() - a.eval(0.37).unwrap()) - n * (0.37 - t0).powi(2)).norm() < 1e-12);
        let found = intersect_curves(&a, &b, 1e-9).unwrap().points;
        let touch = found.iter().find(|h| (h.u - t0).abs() < 1e-6 && (h.v - t0).abs() < 1e-6);
        prop_assert!(touch.is_some(), "tangency at {} not found: {:?}", t0, found);
        let touch = touch.unwrap();
        prop_assert!(touch.tangential, "not flagged: {:?}", touch);
        // Near the contact the gap is about (t − t0)² |n × T̂| (T̂ the unit tangent), which
        // rounds to zero within √(eps / |n × T̂|) of t0: the point of contact is defined to
        // that precision only.
        let tangent = a.derivatives(t0, 1).unwrap()[1].normalize();
        let across = cross(n, tangent).abs();
        let resolution = 4.0 * (4.0 * f64::EPSILON / across).sqrt();
        prop_assert!((touch.u - t0).abs() < resolution && (touch.v - t0).abs() < resolution, "{:?} (resolution {:e})", touch, resolution);
        // Elsewhere, the sampled crossings.
        let reference: Vec<(f64, f64)> = sampled_crossings(&a, &b, 1500, false)
            .into_iter()
            .filter(|&(u, v)| (u - t0).abs() > 1e-3 || (v - t0).abs() > 1e-3)
            .collect();
        check(&a, &b, &found, &reference, 0.0)?;
    }

    #[test]
    fn self_intersections_agree_with_dense_sampling(c in planar_curve(2, 4, false)) {
        let found = self_intersections(&c, 1e-9).unwrap().points;
        for hit in &found {
            prop_assert!(hit.u < hit.v);
        }
        let reference = sampled_crossings(&c, &c, 1500, true);
        // A loop shorter than a few samples is invisible to the sampled reference.
        check(&c, &c, &found, &reference, 5e-3)?;
    }
}

fn line(p: Vector2<f64>, q: Vector2<f64>) -> Curve {
    BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0], vec![p, q]).unwrap()
}

fn unit_circle() -> NurbsCurve<f64, 2> {
    let s = 0.5f64.sqrt();
    let points = vec![
        Vector2::new(1.0, 0.0),
        Vector2::new(1.0, 1.0),
        Vector2::new(0.0, 1.0),
        Vector2::new(-1.0, 1.0),
        Vector2::new(-1.0, 0.0),
        Vector2::new(-1.0, -1.0),
        Vector2::new(0.0, -1.0),
        Vector2::new(1.0, -1.0),
        Vector2::new(1.0, 0.0),
    ];
    let weights = vec![1.0, s, 1.0, s, 1.0, s, 1.0, s, 1.0];
    let knots = vec![
        0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
    ];
    NurbsCurve::from_knots(2, knots, points, weights).unwrap()
}

#[test]
fn circle_and_lines_closed_forms() {
    let circle = unit_circle();
    // A secant y = 1/2: x = ±√3/2.
    let hits = intersect_curves(
        &circle,
        &line(Vector2::new(-2.0, 0.5), Vector2::new(2.0, 0.5)),
        1e-9,
    )
    .unwrap()
    .points;
    assert_eq!(hits.len(), 2, "{hits:?}");
    let mut xs: Vec<f64> = hits.iter().map(|h| h.point.x).collect();
    xs.sort_by(f64::total_cmp);
    assert!(
        (xs[0] + 0.75f64.sqrt()).abs() < 1e-14 && (xs[1] - 0.75f64.sqrt()).abs() < 1e-14,
        "{xs:?}"
    );
    assert!(
        hits.iter()
            .all(|h| !h.tangential && (h.point.y - 0.5).abs() < 1e-14)
    );
    // The tangent y = 1 touches at (0, 1).
    let hits = intersect_curves(
        &circle,
        &line(Vector2::new(-2.0, 1.0), Vector2::new(2.0, 1.0)),
        1e-9,
    )
    .unwrap()
    .points;
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert!(
        hits[0].tangential && (hits[0].point - Vector2::new(0.0, 1.0)).norm() < 1e-12,
        "{hits:?}"
    );
    // A line that misses.
    assert!(
        intersect_curves(
            &circle,
            &line(Vector2::new(-2.0, 1.01), Vector2::new(2.0, 1.2)),
            1e-9
        )
        .unwrap()
        .points
        .is_empty()
    );
    // Two unit circles with centres 1 apart: (1/2, ±√3/2).
    let shifted = NurbsCurve::from_knots(
        2,
        circle.knots().knots().to_vec(),
        circle
            .control_points()
            .iter()
            .map(|p| p + Vector2::new(1.0, 0.0))
            .collect(),
        circle.weights().to_vec(),
    )
    .unwrap();
    let hits = intersect_curves(&circle, &shifted, 1e-9).unwrap().points;
    assert_eq!(hits.len(), 2, "{hits:?}");
    for h in &hits {
        assert!(
            (h.point.x - 0.5).abs() < 1e-14 && (h.point.y.abs() - 0.75f64.sqrt()).abs() < 1e-14
        );
    }
    // Two circles touching from outside at (1, 0).
    let touching = NurbsCurve::from_knots(
        2,
        circle.knots().knots().to_vec(),
        circle
            .control_points()
            .iter()
            .map(|p| p + Vector2::new(2.0, 0.0))
            .collect(),
        circle.weights().to_vec(),
    )
    .unwrap();
    let hits = intersect_curves(&circle, &touching, 1e-9).unwrap().points;
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert!(hits[0].tangential && (hits[0].point - Vector2::new(1.0, 0.0)).norm() < 1e-12);
    // A closed curve has no self-intersection at its seam.
    assert!(self_intersections(&circle, 1e-9).unwrap().points.is_empty());
}

#[test]
fn the_nodal_cubic_crosses_itself_at_the_origin() {
    // (t² − 1, t³ − t) on [−3/2, 3/2]: a cubic (reproduced exactly by interpolation at four
    // parameters) whose loop closes at the origin, t = ∓1, with tangents (∓2, 2).
    let f = |t: f64| Vector2::new(t * t - 1.0, t * t * t - t);
    let params = [-1.5, -0.5, 0.5, 1.5];
    let points: Vec<Vector2<f64>> = params.iter().map(|&t| f(t)).collect();
    let knots = spline_core::KnotVector::bezier(3, -1.5, 1.5).unwrap();
    let curve = spline_fit_free_interpolation(&knots, &params, &points);
    assert!((curve.eval(0.3).unwrap() - f(0.3)).norm() < 1e-14);
    let hits = self_intersections(&curve, 1e-9).unwrap().points;
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert!(
        (hits[0].u + 1.0).abs() < 1e-14 && (hits[0].v - 1.0).abs() < 1e-14,
        "{hits:?}"
    );
    assert!(hits[0].point.norm() < 1e-14 && !hits[0].tangential);
}

/// Interpolation without spline-fit (not a dependency here): the collocation system
/// solved densely.
fn spline_fit_free_interpolation(
    knots: &spline_core::KnotVector<f64>,
    params: &[f64],
    points: &[Vector2<f64>],
) -> Curve {
    let n = knots.num_basis();
    let mut m = nalgebra::DMatrix::zeros(n, n);
    for (r, &u) in params.iter().enumerate() {
        let basis = knots.eval_basis(u).unwrap();
        let first = basis.first();
        for (k, &v) in basis.values().iter().enumerate() {
            m[(r, first + k)] = v;
        }
    }
    let lu = m.lu();
    let xs = lu
        .solve(&nalgebra::DVector::from_iterator(
            n,
            points.iter().map(|p| p.x),
        ))
        .unwrap();
    let ys = lu
        .solve(&nalgebra::DVector::from_iterator(
            n,
            points.iter().map(|p| p.y),
        ))
        .unwrap();
    BSpline::new(
        knots.clone(),
        (0..n).map(|i| Vector2::new(xs[i], ys[i])).collect(),
    )
    .unwrap()
}

#[test]
fn bad_tolerances_are_errors_and_a_curve_overlaps_itself() {
    let a = line(Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0));
    let b = line(Vector2::new(0.0, 1.0), Vector2::new(1.0, 0.0));
    for tol in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(
            intersect_curves(&a, &b, tol).unwrap_err().kind(),
            ErrorKind::InvalidTolerance
        );
        assert_eq!(
            self_intersections(&a, tol).unwrap_err().kind(),
            ErrorKind::InvalidTolerance
        );
    }
    let hits = intersect_curves(&a, &b, 1e-9).unwrap().points;
    assert_eq!(hits.len(), 1);
    assert!((hits[0].point - Vector2::new(0.5, 0.5)).norm() < 1e-15);
    // A curve against itself: one overlap, the whole curve (issue 25: was an error).
    let cubic = BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 2.0),
            Vector2::new(2.0, -1.0),
            Vector2::new(3.0, 0.5),
        ],
    )
    .unwrap();
    let same = intersect_curves(&cubic, &cubic, 1e-9).unwrap();
    assert!(same.points.is_empty(), "{same:?}");
    assert_eq!(same.overlaps.len(), 1, "{same:?}");
    assert_eq!(
        (same.overlaps[0].u, same.overlaps[0].v),
        ((0.0, 1.0), (0.0, 1.0))
    );
    assert!(!same.overlaps[0].reversed);
}

/// Curves with a cusp or a turn back (reproducers `loop.json`, `backforth2.json`): the
/// monotone splitting used to split rounding noise near the cusp until memory ran out. Now
/// the work is bounded by the geometry; every reported point lies on the curve at both
/// parameters.
#[test]
fn cusps_and_turns_back_end_quickly() {
    let cubic = |p: [[f64; 2]; 4]| {
        BSpline::from_knots(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            p.iter().map(|q| Vector2::new(q[0], q[1])).collect(),
        )
        .unwrap()
    };
    // x = 6t(1 − t), y = 6t(1 − t)² + 2t³: a cusp at t = 1/2, the point (1.5, 1).
    let cusp = cubic([[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]]);
    // Out along the x-axis and back over the same points.
    let back = BSpline::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, 0.0),
        ],
    )
    .unwrap();
    // All control points equal.
    let point = cubic([[1.0, 2.0]; 4]);
    let started = std::time::Instant::now();
    let at_cusp = self_intersections(&cusp, 1e-9).unwrap().points;
    // The cusp once (it was reported 7 times).
    assert_eq!(at_cusp.len(), 1, "{at_cusp:?}");
    for hit in &at_cusp {
        assert!(
            (hit.point - Vector2::new(1.5, 1.0)).norm() < 1e-6,
            "{hit:?}"
        );
    }
    // The turn back: one overlap, [0, 1/2] against [1, 1/2] (C(u) = C(1 − u)), no points.
    let turns = self_intersections(&back, 1e-9).unwrap();
    assert!(turns.points.is_empty(), "{turns:?}");
    assert_eq!(turns.overlaps.len(), 1, "{turns:?}");
    let o: spline_algebra::CurveOverlap<f64> = turns.overlaps[0];
    assert!(o.reversed && o.u.0 == 0.0 && o.v.0 == 1.0, "{o:?}");
    // At the fold both sides stay within the tolerance over about √tolerance.
    assert!(
        (o.u.1 - 0.5).abs() < 1e-4 && (o.v.1 - 0.5).abs() < 1e-4,
        "{o:?}"
    );
    // A single point: a clear error.
    assert_eq!(
        self_intersections(&point, 1e-9).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
    assert!(started.elapsed().as_secs_f64() < 1.0);
}

/// Issue 25: a tolerance relative to the curves' size gives the scaled answer of the
/// unscaled problem at every scale (an absolute 1e-9 lost the crossings of a pair scaled by
/// 1e20 and found false ones at 1e-20). A cubic crossing a wavy quadratic three times.
#[test]
fn relative_tolerances_give_the_same_crossings_at_every_scale() {
    let make = |s: f64| {
        let a = BSpline::from_knots(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            vec![
                Vector2::new(0.0, 0.0) * s,
                Vector2::new(1.0, 2.0) * s,
                Vector2::new(2.0, -2.0) * s,
                Vector2::new(3.0, 0.5) * s,
            ],
        )
        .unwrap();
        let b = BSpline::from_knots(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![Vector2::new(-0.5, 0.1) * s, Vector2::new(3.5, 0.2) * s],
        )
        .unwrap();
        (a, b)
    };
    let (a, b) = make(1.0);
    let unit = intersect_curves_relative(&a, &b, 1e-9).unwrap().points;
    assert_eq!(unit.len(), 3);
    for s in [1e-60, 1e-20, 1e20, 1e60] {
        let (a, b) = make(s);
        let hits = intersect_curves_relative(&a, &b, 1e-9).unwrap().points;
        assert_eq!(hits.len(), 3, "scale {s}");
        for (h, g) in hits.iter().zip(&unit) {
            assert!(
                (h.u - g.u).abs() < 1e-12 && (h.v - g.v).abs() < 1e-12,
                "scale {s}"
            );
            assert!(((h.point / s) - g.point).norm() < 1e-12, "scale {s}");
        }
    }
    // A self-intersecting loop likewise.
    let looped = |s: f64| {
        BSpline::from_knots(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            vec![
                Vector2::new(0.0, 0.0) * s,
                Vector2::new(2.0, 2.0) * s,
                Vector2::new(-1.0, 2.0) * s,
                Vector2::new(1.0, 0.0) * s,
            ],
        )
        .unwrap()
    };
    let unit = self_intersections_relative(&looped(1.0), 1e-9)
        .unwrap()
        .points;
    assert_eq!(unit.len(), 1);
    for s in [1e-60, 1e-20, 1e20, 1e60] {
        let hits = self_intersections_relative(&looped(s), 1e-9)
            .unwrap()
            .points;
        assert_eq!(hits.len(), 1, "scale {s}");
        assert!((hits[0].u - unit[0].u).abs() < 1e-12, "scale {s}");
    }
}
