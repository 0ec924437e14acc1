//! Curvature extrema and torsion zeros of space curves, against closed forms, dense
//! sampling, dual numbers and finite differences.

#![allow(clippy::needless_range_loop)]

use crate::common;

use nalgebra::Vector3;
use spline_algebra::{SpaceCurveFeatures, space_numerators, torsion};
use spline_geom::{BSpline, Homogeneous, NurbsCurve};

fn bezier3(points: [[f64; 3]; 4], a: f64, b: f64) -> BSpline<f64, Vector3<f64>> {
    BSpline::from_knots(
        3,
        vec![a, a, a, a, b, b, b, b],
        points
            .iter()
            .map(|p| Vector3::new(p[0], p[1], p[2]))
            .collect(),
    )
    .unwrap()
}

/// The twisted cubic `(u, u², u³)` on [−1, 1]: torsion `3 / (9u⁴ + 9u² + 1)` (no zero),
/// curvature `2 √(9u⁴ + 9u² + 1) / (1 + 4u² + 9u⁴)^{3/2}`, largest at `u = 0` only.
#[test]
fn twisted_cubic_against_its_closed_forms() {
    // Bézier points of (u, u², u³) on [−1, 1].
    let c = bezier3(
        [
            [-1.0, 1.0, -1.0],
            [-1.0 / 3.0, -1.0 / 3.0, 1.0],
            [1.0 / 3.0, -1.0 / 3.0, -1.0],
            [1.0, 1.0, 1.0],
        ],
        -1.0,
        1.0,
    );
    for u in [-0.9, -0.3, 0.0, 0.45, 1.0] {
        let p = c.eval(u).unwrap();
        assert!((p - Vector3::new(u, u * u, u * u * u)).norm() < 1e-14);
        let t = torsion(&c, u).unwrap();
        let q = 9.0 * u.powi(4) + 9.0 * u * u + 1.0;
        assert!((t - 3.0 / q).abs() < 1e-13, "{u}: {t}");
        let kappa = 2.0 * q.sqrt() / (1.0 + 4.0 * u * u + 9.0 * u.powi(4)).powf(1.5);
        assert!((c.curvature_magnitude(u).unwrap() - kappa).abs() < 1e-13);
    }
    let f = c.space_features(1e-13).unwrap();
    assert!(f.torsion_zeros.is_empty(), "{f:?}");
    assert_eq!(f.curvature_extrema.len(), 1, "{f:?}");
    assert!(f.curvature_extrema[0].abs() < 1e-12);
    assert_eq!((f.constant_curvature, f.constant_torsion), (None, None));
}

