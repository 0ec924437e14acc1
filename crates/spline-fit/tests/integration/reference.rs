//! Every case of `tests/data/reference/{interpolate,lsq,natural}.json` (computed by
//! scipy.interpolate, see `generate.py` there) through the library.

#![allow(clippy::needless_range_loop, clippy::cast_lossless)]

use nalgebra::SVector;
use serde_json::Value;
use spline_core::KnotVector;
use spline_fit::{
    InterpolationOptions, KnotChoice, LeastSquares, LsqMethod, Parametrization, interpolate,
    natural_cubic,
};
use spline_geom::BSpline;
use spline_testing::reference::{cases, f64s};

fn rows(v: &Value) -> Vec<Vec<f64>> {
    v.as_array().expect("array").iter().map(f64s).collect()
}

fn points<const D: usize>(rows: &[Vec<f64>]) -> Vec<SVector<f64, D>> {
    rows.iter()
        .map(|r| SVector::<f64, D>::from_column_slice(r))
        .collect()
}

/// Knots within 1e-12 absolute, control points within 1e-9 relative (to max(1, |x|)).
fn assert_curve<const D: usize>(got: &BSpline<f64, SVector<f64, D>>, expected: &Value, what: &str) {
    assert_eq!(
        got.degree() as u64,
        expected["degree"].as_u64().unwrap(),
        "{what}: degree"
    );
    let ek = f64s(&expected["knots"]);
    let gk = got.knots().knots();
    assert_eq!(gk.len(), ek.len(), "{what}: number of knots");
    for (i, (a, b)) in gk.iter().zip(&ek).enumerate() {
        assert!((a - b).abs() <= 1e-12, "{what}: knot {i}: {a} vs {b}");
    }
    let ec = rows(&expected["control_points"]);
    assert_eq!(
        got.control_points().len(),
        ec.len(),
        "{what}: control points"
    );
    for (i, (g, e)) in got.control_points().iter().zip(&ec).enumerate() {
        for c in 0..D {
            let tol = 1e-9 * e[c].abs().max(1.0);
            assert!(
                (g[c] - e[c]).abs() <= tol,
                "{what}: control point {i} coordinate {c}: {} vs {}",
                g[c],
                e[c]
            );
        }
    }
}

fn named(kind: &str) -> Parametrization<f64> {
    match kind {
        "uniform" => Parametrization::Uniform,
        "chordal" => Parametrization::Chordal,
        "centripetal" => Parametrization::Centripetal,
        other => panic!("unknown parametrization {other}"),
    }
}

fn run_interpolate<const D: usize>(case: &Value) {
    let name = case["name"].as_str().unwrap();
    assert_eq!(case["knots"], "averaging");
    let pts = points::<D>(&rows(&case["points"]));
    let degree = case["degree"].as_u64().unwrap() as usize;
    let options = InterpolationOptions {
        parametrization: named(case["parametrization"].as_str().unwrap()),
        knots: KnotChoice::Averaging,
        ..InterpolationOptions::default()
    };
    let fit = interpolate(&pts, degree, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_curve(&fit.curve, &case["expected"], name);
    assert!(fit.deviation.max < 1e-9, "{name}: {}", fit.deviation.max);
}

#[test]
fn interpolation_reference_cases() {
    for case in cases("interpolate") {
        match case["points"][0].as_array().unwrap().len() {
            2 => run_interpolate::<2>(&case),
            3 => run_interpolate::<3>(&case),
            d => panic!("dimension {d}"),
        }
    }
}

fn run_lsq<const D: usize>(case: &Value, method: LsqMethod) {
    let name = case["name"].as_str().unwrap();
    let pts = points::<D>(&rows(&case["points"]));
    let params = f64s(&case["params"]);
    let degree = case["degree"].as_u64().unwrap() as usize;
    let knots = KnotVector::new(degree, f64s(&case["knots"])).unwrap();
    let weights = case.get("weights").map(f64s);
    let mut problem = LeastSquares::new(&pts, &params, knots).method(method);
    if let Some(w) = &weights {
        problem = problem.weights(w);
    }
    let fit = problem.solve().unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_curve(
        &fit.curve,
        &case["expected"],
        &format!("{name} ({method:?})"),
    );
}

#[test]
fn least_squares_reference_cases_both_methods() {
    for method in [LsqMethod::NormalEquations, LsqMethod::Qr] {
        for case in cases("lsq") {
            match case["points"][0].as_array().unwrap().len() {
                1 => run_lsq::<1>(&case, method),
                2 => run_lsq::<2>(&case, method),
                3 => run_lsq::<3>(&case, method),
                d => panic!("dimension {d}"),
            }
        }
    }
}

#[test]
fn natural_reference_cases() {
    for case in cases("natural") {
        let name = case["name"].as_str().unwrap();
        let x = f64s(&case["x"]);
        let y: Vec<SVector<f64, 1>> = f64s(&case["y"])
            .into_iter()
            .map(SVector::from_element)
            .collect();
        let s = natural_cubic(&x, &y).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_curve(&s, &case["expected"], name);
        // Scalar control points give the same function.
        let ys = f64s(&case["y"]);
        let f = natural_cubic(&x, &ys).unwrap();
        for (a, b) in f.control_points().iter().zip(s.control_points()) {
            assert!((a - b[0]).abs() < 1e-12);
        }
    }
}
