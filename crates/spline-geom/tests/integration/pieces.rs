//! The cached piecewise polynomial form behind `BSpline::eval` / `eval_many_into` (and the
//! NURBS paths built on them), checked against evaluations that never use it: the dense
//! basis functions of spline-core combined here with the control points, and de Boor's
//! algorithm. Also: exactness at knots, invalidation by every mutation, and that the cache
//! is not part of the curve's value (equality, `Debug`, JSON).

use nalgebra::Vector2;
use proptest::prelude::*;
use spline_core::KnotVector;
use spline_core::strategies::knot_vector;
use spline_geom::{BSpline, NurbsCurve2};

type Curve = BSpline<f64, Vector2<f64>>;

/// `Σ N_i(u) P_i` from the dense basis (no span search, no cache).
fn dense_point(knots: &KnotVector<f64>, points: &[Vector2<f64>], u: f64) -> Vector2<f64> {
    let basis = knots.dense_basis(u).unwrap();
    points.iter().zip(&basis).map(|(p, &n)| p * n).sum()
}

/// `Σ N_i w_i P_i / Σ N_i w_i` from the dense basis.
fn dense_rational(curve: &NurbsCurve2, u: f64) -> Vector2<f64> {
    let basis = curve.knots().dense_basis(u).unwrap();
    let (mut num, mut den) = (Vector2::zeros(), 0.0);
    for ((p, &w), &n) in curve
        .control_points()
        .iter()
        .zip(curve.weights())
        .zip(&basis)
    {
        num += p * (n * w);
        den += n * w;
    }
    num / den
}

fn points_for(knots: &KnotVector<f64>, seed: f64) -> Vec<Vector2<f64>> {
    (0..knots.num_basis())
        .map(|i| {
            let x = i as f64 + seed;
            Vector2::new((1.7 * x).sin(), (0.9 * x + seed).cos())
        })
        .collect()
}

/// Parameters: `ts` mapped to the domain, every knot in it and both ends.
fn params(knots: &KnotVector<f64>, ts: &[f64]) -> Vec<f64> {
    let (a, b) = knots.domain();
    let mut us: Vec<f64> = ts.iter().map(|t| a + (b - a) * t).collect();
    us.extend(knots.knots().iter().copied().filter(|&k| k >= a && k <= b));
    us.extend([a, b]);
    us
}

/// Evaluates `curve` at enough parameters to build its cache (one batch call).
fn warm(curve: &Curve) {
    let (a, b) = curve.domain();
    let us: Vec<f64> = (0..=curve.len())
        .map(|i| a + (b - a) * i as f64 / curve.len() as f64)
        .collect();
    curve.eval_many(&us).unwrap();
}

fn check_against_dense(curve: &Curve, us: &[f64]) -> Result<(), TestCaseError> {
    let scale = curve
        .control_points()
        .iter()
        .fold(1.0f64, |m, p| m.max(p.amax()));
    let batch = curve.eval_many(us).unwrap();
    for (&u, q) in us.iter().zip(&batch) {
        let exact = dense_point(curve.knots(), curve.control_points(), u);
        let one = curve.eval(u).unwrap();
        prop_assert!(
            (one - exact).amax() <= 1e-13 * scale,
            "eval at {}: {:?} vs {:?}",
            u,
            one,
            exact
        );
        prop_assert!((q - exact).amax() <= 1e-13 * scale, "batch at {}", u);
        prop_assert!((one - curve.de_boor(u).unwrap()).amax() <= 1e-13 * scale);
    }
    Ok(())
}

