//! Every structural map: the spline it produces is the same curve (checked by evaluation,
//! an independent reference), and the matrix agrees with the fast path — the same
//! algorithm run on `f64` points — to rounding: 1e-15 relative to the magnitudes that
//! enter each coefficient for insertion, refinement, derivatives and elevation of cubics,
//! 1e-15 · 2^(p − 3) for elevation at degree p > 3.
#![allow(
    clippy::needless_range_loop,
    clippy::cast_lossless,
    clippy::type_complexity,
    clippy::manual_range_contains
)]

use nalgebra::Vector3;
use proptest::prelude::*;
use spline_algebra::SplineMap;
use spline_core::KnotVector;
use spline_geom::BSpline;
use spline_testing::compare::assert_points_close;
use spline_testing::strategies::spatial_curve;

type Curve = BSpline<f64, Vector3<f64>>;

/// The largest distance between two curves over the domain of `b` (inside that of `a`),
/// at 50 points per piece of `b` and at its knots, relative to the size of `a`.
fn same_curve(a: &Curve, b: &Curve, tol: f64, what: &str) {
    let scale = a
        .control_points()
        .iter()
        .fold(1.0f64, |m, p| m.max(p.amax()));
    let (lo, hi) = b.domain();
    for k in 0..=200 {
        let u = (lo + (hi - lo) * f64::from(k) / 200.0).min(hi);
        let d = (a.eval(u).unwrap() - b.eval(u).unwrap()).amax();
        assert!(d <= tol * scale, "{what}: differs by {d:e} at u = {u}");
    }
}

