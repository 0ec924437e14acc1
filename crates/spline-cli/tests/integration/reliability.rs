//! Regression tests of issue 9 (reliability): every command of the fuzzing campaign that
//! panicked, aborted, hung, printed a wrong answer or refused legal input, with the exact
//! expected answer. Numbers are checked against independent computations (closed forms,
//! the unscaled problem, interpolation conditions).

use crate::common;

use common::{Run, spline, temp_file};
use serde_json::Value;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const LINE: &str =
    r#"{"degree":1,"knots":[0.0,0.0,1.0,1.0],"control_points":[[0.0,0.0],[1.0,1.0]]}"#;

fn line() -> String {
    temp_file("line.json", LINE)
}

fn made(args: &[&str], name: &str) -> String {
    let run = spline(args);
    assert_eq!(run.status, 0, "{}", run.stderr);
    temp_file(name, &run.stdout)
}

fn sphere() -> String {
    made(
        &["make", "sphere", "--center", "[0,0,0]", "--radius", "1"],
        "sphere.json",
    )
}

/// Asserts a clean error (status 2, one line, nothing on stdout) with exactly this message.
fn assert_message(run: &Run, expected: &str) {
    let message = run.assert_clean_error();
    assert_eq!(message, format!("spline: {expected}"));
}

/// Whether a text holds `NaN` or an infinity as a word.
fn has_non_finite(text: &str) -> bool {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .any(|w| ["nan", "inf", "infinity"].contains(&w.to_ascii_lowercase().as_str()))
}

/// Runs the tool and asserts that it finished within `limit`.
fn quick(args: &[&str], limit: Duration) -> Run {
    let start = Instant::now();
    let run = spline(args);
    assert!(
        start.elapsed() < limit,
        "{args:?} took {:?}",
        start.elapsed()
    );
    run
}

// ---------------------------------------------------------------------------------------
// Panics and aborts.

/// Found by the campaign of 2026-12-01 (seed 20261201): `smooth --curvature-extrema` with an
/// absurd count allocated one slot an extremum before anything was checked.
#[test]
fn smooth_with_absurd_extrema_counts_is_refused_before_allocating() {
    let points = temp_file(
        "arc_points.json",
        "[[0.0,0.0],[0.3,0.4],[0.6,0.5],[1.0,0.45],[1.3,0.3],[1.5,0.0]]",
    );
    for k in ["1000000000", "4294967296", "9223372036854775807"] {
        let run = quick(
            &[
                "smooth",
                &points,
                "--control-points",
                "12",
                "--curvature-extrema",
                k,
            ],
            Duration::from_secs(5),
        );
        assert_message(
            &run,
            &format!("--curvature-extrema: at most 1000 extrema can be allowed, got {k}"),
        );
    }
}

#[test]
fn insert_with_absurd_times_is_refused_before_allocating() {
    let path = line();
    for times in ["18446744073709551615", "1000000000"] {
        let run = quick(
            &["insert", &path, "--knot", "0.5", "--times", times],
            Duration::from_secs(5),
        );
        assert_message(
            &run,
            &format!(
                "knot 0.5 appears 0 time(s) and a degree-1 spline allows at most 2: it can be inserted at most 2 more times, not {times}"
            ),
        );
    }
}

#[test]
fn derivative_orders_above_the_limit_are_refused() {
    let path = line();
    let run = spline(&[
        "eval",
        &path,
        "--at",
        "[0.5]",
        "--derivatives",
        "9223372036854775807",
    ]);
    assert_message(
        &run,
        "--derivatives: derivative order 9223372036854775807 is above the supported maximum 1000",
    );
    let sphere = sphere();
    for order in ["1000000000", "100000"] {
        let run = quick(
            &[
                "eval",
                &sphere,
                "--at",
                "[[0.5,0.5]]",
                "--derivatives",
                order,
            ],
            Duration::from_secs(5),
        );
        assert_message(
            &run,
            &format!("--derivatives: derivative order {order} is above the supported maximum 1000"),
        );
    }
    let run = spline(&[
        "basis",
        "--degree",
        "1",
        "--knots",
        "[0,0,1,1]",
        "--at",
        "[0.5]",
        "--derivatives",
        "18446744073709551615",
    ]);
    assert_message(
        &run,
        "--derivatives: derivative order 18446744073709551615 is above the supported maximum 1000",
    );
}

