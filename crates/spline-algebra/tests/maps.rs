//! Every structural map reproduces what spline-geom computes, and its matrix agrees with
//! probing the geom algorithm with unit vectors.
#![allow(
    clippy::needless_range_loop,
    clippy::cast_lossless,
    clippy::type_complexity,
    clippy::manual_range_contains
)]

use nalgebra::Vector3;
use proptest::prelude::*;
use spline_algebra::{CsrMatrix, SplineMap};
use spline_core::KnotVector;
use spline_core::strategies::knot_vector;
use spline_geom::BSpline;

fn points(n: usize, seed: u64) -> Vec<Vector3<f64>> {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    (0..n)
        .map(|_| Vector3::new(next(), next(), next()))
        .collect()
}

fn assert_points_close(got: &[Vector3<f64>], expected: &[Vector3<f64>], tol: f64, what: &str) {
    assert_eq!(got.len(), expected.len(), "{what}: lengths");
    let scale = expected.iter().fold(1.0f64, |m, p| m.max(p.amax()));
    for (i, (a, b)) in got.iter().zip(expected).enumerate() {
        assert!(
            (a - b).amax() <= tol * scale,
            "{what}[{i}]: {a:?} vs {b:?} (diff {:.3e})",
            (a - b).amax()
        );
    }
}

fn check_map(
    map: &SplineMap<f64>,
    curve: &BSpline<f64, Vector3<f64>>,
    expected: &BSpline<f64, Vector3<f64>>,
    what: &str,
) {
    check_map_within(map, curve, expected, 1e-12, what);
}

fn check_map_within(
    map: &SplineMap<f64>,
    curve: &BSpline<f64, Vector3<f64>>,
    expected: &BSpline<f64, Vector3<f64>>,
    tol: f64,
    what: &str,
) {
    assert_eq!(map.target(), expected.knots(), "{what}: target knots");
    let got = map.apply_to(curve).unwrap();
    assert_points_close(got.control_points(), expected.control_points(), tol, what);
}

