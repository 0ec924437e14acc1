//! `Surface::evaluator` and `NurbsSurface::evaluator` (the per-patch Taylor form): points
//! against the dense tensor sum `Σ N_i(u) N_j(v) P_ij` of spline-core's basis (neither the
//! surface's span search nor its kernels), derivatives against `Surface::derivatives_into`
//! (itself checked against dual numbers in `surfaces.rs`) and central differences, the
//! fallbacks (degrees without a form, the domain's far edges) bit for bit, and the errors.

use nalgebra::{Vector3, Vector4};
use proptest::prelude::*;
use spline_core::{ErrorKind, KnotVector};
use spline_geom::{NurbsSurface, Surface};
use spline_testing::strategies::knot_vector;

type S3 = Surface<f64, Vector3<f64>>;

fn surface_on(ku: KnotVector<f64>, kv: KnotVector<f64>, seed: f64) -> S3 {
    let n = ku.num_basis() * kv.num_basis();
    let points = (0..n)
        .map(|k| {
            let x = k as f64 + seed;
            Vector3::new(
                (1.3 * x).sin(),
                (0.7 * x + seed).cos(),
                (2.1 * x).sin() * 0.5,
            )
        })
        .collect();
    Surface::new(ku, kv, points).unwrap()
}

/// `Σ_i Σ_j N_i(u) N_j(v) P_ij` from the dense basis of each direction.
fn dense_point(s: &S3, u: f64, v: f64) -> Vector3<f64> {
    let bu = s.knots_u().dense_basis(u).unwrap();
    let bv = s.knots_v().dense_basis(v).unwrap();
    let nv = bv.len();
    let mut acc = Vector3::zeros();
    for (i, &a) in bu.iter().enumerate() {
        for (j, &b) in bv.iter().enumerate() {
            acc += s.control_points()[i * nv + j] * (a * b);
        }
    }
    acc
}

/// The domain's parameters at fractions `ts`, every knot inside and both ends.
fn params(knots: &KnotVector<f64>, ts: &[f64]) -> Vec<f64> {
    let (a, b) = knots.domain();
    let mut us: Vec<f64> = ts.iter().map(|t| a + (b - a) * t).collect();
    us.extend(knots.knots().iter().copied().filter(|&k| k >= a && k <= b));
    us
}

fn scale(s: &S3) -> f64 {
    s.control_points()
        .iter()
        .fold(1.0f64, |m, p| m.max(p.amax()))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn points_match_the_dense_tensor_sum(
        ku in knot_vector(5, 5, 1.0, true),
        kv in knot_vector(5, 5, 1.0, true),
        ts in proptest::collection::vec(0.0f64..1.0, 6),
        seed in 0.0f64..10.0,
    ) {
        let s = surface_on(ku, kv, seed);
        let evaluator = s.evaluator();
        let tolerance = 1e-11 * scale(&s);
        for &u in &params(s.knots_u(), &ts[..3]) {
            for &v in &params(s.knots_v(), &ts[3..]) {
                let fast = evaluator.eval(u, v).unwrap();
                let exact = dense_point(&s, u, v);
                prop_assert!(
                    (fast - exact).amax() <= tolerance,
                    "({}, {}): {:?} vs {:?}", u, v, fast, exact
                );
            }
        }
    }

    #[test]
    fn derivatives_match_the_basis_derivatives(
        ku in knot_vector(5, 4, 1.0, true),
        kv in knot_vector(5, 4, 1.0, true),
        ts in proptest::collection::vec(0.0f64..1.0, 4),
        order in 0usize..=2,
        seed in 0.0f64..10.0,
    ) {
        let s = surface_on(ku, kv, seed);
        let evaluator = s.evaluator();
        let len = (order + 1) * (order + 1);
        for &u in &params(s.knots_u(), &ts[..2]) {
            for &v in &params(s.knots_v(), &ts[2..]) {
                let mut fast = vec![Vector3::zeros(); len];
                let mut exact = vec![Vector3::zeros(); len];
                evaluator.derivatives_into(u, v, order, &mut fast).unwrap();
                s.derivatives_into(u, v, order, &mut exact).unwrap();
                let size = exact.iter().fold(scale(&s), |m, d| m.max(d.amax()));
                for (k, (a, b)) in fast.iter().zip(&exact).enumerate() {
                    prop_assert!(
                        (a - b).amax() <= 1e-10 * size,
                        "({}, {}) entry {}: {:?} vs {:?}", u, v, k, a, b
                    );
                }
            }
        }
    }
}

/// A bicubic on non-uniform knots with an interior double knot.
fn bicubic() -> S3 {
    let ku = KnotVector::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.2, 0.45, 0.45, 0.7, 1.0, 1.0, 1.0, 1.0],
    )
    .unwrap();
    let kv = KnotVector::clamped_uniform(3, 7, -1.0, 2.0).unwrap();
    surface_on(ku, kv, 0.3)
}

#[test]
fn first_derivatives_match_central_differences() {
    let s = bicubic();
    let evaluator = s.evaluator();
    assert!(evaluator.has_form());
    let h = 1e-6;
    for (u, v) in [(0.1, -0.5), (0.33, 0.4), (0.6, 1.7), (0.9, 0.05)] {
        let mut d = [Vector3::zeros(); 4];
        evaluator.derivatives_into(u, v, 1, &mut d).unwrap();
        let su = (s.eval(u + h, v).unwrap() - s.eval(u - h, v).unwrap()) / (2.0 * h);
        let sv = (s.eval(u, v + h).unwrap() - s.eval(u, v - h).unwrap()) / (2.0 * h);
        assert!((d[2] - su).amax() < 1e-6, "S_u at ({u}, {v})");
        assert!((d[1] - sv).amax() < 1e-6, "S_v at ({u}, {v})");
        assert!((d[0] - s.eval(u, v).unwrap()).amax() < 1e-14);
    }
}

