//! The curve tools through the binary: `intersect`, `offset`, `arclength`, `reduce` and
//! `smoothing`, against closed forms and scipy's reference data, and clean errors.

use crate::common;

use common::{spline, temp_file};
use serde_json::{Value, json};

fn file(v: &Value) -> String {
    temp_file("curve.json", &v.to_string())
}

/// (u, u²) on [−1, 1].
fn parabola() -> String {
    file(
        &json!({"degree": 2, "knots": [-1, -1, -1, 1, 1, 1], "control_points": [[-1, 1], [0, -1], [1, 1]]}),
    )
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[test]
fn intersect_two_curves_and_one_with_itself() {
    // y = u² against y = 1/2: u = ±1/√2.
    let line =
        file(&json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[-2, 0.5], [2, 0.5]]}));
    let hits = spline(&["intersect", &parabola(), &line]).json();
    let hits = hits.as_array().unwrap();
    assert_eq!(hits.len(), 2, "{hits:?}");
    for (h, x) in hits.iter().zip([-0.5f64.sqrt(), 0.5f64.sqrt()]) {
        assert!(
            (num(&h["point"][0]) - x).abs() < 1e-14 && (num(&h["point"][1]) - 0.5).abs() < 1e-14,
            "{h}"
        );
        assert_eq!(h["tangential"], json!(false));
    }
    // The tangent y = 0 touches at the vertex.
    let tangent =
        file(&json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[-2, 0], [2, 0]]}));
    let hits = spline(&["intersect", &parabola(), &tangent]).json();
    assert_eq!(hits.as_array().unwrap().len(), 1);
    assert_eq!(hits[0]["tangential"], json!(true));
    // A cubic loop crosses itself once.
    let looped = file(
        &json!({"degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 1], "control_points": [[0, 0], [2, 2], [-1, 2], [1, 0]]}),
    );
    let hits = spline(&["intersect", &looped]).json();
    assert_eq!(hits.as_array().unwrap().len(), 1);
    assert!(num(&hits[0]["u"]) < num(&hits[0]["v"]));
    // Errors.
    spline(&["intersect", &parabola(), &line, "--tolerance", "0"]).assert_clean_error();
    // A curve from standard input, against a file and alone (it used to fail: "- is not
    // valid JSON: EOF while parsing a value", the input being read twice).
    let parabola_text = std::fs::read_to_string(parabola()).unwrap();
    let hits = spline_with_stdin(&["intersect", "-", &line], &parabola_text);
    assert_eq!(hits.as_array().unwrap().len(), 2, "{hits}");
    let looped_text = std::fs::read_to_string(&looped).unwrap();
    let hits = spline_with_stdin(&["intersect", "-"], &looped_text);
    assert_eq!(hits.as_array().unwrap().len(), 1, "{hits}");
}

/// Reports with an object inside (`smooth`, `offset`, `arclength --reparametrize`) are read
/// wherever an object is: `spline smooth x.dat | spline eval - …` (issue 25: "unknown field
/// closed").
#[test]
fn reports_compose_with_every_reader() {
    let airfoil = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/airfoils/clarkv.dat"
    );
    let run = spline(&["smooth", airfoil, "--control-points", "12"]);
    let report = run.json();
    let values = spline_with_stdin(&["eval", "-", "--at", "[0.5]"], &run.stdout);
    let alone = file(&report["curve"]);
    let expected = spline(&["eval", &alone, "--at", "[0.5]"]).json();
    assert_eq!(values, expected);
    let offset = spline(&["offset", &parabola(), "--distance", "0.1"]);
    assert_eq!(offset.status, 0, "{}", offset.stderr);
    let length = spline_with_stdin(&["arclength", "-"], &offset.stdout);
    assert!(num(&length["length"]) > 0.0, "{length}");
}