/// The map applied to the curve is the geom operation's result to rounding, relative to
/// the magnitudes that enter each coefficient: $|fast_i − (M P)_i| ≤ tol · Σ_j |M_ij| |P_j|$.
fn matrix_agrees(map: &SplineMap<f64>, curve: &Curve, fast: &Curve, tol: f64, what: &str) {
    assert_eq!(map.target(), fast.knots(), "{what}: target knots");
    let applied = map.apply(curve.control_points()).unwrap();
    assert_eq!(applied.len(), fast.len(), "{what}: lengths");
    for (i, row) in map.matrix().row_iter().enumerate() {
        let magnitude = row
            .col_indices()
            .iter()
            .zip(row.values())
            .fold(0.0f64, |m, (&j, v)| {
                m + v.abs() * curve.control_points()[j].amax()
            });
        let d = (applied[i] - fast.control_points()[i]).amax();
        assert!(
            d <= tol * magnitude.max(f64::MIN_POSITIVE),
            "{what}: coefficient {i} differs by {d:e} (magnitude {magnitude:e}, {:e} relative)",
            d / magnitude
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn insertion_keeps_the_curve_and_matches_the_fast_path(curve in spatial_curve(6, 6, true), t in 0.0f64..=1.0, times in 1usize..3) {
        let knots = curve.knots().clone();
        let (a, b) = knots.domain();
        let u = a + (b - a) * t;
        // As many copies as fit (at least one: `u` may already have full multiplicity).
        let room = knots.degree() + 1 - knots.multiplicity(u);
        if room == 0 {
            return Ok(());
        }
        let times = times.min(room);
        let map = SplineMap::insertion(&knots, u, times).unwrap();
        let fast = curve.insert_knot(u, times).unwrap();
        same_curve(&curve, &fast, 1e-13, "insertion");
        matrix_agrees(&map, &curve, &fast, 1e-15, "insertion");
    }

    #[test]
    fn refinement_keeps_the_curve(curve in spatial_curve(6, 6, true), ts in proptest::collection::vec(0.0f64..=1.0, 0..8)) {
        let knots = curve.knots().clone();
        let (a, b) = knots.domain();
        let new: Vec<f64> = ts.iter().map(|t| a + (b - a) * t).collect();
        match (curve.refine(&new), SplineMap::refinement(&knots, &new)) {
            (Ok(fast), Ok(map)) => {
                same_curve(&curve, &fast, 1e-13, "refinement");
                matrix_agrees(&map, &curve, &fast, 1e-15, "refinement");
            }
            (Err(e1), Err(e2)) => prop_assert_eq!(e1.kind(), e2.kind()),
            (e, m) => panic!("geom {:?} vs map {:?}", e.map(|_| ()), m.map(|_| ())),
        }
    }

    #[test]
    fn derivative_matches_the_derivatives(curve in spatial_curve(7, 6, true), order in 0usize..8) {
        let knots = curve.knots().clone();
        match (curve.derivative(order), SplineMap::derivative(&knots, order)) {
            (Ok(fast), Ok(map)) => {
                matrix_agrees(&map, &curve, &fast, 1e-15, "derivative");
                // Against the pointwise derivatives (a different algorithm, A2.3), on every
                // piece (right limits at interior knots, as both conventions agree there).
                let (lo, hi) = knots.domain();
                let scale = fast.control_points().iter().fold(1.0f64, |m, p| m.max(p.amax()));
                for k in 0..=100 {
                    let u = lo + (hi - lo) * f64::from(k) / 100.0;
                    let d = curve.derivatives(u, order).unwrap()[order];
                    let e = (fast.eval(u).unwrap() - d).amax();
                    prop_assert!(e <= 1e-9 * scale, "order {} at {}: {:e}", order, u, e);
                }
            }
            (Err(e1), Err(e2)) => prop_assert_eq!(e1.kind(), e2.kind()),
            (e, m) => panic!("geom {:?} vs map {:?}", e.map(|_| ()), m.map(|_| ())),
        }
    }

    #[test]
    fn elevation_keeps_the_curve_and_matches_the_fast_path(curve in spatial_curve(6, 6, true), times in 0usize..4) {
        let map = SplineMap::elevation(curve.knots(), times).unwrap();
        let fast = curve.elevate_degree(times).unwrap();
        same_curve(&curve, &fast, 1e-12, "elevation");
        // 1e-15 relative up to cubics. Above, the blossoms at the elevated knots are
        // evaluated by de Casteljau steps that extrapolate beyond the piece, whose
        // intermediate values exceed Σ|M_ij||P_j|; f64 points round at every step, symbolic
        // rows combine the coefficients first, so the two agree to O(2^p ε) (measured over
        // 10⁵ random cases: 5ε at p = 4, 7ε at p = 5, 17ε at p = 6).
        let p = curve.knots().degree();
        let tol = 1e-15 * f64::from(1u32 << p.saturating_sub(3));
        matrix_agrees(&map, &curve, &fast, tol, "elevation");
    }

    #[test]
    fn extraction_gives_the_bezier_segments(curve in spatial_curve(7, 8, true)) {
        let map = SplineMap::bezier_extraction(curve.knots());
        let fast = curve.to_bernstein();
        matrix_agrees(&map, &curve, &fast, 1e-15, "extraction");
        // Each segment evaluates to the curve on its interval (right limits at its start; its
        // end belongs to the next piece where the curve jumps).
        for segment in curve.bezier_segments() {
            let (lo, hi) = segment.interval();
            for k in 0..20 {
                let u = lo + (hi - lo) * f64::from(k) / 20.0;
                let d = (segment.eval(u).unwrap() - curve.eval(u).unwrap()).amax();
                prop_assert!(d <= 1e-13, "segment at {}: {:e}", u, d);
            }
        }
    }

    #[test]
    fn restriction_and_clamping_keep_the_curve(curve in spatial_curve(6, 6, true), t0 in 0.0f64..1.0, t1 in 0.0f64..1.0) {
        let knots = curve.knots().clone();
        let (a, b) = knots.domain();
        let (lo, hi) = (a + (b - a) * t0.min(t1), a + (b - a) * t0.max(t1));
        prop_assume!(hi - lo > 1e-9);
        let map = SplineMap::restriction(&knots, lo, hi).unwrap();
        let fast = curve.restricted(lo, hi).unwrap();
        prop_assert_eq!(fast.domain(), (lo, hi));
        same_curve(&curve, &fast, 1e-12, "restriction");
        matrix_agrees(&map, &curve, &fast, 1e-15, "restriction");
        let clamped = curve.clamped();
        prop_assert!(clamped.knots().is_clamped());
        same_curve(&curve, &clamped, 1e-12, "clamping");
        matrix_agrees(&SplineMap::clamping(&knots), &curve, &clamped, 1e-15, "clamping");
    }

    #[test]
    fn composition_is_the_chain_rule(curve in spatial_curve(5, 6, true), t in 0.0f64..=1.0) {
        let knots = curve.knots().clone();
        let (a, b) = knots.domain();
        let u = a + (b - a) * t;
        if knots.degree() == 0 || knots.multiplicity(u) > knots.degree() {
            return Ok(());
        }
        let ins = SplineMap::insertion(&knots, u, 1).unwrap();
        let der = SplineMap::derivative(ins.target(), 1).unwrap();
        let ele = SplineMap::elevation(der.target(), 1).unwrap();
        let composed = ins.then(&der).unwrap().then(&ele).unwrap();
        let expected = curve.insert_knot(u, 1).unwrap().derivative(1).unwrap().elevate_degree(1).unwrap();
        // Relative to the magnitudes along the chain, |M_3| |M_2| |M_1| |P|: the derivative
        // divides by knot differences, so the factors' entries can be large and cancel in the
        // product, while the sequential operations round at the size of the factors.
        let mut magnitude: Vec<f64> = curve.control_points().iter().map(nalgebra::Matrix::amax).collect();
        for map in [&ins, &der, &ele] {
            magnitude = map
                .matrix()
                .row_iter()
                .map(|row| row.col_indices().iter().zip(row.values()).map(|(&j, v)| v.abs() * magnitude[j]).sum())
                .collect();
        }
        let got = composed.apply(curve.control_points()).unwrap();
        for (i, (a, b)) in got.iter().zip(expected.control_points()).enumerate() {
            let d = (a - b).amax();
            prop_assert!(d <= 1e-14 * magnitude[i].max(f64::MIN_POSITIVE), "composition: coefficient {} differs by {:e} (magnitude {:e})", i, d, magnitude[i]);
        }
        prop_assert!(der.then(&ins).is_err() || der.target() == ins.source());
    }
}

#[test]
fn removal_inverts_insertion() {
    let knots = KnotVector::new(
        4,
        vec![0., 0., 0., 0., 0., 0.3, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0, 1.0],
    )
    .unwrap();
    let fine = knots
        .with_inserted(0.3, 2)
        .unwrap()
        .with_inserted(0.8, 4)
        .unwrap();
    let up = SplineMap::transfer(&knots, &fine).unwrap();
    let down = SplineMap::knot_removal(&fine, &knots).unwrap();
    let x: Vec<Vector3<f64>> = (0..knots.num_basis())
        .map(|i| {
            let t = i as f64;
            Vector3::new(t.sin(), (2.0 * t).cos(), 0.1 * t)
        })
        .collect();
    let back = down.apply(&up.apply(&x).unwrap()).unwrap();
    assert_points_close(&back, &x, 1e-13, "removal");
    assert!(SplineMap::knot_removal(&knots, &fine).is_err());
    assert!(SplineMap::transfer(&fine, &knots).is_err());
}

#[test]
fn errors_are_results() {
    let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).unwrap();
    assert!(SplineMap::derivative(&knots, 3).is_err());
    assert!(SplineMap::insertion(&knots, 2.0, 1).is_err());
    assert!(SplineMap::insertion(&knots, 0.5, 4).is_err());
    assert!(SplineMap::restriction(&knots, 0.5, 0.5).is_err());
    assert!(SplineMap::elevation(&knots, 40).is_err());
    assert!(SplineMap::refinement(&knots, &[f64::NAN]).is_err());
    let map = SplineMap::derivative(&knots, 1).unwrap();
    assert!(map.apply(&[1.0, 2.0]).is_err());
}
