//! Properties over random data: interpolation reproduces the data; least squares
//! reproduces a spline sampled in its own space; weights behave like repetitions; the two
//! least-squares methods agree; closed interpolation is periodic.

#![allow(clippy::needless_range_loop, clippy::cast_lossless)]

use nalgebra::Vector2;
use proptest::prelude::*;
use spline_core::KnotVector;
use spline_fit::{
    InterpolationOptions, LeastSquares, LsqMethod, Parametrization, interpolate, interpolate_closed,
};
use spline_testing::strategies::knot_vector;

/// Points along a random walk with steps of length at least 0.05 (no coincident points).
fn walk(min: usize, max: usize) -> impl Strategy<Value = Vec<Vector2<f64>>> {
    proptest::collection::vec((0.05f64..1.0, 0.0f64..std::f64::consts::TAU), min..max).prop_map(
        |steps| {
            let mut p = Vector2::new(0.0, 0.0);
            let mut heading: f64 = 0.0;
            steps
                .into_iter()
                .map(|(len, turn)| {
                    // Turns of at most ±90° keep the walk from folding back on itself.
                    heading += (turn - std::f64::consts::PI) * 0.5;
                    p += Vector2::new(heading.cos(), heading.sin()) * len;
                    p
                })
                .collect()
        },
    )
}

fn kind(k: usize) -> Parametrization<f64> {
    match k % 3 {
        0 => Parametrization::Uniform,
        1 => Parametrization::Chordal,
        _ => Parametrization::Centripetal,
    }
}

/// `p + 1` parameters in every non-empty knot span: the Schoenberg–Whitney conditions hold.
fn sample_params(knots: &KnotVector<f64>) -> Vec<f64> {
    let p = knots.degree();
    let k = knots.knots();
    let mut out = Vec::new();
    for s in p..knots.num_basis() {
        let (a, b) = (k[s], k[s + 1]);
        if a < b {
            for r in 0..=p {
                out.push(a + (b - a) * (r as f64 + 0.5) / (p as f64 + 1.0));
            }
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn interpolation_reproduces_the_data(points in walk(2, 40), degree in 1usize..6, k in 0usize..3) {
        prop_assume!(points.len() > degree);
        let options = InterpolationOptions { parametrization: kind(k), ..InterpolationOptions::default() };
        let fit = interpolate(&points, degree, &options).unwrap();
        let scale = points.iter().fold(1.0f64, |m, p| m.max(p.amax()));
        for (u, q) in fit.params.iter().zip(&points) {
            let c = fit.curve.eval(*u).unwrap();
            prop_assert!((c - q).norm() <= 1e-9 * scale, "{} at {}", (c - q).norm(), u);
        }
        prop_assert_eq!(fit.curve.control_points().len(), points.len());
    }

    #[test]
    fn closed_interpolation_reproduces_the_data(points in walk(6, 30), degree in 1usize..6, k in 0usize..3) {
        let fit = interpolate_closed(&points, degree, &kind(k)).unwrap();
        let scale = points.iter().fold(1.0f64, |m, p| m.max(p.amax()));
        prop_assert!(fit.deviation.max <= 1e-8 * scale, "{}", fit.deviation.max);
    }

    #[test]
    fn least_squares_reproduces_a_spline_of_its_own_space(
        knots in knot_vector(5, 8, 1.0, false),
        seeds in proptest::collection::vec(-5.0f64..5.0, 28),
    ) {
        let n = knots.num_basis();
        let control: Vec<Vector2<f64>> = (0..n).map(|i| Vector2::new(seeds[2 * i], seeds[2 * i + 1])).collect();
        let curve = spline_geom::BSpline::new(knots.clone(), control.clone()).unwrap();
        let params = sample_params(&knots);
        let data = curve.eval_many(&params).unwrap();
        let size = control.iter().fold(1.0f64, |m, c| m.max(c.norm()));
        for method in [LsqMethod::NormalEquations, LsqMethod::Qr] {
            let fit = LeastSquares::new(&data, &params, knots.clone()).method(method).solve().unwrap();
            // The same curve: zero residual at the data and the same values in between.
            prop_assert!(fit.deviation.max <= 1e-10 * size, "{:?}: {}", method, fit.deviation.max);
            let (a, b) = knots.domain();
            for k in 0..=20 {
                let t = a + (b - a) * f64::from(k) / 20.0;
                let d = (fit.curve.eval(t).unwrap() - curve.eval(t).unwrap()).norm();
                prop_assert!(d <= 1e-9 * size, "{:?} at {}: {}", method, t, d);
            }
            // Control points too when the knot vector is clamped (well-conditioned basis).
            if knots.is_clamped() {
                for (p, q) in fit.curve.control_points().iter().zip(&control) {
                    prop_assert!((p - q).norm() <= 1e-7 * size, "{:?}: {} vs {}", method, p, q);
                }
            }
        }
    }

    #[test]
    fn weights_scale_invariance_and_repetition(
        points in walk(12, 40),
        weights in proptest::collection::vec(0.5f64..2.0, 40),
        scale in 0.01f64..100.0,
        doubled in 0usize..12,
    ) {
        let m = points.len();
        let params: Vec<f64> = (0..m).map(|k| k as f64 / (m - 1) as f64).collect();
        let knots = spline_fit::nurbs_book_knots(3, 6.min(m), &params).unwrap();
        let w = &weights[..m];
        let ws: Vec<f64> = w.iter().map(|x| x * scale).collect();
        let base = LeastSquares::new(&points, &params, knots.clone()).weights(w).solve().unwrap();
        let scaled = LeastSquares::new(&points, &params, knots.clone()).weights(&ws).solve().unwrap();
        for (a, b) in base.curve.control_points().iter().zip(scaled.curve.control_points()) {
            prop_assert!((a - b).norm() <= 1e-9 * (1.0 + b.norm()));
        }
        // Weight 2 on one point (unit weights elsewhere) is that point four times.
        let mut w2 = vec![1.0; m];
        w2[doubled] = 2.0;
        let weighted = LeastSquares::new(&points, &params, knots.clone()).weights(&w2).solve().unwrap();
        let mut p4 = Vec::new();
        let mut t4 = Vec::new();
        for k in 0..m {
            let times = if k == doubled { 4 } else { 1 };
            for _ in 0..times {
                p4.push(points[k]);
                t4.push(params[k]);
            }
        }
        let repeated = LeastSquares::new(&p4, &t4, knots.clone()).solve().unwrap();
        for (a, b) in weighted.curve.control_points().iter().zip(repeated.curve.control_points()) {
            prop_assert!((a - b).norm() <= 1e-9 * (1.0 + b.norm()));
        }
    }
}
