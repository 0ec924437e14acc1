//! The selective eraser of curvature extrema on an airfoil and on synthetic data, checked by
//! dense sampling of the curvature (independently of the constraint algebra).

use nalgebra::Vector2;
use spline_core::ErrorKind;
use spline_geom::Curve2;
use spline_geom::exchange::parse_points;
use spline_shape::{EraserOptions, erase_curvature_extrema};

fn airfoil(name: &str) -> Vec<Vector2<f64>> {
    let path = format!(
        "{}/../../data/airfoils/{name}.dat",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap();
    parse_points(&text)
        .unwrap()
        .into_iter()
        .map(|p| Vector2::new(p[0], p[1]))
        .collect()
}

/// Parameters where the sampled curvature turns from increasing to decreasing or back,
/// ignoring changes below `noise` (relative to the largest |κ|).
fn sampled_extrema(curve: &Curve2, samples: usize, noise: f64) -> Vec<f64> {
    let (a, b) = curve.domain();
    let us: Vec<f64> = (0..=samples)
        .map(|i| a + (b - a) * i as f64 / samples as f64)
        .collect();
    let kappa: Vec<f64> = us
        .iter()
        .map(|&u| curve.signed_curvature(u).unwrap())
        .collect();
    let scale = kappa.iter().fold(0.0f64, |m, k| m.max(k.abs()));
    let mut extrema = Vec::new();
    let mut direction = 0i8;
    let mut anchor = kappa[0];
    for (i, &k) in kappa.iter().enumerate().skip(1) {
        let delta = k - anchor;
        if delta.abs() <= noise * scale {
            continue;
        }
        let d = if delta > 0.0 { 1 } else { -1 };
        if direction != 0 && d != direction {
            extrema.push(us[i - 1]);
        }
        direction = d;
        anchor = k;
    }
    extrema
}

#[test]
fn an_airfoil_keeps_one_curvature_maximum_at_the_nose() {
    let points = airfoil("clarkv");
    let result = erase_curvature_extrema(&points, &EraserOptions::new(20, 1)).unwrap();
    // The unconstrained fit wiggles; the result has exactly the allowed extremum.
    assert!(
        result.least_squares_extrema.len() > 3,
        "{:?}",
        result.least_squares_extrema
    );
    assert_eq!(result.curvature_extrema.len(), 1);
    let nose = result.extremum_params[0];
    assert!((result.curvature_extrema[0] - nose).abs() < 1e-9);
    // The extremum is the nose: the point of smallest x.
    let tip = result.curve.eval(nose).unwrap();
    assert!(tip.x < 0.01, "{tip}");
    // Dense sampling agrees: one maximum of the curvature, there.
    let sampled = sampled_extrema(&result.curve, 20_000, 1e-9);
    assert_eq!(sampled.len(), 1, "{sampled:?}");
    assert!((sampled[0] - nose).abs() < 1e-3);
    assert!(result.curve.signed_curvature(nose).unwrap() > 0.0);
    // Close to the data (chord 1): a few millimetres at most, like the thesis's Table 6.1.
    assert!(result.max_deviation < 5e-3, "{}", result.max_deviation);
    assert!(result.rms_deviation < 1e-3, "{}", result.rms_deviation);
    assert!(result.solver.max_constraint < 0.0);
}

#[test]
fn a_noisy_half_ellipse_gets_its_single_extremum_back() {
    // Upper half of x²/4 + y² = 1, from (2, 0) to (−2, 0): curvature maximal at the ends and
    // minimal at the top; with noise, the least-squares fit has many extrema.
    let count: i32 = 80;
    let points: Vec<Vector2<f64>> = (0..count)
        .map(|i| {
            let t = std::f64::consts::PI * (0.05 + 0.9 * f64::from(i) / f64::from(count - 1));
            let noise = 2e-3 * f64::from((i * 7919) % 13) / 13.0 - 1e-3;
            Vector2::new(2.0 * t.cos(), t.sin() + noise)
        })
        .collect();
    let mut options = EraserOptions::new(12, 1);
    options.extremum_params = Some(vec![0.5]);
    options.increasing_first = Some(false);
    let result = erase_curvature_extrema(&points, &options).unwrap();
    assert_eq!(result.curvature_extrema, vec![0.5]);
    assert_eq!(sampled_extrema(&result.curve, 20_000, 1e-9).len(), 1);
    assert!(result.max_deviation < 3e-3, "{}", result.max_deviation);
}

#[test]
fn bad_requests_are_errors() {
    let points = airfoil("clarkv");
    let mut options = EraserOptions::new(20, 1);
    options.degree = 2;
    assert_eq!(
        erase_curvature_extrema(&points, &options)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    let options = EraserOptions::new(6, 4);
    assert_eq!(
        erase_curvature_extrema(&points, &options)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    let mut options = EraserOptions::new(20, 1);
    options.extremum_params = Some(vec![1.5]);
    assert_eq!(
        erase_curvature_extrema(&points, &options)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    options.extremum_params = Some(vec![0.2, 0.4]);
    assert_eq!(
        erase_curvature_extrema(&points, &options)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        erase_curvature_extrema(&points[..3], &EraserOptions::new(20, 1))
            .unwrap_err()
            .kind(),
        ErrorKind::TooFewPoints
    );
}
