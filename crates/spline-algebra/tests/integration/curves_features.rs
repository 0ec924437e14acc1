//! Inflections and curvature extrema of known planar curves (a closed cubic ellipse, cubic
//! and quartic graphs under knot insertion) cross-checked by dense sampling of the signed
//! curvature, and the error cases of `planar_features`.
#![allow(
    clippy::needless_range_loop,
    clippy::cast_lossless,
    clippy::type_complexity,
    clippy::manual_range_contains
)]

use nalgebra::Vector2;
use spline_algebra::{Form, PlanarInvariants, planar_features};
use spline_geom::{BSpline, Curve2};

/// Curvature extrema and inflections by dense sampling of the signed curvature.
fn sampled_features(curve: &Curve2, samples: usize) -> (Vec<f64>, Vec<f64>) {
    let (a, b) = curve.domain();
    let us: Vec<f64> = (0..=samples)
        .map(|i| a + (b - a) * i as f64 / samples as f64)
        .collect();
    let kappa: Vec<f64> = us
        .iter()
        .map(|&u| curve.signed_curvature(u).unwrap())
        .collect();
    let mut extrema = Vec::new();
    let mut inflections = Vec::new();
    for i in 1..samples {
        let (d0, d1) = (kappa[i] - kappa[i - 1], kappa[i + 1] - kappa[i]);
        if d0 * d1 < 0.0 {
            extrema.push(us[i]);
        }
    }
    let mut last: Option<(f64, f64)> = None;
    for (&u, &k) in us.iter().zip(&kappa) {
        if k.abs() < 1e-9 {
            continue;
        }
        if let Some((lu, lk)) = last {
            if lk * k < 0.0 {
                inflections.push(0.5 * (lu + u));
            }
        }
        last = Some((u, k));
    }
    (extrema, inflections)
}

fn assert_matches_samples(found: &[f64], sampled: &[f64], spacing: f64, what: &str) {
    assert_eq!(
        found.len(),
        sampled.len(),
        "{what}: found {found:?}, sampled {sampled:?}"
    );
    for (f, s) in found.iter().zip(sampled) {
        assert!((f - s).abs() <= 2.0 * spacing, "{what}: {f} vs sampled {s}");
    }
}

#[test]
fn closed_cubic_ellipse_has_eight_curvature_extrema_and_no_inflection() {
    let knots: Vec<f64> = (0..=14).map(f64::from).collect();
    let points: Vec<Vector2<f64>> = (0..11)
        .map(|k| {
            let theta = k as f64 * std::f64::consts::FRAC_PI_4;
            Vector2::new(2.0 * theta.cos(), theta.sin())
        })
        .collect();
    let curve = BSpline::from_knots(3, knots, points).unwrap();
    assert_eq!(curve.domain(), (3.0, 11.0));
    let features = planar_features(&curve, 1e-12).unwrap();
    let in_domain: Vec<f64> = features
        .curvature_extrema
        .iter()
        .copied()
        .filter(|&u| (3.0..11.0).contains(&u))
        .collect();
    assert_eq!(
        in_domain.len(),
        8,
        "extrema {:?}",
        features.curvature_extrema
    );
    assert!(features.inflections.is_empty());
    let (sampled, sampled_inflections) = sampled_features(&curve, 80_000);
    assert!(sampled_inflections.is_empty());
    assert_matches_samples(
        &features.curvature_extrema,
        &sampled,
        8.0 / 80_000.0,
        "ellipse extrema",
    );
    // Each reported extremum is a true zero of κ′ (central differences of the curvature).
    for &u in &features.curvature_extrema {
        let h = 1e-5;
        let dk = (curve.signed_curvature(u + h).unwrap() - curve.signed_curvature(u - h).unwrap())
            / (2.0 * h);
        assert!(dk.abs() < 1e-6, "κ′({u}) = {dk}");
    }
}

