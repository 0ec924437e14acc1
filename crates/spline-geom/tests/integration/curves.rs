//! Curve algorithms checked against independent facts: invariance of the curve under every
//! structural operation, finite differences and dual numbers for derivatives, closed forms
//! from the seeds, and error cases.

#![allow(clippy::needless_range_loop)]

use nalgebra::Vector3;
use num_dual::Dual64;
use proptest::prelude::*;
use spline_core::ErrorKind;
use spline_geom::{BSpline, sign_changes};
use spline_testing::strategies::{knot_vector, spatial_curve as curve_strategy};

/// Parameters covering the domain, including every knot in it.
fn samples(curve: &BSpline<f64, Vector3<f64>>) -> Vec<f64> {
    let (a, b) = curve.domain();
    let mut us: Vec<f64> = (0..=60)
        .map(|i| a + (b - a) * f64::from(i) / 60.0)
        .collect();
    us.extend(
        curve
            .knots()
            .knots()
            .iter()
            .copied()
            .filter(|&k| k >= a && k <= b),
    );
    us
}

fn assert_same_shape(
    a: &BSpline<f64, Vector3<f64>>,
    b: &BSpline<f64, Vector3<f64>>,
    us: &[f64],
) -> Result<(), TestCaseError> {
    for &u in us {
        let (pa, pb) = (a.eval(u).unwrap(), b.eval(u).unwrap());
        prop_assert!((pa - pb).norm() < 1e-11, "u = {}: {:?} vs {:?}", u, pa, pb);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn insertion_keeps_the_curve(curve in curve_strategy(6, 8, false), t in 0.0f64..=1.0, times in 1usize..4) {
        let (a, b) = curve.domain();
        let u = a + (b - a) * t;
        let room = curve.degree() + 1 - curve.knots().multiplicity(u);
        match curve.insert_knot(u, times) {
            Ok(c) => {
                prop_assert!(times <= room);
                prop_assert_eq!(c.knots().multiplicity(u), curve.knots().multiplicity(u) + times);
                assert_same_shape(&curve, &c, &samples(&curve))?;
            }
            Err(e) => {
                prop_assert!(times > room);
                prop_assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
            }
        }
    }

    #[test]
    fn refinement_keeps_the_curve_and_matches_repeated_insertion(curve in curve_strategy(5, 6, false), ts in proptest::collection::vec(0.0f64..1.0, 1..8)) {
        let (a, b) = curve.domain();
        let us: Vec<f64> = ts.iter().map(|t| a + (b - a) * ((t * 64.0).round() / 64.0)).collect();
        let too_many = us.iter().any(|&u| curve.knots().multiplicity(u) + us.iter().filter(|&&x| x == u).count() > curve.degree() + 1);
        match curve.refine(&us) {
            Ok(refined) => {
                assert_same_shape(&curve, &refined, &samples(&curve))?;
                let mut one_by_one = curve.clone();
                for &u in &us {
                    one_by_one = one_by_one.insert_knot(u, 1).unwrap();
                }
                prop_assert_eq!(refined.knots(), one_by_one.knots());
                for (p, q) in refined.control_points().iter().zip(one_by_one.control_points()) {
                    prop_assert!((p - q).norm() < 1e-12);
                }
            }
            Err(e) => {
                prop_assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
                prop_assert!(too_many);
            }
        }
        prop_assert!(curve.refine(&us).is_ok() != too_many);
    }

    #[test]
    fn elevation_keeps_the_curve_and_raises_every_multiplicity(curve in curve_strategy(5, 6, true), times in 1usize..4) {
        let e = curve.elevate_degree(times).unwrap();
        prop_assert_eq!(e.degree(), curve.degree() + times);
        if curve.knots().is_clamped() {
            for ((k, m), (k2, m2)) in curve.knots().breakpoints().iter().zip(e.knots().breakpoints()) {
                prop_assert_eq!(*k, k2);
                prop_assert_eq!(m + times, m2);
            }
        }
        assert_same_shape(&curve, &e, &samples(&curve))?;
    }

    #[test]
    fn split_and_bezier_decomposition_keep_the_curve(curve in curve_strategy(5, 6, true), t in 0.01f64..0.99) {
        let (a, b) = curve.domain();
        let u = a + (b - a) * t;
        let (left, right) = curve.split(u).unwrap();
        prop_assert_eq!(left.domain(), (a, u));
        prop_assert_eq!(right.domain(), (u, b));
        prop_assert_eq!(left.knots().multiplicity(u), curve.degree() + 1);
        for &s in &samples(&curve) {
            let part = if s <= u { &left } else { &right };
            prop_assert!((part.eval(s).unwrap() - curve.eval(s).unwrap()).norm() < 1e-11);
        }
        let segments = curve.bezier_segments();
        let nonempty = curve.knots().knots().windows(2).filter(|w| w[0] < w[1] && w[0] >= a && w[1] <= b).count();
        prop_assert_eq!(segments.len(), nonempty);
        for seg in &segments {
            prop_assert_eq!(seg.degree(), curve.degree());
            let (s0, s1) = seg.interval();
            for i in 0..=10 {
                let s = if i == 10 { s1 } else { s0 + (s1 - s0) * f64::from(i) / 10.0 };
                // Segments are closed on both ends: at an interior right end, the left limit.
                let expected = if i == 10 && s1 < b { left_limit(&curve, s) } else { curve.eval(s).unwrap() };
                prop_assert!((seg.eval(s).unwrap() - expected).norm() < 1e-11);
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences_and_the_derivative_curve(curve in curve_strategy(6, 6, false), t in 0.0f64..=1.0) {
        let (a, b) = curve.domain();
        let u = a + (b - a) * t;
        let p = curve.degree();
        let ders = curve.derivatives(u, p + 2).unwrap();
        prop_assert!(ders[p + 1].norm() == 0.0 && ders[p + 2].norm() == 0.0);
        for k in 1..=p {
            let d = curve.derivative(k).unwrap();
            prop_assert_eq!(d.degree(), p - k);
            let scale = 1.0 + ders[k].norm();
            prop_assert!((d.eval(u).unwrap() - ders[k]).norm() <= 1e-9 * scale, "k={}", k);
        }
        // Central differences inside the span.
        let span = curve.knots().find_span(u).unwrap();
        let (lo, hi) = (curve.knots().knots()[span], curve.knots().knots()[span + 1]);
        let h = 1e-5 * (hi - lo);
        if p >= 1 && u - h > lo && u + h < hi {
            let fd = (curve.eval(u + h).unwrap() - curve.eval(u - h).unwrap()) / (2.0 * h);
            prop_assert!((fd - ders[1]).norm() <= 1e-5 * (1.0 + ders[1].norm()) * (1.0 + (1.0 / (hi - lo)).powi(2)));
        }
    }

    #[test]
    fn dual_numbers_give_exact_parameter_derivatives(curve in curve_strategy(6, 6, false), t in 0.0f64..=1.0) {
        let (a, b) = curve.domain();
        let u = a + (b - a) * t;
        let dual: BSpline<Dual64, Vector3<Dual64>> = BSpline::from_knots(
            curve.degree(),
            curve.knots().knots().iter().map(|&k| Dual64::from(k)).collect(),
            curve.control_points().iter().map(|p| p.map(Dual64::from)).collect(),
        ).unwrap();
        let value = dual.eval(Dual64::from(u).derivative()).unwrap();
        let ders = curve.derivatives(u, 1).unwrap();
        for c in 0..3 {
            prop_assert!((value[c].re - ders[0][c]).abs() < 1e-12);
            prop_assert!((value[c].eps - ders[1][c]).abs() <= 1e-9 * (1.0 + ders[1][c].abs()));
        }
    }

    #[test]
    fn dual_numbers_give_the_derivative_with_respect_to_a_control_point(curve in curve_strategy(6, 6, false), t in 0.0f64..=1.0, which in any::<prop::sample::Index>()) {
        let (a, b) = curve.domain();
        let u = a + (b - a) * t;
        let i = which.index(curve.control_points().len());
        // Seed the x coordinate of control point i: dC_x/dx_i = N_i(u), dC_y/dx_i = 0.
        let points: Vec<Vector3<Dual64>> = curve.control_points().iter().enumerate().map(|(j, p)| {
            let mut q = p.map(Dual64::from);
            if j == i { q[0] = q[0].derivative(); }
            q
        }).collect();
        let dual = BSpline::from_knots(curve.degree(), curve.knots().knots().iter().map(|&k| Dual64::from(k)).collect(), points).unwrap();
        let value = dual.eval(Dual64::from(u)).unwrap();
        let basis = curve.knots().basis_function(i, u).unwrap();
        prop_assert!((value[0].eps - basis).abs() < 1e-14);
        prop_assert!(value[1].eps == 0.0 && value[2].eps == 0.0);
    }

    #[test]
    fn de_boor_basis_form_and_batches_agree(curve in curve_strategy(7, 8, true), ts in proptest::collection::vec(0.0f64..=1.0, 1..40)) {
        let (a, b) = curve.domain();
        let mut us: Vec<f64> = ts.iter().map(|t| a + (b - a) * t).collect();
        let unsorted = curve.eval_many(&us).unwrap();
        us.sort_by(f64::total_cmp);
        let sorted = curve.eval_many(&us).unwrap();
        for (&u, p) in us.iter().zip(&sorted) {
            prop_assert!((curve.eval(u).unwrap() - p).norm() < 1e-13);
            prop_assert!((curve.de_boor(u).unwrap() - p).norm() < 1e-12);
        }
        prop_assert_eq!(unsorted.len(), sorted.len());
        let mut many = vec![Vector3::zeros(); us.len() * 3];
        curve.derivatives_many_into(&us, 2, &mut many).unwrap();
        for (i, &u) in us.iter().enumerate() {
            let d = curve.derivatives(u, 2).unwrap();
            prop_assert_eq!(&many[3 * i..3 * i + 3], &d[..]);
        }
    }

    #[test]
    fn removal_undoes_insertion(curve in curve_strategy(5, 6, false), t in 0.05f64..0.95, times in 1usize..3) {
        let (a, b) = curve.domain();
        let u = a + (b - a) * ((t * 128.0).round() / 128.0);
        prop_assume!(curve.knots().multiplicity(u) + times <= curve.degree());
        let inserted = curve.insert_knot(u, times).unwrap();
        let back = inserted.remove_knot(u, times, 1e-9).unwrap();
        prop_assert_eq!(back.knots(), curve.knots());
        for (p, q) in back.control_points().iter().zip(curve.control_points()) {
            prop_assert!((p - q).norm() < 1e-9);
        }
    }

    #[test]
    fn f32_and_f64_agree(curve in curve_strategy(5, 6, false), t in 0.0f64..=1.0) {
        let single: BSpline<f32, Vector3<f32>> = BSpline::from_knots(
            curve.degree(),
            curve.knots().knots().iter().map(|&k| k as f32).collect(),
            curve.control_points().iter().map(|p| p.map(|x| x as f32)).collect(),
        ).unwrap();
        let (a, b) = single.domain();
        let u = a + (b - a) * t as f32;
        let p32 = single.eval(u).unwrap();
        let p64 = curve.eval(f64::from(u)).unwrap();
        prop_assert!((p32.map(f64::from) - p64).norm() < 1e-4);
        // Elevation (clamping, Bézier elevation, then A5.9's knot removal) loses a few more
        // digits than evaluation next to short spans and repeated knots.
        let e32 = single.elevate_degree(1).unwrap().eval(u).unwrap();
        prop_assert!((e32.map(f64::from) - p64).norm() < 1e-3);
    }

    #[test]
    fn variation_diminishing(knots in knot_vector(5, 8, 1.0, false), coefficients in proptest::collection::vec(-1.0f64..1.0, 14)) {
        let f = BSpline::new(knots.clone(), coefficients[..knots.num_basis()].to_vec()).unwrap();
        let (a, b) = f.domain();
        let values: Vec<f64> = (0..=2000).map(|i| f.eval(a + (b - a) * f64::from(i) / 2000.0).unwrap()).collect();
        prop_assert!(sign_changes(&values) <= f.coefficient_sign_changes());
    }

    #[test]
    fn scaled_knots_keep_algorithms_exact(curve in curve_strategy(4, 5, false), exponent in prop::sample::select(vec![-6i32, 6]), t in 0.1f64..0.9) {
        let s = 10f64.powi(exponent);
        let scaled = BSpline::from_knots(curve.degree(), curve.knots().knots().iter().map(|k| k * s).collect(), curve.control_points().to_vec()).unwrap();
        let (a, b) = curve.domain();
        let u = a + (b - a) * t;
        let p = curve.eval(u).unwrap();
        prop_assert!((scaled.eval(u * s).unwrap() - p).norm() < 1e-12);
        prop_assert!((scaled.insert_knot(u * s, 1).unwrap().eval(u * s).unwrap() - p).norm() < 1e-12);
        prop_assert!((scaled.elevate_degree(1).unwrap().eval(u * s).unwrap() - p).norm() < 1e-11);
        let d = curve.derivatives(u, 1).unwrap()[1];
        prop_assert!((scaled.derivatives(u * s, 1).unwrap()[1] * s - d).norm() <= 1e-9 * (1.0 + d.norm()));
    }
}

/// The left limit of a curve at `u` (from the segment to the left).
fn left_limit(curve: &BSpline<f64, Vector3<f64>>, u: f64) -> Vector3<f64> {
    let (a, _) = curve.domain();
    let (left, _) = curve
        .split(u)
        .unwrap_or_else(|_| panic!("split at {u} (domain start {a})"));
    left.eval(u).unwrap()
}
