//! The studio's latency: the server-side handling of one update while a point is dragged
//! and 1,000 data points are approximated (least squares, cubic, 20 control points, chord
//! length, with the curve sampled and the 1,000 projections drawn): parsing the request
//! JSON, the fit, the answer's JSON. The budget is one frame, 16 ms.
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

criterion_group!(benches, drag);
criterion_main!(benches);