fn cubic_graph(extra_knots: &[f64]) -> Curve2 {
    // (u, u³ − u) on [−1, 1].
    let curve = BSpline::from_knots(
        3,
        vec![-1., -1., -1., -1., 1., 1., 1., 1.],
        vec![
            Vector2::new(-1.0, 0.0),
            Vector2::new(-1.0 / 3.0, 4.0 / 3.0),
            Vector2::new(1.0 / 3.0, -4.0 / 3.0),
            Vector2::new(1.0, 0.0),
        ],
    )
    .unwrap();
    curve.refine(extra_knots).unwrap()
}

fn quartic_graph(extra_knots: &[f64]) -> Curve2 {
    // (u, u⁴) on [−1, 1]: Bernstein coefficients of u⁴ are 1, −1, 1, −1, 1.
    let curve = BSpline::from_knots(
        4,
        vec![-1., -1., -1., -1., -1., 1., 1., 1., 1., 1.],
        vec![
            Vector2::new(-1.0, 1.0),
            Vector2::new(-0.5, -1.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(0.5, -1.0),
            Vector2::new(1.0, 1.0),
        ],
    )
    .unwrap();
    curve.refine(extra_knots).unwrap()
}

#[test]
fn graph_inflections() {
    for extra in [
        vec![],
        vec![0.0],
        vec![0.0, 0.0],
        vec![-0.3, 0.25, 0.5],
        vec![1e-7],
    ] {
        let cubic = cubic_graph(&extra);
        for u in [-0.9, -0.2, 0.0, 0.6] {
            assert!((cubic.eval(u).unwrap().y - (u * u * u - u)).abs() < 1e-14);
        }
        let f = planar_features(&cubic, 1e-12).unwrap();
        assert_eq!(
            f.inflections.len(),
            1,
            "extra knots {extra:?}: {:?}",
            f.inflections
        );
        assert!(f.inflections[0].abs() < 1e-12);
        let (sampled_extrema, sampled_inflections) = sampled_features(&cubic, 20_000);
        assert_eq!(sampled_inflections.len(), 1);
        assert_matches_samples(
            &f.curvature_extrema,
            &sampled_extrema,
            2.0 / 20_000.0,
            "cubic graph extrema",
        );

        let quartic = quartic_graph(&extra);
        for u in [-0.9, -0.2, 0.0, 0.6] {
            assert!((quartic.eval(u).unwrap().y - u.powi(4)).abs() < 1e-14);
        }
        let f = planar_features(&quartic, 1e-12).unwrap();
        assert!(
            f.inflections.is_empty(),
            "a double zero of h4 is not an inflection: {:?}",
            f.inflections
        );
        let (sampled_extrema, sampled_inflections) = sampled_features(&quartic, 20_000);
        assert!(sampled_inflections.is_empty());
        // κ = 12u²/(1 + 16u⁶)^{3/2}: a minimum at 0 and two maxima.
        assert_matches_samples(
            &f.curvature_extrema,
            &sampled_extrema,
            2.0 / 20_000.0,
            "quartic graph extrema",
        );
        assert_eq!(f.curvature_extrema.len(), 3);
    }
}

#[test]
fn feature_errors() {
    let line = BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)],
    )
    .unwrap();
    assert!(planar_features(&line, 1e-12).is_err());
    // A cusp: zero velocity at u = 0.5.
    let cusp = BSpline::from_knots(
        3,
        vec![0., 0., 0., 0., 1., 1., 1., 1.],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(1.0, 0.0),
        ],
    )
    .unwrap();
    let err = planar_features(&cusp, 1e-12).unwrap_err();
    assert_eq!(
        err.kind(),
        spline_core::ErrorKind::DegenerateGeometry,
        "{err}"
    );
    let curve = cubic_graph(&[]);
    assert!(planar_features(&curve, 0.0).is_err());
    assert!(planar_features(&curve, f64::NAN).is_err());
    let algebra = PlanarInvariants::new(curve.knots()).unwrap();
    assert!(
        algebra
            .g(&curve.control_points()[..3], Form::BSpline)
            .is_err()
    );
}
