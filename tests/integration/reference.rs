//! Every reference case of `tests/data/reference/` (computed by scipy.interpolate) through the
//! library: basis functions, evaluation with derivatives, insertion, splitting, derivative
//! curves, degree elevation.

use nalgebra::SVector;
use serde_json::{Value, json};
use spline::core::KnotVector;
use spline::geom::BSpline;
use spline::io::exchange::{self, CurveRecord};
use spline_testing::compare::assert_close;
use spline_testing::reference::{assert_same_curve, cases, f64s, flatten};

fn record(v: &Value) -> CurveRecord {
    serde_json::from_value(v.clone()).expect("curve record")
}

/// Runs `$body` with `$curve: BSpline<f64, SVector<f64, D>>` for the case's dimension.
macro_rules! with_curve {
    ($value:expr, |$curve:ident| $body:expr) => {{
        let rec = record($value);
        match rec.dimension().unwrap() {
            1 => {
                let $curve: BSpline<f64, SVector<f64, 1>> = rec.to_bspline().unwrap();
                $body
            }
            2 => {
                let $curve: BSpline<f64, SVector<f64, 2>> = rec.to_bspline().unwrap();
                $body
            }
            3 => {
                let $curve: BSpline<f64, SVector<f64, 3>> = rec.to_bspline().unwrap();
                $body
            }
            d => panic!("dimension {d} not covered"),
        }
    }};
}

fn to_json<const D: usize>(c: &BSpline<f64, SVector<f64, D>>) -> Value {
    exchange::to_value(c)
}

#[test]
fn basis_functions_and_derivatives() {
    let all = cases("basis");
    assert!(!all.is_empty());
    for case in &all {
        let name = case["name"].as_str().unwrap();
        let degree = case["degree"].as_u64().unwrap() as usize;
        let knots = KnotVector::new(degree, f64s(&case["knots"])).unwrap();
        let order = case["derivatives"].as_u64().unwrap() as usize;
        for (u, expected) in f64s(&case["params"])
            .iter()
            .zip(case["expected"].as_array().unwrap())
        {
            let rows = knots.dense_basis_derivatives(*u, order).unwrap();
            for (k, row) in rows.iter().enumerate() {
                let scale = 1f64.max(f64s(&expected[k]).iter().fold(0.0, |m, x| m.max(x.abs())));
                assert_close(
                    row,
                    &f64s(&expected[k]),
                    1e-9 * scale,
                    &format!("{name} u={u} k={k}"),
                );
            }
        }
    }
}

#[test]
fn curve_evaluation_with_derivatives() {
    for case in &cases("curve_eval") {
        let name = case["name"].as_str().unwrap();
        let order = case["derivatives"].as_u64().unwrap() as usize;
        let params = f64s(&case["params"]);
        with_curve!(&case["curve"], |curve| {
            for (u, expected) in params.iter().zip(case["expected"].as_array().unwrap()) {
                let ders = curve.derivatives(*u, order).unwrap();
                let flat: Vec<f64> = ders.iter().flat_map(|p| p.iter().copied()).collect();
                let exp = flatten(expected);
                let scale = 1f64.max(exp.iter().fold(0.0, |m, x| m.max(x.abs())));
                assert_close(&flat, &exp, 1e-9 * scale, &format!("{name} u={u}"));
                // de Boor and basis form agree on the point itself.
                let p = curve.de_boor(*u).unwrap();
                assert_close(
                    p.as_slice(),
                    &exp[..p.len()],
                    1e-12,
                    &format!("{name} de Boor u={u}"),
                );
            }
        });
    }
}

#[test]
fn knot_insertion() {
    for case in &cases("insert") {
        let name = case["name"].as_str().unwrap();
        let u = case["knot"].as_f64().unwrap();
        let times = case["times"].as_u64().unwrap() as usize;
        with_curve!(&case["curve"], |curve| {
            let got = curve.insert_knot(u, times).unwrap();
            assert_same_curve(&to_json(&got), &case["expected"], 1e-12, name);
            let refined = curve.refine(&vec![u; times]).unwrap();
            assert_same_curve(
                &to_json(&refined),
                &case["expected"],
                1e-12,
                &format!("{name} (refine)"),
            );
        });
    }
}

#[test]
fn split() {
    for case in &cases("split") {
        let name = case["name"].as_str().unwrap();
        let u = case["param"].as_f64().unwrap();
        with_curve!(&case["curve"], |curve| {
            let (left, right) = curve.split(u).unwrap();
            assert_same_curve(
                &to_json(&left),
                &case["expected"][0],
                1e-12,
                &format!("{name} left"),
            );
            assert_same_curve(
                &to_json(&right),
                &case["expected"][1],
                1e-12,
                &format!("{name} right"),
            );
        });
    }
}

#[test]
fn derivative_curve() {
    for case in &cases("derivative") {
        let name = case["name"].as_str().unwrap();
        let order = case["order"].as_u64().unwrap() as usize;
        with_curve!(&case["curve"], |curve| {
            let got = curve.derivative(order).unwrap();
            let scale = 1f64.max(
                flatten(&case["expected"]["control_points"])
                    .iter()
                    .fold(0.0, |m, x| m.max(x.abs())),
            );
            assert_same_curve(&to_json(&got), &case["expected"], 1e-10 * scale, name);
        });
    }
}

#[test]
fn degree_elevation() {
    for case in &cases("elevate") {
        let name = case["name"].as_str().unwrap();
        let times = case["times"].as_u64().unwrap() as usize;
        with_curve!(&case["curve"], |curve| {
            let got = curve.elevate_degree(times).unwrap();
            assert_same_curve(&to_json(&got), &case["expected"], 1e-9, name);
        });
    }
}

#[test]
fn serialisation_round_trip() {
    for case in &cases("curve_eval") {
        with_curve!(&case["curve"], |curve| {
            let text = exchange::to_json(&curve);
            let back = exchange::from_json(&text).unwrap();
            assert_eq!(curve, back);
        });
    }
    let bad = json!({"degree": 1, "knots": [0, 0, 1, "x"], "control_points": [[0], [1]]});
    assert!(serde_json::from_value::<CurveRecord>(bad).is_err());
}