/// The other reports with an object inside (`reduce`, `arclength --reparametrize`,
/// `smoothing`, `approximate-surface`) read back as their object, from a file and from
/// standard input: the same values as the object alone.
#[test]
fn every_report_reads_back_as_its_object() {
    let cubic = file(
        &json!({"degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 1], "control_points": [[0, 0], [1, 1], [2, -1], [3, 0]]}),
    );
    let points: Vec<Value> = (0..8)
        .flat_map(|i| (0..8).map(move |j| (i, j)))
        .map(|(i, j)| {
            let (x, y) = (f64::from(i) / 7.0, f64::from(j) / 7.0);
            json!([x, y, x * x - y * y])
        })
        .collect();
    let cloud = temp_file("cloud.json", &Value::Array(points).to_string());
    let runs = [
        (
            vec!["reduce", &cubic, "--tolerance", "1e-3", "--refine"],
            "curve",
            "[0.3]",
        ),
        (
            vec!["arclength", &cubic, "--reparametrize"],
            "curve",
            "[0.3]",
        ),
        (
            vec![
                "smoothing",
                "--x",
                "[0, 1, 2, 3, 4, 5, 6]",
                "--y",
                "[0, 1, 0, 1, 0, 1, 0]",
                "--lambda",
                "0.1",
            ],
            "curve",
            "[0.3]",
        ),
        (
            vec!["approximate-surface", &cloud, "--control-points", "[4, 4]"],
            "surface",
            "[[0.3, 0.6]]",
        ),
    ];
    for (args, field, at) in runs {
        let run = spline(&args);
        assert_eq!(run.status, 0, "{args:?}: {}", run.stderr);
        let report = run.json();
        let alone = file(&report[field]);
        let expected = spline(&["eval", &alone, "--at", at]).json();
        let whole = temp_file("report.json", &run.stdout);
        assert_eq!(
            spline(&["eval", &whole, "--at", at]).json(),
            expected,
            "{args:?}"
        );
        assert_eq!(
            spline_with_stdin(&["eval", "-", "--at", at], &run.stdout),
            expected,
            "{args:?}"
        );
    }
}

/// Negative numbers are values as users type them (issue 25: `--tolerance -1` was "unexpected
/// argument '-1'", with a tip to write `-- -1`): the subcommand says what is wrong.
#[test]
fn negative_values_reach_the_subcommand() {
    for tolerance in ["-1", "-1e-3"] {
        let message =
            spline(&["intersect", &parabola(), "--tolerance", tolerance]).assert_clean_error();
        assert!(
            message.contains("must be positive") && !message.contains("unexpected argument"),
            "{message}"
        );
        let message = spline(&[
            "offset",
            &parabola(),
            "--distance",
            "0.1",
            "--tolerance",
            tolerance,
        ])
        .assert_clean_error();
        assert!(message.contains("must be positive"), "{message}");
    }
    // A negative distance is an offset to the other side.
    let out = spline(&["offset", &parabola(), "--distance", "-1e-1"]).json();
    assert!(out["curve"]["control_points"].is_array());
    // An option still needs its value.
    let message = spline(&["intersect", &parabola(), "--tolerance"]).assert_clean_error();
    assert!(message.contains("value is required"), "{message}");
}

/// Messages of the readers (issue 25, item 7): an OBJ error names the file and the 1-based
/// line; a three-column point file where planar points are expected says so.
#[test]
fn reader_messages_name_the_file_the_line_and_the_columns() {
    let obj = temp_file("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    let message =
        spline(&["approximate-surface", &obj, "--control-points", "[2, 2]"]).assert_clean_error();
    assert!(
        message.contains("bad.obj") && message.contains("line 4"),
        "{message}"
    );
    let xyz = temp_file("xyz.txt", "0 0 0\n1 1 1\n2 0 3\n3 1 1\n4 2 2\n");
    let message = spline(&["smooth", &xyz, "--control-points", "8"]).assert_clean_error();
    assert!(
        message.contains("xyz.txt") && message.contains("got 3 numbers"),
        "{message}"
    );
}

/// Runs the tool with `input` on its standard input; its output as JSON, asserting success.
fn spline_with_stdin(args: &[&str], input: &str) -> Value {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_spline"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run spline");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(input.as_bytes())
        .expect("write stdin");
    let output = child.wait_with_output().expect("wait for spline");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).expect("JSON")
}

#[test]
fn offset_of_the_parabola_with_its_cusps() {
    let x = ((2f64.powf(2.0 / 3.0) - 1.0) / 4.0).sqrt();
    let out = spline(&[
        "offset",
        &parabola(),
        "--distance",
        "1",
        "--tolerance",
        "1e-7",
    ])
    .json();
    let cusps: Vec<f64> = out["cusps"].as_array().unwrap().iter().map(num).collect();
    assert_eq!(cusps.len(), 2);
    assert!(
        (cusps[0] + x).abs() < 1e-12 && (cusps[1] - x).abs() < 1e-12,
        "{cusps:?}"
    );
    // The offset curve against the closed form, through `spline eval`.
    let curve = file(&out["curve"]);
    let us: Vec<f64> = (0..=200).map(|i| -1.0 + f64::from(i) / 100.0).collect();
    let values = spline(&["eval", &curve, "--at", &json!(us).to_string()]).json();
    for (k, &u) in us.iter().enumerate() {
        let s = (1.0 + 4.0 * u * u).sqrt();
        let exact = [u - 2.0 * u / s, u * u + 1.0 / s];
        let got = &values[k][0];
        let e = ((num(&got[0]) - exact[0]).powi(2) + (num(&got[1]) - exact[1]).powi(2)).sqrt();
        assert!(e <= 1e-7, "u = {u}: {e:e}");
    }
    spline(&[
        "offset",
        &parabola(),
        "--distance",
        "1",
        "--tolerance",
        "-1",
    ])
    .assert_clean_error();
    // A space curve needs the direction its offsets are perpendicular to, a plane curve
    // has one already.
    spline(&[
        "offset",
        &parabola(),
        "--distance",
        "0.1",
        "--direction",
        "0,0,1",
    ])
    .assert_clean_error();
    let space = file(
        &json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0, 0], [1, 0, 0]]}),
    );
    spline(&["offset", &space, "--distance", "0.1"]).assert_clean_error();
    spline(&[
        "offset",
        &space,
        "--distance",
        "0.1",
        "--direction",
        "1,0,0",
    ])
    .assert_clean_error();
}

