//! The reference cases computed by scipy (`tests/data/reference/<name>.json`, see the
//! README there), and helpers to read their JSON.

use serde_json::Value;
use std::path::PathBuf;

/// The directory of the reference cases.
#[must_use]
pub fn directory() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/reference")
}

/// The cases of `tests/data/reference/<name>.json` (at least one).
///
/// # Panics
/// If the file cannot be read, is not JSON, or holds no cases.
#[must_use]
pub fn cases(name: &str) -> Vec<Value> {
    let path = directory().join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let data: Value = serde_json::from_str(&text).expect("valid reference JSON");
    let cases = data["cases"].as_array().expect("a list of cases").clone();
    assert!(!cases.is_empty(), "{name}: no cases");
    cases
}

/// The numbers of a JSON array.
///
/// # Panics
/// If `v` is not an array of numbers.
#[must_use]
pub fn f64s(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

/// The numbers of nested JSON arrays, in order.
///
/// # Panics
/// If `v` holds anything but numbers and arrays.
#[must_use]
pub fn flatten(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(items) => items.iter().flat_map(flatten).collect(),
        Value::Number(n) => vec![n.as_f64().expect("a finite number")],
        other => panic!("not a number array: {other}"),
    }
}

/// The nesting of a JSON value (`[[x,x],[x]]`), to compare shapes.
#[must_use]
pub fn shape(v: &Value) -> String {
    match v {
        Value::Array(items) => format!(
            "[{}]",
            items.iter().map(shape).collect::<Vec<_>>().join(",")
        ),
        _ => "x".into(),
    }
}

/// Asserts equal shapes and values within `tol` relative to the largest magnitude of
/// `expected` (at least 1).
///
/// # Panics
/// When they differ.
pub fn assert_close_json(got: &Value, expected: &Value, tol: f64, what: &str) {
    assert_eq!(shape(got), shape(expected), "{what}: shapes differ");
    crate::compare::assert_close_scaled(&flatten(got), &flatten(expected), tol, what);
}

/// Compares exchange-format curves: equal degrees, knots within 1e-12 (relative to the
/// largest, at least 1), control points within `tol` relative.
///
/// # Panics
/// When they differ.
pub fn assert_same_curve(got: &Value, expected: &Value, tol: f64, what: &str) {
    assert_eq!(got["degree"], expected["degree"], "{what}: degree");
    assert_close_json(
        &got["knots"],
        &expected["knots"],
        1e-12,
        &format!("{what}: knots"),
    );
    assert_close_json(
        &got["control_points"],
        &expected["control_points"],
        tol,
        &format!("{what}: control points"),
    );
}
