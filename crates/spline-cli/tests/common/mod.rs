//! Running the `spline` binary in tests.

#![allow(dead_code, unreachable_pub)]

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The result of one run of the tool.
pub struct Run {
    pub status: i32,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    /// The standard output as JSON, asserting success.
    pub fn json(&self) -> Value {
        assert_eq!(self.status, 0, "stderr: {}", self.stderr);
        serde_json::from_str(&self.stdout)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {}", self.stdout))
    }

    /// Asserts the contract for invalid input: exit status 2, one line on stderr, no panic,
    /// nothing on stdout. Returns the message.
    pub fn assert_clean_error(&self) -> String {
        assert_eq!(
            self.status, 2,
            "expected exit status 2; stdout: {} stderr: {}",
            self.stdout, self.stderr
        );
        assert!(self.stdout.is_empty(), "stdout not empty: {}", self.stdout);
        let lines: Vec<&str> = self.stderr.lines().collect();
        assert_eq!(
            lines.len(),
            1,
            "stderr should be one line: {:?}",
            self.stderr
        );
        assert!(!self.stderr.contains("panicked"), "{}", self.stderr);
        assert!(lines[0].starts_with("spline: "), "{}", lines[0]);
        lines[0].to_owned()
    }
}

/// Runs `spline` with arguments.
pub fn spline(args: &[&str]) -> Run {
    let output: Output = Command::new(env!("CARGO_BIN_EXE_spline"))
        .args(args)
        .output()
        .expect("run spline");
    Run {
        status: output.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

static COUNTER: AtomicUsize = AtomicUsize::new(0);

/// Writes `contents` to a fresh temporary file and returns its path.
pub fn temp_file(name: &str, contents: &str) -> String {
    let dir = std::env::temp_dir().join(format!("spline-cli-tests-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let path = dir.join(format!("{n}-{name}"));
    std::fs::write(&path, contents).expect("write temp file");
    path.to_string_lossy().into_owned()
}

/// The cases of a reference file of the repository.
pub fn cases(name: &str) -> Vec<Value> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/reference")
        .join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let data: Value = serde_json::from_str(&text).expect("reference JSON");
    data["cases"].as_array().expect("cases").clone()
}

/// Flattens nested number arrays.
pub fn flatten(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(items) => items.iter().flat_map(flatten).collect(),
        Value::Number(n) => vec![n.as_f64().expect("f64")],
        other => panic!("not a number array: {other}"),
    }
}

/// Asserts equal shapes (nesting and lengths) and values within `tol` relative to the
/// largest magnitude of `expected`.
pub fn assert_close_json(got: &Value, expected: &Value, tol: f64, what: &str) {
    fn shape(v: &Value) -> String {
        match v {
            Value::Array(items) => format!(
                "[{}]",
                items.iter().map(shape).collect::<Vec<_>>().join(",")
            ),
            _ => "x".into(),
        }
    }
    assert_eq!(shape(got), shape(expected), "{what}: shapes differ");
    let (g, e) = (flatten(got), flatten(expected));
    let scale = e.iter().fold(1f64, |m, x| m.max(x.abs()));
    for (i, (x, y)) in g.iter().zip(&e).enumerate() {
        assert!((x - y).abs() <= tol * scale, "{what}[{i}]: {x} vs {y}");
    }
}

/// Compares exchange-format curves: degree, knots (1e-12 absolute), control points.
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