#[test]
fn derivative_orders_above_the_degree_are_zero_and_cheap() {
    // A line: C = (u, u), C' = (1, 1), every higher derivative zero; order 1000 is the limit.
    let path = line();
    let run = quick(
        &["eval", &path, "--at", "[0.25]", "--derivatives", "1000"],
        Duration::from_secs(5),
    );
    let rows = run.json();
    let rows = rows[0].as_array().unwrap();
    assert_eq!(rows.len(), 1001);
    assert_eq!(rows[0], serde_json::json!([0.25, 0.25]));
    assert_eq!(rows[1], serde_json::json!([1.0, 1.0]));
    assert!(
        rows[2..]
            .iter()
            .all(|r| r == &serde_json::json!([0.0, 0.0]))
    );
}

#[test]
fn mesh_segments_are_limited_and_a_bad_output_path_fails_at_once() {
    let sphere = sphere();
    for segments in ["18446744073709551615", "10000000", "100000"] {
        let run = quick(
            &[
                "mesh",
                &sphere,
                "-o",
                &temp_file("m.obj", ""),
                "--segments-u",
                segments,
            ],
            Duration::from_secs(5),
        );
        assert_message(
            &run,
            &format!(
                "{segments} segments in one direction are more than the supported maximum 1000"
            ),
        );
    }
    let run = quick(
        &[
            "mesh",
            &sphere,
            "-o",
            "/nonexistent-directory/m.obj",
            "--segments-u",
            "1000",
        ],
        Duration::from_secs(2),
    );
    assert_message(
        &run,
        "cannot write /nonexistent-directory/m.obj: No such file or directory (os error 2)",
    );
}

#[test]
fn arcs_with_absurd_piece_counts_are_refused() {
    for (piece, pieces) in [("1e-19", "3.6e21"), ("1e-6", "360000000")] {
        let run = quick(
            &[
                "make",
                "arc",
                "--center",
                "[0,0]",
                "--radius",
                "1",
                "--sweep",
                "360",
                "--max-piece",
                piece,
            ],
            Duration::from_secs(5),
        );
        assert_message(
            &run,
            &format!(
                "--max-piece {piece}: an arc of 360° needs {pieces} pieces of at most {piece}°, more than the supported maximum 1000"
            ),
        );
    }
}

#[test]
fn a_full_disk_is_a_one_line_error() {
    let path = line();
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_spline"))
        .args(["eval", &path, "--at", "[0.5]"])
        .stdout(full)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "spline: cannot write to standard output: No space left on device (os error 28)\n"
    );
}

#[test]
fn a_closed_pipe_ends_quietly() {
    // 20 000 parameters: far more output than a pipe holds, so the tool writes after the
    // reader has gone.
    let path = line();
    let at = format!("[{}]", vec!["0.5"; 20_000].join(","));
    let mut child = Command::new(env!("CARGO_BIN_EXE_spline"))
        .args(["eval", &path, "--at", &at, "--derivatives", "3"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(141));
    assert_eq!(String::from_utf8_lossy(&out.stderr), "");
}

#[test]
fn a_closed_standard_output_is_an_error() {
    let path = line();
    let out = Command::new("bash")
        .arg("-c")
        .arg("\"$0\" eval \"$1\" --at '[0.5]' >&-")
        .arg(env!("CARGO_BIN_EXE_spline"))
        .arg(&path)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "spline: standard output is closed; nothing can be printed\n"
    );
}

// ---------------------------------------------------------------------------------------
// Slow.