proptest! {
    #[test]
    fn cached_form_agrees_with_the_dense_basis(
        knots in knot_vector(5, 25, 1.0, true),
        seed in 0.0f64..10.0,
        ts in proptest::collection::vec(0.0f64..=1.0, 1..60),
    ) {
        let curve = Curve::new(knots.clone(), points_for(&knots, seed)).unwrap();
        let us = params(&knots, &ts);
        // Uncached values first (a fresh curve), then the cached ones.
        let fresh: Vec<_> = us.iter().map(|&u| Curve::new(knots.clone(), curve.control_points().to_vec()).unwrap().eval(u).unwrap()).collect();
        warm(&curve);
        check_against_dense(&curve, &us)?;
        // At knots the cached form returns exactly the triangular scheme's value.
        for (&u, f) in us.iter().zip(&fresh) {
            if knots.knots().contains(&u) {
                prop_assert_eq!(curve.eval(u).unwrap(), *f, "at knot {}", u);
            }
        }
    }

    #[test]
    fn mutation_drops_the_cache(
        knots in knot_vector(5, 15, 1.0, false),
        seed in 0.0f64..10.0,
        new_knots in proptest::collection::vec(0.001f64..0.999, 1..6),
        ts in proptest::collection::vec(0.0f64..=1.0, 1..30),
    ) {
        prop_assume!(knots.degree() >= 1);
        let mut curve = Curve::new(knots.clone(), points_for(&knots, seed)).unwrap();
        let (a, b) = knots.domain();
        let inside: Vec<f64> = new_knots.iter().map(|t| a + (b - a) * t).collect();
        warm(&curve);
        // Insertion keeps the curve but moves every span index and coefficient.
        if curve.insert_knot_mut(inside[0], 1).is_ok() {
            check_against_dense(&curve, &params(curve.knots(), &ts))?;
            warm(&curve);
        }
        if curve.refine_mut(&inside).is_ok() {
            check_against_dense(&curve, &params(curve.knots(), &ts))?;
            warm(&curve);
        }
        // Moving control points changes the curve.
        for p in curve.control_points_mut() {
            *p = Vector2::new(p.y, -2.0 * p.x);
        }
        check_against_dense(&curve, &params(curve.knots(), &ts))?;
    }
}

#[test]
fn one_call_per_point_builds_the_cache_and_agrees() {
    // 97 spans: the first 97 calls use the triangular scheme, then the cache.
    let knots = KnotVector::clamped_uniform(3, 100, 0.0, 1.0).unwrap();
    let curve = Curve::new(knots.clone(), points_for(&knots, 0.3)).unwrap();
    for i in 0..1000 {
        let u = (f64::from(i) * 0.618_033_988_749_895).fract();
        let exact = dense_point(&knots, curve.control_points(), u);
        assert!((curve.eval(u).unwrap() - exact).amax() < 1e-14, "u = {u}");
    }
    assert_eq!(curve.eval(1.0).unwrap(), curve.control_points()[99]);
    assert_eq!(curve.eval(0.0).unwrap(), curve.control_points()[0]);
    assert!(curve.eval(1.0 + 1e-12).is_err());
    assert!(curve.eval(f64::NAN).is_err());
}

#[test]
fn the_cache_is_not_part_of_the_value() {
    let knots = KnotVector::clamped_uniform(3, 20, 0.0, 2.0).unwrap();
    let cold = Curve::new(knots.clone(), points_for(&knots, 1.0)).unwrap();
    let warmed = cold.clone();
    warm(&warmed);
    assert_eq!(cold, warmed);
    assert_eq!(format!("{cold:?}"), format!("{warmed:?}"));
    assert!(!format!("{warmed:?}").contains("pieces"));
    // A clone of a warm curve, then changed, does not see the other's cache.
    let mut changed = warmed.clone();
    changed.control_points_mut()[10] = Vector2::new(5.0, 5.0);
    let u = 1.0;
    let exact = dense_point(&knots, changed.control_points(), u);
    assert!((changed.eval(u).unwrap() - exact).amax() < 1e-14);
    assert!((warmed.eval(u).unwrap() - cold.eval(u).unwrap()).amax() < 1e-14);
    // The changed clone rebuilds its own form (the shared one is not reused as storage):
    // both evaluators agree with their own control points everywhere.
    let (fresh, kept) = (changed.evaluator(), warmed.evaluator());
    for i in 0..=200 {
        let u = 2.0 * f64::from(i) / 200.0;
        let exact = dense_point(&knots, changed.control_points(), u);
        assert!(
            (fresh.eval(u).unwrap() - exact).amax() < 1e-13,
            "changed at {u}"
        );
        let exact = dense_point(&knots, warmed.control_points(), u);
        assert!(
            (kept.eval(u).unwrap() - exact).amax() < 1e-13,
            "warmed at {u}"
        );
    }
}

