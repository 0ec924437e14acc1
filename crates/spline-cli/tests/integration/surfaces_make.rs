//! The `spline make` constructions through the tool, checked for exactness: circles both
//! ways, arcs and conics, and the exact surfaces (sphere, torus, extrusion, cone, ruled
//! surface, revolution).

use crate::surfaces::{eval_points, fails, grid, norm, ok, params, run, sub, temp_dir, write};
use serde_json::json;
use spline_testing::compare::assert_close;
use spline_testing::reference::flatten;

#[test]
fn make_circles_both_ways() {
    let dir = temp_dir("circles");
    let square = ok(&["make", "circle", "--center", "[1, -2]", "--radius", "3"]);
    assert_eq!(
        square["knots"],
        json!([
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0
        ])
    );
    assert_eq!(square["control_points"][1], json!([4.0, 1.0]));
    let s = std::f64::consts::FRAC_1_SQRT_2;
    assert_close(
        &flatten(&square["weights"]),
        &[1.0, s, 1.0, s, 1.0, s, 1.0, s, 1.0],
        1e-16,
        "weights (6.10)",
    );
    let triangle = ok(&[
        "make",
        "circle",
        "--center",
        "[1, -2]",
        "--radius",
        "3",
        "--construction",
        "triangle",
    ]);
    assert_eq!(
        triangle["weights"],
        json!([1.0, 0.5, 1.0, 0.5, 1.0, 0.5, 1.0])
    );
    for (name, object) in [("square", &square), ("triangle", &triangle)] {
        let file = write(&dir, &format!("{name}.json"), object);
        for p in eval_points(&file, &params(500)) {
            assert!(
                (norm(&sub(&p, &[1.0, -2.0])) - 3.0).abs() <= 3e-13,
                "{name}: {p:?}"
            );
        }
    }
    let spatial = ok(&[
        "make",
        "circle",
        "--center",
        "[0, 0, 1]",
        "--radius",
        "2",
        "--normal",
        "[1, 1, 1]",
    ]);
    let file = write(&dir, "spatial.json", &spatial);
    // Planar NURBS curves are drawn by `plot` (with a curvature comb); spatial ones are not.
    let square_file = write(&dir, "square.json", &square);
    let svg = dir.join("circle.svg");
    let out = run(&["plot", &square_file, "-o", svg.to_str().unwrap(), "--comb"]);
    assert_eq!(out.code, 0, "{}", out.stderr);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.contains("class=\"comb\""));
    assert!(fails(&["plot", &file, "-o", svg.to_str().unwrap()]).contains("planar"));
    for p in eval_points(&file, &params(300)) {
        let d = sub(&p, &[0.0, 0.0, 1.0]);
        assert!((norm(&d) - 2.0).abs() <= 2e-13);
        assert!((d[0] + d[1] + d[2]).abs() < 1e-12);
    }
}

#[test]
fn make_arcs_and_conics() {
    let dir = temp_dir("arcs");
    let arc = ok(&[
        "make",
        "arc",
        "--center",
        "[0, 0]",
        "--radius",
        "2",
        "--start",
        "30",
        "--sweep",
        "-250",
        "--max-piece",
        "120",
    ]);
    assert_eq!(arc["control_points"].as_array().unwrap().len(), 2 * 3 + 1);
    let file = write(&dir, "arc.json", &arc);
    let pts = eval_points(&file, &params(200));
    for p in &pts {
        assert!((norm(p) - 2.0).abs() <= 2e-13);
    }
    let (a0, a1) = (30f64.to_radians(), (30.0 - 250.0f64).to_radians());
    assert_close(
        &pts[0],
        &[2.0 * a0.cos(), 2.0 * a0.sin()],
        1e-14,
        "arc start",
    );
    assert_close(
        &pts[200],
        &[2.0 * a1.cos(), 2.0 * a1.sin()],
        1e-14,
        "arc end",
    );
    // (6.7): the conic through the shoulder point has w1 = |SM| / |SP1|.
    let conic = ok(&[
        "make", "conic", "--p0", "[0, 0]", "--p1", "[1, 2]", "--p2", "[2, 0]", "--w1", "2",
    ]);
    assert_eq!(conic["weights"], json!([1.0, 2.0, 1.0]));
    let file = write(&dir, "conic.json", &conic);
    let s = eval_points(&file, &json!([0.5])).remove(0);
    let through = ok(&[
        "make",
        "conic",
        "--p0",
        "[0, 0]",
        "--p1",
        "[1, 2]",
        "--p2",
        "[2, 0]",
        "--shoulder",
        &json!(s).to_string(),
    ]);
    assert!((through["weights"][1].as_f64().unwrap() - 2.0).abs() < 1e-13);
    assert!((norm(&sub(&s, &[1.0, 0.0])) / norm(&sub(&s, &[1.0, 2.0])) - 2.0).abs() < 1e-13);
    // The parabola w1 = 1 is the quadratic Bézier curve: y = 4x(1 − x/2)·… checked at u.
    let parabola = ok(&[
        "make", "conic", "--p0", "[0, 0]", "--p1", "[1, 2]", "--p2", "[2, 0]", "--w1", "1",
    ]);
    let file = write(&dir, "parabola.json", &parabola);
    for (i, p) in eval_points(&file, &params(10)).iter().enumerate() {
        let u = i as f64 / 10.0;
        assert_close(p, &[2.0 * u, 4.0 * u * (1.0 - u)], 1e-15, "parabola");
    }
}

