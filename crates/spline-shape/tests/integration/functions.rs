//! Constrained approximation of functions of one variable: the experiments of thesis §5.1
//! and §5.4, checked independently — dense sampling of the derivatives with spline-geom,
//! a brute-force enumeration of active sets built from dense matrices of the thesis formulas
//! (5.20)–(5.21), finite differences — and the error contract.

use nalgebra::{DMatrix, DVector};
use spline_core::{ErrorKind, KnotVector};
use spline_geom::BSpline;
use spline_shape::{
    BarrierProblem, FunctionApproximation, FunctionConstraint, FunctionFit, MAX_SIGN_PATTERNS, Sign,
};
use spline_testing::compare::assert_close_rel;
use std::f64::consts::PI;

const FOUR_PI: f64 = 4.0 * PI;

/// The samples of the experiments: `u_j = 0.01 j` on `[0, 4π]`, 1257 of them. With them the
/// costs of §5.1.4 bis come out as the thesis reports (235.6 and 158.2).
fn thesis_params() -> Vec<f64> {
    (0..=1256).map(|j| 0.01 * f64::from(j)).collect()
}

fn fit(approx: &FunctionApproximation, f: impl Fn(f64) -> f64) -> FunctionFit {
    let params = thesis_params();
    let values: Vec<f64> = params.iter().map(|&u| f(u)).collect();
    approx.fit(&params, &values).expect("the fit succeeds")
}

/// `σ s^(k)` at 4000 uniform points of `[a, b]` and at its ends, by spline-geom.
fn sampled(spline: &BSpline<f64, f64>, order: usize, a: f64, b: f64, sign: Sign) -> Vec<f64> {
    (0..=4000)
        .map(|j| a + (b - a) * f64::from(j) / 4000.0)
        .map(|u| sign.factor() * spline.derivatives(u, order).expect("in the domain")[order])
        .collect()
}

/// The smallest of `σ s^(k)` over dense samples, relative to the largest magnitude.
fn worst_relative(spline: &BSpline<f64, f64>, order: usize, a: f64, b: f64, sign: Sign) -> f64 {
    let v = sampled(spline, order, a, b, sign);
    let scale = v.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
    v.iter().copied().fold(f64::INFINITY, f64::min) / scale
}

/// The dense derivative matrix of thesis (5.20)–(5.21), applied `order` times:
/// `f_i = d/(u_{i+d+1} − u_{i+1}) (x_{i+1} − x_i)`, the knot vector losing its ends.
fn derivative_matrix(knots: &KnotVector<f64>, order: usize) -> DMatrix<f64> {
    let mut t = knots.knots().to_vec();
    let mut d = knots.degree();
    let n = knots.num_basis();
    let mut m = DMatrix::identity(n, n);
    for _ in 0..order {
        let rows = m.nrows();
        let mut step = DMatrix::zeros(rows - 1, rows);
        for i in 0..rows - 1 {
            #[allow(clippy::cast_precision_loss)]
            let s = d as f64 / (t[i + d + 1] - t[i + 1]);
            step[(i, i)] = -s;
            step[(i, i + 1)] = s;
        }
        m = step * m;
        t = t[1..t.len() - 1].to_vec();
        d -= 1;
    }
    m
}

/// `min ½‖Ax − b‖²` subject to `G x ≥ 0` by enumerating every active set: each is an
/// equality-constrained QP (a dense KKT system); the best feasible candidate is the optimum.
fn brute_force_qp(a: &DMatrix<f64>, b: &DVector<f64>, g: &DMatrix<f64>) -> (f64, DVector<f64>) {
    let (n, m) = (a.ncols(), g.nrows());
    assert!(m <= 14, "too many constraints to enumerate");
    let q = a.transpose() * a;
    let c = a.transpose() * b;
    let mut best = (f64::INFINITY, DVector::zeros(n));
    for mask in 0u32..(1 << m) {
        let active: Vec<usize> = (0..m).filter(|&i| mask & (1 << i) != 0).collect();
        let k = active.len();
        let mut kkt = DMatrix::zeros(n + k, n + k);
        kkt.view_mut((0, 0), (n, n)).copy_from(&q);
        let mut rhs = DVector::zeros(n + k);
        rhs.rows_mut(0, n).copy_from(&c);
        for (r, &i) in active.iter().enumerate() {
            for j in 0..n {
                kkt[(n + r, j)] = g[(i, j)];
                kkt[(j, n + r)] = g[(i, j)];
            }
        }
        let Some(sol) = kkt.lu().solve(&rhs) else {
            continue;
        };
        let x = sol.rows(0, n).into_owned();
        let gx = g * &x;
        let scale = 1e-9 * (1.0 + x.amax()) * g.amax();
        if gx.iter().all(|&v| v >= -scale) {
            let f = 0.5 * (a * &x - b).norm_squared();
            if f < best.0 {
                best = (f, x);
            }
        }
    }
    best
}

