//! Periodic B-splines and the curve tools (boxes, tessellation, arc length, join), checked
//! against closed forms, dense sampling and the open container.

use nalgebra::Vector2;
use proptest::prelude::*;
use spline_core::ErrorKind;
use spline_geom::{
    BSpline, NurbsCurve, ParamCurve, PeriodicBSpline, hull_box, param_at_length, pieces_box,
    tessellate,
};
use spline_testing::strategies::linspace;
use spline_testing::strategies::{planar_curve, points};

/// A periodic curve of degree `p` with `n` control points on random (sorted) knots.
fn periodic(max_p: usize) -> impl Strategy<Value = PeriodicBSpline<f64, Vector2<f64>>> {
    (1..=max_p, 0usize..6)
        .prop_flat_map(|(p, extra)| {
            let n = p + 1 + extra;
            (
                Just(p),
                proptest::collection::vec(0.05f64..1.0, n),
                0.01f64..0.5,
                points::<2>(n),
            )
        })
        .prop_map(|(p, steps, start, control)| {
            let mut knots = Vec::with_capacity(steps.len());
            let mut u = start;
            for s in &steps[..steps.len()] {
                knots.push(u);
                u += s;
            }
            let period = u - start;
            PeriodicBSpline::new(p, knots, period, control).expect("valid by construction")
        })
}

#[test]
fn uniform_cubic_at_knots_is_the_one_four_one_average() {
    // Closed form: a uniform periodic cubic at knot t_i is (c_i + 4 c_{i+1} + c_{i+2})/6
    // with this indexing (basis i supported on [t_{i−p}, t_{i+1}], as scipy's).
    let c: Vec<Vector2<f64>> = (0..7)
        .map(|i| Vector2::new(f64::from(i).cos() * 2.0, (f64::from(i) * 1.7).sin()))
        .collect();
    let knots: Vec<f64> = (0..7).map(f64::from).collect();
    let curve = PeriodicBSpline::new(3, knots, 7.0, c.clone()).unwrap();
    for i in 0..7 {
        let expected = (c[i] + c[(i + 1) % 7] * 4.0 + c[(i + 2) % 7]) / 6.0;
        let got = curve.eval(i as f64).unwrap();
        assert!(
            (got - expected).norm() < 1e-14,
            "knot {i}: {got:?} vs {expected:?}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn periodic_in_value_and_derivatives(curve in periodic(5), t in 0.0f64..1.0, shift in -3i32..3) {
        let (a, b) = curve.domain();
        let u = a + (b - a) * t;
        let far = u + f64::from(shift) * curve.period();
        let p = curve.degree();
        let (d0, d1) = (curve.derivatives(u, p).unwrap(), curve.derivatives(far, p).unwrap());
        for k in 0..p {
            let scale = 1.0 + d0[k].norm();
            prop_assert!((d0[k] - d1[k]).norm() < 1e-9 * scale, "order {}", k);
        }
        // C^{p−1} across the closing point: left limits at b equal right limits at a.
        let left = curve.wrapped().derivatives(b, p - 1).unwrap();
        let right = curve.wrapped().derivatives(a, p - 1).unwrap();
        for k in 0..p {
            prop_assert!((left[k] - right[k]).norm() < 1e-8 * (1.0 + left[k].norm()), "order {}", k);
        }
    }

    #[test]
    fn insertion_keeps_the_curve_and_periodicity(curve in periodic(4), t in 0.0f64..1.0, times in 1usize..3) {
        let (a, b) = curve.domain();
        let u = a + (b - a) * t;
        match curve.insert_knot(u, times) {
            Ok(refined) => {
                prop_assert_eq!(refined.len(), curve.len() + times);
                prop_assert_eq!(refined.domain(), curve.domain());
                for v in linspace(a - 0.3, b + 0.3, 97) {
                    let d = (refined.eval(v).unwrap() - curve.eval(v).unwrap()).norm();
                    prop_assert!(d < 1e-12, "v = {}: {:e}", v, d);
                }
            }
            Err(e) => {
                prop_assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
                prop_assert!(times > curve.degree());
            }
        }
    }

    #[test]
    fn opening_gives_the_same_points(curve in periodic(4), t in 0.0f64..1.0) {
        let (a, b) = curve.domain();
        let u = a + (b - a) * t;
        let open = curve.open_at(u).unwrap();
        prop_assert!(open.knots().is_clamped());
        let (c, d) = open.domain();
        prop_assert!((c - u).abs() < 1e-15 && (d - (u + curve.period())).abs() < 1e-12);
        for v in linspace(c, d, 61) {
            let e = (open.eval(v).unwrap() - curve.eval(v).unwrap()).norm();
            prop_assert!(e < 1e-12, "v = {}: {:e}", v, e);
        }
    }

    #[test]
    fn derivative_and_reversal(curve in periodic(4), t in 0.0f64..1.0) {
        let (a, b) = curve.domain();
        let u = a + (b - a) * t;
        let d = curve.derivative().unwrap();
        let expected = curve.derivatives(u, 1).unwrap()[1];
        prop_assert!((d.eval(u).unwrap() - expected).norm() < 1e-9 * (1.0 + expected.norm()));
        let r = curve.reversed();
        prop_assert!((r.eval(a + b - u).unwrap() - curve.eval(u).unwrap()).norm() < 1e-12);
        let back = PeriodicBSpline::from_wrapped(curve.wrapped()).unwrap();
        prop_assert_eq!(back.control_points(), curve.control_points());
    }

    #[test]
    fn tessellation_meets_the_chord_tolerance(curve in planar_curve(1, 5, false), k in 0usize..4) {
        let tol = [0.1, 0.01, 1e-3, 1e-4][k];
        let params = tessellate(&curve, tol).unwrap();
        prop_assert!(params.windows(2).all(|w| w[0] < w[1]));
        for w in params.windows(2) {
            let (pa, pb) = (curve.eval(w[0]).unwrap(), curve.eval(w[1]).unwrap());
            for v in linspace(w[0], w[1], 16) {
                let q = curve.eval(v).unwrap();
                let d = pb - pa;
                let s = if d.norm_squared() > 0.0 { ((q - pa).dot(&d) / d.norm_squared()).clamp(0.0, 1.0) } else { 0.0 };
                let dist = (q - (pa + d * s)).norm();
                prop_assert!(dist <= tol * (1.0 + 1e-9), "{:e} > {:e}", dist, tol);
            }
        }
        for brk in curve.breaks() {
            prop_assert!(params.contains(&brk));
        }
    }

    #[test]
    fn boxes_contain_the_curve(curve in planar_curve(1, 5, false)) {
        let (hull, tight) = (hull_box(&curve), pieces_box(&curve));
        for c in 0..2 {
            prop_assert!(hull.min[c] <= tight.min[c] && tight.max[c] <= hull.max[c]);
        }
        let (a, b) = curve.domain();
        for u in linspace(a, b, 200) {
            let q = curve.eval(u).unwrap();
            for c in 0..2 {
                prop_assert!(tight.min[c] <= q[c] + 1e-15 && q[c] <= tight.max[c] + 1e-15);
            }
        }
    }

    #[test]
    fn join_follows_both_curves(first in planar_curve(1, 4, false), second in planar_curve(1, 4, false)) {
        let end = first.eval(first.domain().1).unwrap();
        let moved = second.map_control_points(|q| q - second.eval(second.domain().0).unwrap() + end);
        let joined = first.join(&moved.clamped(), 1e-12).unwrap();
        let (a, b) = first.domain();
        let (c, d) = moved.domain();
        for u in linspace(a, b, 40) {
            prop_assert!((joined.eval(u).unwrap() - first.eval(u).unwrap()).norm() < 1e-11);
        }
        for v in linspace(c, d, 40) {
            let e = (joined.eval(b + (v - c)).unwrap() - moved.eval(v).unwrap()).norm();
            prop_assert!(e < 1e-11, "{:e}", e);
        }
    }
}

#[test]
fn arc_length_parameter_on_the_circle() {
    // A quarter of the unit circle: the point at arc length s is (cos s, sin s).
    let quarter = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(1.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(0.0, 1.0),
        ],
        vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
    )
    .unwrap();
    for s in [0.0, 0.1, 0.5, 1.0, 1.5, std::f64::consts::FRAC_PI_2] {
        let u = param_at_length(&quarter, s, 1e-13).unwrap();
        let q = quarter.eval(u).unwrap();
        assert!(
            (q - Vector2::new(s.cos(), s.sin())).norm() < 1e-12,
            "s = {s}"
        );
    }
    let e = param_at_length(&quarter, 2.0, 1e-10).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::OutOfDomain);
    let e = param_at_length(&quarter, 1.0, 0.0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidTolerance);
}