#[test]
fn a_changed_curve_rebuilds_its_form_in_the_old_storage() {
    // Changed and evaluated in a loop (as parameter correction does): each round's form is
    // the new curve's, whether the knot vector grows, shrinks back or stays.
    let knots = KnotVector::clamped_uniform(3, 30, 0.0, 1.0).unwrap();
    let mut curve = Curve::new(knots.clone(), points_for(&knots, 0.7)).unwrap();
    for round in 0..6 {
        let evaluator = curve.evaluator();
        for i in 0..=300 {
            let u = f64::from(i) / 300.0;
            let exact = dense_point(curve.knots(), curve.control_points(), u);
            assert!(
                (evaluator.eval(u).unwrap() - exact).amax() < 1e-13,
                "round {round} at {u}"
            );
        }
        if round == 2 {
            curve.refine_mut(&[0.11, 0.52, 0.93]).unwrap();
        } else if round == 4 {
            curve = Curve::new(knots.clone(), curve.control_points()[..30].to_vec()).unwrap();
        } else {
            for p in curve.control_points_mut() {
                *p = Vector2::new(p.y + 0.1, -p.x);
            }
        }
    }
}

proptest! {
    #[test]
    fn nurbs_cached_form_agrees_with_the_dense_rational_formula(
        knots in knot_vector(4, 12, 1.0, true),
        seed in 0.0f64..10.0,
        ts in proptest::collection::vec(0.0f64..=1.0, 1..40),
        insert in 0.01f64..0.99,
    ) {
        prop_assume!(knots.degree() >= 1);
        let points = points_for(&knots, seed);
        let weights: Vec<f64> = (0..points.len()).map(|i| 0.5 + ((i as f64 + seed) * 0.77).sin().abs()).collect();
        let mut curve = NurbsCurve2::new(knots.clone(), points, weights).unwrap();
        for round in 0..2 {
            let us = params(curve.knots(), &ts);
            let mut batch = vec![Vector2::zeros(); us.len().max(curve.len())];
            let mut all = us.clone();
            all.resize(batch.len(), us[0]);
            curve.eval_many_into(&all, &mut batch).unwrap();
            for (&u, q) in us.iter().zip(&batch) {
                let exact = dense_rational(&curve, u);
                let one = curve.eval(u).unwrap();
                prop_assert!((one - exact).amax() <= 1e-12 * exact.amax().max(1.0), "round {} u {}", round, u);
                prop_assert!((q - exact).amax() <= 1e-12 * exact.amax().max(1.0));
            }
            let (a, b) = curve.domain();
            if round == 0 && curve.insert_knot_mut(a + (b - a) * insert, 1).is_err() {
                break;
            }
        }
    }
}

/// The largest coordinate of the control points of the `k`-th derivative curve (which bounds
/// the `k`-th derivative, by the convex hull property).
fn derivative_scale(curve: &Curve, k: usize) -> f64 {
    curve.derivative(k).map_or(1.0, |d| {
        d.control_points()
            .iter()
            .fold(1.0f64, |m, p| m.max(p.amax()))
    })
}

proptest! {
    #[test]
    fn evaluator_agrees_with_the_dense_basis_and_the_derivatives(
        knots in knot_vector(7, 25, 1.0, true),
        seed in 0.0f64..10.0,
        ts in proptest::collection::vec(0.0f64..=1.0, 1..60),
    ) {
        let curve = Curve::new(knots.clone(), points_for(&knots, seed)).unwrap();
        let p = knots.degree();
        let scales: Vec<f64> = (0..=p).map(|k| derivative_scale(&curve, k)).collect();
        let evaluator = curve.evaluator();
        let mut fast = vec![Vector2::zeros(); p + 2];
        let mut exact = vec![Vector2::zeros(); p + 2];
        for u in params(&knots, &ts) {
            let dense = dense_point(&knots, curve.control_points(), u);
            let one = evaluator.eval(u).unwrap();
            prop_assert!((one - dense).amax() <= 1e-13 * scales[0], "eval at {}: {:?} vs {:?}", u, one, dense);
            evaluator.derivatives_into(u, &mut fast).unwrap();
            curve.derivatives_into(u, &mut exact).unwrap();
            for k in 0..=p {
                prop_assert!(
                    (fast[k] - exact[k]).amax() <= 1e-11 * scales[k],
                    "order {} at {}: {:?} vs {:?}", k, u, fast[k], exact[k]
                );
            }
            prop_assert_eq!(fast[p + 1], Vector2::zeros());
        }
        // The domain's end goes through the triangular scheme: bit for bit.
        let (_, b) = curve.domain();
        prop_assert_eq!(evaluator.eval(b).unwrap(), curve.eval(b).unwrap());
    }
}