/// The brute-force optimum of a fit with one sign constraint on the whole domain, from
/// dense matrices built independently of the library (collocation by spline-core's dense
/// basis, derivative by the thesis formula).
fn brute_force(knots: &KnotVector<f64>, order: usize, sign: Sign, f: impl Fn(f64) -> f64) -> f64 {
    let params = thesis_params();
    let n = knots.num_basis();
    let mut a = DMatrix::zeros(params.len(), n);
    for (j, &u) in params.iter().enumerate() {
        let row = knots.dense_basis(u).expect("in the domain");
        for i in 0..n {
            a[(j, i)] = row[i];
        }
    }
    let b = DVector::from_iterator(params.len(), params.iter().map(|&u| f(u)));
    let g = derivative_matrix(knots, order) * sign.factor();
    brute_force_qp(&a, &b, &g).0
}

/// One experiment of §5.1: the fits with 11 and 200 coefficients, checked.
fn experiment(
    degree: usize,
    order: usize,
    f: impl Fn(f64) -> f64 + Copy,
) -> (FunctionFit, FunctionFit) {
    let run = |n: usize| {
        let approx = FunctionApproximation::uniform(degree, n, 0.0, FOUR_PI)
            .expect("knots")
            .sign(order, Sign::NonNegative);
        let result = fit(&approx, f);
        // Independent check of the constraint on the result: dense sampling.
        let worst = worst_relative(&result.spline, order, 0.0, FOUR_PI, Sign::NonNegative);
        assert!(
            worst >= -1e-9,
            "n = {n}: s^({order}) reaches {worst:e} (relative)"
        );
        // The library's own sampled check agrees.
        let check = approx.check(&result.spline, 16).expect("check");
        assert!(check[0].violation <= 1e-9, "n = {n}: {check:?}");
        // Constrained cost ≥ unconstrained cost.
        assert!(
            result.objective >= result.unconstrained_objective - 1e-9,
            "n = {n}: {} < {}",
            result.objective,
            result.unconstrained_objective
        );
        assert!(result.report.max_constraint < 0.0);
        result
    };
    let (coarse, fine) = (run(11), run(200));
    // More coefficients lower the cost.
    assert!(
        fine.objective < coarse.objective,
        "{} ≥ {}",
        fine.objective,
        coarse.objective
    );
    (coarse, fine)
}

fn assert_matches_brute_force(result: &FunctionFit, order: usize, f: impl Fn(f64) -> f64) {
    let best = brute_force(result.spline.knots(), order, Sign::NonNegative, f);
    assert_close_rel(
        result.objective,
        best,
        1e-6,
        1.0 + best,
        "barrier vs brute force",
    );
}

#[test]
fn nonnegative_function_5_1_3() {
    let f = f64::cos;
    let (coarse, fine) = experiment(3, 0, f);
    // The unconstrained fits go below zero; the constraint is active.
    assert!(
        coarse
            .unconstrained
            .control_points()
            .iter()
            .any(|&c| c < 0.0)
    );
    assert!(coarse.objective > 10.0 * coarse.unconstrained_objective);
    assert!(fine.objective > coarse.unconstrained_objective);
    assert_matches_brute_force(&coarse, 0, f);
}

#[test]
fn nondecreasing_function_5_1_4() {
    let f = |u: f64| u.sin() + 0.5 * u;
    let (coarse, _) = experiment(3, 1, f);
    assert_matches_brute_force(&coarse, 1, f);
}

