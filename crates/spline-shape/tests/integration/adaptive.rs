//! Seed 000 §3: minimising perimeter² / area with adaptive parametrisation converges to the
//! half circle, J → 2π (Table 1: 6.3632 … 6.2839 with n = 10, d = 3, N = 10).

use nalgebra::Vector2;
use spline_geom::BSpline;
use spline_shape::{AdaptiveOptions, optimise_perimeter_over_area, perimeter_squared_over_area};
use std::f64::consts::PI;

/// A flattened arch from (0, 0) to (1, 0), vertical at the origin: half an ellipse.
fn flat_arch(count: usize) -> Vec<Vector2<f64>> {
    (0..count)
        .map(|i| {
            let t = PI * i as f64 / (count - 1) as f64;
            let mut p = Vector2::new(0.5 - 0.5 * t.cos(), 0.3 * t.sin());
            if i + 1 == count {
                p = Vector2::new(1.0, 0.0);
            }
            p
        })
        .collect()
}

#[test]
fn the_criterion_against_closed_forms() {
    // y = 4x(1 − x): A = 2/3, P = ∫ √(1 + (4 − 8x)²) dx = (√17)/2 + asinh(4)/8.
    let arch = BSpline::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(0.5, 2.0),
            Vector2::new(1.0, 0.0),
        ],
    )
    .unwrap();
    let (j, p, a) = perimeter_squared_over_area(&arch, 1e-13).unwrap();
    let perimeter = 17f64.sqrt() / 2.0 + 4f64.asinh() / 8.0;
    assert!((a - 2.0 / 3.0).abs() < 1e-14);
    assert!((p - perimeter).abs() < 1e-12, "{p} vs {perimeter}");
    assert!((j - perimeter * perimeter * 1.5).abs() < 1e-11);
    // A curve below the axis has no positive area.
    let below = arch.map_control_points(|q| Vector2::new(q.x, -q.y));
    assert!(perimeter_squared_over_area(&below, 1e-10).is_err());
}

#[test]
fn table_1_converges_to_two_pi() {
    let options = AdaptiveOptions::default();
    let history = optimise_perimeter_over_area(&flat_arch(41), &options).unwrap();
    let js: Vec<f64> = history.iter().map(|h| h.criterion).collect();
    eprintln!("J per iteration: {js:?}");
    // J is an isoperimetric ratio: never below 2π, and close to it at the end.
    assert!(js.iter().all(|&j| j > 2.0 * PI - 1e-9));
    let last = *js.last().unwrap();
    assert!(last - 2.0 * PI < 2e-3, "{last}");
    assert!(js[0] > last);
    // The result is close to the half circle of centre (½, 0) and radius ½.
    let curve = &history.last().unwrap().curve;
    for i in 0..=200 {
        let p = curve.eval(f64::from(i) / 200.0).unwrap();
        assert!(
            ((p - Vector2::new(0.5, 0.0)).norm() - 0.5).abs() < 1e-2,
            "{p}"
        );
    }
    // The fixed coordinates hold: vertical start, through (0, 0) and (1, 0).
    let cp = curve.control_points();
    assert_eq!((cp[0], cp[1].x), (Vector2::zeros(), 0.0));
    assert_eq!(cp[cp.len() - 1], Vector2::new(1.0, 0.0));
}

#[test]
fn bad_settings_are_errors() {
    let options = AdaptiveOptions {
        control_points: 4,
        ..AdaptiveOptions::default()
    };
    assert!(optimise_perimeter_over_area(&flat_arch(41), &options).is_err());
    let options = AdaptiveOptions {
        samples: 5,
        ..AdaptiveOptions::default()
    };
    assert!(optimise_perimeter_over_area(&flat_arch(41), &options).is_err());
    let mut shifted = flat_arch(41);
    shifted[0].x = 0.1;
    assert!(optimise_perimeter_over_area(&shifted, &AdaptiveOptions::default()).is_err());
}

#[test]
fn bad_options_say_what_failed() {
    // Issue 26: the counts of the inequality that fails, and a bad tolerance's kind.
    let arch = flat_arch(12);
    let options = AdaptiveOptions {
        degree: 3,
        control_points: 4,
        ..AdaptiveOptions::default()
    };
    let err = optimise_perimeter_over_area(&arch, &options).unwrap_err();
    assert_eq!(err.kind(), spline_core::ErrorKind::InvalidArgument);
    assert_eq!(err.counts(), Some((5, 4)), "{err}");
    let options = AdaptiveOptions {
        control_points: 11,
        samples: 10,
        ..AdaptiveOptions::default()
    };
    let err = optimise_perimeter_over_area(&arch, &options).unwrap_err();
    assert_eq!(err.counts(), Some((11, 10)), "{err}");
    let options = AdaptiveOptions {
        degree: 0,
        ..AdaptiveOptions::default()
    };
    let err = optimise_perimeter_over_area(&arch, &options).unwrap_err();
    assert_eq!(
        (err.value(), err.interval()),
        (Some(0.0), Some((1.0, f64::INFINITY)))
    );
    let options = AdaptiveOptions {
        simplex_tolerance: -1.0,
        iterations: 1,
        ..AdaptiveOptions::default()
    };
    let err = optimise_perimeter_over_area(&arch, &options).unwrap_err();
    assert_eq!(
        err.kind(),
        spline_core::ErrorKind::InvalidTolerance,
        "{err}"
    );
    assert_eq!(err.value(), Some(-1.0));
}

#[test]
fn the_limits_are_the_librarys() {
    use spline_core::ErrorKind;
    use spline_shape::{MAX_ADAPTIVE_ITERATIONS, default_initial_shape};
    for iterations in [0, MAX_ADAPTIVE_ITERATIONS + 1] {
        let options = AdaptiveOptions {
            iterations,
            ..AdaptiveOptions::default()
        };
        let e = optimise_perimeter_over_area(&default_initial_shape(), &options).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidArgument);
        assert_eq!(e.value(), Some(iterations as f64));
    }
    let options = AdaptiveOptions {
        samples: spline_shape::MAX_ADAPTIVE_SAMPLES + 1,
        ..AdaptiveOptions::default()
    };
    assert!(optimise_perimeter_over_area(&default_initial_shape(), &options).is_err());
}
