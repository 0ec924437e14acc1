//! Regression tests of issue 9 (reliability), part one: every command of the fuzzing
//! campaign that panicked, aborted or hung, with the exact expected answer, and the helpers
//! shared with `reliability_answers` (wrong answers, refused legal input, messages). Numbers
//! are checked against independent computations (closed forms, the unscaled problem,
//! interpolation conditions).

use crate::common;

use common::{Run, spline, temp_file};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const LINE: &str =
    r#"{"degree":1,"knots":[0.0,0.0,1.0,1.0],"control_points":[[0.0,0.0],[1.0,1.0]]}"#;

pub fn line() -> String {
    temp_file("line.json", LINE)
}

pub fn made(args: &[&str], name: &str) -> String {
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
pub fn assert_message(run: &Run, expected: &str) {
    let message = run.assert_clean_error();
    assert_eq!(message, format!("spline: {expected}"));
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
