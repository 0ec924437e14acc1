//! The fitting subcommands (`interpolate`, `natural`, `approximate`) through the `spline`
//! binary: every reference case of `tests/data/reference/{interpolate,lsq,natural}.json`
//! (scipy), the error contract (exit status 2, one line on stderr), and the extensions.

#![allow(clippy::needless_range_loop, clippy::cast_lossless)]

use serde_json::Value;
use spline_testing::reference::{assert_same_curve, cases, flatten};
use std::path::PathBuf;
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A temporary file that is removed when dropped.
struct TempFile(PathBuf);

impl TempFile {
    fn new(contents: &str) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let path = std::env::temp_dir().join(format!(
            "spline-fit-cli-{}-{}.txt",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::write(&path, contents).expect("write temp file");
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

struct Output {
    status: i32,
    stdout: String,
    stderr: String,
}

fn spline(args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_spline"))
        .args(args)
        .output()
        .expect("run spline");
    Output {
        status: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8(out.stdout).expect("UTF-8 stdout"),
        stderr: String::from_utf8(out.stderr).expect("UTF-8 stderr"),
    }
}

fn json_ok(args: &[&str]) -> Value {
    let out = spline(args);
    assert_eq!(out.status, 0, "spline {args:?} failed: {}", out.stderr);
    serde_json::from_str(&out.stdout).unwrap_or_else(|e| panic!("{e}: {}", out.stdout))
}

/// Exit status 2 and exactly one line on stderr that contains `needle`.
fn fails_with(args: &[&str], needle: &str) {
    let out = spline(args);
    assert_eq!(
        out.status, 2,
        "spline {args:?}: status {} ({})",
        out.status, out.stderr
    );
    assert!(out.stdout.is_empty(), "no output expected: {}", out.stdout);
    let lines: Vec<&str> = out.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "one line expected: {:?}", out.stderr);
    assert!(
        lines[0].contains(needle),
        "message {:?} should mention {needle:?}",
        lines[0]
    );
}

#[test]
fn interpolate_reference_cases() {
    for case in cases("interpolate") {
        let name = case["name"].as_str().unwrap();
        let file = TempFile::new(&case["points"].to_string());
        let degree = case["degree"].to_string();
        let kind = case["parametrization"].as_str().unwrap();
        let got = json_ok(&[
            "interpolate",
            file.path(),
            "--degree",
            &degree,
            "--parametrization",
            kind,
            "--knots",
            "averaging",
        ]);
        assert_same_curve(&got, &case["expected"], 1e-9, name);
    }
}

#[test]
fn interpolate_defaults_are_chordal_and_averaging() {
    let case = cases("interpolate")
        .into_iter()
        .find(|c| c["parametrization"] == "chordal")
        .expect("a chordal case");
    // As a whitespace text file this time.
    let text: String = case["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            flatten(p)
                .iter()
                .map(f64::to_string)
                .collect::<Vec<_>>()
                .join(" ")
                + "\n"
        })
        .collect();
    let file = TempFile::new(&format!("# header line\n{text}"));
    let degree = case["degree"].to_string();
    let got = json_ok(&["interpolate", file.path(), "--degree", &degree]);
    assert_same_curve(&got, &case["expected"], 1e-9, "defaults");
}

#[test]
fn least_squares_reference_cases() {
    for method in ["normal", "qr"] {
        for case in cases("lsq") {
            let name = case["name"].as_str().unwrap();
            let file = TempFile::new(&case["points"].to_string());
            let degree = case["degree"].to_string();
            let params = case["params"].to_string();
            let knots = case["knots"].to_string();
            let mut args = vec![
                "approximate",
                file.path(),
                "--degree",
                &degree,
                "--knots",
                &knots,
                "--parametrization",
                &params,
                "--method",
                method,
            ];
            let weights = case.get("weights").map(Value::to_string);
            if let Some(w) = &weights {
                args.extend(["--weights", w]);
            }
            let got = json_ok(&args);
            assert_same_curve(&got, &case["expected"], 1e-9, &format!("{name} {method}"));
        }
    }
}

#[test]
fn natural_reference_cases() {
    for case in cases("natural") {
        let name = case["name"].as_str().unwrap();
        let (x, y) = (case["x"].to_string(), case["y"].to_string());
        let got = json_ok(&["natural", "--x", &x, "--y", &y]);
        assert_same_curve(&got, &case["expected"], 1e-9, name);
    }
}

#[test]
fn natural_quintic_is_linear_data_reproduced() {
    // Order 6 (quintic): data on a line give the line; knots x0×6, x1…, xn×6.
    let got = json_ok(&[
        "natural",
        "--x",
        "[0,1,2.5,3,4]",
        "--y",
        "[1,3,6,7,9]",
        "--order",
        "6",
    ]);
    assert_eq!(got["degree"], 5);
    // 5 points: x_0 and x_4 six times each, x_1 … x_3 once.
    assert_eq!(flatten(&got["knots"]).len(), 6 + 3 + 6);
    // Control points of the line y = 2x + 1 are its values at the Greville abscissae.
    let knots = flatten(&got["knots"]);
    for (i, c) in flatten(&got["control_points"]).iter().enumerate() {
        let g: f64 = knots[i + 1..=i + 5].iter().sum::<f64>() / 5.0;
        assert!((c - (2.0 * g + 1.0)).abs() < 1e-12, "{i}: {c}");
    }
}

#[test]
fn approximate_with_control_points_uses_nurbs_book_knots() {
    // 11 parameters (m = 10), 5 control points (n = 4) of degree 2: d = (m + 1)/(n − p + 1)
    // = 11/3 (The NURBS Book (9.69)).
    let points: Vec<[f64; 2]> = (0..=10)
        .map(|k| [f64::from(k), (f64::from(k) * 0.7).sin()])
        .collect();
    let file = TempFile::new(&serde_json::to_string(&points).unwrap());
    let got = json_ok(&[
        "approximate",
        file.path(),
        "--degree",
        "2",
        "--control-points",
        "5",
        "--parametrization",
        "uniform",
    ]);
    let knots = flatten(&got["knots"]);
    // i = 1: i d = 3.67, j = 3, α = 2/3 → ū_2/3 + 2 ū_3/3 = 0.8/3;
    // i = 2: i d = 7.33, j = 7, α = 1/3 → 2 ū_6/3 + ū_7/3 = 1.9/3.
    let expected = [0.0, 0.0, 0.0, 0.8 / 3.0, 1.9 / 3.0, 1.0, 1.0, 1.0];
    assert_eq!(knots.len(), expected.len());
    for (a, b) in knots.iter().zip(expected) {
        assert!((a - b).abs() < 1e-12, "{knots:?}");
    }
}

#[test]
fn approximate_with_parameter_correction_reports_monotone_errors() {
    let points: Vec<[f64; 2]> = (0..=40)
        .map(|k| {
            let t = f64::from(k) / 40.0;
            let s = t * t; // uneven spacing along the curve
            [3.0 * s, (4.0 * s).sin()]
        })
        .collect();
    let file = TempFile::new(&serde_json::to_string(&points).unwrap());
    let got = json_ok(&[
        "approximate",
        file.path(),
        "--degree",
        "3",
        "--control-points",
        "7",
        "--parametrization",
        "uniform",
        "--correct-parameters",
        "30",
        "--report",
    ]);
    let errors = flatten(&got["correction"]["errors"]);
    assert!(errors.len() >= 2);
    assert!(errors.windows(2).all(|e| e[1] <= e[0]), "{errors:?}");
    assert!(errors[errors.len() - 1] < 0.5 * errors[0], "{errors:?}");
    assert!(got["max_deviation"].as_f64().unwrap() >= 0.0);
    assert!(got["curve"]["knots"].is_array());
}

#[test]
fn closed_interpolation_passes_through_the_points() {
    let file = TempFile::new("1 0\n0 1\n-1 0\n0 -1\n");
    let got = json_ok(&[
        "interpolate",
        file.path(),
        "--degree",
        "3",
        "--closed",
        "--report",
    ]);
    assert!(got["max_deviation"].as_f64().unwrap() < 1e-12);
    let cp = got["curve"]["control_points"].as_array().unwrap();
    assert_eq!(cp.len(), 4 + 3);
    for k in 0..3 {
        assert_eq!(cp[k], cp[4 + k], "wrapped control point {k}");
    }
}

#[test]
fn end_derivatives_add_control_points() {
    let file = TempFile::new("[[0,0],[1,1],[2,0],[3,1]]");
    let got = json_ok(&[
        "interpolate",
        file.path(),
        "--degree",
        "3",
        "--parametrization",
        "uniform",
        "--start-derivative",
        "[3,0]",
        "--end-derivative",
        "[0,-3]",
    ]);
    let cp = got["control_points"].as_array().unwrap();
    assert_eq!(cp.len(), 6);
    // Clamped: C'(0) = p (P_1 − P_0)/(u_{p+1} − u_1).
    let k = flatten(&got["knots"]);
    let (p0, p1) = (flatten(&cp[0]), flatten(&cp[1]));
    let scale = 3.0 / (k[4] - k[1]);
    assert!(((p1[0] - p0[0]) * scale - 3.0).abs() < 1e-12);
    assert!(((p1[1] - p0[1]) * scale).abs() < 1e-12);
}

#[test]
fn fixed_coordinates_are_kept() {
    let points: Vec<[f64; 2]> = (0..=10)
        .map(|k| {
            let t = std::f64::consts::PI * (1.0 - f64::from(k) / 10.0);
            [0.5 + 0.5 * t.cos(), 0.5 * t.sin()]
        })
        .collect();
    let file = TempFile::new(&serde_json::to_string(&points).unwrap());
    let got = json_ok(&[
        "approximate",
        file.path(),
        "--degree",
        "3",
        "--control-points",
        "11",
        "--fix",
        "[[0,0,0],[1,0,0],[0,1,0],[10,1,0],[10,0,1]]",
    ]);
    let cp = got["control_points"].as_array().unwrap();
    assert_eq!(flatten(&cp[0]), vec![0.0, 0.0]);
    assert_eq!(flatten(&cp[1])[0], 0.0);
    assert_eq!(flatten(&cp[10]), vec![1.0, 0.0]);
}

#[test]
fn schoenberg_whitney_violation_is_an_error() {
    let file = TempFile::new("0 0\n0.1 1\n0.2 0\n0.9 1\n1 0\n");
    // N_2 (support [0.3, 0.7]) gets no parameter.
    fails_with(
        &[
            "approximate",
            file.path(),
            "--degree",
            "1",
            "--knots",
            "[0,0,0.3,0.5,0.7,1,1]",
            "--parametrization",
            "[0,0.1,0.2,0.9,1]",
        ],
        "Schoenberg–Whitney",
    );
    fails_with(
        &[
            "interpolate",
            file.path(),
            "--degree",
            "1",
            "--knots",
            "[0,0,0.05,0.1,0.15,1,1]",
            "--parametrization",
            "[0,0.1,0.2,0.9,1]",
        ],
        "Schoenberg–Whitney",
    );
}

#[test]
fn duplicate_points_under_chordal_parameters_are_an_error() {
    let file = TempFile::new("0 0\n1 1\n1 1\n2 0\n");
    fails_with(&["interpolate", file.path(), "--degree", "2"], "coincide");
    fails_with(
        &[
            "approximate",
            file.path(),
            "--degree",
            "1",
            "--control-points",
            "3",
            "--parametrization",
            "centripetal",
        ],
        "coincide",
    );
    // Uniform parameters accept them.
    let ok = spline(&[
        "interpolate",
        file.path(),
        "--degree",
        "2",
        "--parametrization",
        "uniform",
    ]);
    assert_eq!(ok.status, 0, "{}", ok.stderr);
}

#[test]
fn too_few_points_are_an_error() {
    let file = TempFile::new("0 0\n1 1\n2 0\n");
    fails_with(&["interpolate", file.path(), "--degree", "3"], "at least 4");
    fails_with(
        &[
            "approximate",
            file.path(),
            "--degree",
            "2",
            "--control-points",
            "5",
        ],
        "at least 5",
    );
    fails_with(&["natural", "--x", "[0]", "--y", "[1]"], "at least 2");
}

#[test]
fn nan_input_is_an_error() {
    let file = TempFile::new("0 0\n1 NaN\n2 0\n");
    fails_with(&["interpolate", file.path(), "--degree", "1"], "not finite");
    fails_with(&["natural", "--x", "[0,1,2]", "--y", "[0,1e999,2]"], "");
    let good = TempFile::new("0 0\n1 1\n2 0\n");
    fails_with(
        &[
            "approximate",
            good.path(),
            "--degree",
            "1",
            "--control-points",
            "2",
            "--weights",
            "[1,-1,1]",
        ],
        "weight 1",
    );
}

#[test]
fn unsorted_given_parameters_are_an_error() {
    let file = TempFile::new("0 0\n1 1\n2 0\n3 1\n");
    fails_with(
        &[
            "interpolate",
            file.path(),
            "--degree",
            "2",
            "--parametrization",
            "[0,0.6,0.5,1]",
        ],
        "non-decreasing",
    );
    fails_with(
        &[
            "approximate",
            file.path(),
            "--degree",
            "1",
            "--control-points",
            "2",
            "--parametrization",
            "[0,0.6,0.5,1]",
        ],
        "non-decreasing",
    );
    fails_with(
        &["natural", "--x", "[0,2,1]", "--y", "[0,1,2]"],
        "non-decreasing",
    );
}

#[test]
fn malformed_point_files_are_an_error() {
    let ragged = TempFile::new("0 0\n1 1 1\n2 0\n");
    fails_with(&["interpolate", ragged.path(), "--degree", "1"], "line 2");
    let broken = TempFile::new("[[0, 0], [1, ");
    fails_with(&["interpolate", broken.path(), "--degree", "1"], "JSON");
    let empty = TempFile::new("# nothing here\n");
    fails_with(
        &[
            "approximate",
            empty.path(),
            "--degree",
            "1",
            "--control-points",
            "2",
        ],
        "no points",
    );
    fails_with(
        &["interpolate", "/nonexistent/points.txt", "--degree", "1"],
        "cannot read",
    );
    let file = TempFile::new("0 0\n1 1\n2 0\n");
    fails_with(
        &[
            "interpolate",
            file.path(),
            "--degree",
            "1",
            "--parametrization",
            "sideways",
        ],
        "--parametrization (or a JSON array): unknown parametrization \"sideways\" (one of uniform, chordal, centripetal)",
    );
    fails_with(
        &[
            "interpolate",
            file.path(),
            "--degree",
            "1",
            "--knots",
            "even",
        ],
        "--knots (or a JSON array): unknown knot placement \"even\" (one of averaging, uniform, nurbs-book)",
    );
}