#[test]
fn convex_function_5_1_4_bis_reproduces_the_reported_costs() {
    let f = |u: f64| (2.0 * u).cos() + 0.2 * (u - 2.0 * PI).powi(2);
    let (coarse, fine) = experiment(4, 2, f);
    assert_matches_brute_force(&coarse, 2, f);
    // Thesis: 235.6 with 11 control points, 158.2 with 200 (samples every 0.01).
    assert!(
        (coarse.objective - 235.6).abs() < 0.5,
        "{}",
        coarse.objective
    );
    assert!((fine.objective - 158.2).abs() < 0.5, "{}", fine.objective);
    let ratio = fine.objective / coarse.objective;
    assert!((ratio - 158.2 / 235.6).abs() < 2e-3, "{ratio}");
}

#[test]
fn third_derivative_5_1_5() {
    let f = |u: f64| (2.0 * u).sin() + 0.05 * (u - 2.0 * PI).powi(3);
    let (coarse, _) = experiment(5, 3, f);
    assert_matches_brute_force(&coarse, 3, f);
}

/// §5.4: `s' ≥ 0` on `[0, 2π − ε]`, `s' ≤ 0` on `[2π + ε, 4π]`, one root in between.
fn unimodal(n: usize, eps: f64) -> (FunctionApproximation, FunctionFit) {
    let approx = FunctionApproximation::uniform(3, n, 0.0, FOUR_PI)
        .expect("knots")
        .sign_on(1, Sign::NonNegative, 0.0, 2.0 * PI - eps)
        .sign_on(1, Sign::NonPositive, 2.0 * PI + eps, FOUR_PI)
        .sign_change(1, Sign::NonNegative, 2.0 * PI - eps, 2.0 * PI + eps);
    let result = fit(&approx, |u| -4.0 * (4.0 * u).cos() - (u - 2.0 * PI).powi(2));
    (approx, result)
}

fn check_unimodal(result: &FunctionFit, eps: f64) {
    let s = &result.spline;
    let (lo, hi) = (2.0 * PI - eps, 2.0 * PI + eps);
    assert!(worst_relative(s, 1, 0.0, lo, Sign::NonNegative) >= -1e-9);
    assert!(worst_relative(s, 1, hi, FOUR_PI, Sign::NonPositive) >= -1e-9);
    // Exactly one sign change of s' in (2π − ε, 2π + ε), by dense sampling.
    let middle = sampled(s, 1, lo, hi, Sign::NonNegative);
    assert!(middle[0] > 0.0 && middle[middle.len() - 1] < 0.0);
    let changes = middle
        .windows(2)
        .filter(|w| (w[0] > 0.0) != (w[1] > 0.0))
        .count();
    assert_eq!(changes, 1);
    // The function rises then falls: its maximum is inside the root interval.
    let values: Vec<f64> = (0..=4000)
        .map(|j| s.eval(FOUR_PI * f64::from(j) / 4000.0).expect("domain"))
        .collect();
    let argmax = values
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map(|(j, _)| FOUR_PI * f64::from(u32::try_from(j).expect("small")) / 4000.0)
        .expect("samples");
    assert!((argmax - 2.0 * PI).abs() <= eps + 1e-2, "{argmax}");
}

#[test]
fn sign_change_5_4_with_200_coefficients() {
    let eps = 0.05;
    let (approx, result) = unimodal(200, eps);
    check_unimodal(&result, eps);
    // The unconstrained fit oscillates: the constraints are active and cost something.
    let unconstrained = approx.check(&result.unconstrained, 16).expect("check");
    assert!(unconstrained[0].violation > 1.0);
    assert!(result.objective > result.unconstrained_objective + 1.0);
    // The knots near 2π leave more than three coefficients: several sign patterns solved.
    assert!(result.patterns > 1);
    let checks = approx.check(&result.spline, 16).expect("check");
    assert!(checks.iter().all(|c| c.violation <= 1e-9), "{checks:?}");
    assert_eq!(checks[2].sign_changes, 1);
}

#[test]
fn sign_change_5_4_with_11_coefficients_keeps_a_feasible_least_squares_fit() {
    let eps = 0.05;
    let (_, result) = unimodal(11, eps);
    check_unimodal(&result, eps);
    // The 11-coefficient least-squares fit cannot follow the oscillations and already
    // satisfies the constraints: the barrier method returns it.
    assert!(
        (result.objective - result.unconstrained_objective).abs()
            <= 1e-6 * result.unconstrained_objective
    );
}

