//! Curvature invariants of planar curves: closed forms, Jacobians and Hessians against
//! finite differences and dual numbers (the inflections and curvature extrema of known curves
//! are in `curves_features`).
#![allow(
    clippy::needless_range_loop,
    clippy::cast_lossless,
    clippy::type_complexity,
    clippy::manual_range_contains
)]

use crate::common;

use common::dense;
use nalgebra::Vector2;
use num_dual::{Dual64, HyperDual64};
use proptest::collection::vec;
use proptest::prelude::*;
use spline_algebra::{Form, Invariant, PlanarInvariants};
use spline_core::{KnotVector, binomial};
use spline_geom::{BSpline, Curve2};
use spline_testing::compare::assert_close_rel;
use spline_testing::strategies::{parameters, planar_curve};

const INVARIANTS: [Invariant; 4] = [Invariant::H1, Invariant::H2, Invariant::H3, Invariant::H4];

fn bezier2(x: f64, y: f64) -> Curve2 {
    BSpline::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(-1.0, 0.0),
            Vector2::new(x, y),
            Vector2::new(1.0, 0.0),
        ],
    )
    .unwrap()
}

fn wedge(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// h1..h4 and g at u from the curve's derivatives (independent of the algebra).
fn geometric(curve: &Curve2, u: f64) -> [f64; 5] {
    let d = curve.derivatives(u, 3).unwrap();
    let h = [
        d[1].dot(&d[1]),
        wedge(d[1], d[3]),
        d[1].dot(&d[2]),
        wedge(d[1], d[2]),
    ];
    [h[0], h[1], h[2], h[3], h[0] * h[1] - 3.0 * h[2] * h[3]]
}

/// The magnitudes of the terms of [`geometric`]'s values (products of the derivatives'
/// lengths): the scale of their rounding errors, however much the terms cancel.
fn magnitudes(curve: &Curve2, u: f64) -> [f64; 5] {
    let d: Vec<f64> = curve
        .derivatives(u, 3)
        .unwrap()
        .iter()
        .map(nalgebra::Matrix::norm)
        .collect();
    let h = [d[1] * d[1], d[1] * d[3], d[1] * d[2], d[1] * d[2]];
    [h[0], h[1], h[2], h[3], h[0] * h[1] + 3.0 * h[2] * h[3]]
}

#[test]
fn quadratic_bezier_closed_form() {
    let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).unwrap();
    let algebra = PlanarInvariants::new(&knots).unwrap();
    let mut patterns_seen = std::collections::HashSet::new();
    for i in 0..=80 {
        for j in 0..=80 {
            let (x, y) = (
                -2.0 + 4.0 * i as f64 / 80.0 + 1e-3,
                -2.0 + 4.0 * j as f64 / 80.0 + 1e-3,
            );
            let curve = bezier2(x, y);
            let g = algebra.g(curve.control_points(), Form::Bernstein).unwrap();
            let expected = [
                -y * ((x + 0.5) * (x + 0.5) + y * y - 0.25),
                -x * y,
                y * ((x - 0.5) * (x - 0.5) + y * y - 0.25),
            ];
            let gi = g.value.control_points();
            assert_eq!(gi.len(), 3, "(4d − 5)(n − d) = 3 coefficients");
            for k in 0..3 {
                assert_close_rel(
                    gi[k],
                    192.0 * expected[k],
                    1e-12,
                    1.0,
                    &format!("g{k} at ({x}, {y})"),
                );
            }
            let signs: Vec<bool> = gi.iter().map(|&v| v > 0.0).collect();
            assert!(
                signs != [false, true, false] && signs != [true, false, true],
                "forbidden sign pattern at ({x}, {y}): {gi:?}"
            );
            patterns_seen.insert(signs);
            // Translation invariance: every gradient row sums to zero per coordinate.
            for row in dense(&g.jacobian) {
                let sx: f64 = row.iter().step_by(2).sum();
                let sy: f64 = row.iter().skip(1).step_by(2).sum();
                assert!(sx.abs() < 1e-10 && sy.abs() < 1e-10, "row sums {sx}, {sy}");
            }
        }
    }
    assert_eq!(
        patterns_seen.len(),
        6,
        "the six possible sign patterns all occur"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    #[test]
    fn invariants_evaluate_to_the_geometric_quantities(curve in planar_curve(2, 6, false), samples in vec(0.0f64..1.0, 30)) {
        let p = curve.degree();
        let case = format!("p = {p}");
        let algebra = PlanarInvariants::new(curve.knots()).unwrap();
        let pts = curve.control_points();
        let forms = [Form::BSpline, Form::Bernstein];
        for form in forms {
            // The minimal B-spline form is reached by blossoming the pieces at the knots;
            // where two knots lie 1e-4 apart (the pool has such a pair) that space is
            // ill-conditioned and rounding grows with the extrapolation (measured over 10³
            // random cases: up to 3e-6 at degree 5, 1e-5 at degree 6).
            let breaks = curve.knots().domain_breaks();
            let close = breaks.windows(2).any(|w| w[1] - w[0] < 1e-3);
            let tol = match form {
                Form::BSpline if close => 1e-5 * 10f64.powi((p as i32 - 5).max(0)),
                // The reference itself: third derivatives across close knots round at the
                // size of their terms.
                Form::Bernstein if close => 1e-9,
                _ => 1e-10,
            };
            let hs: Vec<_> = INVARIANTS
                .iter()
                .map(|&w| algebra.invariant_value(w, pts, form).unwrap())
                .collect();
            let g = algebra.g_value(pts, form).unwrap();

            for u in parameters(curve.knots(), &samples) {
                let geo = geometric(&curve, u);
                let size = magnitudes(&curve, u);
                for k in 0..4 {
                    assert_close_rel(
                        hs[k].eval(u).unwrap(),
                        geo[k],
                        tol,
                        size[k].max(1.0),
                        &format!("case {case} h{} ({form:?}) at {u}", k + 1),
                    );
                }
                assert_close_rel(
                    g.eval(u).unwrap(),
                    geo[4],
                    tol,
                    size[4].max(1.0),
                    &format!("case {case} g ({form:?}) at {u}"),
                );
            }
        }
        // Coefficient counts of the per-segment form: (4d − 5) per segment.
        let segments = curve.knots().interior_breakpoints().len() + 1;
        assert_eq!(
            algebra.g_space(Form::Bernstein).num_basis(),
            (4 * p - 5) * segments
        );
        // With simple knots, the B-spline form of g has interior multiplicity 3d − 2.
        for (k, m) in curve.knots().interior_breakpoints() {
            let expected = (3 * p - 3 + m).min(4 * p - 5);
            assert_eq!(
                algebra.g_space(Form::BSpline).multiplicity(k),
                expected,
                "case {case}: knot {k} of multiplicity {m}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(60))]

    #[test]
    fn g_of_a_cubic_has_true_degree_4d_minus_7(curve in planar_curve(3, 5, true)) {
        let p = curve.degree();
        {
            let algebra = PlanarInvariants::new(curve.knots()).unwrap();
            let g = algebra
                .g_value(curve.control_points(), Form::Bernstein)
                .unwrap();
            let deg = 4 * p - 6;
            for seg in g.control_points().chunks(deg + 1) {
                let top: f64 = (0..=deg)
                    .map(|i| if (deg - i) % 2 == 0 { 1.0 } else { -1.0 } * binomial::<f64>(deg, i) * seg[i])
                    .sum();
                let scale: f64 = (0..=deg)
                    .map(|i| binomial::<f64>(deg, i) * seg[i].abs())
                    .sum();
                assert!(
                    top.abs() <= 1e-12 * scale.max(1e-300),
                    "leading coefficient {top} (scale {scale})"
                );
                // …and the next one does not vanish in general.
                let next: f64 = (0..deg)
                    .map(|i| if (deg - 1 - i) % 2 == 0 { 1.0 } else { -1.0 } * binomial::<f64>(deg - 1, i) * seg[i])
                    .sum();
                assert!(
                    next.abs() > 1e-12 * scale,
                    "degree 4d − 7 term vanishes too: {next} vs {scale}, {seg:?}"
                );
            }
        }
    }
}

fn to_duals<D: spline_core::Scalar>(
    knots: &KnotVector<f64>,
    f: impl Fn(f64) -> D,
) -> KnotVector<D> {
    KnotVector::new(
        knots.degree(),
        knots.knots().iter().map(|&k| f(k)).collect(),
    )
    .unwrap()
}

// Knots on the grid of eighths: derivatives are checked against finite differences, whose
// own error would dominate near knots 1e-4 apart (g reaches 1e20 there).
proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn jacobians_and_hessians_agree_with_finite_differences_and_dual_numbers(curve in planar_curve(2, 4, true)) {
        let case = format!("p = {}", curve.degree());
        let knots = curve.knots().clone();
        let pts = curve.control_points().to_vec();
        let nx = 2 * pts.len();
        let algebra = PlanarInvariants::new(&knots).unwrap();
        let alg_dual = PlanarInvariants::new(&to_duals(&knots, Dual64::from)).unwrap();
        let alg_hyper = PlanarInvariants::new(&to_duals(&knots, HyperDual64::from)).unwrap();
        let bump = |j: usize, h: f64| {
            let mut q = pts.clone();
            q[j / 2][j % 2] += h;
            q
        };
        for form in [Form::Bernstein, Form::BSpline] {
            let mut quantities: Vec<(
                String,
                Vec<Vec<f64>>,
                Box<dyn Fn(&[Vector2<f64>]) -> Vec<f64>>,
            )> = Vec::new();
            for w in INVARIANTS {
                let d = algebra.invariant(w, &pts, form).unwrap();
                let alg = &algebra;
                quantities.push((
                    format!("{w:?}"),
                    dense(&d.jacobian),
                    Box::new(move |q| {
                        alg.invariant_value(w, q, form)
                            .unwrap()
                            .control_points()
                            .to_vec()
                    }),
                ));
            }
            let g = algebra.g(&pts, form).unwrap();
            let alg = &algebra;
            quantities.push((
                "g".into(),
                dense(&g.jacobian),
                Box::new(move |q| alg.g_value(q, form).unwrap().control_points().to_vec()),
            ));
            // Central finite differences (five points: exact for these quadratic and quartic
            // functions up to rounding).
            let h = 1e-3;
            for (name, jac, eval) in &quantities {
                for j in 0..nx {
                    let (fp, fm) = (eval(&bump(j, h)), eval(&bump(j, -h)));
                    let (fp2, fm2) = (eval(&bump(j, 2.0 * h)), eval(&bump(j, -2.0 * h)));
                    let scale = fp.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                    for k in 0..fp.len() {
                        let fd = (fm2[k] - 8.0 * fm[k] + 8.0 * fp[k] - fp2[k]) / (12.0 * h);
                        assert_close_rel(
                            jac[k][j],
                            fd,
                            1e-6,
                            scale * 1e-3,
                            &format!("case {case} {name} {form:?}: d{k}/dx{j}"),
                        );
                    }
                }
            }
            // Dual numbers.
            for j in 0..nx {
                let dual: Vec<Vector2<Dual64>> = pts
                    .iter()
                    .enumerate()
                    .map(|(i, q)| {
                        Vector2::new(
                            Dual64::new(q.x, if 2 * i == j { 1.0 } else { 0.0 }),
                            Dual64::new(q.y, if 2 * i + 1 == j { 1.0 } else { 0.0 }),
                        )
                    })
                    .collect();
                for (qi, w) in INVARIANTS.iter().enumerate() {
                    let v = alg_dual.invariant_value(*w, &dual, form).unwrap();
                    for (k, c) in v.control_points().iter().enumerate() {
                        let row = quantities[qi].1[k]
                            .iter()
                            .fold(1.0f64, |m, x| m.max(x.abs()));
                        assert_close_rel(
                            quantities[qi].1[k][j],
                            c.eps,
                            1e-12,
                            row,
                            &format!("case {case} dual {w:?}"),
                        );
                    }
                }
                let v = alg_dual.g_value(&dual, form).unwrap();
                for (k, c) in v.control_points().iter().enumerate() {
                    let row = quantities[4].1[k]
                        .iter()
                        .fold(1.0f64, |m, x| m.max(x.abs()));
                    assert_close_rel(
                        quantities[4].1[k][j],
                        c.eps,
                        1e-12,
                        row,
                        &format!("case {case} dual g d{k}/dx{j}"),
                    );
                }
            }
            // Hessians: hyper-dual numbers (every pair of variables) for g and h1..h4.
            let gh = algebra.g_hessian(&pts, form).unwrap();
            let hh: Vec<_> = INVARIANTS
                .iter()
                .map(|&w| algebra.invariant_hessian(w, form))
                .collect();
            let gh_dense: Vec<Vec<Vec<f64>>> =
                (0..gh.nrows()).map(|k| dense(&gh.matrix(k))).collect();
            for j in 0..nx {
                for l in j..nx {
                    let hyper: Vec<Vector2<HyperDual64>> = pts
                        .iter()
                        .enumerate()
                        .map(|(i, q)| {
                            let e = |v: usize| {
                                (
                                    if v == j { 1.0 } else { 0.0 },
                                    if v == l { 1.0 } else { 0.0 },
                                )
                            };
                            let (ax, bx) = e(2 * i);
                            let (ay, by) = e(2 * i + 1);
                            Vector2::new(
                                HyperDual64::new(q.x, ax, bx, 0.0),
                                HyperDual64::new(q.y, ay, by, 0.0),
                            )
                        })
                        .collect();
                    let v = alg_hyper.g_value(&hyper, form).unwrap();
                    for (k, c) in v.control_points().iter().enumerate() {
                        let scale = gh_dense[k]
                            .iter()
                            .flatten()
                            .fold(1.0f64, |m, x| m.max(x.abs()));
                        assert_close_rel(
                            gh_dense[k][j][l],
                            c.eps1eps2,
                            1e-12,
                            scale,
                            &format!("case {case} g hessian {k} ({j}, {l})"),
                        );
                        assert_close_rel(
                            gh_dense[k][l][j],
                            c.eps1eps2,
                            1e-12,
                            scale,
                            "g hessian symmetry",
                        );
                    }
                    for (w, hess) in INVARIANTS.iter().zip(&hh) {
                        let v = alg_hyper.invariant_value(*w, &hyper, form).unwrap();
                        for (k, c) in v.control_points().iter().enumerate() {
                            let stored = hess
                                .row(k)
                                .iter()
                                .find(|e| e.0 == j && e.1 == l)
                                .map_or(0.0, |e| e.2);
                            let scale = hess.row(k).iter().fold(1.0f64, |m, e| m.max(e.2.abs()));
                            assert_close_rel(
                                stored,
                                c.eps1eps2,
                                1e-12,
                                scale,
                                &format!("case {case} {w:?} hessian"),
                            );
                        }
                    }
                }
            }
            // Hessian of g by finite differences of the Jacobian (a few variables).
            for j in (0..nx).step_by(3) {
                let jp = dense(&algebra.g(&bump(j, 1e-6), form).unwrap().jacobian);
                let jm = dense(&algebra.g(&bump(j, -1e-6), form).unwrap().jacobian);
                for k in 0..jp.len() {
                    let scale = jp[k].iter().fold(1.0f64, |m, v| m.max(v.abs()));
                    for l in 0..nx {
                        let fd = (jp[k][l] - jm[k][l]) / 2e-6;
                        // Truncation O(h²) relative, plus the rounding of the difference
                        // quotient: the Jacobian's rounding (a few hundred ε of the terms it
                        // sums, which can exceed max|J|) divided by h.
                        let bound = 1e-6 * fd.abs().max(1e-2 * scale) + 1e-7 * scale;
                        let got = gh_dense[k][l][j];
                        prop_assert!(
                            (got - fd).abs() <= bound,
                            "case {} g hessian FD: got {}, expected {} (bound {:e})",
                            case, got, fd, bound
                        );
                    }
                }
            }
        }
        // The Jacobian of g(u) at parameters (knots included) against finite differences of
        // the geometric g computed from the curve's derivatives.
        let g = algebra.g(&pts, Form::BSpline).unwrap();
        let jac = dense(&g.jacobian);
        let mut params: Vec<f64> = knots
            .knots()
            .iter()
            .copied()
            .filter(|&k| k >= 0.0 && k <= 1.0)
            .collect();
        params.extend([0.123, 0.5, 0.77]);
        for u in params {
            let basis = g.value.knots().dense_basis(u).unwrap();
            for j in 0..nx {
                let analytic: f64 = (0..basis.len()).map(|k| basis[k] * jac[k][j]).sum();
                // Five-point central differences: exact for the quartic g up to rounding.
                let h = 1e-3;
                let gat =
                    |s: f64| geometric(&BSpline::new(knots.clone(), bump(j, s * h)).unwrap(), u)[4];
                let fd = (gat(-2.0) - 8.0 * gat(-1.0) + 8.0 * gat(1.0) - gat(2.0)) / (12.0 * h);
                // Rounding in the differences is about eps·|g|/h.
                let size = 1.0 + analytic.abs() + 1e-3 * geometric(&curve, u)[4].abs();
                assert_close_rel(
                    analytic,
                    fd,
                    1e-6,
                    size,
                    &format!("case {case}: dg({u})/dx{j}"),
                );
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20))]

    #[test]
    fn gradient_rows_sum_to_zero_per_coordinate(curve in planar_curve(2, 5, true)) {

        let algebra = PlanarInvariants::new(curve.knots()).unwrap();
        for form in [Form::Bernstein, Form::BSpline] {
            let g = algebra.g(curve.control_points(), form).unwrap();
            for row in dense(&g.jacobian) {
                let scale = row.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                let sx: f64 = row.iter().step_by(2).sum();
                let sy: f64 = row.iter().skip(1).step_by(2).sum();
                assert!(sx.abs() < 1e-11 * scale && sy.abs() < 1e-11 * scale);
            }
        }
    }
}
