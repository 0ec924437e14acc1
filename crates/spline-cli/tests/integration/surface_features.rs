//! `spline surface-features` through the binary: the torus's parabolic circles, none on a
//! sphere, the ellipsoid's umbilics and ridges (its principal sections), the spheroid's
//! umbilics at its poles, and the error contract.

use crate::common;

use common::{spline, temp_file};

/// A torus (radii 3 and 1, centre (1, 2, 3), axis z) has exactly two parabolic lines, its
/// top and bottom circles; a sphere has none (its poles are singular points of the
/// parametrisation, not parabolic lines).
#[test]
fn torus_and_sphere() {
    let torus = spline(&[
        "make",
        "torus",
        "--center",
        "[1, 2, 3]",
        "--major",
        "3",
        "--minor",
        "1",
    ]);
    let path = temp_file("torus.json", &torus.stdout);
    let out = spline(&["surface-features", &path, "--samples", "4"]).json();
    let lines = out["parabolic_lines"].as_array().unwrap();
    assert_eq!(lines.len(), 2, "{out}");
    // Both principal curvatures are constant along their lines of curvature (meridians and
    // parallels): no ridge curves, every patch a constant region of both colours.
    assert!(out["ridges"].as_array().unwrap().is_empty());
    assert_eq!(out["ridge_constant_regions"].as_array().unwrap().len(), 32);
    let mut heights = Vec::new();
    for line in lines {
        let points = line["points"].as_array().unwrap();
        assert_eq!(points.len(), line["uv"].as_array().unwrap().len());
        assert!(points.len() >= 16);
        for p in points {
            let (x, y, z) = (
                p[0].as_f64().unwrap() - 1.0,
                p[1].as_f64().unwrap() - 2.0,
                p[2].as_f64().unwrap() - 3.0,
            );
            assert!((z.abs() - 1.0).abs() < 1e-12 && (x.hypot(y) - 3.0).abs() < 1e-12);
        }
        heights.push(points[0][2].as_f64().unwrap() - 3.0);
    }
    assert!(heights[0] * heights[1] < 0.0);
    let sphere = spline(&["make", "sphere", "--center", "[0, 0, 0]", "--radius", "2"]);
    let path = temp_file("sphere.json", &sphere.stdout);
    let out = spline(&["surface-features", &path]).json();
    assert!(
        out["parabolic_lines"].as_array().unwrap().is_empty(),
        "{out}"
    );
    // Every point of a sphere is umbilic: none listed, and not isolated.
    assert!(out["umbilics"].as_array().unwrap().is_empty());
    assert_eq!(out["umbilics_isolated"], false);
}

#[test]
fn bad_input_exits_2_with_one_line() {
    let curve = temp_file(
        "curve.json",
        r#"{"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control_points": [[0, 0, 0], [1, 1, 0], [2, 0, 1]]}"#,
    );
    assert!(
        spline(&["surface-features", &curve])
            .assert_clean_error()
            .contains("surface")
    );
    let flat = temp_file(
        "flat.json",
        r#"{"degree": [1, 1], "knots": [[0, 0, 1, 1], [0, 0, 1, 1]], "control_points": [[[0, 0], [0, 1]], [[1, 0], [1, 1]]]}"#,
    );
    assert!(
        spline(&["surface-features", &flat])
            .assert_clean_error()
            .contains("3-D")
    );
    let torus = spline(&[
        "make",
        "torus",
        "--center",
        "[0, 0, 0]",
        "--major",
        "3",
        "--minor",
        "1",
    ]);
    let path = temp_file("torus.json", &torus.stdout);
    assert!(
        spline(&["surface-features", &path, "--samples", "0"])
            .assert_clean_error()
            .contains("samples")
    );
    spline(&["surface-features", "/nonexistent.json"]).assert_clean_error();
}