#[test]
fn high_order_rational_derivatives_are_fast_and_overflow_cleanly() {
    let circle = made(
        &["make", "circle", "--center", "[0,0]", "--radius", "1"],
        "circle.json",
    );
    for order in ["1000", "500"] {
        let run = quick(
            &["eval", &circle, "--at", "[0.3]", "--derivatives", order],
            Duration::from_secs(2),
        );
        let message = run.assert_clean_error();
        assert!(
            message.starts_with("spline: --at entry 0: the rational derivative of order ")
                && message.ends_with(
                    " is too large for floating point (rational derivatives grow like order!)"
                ),
            "{message}"
        );
    }
    for order in ["3200", "10000"] {
        let run = spline(&["eval", &circle, "--at", "[0.3]", "--derivatives", order]);
        assert_message(
            &run,
            &format!("--derivatives: derivative order {order} is above the supported maximum 1000"),
        );
    }
}

/// The first quarter of the square construction: the rational quadratic Bézier curve
/// (1, 0), (1, 1), (0, 1) with weights 1, √2/2, 1 on u ∈ [0, ¼].
fn quarter(u: f64) -> [f64; 2] {
    let t = 4.0 * u;
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let b = [(1.0 - t) * (1.0 - t), 2.0 * t * (1.0 - t) * w, t * t];
    let den = b[0] + b[1] + b[2];
    [(b[0] + b[1]) / den, (b[1] + b[2]) / den]
}

#[test]
fn rational_derivatives_of_a_circle_match_the_closed_form() {
    let circle = made(
        &["make", "circle", "--center", "[0,0]", "--radius", "1"],
        "circle.json",
    );
    let rows = spline(&["eval", &circle, "--at", "[0.1]", "--derivatives", "40"]).json();
    let rows = rows[0].as_array().unwrap();
    assert_eq!(rows.len(), 41);
    // C' by central differences of the closed form; on the unit circle, |C| = 1.
    let h = 1e-6;
    let (a, b) = (quarter(0.1 + h), quarter(0.1 - h));
    let value = common::flatten(&rows[0]);
    assert!((value[0].hypot(value[1]) - 1.0).abs() < 1e-15);
    for c in 0..2 {
        let want = (a[c] - b[c]) / (2.0 * h);
        let got = common::flatten(&rows[1])[c];
        assert!((got - want).abs() < 1e-7, "{got} vs {want}");
    }
    assert!(common::flatten(&rows[40]).iter().all(|x| x.is_finite()));
}

#[test]
fn parameter_correction_sweeps_are_limited() {
    let points = temp_file("p.json", "[[0,0],[1,2],[2.5,2],[4,0.5],[5,1.5]]");
    let run = spline(&[
        "approximate",
        &points,
        "--degree",
        "2",
        "--control-points",
        "4",
        "--correct-parameters",
        "10000000",
    ]);
    assert_message(
        &run,
        "10000000 correction sweeps are more than the supported maximum 10000",
    );
}

// ---------------------------------------------------------------------------------------
// Silent wrong answers.

#[test]
fn elevation_by_an_absurd_count_is_refused_not_wrapped() {
    let cubic = temp_file(
        "cubic.json",
        r#"{"degree":3,"knots":[0,0,0,0,1,1,1,1],"control_points":[[0,0],[1,2],[2,2],[3,0]]}"#,
    );
    let run = spline(&["elevate", &cubic, "--times", "18446744073709551615"]);
    assert_message(
        &run,
        "raising degree 3 by 18446744073709551615 goes above the supported maximum degree 32 (at most 29 more)",
    );
}

#[test]
fn eval_with_an_absurd_order_is_refused_not_empty() {
    let run = spline(&[
        "eval",
        &line(),
        "--at",
        "[0.5]",
        "--derivatives",
        "18446744073709551615",
    ]);
    assert_message(
        &run,
        "--derivatives: derivative order 18446744073709551615 is above the supported maximum 1000",
    );
}

/// The parabola y = x² on [-1, 1] as a quadratic Bézier curve (x(u) = u), scaled.
fn parabola(scale: f64) -> String {
    let p = |x: f64, y: f64| format!("[{:e},{:e}]", x * scale, y * scale);
    temp_file(
        "parabola.json",
        &format!(
            r#"{{"degree":2,"knots":[-1,-1,-1,1,1,1],"control_points":[{},{},{}]}}"#,
            p(-1.0, 1.0),
            p(0.0, -1.0),
            p(1.0, 1.0)
        ),
    )
}

