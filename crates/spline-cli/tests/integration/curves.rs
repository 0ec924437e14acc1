//! The tool on curves: every reference case of basis, curve_eval, insert, split, derivative and
//! elevate through `spline`, the other curve subcommands, and clean errors for bad input.

use crate::common;

use common::{assert_close_json, assert_same_curve, cases, spline, temp_file};
use serde_json::{Value, json};

fn curve_file(curve: &Value) -> String {
    temp_file("curve.json", &curve.to_string())
}

#[test]
fn reference_basis() {
    for case in cases("basis") {
        let run = spline(&[
            "basis",
            "--degree",
            &case["degree"].to_string(),
            "--knots",
            &case["knots"].to_string(),
            "--at",
            &case["params"].to_string(),
            "--derivatives",
            &case["derivatives"].to_string(),
        ]);
        assert_close_json(
            &run.json(),
            &case["expected"],
            1e-9,
            case["name"].as_str().unwrap(),
        );
    }
}

#[test]
fn reference_curve_eval() {
    for case in cases("curve_eval") {
        let path = curve_file(&case["curve"]);
        let run = spline(&[
            "eval",
            &path,
            "--at",
            &case["params"].to_string(),
            "--derivatives",
            &case["derivatives"].to_string(),
        ]);
        assert_close_json(
            &run.json(),
            &case["expected"],
            1e-9,
            case["name"].as_str().unwrap(),
        );
    }
}

#[test]
fn reference_insert() {
    for case in cases("insert") {
        let path = curve_file(&case["curve"]);
        let run = spline(&[
            "insert",
            &path,
            "--knot",
            &case["knot"].to_string(),
            "--times",
            &case["times"].to_string(),
        ]);
        assert_same_curve(
            &run.json(),
            &case["expected"],
            1e-12,
            case["name"].as_str().unwrap(),
        );
        let knots = json!(vec![
            case["knot"].clone();
            case["times"].as_u64().unwrap() as usize
        ]);
        let run = spline(&["refine", &path, "--knots", &knots.to_string()]);
        assert_same_curve(
            &run.json(),
            &case["expected"],
            1e-12,
            case["name"].as_str().unwrap(),
        );
    }
}

#[test]
fn reference_split() {
    for case in cases("split") {
        let path = curve_file(&case["curve"]);
        let got = spline(&["split", &path, "--at", &case["param"].to_string()]).json();
        let name = case["name"].as_str().unwrap();
        assert_same_curve(&got[0], &case["expected"][0], 1e-12, name);
        assert_same_curve(&got[1], &case["expected"][1], 1e-12, name);
    }
}

#[test]
fn reference_derivative() {
    for case in cases("derivative") {
        let path = curve_file(&case["curve"]);
        let got = spline(&["derivative", &path, "--order", &case["order"].to_string()]).json();
        assert_same_curve(
            &got,
            &case["expected"],
            1e-10,
            case["name"].as_str().unwrap(),
        );
    }
}

#[test]
fn reference_elevate() {
    for case in cases("elevate") {
        let path = curve_file(&case["curve"]);
        let got = spline(&["elevate", &path, "--times", &case["times"].to_string()]).json();
        assert_same_curve(
            &got,
            &case["expected"],
            1e-9,
            case["name"].as_str().unwrap(),
        );
    }
}

fn seed_curve() -> String {
    curve_file(&json!({
        "degree": 3,
        "knots": [0, 0, 0, 0, 1, 2, 3, 3, 3, 3],
        "control_points": [[0.41705, 0.10673], [0.28802, 0.60088], [0.90553, 0.46053], [1.3203, 0.79678], [1.8041, 0.63012], [1.477, 0.13012]]
    }))
}

