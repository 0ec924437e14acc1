//! Shared helpers for the cross-crate tests: loading the reference cases and comparing.

#![allow(dead_code, unreachable_pub)]

use serde_json::Value;
use std::path::PathBuf;

/// The cases of `tests/data/reference/<name>.json`.
pub fn cases(name: &str) -> Vec<Value> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/reference")
        .join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let data: Value = serde_json::from_str(&text).expect("valid JSON");
    data["cases"].as_array().expect("cases").clone()
}

pub fn f64s(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

/// Asserts `|a - b| <= tol * max(1, |b|)` element-wise, with context.
pub fn assert_close(a: &[f64], b: &[f64], tol: f64, what: &str) {
    assert_eq!(
        a.len(),
        b.len(),
        "{what}: lengths {} vs {}",
        a.len(),
        b.len()
    );
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        let scale = 1f64.max(y.abs());
        assert!(
            (x - y).abs() <= tol * scale,
            "{what}[{i}]: got {x}, expected {y} (diff {:.3e})",
            (x - y).abs()
        );
    }
}

/// Flattens nested JSON number arrays.
pub fn flatten(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(items) => items.iter().flat_map(flatten).collect(),
        Value::Number(n) => vec![n.as_f64().expect("f64")],
        other => panic!("not a number array: {other}"),
    }
}

/// Compares two exchange-format curve objects: degree equal, knots within 1e-12 absolute,
/// control points within `tol` relative.
pub fn assert_same_curve(got: &Value, expected: &Value, tol: f64, what: &str) {
    assert_eq!(got["degree"], expected["degree"], "{what}: degree");
    let (gk, ek) = (flatten(&got["knots"]), flatten(&expected["knots"]));
    assert_eq!(
        gk.len(),
        ek.len(),
        "{what}: number of knots {gk:?} vs {ek:?}"
    );
    for (i, (x, y)) in gk.iter().zip(&ek).enumerate() {
        assert!((x - y).abs() <= 1e-12, "{what}: knot {i}: {x} vs {y}");
    }
    assert_close(
        &flatten(&got["control_points"]),
        &flatten(&expected["control_points"]),
        tol,
        &format!("{what}: control points"),
    );
}
