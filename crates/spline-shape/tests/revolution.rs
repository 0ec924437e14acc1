//! Shape control of surfaces of revolution through the meridian: parabolic circles checked
//! on the surface itself (spline-algebra's parabolic lines and pointwise curvature), not
//! through the meridian's constraints.

use spline_algebra::parabolic_lines;
use spline_geom::BSpline;
use spline_shape::{ParabolicCircles, Sign, control_parabolic_circles, revolution_surface};

/// The meridian `f(z) = 1 + 0.3 z² + 0.02 sin 6z` on [0, 1] interpolated by a cubic.
fn wavy_meridian() -> BSpline<f64, f64> {
    let z: Vec<f64> = (0..=16).map(|k| f64::from(k) / 16.0).collect();
    let r: Vec<f64> = z
        .iter()
        .map(|&z| 1.0 + 0.3 * z * z + 0.02 * (6.0 * z).sin())
        .collect();
    spline_fit::interpolate_function(&z, &r, 3).unwrap()
}

/// Heights of the parabolic circles of a surface of revolution: each polyline must be a
/// circle (constant height, radius the meridian's) — returns the heights.
fn parabolic_heights(meridian: &BSpline<f64, f64>) -> Vec<f64> {
    let surface = revolution_surface(meridian).unwrap();
    let lines = parabolic_lines(&surface, 8).unwrap();
    assert!(lines.regions.is_empty() && lines.singular.is_empty());
    lines
        .curves
        .iter()
        .map(|c| {
            let points: Vec<_> = c
                .iter()
                .map(|p| surface.eval(p[0], p[1]).unwrap())
                .collect();
            let z = points[0].z;
            for p in &points {
                assert!((p.z - z).abs() < 1e-9, "not a circle: {} vs {z}", p.z);
                let r = meridian.eval(z).unwrap();
                assert!((p.x.hypot(p.y) - r).abs() < 1e-9);
            }
            z
        })
        .collect()
}

/// The example of the issue: the meridian has two unwanted parabolic circles (where
/// `f″ = 0.6 − 0.72 sin 6z` changes sign, z = arcsin(5/6)/6 and (π − arcsin(5/6))/6 for the
/// exact function); controlled, the surface has none, within a deviation of 0.5 % of the
/// radius; the pointwise Gaussian curvature confirms K ≤ 0 everywhere.
#[test]
fn two_unwanted_parabolic_circles_are_removed() {
    let meridian = wavy_meridian();
    let mut before = parabolic_heights(&meridian);
    before.sort_by(f64::total_cmp);
    assert_eq!(before.len(), 2, "{before:?}");
    let exact = [
        (5.0f64 / 6.0).asin() / 6.0,
        (std::f64::consts::PI - (5.0f64 / 6.0).asin()) / 6.0,
    ];
    for (b, e) in before.iter().zip(exact) {
        assert!((b - e).abs() < 0.01, "{before:?} vs {exact:?}");
    }
    let none = ParabolicCircles {
        first: Sign::NonNegative,
        allowed: vec![],
    };
    let controlled = control_parabolic_circles(&meridian, &none, 200, 1).unwrap();
    assert!(
        controlled.max_deviation < 5e-3,
        "{}",
        controlled.max_deviation
    );
    assert!(parabolic_heights(&controlled.meridian).is_empty());
    let surface = revolution_surface(&controlled.meridian).unwrap();
    for i in 0..=200 {
        for v in [0.1, 0.37, 0.8] {
            let u = f64::from(i) / 200.0;
            let k = surface.local_properties(u, v).unwrap().gaussian_curvature;
            assert!(k <= 1e-9, "K = {k} at ({u}, {v})");
        }
    }
    eprintln!(
        "meridian control: max deviation {:.2e}, objective {:.3e} (unconstrained {:.3e})",
        controlled.max_deviation, controlled.fit.objective, controlled.fit.unconstrained_objective
    );
}

/// One allowed circle: a meridian with three sign changes of f″ keeps exactly one, inside
/// the allowed interval.
#[test]
fn an_allowed_parabolic_circle_is_kept_where_asked() {
    let z: Vec<f64> = (0..=24).map(|k| f64::from(k) / 24.0).collect();
    // f″ = −0.8 + 2.4 z − 1.62 sin 9z changes sign at z ≈ 0.347, 0.778, 0.928: a bell-like
    // radius with a wiggle; only the first circle is wanted.
    let f = |z: f64| 1.0 - 0.4 * z * z + 0.4 * z * z * z + 0.02 * (9.0 * z).sin();
    let r: Vec<f64> = z.iter().copied().map(f).collect();
    let meridian = spline_fit::interpolate_function(&z, &r, 3).unwrap();
    let before = parabolic_heights(&meridian);
    assert_eq!(before.len(), 3, "{before:?}");
    let one = ParabolicCircles {
        first: Sign::NonPositive,
        allowed: vec![(0.25, 0.45)],
    };
    let controlled = control_parabolic_circles(&meridian, &one, 300, 1).unwrap();
    let after = parabolic_heights(&controlled.meridian);
    assert_eq!(after.len(), 1, "{after:?}");
    assert!(after[0] > 0.25 && after[0] < 0.45, "{after:?}");
    assert!(
        controlled.max_deviation < 0.02,
        "{}",
        controlled.max_deviation
    );
}

#[test]
fn bad_requests_are_errors() {
    let meridian = wavy_meridian();
    let bad = ParabolicCircles {
        first: Sign::NonNegative,
        allowed: vec![(0.5, 0.4)],
    };
    assert!(control_parabolic_circles(&meridian, &bad, 100, 0).is_err());
    let outside = ParabolicCircles {
        first: Sign::NonNegative,
        allowed: vec![(0.5, 1.5)],
    };
    assert!(control_parabolic_circles(&meridian, &outside, 100, 0).is_err());
    let quadratic =
        BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![1.0, 2.0, 1.0]).unwrap();
    let none = ParabolicCircles {
        first: Sign::NonNegative,
        allowed: vec![],
    };
    assert!(control_parabolic_circles(&quadratic, &none, 100, 0).is_err());
    assert!(control_parabolic_circles(&meridian, &none, 100, 9).is_err());
}