#[test]
fn remove_bezier_plot_and_stdin() {
    let path = seed_curve();
    // Insert then remove gives the curve back.
    let inserted = spline(&["insert", &path, "--knot", "1.5", "--times", "2"]);
    let inserted_path = temp_file("inserted.json", &inserted.stdout);
    let removed = spline(&["remove", &inserted_path, "--knot", "1.5", "--times", "2"]).json();
    let original: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_same_curve(&removed, &original, 1e-9, "remove");
    // Bézier segments: three cubic pieces on [0,1], [1,2], [2,3].
    let segments = spline(&["bezier", &path]).json();
    let segments = segments.as_array().unwrap();
    assert_eq!(segments.len(), 3);
    assert_eq!(
        segments[1]["knots"],
        json!([1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0])
    );
    // The first segment starts at the first control point.
    assert_eq!(
        segments[0]["control_points"][0],
        original["control_points"][0]
    );
    // SVG with curvature comb.
    let svg = std::env::temp_dir().join(format!("spline-plot-{}.svg", std::process::id()));
    let run = spline(&["plot", &path, "-o", svg.to_str().unwrap(), "--comb"]);
    assert_eq!(run.status, 0, "{}", run.stderr);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.contains("polyline") && text.contains("comb"));
    // Standard input.
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_spline"))
        .args(["eval", "-", "--at", "[0, 3]"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child
        .stdin
        .take()
        .unwrap()
        .write_all(std::fs::read_to_string(&path).unwrap().as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let value: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(value, json!([[[0.41705, 0.10673]], [[1.477, 0.13012]]]));
}

#[test]
fn invalid_input_gives_one_line_and_status_2() {
    let path = seed_curve();
    let bad = |value: Value| curve_file(&value);
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec!["eval".into(), path.clone(), "--at".into(), "[3.5]".into()],
            "outside the domain",
        ),
        (
            vec!["eval".into(), path.clone(), "--at".into(), "[0.5".into()],
            "--at",
        ),
        (
            vec![
                "eval".into(),
                "/nonexistent/curve.json".into(),
                "--at".into(),
                "[0]".into(),
            ],
            "cannot read",
        ),
        (
            vec![
                "eval".into(),
                temp_file("bad.json", "{not json"),
                "--at".into(),
                "[0]".into(),
            ],
            "not valid JSON",
        ),
        (
            vec![
                "eval".into(),
                bad(
                    json!({"degree": 1, "knots": [0, 0, 0.7, 0.5, 1, 1], "control_points": [[0], [1], [2], [3]]}),
                ),
                "--at".into(),
                "[0]".into(),
            ],
            "non-decreasing",
        ),
        (
            vec![
                "eval".into(),
                bad(json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1], [2]]})),
                "--at".into(),
                "[0]".into(),
            ],
            "control points",
        ),
        (
            vec![
                "eval".into(),
                bad(json!({"degree": 5, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]})),
                "--at".into(),
                "[0]".into(),
            ],
            "knots",
        ),
        (
            vec![
                "eval".into(),
                bad(json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 1], [1]]})),
                "--at".into(),
                "[0]".into(),
            ],
            "coordinates",
        ),
        (
            vec![
                "eval".into(),
                bad(json!({"degree": 1, "knots": [0, 0, 1, 1]})),
                "--at".into(),
                "[0]".into(),
            ],
            "control_points",
        ),
        (
            vec!["insert".into(), path.clone(), "--knot".into(), "nan".into()],
            "not finite",
        ),
        (
            vec![
                "insert".into(),
                path.clone(),
                "--knot".into(),
                "1".into(),
                "--times".into(),
                "4".into(),
            ],
            "appears",
        ),
        (
            vec!["remove".into(), path.clone(), "--knot".into(), "1".into()],
            "tolerance",
        ),
        (
            vec!["remove".into(), path.clone(), "--knot".into(), "1.5".into()],
            "not an interior knot",
        ),
        (
            vec!["split".into(), path.clone(), "--at".into(), "3".into()],
            "strictly inside",
        ),
        (
            vec![
                "derivative".into(),
                path.clone(),
                "--order".into(),
                "4".into(),
            ],
            "exceeds the degree",
        ),
        (
            vec![
                "elevate".into(),
                path.clone(),
                "--times".into(),
                "40".into(),
            ],
            "maximum",
        ),
        (
            vec![
                "basis".into(),
                "--degree".into(),
                "2".into(),
                "--knots".into(),
                "[0,0,0,1,1]".into(),
                "--at".into(),
                "[0]".into(),
            ],
            "knots",
        ),
        (
            vec![
                "basis".into(),
                "--degree".into(),
                "1".into(),
                "--knots".into(),
                "[0,0,1,1]".into(),
                "--at".into(),
                "[2]".into(),
            ],
            "outside",
        ),
        (
            vec![
                "eval".into(),
                path.clone(),
                "--at".into(),
                "[0]".into(),
                "--bogus".into(),
            ],
            "unexpected argument",
        ),
        (
            vec![
                "insert".into(),
                path.clone(),
                "--knot".into(),
                "1".into(),
                "--direction".into(),
                "u".into(),
            ],
            "surfaces only",
        ),
    ];
    for (args, needle) in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let message = spline(&args).assert_clean_error();
        assert!(
            message.contains(needle),
            "{args:?}: {message:?} should mention {needle:?}"
        );
    }
}
