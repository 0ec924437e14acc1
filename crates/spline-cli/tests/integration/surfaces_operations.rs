//! Structural operations on NURBS curves and surfaces through the tool, checked for
//! invariance, `mesh` outputs, and errors (exit status 2, one line on standard error, never a
//! panic).

use crate::surfaces::{eval_points, fails, grid, norm, ok, params, sub, temp_dir, write};
use serde_json::{Value, json};

#[test]
fn structural_operations_through_the_tool() {
    let dir = temp_dir("structural");
    let sphere = ok(&["make", "sphere", "--center", "[0, 0, 0]", "--radius", "2"]);
    let sphere_file = write(&dir, "sphere.json", &sphere);
    let at = grid(12);
    let reference = eval_points(&sphere_file, &at);
    let check = |value: &Value, what: &str| {
        let file = write(&dir, "result.json", value);
        for (p, q) in eval_points(&file, &at).iter().zip(&reference) {
            assert!(norm(&sub(p, q)) < 1e-13, "{what}: {p:?} vs {q:?}");
        }
    };
    check(
        &ok(&[
            "insert",
            &sphere_file,
            "--knot",
            "0.3",
            "--times",
            "2",
            "--direction",
            "u",
        ]),
        "insert u",
    );
    check(
        &ok(&[
            "refine",
            &sphere_file,
            "--knots",
            "[0.1, 0.1, 0.9]",
            "--direction",
            "v",
        ]),
        "refine v",
    );
    check(
        &ok(&["elevate", &sphere_file, "--times", "2", "--direction", "v"]),
        "elevate v",
    );
    let inserted = ok(&["insert", &sphere_file, "--knot", "0.6", "--direction", "v"]);
    let inserted_file = write(&dir, "inserted.json", &inserted);
    let removed = ok(&[
        "remove",
        &inserted_file,
        "--knot",
        "0.6",
        "--direction",
        "v",
    ]);
    assert_eq!(removed["knots"], sphere["knots"]);
    check(&removed, "remove v");
    let halves = ok(&["split", &sphere_file, "--at", "0.25", "--direction", "u"]);
    assert_eq!(halves.as_array().unwrap().len(), 2);
    let left = write(&dir, "left.json", &halves[0]);
    for p in eval_points(&left, &json!([[0.0, 0.0], [0.1, 0.5], [0.25, 0.9]])) {
        assert!((norm(&p) - 2.0).abs() < 1e-13);
    }
    let patches = ok(&["bezier", &sphere_file]);
    assert_eq!(patches.as_array().unwrap().len(), 2);
    assert_eq!(patches[0].as_array().unwrap().len(), 4);
    // NURBS curves.
    let circle = ok(&[
        "make",
        "circle",
        "--center",
        "[0, 0]",
        "--radius",
        "1",
        "--construction",
        "triangle",
    ]);
    let circle_file = write(&dir, "circle.json", &circle);
    for (args, what) in [
        (
            vec!["insert", circle_file.as_str(), "--knot", "0.5"],
            "insert",
        ),
        (
            vec!["refine", circle_file.as_str(), "--knots", "[0.2, 0.7]"],
            "refine",
        ),
        (
            vec!["elevate", circle_file.as_str(), "--times", "2"],
            "elevate",
        ),
    ] {
        let result = ok(&args);
        let file = write(&dir, "curve.json", &result);
        for p in eval_points(&file, &params(100)) {
            assert!((norm(&p) - 1.0).abs() < 1e-14, "{what}");
        }
    }
    let parts = ok(&["split", &circle_file, "--at", "0.4"]);
    assert_eq!(
        parts[0]["knots"].as_array().unwrap().last().unwrap(),
        &json!(0.4)
    );
    let segments = ok(&["bezier", &circle_file]);
    assert_eq!(segments.as_array().unwrap().len(), 3);
    assert_eq!(segments[1]["weights"], json!([1.0, 0.5, 1.0]));
    // A plain surface's derivative surfaces.
    let patch = json!({"degree": [1, 2], "knots": [[0, 0, 1, 1], [0, 0, 0, 1, 1, 1]], "control_points": [[[0, 0, 0], [0, 1, 1], [0, 2, 0]], [[1, 0, 0], [1, 1, 2], [1, 2, 0]]]});
    let patch_file = write(&dir, "patch.json", &patch);
    let d = ok(&["derivative", &patch_file]);
    assert_eq!(d["du"]["degree"], json!([0, 2]));
    assert_eq!(d["dv"]["degree"], json!([1, 1]));
}

