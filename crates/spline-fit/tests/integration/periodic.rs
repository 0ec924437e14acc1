//! Periodic interpolation against scipy (`make_interp_spline(…, bc_type="periodic")` on
//! random held-out data, `tests/data/periodic/`), periodic least squares against a brute
//! force (dense design matrix, and a vanishing finite-difference gradient of the objective
//! with the smoothing term), and the error cases.

use nalgebra::{DMatrix, DVector, Vector2};
use proptest::prelude::*;
use serde_json::Value;
use spline_core::ErrorKind;
use spline_fit::{interpolate_periodic, least_squares_periodic};
use spline_geom::PeriodicBSpline;
use spline_testing::reference::f64s;

fn cases() -> Vec<Value> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/data/periodic/interpolate_periodic.json"
    );
    let text = std::fs::read_to_string(path).expect("the periodic reference cases");
    let data: Value = serde_json::from_str(&text).unwrap();
    data["cases"].as_array().unwrap().clone()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + b.abs())
}

#[test]
fn interpolation_agrees_with_scipy() {
    let mut checked = 0;
    for case in cases() {
        let name = case["name"].as_str().unwrap();
        let k = case["degree"].as_u64().unwrap() as usize;
        let x = f64s(&case["x"]);
        let at = f64s(&case["at"]);
        let expected = &case["expected"];
        let knots = f64s(&expected["knots"]);
        if k == 1 {
            // scipy returns the ordinary linear interpolant for k = 1 (same values on the
            // period, linear extrapolation outside it): compare inside.
            let y = if case["y"][0].is_array() {
                continue;
            } else {
                f64s(&case["y"])
            };
            let s = interpolate_periodic(&x, &y, 1).unwrap();
            let values = f64s(&expected["values"]);
            for (u, want) in at.iter().zip(&values) {
                if *u >= x[0] && *u <= x[x.len() - 1] {
                    let got: f64 = s.eval(*u).unwrap();
                    assert!(close(got, *want, 1e-12), "{name}: at {u}: {got} vs {want}");
                }
            }
            checked += 2;
            continue;
        }
        if case["y"][0].is_array() {
            let y: Vec<Vector2<f64>> = case["y"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| Vector2::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
                .collect();
            let s = interpolate_periodic(&x, &y, k).unwrap();
            for (got, want) in s.wrapped().knots().knots().iter().zip(&knots) {
                assert!(close(*got, *want, 1e-12), "{name}: knot {got} vs {want}");
            }
            let c = expected["control_points"].as_array().unwrap();
            assert_eq!(c.len(), s.wrapped().len(), "{name}");
            for (got, want) in s.wrapped().control_points().iter().zip(c) {
                for d in 0..2 {
                    assert!(
                        close(got[d], want[d].as_f64().unwrap(), 1e-9),
                        "{name}: control"
                    );
                }
            }
            for (u, want) in at.iter().zip(expected["values"].as_array().unwrap()) {
                let got = s.eval(*u).unwrap();
                for d in 0..2 {
                    assert!(
                        close(got[d], want[d].as_f64().unwrap(), 1e-9),
                        "{name}: at {u}"
                    );
                }
            }
        } else {
            let y = f64s(&case["y"]);
            let s = interpolate_periodic(&x, &y, k).unwrap();
            let c = f64s(&expected["control_points"]);
            assert_eq!(s.wrapped().knots().knots().len(), knots.len(), "{name}");
            for (got, want) in s.wrapped().knots().knots().iter().zip(&knots) {
                assert!(close(*got, *want, 1e-12), "{name}: knot {got} vs {want}");
            }
            for (got, want) in s.wrapped().control_points().iter().zip(&c) {
                assert!(close(*got, *want, 1e-9), "{name}: control {got} vs {want}");
            }
            let values = f64s(&expected["values"]);
            for (u, want) in at.iter().zip(&values) {
                let got: f64 = s.eval(*u).unwrap();
                assert!(close(got, *want, 1e-9), "{name}: at {u}: {got} vs {want}");
            }
            // It interpolates.
            for (xj, yj) in x.iter().zip(&y) {
                assert!((s.eval(*xj).unwrap() - yj).abs() < 1e-10, "{name}");
            }
        }
        checked += 1;
    }
    assert_eq!(checked, 30);
}

/// A periodic planar space of degree `p` on random knots and data parameters covering it.
fn space_and_data() -> impl Strategy<Value = (PeriodicBSpline<f64, Vector2<f64>>, Vec<f64>)> {
    (1usize..=4, 0usize..8)
        .prop_flat_map(|(p, extra)| {
            let n = p + 1 + extra;
            (
                Just(p),
                proptest::collection::vec(0.2f64..1.0, n),
                proptest::collection::vec(-1.0f64..1.0, 2 * n),
                proptest::collection::vec(0.0f64..1.0, 8 * n),
                -3.0f64..3.0,
            )
        })
        .prop_map(|(p, steps, coords, unit, start)| {
            let mut knots = Vec::new();
            let mut u = start;
            for s in &steps {
                knots.push(u);
                u += s;
            }
            let period = u - start;
            let control = coords.chunks(2).map(|c| Vector2::new(c[0], c[1])).collect();
            let space = PeriodicBSpline::new(p, knots, period, control).unwrap();
            // Parameters spread over two periods (reduced by the fit), three per span at least.
            let mut params: Vec<f64> = unit
                .iter()
                .map(|t| start - period + 2.0 * period * t)
                .collect();
            for w in space.period_knots().windows(2) {
                for t in [0.25, 0.5, 0.75] {
                    params.push(w[0] + (w[1] - w[0]) * t);
                }
            }
            let last = space.period_knots()[space.len() - 1];
            for t in [0.25, 0.5, 0.75] {
                params.push(last + (start + period - last) * t);
            }
            (space, params)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn least_squares_reproduces_a_periodic_spline((spline, params) in space_and_data()) {
        let points: Vec<Vector2<f64>> = params.iter().map(|&u| spline.eval(u).unwrap()).collect();
        let fit = least_squares_periodic(&points, &params, &spline, None, 0.0).unwrap();
        for (a, b) in fit.control_points().iter().zip(spline.control_points()) {
            prop_assert!((a - b).norm() < 1e-8, "{:?} vs {:?}", a, b);
        }
    }

    #[test]
    fn least_squares_matches_a_dense_solve((space, params) in space_and_data(), noise in proptest::collection::vec(-1.0f64..1.0, 400)) {
        let points: Vec<Vector2<f64>> = params
            .iter()
            .enumerate()
            .map(|(k, &u)| Vector2::new(u.sin() + noise[k % 400], noise[(k + 7) % 400]))
            .collect();
        let weights: Vec<f64> = (0..points.len()).map(|k| 0.5 + (k % 3) as f64 * 0.25).collect();
        let fit = least_squares_periodic(&points, &params, &space, Some(&weights), 0.0).unwrap();
        // Dense design matrix: column i is the periodic basis function i (unit control point).
        let n = space.len();
        let basis = |i: usize, u: f64| {
            let mut unit = vec![0.0; n];
            unit[i] = 1.0;
            PeriodicBSpline::new(space.degree(), space.period_knots().to_vec(), space.period(), unit)
                .unwrap()
                .eval(u)
                .unwrap()
        };
        let a = DMatrix::from_fn(points.len(), n, |k, i| weights[k] * basis(i, params[k]));
        for d in 0..2 {
            let b = DVector::from_fn(points.len(), |k, _| weights[k] * points[k][d]);
            let x = a.clone().svd(true, true).solve(&b, 1e-14).unwrap();
            for i in 0..n {
                prop_assert!((x[i] - fit.control_points()[i][d]).abs() < 1e-8 * (1.0 + x[i].abs()));
            }
        }
    }

    #[test]
    fn smoothing_optimum_has_a_zero_gradient((space, params) in space_and_data(), lambda in 0.001f64..1.0) {
        prop_assume!(space.degree() >= 2);
        let points: Vec<Vector2<f64>> = params.iter().map(|&u| Vector2::new(u.cos() * 2.0, (3.0 * u).sin())).collect();
        let fit = least_squares_periodic(&points, &params, &space, None, lambda).unwrap();
        // Objective by evaluation: data term plus λ ∫ ‖C''‖² by 12-point Gauss per knot span.
        let (a, b) = fit.domain();
        let mut breaks = fit.period_knots().to_vec();
        breaks.push(b);
        breaks.dedup();
        let gauss: Vec<(f64, f64)> = spline_core::gauss_legendre::<f64>(12);
        let objective = |c: &PeriodicBSpline<f64, Vector2<f64>>| {
            let data: f64 = params.iter().zip(&points).map(|(&u, q)| (c.eval(u).unwrap() - q).norm_squared()).sum();
            let mut penalty = 0.0;
            for w in breaks.windows(2) {
                let (m, r) = ((w[0] + w[1]) / 2.0, (w[1] - w[0]) / 2.0);
                for &(x, wq) in &gauss {
                    penalty += wq * r * c.derivatives(m + r * x, 2).unwrap()[2].norm_squared();
                }
            }
            data + lambda * penalty
        };
        let _ = a;
        let base = fit.control_points().to_vec();
        let f0 = objective(&fit);
        let h = 1e-5;
        for i in 0..base.len() {
            for d in 0..2 {
                let mut plus = base.clone();
                plus[i][d] += h;
                let mut minus = base.clone();
                minus[i][d] -= h;
                let make = |c: Vec<Vector2<f64>>| PeriodicBSpline::new(fit.degree(), fit.period_knots().to_vec(), fit.period(), c).unwrap();
                let g = (objective(&make(plus)) - objective(&make(minus))) / (2.0 * h);
                prop_assert!(g.abs() < 1e-5 * (1.0 + f0), "gradient {} at {},{}", g, i, d);
            }
        }
    }
}

#[test]
fn bad_periodic_data_are_errors() {
    let x = [0.0, 1.0, 2.0, 3.0, 4.0];
    let e = interpolate_periodic(&x, &[0.0, 1.0, 0.5, 2.0, 1.0], 3).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    let e = interpolate_periodic(&x, &[0.0, 1.0, 0.5, 0.0], 3).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    let e = interpolate_periodic(&x[..4], &[0.0, 1.0, 0.5, 0.0], 3).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::TooFewPoints);
    let e = interpolate_periodic(&[0.0, 2.0, 1.0, 3.0, 4.0], &[0.0, 1.0, 0.5, 2.0, 0.0], 3)
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
    let e = interpolate_periodic(&x, &[0.0, f64::NAN, 0.5, 2.0, 0.0], 3).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    let space = PeriodicBSpline::new(3, vec![0.0, 1.0, 2.0, 3.0, 4.0], 5.0, vec![0.0; 5]).unwrap();
    // Data in one knot span only: the other control points are not determined.
    let e = least_squares_periodic(&[1.0, 2.0], &[0.1, 0.2], &space, None, 0.0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::SingularSystem);
    let e = least_squares_periodic(&[1.0, 2.0], &[0.1], &space, None, 0.0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    let e = least_squares_periodic(&[1.0, 2.0], &[0.1, 0.2], &space, None, -1.0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    let e =
        least_squares_periodic(&[1.0, 2.0], &[0.1, f64::INFINITY], &space, None, 0.0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
}
