//! The helix of the checks: a transcendental curve, so an interpolating cubic; its
//! curvature and torsion (from the library's curvature and `torsion`) against the closed
//! forms `a / (a² + b²)` and `b / (a² + b²)`, and no torsion zero.

use nalgebra::Vector3;
use spline::algebra::{SpaceCurveFeatures, torsion};

#[test]
fn helix_curvature_and_torsion_against_the_closed_form() {
    let (a, b) = (1.0f64, 0.5f64);
    let m = 96;
    let end = 4.0 * std::f64::consts::PI;
    let t: Vec<f64> = (0..=m).map(|j| end * f64::from(j) / f64::from(m)).collect();
    let points: Vec<Vector3<f64>> = t
        .iter()
        .map(|&t| Vector3::new(a * t.cos(), a * t.sin(), b * t))
        .collect();
    let helix = spline::fit::interpolate_function(&t, &points, 3).unwrap();
    let (kappa, tau) = (a / (a * a + b * b), b / (a * a + b * b));
    // Interpolation error O(h⁴) in position, O(h²) in second and third derivatives, away
    // from the ends (where the end conditions are not the helix's).
    for j in 40..360 {
        let u = end * (f64::from(j) + 0.5) / 400.0;
        let k = helix.curvature_magnitude(u).unwrap();
        let w = torsion(&helix, u).unwrap();
        assert!((k - kappa).abs() < 2e-3, "κ({u}) = {k} vs {kappa}");
        assert!((w - tau).abs() < 2e-2, "τ({u}) = {w} vs {tau}");
    }
    let f = helix.space_features(1e-12).unwrap();
    assert!(f.torsion_zeros.is_empty(), "{f:?}");
    assert_eq!(f.constant_torsion, None);
}