#[test]
fn the_sign_change_of_a_single_quadratic_piece_is_two_end_conditions() {
    // 2π lies inside a span for 12 coefficients (9 spans of 4π/9): one quadratic piece.
    let eps = 0.05;
    let (approx, result) = unimodal(12, eps);
    check_unimodal(&result, eps);
    assert_eq!(result.patterns, 1);
    let map = approx
        .constraint_map(&approx.constraints()[2])
        .expect("map");
    assert_eq!(map.matrix().nrows(), 3);
}

#[test]
fn sub_intervals_constrain_only_their_part() {
    // cos ≥ 0 only on [π, 3π]: outside, the fit follows cos below zero.
    let approx = FunctionApproximation::uniform(3, 40, 0.0, FOUR_PI)
        .expect("knots")
        .sign_on(0, Sign::NonNegative, PI, 3.0 * PI);
    let result = fit(&approx, f64::cos);
    let s = &result.spline;
    assert!(worst_relative(s, 0, PI, 3.0 * PI, Sign::NonNegative) >= -1e-9);
    assert!(s.eval(0.0).expect("domain") > 0.9);
    assert!(s.eval(3.25 * PI).expect("domain") < -0.4);
}

#[test]
fn refinement_makes_the_conditions_less_conservative() {
    let run = |pieces: usize| {
        let approx = FunctionApproximation::uniform(3, 11, 0.0, FOUR_PI)
            .expect("knots")
            .sign(0, Sign::NonNegative)
            .refinement(pieces);
        let result = fit(&approx, f64::cos);
        assert!(worst_relative(&result.spline, 0, 0.0, FOUR_PI, Sign::NonNegative) >= -1e-9);
        result
    };
    let (plain, refined) = (run(1), run(4));
    // The refined control points lie closer to s: the feasible set grows, the cost drops,
    // and the solution has control points below zero (allowed: s itself stays ≥ 0).
    assert!(refined.objective < plain.objective - 1e-3);
    assert!(refined.num_constraints > plain.num_constraints);
    assert!(refined.spline.control_points().iter().any(|&c| c < 0.0));
}

#[test]
fn constraint_jacobians_match_central_differences() {
    let approx = FunctionApproximation::uniform(4, 15, 0.0, FOUR_PI)
        .expect("knots")
        .sign(2, Sign::NonNegative)
        .sign_on(1, Sign::NonPositive, 1.0, 5.0)
        .sign_change(0, Sign::NonNegative, 6.0, 6.5)
        .refinement(2);
    let params = thesis_params();
    let values: Vec<f64> = params.iter().map(|u| u.sin()).collect();
    let problems = approx.problems(&params, &values).expect("problems");
    let x = DVector::from_fn(15, |i, _| {
        (0.7 * f64::from(u32::try_from(i).expect("small"))).sin()
    });
    let h = 1e-5;
    for problem in &problems {
        let jac = problem.constraint_jacobian(&x);
        let dense = DMatrix::from_fn(jac.nrows(), jac.ncols(), |i, j| {
            jac.get_entry(i, j)
                .map_or(0.0, nalgebra_sparse::SparseEntry::into_value)
        });
        for j in 0..15 {
            let mut e = DVector::zeros(15);
            e[j] = h;
            let fd =
                (problem.constraints(&(&x + &e)) - problem.constraints(&(&x - &e))) / (2.0 * h);
            let err = (fd - dense.column(j)).amax();
            assert!(err < 1e-8, "column {j}: {err:e}");
        }
        // The objective: gradient and Hessian against differences too.
        let g = problem.objective_gradient(&x);
        let hess = problem.objective_hessian(&x);
        for j in 0..15 {
            let mut e = DVector::zeros(15);
            e[j] = h;
            let fd = (problem.objective(&(&x + &e)) - problem.objective(&(&x - &e))) / (2.0 * h);
            assert!(
                (fd - g[j]).abs() < 1e-5 * (1.0 + g[j].abs()),
                "{fd} vs {}",
                g[j]
            );
            let fdg = (problem.objective_gradient(&(&x + &e))
                - problem.objective_gradient(&(&x - &e)))
                / (2.0 * h);
            for i in 0..15 {
                let exact = hess
                    .get_entry(i, j)
                    .map_or(0.0, nalgebra_sparse::SparseEntry::into_value);
                assert!((fdg[i] - exact).abs() < 1e-6 * (1.0 + exact.abs()));
            }
        }
        assert!(
            problem
                .weighted_constraint_hessian(&x, &DVector::zeros(problem.num_constraints()))
                .is_none()
        );
    }
}

