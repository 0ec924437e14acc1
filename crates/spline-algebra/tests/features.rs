//! Inflections and curvature extrema of rational curves, against closed forms and against
//! the sampled signed curvature.

use nalgebra::Vector2;
use spline_algebra::planar_features;
use spline_geom::NurbsCurve;

/// Two quarters of the ellipse x²/4 + y² = 1 from (2, 0) over (0, 1) to (−2, 0): the
/// curvature has its only interior extremum (a minimum, 1/4 · … at the end of the minor
/// axis) at u = 1, and there is no inflection.
#[test]
fn half_ellipse_has_one_curvature_extremum_at_the_minor_axis() {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let ellipse = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0],
        vec![
            Vector2::new(2.0, 0.0),
            Vector2::new(2.0, 1.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(-2.0, 1.0),
            Vector2::new(-2.0, 0.0),
        ],
        vec![1.0, w, 1.0, w, 1.0],
    )
    .unwrap();
    let f = planar_features(&ellipse, 1e-12).unwrap();
    assert!(f.inflections.is_empty(), "{f:?}");
    assert_eq!(f.curvature_extrema.len(), 1, "{f:?}");
    assert!((f.curvature_extrema[0] - 1.0).abs() < 1e-9, "{f:?}");
    // κ at the end of the minor axis of x²/a² + y²/b² = 1 is b/a² = 1/4.
    assert!((ellipse.signed_curvature(1.0).unwrap() - 0.25).abs() < 1e-12);
}

/// A cubic NURBS curve with uneven weights: every sign change of the sampled signed
/// curvature lies near a reported inflection, every sign change of its sampled derivative
/// near a reported curvature extremum, and conversely.
#[test]
fn rational_features_match_the_sampled_curvature() {
    let curve = NurbsCurve::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.55, 0.8, 1.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 2.0),
            Vector2::new(2.5, -1.0),
            Vector2::new(4.0, 1.5),
            Vector2::new(5.0, -0.5),
            Vector2::new(6.5, 1.0),
            Vector2::new(7.0, 0.0),
        ],
        vec![1.0, 3.0, 0.5, 2.0, 0.7, 1.5, 1.0],
    )
    .unwrap();
    let f = planar_features(&curve, 1e-12).unwrap();
    let n = 20_000;
    let u = |j: usize| j as f64 / n as f64;
    let kappa: Vec<f64> = (0..=n)
        .map(|j| curve.signed_curvature(u(j)).unwrap())
        .collect();
    let crossings = |values: &[f64], offset: f64| -> Vec<f64> {
        (1..values.len())
            .filter(|&j| values[j - 1] * values[j] < 0.0)
            .map(|j| u(j) - offset)
            .collect()
    };
    let inflections = crossings(&kappa, 0.5 / n as f64);
    let slope: Vec<f64> = kappa.windows(2).map(|w| w[1] - w[0]).collect();
    let extrema = crossings(&slope, 0.0);
    let near = |found: &[f64], expected: &[f64], what: &str| {
        assert_eq!(
            found.len(),
            expected.len(),
            "{what}: {found:?} vs {expected:?}"
        );
        for (a, b) in found.iter().zip(expected) {
            assert!(
                (a - b).abs() < 3.0 / n as f64,
                "{what}: {found:?} vs {expected:?}"
            );
        }
    };
    assert!(!f.inflections.is_empty() && !f.curvature_extrema.is_empty());
    near(&f.inflections, &inflections, "inflections");
    near(&f.curvature_extrema, &extrema, "curvature extrema");
}

/// Constant curvature has no extrema, a straight segment no inflections: the numerators
/// vanish identically and what the arithmetic leaves of them is rounding, whose sign
/// changes are not features. A slightly flattened circle keeps its four vertices.
#[test]
fn circles_and_straight_segments_have_no_features() {
    use spline_geom::{CircleConstruction, Frame};
    for construction in [CircleConstruction::Square, CircleConstruction::Triangle] {
        for (center, radius) in [((0.0, 0.0), 1.0), ((3.7, -1.1), 0.013), ((-2e3, 5e2), 7e4)] {
            let frame = Frame::planar(Vector2::new(center.0, center.1));
            let circle = NurbsCurve::circle(&frame, radius, construction).unwrap();
            let f = planar_features(&circle, 1e-12).unwrap();
            assert!(
                f.curvature_extrema.is_empty() && f.inflections.is_empty(),
                "{construction:?} {radius}: {f:?}"
            );
            // Squeezed by 1e-6 in y: an ellipse, with vertices at u = 0, ¼, ½, ¾ (the
            // interior ones found).
            let ellipse = NurbsCurve::from_knots(
                2,
                circle.knots().knots().to_vec(),
                circle
                    .control_points()
                    .iter()
                    .map(|p| Vector2::new(p.x, center.1 + (p.y - center.1) * (1.0 - 1e-6)))
                    .collect(),
                circle.weights().to_vec(),
            )
            .unwrap();
            let f = planar_features(&ellipse, 1e-12).unwrap();
            assert_eq!(
                f.curvature_extrema.len(),
                3,
                "{construction:?} {radius}: {f:?}"
            );
        }
    }
    // A rational parabola-like curve with collinear control points: a straight segment.
    let segment = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.1, 0.3),
            Vector2::new(0.7, 0.9),
            Vector2::new(1.9, 2.1),
            Vector2::new(2.2, 2.4),
        ],
        vec![1.0, 3.0, 0.2, 1.0],
    )
    .unwrap();
    let f = planar_features(&segment, 1e-12).unwrap();
    assert!(
        f.inflections.is_empty() && f.curvature_extrema.is_empty(),
        "{f:?}"
    );
}
