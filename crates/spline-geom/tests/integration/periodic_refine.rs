//! `PeriodicBSpline::refine`: many knots at once give the curve of one-at-a-time insertion
//! (point for point, at parameters across the closing point) and the same knots.

use nalgebra::Vector2;
use proptest::prelude::*;
use spline_core::ErrorKind;
use spline_geom::PeriodicBSpline;
use spline_testing::strategies::points;

/// A periodic curve of degree 2..=5 on random sorted knots of period 1 starting at 0.
fn periodic_curve() -> impl Strategy<Value = PeriodicBSpline<f64, Vector2<f64>>> {
    (2usize..=5, 0usize..5)
        .prop_flat_map(|(p, extra)| {
            let n = p + 1 + extra;
            (
                Just(p),
                proptest::collection::vec(0.05f64..1.0, n),
                points::<2>(n),
            )
        })
        .prop_map(|(p, steps, control)| {
            let total: f64 = steps.iter().sum();
            let mut knots = Vec::with_capacity(steps.len());
            let mut u = 0.0;
            for s in &steps {
                knots.push(u / total);
                u += s;
            }
            PeriodicBSpline::new(p, knots, 1.0, control).expect("valid by construction")
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn refine_is_insertion_one_knot_at_a_time(
        curve in periodic_curve(),
        new in proptest::collection::vec(-1.5f64..2.5, 1..6),
    ) {
        let refined = curve.refine(&new).unwrap();
        let mut one_by_one = curve.clone();
        for &u in &new {
            one_by_one = one_by_one.insert_knot(u, 1).unwrap();
        }
        prop_assert_eq!(refined.len(), curve.len() + new.len());
        prop_assert_eq!(refined.period(), 1.0);
        for (a, b) in refined.period_knots().iter().zip(one_by_one.period_knots()) {
            prop_assert!((a - b).abs() < 1e-14, "{a} vs {b}");
        }
        let size = curve.control_points().iter().fold(1.0f64, |m, c| m.max(c.amax()));
        for k in 0..=60 {
            let u = -0.2 + 1.4 * f64::from(k) / 60.0;
            let (r, o, c) = (refined.eval(u).unwrap(), one_by_one.eval(u).unwrap(), curve.eval(u).unwrap());
            prop_assert!((r - c).amax() < 1e-12 * size, "u = {u}: {r:?} vs the curve {c:?}");
            prop_assert!((r - o).amax() < 1e-12 * size, "u = {u}: {r:?} vs one by one {o:?}");
        }
    }
}

#[test]
fn refine_of_a_uniform_cubic_at_midpoints_is_the_closed_form() {
    // Midpoint subdivision of a uniform periodic cubic (Lane–Riesenfeld): the new control
    // points are (c_{i-1} + 6 c_i + c_{i+1}) / 8 (vertex points) and (c_i + c_{i+1}) / 2
    // (edge points), with the index shift of the wrapped form (basis i on [t_{i−p}, t_{i+1}]).
    let c: Vec<Vector2<f64>> = (0..5)
        .map(|i| Vector2::new(f64::from(i).cos(), (1.3 * f64::from(i)).sin()))
        .collect();
    let knots: Vec<f64> = (0..5).map(|i| f64::from(i) / 5.0).collect();
    let curve = PeriodicBSpline::new(3, knots, 1.0, c.clone()).unwrap();
    let middles: Vec<f64> = (0..5).map(|i| (f64::from(i) + 0.5) / 5.0).collect();
    let fine = curve.refine(&middles).unwrap();
    assert_eq!(fine.len(), 10);
    // Every control point of the fine curve is a vertex or an edge point of the coarse one.
    let vertex = |i: usize| (c[(i + 4) % 5] + c[i] * 6.0 + c[(i + 1) % 5]) / 8.0;
    let edge = |i: usize| (c[i] + c[(i + 1) % 5]) / 2.0;
    let mut expected: Vec<Vector2<f64>> = (0..5).flat_map(|i| [vertex(i), edge(i)]).collect();
    for got in fine.control_points() {
        let k = expected
            .iter()
            .position(|e| (e - got).norm() < 1e-14)
            .unwrap_or_else(|| panic!("{got:?} is no subdivision point"));
        expected.remove(k);
    }
    assert!(expected.is_empty());
}

#[test]
fn refine_refuses_a_discontinuous_curve_and_bad_knots() {
    let c: Vec<Vector2<f64>> = (0..4).map(|i| Vector2::new(f64::from(i), 1.0)).collect();
    let curve = PeriodicBSpline::new(3, vec![0.0, 0.25, 0.5, 0.75], 1.0, c).unwrap();
    // 0.25 twice more is multiplicity 3 = p (allowed); three more, 4 > p.
    assert_eq!(curve.refine(&[0.25, 1.25]).unwrap().len(), 6);
    let err = curve.refine(&[0.25, 1.25, -0.75]).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::KnotMultiplicity);
    // The end of the period is its start: 1.0 and 0.0 are the same knot.
    let err = curve.refine(&[1.0, 0.0, 2.0]).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::KnotMultiplicity);
    assert_eq!(
        curve.refine(&[f64::NAN]).unwrap_err().kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(curve.refine(&[]).unwrap(), curve);
}
