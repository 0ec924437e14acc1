//! `spline smooth` through the binary: an airfoil keeps one curvature extremum; bad input
//! gives exit status 2 and one line.

mod common;

use common::{spline, temp_file};

fn airfoil() -> String {
    format!(
        "{}/../../data/airfoils/clarkv.dat",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn smoothing_an_airfoil() {
    let out = spline(&[
        "smooth",
        &airfoil(),
        "--control-points",
        "20",
        "--curvature-extrema",
        "1",
    ])
    .json();
    assert_eq!(out["curvature_extrema"].as_array().unwrap().len(), 1);
    assert!(out["max_deviation"].as_f64().unwrap() < 5e-3);
    assert_eq!(out["curve"]["degree"], 3);
    assert_eq!(out["curve"]["control_points"].as_array().unwrap().len(), 20);
    assert!(
        out["least_squares_curvature_extrema"]
            .as_array()
            .unwrap()
            .len()
            > 1
    );
    // The curve evaluates through the tool.
    let curve = temp_file("smoothed.json", &out["curve"].to_string());
    let ends = spline(&["eval", &curve, "--at", "[0, 1]"]).json();
    assert!((ends[0][0][0].as_f64().unwrap() - 1.0).abs() < 1e-2);
}

#[test]
fn smoothing_errors() {
    let points3d = temp_file("p.json", "[[0,0,0],[1,0,0],[2,1,0],[3,0,0]]");
    for (args, needle) in [
        (
            vec![
                "smooth",
                &points3d as &str,
                "--control-points",
                "4",
                "--curvature-extrema",
                "1",
            ],
            "planar",
        ),
        (
            vec![
                "smooth",
                &airfoil(),
                "--control-points",
                "20",
                "--curvature-extrema",
                "1",
                "--degree",
                "2",
            ],
            "degree 3",
        ),
        (
            vec![
                "smooth",
                &airfoil(),
                "--control-points",
                "20",
                "--curvature-extrema",
                "1",
                "--extremum-at",
                "[2]",
            ],
            "inside (0, 1)",
        ),
        (
            vec![
                "smooth",
                &airfoil(),
                "--control-points",
                "6",
                "--curvature-extrema",
                "5",
            ],
            "knot spans",
        ),
    ] {
        let args: Vec<&str> = args.iter().map(AsRef::as_ref).collect();
        let message = spline(&args).assert_clean_error();
        assert!(message.contains(needle), "{message}");
    }
}