#[test]
fn meshes_through_the_tool() {
    let dir = temp_dir("mesh");
    let torus = ok(&[
        "make",
        "torus",
        "--center",
        "[0, 0, 0]",
        "--major",
        "3",
        "--minor",
        "1",
    ]);
    let torus_file = write(&dir, "torus.json", &torus);
    let off = dir.join("torus.off");
    let summary = ok(&[
        "mesh",
        &torus_file,
        "-o",
        off.to_str().unwrap(),
        "--segments-u",
        "12",
        "--segments-v",
        "24",
    ]);
    let text = std::fs::read_to_string(&off).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("OFF"));
    let counts: Vec<usize> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(counts[0], summary["vertices"].as_u64().unwrap() as usize);
    assert_eq!(counts[1], summary["triangles"].as_u64().unwrap() as usize);
    // A closed torus: V − E + F = 0 with E = 3F/2, so F = 2V.
    assert_eq!(counts[1], 2 * counts[0]);
    for line in lines.clone().take(counts[0]) {
        let c: Vec<f64> = line
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        let rho = (c[0] * c[0] + c[1] * c[1]).sqrt();
        assert!((((rho - 3.0).powi(2) + c[2] * c[2]).sqrt() - 1.0).abs() < 1e-13);
    }
    let obj = dir.join("torus.obj");
    ok(&["mesh", &torus_file, "-o", obj.to_str().unwrap()]);
    let text = std::fs::read_to_string(&obj).unwrap();
    assert!(text.lines().any(|l| l.starts_with("vn ")));
    assert!(text.lines().any(|l| l.starts_with("f ")));
    let svg = dir.join("torus.svg");
    ok(&["mesh", &torus_file, "-o", svg.to_str().unwrap()]);
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
}

