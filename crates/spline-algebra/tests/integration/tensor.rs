//! Tensor-product splines: Kronecker maps, partial derivatives, products, the Hessian
//! determinant with gradient and Hessian, and the ridge polynomials.
#![allow(
    clippy::needless_range_loop,
    clippy::cast_lossless,
    clippy::type_complexity,
    clippy::manual_range_contains
)]

use crate::common;

use common::dense;
use num_dual::{Dual64, HyperDual64};
use proptest::collection::vec;
use proptest::prelude::*;
use spline_algebra::{
    SplineMap, TensorMap, hessian_determinant, partials, ridge_polynomials,
    tensor_linear_combination, tensor_product,
};
use spline_core::{KnotVector, Scalar};
use spline_geom::Surface;
use spline_testing::compare::assert_close_rel;

fn knots(p: usize, interior: &[f64]) -> KnotVector<f64> {
    KnotVector::clamped(p, 0.0, 1.0, interior).unwrap()
}

/// A surface of degrees `(p, q)` with a double knot in `u`, from its
/// `(p + 4)(q + 4)` coefficients.
fn surface(p: usize, q: usize, coefficients: Vec<f64>) -> Surface<f64, f64> {
    let ku = knots(p, &[0.3, 0.3, 0.6]);
    let kv = knots(q, &[0.25, 0.5, 0.8]);
    Surface::new(ku, kv, coefficients).unwrap()
}

