//! `closest`, `intersect` (surface cases), `make skin | sweep | coons | gordon` and
//! `approximate-surface` through the binary: results against closed forms, and the error
//! contract (exit status 2, one line).

// Grid indices become coordinates: small integer counts, exact as f64.
#![allow(clippy::cast_lossless)]

use crate::common;
use common::{spline, temp_file};
use serde_json::Value;

fn line(a: [f64; 3], b: [f64; 3]) -> String {
    format!(r#"{{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [{a:?}, {b:?}]}}"#)
}

fn num(v: &Value) -> f64 {
    v.as_f64().expect("a number")
}

#[test]
fn closest_on_a_sphere_and_a_curve() {
    let sphere = spline(&["make", "sphere", "--center", "[0,0,0]", "--radius", "2"]).json();
    let path = temp_file("sphere.json", &sphere.to_string());
    let out = spline(&["closest", &path, "--points", "[[3,4,0],[0,0,5]]"]).json();
    assert!((num(&out[0]["distance"]) - 3.0).abs() < 1e-12);
    assert!((num(&out[1]["point"][2]) - 2.0).abs() < 1e-12);
    assert!(out[0]["v"].is_number());
    let c = temp_file("line.json", &line([0.0, 0.0, 0.0], [2.0, 0.0, 0.0]));
    let out = spline(&["closest", &c, "--points", "[[0.5,1,0]]"]).json();
    assert!((num(&out[0]["u"]) - 0.25).abs() < 1e-12);
    assert!(out[0].get("v").is_none());
    // Errors: wrong dimension, malformed points, not finite.
    spline(&["closest", &path, "--points", "[[1,2]]"]).assert_clean_error();
    spline(&["closest", &path, "--points", "[1,2,3]"]).assert_clean_error();
    spline(&["closest", &path, "--points", "[[1e999,0,0]]"]).assert_clean_error();
}

#[test]
fn intersections() {
    let sphere = spline(&["make", "sphere", "--center", "[0,0,0]", "--radius", "1"]).json();
    let s = temp_file("sphere.json", &sphere.to_string());
    let l = temp_file("line.json", &line([-2.0, 0.0, 0.0], [2.0, 0.0, 0.0]));
    let hits = spline(&["intersect", &l, &s]).json();
    assert_eq!(hits.as_array().unwrap().len(), 2);
    assert!((num(&hits[0]["point"][0]) + 1.0).abs() < 1e-12);
    assert_eq!(hits[0]["tangential"], Value::Bool(false));
    // Either order.
    let again = spline(&["intersect", &s, &l]).json();
    assert_eq!(again.as_array().unwrap().len(), 2);
    let plane = temp_file(
        "plane.json",
        r#"{"degree": [1, 1], "knots": [[0,0,1,1],[0,0,1,1]], "control_points": [[[-2,-2,0.5],[-2,2,0.5]],[[2,-2,0.5],[2,2,0.5]]]}"#,
    );
    let curves = spline(&["intersect", &s, &plane, "--tolerance", "1e-5"]).json();
    assert_eq!(curves.as_array().unwrap().len(), 1);
    assert_eq!(curves[0]["closed"], Value::Bool(true));
    for p in curves[0]["points"].as_array().unwrap() {
        let (x, y) = (num(&p[0]), num(&p[1]));
        assert!(((x * x + y * y).sqrt() - 0.75f64.sqrt()).abs() < 1e-9);
    }
    assert_eq!(
        curves[0]["uv_a"].as_array().unwrap().len(),
        curves[0]["points"].as_array().unwrap().len()
    );
    // The same curve as B-splines: in space, and on both surfaces' parameters, each a
    // curve every reader takes.
    let pieces = curves[0]["pieces"].as_array().unwrap();
    assert_eq!(pieces.len(), 1);
    assert!(num(&pieces[0]["max_error"]) <= 1e-5);
    let curve = temp_file("ssi.json", &pieces[0]["curve"].to_string());
    let ts = "[0, 0.1, 0.25, 0.5, 0.8, 1]";
    let on_curve = spline(&["eval", &curve, "--at", ts]).json();
    let on_a = spline(&[
        "eval",
        &temp_file("pa.json", &pieces[0]["pcurve_a"].to_string()),
        "--at",
        ts,
    ])
    .json();
    for (k, value) in on_curve.as_array().unwrap().iter().enumerate() {
        let p = &value[0];
        let (x, y, z) = (num(&p[0]), num(&p[1]), num(&p[2]));
        assert!(((x * x + y * y).sqrt() - 0.75f64.sqrt()).abs() < 1e-5 && (z - 0.5).abs() < 1e-5);
        // The sphere at the image's parameters is the same point.
        let uv = &on_a[k][0];
        let at = spline(&[
            "eval",
            &s,
            "--at",
            &format!("[[{}, {}]]", num(&uv[0]), num(&uv[1])),
        ])
        .json();
        let q = &at[0][0][0];
        let gap =
            ((num(&q[0]) - x).powi(2) + (num(&q[1]) - y).powi(2) + (num(&q[2]) - z).powi(2)).sqrt();
        assert!(gap < 2e-5, "{gap}");
    }
    spline(&["intersect", &s, &plane, "--tolerance", "-1"]).assert_clean_error();
    spline(&["intersect", &l, &l]).assert_clean_error();
    let flat = temp_file(
        "flat.json",
        r#"{"degree": 1, "knots": [0,0,1,1], "control_points": [[0,0],[1,1]]}"#,
    );
    spline(&["intersect", &flat, &s]).assert_clean_error();
}

#[test]
fn constructions() {
    let bottom = temp_file("b.json", &line([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]));
    let top = temp_file("t.json", &line([0.0, 1.0, 0.0], [1.0, 1.0, 0.0]));
    let left = temp_file("l.json", &line([0.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
    let right = temp_file("r.json", &line([1.0, 0.0, 0.0], [1.0, 1.0, 0.0]));
    let coons = spline(&["make", "coons", "--curves", &bottom, &top, &left, &right]).json();
    let c = temp_file("coons.json", &coons.to_string());
    let at = spline(&["eval", &c, "--at", "[[0.25,0.5]]"]).json();
    assert!(
        (num(&at[0][0][0][0]) - 0.25).abs() < 1e-15 && (num(&at[0][0][0][1]) - 0.5).abs() < 1e-15
    );
    // Skin through three lines at heights 0, 1, 3.
    let l1 = temp_file("s1.json", &line([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]));
    let l2 = temp_file("s2.json", &line([0.0, 0.5, 1.0], [1.0, 0.5, 1.0]));
    let l3 = temp_file("s3.json", &line([0.0, 0.0, 3.0], [1.0, 0.0, 3.0]));
    let skinned = spline(&["make", "skin", "--curves", &l1, &l2, &l3, "--degree", "2"]).json();
    assert_eq!(skinned["surface"]["degree"][1], 2);
    // The sections' parameters: averaged chord lengths 1.118… and 2.062… between them, and
    // the surface there is the middle section.
    let params: Vec<f64> = skinned["params"]
        .as_array()
        .unwrap()
        .iter()
        .map(num)
        .collect();
    let (a, b) = (1.25f64.sqrt(), 4.25f64.sqrt());
    assert_eq!(params.len(), 3);
    assert!(params[0] == 0.0 && params[2] == 1.0 && (params[1] - a / (a + b)).abs() < 1e-15);
    let sk = temp_file("skinned.json", &skinned.to_string());
    let at = spline(&["eval", &sk, "--at", &format!("[[0.3,{}]]", params[1])]).json();
    let p = &at[0][0][0];
    assert!((num(&p[0]) - 0.3).abs() < 1e-14 && (num(&p[1]) - 0.5).abs() < 1e-14);
    assert!((num(&p[2]) - 1.0).abs() < 1e-14, "{at}");
    // Sweep a segment along a straight path.
    let path = temp_file("path.json", &line([0.0, 0.0, 0.0], [0.0, 0.0, 4.0]));
    let prof = temp_file("prof.json", &line([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]));
    let swept = spline(&[
        "make",
        "sweep",
        "--profile",
        &prof,
        "--path",
        &path,
        "--sections",
        "3",
    ])
    .json();
    let sw = temp_file("sweep.json", &swept.to_string());
    let at = spline(&["eval", &sw, "--at", "[[1,1]]"]).json();
    assert!((num(&at[0][0][0][2]) - 4.0).abs() < 1e-12);
    // Gordon through the four lines of a square network.
    let g = spline(&[
        "make",
        "gordon",
        "--u-curves",
        &bottom,
        &top,
        "--v-curves",
        &left,
        &right,
    ])
    .json();
    assert!(g["surface"]["control_points"].is_array());
    assert_eq!(g["params_u"], serde_json::json!([0.0, 1.0]));
    assert_eq!(g["params_v"], serde_json::json!([0.0, 1.0]));
    assert_eq!(g["crossing_gap"], 0.0);
    // Errors.
    spline(&["make", "coons", "--curves", &bottom, &top, &left, &l3]).assert_clean_error();
    spline(&["make", "skin", "--curves", &l1]).assert_clean_error();
    spline(&[
        "make",
        "sweep",
        "--profile",
        &prof,
        "--path",
        &path,
        "--sections",
        "1",
    ])
    .assert_clean_error();
    spline(&[
        "make",
        "gordon",
        "--u-curves",
        &bottom,
        &l3,
        "--v-curves",
        &left,
        &right,
    ])
    .assert_clean_error();
}

#[test]
fn approximate_surface_from_points_and_a_mesh() {
    let mut pts = Vec::new();
    for i in 0..=20u8 {
        for j in 0..=20u8 {
            let (x, y) = (f64::from(i) / 20.0, f64::from(j) / 20.0);
            pts.push(vec![x, y, 0.2 * (3.0 * x).sin() * y]);
        }
    }
    let file = temp_file("pts.json", &serde_json::to_string(&pts).unwrap());
    let out = spline(&["approximate-surface", &file, "--control-points", "[8,8]"]).json();
    assert!(
        num(&out["max_deviation"]) < 1e-3,
        "{}",
        out["max_deviation"]
    );
    assert!(out["surface"]["control_points"].is_array());
    assert!(out["rms"].is_number() && out["max_deviation_to_data"].is_number());
    let mut obj = String::new();
    for p in &pts {
        obj += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for i in 0..20 {
        for j in 0..20 {
            let k = i * 21 + j + 1;
            obj += &format!(
                "f {} {} {}\nf {} {} {}\n",
                k,
                k + 21,
                k + 1,
                k + 1,
                k + 21,
                k + 22
            );
        }
    }
    let mesh = temp_file("mesh.obj", &obj);
    let out = spline(&[
        "approximate-surface",
        &mesh,
        "--control-points",
        "[8,8]",
        "--degree",
        "[2,2]",
    ])
    .json();
    assert!(num(&out["max_deviation"]) < 1e-3);
    // Errors: too many control points for the data, bad counts, bad mesh.
    spline(&["approximate-surface", &file, "--control-points", "[30,30]"]).assert_clean_error();
    spline(&[
        "approximate-surface",
        &file,
        "--control-points",
        "[18446744073709551615,4]",
    ])
    .assert_clean_error();
    spline(&[
        "approximate-surface",
        &file,
        "--control-points",
        "[8,8]",
        "--smoothing",
        "-1",
    ])
    .assert_clean_error();
    let bad = temp_file("bad.obj", "v 0 0 0\nf 1 2 x\n");
    spline(&["approximate-surface", &bad, "--control-points", "[4,4]"]).assert_clean_error();
}

/// Skinning four rational conics whose middle weights are 1, 8, 0.2, 8 (reproducer
/// `conic_section_*.json`, issue 25 item 3): the weights interpolated at degree 3 across
/// the sections went down to −19.7 and the tool reported "weight 6 … got -19.70" as if the
/// user had given it. Now the surface has positive weights and passes through every
/// section: points of each conic, from `spline eval`, are on it (`spline closest`).
#[test]
fn skinning_rational_conics_keeps_the_weights_positive() {
    let conic = |z: f64, w: f64| {
        temp_file(
            "conic.json",
            &format!(
                r#"{{"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control_points": [[0, 0, {z}], [1, 1, {z}], [2, 0, {z}]], "weights": [1, {w}, 1]}}"#
            ),
        )
    };
    let sections = [
        conic(0.0, 1.0),
        conic(1.0, 8.0),
        conic(2.0, 0.2),
        conic(3.0, 8.0),
    ];
    let mut args = vec!["make", "skin", "--curves"];
    args.extend(sections.iter().map(String::as_str));
    let run = spline(&args);
    assert_eq!(run.status, 0, "{}", run.stderr);
    let report = run.json();
    assert_eq!(report["params"].as_array().map(Vec::len), Some(4));
    let surface = &report["surface"];
    let weights: Vec<f64> = surface["weights"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|row| row.as_array().unwrap().iter().map(num))
        .collect();
    assert!(weights.iter().all(|&w| w > 0.0), "{weights:?}");
    let path = temp_file("skin.json", &surface.to_string());
    let us = "[0, 0.1, 0.25, 0.5, 0.7, 0.9, 1]";
    for section in &sections {
        let values = spline(&["eval", section, "--at", us]).json();
        let points: Vec<Value> = values
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v[0].clone())
            .collect();
        let hits = spline(&[
            "closest",
            &path,
            "--points",
            &Value::Array(points).to_string(),
        ])
        .json();
        for hit in hits.as_array().unwrap() {
            assert!(num(&hit["distance"]) < 1e-9, "{hit}");
        }
    }
}

/// `make coons` with rational boundaries (issue 25 item 9): a NURBS patch through two
/// circular arcs and two lines is the quarter cylinder between them, every boundary on it.
#[test]
fn rational_coons_is_the_cylinder_between_two_arcs() {
    let h = 0.5f64.sqrt();
    let arc = |z: f64| {
        temp_file(
            "arc.json",
            &format!(
                r#"{{"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control_points": [[1, 0, {z}], [1, 1, {z}], [0, 1, {z}]], "weights": [1, {h}, 1]}}"#
            ),
        )
    };
    let (bottom, top) = (arc(0.0), arc(2.0));
    let left = temp_file("l.json", &line([1.0, 0.0, 0.0], [1.0, 0.0, 2.0]));
    let right = temp_file("r.json", &line([0.0, 1.0, 0.0], [0.0, 1.0, 2.0]));
    let patch = spline(&["make", "coons", "--curves", &bottom, &top, &left, &right]).json();
    assert!(patch["weights"].is_array(), "{patch}");
    let path = temp_file("coons.json", &patch.to_string());
    let at = spline(&[
        "eval",
        &path,
        "--at",
        "[[0, 0.5], [0.3, 0.7], [0.8, 1], [1, 0.25]]",
    ])
    .json();
    for (k, z) in [1.0, 1.4, 2.0, 0.5].iter().enumerate() {
        let p = &at[k][0][0];
        let (x, y) = (num(&p[0]), num(&p[1]));
        assert!((x.hypot(y) - 1.0).abs() < 1e-14, "{at}");
        assert!((num(&p[2]) - z).abs() < 1e-14, "{at}");
    }
    // A boundary that misses a corner is a clean error.
    let off = temp_file("off.json", &line([0.0, 1.0, 0.0], [0.0, 1.0, 2.5]));
    spline(&["make", "coons", "--curves", &bottom, &top, &left, &off]).assert_clean_error();
}
