//! The dense segment kernel of `g` against the sparse bilinear algebra
//! (`PlanarInvariants`, built independently from Bernstein products of whole splines) and
//! against finite differences.

use nalgebra::Vector2;
use proptest::prelude::*;
use spline_algebra::{Form, PlanarInvariants, SegmentCurvature};
use spline_core::KnotVector;

/// A degree, a knot vector (clamped or not, interior multiplicities up to `p`) and
/// control points.
fn curve_strategy() -> impl Strategy<Value = (KnotVector<f64>, Vec<Vector2<f64>>)> {
    (3usize..=6, 0usize..=4, any::<bool>())
        .prop_flat_map(|(p, interior, clamped)| {
            (
                Just(p),
                prop::collection::vec((0.05f64..0.95, 1usize..=p), interior),
                Just(clamped),
                prop::collection::vec(0.0f64..0.3, p),
            )
        })
        .prop_flat_map(|(p, interior, clamped, left)| {
            let mut knots: Vec<f64> = Vec::new();
            if clamped {
                knots.extend(std::iter::repeat_n(0.0, p + 1));
            } else {
                let mut acc = 0.0;
                let mut before: Vec<f64> = left
                    .iter()
                    .map(|d| {
                        acc -= 0.05 + d;
                        acc
                    })
                    .collect();
                before.reverse();
                knots.extend(before);
                knots.push(0.0);
            }
            let mut inner: Vec<(f64, usize)> = interior;
            inner.sort_by(|a, b| a.0.total_cmp(&b.0));
            inner.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-3);
            for (u, m) in inner {
                knots.extend(std::iter::repeat_n(u, m));
            }
            if clamped {
                knots.extend(std::iter::repeat_n(1.0, p + 1));
            } else {
                knots.push(1.0);
                let mut acc = 1.0;
                for d in &left {
                    acc += 0.05 + d;
                    knots.push(acc);
                }
            }
            let knots = KnotVector::new(p, knots).expect("valid knot vector");
            let n = knots.num_basis();
            (
                Just(knots),
                prop::collection::vec((-2.0f64..2.0, -2.0f64..2.0), n)
                    .prop_map(|v| v.into_iter().map(|(x, y)| Vector2::new(x, y)).collect()),
            )
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(120))]

    #[test]
    fn kernel_matches_the_sparse_algebra((knots, points) in curve_strategy(), seed in 0u64..1000) {
        let kernel = SegmentCurvature::new(&knots).unwrap();
        let algebra = PlanarInvariants::new(&knots).unwrap();
        let reference = algebra.g(&points, Form::Bernstein).unwrap();
        let coefficients = reference.value.control_points();
        prop_assert_eq!(coefficients.len(), kernel.num_coefficients());
        let scale = coefficients.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let q1 = kernel.coefficients_per_segment();
        let nl = kernel.local_variables();
        let mut ws = kernel.workspace();
        // Weights for the Hessian check, deterministic from the seed.
        let weights: Vec<f64> = (0..kernel.num_coefficients())
            .map(|k| (((k as u64 + 1) * (seed + 7)) % 13) as f64 / 6.0 - 1.0)
            .collect();
        let nvar = 2 * points.len();
        let mut dense_hessian = vec![0.0; nvar * nvar];
        for s in 0..kernel.num_segments() {
            let mut values = vec![0.0; q1];
            let mut jac = vec![0.0; q1 * nl];
            let mut hess = vec![0.0; nl * nl];
            kernel.segment(
                s,
                &points,
                &mut ws,
                &mut values,
                Some(&mut jac),
                Some((&weights[s * q1..(s + 1) * q1], &mut hess)),
            );
            let first = kernel.first_point(s);
            for k in 0..q1 {
                let row = s * q1 + k;
                prop_assert!((values[k] - coefficients[row]).abs() <= 1e-10 * scale,
                    "value {} vs {}", values[k], coefficients[row]);
                // Jacobian row: local column c ↔ global variable 2 first + c.
                let global = reference.jacobian.row(row);
                let mut expected = vec![0.0; nl];
                for (&c, &v) in global.col_indices().iter().zip(global.values()) {
                    prop_assert!(c >= 2 * first && c < 2 * first + nl, "support outside the segment");
                    expected[c - 2 * first] = v;
                }
                for c in 0..nl {
                    prop_assert!((jac[k * nl + c] - expected[c]).abs() <= 1e-10 * scale,
                        "jacobian {} vs {}", jac[k * nl + c], expected[c]);
                }
            }
            for a in 0..nl {
                for b in 0..nl {
                    dense_hessian[(2 * first + a) * nvar + 2 * first + b] += hess[a * nl + b];
                }
            }
        }
        // Σ w_k ∇²g_k from the sparse bilinear Hessian.
        let hessian = algebra.g_hessian(&points, Form::Bernstein).unwrap();
        let mut expected = vec![0.0; nvar * nvar];
        for (k, &w) in weights.iter().enumerate() {
            for &(i, j, v) in hessian.row(k) {
                expected[i * nvar + j] += w * v;
            }
        }
        let hscale = expected.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        for (a, b) in dense_hessian.iter().zip(&expected) {
            prop_assert!((a - b).abs() <= 1e-10 * hscale, "hessian {} vs {}", a, b);
        }
    }
}

/// Central differences of the values reproduce the Jacobian (an independent check of the
/// product rule, without the sparse algebra).
#[test]
fn jacobian_matches_finite_differences() {
    let knots = KnotVector::new(
        4,
        vec![
            0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 0.7, 1.0, 1.0, 1.0, 1.0, 1.0,
        ],
    )
    .unwrap();
    let points: Vec<Vector2<f64>> = (0..knots.num_basis())
        .map(|i| {
            let t = i as f64;
            Vector2::new(t.cos() + 0.3 * t, (1.7 * t).sin())
        })
        .collect();
    let kernel = SegmentCurvature::new(&knots).unwrap();
    let q1 = kernel.coefficients_per_segment();
    let nl = kernel.local_variables();
    let mut ws = kernel.workspace();
    for s in 0..kernel.num_segments() {
        let mut values = vec![0.0; q1];
        let mut jac = vec![0.0; q1 * nl];
        kernel.segment(s, &points, &mut ws, &mut values, Some(&mut jac), None);
        let first = kernel.first_point(s);
        for c in 0..nl {
            let h = 1e-6;
            let mut plus = points.clone();
            let mut minus = points.clone();
            plus[first + c / 2][c % 2] += h;
            minus[first + c / 2][c % 2] -= h;
            let (mut vp, mut vm) = (vec![0.0; q1], vec![0.0; q1]);
            kernel.segment(s, &plus, &mut ws, &mut vp, None, None);
            kernel.segment(s, &minus, &mut ws, &mut vm, None, None);
            for k in 0..q1 {
                let fd = (vp[k] - vm[k]) / (2.0 * h);
                let scale = 1.0 + jac[k * nl + c].abs();
                assert!(
                    (fd - jac[k * nl + c]).abs() < 1e-5 * scale,
                    "segment {s}, coefficient {k}, variable {c}: {fd} vs {}",
                    jac[k * nl + c]
                );
            }
        }
    }
}

#[test]
fn degree_below_three_is_refused() {
    let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).unwrap();
    let err = SegmentCurvature::new(&knots).unwrap_err();
    assert!(err.to_string().contains("degree 3"), "{err}");
}