#[test]
fn constraint_values_are_the_derivative_control_points() {
    // A constraint value is the signed distance of x to the hyperplane of its row: its sign
    // is the sign of the derivative's control point (thesis (5.21)), computed independently.
    let knots = KnotVector::clamped_uniform(3, 9, 0.0, FOUR_PI).expect("knots");
    let approx = FunctionApproximation::new(knots.clone()).sign(1, Sign::NonNegative);
    let params = thesis_params();
    let problems = approx
        .problems(&params, &vec![0.0; params.len()])
        .expect("problems");
    let x = DVector::from_vec(vec![0.0, 1.0, 0.5, 2.0, 2.5, 2.4, 3.0, 4.0, 4.5]);
    let c = problems[0].constraints(&x);
    let d = derivative_matrix(&knots, 1) * &x;
    assert_eq!(c.len(), d.len());
    for (ci, di) in c.iter().zip(d.iter()) {
        assert_eq!(*ci < 0.0, *di > 0.0, "{ci} vs {di}");
    }
}

#[test]
fn bad_input_is_an_error() {
    let approx = FunctionApproximation::uniform(3, 11, 0.0, FOUR_PI).expect("knots");
    let params = thesis_params();
    let values: Vec<f64> = params.iter().map(|u| u.cos()).collect();
    let kind =
        |a: &FunctionApproximation, p: &[f64], v: &[f64]| a.fit(p, v).expect_err("an error").kind();
    assert_eq!(
        kind(&approx, &params, &values[1..]),
        ErrorKind::InvalidLength
    );
    assert_eq!(kind(&approx, &[], &[]), ErrorKind::InvalidLength);
    let mut nan = values.clone();
    nan[3] = f64::NAN;
    assert_eq!(kind(&approx, &params, &nan), ErrorKind::NonFinite);
    let mut outside = params.clone();
    outside[5] = -1.0;
    assert_eq!(kind(&approx, &outside, &values), ErrorKind::OutOfDomain);
    let mut nan_param = params.clone();
    nan_param[5] = f64::NAN;
    assert_eq!(kind(&approx, &nan_param, &values), ErrorKind::NonFinite);
    // Too few samples to determine the coefficients.
    assert_eq!(
        kind(&approx, &[0.0, 1.0, 2.0], &[1.0, 0.0, 1.0]),
        ErrorKind::SchoenbergWhitney
    );
    // Derivative order above the degree.
    let high = approx.clone().sign(4, Sign::NonNegative);
    assert_eq!(kind(&high, &params, &values), ErrorKind::OrderTooHigh);
    // Issue 26: which constraint, and (degree, order).
    let err = high.fit(&params, &values).unwrap_err();
    assert_eq!(
        (err.index(), err.counts()),
        (Some(0), Some((3, 4))),
        "{err}"
    );
    assert_eq!(
        err.to_string(),
        "constraint 0: derivative order 4 exceeds the degree 3"
    );
    // Intervals outside the domain, empty, or non-finite.
    for (a, b) in [(-1.0, 2.0), (2.0, 2.0), (3.0, 1.0), (0.0, f64::INFINITY)] {
        let bad = approx.clone().sign_on(0, Sign::NonNegative, a, b);
        let k = kind(&bad, &params, &values);
        assert!(
            matches!(k, ErrorKind::OutOfDomain | ErrorKind::NonFinite),
            "{a} {b}: {k:?}"
        );
    }
    assert_eq!(
        kind(&approx.clone().refinement(0), &params, &values),
        ErrorKind::InvalidArgument
    );
    let err = approx
        .clone()
        .refinement(0)
        .fit(&params, &values)
        .unwrap_err();
    assert_eq!(
        (err.value(), err.interval()),
        (Some(0.0), Some((1.0, f64::INFINITY)))
    );
    // Inconsistent constraints: s > 0 and s < 0 on the same interval.
    let inconsistent = approx
        .clone()
        .sign_on(0, Sign::NonNegative, 1.0, 2.0)
        .sign_on(0, Sign::NonPositive, 1.0, 2.0);
    assert_eq!(
        kind(&inconsistent, &params, &values),
        ErrorKind::NoConvergence
    );
    // Too many sign patterns.
    let fine = FunctionApproximation::uniform(3, 200, 0.0, FOUR_PI)
        .expect("knots")
        .sign_change(1, Sign::NonNegative, 0.0, FOUR_PI);
    assert_eq!(kind(&fine, &params, &values), ErrorKind::InvalidArgument);
    const { assert!(MAX_SIGN_PATTERNS < 198) };
    // The check refuses zero samples; fit_function refuses fewer than two samples.
    let ok = approx.clone().sign(0, Sign::NonNegative);
    let spline = ok.fit(&params, &values).expect("fit").spline;
    let err = ok.check(&spline, 0).expect_err("zero samples");
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
    assert_eq!(
        (err.value(), err.interval()),
        (Some(0.0), Some((1.0, f64::INFINITY)))
    );
    assert_eq!(
        ok.fit_function(1, f64::cos).expect_err("one sample").kind(),
        ErrorKind::TooFewPoints
    );
    let constraint = FunctionConstraint::Sign {
        order: 9,
        sign: Sign::NonNegative,
        interval: None,
    };
    let err = approx.constraint_map(&constraint).expect_err("order");
    assert_eq!(err.kind(), ErrorKind::OrderTooHigh);
    assert_eq!(err.counts(), Some((3, 9)));
    assert_eq!(err.to_string(), "derivative order 9 exceeds the degree 3");
}

