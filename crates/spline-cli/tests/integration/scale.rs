//! Every operation at every scale (issue 25, item 2): the reproducers of
//! `tests/data/reproducers/` (see its README) give the scaled answer of the unscaled problem.
//! The expected values are independent: closed forms, or scipy (`BSpline`, `fsolve`,
//! `brentq`, `minimize`) on the unscaled data, times the scale.

use crate::common::{num, reproducer as data, spline, temp_file};
use serde_json::{Value, json};

fn point(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(num).collect()
}

/// `|a − b| ≤ rel · scale`.
fn assert_near(a: f64, b: f64, rel: f64, scale: f64, what: &str) {
    assert!(
        (a - b).abs() <= rel * scale,
        "{what}: {a:e} vs {b:e} (allowed {:e})",
        rel * scale
    );
}

/// A curve of the reproducers with its control points times `s`, as a temporary file.
fn scaled_curve(name: &str, s: f64) -> String {
    let mut curve: Value =
        serde_json::from_str(&std::fs::read_to_string(data(name)).unwrap()).unwrap();
    for p in curve["control_points"].as_array_mut().unwrap() {
        for x in p.as_array_mut().unwrap() {
            *x = json!(num(x) * s);
        }
    }
    temp_file(name, &curve.to_string())
}

/// A crossing: the parameters on both curves and the point of the unscaled pair.
type Crossing = (f64, f64, [f64; 2]);

/// `x1e20_*` (a pair of cubics × 1e20) keeps its 2 crossings and `x1e-20_*`
/// (`unscaled0078_*` × 1e-20) has its 3, no false ones; so do both pairs scaled further,
/// to sizes near 1e300 and 1e-300. scipy: polyline crossings of 2001 samples each,
/// polished by `fsolve` on the unscaled pairs.
#[test]
fn curve_intersections_scaled_by_1e20_and_1e_minus_20_and_to_1e300() {
    let cases: [(&str, f64, &[Crossing]); 2] = [
        (
            "x1e20",
            1e20,
            &[
                (
                    0.105_656_277_630_010_4,
                    0.579_306_315_037_541,
                    [0.633_932_998_607_329, 0.432_947_405_545_731],
                ),
                (
                    0.394_625_249_972_014_2,
                    0.923_535_521_194_564_2,
                    [0.682_252_828_732_515_4, 0.650_835_646_625_890_8],
                ),
            ],
        ),
        (
            "x1e-20",
            1e-20,
            &[
                (
                    0.837_779_860_264_971,
                    0.058_983_064_313_763_36,
                    [0.476_386_605_501_655_2, 0.607_568_001_363_052_6],
                ),
                (
                    0.907_373_660_207_649_3,
                    0.086_651_303_992_842_02,
                    [0.422_340_974_887_780_7, 0.623_878_995_108_332_1],
                ),
                (
                    0.948_662_840_017_949_3,
                    0.185_626_405_182_011_3,
                    [0.382_741_563_858_146_4, 0.567_188_333_322_014],
                ),
            ],
        ),
    ];
    // Each pair also scaled to sizes near 1e300 and 1e-300, and beyond 1e±100 the other way.
    let further = |s: f64| {
        if s > 1.0 {
            [1.0, 1e280, 1e-150]
        } else {
            [1.0, 1e-280, 1e150]
        }
    };
    for ((name, s, expected), more) in cases
        .iter()
        .flat_map(|case| further(case.1).map(move |m| (*case, m)))
    {
        let (a, b) = (format!("{name}_a.json"), format!("{name}_b.json"));
        let (a, b) = if more == 1.0 {
            (data(&a), data(&b))
        } else {
            (scaled_curve(&a, more), scaled_curve(&b, more))
        };
        let (s, name) = (s * more, format!("{name} × {more:e}"));
        let hits = spline(&["intersect", &a, &b]).json();
        let hits = hits.as_array().unwrap();
        assert_eq!(hits.len(), expected.len(), "{name}: {hits:?}");
        for (h, (u, v, p)) in hits.iter().zip(expected) {
            assert!(!h["tangential"].as_bool().unwrap(), "{name}: {h}");
            assert_near(num(&h["u"]), *u, 1e-9, 1.0, &name);
            assert_near(num(&h["v"]), *v, 1e-9, 1.0, &name);
            let q = point(&h["point"]);
            for k in 0..2 {
                assert_near(q[k], p[k] * s, 1e-9, s, &name);
            }
        }
    }
}

