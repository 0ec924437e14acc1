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

/// Turning points of the normal curvature along the meridian `v = 0` of a surface, sampled
/// (the meridian is a line of curvature, so this is the principal curvature whose extrema
/// along it are the ridge circles), with their heights.
fn sampled_ridge_heights(surface: &spline_geom::NurbsSurface<f64, 3>, m: usize) -> Vec<f64> {
    let ((u0, u1), (v0, _)) = surface.domain();
    let samples: Vec<(f64, f64)> = (0..=m)
        .map(|k| {
            let u = u0 + (u1 - u0) * k as f64 / m as f64;
            let local = surface.local_properties(u, v0).unwrap();
            (
                surface.eval(u, v0).unwrap().z,
                local.normal_curvature(1.0, 0.0).unwrap(),
            )
        })
        .collect();
    let mut heights = Vec::new();
    for w in samples.windows(3) {
        let (a, b, c) = (w[0].1, w[1].1, w[2].1);
        if (b - a) * (c - b) < 0.0 && (b - a).abs() > 1e-12 && (c - b).abs() > 1e-12 {
            heights.push(w[1].0);
        }
    }
    heights
}

#[test]
fn ridge_circles_are_controlled_by_the_eraser_on_the_meridian() {
    // f(z) = 1 + 0.3 z² + 0.01 sin 12z: its meridian curvature wiggles.
    let z: Vec<f64> = (0..=32).map(|k| f64::from(k) / 32.0).collect();
    let r: Vec<f64> = z
        .iter()
        .map(|&z| 1.0 + 0.3 * z * z + 0.01 * (12.0 * z).sin())
        .collect();
    let meridian = spline_fit::interpolate_function(&z, &r, 3).unwrap();
    let before = spline_algebra::revolution_features(&meridian, 1e-12).unwrap();
    assert!(before.ridges.len() >= 3, "{:?}", before.ridges);
    // The surface of the meridian agrees with the algebra (sampled on the surface itself).
    let heights = sampled_ridge_heights(&revolution_surface(&meridian).unwrap(), 4000);
    assert_eq!(
        heights.len(),
        before.ridges.len(),
        "{heights:?} {:?}",
        before.ridges
    );
    for (h, r) in heights.iter().zip(&before.ridges) {
        assert!((h - r.z).abs() < 2e-3, "{h} vs {r:?}");
    }
    // One ridge circle allowed, halfway up.
    let mut options = spline_shape::SmoothingOptions::new(10);
    options.extrema = vec!["min@0.5".parse().unwrap()];
    let controlled = spline_shape::control_ridge_circles(&meridian, 200, &options).unwrap();
    assert_eq!(controlled.ridge_circles.len(), 1);
    let after = sampled_ridge_heights(&controlled.surface, 4000);
    assert_eq!(after.len(), 1, "{after:?}");
    assert!((after[0] - controlled.ridge_circles[0]).abs() < 2e-3);
    assert!(controlled.profile.deviation.to_curve.max < 0.01);
}

/// The parabolic lines of a surface, all parameter lines: `(u-lines, v-lines)` by their
/// constant coordinate.
fn parameter_lines(
    surface: &spline_geom::Surface<f64, nalgebra::Vector3<f64>>,
) -> (Vec<f64>, Vec<f64>) {
    let rational = spline_geom::NurbsSurface::from_surface(surface);
    let lines = parabolic_lines(&rational, 8).unwrap();
    let (mut us, mut vs) = (Vec::new(), Vec::new());
    for curve in &lines.curves {
        let spread = |k: usize| {
            let lo = curve.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
            let hi = curve.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
            (lo, hi)
        };
        let ((u0, u1), (v0, v1)) = (spread(0), spread(1));
        if u1 - u0 < 1e-9 {
            us.push(u0);
        } else {
            assert!(v1 - v0 < 1e-9, "not a parameter line: {curve:?}");
            vs.push(v0);
        }
    }
    // A line crossed by another is reported in pieces: one value per line.
    for values in [&mut us, &mut vs] {
        values.sort_by(f64::total_cmp);
        values.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
    }
    (us, vs)
}

#[test]
fn translation_surfaces_are_controlled_through_their_profiles() {
    let x: Vec<f64> = (0..=24).map(|k| f64::from(k) / 24.0).collect();
    // g″ = −0.9π² sin 3πx: inflections at 1/3 and 2/3; h″ = 1.2 (y − 0.5) + 0.2: one at 1/3.
    let g: Vec<f64> = x
        .iter()
        .map(|&x| 0.1 * (3.0 * std::f64::consts::PI * x).sin())
        .collect();
    let h: Vec<f64> = x
        .iter()
        .map(|&y| 0.2 * (y - 0.5).powi(3) + 0.1 * y * y)
        .collect();
    let g = spline_fit::interpolate_function(&x, &g, 3).unwrap();
    let h = spline_fit::interpolate_function(&x, &h, 3).unwrap();
    let surface = spline_shape::translation_surface(&g, &h).unwrap();
    // The surface is the graph of g(x) + h(y).
    let p = spline_geom::ParamSurface::eval(&surface, 0.3, 0.7).unwrap();
    assert!(
        (p - nalgebra::Vector3::new(0.3, 0.7, g.eval(0.3).unwrap() + h.eval(0.7).unwrap())).norm()
            < 1e-12
    );
    let (us, vs) = parameter_lines(&surface);
    assert_eq!(us.len(), 2, "{us:?}");
    assert_eq!(vs.len(), 1, "{vs:?}");
    assert!((us[0] - 1.0 / 3.0).abs() < 1e-3 && (us[1] - 2.0 / 3.0).abs() < 1e-3);
    assert!((vs[0] - 1.0 / 3.0).abs() < 1e-3);
    // No inflection left in g; the one of h kept inside (0.2, 0.5).
    let none = ParabolicCircles {
        first: Sign::NonPositive,
        allowed: vec![],
    };
    let one = ParabolicCircles {
        first: Sign::NonPositive,
        allowed: vec![(0.2, 0.5)],
    };
    let controlled =
        spline_shape::control_translation_parabolic_lines(&g, &h, &none, &one, 200).unwrap();
    let (us, vs) = parameter_lines(&controlled.surface);
    assert!(us.is_empty(), "{us:?}");
    assert_eq!(vs.len(), 1, "{vs:?}");
    assert!(vs[0] > 0.2 && vs[0] < 0.5);
    assert!(
        controlled.second.max_deviation < 1e-4,
        "h needs hardly a change: {}",
        controlled.second.max_deviation
    );
    // g loses both inflections: the closest concave function to 1.5 periods of a sine of
    // amplitude 0.1 is about 0.12 away at worst.
    assert!(
        controlled.first.max_deviation < 0.15,
        "{}",
        controlled.first.max_deviation
    );
}
