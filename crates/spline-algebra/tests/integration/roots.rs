//! Root isolation: known roots (simple, double, at knots, at the ends), identically zero
//! pieces, jumps, the requested accuracy, and random functions against dense sampling.

#![allow(clippy::cast_lossless)]

use proptest::collection::vec;
use proptest::prelude::*;
use spline_algebra::{SplineMap, product, sign_change_params, zeros};
use spline_geom::BSpline;
use spline_testing::strategies::function;

/// `u − r` on `[0, 1]`.
fn linear(r: f64) -> BSpline<f64, f64> {
    BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0], vec![-r, 1.0 - r]).unwrap()
}

fn from_roots(roots: &[f64]) -> BSpline<f64, f64> {
    let mut f = linear(roots[0]);
    for &r in &roots[1..] {
        f = product(&f, &linear(r)).unwrap();
    }
    f
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn known_simple_roots_with_interior_knots(roots in vec(0.02f64..0.98, 1..=7), extra in vec(0.01f64..0.99, 2)) {
        let mut roots = roots;
        roots.sort_by(f64::total_cmp);
        if roots.windows(2).any(|w| w[1] - w[0] < 1e-3) {
            return Ok(());
        }
        let f = from_roots(&roots);
        // Insert some knots (one of them exactly at a root) so that roots fall inside
        // segments and on breakpoints.
        let mut extra = vec![roots[0], extra[0], extra[1]];
        extra.sort_by(f64::total_cmp);
        let map = SplineMap::refinement(f.knots(), &extra).unwrap();
        let f = map.apply_to(&f).unwrap();
        for accuracy in [1e-6, 1e-13] {
            let z = zeros(&f, accuracy).unwrap();
            assert_eq!(z.len(), roots.len(), "{z:?} vs {roots:?}");
            for (i, (zi, r)) in z.iter().zip(&roots).enumerate() {
                assert!(!zi.is_interval());
                assert!(zi.sign_change, "roots {roots:?}: simple root {r} is a crossing");
                // A root is determined only up to its condition number: rounding of the
                // coefficients (~eps) moves it by about eps / |f'(r)|.
                let slope: f64 = (0..roots.len())
                    .filter(|&j| j != i)
                    .map(|j| (r - roots[j]).abs())
                    .product();
                let conditioning = 1e3 * f64::EPSILON / slope;
                assert!(
                    (zi.at() - r).abs() <= accuracy.max(conditioning),
                    "roots {roots:?}: {} vs {r} (accuracy {accuracy}, conditioning {conditioning:.1e})",
                    zi.at()
                );
                if accuracy >= 1e-6 {
                    let (lo, hi) = (zi.at() - accuracy, zi.at() + accuracy);
                    assert!(f.eval(lo.max(0.0)).unwrap() * f.eval(hi.min(1.0)).unwrap() <= 0.0);
                }
            }
            assert_eq!(sign_change_params(&f, accuracy).unwrap().len(), roots.len());
        }
    }
}

#[test]
fn double_roots_ends_and_knots() {
    // (u − 0.3)² (u − 0.7): a touching zero and a crossing.
    let f = from_roots(&[0.3, 0.3, 0.7]);
    let z = zeros(&f, 1e-12).unwrap();
    assert_eq!(z.len(), 2, "{z:?}");
    assert!((z[0].at() - 0.3).abs() < 1e-6 && !z[0].sign_change);
    assert!((z[1].at() - 0.7).abs() < 1e-12 && z[1].sign_change);
    assert_eq!(sign_change_params(&f, 1e-12).unwrap().len(), 1);
    // (u − 0.5)⁴: one touching zero.
    let f = from_roots(&[0.5, 0.5, 0.5, 0.5]);
    let z = zeros(&f, 1e-12).unwrap();
    assert_eq!(z.len(), 1, "{z:?}");
    assert!(!z[0].sign_change);
    // (u − 0.5)³: a triple root is a crossing.
    let f = from_roots(&[0.5, 0.5, 0.5]);
    let z = zeros(&f, 1e-12).unwrap();
    assert_eq!(z.len(), 1, "{z:?}");
    assert!(z[0].sign_change && (z[0].at() - 0.5).abs() < 1e-4);
    // u (u − 0.5) with a knot at 0.5: zeros at the start (not a crossing) and on the knot.
    let f = from_roots(&[0.0, 0.5]);
    let f = SplineMap::insertion(f.knots(), 0.5, 1)
        .unwrap()
        .apply_to(&f)
        .unwrap();
    let z = zeros(&f, 1e-12).unwrap();
    assert_eq!(z.len(), 2, "{z:?}");
    assert_eq!((z[0].at(), z[0].sign_change), (0.0, false));
    assert!((z[1].at() - 0.5).abs() < 1e-12 && z[1].sign_change);
}