/// An ellipsoid with semi-axes 1.5 (x), 2 (y), 1 (z): four umbilics at x = 0,
/// |y| = 2 √(1.75/3), |z| = √(1.25/3); no parabolic line.
#[test]
fn ellipsoid_umbilics() {
    let sphere = spline(&["make", "sphere", "--center", "[0, 0, 0]", "--radius", "1"]).json();
    let mut ellipsoid = sphere.clone();
    for p in ellipsoid["control_points"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .flat_map(|row| row.as_array_mut().unwrap())
    {
        let q = p.as_array_mut().unwrap();
        q[0] = (1.5 * q[0].as_f64().unwrap()).into();
        q[1] = (2.0 * q[1].as_f64().unwrap()).into();
    }
    let path = temp_file("ellipsoid.json", &ellipsoid.to_string());
    let out = spline(&["surface-features", &path]).json();
    // Ridges: red (κ₂) on the planes z = 0 and x = 0, blue (κ₁) on y = 0 and x = 0.
    let ridges = out["ridges"].as_array().unwrap();
    let mut colours = [0, 0];
    for r in ridges {
        let (planes, k) = match r["colour"].as_str().unwrap() {
            "red" => ([2, 0], 0),
            "blue" => ([1, 0], 1),
            other => panic!("colour {other}"),
        };
        colours[k] += 1;
        assert_eq!(
            r["points"].as_array().unwrap().len(),
            r["uv"].as_array().unwrap().len()
        );
        for p in r["points"].as_array().unwrap() {
            let d = planes
                .iter()
                .map(|&c| p[c].as_f64().unwrap().abs())
                .fold(f64::INFINITY, f64::min);
            assert!(d < 2e-6, "{r}");
        }
    }
    assert!(colours[0] > 0 && colours[1] > 0, "{out}");
    assert!(out["ridge_constant_regions"].as_array().unwrap().is_empty());
    assert!(
        out["parabolic_lines"].as_array().unwrap().is_empty(),
        "{out}"
    );
    let umbilics = out["umbilics"].as_array().unwrap();
    assert_eq!(umbilics.len(), 4, "{out}");
    assert_eq!(out["umbilics_isolated"], true);
    for u in umbilics {
        let p: Vec<f64> = u["point"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!(p[0].abs() < 1e-9);
        assert!((p[1].abs() - 2.0 * (1.75f64 / 3.0).sqrt()).abs() < 1e-9);
        assert!((p[2].abs() - (1.25f64 / 3.0).sqrt()).abs() < 1e-9);
        assert_eq!(u["singular_line"], false);
    }
    // `mesh --features` draws the ridges in their colours.
    let dir = std::env::temp_dir().join(format!("spline-mesh-ridges-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("ellipsoid.svg");
    spline(&["mesh", &path, "-o", svg.to_str().unwrap(), "--features"]).json();
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("rgb(215,30,40)") && text.contains("rgb(30,80,220)"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The spheroid with semi-axes 1.5, 1.5, 1: its two umbilics are its poles, on the lines
/// of the net that the sphere's construction collapses to them.
#[test]
fn spheroid_umbilics_at_the_poles() {
    let sphere = spline(&["make", "sphere", "--center", "[0, 0, 0]", "--radius", "1"]).json();
    let mut spheroid = sphere.clone();
    for p in spheroid["control_points"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .flat_map(|row| row.as_array_mut().unwrap())
    {
        let q = p.as_array_mut().unwrap();
        q[0] = (1.5 * q[0].as_f64().unwrap()).into();
        q[1] = (1.5 * q[1].as_f64().unwrap()).into();
    }
    let path = temp_file("spheroid.json", &spheroid.to_string());
    let out = spline(&["surface-features", &path]).json();
    let umbilics = out["umbilics"].as_array().unwrap();
    assert_eq!(umbilics.len(), 2, "{out}");
    assert_eq!(out["umbilics_isolated"], true);
    let mut z: Vec<f64> = umbilics
        .iter()
        .map(|u| {
            assert_eq!(u["singular_line"], true);
            let p = u["point"].as_array().unwrap();
            assert!(p[0].as_f64().unwrap().abs() < 1e-12 && p[1].as_f64().unwrap().abs() < 1e-12);
            p[2].as_f64().unwrap()
        })
        .collect();
    z.sort_by(f64::total_cmp);
    assert!((z[0] + 1.0).abs() < 1e-12 && (z[1] - 1.0).abs() < 1e-12);
    // A surface of revolution: the parallels' curvature is constant along them.
    assert!(!out["ridge_constant_regions"].as_array().unwrap().is_empty());
}

/// `mesh --features` draws the parabolic lines over the shaded surface (SVG only).
#[test]
fn mesh_draws_the_features() {
    let torus = spline(&[
        "make",
        "torus",
        "--center",
        "[0, 0, 0]",
        "--major",
        "3",
        "--minor",
        "1",
    ]);
    let path = temp_file("torus.json", &torus.stdout);
    let dir = std::env::temp_dir().join(format!("spline-mesh-features-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("torus.svg");
    let svg = svg.to_str().unwrap();
    spline(&["mesh", &path, "-o", svg, "--features"]).json();
    let text = std::fs::read_to_string(svg).unwrap();
    // Two circles of 4 patches × 8 samples: 64 segments, in the torus's orange.
    assert_eq!(text.matches("<line").count(), 64);
    assert!(text.contains("rgb(235,110,20)"));
    let plain = dir.join("plain.svg");
    spline(&["mesh", &path, "-o", plain.to_str().unwrap()]).json();
    assert!(!std::fs::read_to_string(plain).unwrap().contains("<line"));
    let obj = dir.join("torus.obj");
    assert!(
        spline(&["mesh", &path, "-o", obj.to_str().unwrap(), "--features"])
            .assert_clean_error()
            .contains("svg")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A function `s(u, v) = (u − ½)³ + v²` as its graph: the Hessian determinant is
/// `12 (u − ½)`, so the one parabolic line is `u = ½`; the output carries the ridges with
/// their colours and the graph's points.
#[test]
fn functions_as_graphs() {
    let b = [-0.125, 0.125, -0.125, 0.125];
    let w = [0.0, 0.0, 1.0];
    let rows: Vec<Vec<[f64; 1]>> = b
        .iter()
        .map(|bi| w.iter().map(|wj| [bi + wj]).collect())
        .collect();
    let json = serde_json::json!({"degree": [3, 2], "knots": [[0, 0, 0, 0, 1, 1, 1, 1], [0, 0, 0, 1, 1, 1]],
        "control_points": rows});
    let path = temp_file("function.json", &json.to_string());
    let out = spline(&["surface-features", &path]).json();
    let lines = out["parabolic_lines"].as_array().unwrap();
    assert_eq!(lines.len(), 1, "{out}");
    for (uv, p) in lines[0]["uv"]
        .as_array()
        .unwrap()
        .iter()
        .zip(lines[0]["points"].as_array().unwrap())
    {
        let (u, v) = (uv[0].as_f64().unwrap(), uv[1].as_f64().unwrap());
        assert!((u - 0.5).abs() < 1e-12);
        assert!((p[2].as_f64().unwrap() - ((u - 0.5).powi(3) + v * v)).abs() < 1e-12);
    }
    for r in out["ridges"].as_array().unwrap() {
        assert!(r["colour"] == "red" || r["colour"] == "blue");
    }
}