/// Column j of the matrix must be the geom operation applied to the unit vector e_j.
fn check_by_unit_vectors(
    matrix: &CsrMatrix<f64>,
    knots: &KnotVector<f64>,
    op: impl Fn(&BSpline<f64, f64>) -> Vec<f64>,
) {
    let n = knots.num_basis();
    let mut dense = vec![vec![0.0; n]; matrix.nrows()];
    for (i, j, v) in matrix.triplet_iter() {
        dense[i][j] = *v;
    }
    for j in 0..n {
        let mut e = vec![0.0; n];
        e[j] = 1.0;
        let col = op(&BSpline::new(knots.clone(), e).unwrap());
        assert_eq!(col.len(), matrix.nrows());
        for (i, &c) in col.iter().enumerate() {
            assert!(
                (dense[i][j] - c).abs() <= 1e-12 * c.abs().max(1.0),
                "entry ({i}, {j}): {} vs {c}",
                dense[i][j]
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn insertion_matches_geom(knots in knot_vector(6, 6, 1.0, true), t in 0.0f64..=1.0, times in 1usize..3, seed in any::<u64>()) {
        let (a, b) = knots.domain();
        let u = a + (b - a) * t;
        prop_assume!(knots.multiplicity(u) + times <= knots.degree() + 1);
        let curve = BSpline::new(knots.clone(), points(knots.num_basis(), seed)).unwrap();
        let map = SplineMap::insertion(&knots, u, times).unwrap();
        check_map(&map, &curve, &curve.insert_knot(u, times).unwrap(), "insertion");
        check_by_unit_vectors(map.matrix(), &knots, |f| f.insert_knot(u, times).unwrap().control_points().to_vec());
    }

    #[test]
    fn refinement_matches_geom(knots in knot_vector(6, 6, 1.0, true), ts in proptest::collection::vec(0.0f64..=1.0, 0..8), seed in any::<u64>()) {
        let (a, b) = knots.domain();
        let new: Vec<f64> = ts.iter().map(|t| a + (b - a) * t).collect();
        let curve = BSpline::new(knots.clone(), points(knots.num_basis(), seed)).unwrap();
        let expected = curve.refine(&new);
        let map = SplineMap::refinement(&knots, &new);
        match (expected, map) {
            (Ok(e), Ok(m)) => check_map(&m, &curve, &e, "refinement"),
            (Err(e1), Err(e2)) => prop_assert_eq!(e1.kind(), e2.kind()),
            (e, m) => panic!("geom {:?} vs map {:?}", e.map(|_| ()), m.map(|_| ())),
        }
    }

    #[test]
    fn derivative_matches_geom(knots in knot_vector(7, 6, 1.0, true), order in 0usize..8, seed in any::<u64>()) {
        let curve = BSpline::new(knots.clone(), points(knots.num_basis(), seed)).unwrap();
        match (curve.derivative(order), SplineMap::derivative(&knots, order)) {
            (Ok(e), Ok(m)) => {
                check_map(&m, &curve, &e, "derivative");
                check_by_unit_vectors(m.matrix(), &knots, |f| f.derivative(order).unwrap().control_points().to_vec());
            }
            (Err(e1), Err(e2)) => prop_assert_eq!(e1.kind(), e2.kind()),
            (e, m) => panic!("geom {:?} vs map {:?}", e.map(|_| ()), m.map(|_| ())),
        }
    }

    #[test]
    fn elevation_matches_geom(knots in knot_vector(6, 6, 1.0, true), times in 0usize..4, seed in any::<u64>()) {
        let curve = BSpline::new(knots.clone(), points(knots.num_basis(), seed)).unwrap();
        let map = SplineMap::elevation(&knots, times).unwrap();
        // A5.9 removes knots after elevating Bézier pieces: next to very short spans it loses
        // a few more digits (up to ~5e-13 here) than the blossom rows of the map.
        check_map_within(&map, &curve, &curve.elevate_degree(times).unwrap(), 1e-10, "elevation");
    }

    #[test]
    fn extraction_matches_geom(knots in knot_vector(7, 8, 1.0, true), seed in any::<u64>()) {
        let curve = BSpline::new(knots.clone(), points(knots.num_basis(), seed)).unwrap();
        let map = SplineMap::bezier_extraction(&knots);
        let got = map.apply_to(&curve).unwrap();
        let expected: Vec<Vector3<f64>> = curve
            .bezier_segments()
            .iter()
            .flat_map(|b| b.control_points().to_vec())
            .collect();
        assert_points_close(got.control_points(), &expected, 1e-12, "extraction");
        check_by_unit_vectors(map.matrix(), &knots, |f| f.bezier_segments().iter().flat_map(|b| b.control_points().to_vec()).collect());
    }

    #[test]
    fn restriction_matches_split(knots in knot_vector(6, 6, 1.0, true), t0 in 0.0f64..1.0, t1 in 0.0f64..1.0, seed in any::<u64>()) {
        let (a, b) = knots.domain();
        let (lo, hi) = (a + (b - a) * t0.min(t1), a + (b - a) * t0.max(t1));
        prop_assume!(hi - lo > 1e-9);
        let curve = BSpline::new(knots.clone(), points(knots.num_basis(), seed)).unwrap();
        let mut expected = curve.clamped();
        if lo > a { expected = expected.split(lo).unwrap().1; }
        if hi < b { expected = expected.split(hi).unwrap().0; }
        let map = SplineMap::restriction(&knots, lo, hi).unwrap();
        check_map(&map, &curve, &expected, "restriction");
        check_map(&SplineMap::clamping(&knots), &curve, &curve.clamped(), "clamping");
    }

    #[test]
    fn composition_is_the_chain_rule(knots in knot_vector(5, 6, 1.0, true), t in 0.0f64..=1.0, seed in any::<u64>()) {
        let (a, b) = knots.domain();
        let u = a + (b - a) * t;
        prop_assume!(knots.multiplicity(u) < knots.degree() + 1);
        prop_assume!(knots.degree() >= 1);
        let curve = BSpline::new(knots.clone(), points(knots.num_basis(), seed)).unwrap();
        let ins = SplineMap::insertion(&knots, u, 1).unwrap();
        let der = SplineMap::derivative(ins.target(), 1).unwrap();
        let ele = SplineMap::elevation(der.target(), 1).unwrap();
        let composed = ins.then(&der).unwrap().then(&ele).unwrap();
        let expected = curve.insert_knot(u, 1).unwrap().derivative(1).unwrap().elevate_degree(1).unwrap();
        check_map(&composed, &curve, &expected, "composition");
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
    let x = points(knots.num_basis(), 7);
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
