//! Curve intersections against dense sampling plus Newton's method (none missed, none
//! invented) on random pairs, constructed tangencies and self-intersections (the closed forms,
//! constructed examples and error cases are in `intersections_examples`).

use nalgebra::Vector2;
use proptest::prelude::*;
use spline_algebra::{CurveIntersection, intersect_curves, self_intersections};
use spline_geom::{BSpline, ParamCurve, PlanarCurve};
use spline_testing::strategies::{planar_curve, two_planar_curves};

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
        // Near the contact the gap is about (t − t0)² |n × T̂(t)| (T̂ the unit tangent), which
        // rounds to zero within √(eps / |n × T̂|) of t0: the point of contact is defined to
        // that precision only. Where n runs nearly along the tangent of a sharply bent A,
        // n × T̂(t) itself vanishes close to t0 and the gap rounds to zero on a longer arc:
        // a contact found there, where the curves cannot be told apart, is that contact.
        let tangent = a.derivatives(t0, 1).unwrap()[1].normalize();
        let across = cross(n, tangent).abs();
        let resolution = 4.0 * (4.0 * f64::EPSILON / across).sqrt();
        let normal_gap = |t: f64| {
            let tangent = a.derivatives(t, 1).unwrap()[1].normalize();
            cross(n, tangent).abs() * (t - t0).powi(2)
        };
        let touch = found.iter().find(|h| {
            let close = (h.u - t0).abs() < resolution.max(1e-6) && (h.v - t0).abs() < resolution.max(1e-6);
            let indistinct = (h.u - t0).abs() < 1e-3
                && (h.v - t0).abs() < 1e-3
                && normal_gap(h.u) <= 64.0 * f64::EPSILON;
            close || indistinct
        });
        prop_assert!(touch.is_some(), "tangency at {} not found (resolution {:e}): {:?}", t0, resolution, found);
        let touch = touch.unwrap();
        prop_assert!(touch.tangential, "not flagged: {:?}", touch);
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
