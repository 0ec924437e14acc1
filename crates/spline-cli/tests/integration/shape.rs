//! `spline smooth` and `spline optimize` through the binary: an airfoil keeps one curvature
//! extremum, the thesis's settings can be written on the command line, a directory gives one
//! JSON per airfoil and a summary, bad input gives exit status 2 and one line.

use crate::common;

use common::{spline, temp_file};
use serde_json::Value;

fn airfoil(name: &str) -> String {
    format!(
        "{}/../../data/airfoils/{name}.dat",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn smoothing_an_airfoil() {
    let out = spline(&["smooth", &airfoil("clarkv"), "--control-points", "20"]).json();
    assert_eq!(out["curvature_extrema"].as_array().unwrap().len(), 1);
    assert_eq!(out["extrema"][0]["kind"], "maximum");
    let nose_x = out["extrema"][0]["point"][0].as_f64().unwrap();
    assert!(nose_x < 0.01, "{nose_x}");
    assert!(out["max_deviation"].as_f64().unwrap() < 2e-3);
    assert!(out["max_deviation_to_data"].as_f64().unwrap() < 4e-3);
    assert!(out["rms"].as_f64().unwrap() < out["max_deviation"].as_f64().unwrap());
    assert_eq!(out["curve"]["degree"], 3);
    assert_eq!(out["control_points"], 20);
    assert_eq!(out["curve"]["control_points"].as_array().unwrap().len(), 20);
    assert!(out["least_squares_curvature_extrema"].as_u64().unwrap() > 1);
    // The curve evaluates through the tool and starts at the first data point (1, 0).
    let curve = temp_file("smoothed.json", &out["curve"].to_string());
    let ends = spline(&["eval", &curve, "--at", "[0, 1]"]).json();
    assert!((ends[0][0][0].as_f64().unwrap() - 1.0).abs() < 1e-2);
}

#[test]
fn the_thesis_settings_on_the_command_line() {
    // ah63k127: a minimum at u = 0.02 near the trailing edge, then the nose maximum.
    let out = spline(&[
        "smooth",
        &airfoil("table61/ah63k127"),
        "--control-points",
        "26",
        "--extremum",
        "min@0.02",
        "--extremum",
        "max",
    ])
    .json();
    let extrema = out["extrema"].as_array().unwrap();
    assert_eq!(extrema.len(), 2, "{extrema:?}");
    assert_eq!(extrema[0]["kind"], "minimum");
    assert!((extrema[0]["u"].as_f64().unwrap() - 0.02).abs() < 1e-9);
    assert_eq!(extrema[1]["kind"], "maximum");
    assert!(out["max_deviation"].as_f64().unwrap() < 2.7e-3);
}

#[test]
fn fewest_control_points_for_a_tolerance() {
    let out = spline(&["smooth", &airfoil("clarkv"), "--max-deviation", "0.002"]).json();
    let n = out["control_points"].as_u64().unwrap();
    assert!(out["max_deviation"].as_f64().unwrap() <= 0.002);
    // One control point less does not reach the tolerance (or finds no curve).
    let fewer = (n - 1).to_string();
    let run = spline(&["smooth", &airfoil("clarkv"), "--control-points", &fewer]);
    if run.status == 0 {
        let d = run.json()["max_deviation"].as_f64().unwrap();
        assert!(
            d > 0.002,
            "{n} control points were not the fewest: {fewer} give {d}"
        );
    }
}

#[test]
fn a_directory_of_airfoils() {
    let dir = std::env::temp_dir().join(format!("spline-smooth-batch-{}", std::process::id()));
    let input = dir.join("in");
    let out = dir.join("out");
    std::fs::create_dir_all(&input).unwrap();
    for name in ["clarkv", "e422"] {
        std::fs::copy(airfoil(name), input.join(format!("{name}.dat"))).unwrap();
    }
    // Not an airfoil: text between the points.
    std::fs::write(
        input.join("broken.dat"),
        "name\n1 0\nnot a point\n0 0\n1 -0.1\n",
    )
    .unwrap();
    let run = spline(&[
        "smooth",
        input.to_str().unwrap(),
        "--control-points",
        "16",
        "--jobs",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    // One input failed: exit status 2 and one line, after every input was handled.
    let message = run.assert_clean_error();
    assert!(message.contains("smoothed 2 of 3"), "{message}");
    let summary = std::fs::read_to_string(out.join("summary.jsonl")).unwrap();
    let rows: Vec<Value> = summary
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(rows.len(), 3);
    for row in &rows {
        if row["name"] == "broken" {
            assert!(row["error"].as_str().unwrap().contains("line 3"), "{row}");
        } else {
            assert!(row["error"].is_null(), "{row}");
            assert_eq!(row["control_points"], 16);
            assert_eq!(row["extrema"], 1);
            let one: Value = serde_json::from_str(
                &std::fs::read_to_string(
                    out.join(format!("{}.json", row["name"].as_str().unwrap())),
                )
                .unwrap(),
            )
            .unwrap();
            assert_eq!(one["max_deviation"], row["max_deviation"]);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Two inputs with the same file name in different folders: two outputs, none overwritten
/// (reproducer `smooth d/a.dat e/a.dat --out O`).
#[test]
fn inputs_with_the_same_name_get_outputs_of_their_own() {
    let dir = std::env::temp_dir().join(format!("spline-smooth-same-{}", std::process::id()));
    let out = dir.join("out");
    for (folder, name) in [("d", "clarkv"), ("e", "e422")] {
        std::fs::create_dir_all(dir.join(folder)).unwrap();
        std::fs::copy(airfoil(name), dir.join(folder).join("a.dat")).unwrap();
    }
    let first = dir.join("d").join("a.dat");
    let second = dir.join("e").join("a.dat");
    let run = spline(&[
        "smooth",
        first.to_str().unwrap(),
        second.to_str().unwrap(),
        "--control-points",
        "16",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status, 0, "{}", run.stderr);
    let summary = std::fs::read_to_string(out.join("summary.jsonl")).unwrap();
    let rows: Vec<Value> = summary
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let names: Vec<&str> = rows.iter().map(|r| r["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["a", "a-2"], "{summary}");
    assert_eq!(rows[0]["input"], first.to_str().unwrap());
    assert_eq!(rows[1]["input"], second.to_str().unwrap());
    // Each output holds its own airfoil's result.
    for row in &rows {
        let file = out.join(format!("{}.json", row["name"].as_str().unwrap()));
        let one: Value = serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
        assert_eq!(one["max_deviation"], row["max_deviation"]);
    }
    assert_ne!(rows[0]["max_deviation"], rows[1]["max_deviation"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn smoothing_errors() {
    let points3d = temp_file("p.json", "[[0,0,0],[1,0,0],[2,1,0],[3,0,0]]");
    let clarkv = airfoil("clarkv");
    for (args, needle) in [
        (
            vec!["smooth", &points3d as &str, "--control-points", "4"],
            "planar",
        ),
        (
            vec!["smooth", &clarkv, "--control-points", "20", "--degree", "2"],
            "degree 3",
        ),
        (
            vec![
                "smooth",
                &clarkv,
                "--control-points",
                "20",
                "--extremum",
                "max@2",
            ],
            "(0, 1)",
        ),
        (
            vec![
                "smooth",
                &clarkv,
                "--control-points",
                "20",
                "--extremum",
                "top",
            ],
            "--extremum",
        ),
        (
            vec![
                "smooth",
                &clarkv,
                "--control-points",
                "20",
                "--extremum",
                "max",
                "--extremum",
                "max",
            ],
            "alternate",
        ),
        (
            vec![
                "smooth",
                &clarkv,
                "--control-points",
                "6",
                "--curvature-extrema",
                "5",
            ],
            "at least",
        ),
        (vec!["smooth", &clarkv], "--control-points"),
        (
            vec!["smooth", &clarkv, &clarkv, "--control-points", "20"],
            "--out",
        ),
        (vec!["smooth", &clarkv, "--max-deviation", "0"], "positive"),
    ] {
        let args: Vec<&str> = args.iter().map(AsRef::as_ref).collect();
        let message = spline(&args).assert_clean_error();
        assert!(message.contains(needle), "{args:?}: {message}");
    }
}

#[test]
fn optimising_perimeter_squared_over_area() {
    let out = spline(&["optimize", "--iterations", "3"]).json();
    let j = out["criterion"].as_f64().unwrap();
    assert!((j - 2.0 * std::f64::consts::PI).abs() < 1e-3, "{j}");
    assert_eq!(out["iterations"].as_array().unwrap().len(), 3);
    let message = spline(&["optimize", "--iterations", "0"]).assert_clean_error();
    assert!(
        message.contains("iterations must be 1 to 1000"),
        "{message}"
    );
    // Degree 0 is refused at once (it used to run 30 s before failing on the area).
    let started = std::time::Instant::now();
    let message = spline(&["optimize", "--degree", "0"]).assert_clean_error();
    assert!(message.contains("degree must be at least 1"), "{message}");
    assert!(started.elapsed().as_secs_f64() < 5.0);
}

/// Points of a noisy ellipse, closed by a repeated first point, as JSON.
fn closed_ellipse() -> String {
    let points: Vec<[f64; 2]> = (0..=60)
        .map(|k| {
            let k = k % 60;
            let t = 0.3 + std::f64::consts::TAU * f64::from(k) / 60.0;
            let noise = 1e-3 * f64::from((k * 37) % 7) / 7.0;
            [2.0 * t.cos() + noise, t.sin()]
        })
        .collect();
    temp_file("ellipse.json", &serde_json::to_string(&points).unwrap())
}

#[test]
fn smoothing_a_closed_contour() {
    let input = closed_ellipse();
    let out = spline(&[
        "smooth",
        &input,
        "--closed",
        "--control-points",
        "14",
        "--curvature-extrema",
        "4",
    ])
    .json();
    assert_eq!(out["closed"], true);
    assert_eq!(out["control_points"], 14);
    let extrema = out["extrema"].as_array().unwrap();
    assert_eq!(extrema.len(), 4, "{extrema:?}");
    let kinds: Vec<&str> = extrema
        .iter()
        .map(|e| e["kind"].as_str().unwrap())
        .collect();
    assert!(kinds.windows(2).all(|w| w[0] != w[1]), "{kinds:?}");
    assert!(out["max_deviation"].as_f64().unwrap() < 3e-3);
    // The wrapped container: 14 + 3 control points, the last three repeating the first.
    let control = out["curve"]["control_points"].as_array().unwrap();
    assert_eq!(control.len(), 17);
    for i in 0..3 {
        assert_eq!(control[i], control[14 + i]);
    }
    // The curve closes: the same point at both ends of its domain, through the tool.
    let curve = temp_file("closed.json", &out["curve"].to_string());
    let ends = spline(&["eval", &curve, "--at", "[0, 1]"]).json();
    for c in 0..2 {
        let gap = ends[0][0][c].as_f64().unwrap() - ends[1][0][c].as_f64().unwrap();
        assert!(gap.abs() < 1e-12, "{ends}");
    }
    // An odd number of extrema cannot alternate round a closed curve.
    let odd = spline(&[
        "smooth",
        &input,
        "--closed",
        "--control-points",
        "14",
        "--curvature-extrema",
        "3",
    ]);
    let message = odd.assert_clean_error();
    assert!(message.contains("as many maxima as minima"), "{message}");
}

#[test]
fn smoothing_that_cannot_follow_the_data_warns() {
    // A sharp-nosed plate (UIUC goe417a) with one maximum: a warning in the report and on
    // standard error; an ordinary airfoil's report has no warnings field at all.
    let plate = airfoil("plates/goe417a");
    let run = spline(&["smooth", &plate, "--control-points", "20"]);
    let out = run.json();
    let warnings = out["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(out["max_deviation"].as_f64().unwrap() > 8e-3);
    let warning = warnings[0].as_str().unwrap();
    assert!(
        run.stderr.contains("warning:") && run.stderr.contains(warning),
        "{}",
        run.stderr
    );
    let calm = spline(&["smooth", &airfoil("clarkv"), "--control-points", "20"]);
    assert!(calm.json().get("warnings").is_none());
    assert!(calm.stderr.is_empty(), "{}", calm.stderr);
    // `auto`: the fewest extrema within the default tolerance, two on the plate.
    let auto = spline(&[
        "smooth",
        &plate,
        "--control-points",
        "20",
        "--curvature-extrema",
        "auto",
    ])
    .json();
    assert_eq!(auto["extrema"].as_array().unwrap().len(), 2);
    assert!(auto["max_deviation"].as_f64().unwrap() < 2e-3);
    assert!(auto.get("warnings").is_none());
    // With --max-deviation as the tolerance; a tolerance nothing reaches is a clean error.
    let tight = spline(&[
        "smooth",
        &plate,
        "--control-points",
        "20",
        "--curvature-extrema",
        "auto",
        "--max-deviation",
        "1e-6",
    ]);
    let message = tight.assert_clean_error();
    assert!(message.contains("within"), "{message}");
    let neither = spline(&[
        "smooth",
        &plate,
        "--control-points",
        "20",
        "--max-deviation",
        "0.001",
    ]);
    assert!(neither.assert_clean_error().contains("not both"));
}
