//! Regression tests of issue 9 (reliability), part two: every command of the fuzzing
//! campaign that printed a wrong answer, refused legal input or explained itself badly, with
//! the exact expected answer (the panics, aborts and hangs are in `reliability`). Numbers are
//! checked against independent computations (closed forms, the unscaled problem,
//! interpolation conditions).

use crate::common;
use crate::reliability::{assert_message, line, made};

use common::{spline, temp_file};
use serde_json::Value;

/// Whether a text holds `NaN` or an infinity as a word.
fn has_non_finite(text: &str) -> bool {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .any(|w| ["nan", "inf", "infinity"].contains(&w.to_ascii_lowercase().as_str()))
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
