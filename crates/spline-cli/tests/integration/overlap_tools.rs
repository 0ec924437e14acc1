//! Issue 25, items 1–3 through the binary: overlaps as intervals in `intersect`'s array,
//! self-intersections of a cusp and of a curve that goes back over itself, a single point
//! refused, and the global closest point on an offset's swallowtail.

use crate::common::{spline, temp_file};
use serde_json::{Value, json};
use std::time::Instant;

fn data(name: &str) -> String {
    format!("{}/tests/data/overlap/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// `spline intersect parabola.json parabola.json` printed 65,536 tangential points after
/// 8–12 s, `same_rand.json` 94,756 after ~22 s: one overlap entry each.
#[test]
fn a_curve_against_itself_is_one_overlap_entry() {
    for name in ["parabola.json", "same_rand.json"] {
        let started = Instant::now();
        let out = spline(&["intersect", &data(name), &data(name)]).json();
        assert!(started.elapsed().as_secs_f64() < 5.0, "{name}");
        let entries = out.as_array().unwrap();
        assert_eq!(entries.len(), 1, "{name}: {out}");
        let o = &entries[0];
        assert_eq!(o["overlap"], json!(true), "{o}");
        assert_eq!(o["u"], json!([0.0, 1.0]), "{o}");
        assert_eq!(o["v"], json!([0.0, 1.0]), "{o}");
        assert_eq!(o["reversed"], json!(false), "{o}");
    }
}

/// `spline intersect loop.json` (a cusp) and `backforth2.json` ran out of memory: the cusp
/// at most once, the turn back as one reversed overlap; all control points equal is a
/// clean error.
#[test]
fn cusp_turn_back_and_point() {
    let started = Instant::now();
    let out = spline(&["intersect", &data("loop.json")]).json();
    let entries = out.as_array().unwrap();
    // Its one self-intersection: the cusp at (1.5, 1), reported once, as tangential.
    assert_eq!(entries.len(), 1, "{out}");
    let e = &entries[0];
    assert!((num(&e["point"][0]) - 1.5).abs() < 1e-6, "{e}");
    assert!((num(&e["point"][1]) - 1.0).abs() < 1e-6, "{e}");
    assert_eq!(e["tangential"], json!(true), "{e}");
    let out = spline(&["intersect", &data("backforth2.json")]).json();
    let entries = out.as_array().unwrap();
    assert_eq!(entries.len(), 1, "{out}");
    let o = &entries[0];
    assert_eq!(o["overlap"], json!(true), "{o}");
    assert_eq!(o["reversed"], json!(true), "{o}");
    assert_eq!((num(&o["u"][0]), num(&o["v"][0])), (0.0, 1.0), "{o}");
    assert!((num(&o["u"][1]) - 0.5).abs() < 1e-4, "{o}");
    assert!(started.elapsed().as_secs_f64() < 5.0);
    let point = temp_file(
        "point.json",
        &json!({"degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 1],
                "control_points": [[1, 2], [1, 2], [1, 2], [1, 2]]})
        .to_string(),
    );
    let message = spline(&["intersect", &point]).assert_clean_error();
    assert!(message.contains("single point"), "{message}");
}

/// `spline closest off86_curve.json --points '[[0.27074343591339467,0.14593169505383835]]'`
/// gave 4.33e-6, a local minimum; the global one is 4.7e-8 (scipy's dense sampling:
/// 4.7169e-8 at u ≈ 0.16000).
#[test]
fn closest_point_on_the_swallowtail_is_global() {
    let out = spline(&[
        "closest",
        &data("off86_curve.json"),
        "--points",
        "[[0.27074343591339467,0.14593169505383835]]",
    ])
    .json();
    let d = num(&out[0]["distance"]);
    assert!(d < 4.72e-8 && d > 4.0e-8, "{out}");
    assert!((num(&out[0]["u"]) - 0.16).abs() < 1e-3, "{out}");
}

/// A curve lying in a surface over an interval: one overlap entry with its interval, and
/// the crossing elsewhere as a point (a polyline in the plane z = 0 over t in [0.5, 1], then
/// up and back down across it at t = 2.5).
#[test]
fn a_curve_in_a_surface_is_one_overlap_entry() {
    let plane = temp_file(
        "plane.json",
        r#"{"degree": [1, 1], "knots": [[0,0,1,1],[0,0,1,1]], "control_points": [[[0,0,0],[0,1,0]],[[1,0,0],[1,1,0]]]}"#,
    );
    let curve = temp_file(
        "polyline.json",
        r#"{"degree": 1, "knots": [0,0,1,2,3,3], "control_points": [[-0.5,0.5,0],[0.5,0.5,0],[0.8,0.5,1],[0.9,0.5,-1]]}"#,
    );
    let out = spline(&["intersect", &curve, &plane]).json();
    let entries = out.as_array().unwrap();
    assert_eq!(entries.len(), 2, "{out}");
    let o = &entries[0];
    assert_eq!(o["overlap"], json!(true), "{o}");
    assert!((num(&o["t"][0]) - 0.5).abs() < 1e-8 && (num(&o["t"][1]) - 1.0).abs() < 1e-8);
    assert!((num(&entries[1]["t"]) - 2.5).abs() < 1e-12, "{out}");
    assert!((num(&entries[1]["point"][0]) - 0.85).abs() < 1e-12, "{out}");
}