#[test]
fn curvature_is_scale_invariant() {
    // κ(u) = 2 / (1 + 4u²)^{3/2} for y = x², divided by the scale.
    for scale in [1.0, 1e150, 1e-150, 1e300, 1e-300] {
        let values = spline(&["curvature", &parabola(scale), "--at", "[0,0.5,-1]"]).json();
        for (got, u) in values.as_array().unwrap().iter().zip([0.0f64, 0.5, -1.0]) {
            let want = 2.0 / (1.0 + 4.0 * u * u).powf(1.5) / scale;
            let got = got.as_f64().unwrap();
            assert!(
                ((got - want) / want).abs() < 1e-13,
                "scale {scale}, u = {u}: {got} vs {want}"
            );
        }
    }
}

#[test]
fn features_are_scale_invariant() {
    // The parabola's only curvature extremum is its vertex, u = 0; it has no inflection.
    for scale in [1.0, 1e80, 1e-100, 1e150, 1e-150] {
        let f = spline(&["features", &parabola(scale)]).json();
        assert_eq!(f["inflections"], serde_json::json!([]), "scale {scale}");
        let extrema = f["curvature_extrema"].as_array().unwrap();
        assert_eq!(extrema.len(), 1, "scale {scale}: {f}");
        assert!(
            extrema[0].as_f64().unwrap().abs() < 1e-12,
            "scale {scale}: {f}"
        );
    }
}

#[test]
fn the_comb_of_a_curve_with_extreme_weights_has_no_nan() {
    let path = temp_file(
        "w.json",
        r#"{"degree":2,"knots":[0,0,0,1,1,1],"control_points":[[0,0],[1,1],[2,0]],"weights":[1e-300,1e-300,1e300]}"#,
    );
    let svg = temp_file("w.svg", "");
    let run = spline(&["plot", &path, "-o", &svg, "--comb"]);
    assert_eq!(run.status, 0, "{}", run.stderr);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg"));
    assert!(!has_non_finite(&text), "{text}");
}

#[test]
fn json_numbers_are_read_with_correct_rounding() {
    let path = temp_file(
        "r.json",
        r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0.10545323933610895],[1]]}"#,
    );
    let run = spline(&["eval", &path, "--at", "[0]"]);
    assert_eq!(run.stdout.trim(), "[[[0.10545323933610895]]]");
}

#[test]
fn a_no_op_refinement_keeps_every_number() {
    // Every curve of the reference cases: refining by nothing prints the same numbers, to
    // the last digit.
    let mut checked = 0;
    for case in common::cases("curve_eval") {
        let curve = &case["curve"];
        if curve.is_null() {
            continue;
        }
        let path = temp_file("ref.json", &curve.to_string());
        let out = spline(&["refine", &path, "--knots", "[]"]).json();
        assert_eq!(
            common::flatten(&out["control_points"]),
            common::flatten(&curve["control_points"])
        );
        assert_eq!(
            common::flatten(&out["knots"]),
            common::flatten(&curve["knots"])
        );
        checked += 1;
    }
    assert!(checked > 0);
}

#[test]
fn a_knot_in_a_file_and_on_the_command_line_agree() {
    let path = temp_file(
        "k.json",
        r#"{"degree":1,"knots":[0,0,1000000000000.0941,2000000000000,2000000000000],"control_points":[[0],[1],[2]]}"#,
    );
    let out = spline(&[
        "remove",
        &path,
        "--knot",
        "1000000000000.0941",
        "--tolerance",
        "1",
    ])
    .json();
    assert_eq!(
        out["knots"],
        serde_json::json!([0.0, 0.0, 2_000_000_000_000.0, 2_000_000_000_000.0])
    );
    let out = spline(&["insert", &path, "--knot", "1000000000000.0941"]).json();
    let knots = common::flatten(&out["knots"]);
    assert_eq!(knots[2], 1_000_000_000_000.094_1);
    assert_eq!(knots[3], 1_000_000_000_000.094_1);
}