#[test]
fn identically_zero_pieces_and_jumps() {
    // Negative on [0, 0.4), zero on [0.4, 0.6], positive after (C⁰ knots of multiplicity 3).
    let knots = vec![0., 0., 0., 0., 0.4, 0.4, 0.4, 0.6, 0.6, 0.6, 1., 1., 1., 1.];
    let f =
        BSpline::from_knots(3, knots, vec![-1., -2., -0.5, 0., 0., 0., 0., 1., 0.5, 2.]).unwrap();
    let z = zeros(&f, 1e-12).unwrap();
    assert_eq!(z.len(), 1, "{z:?}");
    assert!(z[0].is_interval() && z[0].sign_change);
    assert_eq!((z[0].start, z[0].end), (0.4, 0.6));
    assert_eq!(sign_change_params(&f, 1e-12).unwrap(), vec![0.5]);
    // The same with the same sign on both sides: not a crossing.
    let knots = vec![0., 0., 0., 0., 0.4, 0.4, 0.4, 0.6, 0.6, 0.6, 1., 1., 1., 1.];
    let f = BSpline::from_knots(3, knots, vec![1., 2., 0.5, 0., 0., 0., 0., 1., 0.5, 2.]).unwrap();
    let z = zeros(&f, 1e-12).unwrap();
    assert_eq!(z.len(), 1);
    assert!(z[0].is_interval() && !z[0].sign_change);
    // The zero function.
    let f = BSpline::from_knots(2, vec![0., 0., 0., 1., 1., 1.], vec![0.0; 3]).unwrap();
    let z = zeros(&f, 1e-12).unwrap();
    assert_eq!(z.len(), 1);
    assert_eq!((z[0].start, z[0].end), (0.0, 1.0));
    // A jump across zero is a sign change but not a zero; a zero next to a jump is a crossing
    // judged on its own side of the jump.
    let f: BSpline<f64, f64> =
        BSpline::from_knots(1, vec![0., 0., 0.5, 0.5, 1., 1.], vec![-1., 1., -1., 1.]).unwrap();
    let z = zeros(&f, 1e-12).unwrap();
    assert_eq!(z.len(), 2, "{z:?}");
    assert!(z.iter().all(|z| z.sign_change));
    assert!((z[0].at() - 0.25).abs() < 1e-12 && (z[1].at() - 0.75).abs() < 1e-12);
    assert_eq!(
        sign_change_params(&f, 1e-12).unwrap(),
        vec![0.25, 0.5, 0.75]
    );
}

#[test]
fn requested_accuracy_and_errors() {
    // u² − 0.5 on [0, 1].
    let f = BSpline::from_knots(2, vec![0., 0., 0., 1., 1., 1.], vec![-0.5, -0.5, 0.5]).unwrap();
    for accuracy in [1e-3, 1e-8, 1e-14] {
        let z = zeros(&f, accuracy).unwrap();
        assert_eq!(z.len(), 1);
        assert!((z[0].at() - 0.5f64.sqrt()).abs() <= accuracy.max(2e-16));
    }
    assert!(zeros(&f, 0.0).is_err());
    assert!(zeros(&f, -1.0).is_err());
    assert!(zeros(&f, f64::NAN).is_err());
    assert!(zeros(&f, f64::INFINITY).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn random_functions_against_dense_sampling(f in function(1, 7, false)) {

        let crossings: Vec<f64> = zeros(&f, 1e-12)
            .unwrap()
            .iter()
            .filter(|z| z.sign_change)
            .map(spline_algebra::Zero::at)
            .collect();
        // The accuracy 1e-12 is in the parameter: |f| at a zero is at most 1e-12 times the
        // largest slope, bounded by the derivative's coefficients.
        let slope = f
            .derivative(1)
            .unwrap()
            .control_points()
            .iter()
            .fold(1.0f64, |m, c| m.max(c.abs()));
        for &u in &crossings {
            assert!(
                f.eval(u).unwrap().abs() < 1e-9 + 2e-12 * slope,
                "f({u}) = {}",
                f.eval(u).unwrap()
            );
        }
        let samples = 20_000;
        let spacing = 1.0 / samples as f64;
        if crossings.windows(2).any(|w| w[1] - w[0] < 4.0 * spacing) {
            return Ok(());
        }
        let values: Vec<f64> = (0..=samples)
            .map(|i| f.eval(i as f64 * spacing).unwrap())
            .collect();
        let mut sampled = Vec::new();
        for i in 0..samples {
            if values[i] * values[i + 1] < 0.0 {
                sampled.push((i as f64 + 0.5) * spacing);
            }
        }
        // Sampling can only miss pairs closer than the spacing (excluded above) or a
        // crossing exactly on a sample; anything else is a bug.
        assert_eq!(
            sampled.len(),
            crossings.len(),
            "{crossings:?} vs sampled {sampled:?}"
        );
        for (c, s) in crossings.iter().zip(&sampled) {
            assert!((c - s).abs() <= spacing, "{c} vs {s}");
        }
    }
}
