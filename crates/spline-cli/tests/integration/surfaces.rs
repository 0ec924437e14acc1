//! The `spline` tool on NURBS curves and surfaces: every reference case of
//! `tests/data/reference/{nurbs_eval,surface_eval}.json` through `spline eval`, and the helpers
//! shared with `surfaces_make` (the `make` constructions checked for exactness) and
//! `surfaces_operations` (structural operations, `mesh` outputs and errors: exit status 2, one
//! line on standard error, never a panic).

use serde_json::{Value, json};
use spline_testing::compare::assert_close;
use spline_testing::reference::{cases, flatten};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh directory for one test's files, removed when the test ends.
pub struct TempDir(PathBuf);

impl TempDir {
    pub fn join(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl std::ops::Deref for TempDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

pub fn temp_dir(test: &str) -> TempDir {
    let dir =
        std::env::temp_dir().join(format!("spline-cli-surfaces-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    TempDir(dir)
}

pub fn write(dir: &Path, name: &str, value: &Value) -> String {
    let path = dir.join(name);
    std::fs::write(&path, value.to_string()).unwrap();
    path.to_str().unwrap().to_owned()
}

pub struct Output {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

pub fn run(args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_spline"))
        .args(args)
        .output()
        .expect("the spline binary runs");
    Output {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8(out.stdout).unwrap(),
        stderr: String::from_utf8(out.stderr).unwrap(),
    }
}

/// Runs a command that must succeed and print JSON.
pub fn ok(args: &[&str]) -> Value {
    let out = run(args);
    assert_eq!(out.code, 0, "spline {args:?} failed: {}", out.stderr);
    serde_json::from_str(&out.stdout)
        .unwrap_or_else(|e| panic!("spline {args:?}: {e}: {}", out.stdout))
}

/// Runs a command that must fail cleanly; returns the message.
pub fn fails(args: &[&str]) -> String {
    let out = run(args);
    assert_eq!(
        out.code, 2,
        "spline {args:?} should fail with status 2; stdout {}",
        out.stdout
    );
    assert!(
        out.stdout.is_empty(),
        "spline {args:?} printed {}",
        out.stdout
    );
    let lines: Vec<&str> = out.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "spline {args:?}: stderr {:?}", out.stderr);
    assert!(lines[0].starts_with("spline: "), "{}", lines[0]);
    assert!(!out.stderr.contains("panicked"));
    lines[0].to_owned()
}

pub fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

pub fn sub(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

pub fn eval_points(path: &str, at: &Value) -> Vec<Vec<f64>> {
    ok(&["eval", path, "--at", &at.to_string()])
        .as_array()
        .unwrap()
        .iter()
        .map(|d| flatten(if d[0][0].is_array() { &d[0][0] } else { &d[0] }))
        .collect()
}

pub fn params(n: usize) -> Value {
    json!((0..=n).map(|i| i as f64 / n as f64).collect::<Vec<_>>())
}

pub fn grid(n: usize) -> Value {
    let mut uv = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            uv.push(json!([i as f64 / n as f64, j as f64 / n as f64]));
        }
    }
    json!(uv)
}

#[test]
fn reference_nurbs_eval_through_the_tool() {
    let dir = temp_dir("nurbs-eval");
    let all = cases("nurbs_eval");
    assert!(all.len() >= 13);
    for case in &all {
        let name = case["name"].as_str().unwrap();
        let file = write(&dir, &format!("{name}.json"), &case["curve"]);
        let k = case["derivatives"].to_string();
        let got = ok(&[
            "eval",
            &file,
            "--at",
            &case["params"].to_string(),
            "--derivatives",
            &k,
        ]);
        for (i, (g, e)) in got
            .as_array()
            .unwrap()
            .iter()
            .zip(case["expected"].as_array().unwrap())
            .enumerate()
        {
            let e = flatten(e);
            let scale = e.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert_close(
                &flatten(g),
                &e,
                1e-9 * scale,
                &format!("{name} parameter {i}"),
            );
        }
    }
}

#[test]
fn reference_surface_eval_through_the_tool() {
    let dir = temp_dir("surface-eval");
    let all = cases("surface_eval");
    assert!(all.len() >= 12);
    for case in &all {
        let name = case["name"].as_str().unwrap();
        let file = write(&dir, &format!("{name}.json"), &case["surface"]);
        let k = case["derivatives"].to_string();
        let got = ok(&[
            "eval",
            &file,
            "--at",
            &case["params"].to_string(),
            "--derivatives",
            &k,
        ]);
        let got = got.as_array().unwrap();
        assert_eq!(got.len(), case["params"].as_array().unwrap().len());
        for (i, (g, e)) in got
            .iter()
            .zip(case["expected"].as_array().unwrap())
            .enumerate()
        {
            // [k][l][coord] for k, l = 0..=K.
            assert_eq!(g.as_array().unwrap().len(), 3);
            assert_eq!(g[0].as_array().unwrap().len(), 3);
            let e = flatten(e);
            let scale = e.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert_close(
                &flatten(g),
                &e,
                1e-9 * scale,
                &format!("{name} parameter {i}"),
            );
        }
        // The same surface with unit weights is the same surface.
        let mut rational = case["surface"].clone();
        let shape: Vec<Value> = rational["control_points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|row| json!(vec![1.0; row.as_array().unwrap().len()]))
            .collect();
        rational["weights"] = json!(shape);
        let file = write(&dir, &format!("{name}-rational.json"), &rational);
        let got = ok(&[
            "eval",
            &file,
            "--at",
            &case["params"].to_string(),
            "--derivatives",
            &k,
        ]);
        for (g, e) in got
            .as_array()
            .unwrap()
            .iter()
            .zip(case["expected"].as_array().unwrap())
        {
            let e = flatten(e);
            let scale = e.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert_close(
                &flatten(g),
                &e,
                1e-9 * scale,
                &format!("{name} with unit weights"),
            );
        }
    }
}
