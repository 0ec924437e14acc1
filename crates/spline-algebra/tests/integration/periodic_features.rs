//! Inflections and curvature extrema of closed (periodic) curves, the closing point
//! included: against dense sampling of the signed curvature round the period and the
//! symmetries of the shapes.

use nalgebra::Vector2;
use spline_algebra::planar_features;
use spline_geom::{PeriodicBSpline, PlanarCurve};
use std::f64::consts::TAU;

/// The sign changes of `f` sampled at `m` points round the period `[0, 1)`, cyclically:
/// the parameters halfway between the samples where it changes.
fn cyclic_sign_changes(f: &[f64]) -> Vec<f64> {
    let m = f.len();
    (0..m)
        .filter(|&k| f[k] * f[(k + 1) % m] < 0.0)
        .map(|k| ((k as f64 + 0.5) / m as f64).rem_euclid(1.0))
        .collect()
}

/// Curvature extrema and inflections of `curve` by dense sampling of κ (finite differences
/// of the samples for κ′).
fn sampled(curve: &PeriodicBSpline<f64, Vector2<f64>>) -> (Vec<f64>, Vec<f64>) {
    let m = 200_000;
    let kappa: Vec<f64> = (0..m)
        .map(|k| curve.signed_curvature(k as f64 / m as f64).unwrap())
        .collect();
    // κ′ between samples k and k + 1 sits at (k + 1/2)/m; its sign changes at (k + 1)/m.
    let slope: Vec<f64> = (0..m).map(|k| kappa[(k + 1) % m] - kappa[k]).collect();
    let extrema = cyclic_sign_changes(&slope)
        .into_iter()
        .map(|u| (u + 0.5 / m as f64).rem_euclid(1.0))
        .collect();
    (extrema, cyclic_sign_changes(&kappa))
}

/// `found` and `expected` (parameters round the period) match one for one within `tol`.
fn assert_cyclic_match(found: &[f64], expected: &[f64], tol: f64, what: &str) {
    assert_eq!(
        found.len(),
        expected.len(),
        "{what}: {found:?} vs {expected:?}"
    );
    for e in expected {
        let near = found
            .iter()
            .any(|f| ((f - e).rem_euclid(1.0)).min((e - f).rem_euclid(1.0)) < tol);
        assert!(near, "{what}: {e} sampled, found {found:?}");
    }
}

/// A uniform periodic cubic on `n` control points on an ellipse of semi-axes `a`, `b`, the
/// first at the end of the major axis (the closing point is a vertex by symmetry).
fn elliptic(n: usize, a: f64, b: f64, turn: f64) -> PeriodicBSpline<f64, Vector2<f64>> {
    let control: Vec<Vector2<f64>> = (0..n)
        .map(|i| {
            let t = TAU * (i as f64 + turn) / n as f64;
            Vector2::new(a * t.cos(), b * t.sin())
        })
        .collect();
    let knots: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
    PeriodicBSpline::new(3, knots, 1.0, control).unwrap()
}

#[test]
fn an_oval_closed_curve_has_four_vertices_at_its_axes() {
    // Uniform cubic on 6 points of an ellipse of axes 3:2, control point 0 at the end of the
    // major axis; the curve passes there at t_{−1} = −1/6 (its point at t_i is centred on
    // c_{i+1}). (With more control points, or flatter ellipses, the control polygon's
    // corners add extrema: dense sampling says so too.)
    let curve = elliptic(6, 1.5, 1.0, 0.0);
    let shifted = |u: f64| (u + 1.0 / 6.0).rem_euclid(1.0);
    let features = planar_features(&curve, 1e-12).unwrap();
    assert!(
        features.inflections.is_empty(),
        "{:?}",
        features.inflections
    );
    let (extrema, inflections) = sampled(&curve);
    assert!(inflections.is_empty());
    assert_cyclic_match(&features.curvature_extrema, &extrema, 2e-5, "extrema");
    assert_eq!(features.curvature_extrema.len(), 4);
    // By symmetry (D2, and uniform knots) the vertices are a quarter period apart, one at
    // u = −1/6 + 1/4.
    let vertices: Vec<f64> = features
        .curvature_extrema
        .iter()
        .map(|&u| shifted(u))
        .collect();
    for k in 0..4 {
        let e = (0.25 + f64::from(k) / 4.0).rem_euclid(1.0);
        assert!(
            vertices
                .iter()
                .any(|v| (v - e).abs() < 1e-9 || (v - e - 1.0).abs() < 1e-9),
            "vertex near {e}: {vertices:?}"
        );
    }
}