#[test]
fn bad_periodic_input_is_an_error() {
    let q = vec![Vector2::new(0.0, 0.0); 4];
    let e = PeriodicBSpline::new(3, vec![0.0, 1.0, 2.0], 4.0, q.clone()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    let e = PeriodicBSpline::new(4, vec![0.0, 1.0, 2.0, 3.0], 4.0, q.clone()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::TooFewPoints);
    let e = PeriodicBSpline::new(3, vec![0.0, 1.0, 2.0, 3.0], 3.0, q.clone()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::EmptyDomain);
    let e = PeriodicBSpline::new(2, vec![0.0, 1.0, 1.0, 1.0], 4.0, q.clone()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
    let e = PeriodicBSpline::new(2, vec![0.0, f64::NAN, 2.0, 3.0], 4.0, q.clone()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    let e = PeriodicBSpline::new(2, vec![0.0, 2.0, 1.0, 3.0], 4.0, q).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
    let open = BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 2.0, 2.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, 1.0),
        ],
    )
    .unwrap();
    let e = PeriodicBSpline::from_wrapped(&open).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(e.message(), "knots 0 and 2 do not differ by the period 2");
    assert_eq!(e.index(), Some(2));
    // The derivative of a polygon is a step function, whose own derivative is not a
    // periodic B-spline.
    let polygon = PeriodicBSpline::new(1, vec![0.0, 1.0, 2.0], 3.0, vec![1.0, 2.0, 0.0]).unwrap();
    let steps = polygon.derivative().unwrap();
    let e = steps.derivative().unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Unsupported);
    let curve = PeriodicBSpline::new(
        2,
        vec![0.0, 1.0, 2.0],
        3.0,
        vec![
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(-1.0, 0.0),
        ],
    )
    .unwrap();
    assert_eq!(
        curve.eval(f64::INFINITY).unwrap_err().kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(
        curve.insert_knot(1.0, 2).unwrap_err().kind(),
        ErrorKind::KnotMultiplicity
    );
    assert_eq!(
        tessellate(&curve, -1.0).unwrap_err().kind(),
        ErrorKind::InvalidTolerance
    );
    let far = open.map_control_points(|q| q + Vector2::new(5.0, 0.0));
    assert_eq!(
        open.join(&far, 1e-9).unwrap_err().kind(),
        ErrorKind::ToleranceExceeded
    );
}