#[test]
fn errors_are_one_line_with_status_2() {
    let dir = temp_dir("errors");
    let curve = |w: f64| json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0], [1, 0]], "weights": [1.0, w]});
    for w in [0.0, -1.0] {
        let file = write(&dir, "bad.json", &curve(w));
        let message = fails(&["eval", &file, "--at", "[0.5]"]);
        assert!(message.contains("weight"), "{message}");
        fails(&["insert", &file, "--knot", "0.5"]);
    }
    let surface = |weights: Value, net: Value| json!({"degree": [1, 1], "knots": [[0, 0, 1, 1], [0, 0, 1, 1]], "control_points": net, "weights": weights});
    let net = json!([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 0]]]);
    for w in [
        json!([[1, 1], [1, 0]]),
        json!([[1, 1], [-2, 1]]),
        json!([[1, 1], [1]]),
    ] {
        let file = write(&dir, "bad-surface.json", &surface(w, net.clone()));
        fails(&["eval", &file, "--at", "[[0.5, 0.5]]"]);
    }
    // Mismatched net sizes, ragged nets, mixed dimensions.
    let mut plain = surface(json!(null), json!([[[0, 0, 0], [0, 1, 0]]]));
    plain.as_object_mut().unwrap().remove("weights");
    let file = write(&dir, "short.json", &plain);
    assert!(fails(&["eval", &file, "--at", "[[0.5, 0.5]]"]).contains("rows"));
    plain["control_points"] = json!([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0]]]);
    let file = write(&dir, "ragged.json", &plain);
    assert!(fails(&["eval", &file, "--at", "[[0.5, 0.5]]"]).contains("row 1"));
    plain["control_points"] = json!([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1]]]);
    let file = write(&dir, "mixed.json", &plain);
    fails(&["eval", &file, "--at", "[[0.5, 0.5]]"]);
    // Out of the domain; NURBS derivative. Without --direction, operations act along u.
    plain["control_points"] = net.clone();
    let file = write(&dir, "good.json", &plain);
    fails(&["eval", &file, "--at", "[[0.5, 1.5]]"]);
    let along_u = ok(&["insert", &file, "--knot", "0.5"]);
    assert_eq!(
        along_u,
        ok(&["insert", &file, "--knot", "0.5", "--direction", "u"])
    );
    fails(&["split", &file, "--at", "1.0", "--direction", "u"]);
    let file = write(
        &dir,
        "circle.json",
        &ok(&["make", "circle", "--center", "[0, 0]", "--radius", "1"]),
    );
    fails(&["derivative", &file]);
    fails(&["insert", &file, "--knot", "0.5", "--direction", "u"]);
    // Degenerate axes and normals, bad radii and angles.
    let profile = write(
        &dir,
        "profile.json",
        &json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[1, 0, 0], [1, 0, 1]]}),
    );
    assert!(
        fails(&["make", "revolve", &profile, "--axis-direction", "[0, 0, 0]"]).contains("axis")
    );
    fails(&["make", "revolve", &profile, "--angle", "0"]);
    fails(&["make", "revolve", &profile, "--angle", "400"]);
    assert!(
        fails(&[
            "make",
            "torus",
            "--center",
            "[0, 0, 0]",
            "--major",
            "2",
            "--minor",
            "1",
            "--axis",
            "[0, 0, 0]"
        ])
        .contains("axis")
    );
    fails(&[
        "make",
        "torus",
        "--center",
        "[0, 0, 0]",
        "--major",
        "1",
        "--minor",
        "2",
    ]);
    assert!(
        fails(&[
            "make",
            "circle",
            "--center",
            "[0, 0, 0]",
            "--radius",
            "1",
            "--normal",
            "[0, 0, 0]"
        ])
        .contains("normal")
    );
    fails(&["make", "circle", "--center", "[0, 0]", "--radius", "-1"]);
    fails(&[
        "make",
        "circle",
        "--center",
        "[0, 0]",
        "--radius",
        "1",
        "--normal",
        "[0, 0, 1]",
    ]);
    fails(&["make", "sphere", "--center", "[0, 0]", "--radius", "1"]);
    fails(&[
        "make", "arc", "--center", "[0, 0]", "--radius", "1", "--sweep", "0",
    ]);
    fails(&[
        "make", "conic", "--p0", "[0, 0]", "--p1", "[1, 0]", "--p2", "[2, 0]", "--w1", "1",
    ]);
    fails(&[
        "make", "conic", "--p0", "[0, 0]", "--p1", "[1, 1]", "--p2", "[2, 0]", "--w1", "0",
    ]);
    let line = write(
        &dir,
        "line.json",
        &json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0], [1, 0]]}),
    );
    assert!(fails(&["make", "extrude", &line, "--vector", "[0, 0]"]).contains("zero"));
    fails(&["make", "extrude", &line, "--vector", "[0, 0, 1]"]);
    // Meshes: bad extension, 4-D surfaces, curves.
    let sphere = write(
        &dir,
        "sphere.json",
        &ok(&["make", "sphere", "--center", "[0, 0, 0]", "--radius", "1"]),
    );
    fails(&[
        "mesh",
        &sphere,
        "-o",
        dir.join("sphere.stl").to_str().unwrap(),
    ]);
    fails(&[
        "mesh",
        &sphere,
        "-o",
        dir.join("sphere.obj").to_str().unwrap(),
        "--segments-u",
        "0",
    ]);
    fails(&["mesh", &line, "-o", dir.join("line.obj").to_str().unwrap()]);
    let four = json!({"degree": [1, 1], "knots": [[0, 0, 1, 1], [0, 0, 1, 1]], "control_points": [[[0, 0, 0, 0], [0, 1, 0, 0]], [[1, 0, 0, 0], [1, 1, 0, 0]]]});
    let four = write(&dir, "four.json", &four);
    fails(&["mesh", &four, "-o", dir.join("four.obj").to_str().unwrap()]);
}