/// `(u, u², u⁴)`: `det(c′, c″, c‴) = 48u`, one torsion zero at `u = 0`.
#[test]
fn torsion_zero_of_a_quartic() {
    // Power basis → Bernstein on [−1, 1] by sampling-free conversion: interpolate through
    // the monomials with the curve's own evaluation is circular, so use the blossom:
    // for degree 4 on [−1, 1], b_k = Σ_j C(k, j)/C(4, j) · (coefficients of t = (u + 1)/2).
    let power = |coef: [f64; 5]| -> Vec<f64> {
        // f(u) = Σ a_i u^i with u = 2t − 1: expand into t-power coefficients, then Bernstein.
        let mut t = [0.0; 5];
        let binom = |n: usize, k: usize| -> f64 {
            (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
        };
        for (i, &a) in coef.iter().enumerate() {
            for j in 0..=i {
                t[j] += a * binom(i, j) * 2f64.powi(j as i32) * (-1f64).powi((i - j) as i32);
            }
        }
        (0..5)
            .map(|k| (0..=k).map(|j| binom(k, j) / binom(4, j) * t[j]).sum())
            .collect()
    };
    let (x, y, z) = (
        power([0.0, 1.0, 0.0, 0.0, 0.0]),
        power([0.0, 0.0, 1.0, 0.0, 0.0]),
        power([0.0, 0.0, 0.0, 0.0, 1.0]),
    );
    let c = BSpline::from_knots(
        4,
        vec![-1.0, -1.0, -1.0, -1.0, -1.0, 1.0, 1.0, 1.0, 1.0, 1.0],
        (0..5).map(|k| Vector3::new(x[k], y[k], z[k])).collect(),
    )
    .unwrap();
    let p = c.eval(0.7).unwrap();
    assert!((p - Vector3::new(0.7, 0.49, 0.7f64.powi(4))).norm() < 1e-14);
    let f = c.space_features(1e-13).unwrap();
    assert_eq!(f.torsion_zeros.len(), 1, "{f:?}");
    assert!(f.torsion_zeros[0].abs() < 1e-12);
}

/// A planar curve embedded in space has constant (zero) torsion; a circle in space has
/// constant curvature.
#[test]
fn planar_space_curves_and_circles() {
    use spline_geom::{CircleConstruction, Frame};
    let frame = Frame::new(
        Vector3::new(1.0, 2.0, 3.0),
        Vector3::new(1.0, 1.0, 0.0).normalize(),
        Vector3::new(0.0, 0.0, 1.0),
    )
    .unwrap();
    let circle = NurbsCurve::circle(&frame, 2.5, CircleConstruction::Square).unwrap();
    let f = circle.space_features(1e-12).unwrap();
    assert!(
        (f.constant_curvature.unwrap() - 0.4f64).abs() < 1e-12,
        "{f:?}"
    );
    assert_eq!(f.constant_torsion, Some(0.0));
    assert!(f.curvature_extrema.is_empty() && f.torsion_zeros.is_empty());
}

/// Random rational cubics: every sign change of the sampled torsion and of the sampled
/// derivative of the curvature is reported, and nothing else.
#[test]
fn rational_space_features_match_dense_sampling() {
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut seen = (0, 0);
    for case in 0..12 {
        let n: usize = 6;
        let points: Vec<Vector3<f64>> = (0..n)
            .map(|i| Vector3::new(i as f64 + next(), 3.0 * next() - 1.5, 3.0 * next() - 1.5))
            .collect();
        let weights: Vec<f64> = (0..n)
            .map(|_| {
                if case % 2 == 0 {
                    1.0
                } else {
                    0.4 + 2.0 * next()
                }
            })
            .collect();
        let curve = NurbsCurve::from_knots(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.35, 0.6, 1.0, 1.0, 1.0, 1.0],
            points,
            weights,
        )
        .unwrap();
        let f = curve.space_features(1e-13).unwrap();
        let m = 40_000;
        let u = |j: usize| j as f64 / m as f64;
        let tau: Vec<f64> = (0..=m).map(|j| torsion(&curve, u(j)).unwrap()).collect();
        let kappa: Vec<f64> = (0..=m)
            .map(|j| curve.curvature_magnitude(u(j)).unwrap())
            .collect();
        let crossings = |values: &[f64], offset: f64| -> Vec<f64> {
            (1..values.len())
                .filter(|&j| values[j - 1] * values[j] < 0.0)
                .map(|j| u(j) - offset)
                .collect()
        };
        let tz = crossings(&tau, 0.5 / m as f64);
        let slope: Vec<f64> = kappa.windows(2).map(|w| w[1] - w[0]).collect();
        let ex = crossings(&slope, 0.0);
        for (found, expected, what) in [
            (&f.torsion_zeros, &tz, "torsion zeros"),
            (&f.curvature_extrema, &ex, "curvature extrema"),
        ] {
            assert_eq!(
                found.len(),
                expected.len(),
                "case {case} {what}: {found:?} vs {expected:?}"
            );
            for (a, b) in found.iter().zip(expected) {
                assert!(
                    (a - b).abs() < 3.0 / m as f64,
                    "case {case} {what}: {found:?} vs {expected:?}"
                );
            }
        }
        seen.0 += tz.len();
        seen.1 += ex.len();
    }
    // The check is not vacuous.
    assert!(seen.0 > 3 && seen.1 > 3, "{seen:?}");
}

