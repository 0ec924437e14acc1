//! Overlaps as parameter intervals (issue 25, item 1) and subdivision bounded by the
//! geometry (item 2): the reproducers, partial overlaps, crossings beside an overlap, and an
//! independent check of every interval (points inside on both curves, points just outside
//! not).

use nalgebra::Vector2;
use spline_algebra::{
    CurveIntersections, intersect_curves, intersect_curves_relative, self_intersections_relative,
};
use spline_core::KnotVector;
use spline_geom::BSpline;

use std::time::Instant;

type Curve = BSpline<f64, Vector2<f64>>;

fn reproducer(name: &str) -> Curve {
    let path = format!(
        "{}/tests/data/reproducers/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let degree = v["degree"].as_u64().unwrap() as usize;
    let knots: Vec<f64> = v["knots"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let points = v["control_points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| Vector2::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect();
    BSpline::new(KnotVector::new(degree, knots).unwrap(), points).unwrap()
}

/// Brute-force distance from a point to a curve: dense samples, then golden-section
/// refinement around the best (the test's own, no Newton of the library).
fn distance_to(c: &Curve, p: Vector2<f64>) -> f64 {
    let (a, b) = c.domain();
    let n = 4000u32;
    let at = |u: f64| (c.eval(u).unwrap() - p).norm();
    let mut best = (a, at(a));
    for k in 1..=n {
        let u = a + (b - a) * f64::from(k) / f64::from(n);
        let d = at(u);
        if d < best.1 {
            best = (u, d);
        }
    }
    let h = (b - a) / f64::from(n);
    let (mut lo, mut hi) = ((best.0 - h).max(a), (best.0 + h).min(b));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..100 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if at(x1) < at(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    best.1.min(at(0.5 * (lo + hi)))
}

/// Every overlap: points sampled inside are on both curves within the tolerance, at the
/// matching parameters; points just outside (a thousandth of the curve's domain) are not on
/// both unless the overlap ends at the end of a domain.
fn check_intervals(a: &Curve, b: &Curve, found: &CurveIntersections<f64>, tolerance: f64) {
    for o in &found.overlaps {
        assert!(o.u.0 < o.u.1, "{o:?}");
        assert_eq!(o.reversed, o.v.1 < o.v.0, "{o:?}");
        for k in 0..=50 {
            let u = o.u.0 + (o.u.1 - o.u.0) * f64::from(k) / 50.0;
            let d = distance_to(b, a.eval(u).unwrap());
            assert!(d <= tolerance * 1.01, "inside at {u}: {d} in {o:?}");
        }
        assert!((a.eval(o.u.0).unwrap() - b.eval(o.v.0).unwrap()).norm() <= tolerance * 1.01);
        assert!((a.eval(o.u.1).unwrap() - b.eval(o.v.1).unwrap()).norm() <= tolerance * 1.01);
        let (da, db) = a.domain();
        let step = (db - da) * 1e-3;
        if o.u.0 - step > da {
            assert!(
                distance_to(b, a.eval(o.u.0 - step).unwrap()) > tolerance,
                "{o:?}"
            );
        }
        if o.u.1 + step < db {
            assert!(
                distance_to(b, a.eval(o.u.1 + step).unwrap()) > tolerance,
                "{o:?}"
            );
        }
    }
}

/// `spline intersect parabola.json parabola.json` gave 65,536 tangential points after
/// 8–12 s, `same_rand.json` against itself 94,756 after ~22 s: one overlap each, at once.
#[test]
fn a_curve_against_itself_is_one_overlap() {
    for name in ["parabola.json", "same_rand.json"] {
        let c = reproducer(name);
        let started = Instant::now();
        let found = intersect_curves_relative(&c, &c, 1e-9).unwrap();
        let seconds = started.elapsed().as_secs_f64();
        assert!(seconds < 1.0, "{name}: {seconds} s");
        assert!(found.points.is_empty(), "{name}: {found:?}");
        assert_eq!(found.overlaps.len(), 1, "{name}: {found:?}");
        let o: spline_algebra::CurveOverlap<f64> = found.overlaps[0];
        assert_eq!(
            (o.u, o.v, o.reversed),
            ((0.0, 1.0), (0.0, 1.0), false),
            "{name}"
        );
        check_intervals(&c, &c, &found, 1e-9 * 2.0);
    }
}

/// A piece of a curve against the whole curve, also reversed: the piece's interval.
#[test]
fn a_piece_against_the_whole_curve() {
    let c = reproducer("same_rand.json");
    let piece: Curve = c.split(0.3).unwrap().1.split(0.7).unwrap().0;
    // The same piece run backwards: w ↦ piece(1 − w) on the same domain [0.3, 0.7].
    let knots = piece.knots().knots();
    let reversed: Curve = BSpline::new(
        KnotVector::new(
            piece.degree(),
            knots.iter().rev().map(|k| 1.0 - k).collect(),
        )
        .unwrap(),
        piece.control_points().iter().rev().copied().collect(),
    )
    .unwrap();
    for (b, flipped) in [(&piece, false), (&reversed, true)] {
        let found = intersect_curves(&c, b, 1e-9).unwrap();
        assert_eq!(found.overlaps.len(), 1, "{found:?}");
        let o: spline_algebra::CurveOverlap<f64> = found.overlaps[0];
        assert!(
            (o.u.0 - 0.3).abs() < 1e-6 && (o.u.1 - 0.7).abs() < 1e-6,
            "{o:?}"
        );
        assert_eq!(o.reversed, flipped);
        let (v0, v1) = if flipped { (0.7, 0.3) } else { (0.3, 0.7) };
        assert!(
            (o.v.0 - v0).abs() < 1e-6 && (o.v.1 - v1).abs() < 1e-6,
            "{o:?}"
        );
        check_intervals(&c, b, &found, 1e-9);
        // The piece's own crossings with the rest of the curve are points.
        for p in &found.points {
            assert!(
                (c.eval(p.u).unwrap() - b.eval(p.v).unwrap()).norm() < 1e-12,
                "{p:?}"
            );
        }
    }
}

/// Two curves sharing a middle segment and crossing elsewhere: the overlap and the
/// crossings. A: the x-axis from 0 to 4 (a cubic with collinear control points); B: a
/// quadratic B-spline that runs along the axis over [1, 3] and comes back across it.
#[test]
fn a_shared_segment_and_crossings_elsewhere() {
    let a = BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector2::new(0.0, 0.0), Vector2::new(4.0, 0.0)],
    )
    .unwrap();
    // A polyline: down to (1, 0), along the axis to (3, 0), below it to (3.5, −1) and back
    // across it to (0.25, 1).
    let b = BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0],
        vec![
            Vector2::new(0.5, 1.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(3.0, 0.0),
            Vector2::new(3.5, -1.0),
            Vector2::new(0.25, 1.0),
        ],
    )
    .unwrap();
    let found = intersect_curves(&a, &b, 1e-9).unwrap();
    assert_eq!(found.overlaps.len(), 1, "{found:?}");
    let o: spline_algebra::CurveOverlap<f64> = found.overlaps[0];
    assert!(
        (o.u.0 - 0.25).abs() < 1e-9 && (o.u.1 - 0.75).abs() < 1e-9,
        "{o:?}"
    );
    assert!(
        (o.v.0 - 1.0).abs() < 1e-9 && (o.v.1 - 2.0).abs() < 1e-9,
        "{o:?}"
    );
    // The last leg crosses the axis once, at y = 0 between (3.5, −1) and (0.25, 1).
    let x = 3.5 - 3.25 * 0.5;
    assert_eq!(found.points.len(), 1, "{found:?}");
    assert!(
        (found.points[0].point - Vector2::new(x, 0.0)).norm() < 1e-12,
        "{found:?}"
    );
    check_intervals(&a, &b, &found, 1e-9);
}

/// `spline intersect loop.json` (a cusp) and `backforth2.json` (out and back) allocated
/// until the memory limit: now the cusp once, the turn back as one overlap, quickly.
#[test]
fn cusp_and_turn_back_reproducers() {
    let started = Instant::now();
    let cusp = reproducer("loop.json");
    let found = self_intersections_relative(&cusp, 1e-9).unwrap();
    assert!(found.overlaps.is_empty(), "{found:?}");
    assert!(found.points.len() <= 1, "{found:?}");
    for p in &found.points {
        assert!((p.point - Vector2::new(1.5, 1.0)).norm() < 1e-6, "{p:?}");
    }
    let back = reproducer("backforth2.json");
    let found = self_intersections_relative(&back, 1e-9).unwrap();
    assert!(found.points.is_empty(), "{found:?}");
    assert_eq!(found.overlaps.len(), 1, "{found:?}");
    let o: spline_algebra::CurveOverlap<f64> = found.overlaps[0];
    assert!(o.reversed && o.u.0 == 0.0 && o.v.0 == 1.0, "{o:?}");
    assert!(
        (o.u.1 - 0.5).abs() < 1e-4 && (o.v.1 - 0.5).abs() < 1e-4,
        "{o:?}"
    );
    assert!(started.elapsed().as_secs_f64() < 1.0);
}
