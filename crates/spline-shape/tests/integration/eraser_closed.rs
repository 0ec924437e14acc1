//! The selective eraser on closed contours: the result is a periodic curve whose curvature,
//! sampled densely all the way round (across the closing point too), has exactly the
//! allowed extrema, close to the data.

use nalgebra::Vector2;
use spline_core::ErrorKind;
use spline_geom::PeriodicBSpline;
use spline_shape::{Extremum, ExtremumKind, SmoothingOptions, smooth};

/// Oriented curvature of a closed curve at `m` parameters round the period.
fn curvature_round(curve: &PeriodicBSpline<f64, Vector2<f64>>, m: usize) -> Vec<f64> {
    (0..m)
        .map(|k| {
            let d = curve.derivatives(k as f64 / m as f64, 2).unwrap();
            (d[1].x * d[2].y - d[1].y * d[2].x) / d[1].norm().powi(3)
        })
        .collect()
}

/// Turning points of a periodic sequence (changes of direction, plateaus skipped, steps
/// below `noise` ignored).
fn cyclic_turning_points(values: &[f64], noise: f64) -> usize {
    let m = values.len();
    let mut directions = Vec::new();
    for k in 0..m {
        let step = values[(k + 1) % m] - values[k];
        if step.abs() > noise {
            directions.push(step > 0.0);
        }
    }
    let d = directions.len();
    (0..d)
        .filter(|&k| directions[k] != directions[(k + 1) % d])
        .count()
}

/// Points of a closed contour `r(t)` round the origin, with a deterministic jitter.
fn contour(count: usize, radius: impl Fn(f64) -> (f64, f64), jitter: f64) -> Vec<Vector2<f64>> {
    (0..count)
        .map(|k| {
            let t = 0.3 + std::f64::consts::TAU * k as f64 / count as f64;
            let (x, y) = radius(t);
            let noise = jitter * (((k * 7919) % 13) as f64 / 6.0 - 1.0);
            Vector2::new(x + noise, y - noise)
        })
        .collect()
}

fn four_vertices() -> Vec<Extremum> {
    ["min", "max", "min", "max"]
        .iter()
        .map(|t| t.parse().unwrap())
        .collect()
}

#[test]
fn a_noisy_ellipse_gets_its_four_vertices_back() {
    let points = contour(80, |t| (2.0 * t.cos(), t.sin()), 2e-3);
    let start = {
        let mut options = SmoothingOptions::new(16);
        options.closed = true;
        options
    };
    let mut options = start.clone();
    options.extrema = four_vertices();
    let result = smooth(&points, &options).unwrap();
    let periodic = result.periodic.as_ref().expect("a closed result");
    let kappa = curvature_round(periodic, 8000);
    assert_eq!(
        cyclic_turning_points(&kappa, 1e-9),
        4,
        "{:?}",
        result.extrema
    );
    assert_eq!(result.extrema.len(), 4);
    assert!(
        result.deviation.to_curve.max < 6e-3,
        "{:?}",
        result.deviation
    );
    // The vertices lie near the axes: curvature maxima at (±2, 0) (sharp: placed closely),
    // minima at (0, ±1) (the curvature is flat there — 1.5 % above its minimum at x = ±0.23 —
    // so they are placed more loosely).
    for e in &result.extrema {
        match e.kind {
            ExtremumKind::Maximum => {
                assert!(e.point.y.abs() < 0.1 && e.point.x.abs() > 1.9, "{e:?}");
            }
            ExtremumKind::Minimum => {
                assert!(e.point.x.abs() < 0.15 && e.point.y.abs() > 0.95, "{e:?}");
            }
        }
    }
    // The curve closes smoothly: value and two derivatives agree across the closing point.
    let before = periodic.derivatives(1.0 - 1e-9, 2).unwrap();
    let after = periodic.derivatives(1e-9, 2).unwrap();
    for k in 0..3 {
        assert!((before[k] - after[k]).norm() < 1e-5 * (1.0 + after[k].norm()));
    }
    // The opened curve is the same curve.
    for k in 0..=50 {
        let u = f64::from(k) / 50.0;
        let gap = (result.curve.eval(u).unwrap() - periodic.eval(u).unwrap()).norm();
        assert!(gap < 1e-12);
    }
}

#[test]
fn a_wobbly_contour_keeps_only_the_allowed_extrema() {
    // r = 1 + 0.04 sin 7t stretched into an ellipse: 14 extra wiggles of the curvature.
    let points = contour(
        120,
        |t| {
            let r = 1.0 + 0.04 * (7.0 * t).sin();
            (1.6 * r * t.cos(), r * t.sin())
        },
        1e-3,
    );
    let mut options = SmoothingOptions::new(24);
    options.closed = true;
    options.extrema = four_vertices();
    let result = smooth(&points, &options).unwrap();
    assert!(
        result.start_extrema > 4,
        "the fit wiggles: {}",
        result.start_extrema
    );
    let kappa = curvature_round(result.periodic.as_ref().unwrap(), 8000);
    assert_eq!(cyclic_turning_points(&kappa, 1e-9), 4);
    assert!(
        result.deviation.to_curve.max < 0.08,
        "{:?}",
        result.deviation
    );
}

#[test]
fn closed_contours_need_as_many_maxima_as_minima() {
    let points = contour(40, |t| (t.cos(), t.sin()), 0.0);
    let mut options = SmoothingOptions::new(10);
    options.closed = true;
    options.extrema = vec![Extremum::maximum()];
    let error = smooth(&points, &options).unwrap_err();
    assert_eq!(error.kind(), ErrorKind::InvalidArgument);
    assert!(
        error.to_string().contains("as many maxima as minima"),
        "{error}"
    );
}

#[test]
fn a_closing_repeated_point_counts_once() {
    let mut points = contour(60, |t| (2.0 * t.cos(), t.sin()), 1e-3);
    let mut options = SmoothingOptions::new(14);
    options.closed = true;
    options.extrema = four_vertices();
    let open_ended = smooth(&points, &options).unwrap();
    points.push(points[0]);
    let repeated = smooth(&points, &options).unwrap();
    assert!((open_ended.deviation.to_curve.max - repeated.deviation.to_curve.max).abs() < 1e-12);
}