/// The line `y = 1e299, z = 2e299` against the sphere of radius 1e300 about the origin:
/// `x = ±√(1 − 0.01 − 0.04) · 1e300`, not one point at the centre.
#[test]
fn line_against_a_sphere_of_radius_1e300() {
    let hits = spline(&["intersect", &data("l300.json"), &data("s300.json")]).json();
    let hits = hits.as_array().unwrap();
    assert_eq!(hits.len(), 2, "{hits:?}");
    let x = 0.95f64.sqrt() * 1e300;
    for (h, sign) in hits.iter().zip([-1.0, 1.0]) {
        assert!(!h["tangential"].as_bool().unwrap(), "{h}");
        let q = point(&h["point"]);
        for (got, want) in q.iter().zip([sign * x, 1e299, 2e299]) {
            assert_near(*got, want, 1e-9, 1e300, "line–sphere point");
        }
        // The line runs from x = −2e300 to 2e300.
        assert_near(num(&h["t"]), 0.5 + sign * x / 4e300, 1e-9, 1.0, "t");
    }
}

/// `off_base.json` × s offset by 0.05 s within 1e-6 s: the same 4 cusps at every scale.
/// scipy: sign changes of κ d − 1 on 200,001 samples, `brentq`.
#[test]
fn offset_cusps_at_every_scale() {
    let cusps = [
        0.237_667_711_955_852_35,
        0.279_869_413_553_923_53,
        0.575_379_758_342_039_2,
        0.644_762_557_925_027_9,
    ];
    for s in [1e-300, 1e-100, 1.0, 1e100] {
        let curve = scaled_curve("off_base.json", s);
        let run = spline(&[
            "offset",
            &curve,
            "--distance",
            &format!("{:e}", 0.05 * s),
            "--tolerance",
            &format!("{:e}", 1e-6 * s),
        ]);
        let out = run.json();
        let found: Vec<f64> = out["cusps"].as_array().unwrap().iter().map(num).collect();
        assert_eq!(found.len(), 4, "scale {s:e}: {found:?}");
        for (u, want) in found.iter().zip(cusps) {
            assert_near(*u, want, 1e-9, 1.0, &format!("cusp at scale {s:e}"));
        }
        let error = num(&out["max_error"]);
        assert!(error > 0.0 && error <= 1e-6 * s, "scale {s:e}: {error:e}");
    }
}

/// Closest points on `surf150.json` (`surf0352_unscaled.json` × 1e150) from the points of
/// `q0352.json` × 1e150: the unscaled distances × 1e150 (scipy: the best of a 41 × 41 grid
/// polished by L-BFGS-B); points of `skin150.json` (evaluated by scipy) are on it.
#[test]
fn closest_points_on_surfaces_at_1e150() {
    let q: Vec<Vec<f64>> =
        serde_json::from_str(&std::fs::read_to_string(data("q0352.json")).unwrap()).unwrap();
    let targets: Vec<Vec<f64>> = q
        .iter()
        .map(|p| p.iter().map(|x| x * 1e150).collect())
        .collect();
    let hits = spline(&[
        "closest",
        &data("surf150.json"),
        "--points",
        &json!(targets).to_string(),
    ])
    .json();
    let unscaled = [0.0, 0.090_002_002_564_125_26, 0.025_834_036_884_730_963];
    for (h, d) in hits.as_array().unwrap().iter().zip(unscaled) {
        assert_near(num(&h["distance"]), d * 1e150, 1e-9, 1e150, "distance");
    }
    let on_skin = json!([
        [
            -5.133_333_333_333_331_5e149,
            6.189_194_885_712_788e149,
            1.199_999_999_999_999_8e150
        ],
        [
            -4.805_333_333_333_339e149,
            -6.419_118_856_914_863e149,
            4.000_000_000_000_000_7e149
        ]
    ]);
    let hits = spline(&[
        "closest",
        &data("skin150.json"),
        "--points",
        &on_skin.to_string(),
    ])
    .json();
    for (h, (u, v)) in hits
        .as_array()
        .unwrap()
        .iter()
        .zip([(0.3, 0.6), (0.71, 0.2)])
    {
        assert_near(num(&h["distance"]), 0.0, 1e-12, 1e150, "on the skin");
        assert_near(num(&h["u"]), u, 1e-9, 1.0, "u");
        assert_near(num(&h["v"]), v, 1e-9, 1.0, "v");
    }
}

