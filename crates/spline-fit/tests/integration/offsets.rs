//! Offsets and degree reduction within their tolerances, checked by dense sampling against
//! closed forms (the offsets of the parabola, with their cusps) and against the curves.

use nalgebra::Vector2;
use proptest::prelude::*;
use spline_core::ErrorKind;
use spline_fit::{offset_curve, reduce_degree};
use spline_geom::{BSpline, ParamCurve};
use spline_testing::strategies::linspace;
use spline_testing::strategies::planar_curve;

/// (u, u²) on [−1, 1].
fn parabola() -> BSpline<f64, Vector2<f64>> {
    BSpline::from_knots(
        2,
        vec![-1.0, -1.0, -1.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(-1.0, 1.0),
            Vector2::new(0.0, -1.0),
            Vector2::new(1.0, 1.0),
        ],
    )
    .unwrap()
}

/// The offset of (u, u²) by d along the left normal (−2u, 1)/√(1 + 4u²), in closed form.
fn parabola_offset(u: f64, d: f64) -> Vector2<f64> {
    let s = (1.0 + 4.0 * u * u).sqrt();
    Vector2::new(u - 2.0 * u * d / s, u * u + d / s)
}

#[test]
fn parabola_offsets_with_and_without_cusps() {
    let c = parabola();
    // κ = 2 / (1 + 4u²)^{3/2}: for d = 1 the cusps are at κ = 1.
    let x = ((2f64.powf(2.0 / 3.0) - 1.0) / 4.0).sqrt();
    for (d, cusps) in [(-0.3, vec![]), (0.3, vec![]), (1.0, vec![-x, x])] {
        for tol in [1e-3, 1e-7] {
            let fit = offset_curve(&c, d, 3, tol, &cusps).unwrap();
            let worst = linspace(-1.0, 1.0, 20_000)
                .into_iter()
                .map(|u| (fit.curve.eval(u).unwrap() - parabola_offset(u, d)).norm())
                .fold(0.0, f64::max);
            assert!(worst <= tol, "d = {d}, tol = {tol}: {worst:e}");
            for &k in &cusps {
                assert_eq!(
                    fit.curve.knots().multiplicity(k),
                    3,
                    "a corner at the cusp {k}"
                );
                // The offset stops there: its two one-sided tangents are opposite.
                let l = parabola_offset(k, d) - parabola_offset(k - 1e-4, d);
                let r = parabola_offset(k + 1e-4, d) - parabola_offset(k, d);
                assert!(l.dot(&r) < 0.0);
            }
        }
    }
    // Without its cusps the kinked offset needs far more pieces: a small budget fails.
    let e = spline_fit::AdaptiveApproximation::new(3, 1e-7)
        .max_pieces(50)
        .fit((-1.0, 1.0), |u| Ok(parabola_offset(u, 1.0)))
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::ToleranceExceeded);
}

#[test]
fn offsets_reject_corners_and_stops() {
    let polyline = BSpline::from_knots(
        1,
        vec![0.0, 0.0, 0.5, 1.0, 1.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(1.0, 1.0),
        ],
    )
    .unwrap();
    let e = offset_curve(&polyline, 0.1, 3, 1e-6, &[]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert!(e.message().contains("corner at u = 0.5"), "{}", e.message());
    // A curve that stops at its start: (t², t³)-like cusp.
    let stop = BSpline::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 1.0),
        ],
    )
    .unwrap();
    assert!(offset_curve(&stop, 0.1, 3, 1e-6, &[]).is_err());
    assert_eq!(
        offset_curve(&parabola(), f64::NAN, 3, 1e-6, &[])
            .unwrap_err()
            .kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(
        offset_curve(&parabola(), 0.1, 3, 0.0, &[])
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidTolerance
    );
    assert_eq!(
        offset_curve(&parabola(), 1.0, 3, 1e-6, &[5.0])
            .unwrap_err()
            .kind(),
        ErrorKind::OutOfDomain
    );
}

#[test]
fn reduction_of_elevated_curves_is_exact_and_bad_input_is_an_error() {
    let c = parabola();
    let cubic = c.elevate_degree(1).unwrap();
    let fit = reduce_degree(&cubic, 2, 1e-12, false).unwrap();
    assert_eq!(fit.curve.degree(), 2);
    for u in linspace(-1.0, 1.0, 1000) {
        assert!((fit.curve.eval(u).unwrap() - c.eval(u).unwrap()).norm() < 1e-12);
    }
    assert_eq!(
        reduce_degree(&cubic, 2, -1.0, false).unwrap_err().kind(),
        ErrorKind::InvalidTolerance
    );
    assert_eq!(
        reduce_degree(&cubic, 99, 1e-3, false).unwrap_err().kind(),
        ErrorKind::DegreeTooHigh
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn random_offsets_within_the_tolerance(c in planar_curve(2, 4, true), side in prop::bool::ANY) {
        // A distance below the smallest radius of curvature (no cusps), away from stops.
        let (a, b) = c.domain();
        let us = linspace(a, b, 2000);
        let speeds: Vec<f64> = us.iter().map(|&u| c.speed(u).unwrap()).collect();
        let mean = speeds.iter().sum::<f64>() / speeds.len() as f64;
        prop_assume!(speeds.iter().all(|&s| s > 1e-2 * mean));
        let kmax = us.iter().map(|&u| c.signed_curvature(u).unwrap().abs()).fold(0.0, f64::max);
        let d = if side { 0.5 } else { -0.5 } / kmax.max(1.0);
        let tol = 1e-5;
        let fit = offset_curve(&c, d, 3, tol, &[]);
        let breaks = c.breaks();
        let corner = breaks[1..breaks.len() - 1].iter().find(|&&k| {
            let (l, r) = (c.unit_tangent(k - 1e-7).unwrap(), c.unit_tangent(k + 1e-7).unwrap());
            (l - r).norm() > 1e-3
        });
        if let Some(k) = corner {
            // A C⁰ knot where the tangent turns: the offset tears there.
            let e = fit.unwrap_err();
            prop_assert!(e.message().contains(&format!("corner at u = {k}")), "{}", e.message());
            return Ok(());
        }
        let fit = fit.unwrap();
        for u in linspace(a, b, 5000) {
            // The offset from the test's own formula: C + d (−y', x') / |C'|.
            let dd = c.derivatives(u, 1).unwrap();
            let exact = dd[0] + Vector2::new(-dd[1].y, dd[1].x) * (d / dd[1].norm());
            let e = (fit.curve.eval(u).unwrap() - exact).norm();
            prop_assert!(e <= tol, "u = {}: {:e}", u, e);
        }
    }

    #[test]
    fn random_reductions_within_the_tolerance(c in planar_curve(3, 4, true)) {
        let tol = 1e-4;
        let q = c.degree() - 1;
        let fit = reduce_degree(&c, q, tol, true).unwrap();
        prop_assert_eq!(fit.curve.degree(), q);
        let (a, b) = c.domain();
        for u in linspace(a, b, 5000) {
            let e = (fit.curve.eval(u).unwrap() - c.eval(u).unwrap()).norm();
            prop_assert!(e <= tol, "u = {}: {:e}", u, e);
        }
        // On the curve's own knots: either within the tolerance, or an error that gives
        // the best deviation, which really is above the tolerance.
        match reduce_degree(&c, q, tol, false) {
            Ok(fit) => prop_assert!(fit.max_error <= tol && fit.curve.breaks() == c.breaks()),
            Err(e) => {
                prop_assert_eq!(e.kind(), ErrorKind::ToleranceExceeded);
                prop_assert!(e.message().contains("best deviation"), "{}", e.message());
            }
        }
    }
}
