//! Smoothing that cannot follow the data says so (issue 25, item 5): a warning when the
//! allowed extrema cost more than `DEVIATION_WARNING_FACTOR` times the least-squares fit's
//! deviation, and the fewest extrema within a tolerance.

use crate::airfoils::airfoil;
use nalgebra::Vector2;
use spline_core::ErrorKind;
use spline_shape::{
    AUTO_EXTREMA_TOLERANCE, DEVIATION_WARNING_FACTOR, DEVIATION_WARNING_FLOOR, SmoothingOptions,
    smooth, smooth_fewest_extrema,
};

/// The largest distance from `points` to the curve, by dense sampling of the curve (an
/// upper bound of the closest-point distance, independent of the library's projection).
fn sampled_distance(curve: &spline_geom::Curve2<f64>, points: &[Vector2<f64>]) -> f64 {
    let samples: Vec<Vector2<f64>> = (0..=200_000)
        .map(|k| curve.eval(f64::from(k) / 200_000.0).unwrap())
        .collect();
    points
        .iter()
        .map(|q| {
            samples
                .iter()
                .map(|s| (s - q).norm())
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_sharp_nosed_plate_with_one_maximum_warns() {
    // UIUC goe417a: one maximum leaves the curve about 1 % of the chord from the data, eight
    // times the least-squares fit with the same 20 control points.
    let points = airfoil("plates/goe417a");
    let result = smooth(&points, &SmoothingOptions::new(20)).unwrap();
    let max = result.deviation.to_curve.max;
    assert!(max > 8e-3, "{max}");
    assert!((sampled_distance(&result.curve, &points) - max).abs() < 1e-5);
    assert!(max > DEVIATION_WARNING_FACTOR * result.least_squares_deviation);
    assert!(max > DEVIATION_WARNING_FLOOR);
    assert_eq!(result.warnings.len(), 1, "{:?}", result.warnings);
    let warning = &result.warnings[0];
    assert!(warning.contains("more extrema"), "{warning}");
    assert!(warning.contains(&format!("{max:.3e}")), "{warning}");
}

#[test]
fn an_ordinary_airfoil_does_not_warn() {
    for name in ["clarkv", "e715", "naca23021", "goe404"] {
        let result = smooth(&airfoil(name), &SmoothingOptions::new(20)).unwrap();
        assert!(result.warnings.is_empty(), "{name}: {:?}", result.warnings);
        assert!(result.deviation.to_curve.max < 3e-3);
    }
}

#[test]
fn auto_extrema_on_a_plate_picks_two() {
    let points = airfoil("plates/goe417a");
    let result = smooth_fewest_extrema(&points, None, &SmoothingOptions::new(20)).unwrap();
    assert_eq!(result.extrema.len(), 2, "{:?}", result.extrema);
    assert!(result.warnings.is_empty(), "{:?}", result.warnings);
    // Within the default tolerance (the data's diagonal is about the chord, 1).
    let max = result.deviation.to_curve.max;
    assert!(max <= AUTO_EXTREMA_TOLERANCE * 1.01, "{max}");
    assert!((sampled_distance(&result.curve, &points) - max).abs() < 1e-5);
    // An ordinary airfoil needs its one maximum only; a tolerance nothing reaches is an error.
    let clarkv = airfoil("clarkv");
    let one = smooth_fewest_extrema(&clarkv, Some(2e-3), &SmoothingOptions::new(20)).unwrap();
    assert_eq!(one.extrema.len(), 1);
    let err = smooth_fewest_extrema(&clarkv, Some(1e-9), &SmoothingOptions::new(12)).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::ToleranceExceeded, "{err}");
    let err = smooth_fewest_extrema(&clarkv, Some(-1.0), &SmoothingOptions::new(12)).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::InvalidTolerance);
    assert_eq!(
        (err.value(), err.interval()),
        (Some(-1.0), Some((0.0, f64::INFINITY)))
    );
}