#[test]
fn a_vertex_exactly_at_the_closing_point_is_reported_there() {
    // A uniform cubic at its knot t_i is (c_i + 4 c_{i+1} + c_{i+2}) / 6: with control point
    // 1 at the end of the major axis (turn −1), u = 0 is that end, a vertex by symmetry.
    let curve = elliptic(6, 1.5, 1.0, -1.0);
    let point = curve.eval(0.0).unwrap();
    assert!(point.y.abs() < 1e-15 && point.x > 1.0, "{point:?}");
    let features = planar_features(&curve, 1e-12).unwrap();
    assert_eq!(
        features.curvature_extrema.len(),
        4,
        "{:?}",
        features.curvature_extrema
    );
    assert_eq!(features.curvature_extrema[0], 0.0);
    let (extrema, _) = sampled(&curve);
    assert_cyclic_match(&features.curvature_extrema, &extrema, 2e-5, "extrema");
}

#[test]
fn a_kidney_has_inflections_and_extrema_across_the_closing_point() {
    // A closed curve with two dents (r = 1 − 0.6 cos⁸ t, stretched), the closing point
    // inside one of them: inflections and extrema on both sides of it.
    let n: usize = 20;
    let control: Vec<Vector2<f64>> = (0..n)
        .map(|i| {
            let t = TAU * (i as f64 + 0.37) / n as f64;
            let r = 1.0 - 0.6 * (t).cos().powi(8);
            Vector2::new(r * t.cos() * 1.3, r * t.sin())
        })
        .collect();
    let knots: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
    let curve = PeriodicBSpline::new(3, knots, 1.0, control).unwrap();
    let features = planar_features(&curve, 1e-12).unwrap();
    let (extrema, inflections) = sampled(&curve);
    assert!(!inflections.is_empty());
    assert_cyclic_match(&features.inflections, &inflections, 2e-5, "inflections");
    assert_cyclic_match(&features.curvature_extrema, &extrema, 2e-5, "extrema");
    // The opened curve sees the same features (the seam rule of open curves that close).
    let opened = planar_features(&curve.open_at(0.0).unwrap(), 1e-12).unwrap();
    assert_eq!(
        opened.curvature_extrema.len(),
        features.curvature_extrema.len()
    );
}

#[test]
fn a_regular_polygon_gives_twice_as_many_extrema_as_corners() {
    // A uniform cubic on a regular hexagon: curvature largest near each corner and smallest
    // between, 12 extrema by the six-fold symmetry, no inflection.
    let control: Vec<Vector2<f64>> = (0..6)
        .map(|i| {
            let t = TAU * f64::from(i) / 6.0;
            Vector2::new(t.cos(), t.sin())
        })
        .collect();
    let knots: Vec<f64> = (0..6).map(|i| f64::from(i) / 6.0).collect();
    let curve = PeriodicBSpline::new(3, knots, 1.0, control).unwrap();
    let features = planar_features(&curve, 1e-12).unwrap();
    assert!(features.inflections.is_empty());
    assert!(features.constant_curvature.is_none());
    assert_eq!(
        features.curvature_extrema.len(),
        12,
        "{:?}",
        features.curvature_extrema
    );
    let (extrema, _) = sampled(&curve);
    assert_cyclic_match(&features.curvature_extrema, &extrema, 2e-5, "extrema");
    // The extrema sit at the knots and halfway between (by symmetry), the closing point one.
    assert_eq!(features.curvature_extrema[0], 0.0);
    for (k, u) in features.curvature_extrema.iter().enumerate() {
        assert!((u - k as f64 / 12.0).abs() < 1e-9, "{k}: {u}");
    }
}