#[test]
fn make_surfaces_exactly() {
    let dir = temp_dir("surfaces");
    // Sphere (6.13)–(6.14).
    let sphere = ok(&["make", "sphere", "--center", "[1, 2, 3]", "--radius", "0.5"]);
    assert_eq!(sphere["degree"], json!([2, 2]));
    assert_eq!(sphere["control_points"].as_array().unwrap().len(), 5);
    assert_eq!(sphere["control_points"][0].as_array().unwrap().len(), 9);
    let file = write(&dir, "sphere.json", &sphere);
    for p in eval_points(&file, &grid(30)) {
        assert!((norm(&sub(&p, &[1.0, 2.0, 3.0])) - 0.5).abs() <= 0.5e-13);
    }
    // Torus about a tilted axis.
    let torus = ok(&[
        "make",
        "torus",
        "--center",
        "[0, 0, 0]",
        "--major",
        "2",
        "--minor",
        "0.5",
        "--axis",
        "[0, 1, 0]",
    ]);
    let file = write(&dir, "torus.json", &torus);
    for p in eval_points(&file, &grid(30)) {
        let rho = (p[0] * p[0] + p[2] * p[2]).sqrt();
        assert!((((rho - 2.0).powi(2) + p[1] * p[1]).sqrt() - 0.5).abs() <= 0.5e-13);
    }
    // Extrusion (5.14) of a B-spline curve and of a NURBS circle.
    let curve = json!({"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control_points": [[0, 0, 0], [1, 1, 0], [2, 0, 0]]});
    let curve_file = write(&dir, "curve.json", &curve);
    let extruded = ok(&["make", "extrude", &curve_file, "--vector", "[0, 0, 2]"]);
    assert!(extruded.get("weights").is_none());
    let file = write(&dir, "extruded.json", &extruded);
    for (k, p) in eval_points(&file, &grid(4)).iter().enumerate() {
        let (u, v) = ((k / 5) as f64 / 4.0, (k % 5) as f64 / 4.0);
        assert_close(
            p,
            &[2.0 * u, 2.0 * u * (1.0 - u), 2.0 * v],
            1e-15,
            "extrusion",
        );
    }
    let circle = ok(&["make", "circle", "--center", "[0, 0, 0]", "--radius", "1"]);
    let circle_file = write(&dir, "circle.json", &circle);
    let cylinder = ok(&["make", "extrude", &circle_file, "--vector", "[0, 0, 3]"]);
    assert!(cylinder.get("weights").is_some());
    let file = write(&dir, "cylinder.json", &cylinder);
    for (k, p) in eval_points(&file, &grid(10)).iter().enumerate() {
        assert!(((p[0] * p[0] + p[1] * p[1]).sqrt() - 1.0).abs() < 1e-14);
        assert!((p[2] - 3.0 * (k % 11) as f64 / 10.0).abs() < 1e-14);
    }
    // Cone (5.17) over the circle, ruled surface (5.16) between the curve and a line.
    let cone = ok(&["make", "cone", &circle_file, "--apex", "[0, 0, 2]"]);
    let file = write(&dir, "cone.json", &cone);
    for p in eval_points(&file, &grid(10)) {
        assert!(((p[0] * p[0] + p[1] * p[1]).sqrt() - (2.0 - p[2]) / 2.0).abs() < 1e-13);
    }
    let line =
        json!({"degree": 1, "knots": [5, 5, 7, 7], "control_points": [[0, 0, 1], [2, 0, 1]]});
    let line_file = write(&dir, "line.json", &line);
    let ruled = ok(&["make", "ruled", &curve_file, &line_file]);
    assert_eq!(ruled["degree"], json!([2, 1]));
    let file = write(&dir, "ruled.json", &ruled);
    for (k, p) in eval_points(&file, &grid(4)).iter().enumerate() {
        let (u, v) = ((k / 5) as f64 / 4.0, (k % 5) as f64 / 4.0);
        let expected = [2.0 * u, (1.0 - v) * 2.0 * u * (1.0 - u), v];
        assert_close(p, &expected, 1e-14, "ruled");
    }
    // Revolution of a planar profile (x = radius, y = height) about the y axis, half a turn.
    let profile = json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[1, 0], [2, 1]]});
    let profile_file = write(&dir, "profile.json", &profile);
    let revolved = ok(&[
        "make",
        "revolve",
        &profile_file,
        "--axis-direction",
        "[0, 1]",
        "--angle",
        "180",
    ]);
    assert_eq!(revolved["control_points"][0].as_array().unwrap().len(), 5);
    let file = write(&dir, "revolved.json", &revolved);
    for (k, p) in eval_points(&file, &grid(8)).iter().enumerate() {
        let u = (k / 9) as f64 / 8.0;
        assert!(((p[0] * p[0] + p[2] * p[2]).sqrt() - (1.0 + u)).abs() < 1e-14);
        assert!((p[1] - u).abs() < 1e-15);
        assert!(p[2] <= 1e-15); // right-handed about +y from +x: towards −z
    }
}
