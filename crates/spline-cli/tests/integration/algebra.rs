//! The algebra subcommands (`product`, `curvature`, `features`) through the `spline` binary:
//! values checked against independent evaluation, the Jacobian format, and the error
//! contract (exit status 2, one line on standard error, never a panic).

#![allow(clippy::needless_range_loop)]

use serde_json::{Value, json};
use spline_geom::BSpline;
use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};

/// A temporary JSON file, removed when dropped.
struct TempFile(PathBuf);

impl TempFile {
    fn new(value: &Value) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let path = std::env::temp_dir().join(format!(
            "spline-algebra-cli-{}-{}.json",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::write(&path, value.to_string()).expect("write temp file");
        Self(path)
    }

    fn path(&self) -> &str {
        self.0.to_str().expect("UTF-8 path")
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// Runs the tool; returns (exit code, stdout, stderr).
fn run(args: &[&str], stdin: Option<&str>) -> (i32, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_spline"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run spline");
    if let Some(text) = stdin {
        child
            .stdin
            .take()
            .unwrap()
            .write_all(text.as_bytes())
            .unwrap();
    }
    drop(child.stdin.take());
    let out = child.wait_with_output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

fn ok_json(args: &[&str]) -> Value {
    let (code, out, err) = run(args, None);
    assert_eq!(code, 0, "spline {args:?} failed: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{out}: {e}"))
}

fn assert_usage_error(args: &[&str], stdin: Option<&str>, needle: &str) {
    let (code, out, err) = run(args, stdin);
    assert_eq!(
        code, 2,
        "spline {args:?}: expected exit 2, got {code}; stderr {err}"
    );
    assert!(out.is_empty(), "no output on error: {out}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "one-line message: {err:?}"
    );
    assert!(err.starts_with("spline: "), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        err.contains(needle),
        "message {err:?} should mention {needle:?}"
    );
}

fn function(value: &Value) -> BSpline<f64, f64> {
    let degree = value["degree"].as_u64().unwrap() as usize;
    let knots: Vec<f64> = value["knots"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k.as_f64().unwrap())
        .collect();
    let points: Vec<f64> = value["control_points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let p = p.as_array().unwrap();
            assert_eq!(p.len(), 1, "1-D control points");
            p[0].as_f64().unwrap()
        })
        .collect();
    BSpline::from_knots(degree, knots, points).unwrap()
}

fn dense(m: &Value) -> Vec<Vec<f64>> {
    let (rows, cols) = (
        m["rows"].as_u64().unwrap() as usize,
        m["cols"].as_u64().unwrap() as usize,
    );
    let mut d = vec![vec![0.0; cols]; rows];
    for e in m["entries"].as_array().unwrap() {
        let e = e.as_array().unwrap();
        assert_eq!(e.len(), 3);
        let (i, j) = (
            e[0].as_u64().unwrap() as usize,
            e[1].as_u64().unwrap() as usize,
        );
        d[i][j] += e[2].as_f64().unwrap();
    }
    d
}

fn factors() -> (Value, Value) {
    (
        json!({"degree": 2, "knots": [0, 0, 0, 0.3, 0.7, 1, 1, 1], "control_points": [[1], [-2], [0.5], [3], [1]]}),
        json!({"degree": 1, "knots": [0, 0, 0.3, 0.5, 1, 1], "control_points": [[2], [0], [1], [-1]]}),
    )
}

#[test]
fn product_evaluates_to_the_product_with_minimal_knots() {
    let (a, b) = factors();
    let (fa, fb) = (TempFile::new(&a), TempFile::new(&b));
    let c = ok_json(&["product", fa.path(), fb.path()]);
    let (ea, eb, ec) = (function(&a), function(&b), function(&c));
    assert_eq!(ec.degree(), 3);
    // 0.3 shared (C^1 and C^0: multiplicity 3 − min(1, 0) = 3), 0.7 of a only (1 + 1 = 2),
    // 0.5 of b only (2 + 1 = 3).
    assert_eq!(
        ec.knots().knots(),
        &[
            0., 0., 0., 0., 0.3, 0.3, 0.3, 0.5, 0.5, 0.5, 0.7, 0.7, 1., 1., 1., 1.
        ]
    );
    for i in 0..=200 {
        let u = f64::from(i) / 200.0;
        let expected = ea.eval(u).unwrap() * eb.eval(u).unwrap();
        assert!((ec.eval(u).unwrap() - expected).abs() < 1e-13, "u = {u}");
    }
    // Standard input for one factor.
    let (code, out, err) = run(&["product", "-", fb.path()], Some(&a.to_string()));
    assert_eq!(code, 0, "{err}");
    let from_stdin: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(from_stdin, c);
}

#[test]
fn product_jacobians() {
    let (a, b) = factors();
    let (fa, fb) = (TempFile::new(&a), TempFile::new(&b));
    let out = ok_json(&["product", fa.path(), fb.path(), "--jacobian"]);
    let c = function(&out["product"]);
    let (ea, eb) = (function(&a), function(&b));
    let ja = dense(&out["jacobian_a"]);
    let jb = dense(&out["jacobian_b"]);
    assert_eq!((ja.len(), ja[0].len()), (c.control_points().len(), 5));
    assert_eq!((jb.len(), jb[0].len()), (c.control_points().len(), 4));
    // The product is bilinear: c = J_a a = J_b b, and J_a depends on b only.
    for (k, &ck) in c.control_points().iter().enumerate() {
        let via_a: f64 = ja[k]
            .iter()
            .zip(ea.control_points())
            .map(|(x, y)| x * y)
            .sum();
        let via_b: f64 = jb[k]
            .iter()
            .zip(eb.control_points())
            .map(|(x, y)| x * y)
            .sum();
        assert!((via_a - ck).abs() < 1e-13 && (via_b - ck).abs() < 1e-13);
    }
    // Column j of J_a: the product with a replaced by the unit vector e_j.
    for j in 0..5 {
        let mut unit = a.clone();
        for (i, p) in unit["control_points"]
            .as_array_mut()
            .unwrap()
            .iter_mut()
            .enumerate()
        {
            *p = json!([if i == j { 1.0 } else { 0.0 }]);
        }
        let fu = TempFile::new(&unit);
        let cj = function(&ok_json(&["product", fu.path(), fb.path()]));
        for (k, &v) in cj.control_points().iter().enumerate() {
            assert!((ja[k][j] - v).abs() < 1e-14);
        }
    }
}

#[test]
fn curvature_of_curves() {
    // y = x² at x = 0: curvature 2; at x = 1: 2 / 5^{3/2}.
    let parabola = json!({"degree": 2, "knots": [-1, -1, -1, 1, 1, 1], "control_points": [[-1, 1], [0, -1], [1, 1]]});
    let f = TempFile::new(&parabola);
    let k = ok_json(&["curvature", f.path(), "--at", "[-1, 0, 1]"]);
    let k: Vec<f64> = k
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!((k[1] - 2.0).abs() < 1e-14);
    assert!((k[2] - 2.0 / 5f64.powf(1.5)).abs() < 1e-14 && (k[0] - k[2]).abs() < 1e-14);
    // A NURBS quarter circle of radius 2: curvature 1/2 everywhere (counter-clockwise).
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let arc = json!({"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control_points": [[2, 0], [2, 2], [0, 2]], "weights": [1, h, 1]});
    let f = TempFile::new(&arc);
    let k = ok_json(&["curvature", f.path(), "--at", "[0, 0.25, 0.5, 1]"]);
    for v in k.as_array().unwrap() {
        assert!((v.as_f64().unwrap() - 0.5).abs() < 1e-14, "{k}");
    }
}

#[test]
fn features_of_known_curves() {
    let cubic = json!({"degree": 3, "knots": [-1, -1, -1, -1, 1, 1, 1, 1],
        "control_points": [[-1, 0], [-0.3333333333333333, 1.3333333333333333], [0.3333333333333333, -1.3333333333333333], [1, 0]]});
    let f = TempFile::new(&cubic);
    let out = ok_json(&["features", f.path()]);
    let inflections = out["inflections"].as_array().unwrap();
    assert_eq!(inflections.len(), 1);
    assert!(inflections[0].as_f64().unwrap().abs() < 1e-12);
    // Curvature extrema of y = x³ − x: κ′ = 0 at |u| = 0.6186898…, found by sampling.
    let extrema: Vec<f64> = out["curvature_extrema"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(extrema.len(), 2);
    assert!(
        (extrema[0] + 0.618_689_873_133_7).abs() < 1e-9
            && (extrema[1] - 0.618_689_873_133_7).abs() < 1e-9
    );

    let points: Vec<Value> = (0..11)
        .map(|k| {
            let t = f64::from(k) * std::f64::consts::FRAC_PI_4;
            json!([2.0 * t.cos(), t.sin()])
        })
        .collect();
    let ellipse =
        json!({"degree": 3, "knots": (0..=14).collect::<Vec<_>>(), "control_points": points});
    let f = TempFile::new(&ellipse);
    let out = ok_json(&["features", f.path()]);
    assert!(out["inflections"].as_array().unwrap().is_empty());
    assert_eq!(
        out["curvature_extrema"].as_array().unwrap().len(),
        8,
        "{out}"
    );
}

/// NURBS and 3-D curves: a circle reports its constant curvature (and, in space, zero
/// torsion); the twisted cubic `(u, u², u³)` on [−1, 1] has one curvature extremum at 0
/// and no torsion zero; `(u, u², u⁴)` one torsion zero at 0.
#[test]
fn features_of_nurbs_and_space_curves() {
    let circle = run(
        &["make", "circle", "--center", "[1, 2]", "--radius", "4"],
        None,
    )
    .1;
    let (code, stdout, _) = run(&["features", "-"], Some(&circle));
    assert_eq!(code, 0);
    let out: Value = serde_json::from_str(&stdout).unwrap();
    assert!(
        (out["constant_curvature"].as_f64().unwrap().abs() - 0.25).abs() < 1e-12,
        "{out}"
    );
    assert!(out["curvature_extrema"].as_array().unwrap().is_empty());
    let circle3 = run(
        &[
            "make",
            "circle",
            "--center",
            "[1, 2, 3]",
            "--normal",
            "[1, 1, 1]",
            "--radius",
            "2",
        ],
        None,
    )
    .1;
    let (code, stdout, _) = run(&["features", "-"], Some(&circle3));
    assert_eq!(code, 0);
    let out: Value = serde_json::from_str(&stdout).unwrap();
    assert!(
        (out["constant_curvature"].as_f64().unwrap() - 0.5).abs() < 1e-12,
        "{out}"
    );
    assert_eq!(out["constant_torsion"], json!(0.0));
    let third = 1.0 / 3.0;
    let twisted = TempFile::new(&json!({"degree": 3, "knots": [-1, -1, -1, -1, 1, 1, 1, 1],
        "control_points": [[-1, 1, -1], [-third, -third, 1], [third, -third, -1], [1, 1, 1]]}));
    let out = ok_json(&["features", twisted.path()]);
    assert!(out["torsion_zeros"].as_array().unwrap().is_empty(), "{out}");
    let extrema = out["curvature_extrema"].as_array().unwrap();
    assert_eq!(extrema.len(), 1, "{out}");
    assert!(extrema[0].as_f64().unwrap().abs() < 1e-12);
    // (u, u², u⁴) on [0, 1] shifted to [−1, 1]: Bernstein points of (u, u², u⁴) on [−1, 1].
    let quartic = TempFile::new(
        &json!({"degree": 4, "knots": [-1, -1, -1, -1, -1, 1, 1, 1, 1, 1],
        "control_points": [[-1, 1, 1], [-0.5, 0, -1], [0, -third, 1], [0.5, 0, -1], [1, 1, 1]]}),
    );
    let out = ok_json(&["features", quartic.path()]);
    let zeros = out["torsion_zeros"].as_array().unwrap();
    assert_eq!(zeros.len(), 1, "{out}");
    assert!(zeros[0].as_f64().unwrap().abs() < 1e-12);
}

#[test]
fn errors_exit_2_with_one_line() {
    let (a, b) = factors();
    let fa = TempFile::new(&a);
    let planar = TempFile::new(
        &json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0], [1, 1]]}),
    );
    let other_domain =
        TempFile::new(&json!({"degree": 1, "knots": [0, 0, 2, 2], "control_points": [[0], [1]]}));
    let spatial = TempFile::new(
        &json!({"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control_points": [[0, 0, 0], [1, 1, 0], [2, 0, 1]]}),
    );
    let cusp = TempFile::new(
        &json!({"degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 1], "control_points": [[0, 0], [1, 1], [0, 1], [1, 0]]}),
    );
    let bad_knots =
        TempFile::new(&json!({"degree": 1, "knots": [0, 1, 0.5, 1], "control_points": [[0], [1]]}));
    let _ = b;
    assert_usage_error(&["product", fa.path(), planar.path()], None, "1-D");
    assert_usage_error(
        &["product", fa.path(), other_domain.path()],
        None,
        "same domain",
    );
    assert_usage_error(
        &["product", fa.path(), bad_knots.path()],
        None,
        "non-decreasing",
    );
    assert_usage_error(
        &["product", fa.path(), "/nonexistent/file.json"],
        None,
        "cannot read",
    );
    assert_usage_error(
        &["product", fa.path(), "-"],
        Some("{not json"),
        "not valid JSON",
    );
    assert_usage_error(
        &["curvature", planar.path(), "--at", "[2]"],
        None,
        "outside the domain",
    );
    assert_usage_error(
        &["curvature", spatial.path(), "--at", "[0.5]"],
        None,
        "planar",
    );
    assert_usage_error(
        &["curvature", cusp.path(), "--at", "[0.5]"],
        None,
        "zero velocity",
    );
    assert_usage_error(&["curvature", planar.path(), "--at", "0.5,"], None, "--at");
    let spatial_line = TempFile::new(
        &json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0, 0], [1, 1, 0]]}),
    );
    assert_usage_error(&["features", spatial_line.path()], None, "degree");
    assert_usage_error(&["features", planar.path()], None, "degree");
    assert_usage_error(&["features", cusp.path()], None, "not regular");
    assert_usage_error(&["features", fa.path()], None, "planar");
}