// ---------------------------------------------------------------------------------------
// Legal input refused.

#[test]
fn natural_splines_accept_any_spacing() {
    // The spline interpolates: evaluating it at the abscissae gives the ordinates.
    let y = [0.0, 1.0, 0.5, 2.0, 1.0, -1.0, 0.25];
    for order in ["4", "6"] {
        for spacing in [1.0, 1e-12, 1e-9, 1e-6, 1e6, 1e9, 1e12, 1e-300, 1e300] {
            let x: Vec<f64> = (0..y.len())
                .map(|k| (k as f64 + 0.1 * (k % 2) as f64) * spacing)
                .collect();
            let xs = serde_json::to_string(&x).unwrap();
            let ys = serde_json::to_string(&y).unwrap();
            let run = spline(&["natural", "--x", &xs, "--y", &ys, "--order", order]);
            assert_eq!(
                run.status, 0,
                "spacing {spacing}, order {order}: {}",
                run.stderr
            );
            let path = temp_file("nat.json", &run.stdout);
            let values = spline(&["eval", &path, "--at", &xs]).json();
            for (k, row) in values.as_array().unwrap().iter().enumerate() {
                let got = row[0][0].as_f64().unwrap();
                assert!(
                    (got - y[k]).abs() < 1e-12,
                    "spacing {spacing}, order {order}, x_{k}: {got} vs {}",
                    y[k]
                );
            }
        }
    }
}

#[test]
fn chordal_parameters_accept_any_scale() {
    let base = [[0.0, 0.0], [3.0, 4.0], [3.0, 10.0], [11.0, 16.0]];
    // Chord lengths 5, 6, 10: parameters 0, 5/21, 11/21, 1.
    let expected = [0.0, 5.0 / 21.0, 11.0 / 21.0, 1.0];
    for scale in [1.0, 1e154, 1e200, 1e300, 1e-200, 1e-300] {
        let pts: Vec<[f64; 2]> = base.iter().map(|p| [p[0] * scale, p[1] * scale]).collect();
        let path = temp_file("pts.json", &serde_json::to_string(&pts).unwrap());
        let run = spline(&["interpolate", &path, "--degree", "2", "--report"]);
        let report = run.json();
        for (got, want) in common::flatten(&report["params"]).iter().zip(expected) {
            assert!((got - want).abs() < 1e-15, "scale {scale}: {got} vs {want}");
        }
        // The curve passes through the points.
        let curve = temp_file("c.json", &report["curve"].to_string());
        let at = serde_json::to_string(&expected).unwrap();
        let values = spline(&["eval", &curve, "--at", &at]).json();
        for (k, row) in values.as_array().unwrap().iter().enumerate() {
            for c in 0..2 {
                let got = row[0][c].as_f64().unwrap();
                let want = pts[k][c];
                assert!(
                    (got - want).abs() <= 1e-13 * scale * 16.0,
                    "scale {scale}: {got} vs {want}"
                );
            }
        }
    }
}

#[test]
fn a_sphere_of_radius_1e155_is_a_sphere() {
    let path = made(
        &["make", "sphere", "--center", "[0,0,0]", "--radius", "1e155"],
        "big_sphere.json",
    );
    let values = spline(&["eval", &path, "--at", "[[0.3,0.7],[0.5,0.5]]"]).json();
    for row in values.as_array().unwrap() {
        let p = common::flatten(&row[0][0]);
        let r = p.iter().map(|x| (x / 1e155).powi(2)).sum::<f64>().sqrt();
        assert!((r - 1.0).abs() < 1e-14, "{p:?}");
    }
    let mesh = temp_file("big.obj", "");
    let run = spline(&[
        "mesh",
        &path,
        "-o",
        &mesh,
        "--segments-u",
        "8",
        "--segments-v",
        "8",
    ]);
    assert_eq!(run.status, 0, "{}", run.stderr);
    let text = std::fs::read_to_string(&mesh).unwrap();
    assert!(!has_non_finite(&text));
}