/// The Jacobians of the space numerators w.r.t. the weighted control points, every column
/// against dual numbers.
#[test]
fn space_numerator_jacobians_agree_with_dual_numbers() {
    use num_dual::Dual64;
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
    let hom: Vec<[f64; 4]> = vec![
        [0.0, 0.0, 0.0, 1.0],
        [1.0, 2.0, -0.5, 1.5],
        [2.0, -1.0, 1.0, 0.7],
        [3.0, 1.0, 2.0, 1.2],
        [4.0, 0.0, 0.5, 1.0],
    ];
    let n = space_numerators(
        &NurbsCurve::from_homogeneous(
            BSpline::from_knots(
                3,
                knots.clone(),
                hom.iter()
                    .map(|q| Homogeneous::new(Vector3::new(q[0], q[1], q[2]), q[3]))
                    .collect(),
            )
            .unwrap(),
        )
        .unwrap(),
    )
    .unwrap();
    let jg = common::dense(&n.curvature_extremum.jacobian);
    let jt = common::dense(&n.torsion.jacobian);
    for col in 0..20 {
        let dual = NurbsCurve::from_homogeneous(
            BSpline::from_knots(
                3,
                knots.iter().map(|&k| Dual64::from(k)).collect(),
                hom.iter()
                    .enumerate()
                    .map(|(i, q)| {
                        let d =
                            |k: usize| Dual64::new(q[k], if 4 * i + k == col { 1.0 } else { 0.0 });
                        Homogeneous::new(Vector3::new(d(0), d(1), d(2)), d(3))
                    })
                    .collect(),
            )
            .unwrap(),
        )
        .unwrap();
        let nd = space_numerators(&dual).unwrap();
        for (which, jac, values) in [
            ("G", &jg, nd.curvature_extremum.value.control_points()),
            ("T", &jt, nd.torsion.value.control_points()),
        ] {
            let scale = values.iter().fold(1.0f64, |m, v| m.max(v.eps.abs()));
            for (r, v) in values.iter().enumerate() {
                assert!(
                    (jac[r][col] - v.eps).abs() < 1e-10 * scale,
                    "{which} row {r} col {col}: {} vs {}",
                    jac[r][col],
                    v.eps
                );
            }
        }
    }
}

/// The Hessians of the space numerators against hyper-dual numbers (second derivatives of
/// the values, independent of the Jacobian code) on every pair of variables of the two
/// middle control points, and symmetric.
#[test]
fn space_numerator_hessians_agree_with_hyper_dual_numbers() {
    use num_dual::HyperDual64;
    use spline_algebra::space_numerator_hessians;
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
    let hom: Vec<[f64; 4]> = vec![
        [0.0, 0.0, 0.0, 1.0],
        [1.0, 2.0, -0.5, 1.5],
        [2.0, -1.0, 1.0, 0.7],
        [3.0, 1.0, 2.0, 1.2],
        [4.0, 0.0, 0.5, 1.0],
    ];
    let curve = NurbsCurve::from_homogeneous(
        BSpline::from_knots(
            3,
            knots.clone(),
            hom.iter()
                .map(|q| Homogeneous::new(Vector3::new(q[0], q[1], q[2]), q[3]))
                .collect(),
        )
        .unwrap(),
    )
    .unwrap();
    let [hg, ht] = space_numerator_hessians(&curve).unwrap();
    assert_eq!((hg.left_dim(), ht.left_dim()), (20, 20));
    let mut checked = 0;
    let mut largest = 0.0f64;
    for a in 4..12 {
        for b in a..12 {
            let hyper = NurbsCurve::from_homogeneous(
                BSpline::from_knots(
                    3,
                    knots.iter().map(|&k| HyperDual64::from(k)).collect(),
                    hom.iter()
                        .enumerate()
                        .map(|(i, q)| {
                            let d = |k: usize| {
                                let j = 4 * i + k;
                                HyperDual64::new(
                                    q[k],
                                    if j == a { 1.0 } else { 0.0 },
                                    if j == b { 1.0 } else { 0.0 },
                                    0.0,
                                )
                            };
                            Homogeneous::new(Vector3::new(d(0), d(1), d(2)), d(3))
                        })
                        .collect(),
                )
                .unwrap(),
            )
            .unwrap();
            let n = space_numerators(&hyper).unwrap();
            for (which, h, values) in [
                ("G", &hg, n.curvature_extremum.value.control_points()),
                ("T", &ht, n.torsion.value.control_points()),
            ] {
                assert_eq!(h.nrows(), values.len());
                let scale = values.iter().fold(1.0f64, |m, v| m.max(v.eps1eps2.abs()));
                for (k, v) in values.iter().enumerate() {
                    let m = common::dense(&h.matrix(k));
                    assert!(
                        (m[a][b] - v.eps1eps2).abs() < 1e-10 * scale,
                        "{which} row {k} ({a}, {b}): {} vs {}",
                        m[a][b],
                        v.eps1eps2
                    );
                    assert!((m[a][b] - m[b][a]).abs() < 1e-10 * scale);
                    checked += 1;
                    largest = largest.max(v.eps1eps2.abs());
                }
            }
        }
    }
    assert!(checked > 100);
    assert!(
        largest > 1e-3,
        "the second derivatives checked are all zero"
    );
}