#[test]
fn offset_of_a_quarter_circle_is_the_concentric_arc() {
    let nurbs = file(
        &json!({"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control_points": [[1, 0], [1, 1], [0, 1]], "weights": [1, std::f64::consts::FRAC_1_SQRT_2, 1]}),
    );
    for (distance, radius) in [(0.1, 0.9), (-0.25, 1.25)] {
        let out = spline(&["offset", &nurbs, "--distance", &distance.to_string()]).json();
        assert!(out["cusps"].as_array().unwrap().is_empty());
        assert!(num(&out["max_error"]) <= 1e-12);
        let curve = file(&out["curve"]);
        let us: Vec<f64> = (0..=64).map(|i| f64::from(i) / 64.0).collect();
        let values = spline(&["eval", &curve, "--at", &json!(us).to_string()]).json();
        for (k, &u) in us.iter().enumerate() {
            let (x, y) = (num(&values[k][0][0]), num(&values[k][0][1]));
            let r = x.hypot(y);
            assert!((r - radius).abs() <= 1e-14, "u = {u}: radius {r}");
            assert!(
                x >= -1e-15 && y >= -1e-15,
                "u = {u}: ({x}, {y}) leaves the quadrant"
            );
        }
    }
}

#[test]
fn offset_of_a_space_cubic_along_the_binormal_of_a_direction() {
    // c(u) a cubic Bézier; the offset is c + d (c' × V) / |c' × V| with V = e_z.
    let points = [
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 0.5],
        [2.0, -1.0, 1.0],
        [3.0, 0.0, 1.5],
    ];
    let cubic =
        file(&json!({"degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 1], "control_points": points}));
    let distance = 0.1;
    let out = spline(&[
        "offset",
        &cubic,
        "--distance",
        "0.1",
        "--direction",
        "0,0,1",
        "--tolerance",
        "1e-8",
    ])
    .json();
    assert!(num(&out["max_error"]) <= 1e-8);
    let curve = file(&out["curve"]);
    let us: Vec<f64> = (0..=100).map(|i| f64::from(i) / 100.0).collect();
    let values = spline(&["eval", &curve, "--at", &json!(us).to_string()]).json();
    for (k, &u) in us.iter().enumerate() {
        let v = 1.0 - u;
        let basis = [v * v * v, 3.0 * u * v * v, 3.0 * u * u * v, u * u * u];
        let slope = [
            -3.0 * v * v,
            3.0 * v * (v - 2.0 * u),
            3.0 * u * (2.0 * v - u),
            3.0 * u * u,
        ];
        let mut c = [0.0; 3];
        let mut t = [0.0; 3];
        for (j, p) in points.iter().enumerate() {
            for i in 0..3 {
                c[i] += basis[j] * p[i];
                t[i] += slope[j] * p[i];
            }
        }
        // t × e_z = (t_y, -t_x, 0)
        let n = t[0].hypot(t[1]);
        let exact = [c[0] + distance * t[1] / n, c[1] - distance * t[0] / n, c[2]];
        let got = &values[k][0];
        let e = (0..3)
            .map(|i| (num(&got[i]) - exact[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(e <= 1e-8, "u = {u}: {e:e}");
    }
}

#[test]
fn arclength_of_a_segment_and_a_quarter_circle() {
    let segment =
        file(&json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0], [3, 4]]}));
    let out = spline(&["arclength", &segment, "--at-length", "[0, 2.5, 5]"]).json();
    assert!((num(&out["length"]) - 5.0).abs() < 1e-12);
    let params: Vec<f64> = out["params"].as_array().unwrap().iter().map(num).collect();
    assert!(
        params[0].abs() < 1e-9 && (params[1] - 0.5).abs() < 1e-9 && (params[2] - 1.0).abs() < 1e-9,
        "{params:?}"
    );
    let quarter = file(
        &json!({"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control_points": [[1, 0], [1, 1], [0, 1]], "weights": [1, std::f64::consts::FRAC_1_SQRT_2, 1]}),
    );
    let out = spline(&["arclength", &quarter]).json();
    assert!((num(&out["length"]) - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
    let out = spline(&[
        "arclength",
        &quarter,
        "--reparametrize",
        "--tolerance",
        "1e-7",
    ])
    .json();
    let curve = file(&out["curve"]);
    let values = spline(&["eval", &curve, "--at", "[0.5, 1.0]"]).json();
    for (k, s) in [0.5f64, 1.0].iter().enumerate() {
        let p = &values[k][0];
        assert!(
            (num(&p[0]) - s.cos()).abs() < 1e-7 && (num(&p[1]) - s.sin()).abs() < 1e-7,
            "{p}"
        );
    }
    spline(&["arclength", &segment, "--at-length", "[6]"]).assert_clean_error();
    spline(&["arclength", &segment, "--tolerance", "0"]).assert_clean_error();
}

/// A C¹ curve whose tangent turns by almost 90° within 0.001 of its knot (reproducer
/// `offset_c1.json`): it used to be refused as having a corner there.
#[test]
fn offset_of_a_c1_curve_that_turns_fast_at_a_knot() {
    let base = file(
        &json!({"degree": 2, "knots": [0, 0, 0, 0.5, 1, 1, 1], "control_points": [[0, 0], [1, 0], [1, 0.001], [0, 1]]}),
    );
    let out = spline(&[
        "offset",
        &base,
        "--distance",
        "0.001",
        "--tolerance",
        "1e-7",
    ])
    .json();
    let curve = file(&out["curve"]);
    let us: Vec<f64> = (0..=50).map(|i| f64::from(i) / 50.0).collect();
    let values = spline(&["eval", &curve, "--at", &json!(us).to_string()]).json();
    // The offset keeps the base's parametrisation: C(u) + d·N(u) with the unit normal N
    // from the base's first derivative (through `spline eval`).
    let base_values = spline(&[
        "eval",
        &base,
        "--at",
        &json!(us).to_string(),
        "--derivatives",
        "1",
    ])
    .json();
    for (k, u) in us.iter().enumerate() {
        let (p, d) = (&base_values[k][0], &base_values[k][1]);
        let speed = num(&d[0]).hypot(num(&d[1]));
        let exact = [
            num(&p[0]) - 0.001 * num(&d[1]) / speed,
            num(&p[1]) + 0.001 * num(&d[0]) / speed,
        ];
        let got = &values[k][0];
        let e = (num(&got[0]) - exact[0]).hypot(num(&got[1]) - exact[1]);
        assert!(e <= 1e-7, "u = {u}: {e:e}");
    }
}

/// Lengths at the ends of the floating-point range (reproducers `hugedom.json` and
/// `seg_tiny.json`): the speed's squares used to underflow, giving length 0.
#[test]
fn arclength_at_extreme_scales() {
    // The parabola [[0,0],[1,1],[2,0]] on knots up to 1e300: its length does not depend on
    // the parametrisation: ∫₀¹ 2√(1 + (1 − 2t)²) dt = √2 + asinh(1) = 2.2956.
    let hugedom = file(
        &json!({"degree": 2, "knots": [0, 0, 0, 1e300, 1e300, 1e300], "control_points": [[0, 0], [1, 1], [2, 0]]}),
    );
    let expected = 2f64.sqrt() + 1f64.asinh();
    let length = num(&spline(&["arclength", &hugedom]).json()["length"]);
    assert!((length - expected).abs() < 1e-9, "{length} vs {expected}");
    let tiny = file(
        &json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0], [3e-300, 4e-300]]}),
    );
    let length = num(&spline(&["arclength", &tiny]).json()["length"]);
    assert!((length / 5e-300 - 1.0).abs() < 1e-12, "{length}");
    // A point 1e-295 from a segment of length 1e-300 (reproducer `tinyseg.json`): the
    // distance used to come out 0.
    let hits = spline(&["closest", &tiny, "--points", "[[0, 1e-295]]"]).json();
    let d = num(&hits[0]["distance"]);
    // The closest point is the segment's end (3e-300, 4e-300).
    let expected = 3e-300f64.hypot(1e-295 - 4e-300);
    assert!((d / expected - 1.0).abs() < 1e-12, "{d} vs {expected}");
}

