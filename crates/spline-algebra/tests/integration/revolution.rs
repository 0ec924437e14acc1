//! Feature circles of surfaces of revolution: closed forms of polynomial meridians, dense
//! sampling of random meridians (derivatives evaluated directly, not through the product
//! algebra), Jacobians against central differences.

use proptest::prelude::*;
use spline_algebra::{revolution_features, revolution_numerators};
use spline_core::{ErrorKind, KnotVector};
use spline_geom::BSpline;

/// The Bézier form on `[a, b]` of the polynomial `Σ c_k z^k` (blossoms at the ends).
fn polynomial(c: &[f64], a: f64, b: f64) -> BSpline<f64, f64> {
    let p = c.len() - 1;
    // Blossom of z^k at (a × (p − i), b × i): the elementary symmetric mean.
    let blossom = |k: usize, i: usize| -> f64 {
        // Σ over subsets of size k of the product, divided by C(p, k).
        let choose = |n: usize, r: usize| -> f64 {
            (0..r).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64)
        };
        let mut sum = 0.0;
        for j in 0..=k.min(i) {
            // j factors b (from the i copies), k − j factors a (from the p − i copies).
            if k - j > p - i {
                continue;
            }
            sum += choose(i, j) * choose(p - i, k - j) * b.powi(j as i32) * a.powi((k - j) as i32);
        }
        sum / choose(p, k)
    };
    let control: Vec<f64> = (0..=p)
        .map(|i| (0..=p).map(|k| c[k] * blossom(k, i)).sum())
        .collect();
    let mut knots = vec![a; p + 1];
    knots.extend(vec![b; p + 1]);
    BSpline::from_knots(p, knots, control).unwrap()
}

fn eval_poly(c: &[f64], z: f64, order: usize) -> f64 {
    (order..c.len())
        .map(|k| {
            let factor: f64 = (0..order).map(|j| (k - j) as f64).product();
            c[k] * factor * z.powi((k - order) as i32)
        })
        .sum()
}

/// `(f″, R, F)` at `z` from the derivatives `d = [f, f′, f″, f‴]`.
fn closed_forms(d: [f64; 4]) -> (f64, f64, f64) {
    let [f, f1, f2, f3] = d;
    (
        f2,
        f3 * (1.0 + f1 * f1) - 3.0 * f1 * f2 * f2,
        3.0 * f1 * f2 + f * f3,
    )
}

/// Sign changes of `g` on a grid of `m` intervals of `[a, b]`, refined by bisection.
fn sampled_crossings(g: impl Fn(f64) -> f64, a: f64, b: f64, m: usize) -> Vec<f64> {
    let mut out = Vec::new();
    let mut previous = (a, g(a));
    for k in 1..=m {
        let z = a + (b - a) * k as f64 / m as f64;
        let v = g(z);
        if v != 0.0 && previous.1 != 0.0 && (v > 0.0) != (previous.1 > 0.0) {
            let (mut lo, mut hi) = (previous.0, z);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if (g(mid) > 0.0) == (previous.1 > 0.0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            out.push(0.5 * (lo + hi));
        }
        if v != 0.0 {
            previous = (z, v);
        }
    }
    out
}

fn assert_close(found: &[f64], expected: &[f64], tol: f64, what: &str) {
    assert_eq!(
        found.len(),
        expected.len(),
        "{what}: {found:?} vs {expected:?}"
    );
    for (f, e) in found.iter().zip(expected) {
        assert!((f - e).abs() < tol, "{what}: {found:?} vs {expected:?}");
    }
}

#[test]
fn a_quintic_meridian_against_its_closed_forms() {
    // f(z) = 3 + 0.5 z − z³ + 0.4 z⁵ on [−1.5, 1.5]: positive, several features.
    let c = [3.0, 0.5, 0.0, -1.0, 0.0, 0.4];
    let (a, b) = (-1.5, 1.5);
    let meridian = polynomial(&c, a, b);
    for k in 0..=10 {
        let z = a + (b - a) * f64::from(k) / 10.0;
        assert!((meridian.eval(z).unwrap() - eval_poly(&c, z, 0)).abs() < 1e-12);
    }
    let features = revolution_features(&meridian, 1e-13).unwrap();
    let d = |z: f64| [0, 1, 2, 3].map(|o| eval_poly(&c, z, o));
    let parabolic = sampled_crossings(|z| closed_forms(d(z)).0, a, b, 20_000);
    let ridges = sampled_crossings(|z| closed_forms(d(z)).1, a, b, 20_000);
    let flecnodal: Vec<f64> = sampled_crossings(|z| closed_forms(d(z)).2, a, b, 20_000)
        .into_iter()
        .filter(|&z| closed_forms(d(z)).0 > 0.0)
        .collect();
    assert!(!parabolic.is_empty() && !ridges.is_empty() && !flecnodal.is_empty());
    assert_close(&features.parabolic, &parabolic, 1e-9, "parabolic");
    let ridge_z: Vec<f64> = features.ridges.iter().map(|r| r.z).collect();
    assert_close(&ridge_z, &ridges, 1e-9, "ridges");
    assert_close(&features.flecnodal, &flecnodal, 1e-9, "flecnodal");
    // The kind of each ridge circle from the sampled meridian curvature κ = −f″/w^{3/2}.
    let kappa = |z: f64| {
        let [_, f1, f2, _] = d(z);
        -f2 / (1.0 + f1 * f1).powf(1.5)
    };
    for r in &features.ridges {
        let h = 1e-4;
        let maximum = kappa(r.z) > kappa(r.z - h) && kappa(r.z) > kappa(r.z + h);
        assert_eq!(r.maximum, maximum, "{r:?}");
    }
}

#[test]
fn a_cylinder_and_a_cone_have_no_feature_circles() {
    let cylinder = polynomial(&[1.0, 0.0, 0.0, 0.0], 0.0, 2.0);
    let features = revolution_features(&cylinder, 1e-12).unwrap();
    assert!(features.parabolic.is_empty() && features.ridges.is_empty());
    assert!(features.flecnodal.is_empty());
    let cone = polynomial(&[1.0, 0.5, 0.0, 0.0], 0.0, 2.0);
    let features = revolution_features(&cone, 1e-12).unwrap();
    assert!(features.parabolic.is_empty() && features.ridges.is_empty());
}

#[test]
fn bad_meridians_are_refused() {
    let quadratic =
        BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![1.0, 2.0, 1.0]).unwrap();
    let error = revolution_features(&quadratic, 1e-12).unwrap_err();
    assert_eq!(error.kind(), ErrorKind::InvalidArgument);
    // z − 0.5 on [0, 1] crosses the axis.
    let crossing = polynomial(&[-0.5, 1.0, 0.0, 0.0], 0.0, 1.0);
    let error = revolution_features(&crossing, 1e-12).unwrap_err();
    assert!(error.to_string().contains("reaches zero"), "{error}");
}

