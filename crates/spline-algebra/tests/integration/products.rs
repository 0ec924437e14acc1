//! Products: values, minimal multiplicities, Jacobians (finite differences and dual
//! numbers), the bilinear second derivative (hyper-dual numbers), dot/wedge/sums/squares.
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
    ProductMap, difference, dot_product, linear_combination, product, product_knots,
    product_with_jacobians, square, sum, wedge_product,
};
use spline_core::KnotVector;
use spline_geom::BSpline;
use spline_testing::compare::assert_close_rel;
use spline_testing::strategies::{
    functions_on_a_pool, parameters, two_functions, two_planar_curves,
};

fn to_dual<T: spline_core::Scalar>(k: &KnotVector<f64>, f: impl Fn(f64) -> T) -> KnotVector<T> {
    KnotVector::new(k.degree(), k.knots().iter().map(|&x| f(x)).collect()).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn products_evaluate_to_the_product_of_values((a, b) in two_functions(7, 7), samples in vec(0.0f64..1.0, 40)) {
        let (ka, kb) = (a.knots().clone(), b.knots().clone());
        let (p, q) = (ka.degree(), kb.degree());
        let case = format!("p = {p}, q = {q}");
        let c = product(&a, &b).unwrap();
        let scale = a
            .control_points()
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()))
            * b.control_points()
                .iter()
                .fold(0.0f64, |m, x| m.max(x.abs()));
        for u in parameters(c.knots(), &samples) {
            let expected = a.eval(u).unwrap() * b.eval(u).unwrap();
            assert_close_rel(
                c.eval(u).unwrap(),
                expected,
                1e-12,
                scale,
                &format!("case {case} (p={p}, q={q}) at u={u}"),
            );
        }
        // Per-segment Bernstein form agrees too.
        let map = ProductMap::new(&ka, &kb).unwrap();
        let pieces = BSpline::new(
            map.bernstein_target().clone(),
            map.apply_bernstein(a.control_points(), b.control_points())
                .unwrap(),
        )
        .unwrap();
        for u in parameters(c.knots(), &samples[..10]) {
            let expected = a.eval(u).unwrap() * b.eval(u).unwrap();
            assert_close_rel(
                pieces.eval(u).unwrap(),
                expected,
                1e-12,
                scale,
                "Bernstein form",
            );
        }
    }
}

