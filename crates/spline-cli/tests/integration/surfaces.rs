//! The `spline` tool on NURBS curves and surfaces: every reference case of
//! `tests/data/reference/{nurbs_eval,surface_eval}.json` through `spline eval`, the `make`
//! constructions checked for exactness, structural operations checked for invariance,
//! `mesh` outputs, and errors (exit status 2, one line on standard error, never a panic).

use serde_json::{Value, json};
use spline_testing::compare::assert_close;
use spline_testing::reference::{cases, flatten};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh directory for one test's files, removed when the test ends.
struct TempDir(PathBuf);

impl TempDir {
    fn join(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl std::ops::Deref for TempDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn temp_dir(test: &str) -> TempDir {
    let dir =
        std::env::temp_dir().join(format!("spline-cli-surfaces-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    TempDir(dir)
}

fn write(dir: &Path, name: &str, value: &Value) -> String {
    let path = dir.join(name);
    std::fs::write(&path, value.to_string()).unwrap();
    path.to_str().unwrap().to_owned()
}

struct Output {
    code: i32,
    stdout: String,
    stderr: String,
}

fn run(args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_spline"))
        .args(args)
        .output()
        .expect("the spline binary runs");
    Output {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8(out.stdout).unwrap(),
        stderr: String::from_utf8(out.stderr).unwrap(),
    }
}

/// Runs a command that must succeed and print JSON.
fn ok(args: &[&str]) -> Value {
    let out = run(args);
    assert_eq!(out.code, 0, "spline {args:?} failed: {}", out.stderr);
    serde_json::from_str(&out.stdout)
        .unwrap_or_else(|e| panic!("spline {args:?}: {e}: {}", out.stdout))
}

/// Runs a command that must fail cleanly; returns the message.
fn fails(args: &[&str]) -> String {
    let out = run(args);
    assert_eq!(
        out.code, 2,
        "spline {args:?} should fail with status 2; stdout {}",
        out.stdout
    );
    assert!(
        out.stdout.is_empty(),
        "spline {args:?} printed {}",
        out.stdout
    );
    let lines: Vec<&str> = out.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "spline {args:?}: stderr {:?}", out.stderr);
    assert!(lines[0].starts_with("spline: "), "{}", lines[0]);
    assert!(!out.stderr.contains("panicked"));
    lines[0].to_owned()
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn sub(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

fn eval_points(path: &str, at: &Value) -> Vec<Vec<f64>> {
    ok(&["eval", path, "--at", &at.to_string()])
        .as_array()
        .unwrap()
        .iter()
        .map(|d| flatten(if d[0][0].is_array() { &d[0][0] } else { &d[0] }))
        .collect()
}

#[test]
fn reference_nurbs_eval_through_the_tool() {
    let dir = temp_dir("nurbs-eval");
    let all = cases("nurbs_eval");
    assert!(all.len() >= 13);
    for case in &all {
        let name = case["name"].as_str().unwrap();
        let file = write(&dir, &format!("{name}.json"), &case["curve"]);
        let k = case["derivatives"].to_string();
        let got = ok(&[
            "eval",
            &file,
            "--at",
            &case["params"].to_string(),
            "--derivatives",
            &k,
        ]);
        for (i, (g, e)) in got
            .as_array()
            .unwrap()
            .iter()
            .zip(case["expected"].as_array().unwrap())
            .enumerate()
        {
            let e = flatten(e);
            let scale = e.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert_close(
                &flatten(g),
                &e,
                1e-9 * scale,
                &format!("{name} parameter {i}"),
            );
        }
    }
}

#[test]
fn reference_surface_eval_through_the_tool() {
    let dir = temp_dir("surface-eval");
    let all = cases("surface_eval");
    assert!(all.len() >= 12);
    for case in &all {
        let name = case["name"].as_str().unwrap();
        let file = write(&dir, &format!("{name}.json"), &case["surface"]);
        let k = case["derivatives"].to_string();
        let got = ok(&[
            "eval",
            &file,
            "--at",
            &case["params"].to_string(),
            "--derivatives",
            &k,
        ]);
        let got = got.as_array().unwrap();
        assert_eq!(got.len(), case["params"].as_array().unwrap().len());
        for (i, (g, e)) in got
            .iter()
            .zip(case["expected"].as_array().unwrap())
            .enumerate()
        {
            // [k][l][coord] for k, l = 0..=K.
            assert_eq!(g.as_array().unwrap().len(), 3);
            assert_eq!(g[0].as_array().unwrap().len(), 3);
            let e = flatten(e);
            let scale = e.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert_close(
                &flatten(g),
                &e,
                1e-9 * scale,
                &format!("{name} parameter {i}"),
            );
        }
        // The same surface with unit weights is the same surface.
        let mut rational = case["surface"].clone();
        let shape: Vec<Value> = rational["control_points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|row| json!(vec![1.0; row.as_array().unwrap().len()]))
            .collect();
        rational["weights"] = json!(shape);
        let file = write(&dir, &format!("{name}-rational.json"), &rational);
        let got = ok(&[
            "eval",
            &file,
            "--at",
            &case["params"].to_string(),
            "--derivatives",
            &k,
        ]);
        for (g, e) in got
            .as_array()
            .unwrap()
            .iter()
            .zip(case["expected"].as_array().unwrap())
        {
            let e = flatten(e);
            let scale = e.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert_close(
                &flatten(g),
                &e,
                1e-9 * scale,
                &format!("{name} with unit weights"),
            );
        }
    }
}

fn params(n: usize) -> Value {
    json!((0..=n).map(|i| i as f64 / n as f64).collect::<Vec<_>>())
}

fn grid(n: usize) -> Value {
    let mut uv = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            uv.push(json!([i as f64 / n as f64, j as f64 / n as f64]));
        }
    }
    json!(uv)
}

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
