//! The studio's latency: the server-side handling of one update while a point is dragged
//! and 1,000 data points are approximated (least squares, cubic, 20 control points, chord
//! length, with the curve sampled and the 1,000 projections drawn): parsing the request
//! JSON, the fit, the answer's JSON. The budget is one frame, 16 ms. And the eraser lab's
//! update while a data point of an airfoil (clarkv, 20 control points, one curvature
//! maximum) is dragged, afresh and from the previous answer (the page sends its `warm`
//! record back while dragging): issue 27 asks for 50 ms.
//! `cargo bench -p spline-studio --bench drag`.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use serde_json::json;
use std::hint::black_box;

/// 1,000 points along a wavy curve, as the page sends them.
fn request(dragged: f64) -> Vec<u8> {
    let points: Vec<[f64; 2]> = (0..1000)
        .map(|k| {
            let t = f64::from(k) / 999.0;
            [
                t * 1.6,
                0.5 + 0.3 * (7.0 * t).sin() * (1.0 - t) + 0.02 * (53.0 * t).cos(),
            ]
        })
        .collect();
    let mut points = points;
    points[500][1] += dragged;
    json!({
        "points": points,
        "degree": 3,
        "control_points": 20,
        "parametrization": "chordal",
        "correct": 0,
    })
    .to_string()
    .into_bytes()
}

fn drag(c: &mut Criterion) {
    let bodies: Vec<Vec<u8>> = (0..8).map(|k| request(0.01 * f64::from(k))).collect();
    let mut k = 0;
    c.bench_function(
        "studio/drag: approximate 1000 points, 20 control points",
        |b| {
            b.iter(|| {
                k = (k + 1) % bodies.len();
                let answer = spline_studio::api::handle("approximate", black_box(&bodies[k]))
                    .expect("a fit");
                black_box(answer.to_string())
            });
        },
    );
}

/// The eraser lab's data for clarkv (from `data/airfoils/`), one data point on the upper
/// surface moved by a few tenths of a millimetre per update.
fn erase_data() -> Vec<Vec<[f64; 2]>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/airfoils/clarkv.dat"
    );
    let text = std::fs::read_to_string(path).expect("the shipped airfoil");
    let points: Vec<[f64; 2]> = text
        .lines()
        .filter_map(|line| {
            let mut words = line.split_whitespace().map(str::parse::<f64>);
            match (words.next(), words.next(), words.next()) {
                (Some(Ok(x)), Some(Ok(y)), None) => Some([x, y]),
                _ => None,
            }
        })
        .collect();
    let dragged = points.len() / 4;
    (0..8)
        .map(|k| {
            let mut points = points.clone();
            points[dragged][1] += 2e-4 * f64::from(k);
            points
        })
        .collect()
}

fn erase(c: &mut Criterion) {
    let data = erase_data();
    let body = |points: &[[f64; 2]], warm: Option<&serde_json::Value>| {
        let mut request = json!({ "points": points, "control_points": 20, "extrema": 1 });
        if let Some(warm) = warm {
            request["warm"] = warm.clone();
        }
        request.to_string().into_bytes()
    };
    let mut group = c.benchmark_group("studio");
    group.sample_size(10);
    let mut k = 0;
    group.bench_function(
        "drag: erase clarkv afresh, 20 control points, one maximum",
        |b| {
            b.iter(|| {
                k = (k + 1) % data.len();
                let answer = spline_studio::api::handle("erase", black_box(&body(&data[k], None)))
                    .expect("smoothed");
                black_box(answer.to_string())
            });
        },
    );
    // Each update starts from the previous answer, as the page sends it while dragging.
    let first = spline_studio::api::handle("erase", &body(&data[0], None)).expect("smoothed");
    let mut warm = first["warm"].clone();
    group.bench_function("drag: erase clarkv from the previous answer", |b| {
        b.iter(|| {
            k = (k + 1) % data.len();
            let answer =
                spline_studio::api::handle("erase", black_box(&body(&data[k], Some(&warm))))
                    .expect("smoothed");
            let text = answer.to_string();
            warm = answer["warm"].clone();
            black_box(text)
        });
    });
    group.finish();
}

criterion_group!(benches, drag, erase);
criterion_main!(benches);