// The multiplicities of the product space, computed independently from the continuity rule.
proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn product_space_has_minimal_multiplicities((pool, a, b) in functions_on_a_pool(7, 7)) {
        let (ka, kb) = (a.knots().clone(), b.knots().clone());
        let (p, q) = (ka.degree(), kb.degree());
        let case = format!("p = {p}, q = {q}");
        let w = product_knots(&ka, &kb).unwrap();
        assert_eq!(w.degree(), p + q);
        assert!(w.is_clamped());
        assert_eq!(w.domain(), (0.0, 1.0));
        let mut expected_interior = 0;
        for &x in &pool {
            let (ma, mb) = (ka.multiplicity(x), kb.multiplicity(x));
            // Continuity of each factor at x (a polynomial piece is infinitely smooth).
            let ca = if ma > 0 {
                p as isize - ma as isize
            } else {
                isize::MAX
            };
            let cb = if mb > 0 {
                q as isize - mb as isize
            } else {
                isize::MAX
            };
            let expected = if ma == 0 && mb == 0 {
                0
            } else {
                ((p + q) as isize - ca.min(cb)) as usize
            };
            assert_eq!(
                w.multiplicity(x),
                expected,
                "case {case}: knot {x}, m_a={ma}, m_b={mb}, p={p}, q={q}"
            );
            if ma > 0 && mb > 0 {
                assert_eq!(
                    expected as isize,
                    (p + q) as isize - (p as isize - ma as isize).min(q as isize - mb as isize)
                );
            }
            expected_interior += expected;
        }
        assert_eq!(w.len(), expected_interior + 2 * (p + q + 1));
        // The product is exactly representable: it evaluates correctly (checked above), and a
        // generic product really needs every knot: a space with one fewer copy of any
        // interior knot cannot represent it (the removal error is large) — unless another
        // knot lies close by (the pool has knots 1e-4 apart), which makes the smaller space
        // numerically as good: such knots are not tested.
        let c = product(&a, &b).unwrap();
        let breaks = w.domain_breaks();
        let isolated = (1..breaks.len() - 1)
            .find(|&k| breaks[k] - breaks[k - 1] > 0.01 && breaks[k + 1] - breaks[k] > 0.01)
            .map(|k| breaks[k]);
        if let Some(x) = isolated {
            if p + q > 0 {
                let removed = c.remove_knot(x, 1, 1e-9);
                assert!(
                    removed.is_err(),
                    "case {case}: knot {x} of the product was removable"
                );
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(60))]

    #[test]
    fn jacobians_agree_with_finite_differences_and_dual_numbers((a, b) in two_functions(5, 5)) {
        let (ka, kb) = (a.knots().clone(), b.knots().clone());
        let (p, q) = (ka.degree(), kb.degree());
        let case = format!("p = {p}, q = {q}");
        let r = product_with_jacobians(&a, &b).unwrap();
        let ja = dense(&r.jacobian_a);
        let jb = dense(&r.jacobian_b);
        let map = ProductMap::new(&ka, &kb).unwrap();
        let bil = map.bilinear();
        // Finite differences (the product is bilinear: central differences are exact up to
        // rounding).
        let h = 1e-6;
        for j in 0..a.control_points().len() {
            let mut plus = a.control_points().to_vec();
            let mut minus = plus.clone();
            plus[j] += h;
            minus[j] -= h;
            let cp = map.apply(&plus, b.control_points()).unwrap();
            let cm = map.apply(&minus, b.control_points()).unwrap();
            for k in 0..cp.len() {
                let fd = (cp[k] - cm[k]) / (2.0 * h);
                assert_close_rel(
                    ja[k][j],
                    fd,
                    1e-6,
                    1.0,
                    &format!("case {case}: dc{k}/da{j}"),
                );
            }
        }
        // Dual numbers, seeding one coefficient of b at a time.
        let kad = to_dual(&ka, Dual64::from);
        let kbd = to_dual(&kb, Dual64::from);
        let mapd = ProductMap::new(&kad, &kbd).unwrap();
        let ad: Vec<Dual64> = a
            .control_points()
            .iter()
            .map(|&x| Dual64::from(x))
            .collect();
        for l in 0..b.control_points().len() {
            let bd: Vec<Dual64> = b
                .control_points()
                .iter()
                .enumerate()
                .map(|(i, &x)| Dual64::new(x, if i == l { 1.0 } else { 0.0 }))
                .collect();
            let c = mapd.apply(&ad, &bd).unwrap();
            for k in 0..c.len() {
                assert!((c[k].re - r.product.control_points()[k]).abs() < 1e-14);
                assert_close_rel(
                    jb[k][l],
                    c[k].eps,
                    1e-12,
                    1.0,
                    &format!("case {case}: dual dc{k}/db{l}"),
                );
            }
        }
        // Hyper-dual numbers: the mixed second derivatives are the bilinear map.
        let kah = to_dual(&ka, HyperDual64::from);
        let kbh = to_dual(&kb, HyperDual64::from);
        let maph = ProductMap::new(&kah, &kbh).unwrap();
        for j in 0..a.control_points().len() {
            for l in 0..b.control_points().len() {
                let ah: Vec<HyperDual64> = a
                    .control_points()
                    .iter()
                    .enumerate()
                    .map(|(i, &x)| HyperDual64::new(x, if i == j { 1.0 } else { 0.0 }, 0.0, 0.0))
                    .collect();
                let bh: Vec<HyperDual64> = b
                    .control_points()
                    .iter()
                    .enumerate()
                    .map(|(i, &x)| HyperDual64::new(x, 0.0, if i == l { 1.0 } else { 0.0 }, 0.0))
                    .collect();
                let c = maph.apply(&ah, &bh).unwrap();
                for k in 0..c.len() {
                    let stored = bil
                        .row(k)
                        .iter()
                        .find(|e| e.0 == j && e.1 == l)
                        .map_or(0.0, |e| e.2);
                    assert_close_rel(
                        stored,
                        c[k].eps1eps2,
                        1e-12,
                        1.0,
                        &format!("case {case}: d2c{k}/da{j}db{l}"),
                    );
                }
            }
        }
        // The bilinear map reproduces the product and both Jacobians.
        let value = bil.apply(a.control_points(), b.control_points()).unwrap();
        for (x, y) in value.iter().zip(r.product.control_points()) {
            assert!((x - y).abs() < 1e-13);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    #[test]
    fn dot_wedge_sum_square((a, b) in two_planar_curves(5, 5), samples in vec(0.0f64..1.0, 30)) {
        let (ka, kb) = (a.knots().clone(), b.knots().clone());
        let case = format!("p = {}, q = {}", a.degree(), b.degree());
        let d = dot_product(&a, &b).unwrap();
        let w = wedge_product(&a, &b).unwrap();
        let s = sum(&a, &b).unwrap();
        let diff = difference(&a, &b).unwrap();
        let fa = a.map_control_points(|v| v.x);
        let fb = b.map_control_points(|v| v.y);
        let sq_all = square(&fa).unwrap();
        let (sq, sq_jac, sq_hess) = (sq_all.value, sq_all.jacobian, sq_all.hessian);
        let lc = linear_combination(0.5, &fa, -2.0, &fb).unwrap();
        for u in parameters(&ka, &samples) {
            let (va, vb) = (a.eval(u).unwrap(), b.eval(u).unwrap());
            assert_close_rel(d.product.eval(u).unwrap(), va.dot(&vb), 1e-12, 1.0, "dot");
            assert_close_rel(
                w.product.eval(u).unwrap(),
                va.x * vb.y - va.y * vb.x,
                1e-12,
                1.0,
                "wedge",
            );
            assert!((s.eval(u).unwrap() - (va + vb)).amax() < 1e-12, "sum");
            assert!(
                (diff.eval(u).unwrap() - (va - vb)).amax() < 1e-12,
                "difference"
            );
            assert_close_rel(sq.eval(u).unwrap(), va.x * va.x, 1e-12, 1.0, "square");
            assert_close_rel(
                lc.eval(u).unwrap(),
                0.5 * va.x - 2.0 * vb.y,
                1e-12,
                1.0,
                "linear combination",
            );
        }
        // Dot Jacobian by finite differences on the interleaved coordinates of a.
        let ja = dense(&d.jacobian_a);
        let h = 1e-6;
        for j in 0..2 * a.control_points().len() {
            let bump = |s: f64| {
                let mut pts = a.control_points().to_vec();
                pts[j / 2][j % 2] += s;
                dot_product(&BSpline::new(ka.clone(), pts).unwrap(), &b)
                    .unwrap()
                    .product
            };
            let (cp, cm) = (bump(h), bump(-h));
            for k in 0..ja.len() {
                let fd = (cp.control_points()[k] - cm.control_points()[k]) / (2.0 * h);
                assert_close_rel(
                    ja[k][j],
                    fd,
                    1e-6,
                    1.0,
                    &format!("case {case}: dot jacobian ({k}, {j})"),
                );
            }
        }
        let jw = dense(&w.jacobian_b);
        for j in 0..2 * b.control_points().len() {
            let bump = |s: f64| {
                let mut pts = b.control_points().to_vec();
                pts[j / 2][j % 2] += s;
                wedge_product(&a, &BSpline::new(kb.clone(), pts).unwrap())
                    .unwrap()
                    .product
            };
            let (cp, cm) = (bump(h), bump(-h));
            for k in 0..jw.len() {
                let fd = (cp.control_points()[k] - cm.control_points()[k]) / (2.0 * h);
                assert_close_rel(
                    jw[k][j],
                    fd,
                    1e-6,
                    1.0,
                    &format!("case {case}: wedge jacobian ({k}, {j})"),
                );
            }
        }
        // Square: Jacobian 2·B(·, a) and Hessian B + Bᵀ, checked by finite differences.
        let sj = dense(&sq_jac);
        for j in 0..fa.control_points().len() {
            let bump = |s: f64| {
                let mut pts = fa.control_points().to_vec();
                pts[j] += s;
                square(&BSpline::new(ka.clone(), pts).unwrap()).unwrap()
            };
            let (cp, cm) = (bump(h), bump(-h));
            let hp = dense(&cp.jacobian);
            let hm = dense(&cm.jacobian);
            for k in 0..sj.len() {
                let fd = (cp.value.control_points()[k] - cm.value.control_points()[k]) / (2.0 * h);
                assert_close_rel(sj[k][j], fd, 1e-6, 1.0, "square jacobian");
                let hess = dense(&sq_hess.matrix(k));
                for l in 0..fa.control_points().len() {
                    let fd2 = (hp[k][l] - hm[k][l]) / (2.0 * h);
                    assert_close_rel(hess[l][j], fd2, 1e-6, 1.0, "square hessian");
                }
            }
        }
    }
}

#[test]
fn product_errors() {
    let a = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 1.0]).unwrap();
    let b = BSpline::from_knots(1, vec![0.0, 0.0, 2.0, 2.0], vec![0.0, 1.0]).unwrap();
    assert!(product(&a, &b).is_err());
    assert!(sum(&a, &b).is_err());
    let high =
        BSpline::from_knots(20, [vec![0.0; 21], vec![1.0; 21]].concat(), vec![0.0; 21]).unwrap();
    assert_eq!(
        product(&high, &high).unwrap_err().kind(),
        spline_core::ErrorKind::DegreeTooHigh
    );
    let map = ProductMap::new(a.knots(), a.knots()).unwrap();
    assert!(map.apply(&[1.0], &[1.0, 2.0]).is_err());
    assert!(map.product(&a, &b).is_err());
}
