//! `spline offset` on surfaces through the binary: a sphere exactly, a torus within the
//! tolerance (its tube radius grows by the distance), folds and misplaced options refused;
//! and `spline make sphere --axis` (its poles on the axis).

use crate::common;

use common::{spline, temp_file};
use serde_json::{Value, json};

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The offset surface evaluated by `spline eval` on an `n × n` grid of its domain.
fn points_of(surface: &Value, n: u32) -> Vec<[f64; 3]> {
    let path = temp_file("offset-surface.json", &surface.to_string());
    let bounds = |knots: &Value| {
        let k = knots.as_array().unwrap();
        (num(&k[0]), num(&k[k.len() - 1]))
    };
    let (a, b) = bounds(&surface["knots"][0]);
    let (c, d) = bounds(&surface["knots"][1]);
    let at = |lo: f64, hi: f64, k: u32| lo + (hi - lo) * f64::from(k) / f64::from(n - 1);
    let params: Vec<[f64; 2]> = (0..n)
        .flat_map(|i| (0..n).map(move |j| [at(a, b, i), at(c, d, j)]))
        .collect();
    let values = spline(&["eval", &path, "--at", &json!(params).to_string()]).json();
    values
        .as_array()
        .unwrap()
        .iter()
        .map(|v| {
            let p = &v[0][0];
            [num(&p[0]), num(&p[1]), num(&p[2])]
        })
        .collect()
}

#[test]
fn offset_of_a_sphere_is_the_concentric_sphere() {
    let sphere = spline(&["make", "sphere", "--center", "[1, 2, 3]", "--radius", "2"]).json();
    let path = temp_file("sphere.json", &sphere.to_string());
    let out = spline(&["offset", &path, "--distance", "0.5"]).json();
    assert_eq!(out["exact"], "sphere");
    assert_eq!(num(&out["max_error"]), 0.0);
    for p in points_of(&out["surface"], 13) {
        let r = ((p[0] - 1.0).powi(2) + (p[1] - 2.0).powi(2) + (p[2] - 3.0).powi(2)).sqrt();
        assert!((r - 2.5).abs() <= 1e-13, "{p:?}: {r}");
    }
}

#[test]
fn offset_of_a_torus_is_exact_and_its_fold() {
    let torus = spline(&[
        "make",
        "torus",
        "--center",
        "[0, 0, 0]",
        "--major",
        "2",
        "--minor",
        "0.5",
    ])
    .json();
    let path = temp_file("torus.json", &torus.to_string());
    let out = spline(&["offset", &path, "--distance", "0.2", "--tolerance", "1e-6"]).json();
    // The revolution of the concentric tube circle.
    assert_eq!(out["exact"], "revolution");
    assert_eq!(num(&out["max_error"]), 0.0);
    assert!(out["surface"]["weights"].is_array());
    for p in points_of(&out["surface"], 21) {
        let tube = (p[0].hypot(p[1]) - 2.0).hypot(p[2]);
        assert!((tube - 0.7).abs() <= 1e-13, "{p:?}: {tube}");
    }
    let message = spline(&["offset", &path, "--distance", "-0.6"]).assert_clean_error();
    assert!(message.contains("folds"), "{message}");
    let message = spline(&["offset", &path, "--distance", "0.1", "--direction", "0,0,1"])
        .assert_clean_error();
    assert!(message.contains("normal"), "{message}");
}

#[test]
fn make_sphere_with_its_poles_on_an_axis() {
    let default = spline(&["make", "sphere", "--center", "[1, 2, 3]", "--radius", "2"]).json();
    let along_z = spline(&[
        "make",
        "sphere",
        "--center",
        "[1, 2, 3]",
        "--radius",
        "2",
        "--axis",
        "[0, 0, 5]",
    ])
    .json();
    assert_eq!(default, along_z, "--axis z is the default sphere");
    let axis = [1.0, -2.0, 2.0]; // length 3
    let sphere = spline(&[
        "make",
        "sphere",
        "--center",
        "[1, 2, 3]",
        "--radius",
        "2",
        "--axis",
        "[1, -2, 2]",
    ])
    .json();
    let points = points_of(&sphere, 11);
    for p in &points {
        let r = ((p[0] - 1.0).powi(2) + (p[1] - 2.0).powi(2) + (p[2] - 3.0).powi(2)).sqrt();
        assert!((r - 2.0).abs() <= 1e-14, "{p:?}: {r}");
    }
    // The first row of the grid is u = 0 (the north pole), the last u = 1 (the south).
    for (row, sign) in [(0, 1.0), (10, -1.0)] {
        for p in &points[row * 11..(row + 1) * 11] {
            let pole = [
                1.0 + sign * 2.0 * axis[0] / 3.0,
                2.0 + sign * 2.0 * axis[1] / 3.0,
                3.0 + sign * 2.0 * axis[2] / 3.0,
            ];
            let e = (0..3).map(|i| (p[i] - pole[i]).powi(2)).sum::<f64>().sqrt();
            assert!(e <= 1e-14, "{p:?} vs {pole:?}");
        }
    }
    for bad in ["[0, 0, 0]", "[1, NaN, 0]", "[1, 2]"] {
        spline(&[
            "make",
            "sphere",
            "--center",
            "[0, 0, 0]",
            "--radius",
            "1",
            "--axis",
            bad,
        ])
        .assert_clean_error();
    }
}