fn cast_surface<D: Scalar>(s: &Surface<f64, f64>, coefficients: Vec<D>) -> Surface<D, D> {
    let k = |k: &KnotVector<f64>| {
        KnotVector::new(
            k.degree(),
            k.knots().iter().map(|&x| spline_core::cast(x)).collect(),
        )
        .unwrap()
    };
    Surface::new(k(s.knots_u()), k(s.knots_v()), coefficients).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn kronecker_maps_and_partials(coefficients in vec(-1.0f64..=1.0, 42), points in vec((0.0f64..1.0, 0.0f64..1.0), 50)) {
        let s = surface(3, 2, coefficients);
        // The Kronecker matrix and the two-pass application agree.
        let map = TensorMap::new(
            SplineMap::insertion(s.knots_u(), 0.45, 2).unwrap(),
            SplineMap::elevation(s.knots_v(), 1).unwrap(),
        );
        let fast = map.apply(&s).unwrap();
        let m = dense(&map.matrix());
        for (r, row) in m.iter().enumerate() {
            let slow: f64 = row.iter().zip(s.control_points()).map(|(a, b)| a * b).sum();
            assert!((slow - fast.control_points()[r]).abs() < 1e-13);
        }
        for &(u, v) in &points {
            assert!((fast.eval(u, v).unwrap() - s.eval(u, v).unwrap()).abs() < 1e-13);
        }
        let all = partials(&s, 4).unwrap();
        assert_eq!(all.len(), 11); // (k, l) with k ≤ 3, l ≤ 2, k + l ≤ 4
        for ((k, l), d) in &all {
            assert_eq!(d.knots_u().degree(), 3 - k);
            assert_eq!(d.knots_v().degree(), 2 - l);
            for u in [0.0, 0.3, 0.45, 0.6, 0.99, 1.0] {
                for v in [0.0, 0.25, 0.7, 1.0] {
                    let expected = s.derivative_at(u, v, *k, *l).unwrap();
                    assert_close_rel(
                        d.eval(u, v).unwrap(),
                        expected,
                        1e-12,
                        10.0,
                        &format!("∂({k},{l}) at ({u},{v})"),
                    );
                }
            }
        }
        assert!(TensorMap::partial_derivative(s.knots_u(), s.knots_v(), 4, 0).is_err());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn bivariate_products_and_sums(ca in vec(-1.0f64..=1.0, 42), cb in vec(-1.0f64..=1.0, 20), points in vec((0.0f64..1.0, 0.0f64..1.0), 300)) {
        let a = surface(3, 2, ca);
        let kb = (knots(2, &[0.5, 0.75]), knots(1, &[0.25, 0.4]));
        let b = Surface::new(kb.0, kb.1, cb).unwrap();
        let c = tensor_product(&a, &b).unwrap();
        let s = tensor_linear_combination(2.0, &a, -3.0, &b).unwrap();
        for &(u, v) in &points {
            let (x, y) = (a.eval(u, v).unwrap(), b.eval(u, v).unwrap());
            assert_close_rel(c.eval(u, v).unwrap(), x * y, 1e-12, 1.0, "product");
            assert_close_rel(s.eval(u, v).unwrap(), 2.0 * x - 3.0 * y, 1e-12, 1.0, "sum");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    #[test]
    fn hessian_determinant_value_gradient_and_hessian(coefficients in vec(-1.0f64..=1.0, 49), points in vec((0.0f64..1.0, 0.0f64..1.0), 200)) {
        let s = surface(3, 3, coefficients);
        let det = hessian_determinant(&s).unwrap();
        for &(u, v) in &points {
            let (suu, svv, suv) = (
                s.derivative_at(u, v, 2, 0).unwrap(),
                s.derivative_at(u, v, 0, 2).unwrap(),
                s.derivative_at(u, v, 1, 1).unwrap(),
            );
            assert_close_rel(
                det.value.eval(u, v).unwrap(),
                suu * svv - suv * suv,
                1e-11,
                suu.abs() * svv.abs() + suv * suv,
                "s_uu s_vv − s_uv²",
            );
        }
        let x = s.control_points().to_vec();
        let nx = x.len();
        let grad = dense(&det.gradient);
        // Dual numbers (every variable) and five-point differences (exact for quadratics).
        for j in 0..nx {
            let seeded: Vec<Dual64> = x
                .iter()
                .enumerate()
                .map(|(i, &c)| Dual64::new(c, if i == j { 1.0 } else { 0.0 }))
                .collect();
            let dual = hessian_determinant(&cast_surface(&s, seeded)).unwrap();
            let h = 1e-3;
            let at = |t: f64| {
                let mut y = x.clone();
                y[j] += t * h;
                hessian_determinant(&Surface::new(s.knots_u().clone(), s.knots_v().clone(), y).unwrap())
                    .unwrap()
                    .value
            };
            let (m2, m1, p1, p2) = (at(-2.0), at(-1.0), at(1.0), at(2.0));
            for k in 0..grad.len() {
                let row = grad[k].iter().fold(1.0f64, |m, v| m.max(v.abs()));
                assert_close_rel(
                    grad[k][j],
                    dual.value.control_points()[k].eps,
                    1e-12,
                    row,
                    "gradient vs dual",
                );
                let fd = (m2.control_points()[k] - 8.0 * m1.control_points()[k]
                    + 8.0 * p1.control_points()[k]
                    - p2.control_points()[k])
                    / (12.0 * h);
                assert_close_rel(grad[k][j], fd, 1e-6, row, "gradient vs finite differences");
            }
        }
        // Hyper-dual numbers for a sample of variable pairs.
        for (j, l) in [
            (0, 0),
            (5, 5),
            (5, 6),
            (12, 30),
            (20, 21),
            (7, 43),
            (48, 48),
        ] {
            let seeded: Vec<HyperDual64> = x
                .iter()
                .enumerate()
                .map(|(i, &c)| {
                    HyperDual64::new(
                        c,
                        if i == j { 1.0 } else { 0.0 },
                        if i == l { 1.0 } else { 0.0 },
                        0.0,
                    )
                })
                .collect();
            let hyper = hessian_determinant(&cast_surface(&s, seeded)).unwrap();
            for k in 0..det.hessian.nrows() {
                let stored = det
                    .hessian
                    .row(k)
                    .iter()
                    .find(|e| e.0 == j && e.1 == l)
                    .map_or(0.0, |e| e.2);
                let scale = det
                    .hessian
                    .row(k)
                    .iter()
                    .fold(1.0f64, |m, e| m.max(e.2.abs()));
                assert_close_rel(
                    stored,
                    hyper.value.control_points()[k].eps1eps2,
                    1e-12,
                    scale,
                    "hessian vs hyper-dual",
                );
            }
        }
        let low = Surface::new(knots(1, &[]), knots(3, &[]), vec![0.0; 8]).unwrap();
        assert!(hessian_determinant(&low).is_err());
    }
}

// The corrected eigenvalue derivatives of the digest against finite differences of the
// numerically computed eigenvalues, and the ridge polynomials against e₁e₂d and f₁f₂d.
proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    #[test]
    fn ridge_polynomials_match_the_eigenvalue_formulas(coefficients in vec(-1.0f64..=1.0, 25), points in vec((0.0f64..1.0, 0.0f64..1.0), 100)) {
        let ku = knots(3, &[0.5]);
        let kv = knots(3, &[0.5]);
        let s = Surface::new(ku, kv, coefficients).unwrap();
        let (r1, r2) = ridge_polynomials(&s).unwrap();
        assert_eq!(r1.knots_u().degree(), 18);
        let eigen = |u: f64, v: f64| {
            let (suu, svv, suv) = (
                s.derivative_at(u, v, 2, 0).unwrap(),
                s.derivative_at(u, v, 0, 2).unwrap(),
                s.derivative_at(u, v, 1, 1).unwrap(),
            );
            let d = (suu - svv).powi(2) + 4.0 * suv * suv;
            (0.5 * (suu + svv + d.sqrt()), 0.5 * (suu + svv - d.sqrt()))
        };
        for &(u, v) in &points {
            let (u, v) = (0.02 + 0.96 * u, 0.02 + 0.96 * v);
            let dv = |k, l| s.derivative_at(u, v, k, l).unwrap();
            let (suu, svv, suv) = (dv(2, 0), dv(0, 2), dv(1, 1));
            let (suuu, suuv, suvv, svvv) = (dv(3, 0), dv(2, 1), dv(1, 2), dv(0, 3));
            let d = (suu - svv).powi(2) + 4.0 * suv * suv;
            let c1 = 0.5 * (suuu + suvv);
            let c2 = 2.0 * (suu - svv) * (suuu - suvv) + 8.0 * suv * suuv;
            let c3 = 0.5 * (suuv + svvv);
            let c4 = 2.0 * (suu - svv) * (suuv - svvv) + 8.0 * suv * suvv;
            let c5 = suu + svv;
            let sd = d.sqrt();
            let lam = [0.5 * (c5 + sd), 0.5 * (c5 - sd)];
            let lu = [c1 + c2 / (4.0 * sd), c1 - c2 / (4.0 * sd)];
            let lv = [c3 + c4 / (4.0 * sd), c3 - c4 / (4.0 * sd)];
            // Corrected λ_u, λ_v against finite differences of the eigenvalues (fourth order,
            // not across the interior knot 0.5, where third derivatives jump). √d is smooth
            // on a scale d / |∇d| (∇d = (c2, c4)): the step stays well inside it.
            let h = (1e-3 * d / (c2.abs() + c4.abs()).max(1e-300)).min(1e-4);
            if d > 1e-2 && (u - 0.5).abs() > 3.0 * h && (v - 0.5).abs() > 3.0 * h {
                let fd = |f: &dyn Fn(f64) -> (f64, f64)| {
                    let (a, b, c, e) = (f(2.0 * h), f(h), f(-h), f(-2.0 * h));
                    (
                        (-a.0 + 8.0 * b.0 - 8.0 * c.0 + e.0) / (12.0 * h),
                        (-a.1 + 8.0 * b.1 - 8.0 * c.1 + e.1) / (12.0 * h),
                    )
                };
                let du = fd(&|s| eigen(u + s, v));
                let dv = fd(&|s| eigen(u, v + s));
                assert_close_rel(lu[0], du.0, 1e-6, 1.0, "λ1_u");
                assert_close_rel(lu[1], du.1, 1e-6, 1.0, "λ2_u");
                assert_close_rel(lv[0], dv.0, 1e-6, 1.0, "λ1_v");
                assert_close_rel(lv[1], dv.1, 1e-6, 1.0, "λ2_v");
            }
            let e: Vec<f64> = (0..2)
                .map(|i| lu[i] * suv + lv[i] * (lam[i] - suu))
                .collect();
            let f: Vec<f64> = (0..2)
                .map(|i| lu[i] * (svv - lam[i]) - lv[i] * suv)
                .collect();
            let expected1 = e[0] * e[1] * d;
            let expected2 = f[0] * f[1] * d;
            let scale = 1.0
                + (e[0] * e[1]).abs().max(1.0) * d
                + (c1.abs() + c2.abs() + c3.abs() + c4.abs()).powi(2) * (1.0 + d);
            assert_close_rel(r1.eval(u, v).unwrap(), expected1, 1e-9, scale, "a²d − b²");
            assert_close_rel(r2.eval(u, v).unwrap(), expected2, 1e-9, scale, "a′²d − b′²");
        }
    }
}