/// Degree reduction of `off_base.json` × 1e-300 with `--refine --tolerance 1e-303`: the
/// reported error is the true one (it used to underflow to 0 while the curves were 75 times
/// the tolerance apart): the deviation sampled at 2001 parameters (values × 1e300 before
/// differences are squared) is within the tolerance and near the report.
#[test]
fn degree_reduction_at_1e_minus_300() {
    let s = 1e-300;
    let curve = scaled_curve("off_base.json", s);
    let out = spline(&[
        "reduce",
        &curve,
        "--times",
        "1",
        "--refine",
        "--tolerance",
        "1e-303",
    ])
    .json();
    let reported = num(&out["max_error"]);
    let result = temp_file("reduced.json", &out["curve"].to_string());
    let at: Vec<f64> = (0..=2000).map(|k| f64::from(k) / 2000.0).collect();
    let at = json!(at).to_string();
    let a = spline(&["eval", &curve, "--at", &at]).json();
    let b = spline(&["eval", &result, "--at", &at]).json();
    let mut sampled = 0.0f64;
    for (p, q) in a.as_array().unwrap().iter().zip(b.as_array().unwrap()) {
        let (p, q) = (point(&p[0]), point(&q[0]));
        let d = ((p[0] - q[0]) / s).hypot((p[1] - q[1]) / s) * s;
        sampled = sampled.max(d);
    }
    assert!(reported > 0.0 && reported <= 1e-303, "{reported:e}");
    assert!(sampled <= 1e-303, "sampled {sampled:e}");
    assert!(
        reported >= 0.5 * sampled,
        "{reported:e} vs sampled {sampled:e}"
    );
    // The same reduction unscaled, times the scale.
    let unit = scaled_curve("off_base.json", 1.0);
    let unscaled = spline(&["reduce", &unit, "--refine", "--tolerance", "1e-3"]).json();
    assert_near(
        reported,
        num(&unscaled["max_error"]) * s,
        1e-6,
        1e-303,
        "scaled report",
    );
}

/// `smooth` on an airfoil scaled by 1e300 or 1e-300: the unscaled curve, scaled (it said
/// "points 0 and 1 coincide" / "the data points all coincide").
#[test]
fn smoothing_airfoil_data_at_1e300_and_1e_minus_300() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/airfoils/clarkv.dat"
    ))
    .unwrap();
    let points: Vec<[f64; 2]> = text
        .lines()
        .filter_map(|line| {
            let v: Vec<f64> = line
                .split_whitespace()
                .map(str::parse)
                .collect::<Result<_, _>>()
                .ok()?;
            (v.len() == 2 && v[0] <= 1.0).then(|| [v[0], v[1]])
        })
        .collect();
    let run = |s: f64| {
        let scaled: Vec<[f64; 2]> = points.iter().map(|p| [p[0] * s, p[1] * s]).collect();
        let file = temp_file("airfoil.json", &json!(scaled).to_string());
        spline(&["smooth", &file, "--control-points", "12"]).json()
    };
    let unit = run(1.0);
    let control = |out: &Value| -> Vec<Vec<f64>> {
        out["curve"]["control_points"]
            .as_array()
            .unwrap()
            .iter()
            .map(point)
            .collect()
    };
    // Powers of two scale exactly: the same curve to the bit.
    for s in [2f64.powi(996), 2f64.powi(-996)] {
        let out = run(s);
        let scaled_back: Vec<Vec<f64>> = control(&out)
            .iter()
            .map(|p| p.iter().map(|x| x / s).collect())
            .collect();
        assert_eq!(scaled_back, control(&unit), "scale {s:e}");
    }
    // Decimal scales round the data (by 1e-16): the optimum of the largest deviation is
    // flat and the optimiser's path changes with such perturbations (as at scales 1.1 or
    // 1e290), so the curve is the same to the optimiser's convergence: the deviation to
    // 1e-4 of itself, every point of the scaled curve (scaled back) within a quarter of the
    // deviation of the unscaled curve (closest points).
    let at: Vec<f64> = (0..=100).map(|k| f64::from(k) / 100.0).collect();
    let at = json!(at).to_string();
    let unit_curve = temp_file("smoothed.json", &unit["curve"].to_string());
    let deviation = num(&unit["max_deviation"]);
    for s in [1e300, 1e-300] {
        let out = run(s);
        assert!(out.get("warnings").is_none(), "{}", out["warnings"]);
        assert_eq!(out["curvature_extrema"], unit["curvature_extrema"]);
        assert_near(
            num(&out["max_deviation"]) / s,
            deviation,
            1e-4,
            deviation,
            "deviation",
        );
        let file = temp_file("scaled.json", &out["curve"].to_string());
        let values = spline(&["eval", &file, "--at", &at]).json();
        let back: Vec<Vec<f64>> = values
            .as_array()
            .unwrap()
            .iter()
            .map(|v| point(&v[0]).iter().map(|x| x / s).collect())
            .collect();
        let hits = spline(&["closest", &unit_curve, "--points", &json!(back).to_string()]).json();
        for h in hits.as_array().unwrap() {
            assert_near(
                num(&h["distance"]),
                0.0,
                0.25,
                deviation,
                &format!("curve at {s:e}"),
            );
        }
    }
}