#[test]
fn evaluator_rejects_what_eval_rejects() {
    let knots = KnotVector::clamped_uniform(3, 8, 0.0, 1.0).unwrap();
    let curve = Curve::new(knots.clone(), points_for(&knots, 0.3)).unwrap();
    let evaluator = curve.evaluator();
    let mut d = [Vector2::zeros(); 3];
    for u in [f64::NAN, f64::INFINITY, -0.5, 1.0 + 1e-9] {
        let expected = curve.eval(u).unwrap_err().kind();
        assert_eq!(
            evaluator.eval(u).unwrap_err().kind(),
            expected,
            "eval at {u}"
        );
        assert_eq!(
            evaluator.derivatives_into(u, &mut d).unwrap_err().kind(),
            expected,
            "derivatives at {u}"
        );
    }
    assert_eq!(evaluator.curve(), &curve);
}

#[test]
fn ill_conditioned_forms_fall_back_to_the_triangular_scheme() {
    // Degree 5 with alternating control points: Σ |c_k| h^k reaches far beyond 32 times the
    // largest control point, so the cached form is refused and the evaluator returns the
    // triangular scheme's values, bit for bit.
    let knots = KnotVector::clamped_uniform(5, 12, 0.0, 1.0).unwrap();
    let points = (0..12)
        .map(|i| Vector2::new(if i % 2 == 0 { 1.0 } else { -1.0 }, 0.0))
        .collect();
    let curve = Curve::new(knots, points).unwrap();
    let evaluator = curve.evaluator();
    let mut fast = [Vector2::zeros(); 4];
    let mut exact = [Vector2::zeros(); 4];
    for i in 0..=997 {
        let u = f64::from(i) / 997.0;
        assert_eq!(evaluator.eval(u).unwrap(), curve.eval(u).unwrap(), "at {u}");
        evaluator.derivatives_into(u, &mut fast).unwrap();
        curve.derivatives_into(u, &mut exact).unwrap();
        assert_eq!(fast, exact, "derivatives at {u}");
    }
}

proptest! {
    #[test]
    fn nurbs_evaluator_agrees_with_the_rational_formula(
        knots in knot_vector(4, 12, 1.0, true),
        seed in 0.0f64..10.0,
        ts in proptest::collection::vec(0.0f64..=1.0, 1..40),
    ) {
        prop_assume!(knots.degree() >= 1);
        let points = points_for(&knots, seed);
        let weights: Vec<f64> = (0..points.len()).map(|i| 0.5 + ((i as f64 + seed) * 0.77).sin().abs()).collect();
        let curve = NurbsCurve2::new(knots.clone(), points, weights).unwrap();
        let evaluator = curve.evaluator();
        let (mut fast, mut exact) = ([Vector2::zeros(); 3], [Vector2::zeros(); 3]);
        for u in params(&knots, &ts) {
            let dense = dense_rational(&curve, u);
            prop_assert!((evaluator.eval(u).unwrap() - dense).amax() <= 1e-12 * dense.amax().max(1.0), "u {}", u);
            evaluator.derivatives_into(u, &mut fast).unwrap();
            curve.derivatives_into(u, &mut exact).unwrap();
            for k in 0..3 {
                let scale = exact[k].amax().max(exact[0].amax()).max(1.0);
                prop_assert!((fast[k] - exact[k]).amax() <= 1e-9 * scale, "order {} at {}: {:?} vs {:?}", k, u, fast[k], exact[k]);
            }
        }
    }
}