/// A random space cubic whose curvature numerator is 1e20 near one end and 1e6 in the
/// middle (reproducer `space_cubic_extrema.json`): the zero test was relative to the largest
/// coefficient anywhere, so two extrema of the middle (a maximum κ = 42.37 at u ≈ 0.5389,
/// a minimum at u ≈ 0.3440) were missed. Checked against dense sampling of κ.
#[test]
fn extrema_where_the_numerator_is_small_against_its_largest_coefficient() {
    let curve = BSpline::from_knots(
        3,
        vec![
            0.0,
            0.0,
            0.0,
            0.0,
            0.00814621021272166,
            0.39983511463936516,
            0.6268196454053702,
            0.7457955928052529,
            0.8129430514019474,
            1.0,
            1.0,
            1.0,
            1.0,
        ],
        [
            [
                0.1432771670085956,
                -0.34079530431860283,
                -0.2988362348789169,
            ],
            [-0.308447270562775, -0.6457669113733923, -1.188076424014336],
            [-0.603921585887524, 1.1240688507924026, 0.9008051480098249],
            [0.9487941399458188, 0.38271955761798154, -0.5355460157441487],
            [
                0.6931550193107057,
                -0.49121344674450407,
                -0.8030453663336368,
            ],
            [0.27144205690772577, 0.9109990637377727, -0.3822688931373175],
            [0.20236196169795995, -0.11420765761408846, 1.397631012959613],
            [1.0628706544997046, 0.3613607558620529, -0.1875892342371591],
            [
                -0.7365078073717658,
                -0.8510034128648848,
                -1.7117409925828153,
            ],
        ]
        .iter()
        .map(|p| Vector3::new(p[0], p[1], p[2]))
        .collect(),
    )
    .unwrap();
    let found = curve.space_features(1e-12).unwrap().curvature_extrema;
    // Dense sampling: the turning points of κ on a grid of 400,001 parameters.
    let n = 400_000;
    let kappa: Vec<f64> = (0..=n)
        .map(|i| {
            curve
                .curvature_magnitude(f64::from(i) / f64::from(n))
                .unwrap()
        })
        .collect();
    let sampled: Vec<f64> = (1..n as usize)
        .filter(|&i| (kappa[i] - kappa[i - 1]) * (kappa[i + 1] - kappa[i]) < 0.0)
        .map(|i| i as f64 / f64::from(n))
        .collect();
    assert_eq!(found.len(), 9, "{found:?}");
    assert_eq!(
        sampled.len(),
        found.len(),
        "sampled {sampled:?} found {found:?}"
    );
    for (s, f) in sampled.iter().zip(&found) {
        assert!((s - f).abs() < 1e-5, "sampled {s} found {f}");
    }
}