/// Positive cubic meridians on uniform knots.
fn meridians() -> impl Strategy<Value = BSpline<f64, f64>> {
    (4usize..10).prop_flat_map(|n| {
        prop::collection::vec(0.5f64..2.0, n).prop_map(move |control| {
            let interior: Vec<f64> = (1..n - 3).map(|i| i as f64 / (n - 3) as f64).collect();
            let knots = KnotVector::clamped(3, 0.0, 1.0, &interior).unwrap();
            BSpline::new(knots, control).unwrap()
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    /// Every sign change of the numerators, evaluated directly from the meridian's
    /// derivatives on a dense grid, is found, and no other.
    #[test]
    fn features_match_dense_sampling(meridian in meridians()) {
        let features = revolution_features(&meridian, 1e-12).unwrap();
        let d = |z: f64| {
            let v = meridian.derivatives(z, 3).unwrap();
            [v[0], v[1], v[2], v[3]]
        };
        let m = 20_000;
        // Grid points avoid the knots (f‴ jumps there) by a half step.
        let parabolic = sampled_crossings(|z| closed_forms(d(z)).0, 0.0, 1.0, m);
        let ridges = sampled_crossings(|z| closed_forms(d(z)).1, 0.0, 1.0, m);
        let flecnodal: Vec<f64> = sampled_crossings(|z| closed_forms(d(z)).2, 0.0, 1.0, m)
            .into_iter()
            .filter(|&z| closed_forms(d(z)).0 > 0.0)
            .collect();
        let tol = 2.0 / m as f64;
        let near = |found: &[f64], sampled: &[f64]| {
            found.len() == sampled.len()
                && found.iter().zip(sampled).all(|(f, s)| (f - s).abs() < tol)
        };
        prop_assert!(near(&features.parabolic, &parabolic), "{:?} {:?}", features.parabolic, parabolic);
        let ridge_z: Vec<f64> = features.ridges.iter().map(|r| r.z).collect();
        prop_assert!(near(&ridge_z, &ridges), "{:?} {:?}", ridge_z, ridges);
        prop_assert!(near(&features.flecnodal, &flecnodal), "{:?} {:?}", features.flecnodal, flecnodal);
    }

    /// The Jacobians of the numerators against central differences.
    #[test]
    fn jacobians_match_central_differences(meridian in meridians()) {
        let numerators = revolution_numerators(&meridian).unwrap();
        let h = 1e-6;
        let n = meridian.control_points().len();
        for k in 0..n {
            let shifted = |s: f64| {
                let mut c = meridian.control_points().to_vec();
                c[k] += s;
                revolution_numerators(&BSpline::new(meridian.knots().clone(), c).unwrap()).unwrap()
            };
            let (plus, minus) = (shifted(h), shifted(-h));
            for (which, base, p, m) in [
                ("parabolic", &numerators.parabolic, &plus.parabolic, &minus.parabolic),
                ("ridge", &numerators.ridge, &plus.ridge, &minus.ridge),
                ("flecnodal", &numerators.flecnodal, &plus.flecnodal, &minus.flecnodal),
            ] {
                let dense = nalgebra::DMatrix::from(&base.jacobian);
                prop_assert_eq!(dense.ncols(), n);
                for (i, (a, b)) in p.value.control_points().iter().zip(m.value.control_points()).enumerate() {
                    let fd = (a - b) / (2.0 * h);
                    prop_assert!((fd - dense[(i, k)]).abs() < 1e-5 * (1.0 + fd.abs()),
                        "{} coefficient {} variable {}: {} vs {}", which, i, k, fd, dense[(i, k)]);
                }
            }
        }
    }
}
