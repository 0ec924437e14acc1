//! Smoothing splines against scipy (`make_smoothing_spline`, `make_splrep`, `make_splprep`
//! on held-out random data, `tests/data/smoothing/`), closed forms and the error contract.

use nalgebra::Vector2;
use serde_json::Value;
use spline_core::ErrorKind;
use spline_fit::{
    SmoothingParameter, smoothing_curve_to_residual, smoothing_spline, smoothing_to_residual,
};

fn cases(name: &str) -> Vec<Value> {
    let path = format!(
        "{}/tests/data/smoothing/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let json: Value = serde_json::from_str(&text).expect("JSON");
    json["cases"].as_array().expect("cases").clone()
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

fn weights(case: &Value) -> Option<Vec<f64>> {
    (!case["weights"].is_null()).then(|| floats(&case["weights"]))
}

/// `|a − b| ≤ tol · max(1, |b|)` entry by entry, with the worst relative error.
fn assert_close(what: &str, got: &[f64], expected: &[f64], tol: f64) -> f64 {
    assert_eq!(got.len(), expected.len(), "{what}: lengths");
    let scale = expected.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    let mut worst = 0.0f64;
    for (i, (g, e)) in got.iter().zip(expected).enumerate() {
        let err = (g - e).abs() / scale;
        worst = worst.max(err);
        assert!(err <= tol, "{what}[{i}]: {g} vs {e} ({err:e} relative)");
    }
    worst
}

/// The weight chosen by cross-validation is scipy's: scipy's search step for step on our
/// scores. Near the minimum the search ends with parabolic steps through scores that differ
/// by ~1e-8 relative, so the rounding of the scores (ours and scipy's; see
/// `tests/data/smoothing/README.md`) moves λ by up to ~1e-5 relative on the largest case —
/// 1e-9 absolute, far inside the search's own tolerance of 1e-5. At scipy's λ the splines
/// agree to 1e-8.
#[test]
fn gcv_gives_scipys_lambda_and_spline() {
    let mut worst_lambda = 0.0f64;
    let mut worst_values = 0.0f64;
    let mut worst_at_scipys = 0.0f64;
    for case in cases("gcv") {
        let name = case["name"].as_str().unwrap();
        let (x, y) = (floats(&case["x"]), floats(&case["y"]));
        let w = weights(&case);
        let fit = smoothing_spline(&x, &y, w.as_deref(), SmoothingParameter::Gcv).unwrap();
        let lambda = case["lambda"].as_f64().unwrap();
        let err = (fit.lambda - lambda).abs() / lambda;
        eprintln!(
            "{name}: {} data, λ {} (scipy {lambda}, {err:.1e} relative)",
            x.len(),
            fit.lambda
        );
        worst_lambda = worst_lambda.max(err);
        assert!(
            err < 1e-5,
            "{name}: λ {} vs scipy {lambda} ({err:e})",
            fit.lambda
        );
        assert!(
            (fit.lambda - lambda).abs() < 1e-8,
            "{name}: λ {} vs {lambda}",
            fit.lambda
        );
        assert_close(
            &format!("{name} knots"),
            fit.spline.knots().knots(),
            &floats(&case["spline"]["knots"]),
            1e-15,
        );
        let expected = floats(&case["spline"]["coefficients"]);
        assert_close(
            &format!("{name} coefficients"),
            fit.spline.control_points(),
            &expected,
            1e-6,
        );
        let values = fit.spline.eval_many(&floats(&case["at"])).unwrap();
        worst_values = worst_values.max(assert_close(
            &format!("{name} values"),
            &values,
            &floats(&case["values"]),
            1e-6,
        ));
        let at_scipys =
            smoothing_spline(&x, &y, w.as_deref(), SmoothingParameter::Lambda(lambda)).unwrap();
        worst_at_scipys = worst_at_scipys.max(assert_close(
            &format!("{name} coefficients at scipy's λ"),
            at_scipys.spline.control_points(),
            &expected,
            1e-8,
        ));
    }
    eprintln!(
        "gcv: worst λ {worst_lambda:.1e}, values {worst_values:.1e}; at scipy's λ {worst_at_scipys:.1e} (relative)"
    );
}

#[test]
fn given_lambda_matches_scipy_including_interpolation() {
    for case in cases("lambda") {
        let name = case["name"].as_str().unwrap();
        let (x, y) = (floats(&case["x"]), floats(&case["y"]));
        let w = weights(&case);
        let lambda = case["lambda"].as_f64().unwrap();
        let fit =
            smoothing_spline(&x, &y, w.as_deref(), SmoothingParameter::Lambda(lambda)).unwrap();
        assert_eq!(fit.lambda, lambda);
        assert_close(
            &format!("{name} coefficients"),
            fit.spline.control_points(),
            &floats(&case["spline"]["coefficients"]),
            1e-8,
        );
        let values = fit.spline.eval_many(&floats(&case["at"])).unwrap();
        assert_close(
            &format!("{name} values"),
            &values,
            &floats(&case["values"]),
            1e-8,
        );
        if lambda == 0.0 {
            // Interpolation: every residual vanishes, the influence matrix is the identity.
            assert!(fit.residual == 0.0 && fit.trace == x.len() as f64);
            let at = fit.spline.eval_many(&x).unwrap();
            assert_close(&format!("{name} interpolation"), &at, &y, 1e-12);
        }
    }
}

#[test]
fn residual_target_matches_make_splrep() {
    let mut worst = 0.0f64;
    for case in cases("residual") {
        let name = case["name"].as_str().unwrap();
        let (x, y) = (floats(&case["x"]), floats(&case["y"]));
        let w = weights(&case);
        let k = case["degree"].as_u64().unwrap() as usize;
        let s = case["s"].as_f64().unwrap();
        let fit = smoothing_to_residual(&x, &y, w.as_deref(), k, s).unwrap();
        // The knots are data abscissae: the same ones, bit for bit.
        assert_eq!(
            fit.spline.knots().knots(),
            floats(&case["spline"]["knots"]).as_slice(),
            "{name}: knots"
        );
        worst = worst.max(assert_close(
            &format!("{name} coefficients"),
            fit.spline.control_points(),
            &floats(&case["spline"]["coefficients"]),
            1e-7,
        ));
        let residual = case["residual"].as_f64().unwrap();
        assert!(
            (fit.residual - residual).abs() <= 1e-8 * residual.max(1e-12),
            "{name}: residual {} vs {residual}",
            fit.residual
        );
        // FITPACK's acceptance: within 0.1 % of the target, or below it without smoothing.
        assert!(
            (fit.residual - s).abs() <= 1e-3 * s || (fit.smoothing.is_none() && fit.residual <= s),
            "{name}: residual {} for target {s}",
            fit.residual
        );
    }
    eprintln!("make_splrep: worst coefficient error {worst:e}");
}

#[test]
fn parametric_curves_match_make_splprep() {
    for case in cases("curves") {
        let name = case["name"].as_str().unwrap();
        let points: Vec<Vector2<f64>> = case["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| {
                let p = floats(p);
                Vector2::new(p[0], p[1])
            })
            .collect();
        let s = case["s"].as_f64().unwrap();
        let (fit, params) = smoothing_curve_to_residual(&points, None, 3, s).unwrap();
        assert_close(
            &format!("{name} params"),
            &params,
            &floats(&case["params"]),
            1e-14,
        );
        assert_close(
            &format!("{name} knots"),
            fit.spline.knots().knots(),
            &floats(&case["spline"]["knots"]),
            1e-14,
        );
        // scipy's coefficients are `[i][coordinate]`.
        let coefficients: Vec<Vec<f64>> = case["spline"]["coefficients"]
            .as_array()
            .unwrap()
            .iter()
            .map(floats)
            .collect();
        for c in 0..2 {
            let got: Vec<f64> = fit.spline.control_points().iter().map(|p| p[c]).collect();
            let expected: Vec<f64> = coefficients.iter().map(|p| p[c]).collect();
            assert_close(&format!("{name} coordinate {c}"), &got, &expected, 1e-7);
        }
    }
}

#[test]
fn a_huge_penalty_gives_the_weighted_regression_line() {
    // λ → ∞ leaves f'' = 0: the straight line of weighted least squares (closed form),
    // approached as 1/λ.
    let x: Vec<f64> = (0..30).map(|i| f64::from(i).powf(1.3) * 0.1).collect();
    let y: Vec<f64> = x.iter().map(|t| (2.0 * t).sin() + 0.5 * t).collect();
    let w: Vec<f64> = (0..30).map(|i| 0.5 + f64::from(i % 4)).collect();
    let sw: f64 = w.iter().sum();
    let mx = x.iter().zip(&w).map(|(a, b)| a * b).sum::<f64>() / sw;
    let my = y.iter().zip(&w).map(|(a, b)| a * b).sum::<f64>() / sw;
    let sxy: f64 = x
        .iter()
        .zip(&y)
        .zip(&w)
        .map(|((a, b), c)| c * (a - mx) * (b - my))
        .sum();
    let sxx: f64 = x.iter().zip(&w).map(|(a, c)| c * (a - mx).powi(2)).sum();
    let slope = sxy / sxx;
    let distance = |lambda: f64| {
        let fit = smoothing_spline(&x, &y, Some(&w), SmoothingParameter::Lambda(lambda)).unwrap();
        let d = x
            .iter()
            .map(|&t| (fit.spline.eval(t).unwrap() - (my + slope * (t - mx))).abs())
            .fold(0.0f64, f64::max);
        (d, fit.trace)
    };
    // (Beyond λ ≈ 1e7 rounding, ~eps · cond(BᵀWB + λΩ), takes over: scipy's too.)
    let (d4, _) = distance(1e4);
    let (d5, _) = distance(1e5);
    let (d6, trace) = distance(1e6);
    assert!(d6 < 5e-5, "{d6:e}");
    assert!(
        (d4 / d5 - 10.0).abs() < 0.5 && (d5 / d6 - 10.0).abs() < 0.5,
        "{d4:e} {d5:e} {d6:e}"
    );
    // Two parameters left (a line): tr H → 2.
    assert!((trace - 2.0).abs() < 1e-3, "{trace}");
}

#[test]
fn vector_values_smooth_each_coordinate_with_one_lambda() {
    let x: Vec<f64> = (0..25).map(|i| f64::from(i) / 24.0).collect();
    let y: Vec<Vector2<f64>> = x
        .iter()
        .enumerate()
        .map(|(i, t)| Vector2::new(t.cos(), (3.0 * t).sin() + 0.02 * f64::from(i as u8 % 3)))
        .collect();
    let both = smoothing_spline(&x, &y, None, SmoothingParameter::Lambda(1e-3)).unwrap();
    for c in 0..2 {
        let yc: Vec<f64> = y.iter().map(|p| p[c]).collect();
        let one = smoothing_spline(&x, &yc, None, SmoothingParameter::Lambda(1e-3)).unwrap();
        for (a, b) in both
            .spline
            .control_points()
            .iter()
            .zip(one.spline.control_points())
        {
            assert!((a[c] - b).abs() < 1e-12);
        }
    }
}

#[test]
fn bad_input_is_a_clear_error() {
    let x = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
    let y = [0.0, 1.0, 0.0, 1.0, 0.0, 1.0];
    let kind = |r: spline_core::Result<spline_fit::SmoothingFit<f64, f64>>| r.unwrap_err().kind();
    assert_eq!(
        kind(smoothing_spline(
            &x[..4],
            &y[..4],
            None,
            SmoothingParameter::Gcv
        )),
        ErrorKind::TooFewPoints
    );
    assert_eq!(
        kind(smoothing_spline(&x, &y[..5], None, SmoothingParameter::Gcv)),
        ErrorKind::InvalidLength
    );
    let unsorted = [0.0, 2.0, 1.0, 3.0, 4.0, 5.0];
    assert_eq!(
        kind(smoothing_spline(
            &unsorted,
            &y,
            None,
            SmoothingParameter::Gcv
        )),
        ErrorKind::UnsortedKnots
    );
    let repeated = [0.0, 1.0, 1.0, 3.0, 4.0, 5.0];
    assert_eq!(
        kind(smoothing_spline(
            &repeated,
            &y,
            None,
            SmoothingParameter::Gcv
        )),
        ErrorKind::UnsortedKnots
    );
    let w = [1.0, 1.0, 0.0, 1.0, 1.0, 1.0];
    assert_eq!(
        kind(smoothing_spline(&x, &y, Some(&w), SmoothingParameter::Gcv)),
        ErrorKind::InvalidWeight
    );
    assert_eq!(
        kind(smoothing_spline(
            &x,
            &y,
            None,
            SmoothingParameter::Lambda(-1.0)
        )),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        kind(smoothing_spline(
            &x,
            &y,
            None,
            SmoothingParameter::Lambda(f64::NAN)
        )),
        ErrorKind::InvalidArgument
    );
    let nan_y = [0.0, f64::NAN, 0.0, 1.0, 0.0, 1.0];
    assert_eq!(
        kind(smoothing_spline(&x, &nan_y, None, SmoothingParameter::Gcv)),
        ErrorKind::NonFinite
    );

    let rkind = |r: spline_core::Result<spline_fit::ResidualFit<f64, f64>>| r.unwrap_err().kind();
    assert_eq!(
        rkind(smoothing_to_residual(&x, &y, None, 3, -1.0)),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        rkind(smoothing_to_residual(&x, &y, None, 0, 1.0)),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        rkind(smoothing_to_residual(&x, &y, None, 6, 1.0)),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        rkind(smoothing_to_residual(&x[..3], &y[..3], None, 3, 1.0)),
        ErrorKind::TooFewPoints
    );
    assert_eq!(
        rkind(smoothing_to_residual(&unsorted, &y, None, 3, 1.0)),
        ErrorKind::UnsortedKnots
    );
    assert_eq!(
        rkind(smoothing_to_residual(&x, &y, Some(&w), 3, 1.0)),
        ErrorKind::InvalidWeight
    );
    assert_eq!(
        rkind(smoothing_to_residual(&x, &y, None, 3, f64::INFINITY)),
        ErrorKind::InvalidArgument
    );
    // s = 0 interpolates (not-a-knot) and needs strictly increasing abscissae.
    let exact = smoothing_to_residual(&x, &y, None, 3, 0.0).unwrap();
    for (t, v) in x.iter().zip(&y) {
        assert!((exact.spline.eval(*t).unwrap() - v).abs() < 1e-12);
    }
    assert!(smoothing_to_residual(&repeated, &y, None, 3, 0.0).is_err());
}