#[test]
fn reduce_exactly_or_say_how_close_it_gets() {
    // The parabola elevated to a cubic comes back exactly.
    let cubic = file(
        &json!({"degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 1], "control_points": [[0, 0], [0.3333333333333333, 0.6666666666666666], [0.6666666666666666, 0.6666666666666666], [1, 0]]}),
    );
    let out = spline(&["reduce", &cubic, "--tolerance", "1e-12"]).json();
    assert_eq!(out["curve"]["degree"], json!(2));
    assert!(num(&out["max_error"]) < 1e-12);
    let s = file(
        &json!({"degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 1], "control_points": [[0, 0], [1, 1], [2, -1], [3, 0]]}),
    );
    let message = spline(&["reduce", &s, "--tolerance", "1e-6"]).assert_clean_error();
    assert!(message.contains("best deviation"), "{message}");
    let out = spline(&["reduce", &s, "--tolerance", "1e-6", "--refine"]).json();
    assert!(num(&out["max_error"]) <= 1e-6);
    spline(&["reduce", &s, "--tolerance", "1e-6", "--times", "3"]).assert_clean_error();
}

#[test]
fn smoothing_agrees_with_scipy() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../spline-fit/tests/data/smoothing/gcv.json"
    );
    let data: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    for case in data["cases"].as_array().unwrap().iter().take(6) {
        let (x, y, w) = (
            case["x"].to_string(),
            case["y"].to_string(),
            case["weights"].to_string(),
        );
        let mut args = vec!["smoothing", "--x", &x, "--y", &y, "--gcv"];
        if !case["weights"].is_null() {
            args.extend(["--weights", &w]);
        }
        let out = spline(&args).json();
        let lambda = num(&case["lambda"]);
        assert!(
            (num(&out["lambda"]) - lambda).abs() <= 1e-8 * lambda.max(1.0),
            "{} vs {lambda}",
            out["lambda"]
        );
        let ours: Vec<f64> = out["curve"]["control_points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| num(&p[0]))
            .collect();
        let theirs: Vec<f64> = case["spline"]["coefficients"]
            .as_array()
            .unwrap()
            .iter()
            .map(num)
            .collect();
        assert_eq!(ours.len(), theirs.len());
        for (a, b) in ours.iter().zip(&theirs) {
            assert!((a - b).abs() <= 1e-6 * (1.0 + b.abs()), "{a} vs {b}");
        }
    }
    let x = "[0, 1, 2, 3, 4, 5, 6, 7]";
    let y = "[0, 0.8, 0.9, 0.1, -0.7, -1.0, -0.3, 0.6]";
    let out = spline(&["smoothing", "--x", x, "--y", y, "--residual", "0.05"]).json();
    assert!((num(&out["residual"]) - 0.05).abs() < 0.05 * 1e-3 || out["converged"] == json!(false));
    spline(&["smoothing", "--x", x, "--y", y]).assert_clean_error();
    spline(&["smoothing", "--x", x, "--y", y, "--gcv", "--lambda", "1"]).assert_clean_error();
    spline(&["smoothing", "--x", "[0, 1]", "--y", "[0, 1, 2]", "--gcv"]).assert_clean_error();
}

/// Found by the Open CASCADE geometry suite: the cusp search's last grid point,
/// `lo + (hi − lo)`, rounded one step past the end knot 0.1533580674213022 and the offset
/// failed with "parameter … is outside the domain".
#[test]
fn offset_on_a_domain_whose_end_rounds() {
    let curve = temp_file(
        "od4.json",
        r#"{"degree":3,"knots":[-0.7457635633497997,-0.7457635633497997,-0.7457635633497997,-0.7457635633497997,-0.4089356716219618,0.1533580674213022,0.1533580674213022,0.1533580674213022,0.1533580674213022],"control_points":[[0,0],[2,1],[4,1],[5,0],[5,0.5]]}"#,
    );
    let run = spline(&["offset", &curve, "--distance", "0.1"]);
    assert_eq!(run.status, 0, "{}", run.stderr);
    let out = run.json();
    assert!(out["max_error"].as_f64().unwrap() <= 1e-6);
}