#[test]
fn unequal_degrees_match_the_dense_sum() {
    // A bicubic × biquadratic with interior knots: the general (not unrolled) Horner path.
    let ku = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0]).unwrap();
    let kv = KnotVector::new(2, vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]).unwrap();
    let s = surface_on(ku, kv, 1.1);
    let evaluator = s.evaluator();
    assert!(evaluator.has_form(), "unequal degrees have a form too");
    for k in 0..=20 {
        for l in 0..=20 {
            let (u, v) = (f64::from(k) / 20.0, f64::from(l) / 20.0);
            let fast = evaluator.eval(u, v).unwrap();
            assert!((fast - dense_point(&s, u, v)).amax() < 1e-14, "({u}, {v})");
        }
    }
}

#[test]
fn far_edges_and_high_degrees_use_the_surface_bit_for_bit() {
    let s = bicubic();
    let evaluator = s.evaluator();
    for v in [-1.0, -0.3, 0.5, 2.0] {
        assert_eq!(evaluator.eval(1.0, v).unwrap(), s.eval(1.0, v).unwrap());
    }
    for u in [0.0, 0.45, 1.0] {
        assert_eq!(evaluator.eval(u, 2.0).unwrap(), s.eval(u, 2.0).unwrap());
    }
    let mut d = [Vector3::zeros(); 9];
    let mut e = [Vector3::zeros(); 9];
    evaluator.derivatives_into(1.0, 2.0, 2, &mut d).unwrap();
    s.derivatives_into(1.0, 2.0, 2, &mut e).unwrap();
    assert_eq!(d, e);
    // Degree 6 in u: no form, every value the surface's own.
    let high = surface_on(
        KnotVector::clamped_uniform(6, 9, 0.0, 1.0).unwrap(),
        KnotVector::clamped_uniform(2, 4, 0.0, 1.0).unwrap(),
        0.0,
    );
    let evaluator = high.evaluator();
    assert!(!evaluator.has_form());
    for (u, v) in [(0.1, 0.2), (0.5, 0.5), (0.77, 0.9)] {
        assert_eq!(evaluator.eval(u, v).unwrap(), high.eval(u, v).unwrap());
    }
}

#[test]
fn bad_parameters_and_lengths_are_errors() {
    let s = bicubic();
    let evaluator = s.evaluator();
    for (u, v) in [
        (1.5, 0.0),
        (0.5, -1.5),
        (f64::NAN, 0.0),
        (0.5, f64::INFINITY),
    ] {
        let ours = evaluator.eval(u, v).unwrap_err();
        let theirs = s.eval(u, v).unwrap_err();
        assert_eq!(ours.kind(), theirs.kind(), "({u}, {v})");
        let mut d = [Vector3::zeros(); 4];
        assert_eq!(
            evaluator
                .derivatives_into(u, v, 1, &mut d)
                .unwrap_err()
                .kind(),
            theirs.kind()
        );
    }
    let mut short = [Vector3::zeros(); 3];
    assert_eq!(
        evaluator
            .derivatives_into(0.5, 0.5, 1, &mut short)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidLength
    );
}

#[test]
fn nurbs_evaluator_stays_on_the_sphere_and_matches_the_derivatives() {
    let centre = Vector3::new(1.0, -2.0, 0.5);
    let sphere = NurbsSurface::sphere(centre, 2.0).unwrap();
    let evaluator = sphere.evaluator();
    assert!(evaluator.has_form());
    let ((ua, ub), (va, vb)) = sphere.domain();
    for k in 0..=16 {
        for l in 0..=16 {
            let u = ua + (ub - ua) * f64::from(k) / 16.0;
            let v = va + (vb - va) * f64::from(l) / 16.0;
            let p = evaluator.eval(u, v).unwrap();
            assert!(((p - centre).norm() - 2.0).abs() < 1e-14, "({u}, {v})");
            assert!((p - sphere.eval(u, v).unwrap()).amax() < 1e-14);
            let mut fast = [Vector3::zeros(); 9];
            let mut exact = [Vector3::zeros(); 9];
            evaluator.derivatives_into(u, v, 2, &mut fast).unwrap();
            sphere.derivatives_into(u, v, 2, &mut exact).unwrap();
            let size = exact.iter().fold(1.0f64, |m, d| m.max(d.amax()));
            for (a, b) in fast.iter().zip(&exact) {
                assert!((a - b).amax() < 1e-12 * size, "({u}, {v}): {a:?} vs {b:?}");
            }
        }
    }
    assert!(evaluator.eval(ub + 1.0, va).is_err());
}

#[test]
fn four_coordinates_work_as_three() {
    // Homogeneous-sized points go through the same form.
    let s = bicubic();
    let lifted = s.map_control_points(|p| Vector4::new(p.x, p.y, p.z, p.x - p.y));
    let evaluator = lifted.evaluator();
    for (u, v) in [(0.05, -0.9), (0.45, 0.0), (0.8, 1.4)] {
        let p = evaluator.eval(u, v).unwrap();
        let q = dense_point(&s, u, v);
        assert!((p.xyz() - q).amax() < 1e-14);
        assert!((p.w - (q.x - q.y)).abs() < 1e-14);
    }
}