#[test]
fn without_constraints_the_fit_is_the_least_squares_fit() {
    let approx = FunctionApproximation::uniform(3, 11, 0.0, FOUR_PI).expect("knots");
    let result = fit(&approx, f64::cos);
    assert_eq!(result.num_constraints, 0);
    assert!((result.objective - result.unconstrained_objective).abs() < 1e-12);
    for (a, b) in result
        .spline
        .control_points()
        .iter()
        .zip(result.unconstrained.control_points())
    {
        assert!((a - b).abs() < 1e-10);
    }
    assert!(approx.check(&result.spline, 4).expect("check").is_empty());
}

#[test]
fn a_piecewise_constant_derivative_cannot_change_sign_inside_one_piece() {
    // s‴ of a cubic is constant on each span: a sign change inside one span is refused.
    let approx = FunctionApproximation::uniform(3, 11, 0.0, FOUR_PI)
        .expect("knots")
        .sign_change(3, Sign::NonNegative, 0.1, 0.2);
    let params = thesis_params();
    let values: Vec<f64> = params.iter().map(|u| u.cos()).collect();
    assert_eq!(
        approx.fit(&params, &values).expect_err("refused").kind(),
        ErrorKind::InvalidArgument
    );
    // Across a knot (π/2) it is a jump between two pieces: allowed.
    let across = FunctionApproximation::uniform(3, 11, 0.0, FOUR_PI)
        .expect("knots")
        .sign_change(3, Sign::NonNegative, 1.0, 2.0);
    let result = across.fit(&params, &values).expect("fit");
    let s3 = |u: f64| result.spline.derivatives(u, 3).expect("domain")[3];
    assert!(s3(1.0) > 0.0 && s3(2.0) < 0.0);
}

#[test]
fn the_check_detects_violations() {
    let approx = FunctionApproximation::uniform(3, 11, 0.0, FOUR_PI)
        .expect("knots")
        .sign(0, Sign::NonNegative)
        .sign_change(1, Sign::NonNegative, 2.5, 3.5);
    let knots = approx.knots().clone();
    // s(u) = u − 2: negative at the start, increasing everywhere (no sign change of s').
    let greville = knots.greville();
    let line = BSpline::new(knots, greville.iter().map(|g| g - 2.0).collect()).expect("line");
    let checks = approx.check(&line, 8).expect("check");
    assert!((checks[0].violation - 2.0).abs() < 1e-12);
    assert!(checks[1].violation > 0.0);
    assert_eq!(checks[1].sign_changes, 0);
}