// ---------------------------------------------------------------------------------------
// Messages for people.

#[test]
fn messages_name_the_entry_once_and_write_numbers_short() {
    let path = line();
    assert_message(
        &spline(&["eval", &path, "--at", "[0.5, 4]"]),
        "--at entry 1: parameter 4 is outside the domain [0, 1]",
    );
    assert_message(
        &spline(&["eval", &path, "--at", "[-5e-324]"]),
        "--at entry 0: parameter -5e-324 is outside the domain [0, 1]",
    );
    let long = format!("[{},\"x\"]", vec!["0.5"; 30_000].join(","));
    let run = spline(&["eval", &path, "--at", &long]);
    assert_message(
        &run,
        "--at: entry 30000: expected a number, got the string \"x\"",
    );
    let run = spline(&[
        "eval",
        &path,
        "--at",
        &format!("[{}", vec!["0.5"; 30_000].join(",")),
    ]);
    let message = run.assert_clean_error();
    assert!(message.len() < 200, "{message}");
    assert!(message.contains("(120000 characters)"), "{message}");
}

#[test]
fn malformed_objects_name_the_field_and_the_file() {
    let path = temp_file(
        "bad.json",
        r#"{"degree":1,"knots":[0,0,1,1],"control_points":[0.0,1]}"#,
    );
    assert_message(
        &spline(&["eval", &path, "--at", "[0.5]"]),
        &format!(
            "{path}: malformed curve: field control_points[0]: expected an array, got the number 0.0"
        ),
    );
    let path = temp_file(
        "badw.json",
        r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]],"weights":[1,-1]}"#,
    );
    assert_message(
        &spline(&["eval", &path, "--at", "[0.5]"]),
        &format!("{path}: weight 1: weights must be positive and finite, got -1"),
    );
}

#[test]
fn missing_and_unknown_subcommands_get_one_line() {
    assert_message(
        &spline(&["make"]),
        "spline make needs one of: circle, arc, conic, extrude, ruled, cone, revolve, sphere, torus, skin, sweep, coons, gordon (see spline make --help)",
    );
    assert_message(
        &spline(&["evall", "x"]),
        "unrecognized subcommand 'evall' tip: some similar subcommands exist: 'elevate', 'eval' (see spline --help)",
    );
    assert_message(
        &spline(&["make", "circl"]),
        "unrecognized subcommand 'circl' tip: a similar subcommand exists: 'circle' (see spline --help)",
    );
}

#[test]
fn singular_systems_are_explained_in_plain_words() {
    // Two equal abscissae after normalisation: 1 and 1 + 1e-17 are the same number.
    let run = spline(&[
        "natural",
        "--x",
        "[0, 1, 1.00000000000000001, 2]",
        "--y",
        "[0, 1, 2, 3]",
    ]);
    let message = run.assert_clean_error();
    assert!(!message.contains("pivot"), "{message}");
    let value: Value = Value::String(message);
    assert!(value.as_str().is_some());
}

#[test]
fn pictures_do_not_depend_on_the_scale() {
    // The parabola and a rational arc drawn with combs and features: the same picture at
    // every scale (coordinates are mapped to the page relative to their extent).
    let draw = |scale: f64| {
        let arc = temp_file(
            "arc.json",
            &format!(
                r#"{{"degree":2,"knots":[0,0,0,1,1,1],"control_points":[[{a:e},0],[{a:e},{a:e}],[0,{a:e}]],"weights":[1,2,1]}}"#,
                a = scale
            ),
        );
        let svg = temp_file("p.svg", "");
        let run = spline(&[
            "plot",
            &parabola(scale),
            &arc,
            "-o",
            &svg,
            "--comb",
            "--features",
        ]);
        assert_eq!(run.status, 0, "{}", run.stderr);
        std::fs::read_to_string(&svg).unwrap()
    };
    let unit = draw(1.0);
    assert!(unit.contains(r#"class="comb""#));
    for scale in [1e300, 1e-300, 0.25, 1024.0] {
        assert_eq!(draw(scale), unit, "scale {scale}");
    }
}
