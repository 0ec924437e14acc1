//! Constrained approximation of functions of two variables: the experiments of thesis
//! §5.5–5.6, checked independently — dense sampling of the partial derivatives with
//! spline-geom's surface evaluation, central differences of the constraint gradients and
//! Hessians, the symmetry convex ↔ concave — and the error contract.

use nalgebra::DVector;
use nalgebra_sparse::CsrMatrix;
use spline_core::ErrorKind;
use spline_geom::Surface;
use spline_shape::{BarrierProblem, ConstrainedSurfaceFit, Sign, SurfaceApproximation};
use std::f64::consts::PI;

const FOUR_PI: f64 = 4.0 * PI;
const DOMAIN: (f64, f64) = (0.0, FOUR_PI);

fn uniform(n: usize) -> SurfaceApproximation {
    SurfaceApproximation::uniform((3, 3), (n, n), DOMAIN, DOMAIN).expect("knots")
}

/// `f(u_k, v_l)` on `count × count` grid points of `[0, 4π]²`.
fn grid(count: usize) -> Vec<f64> {
    (0..count)
        .map(|k| FOUR_PI * f64::from(u32::try_from(k).expect("small")) / (count - 1) as f64)
        .collect()
}

/// The partial derivatives `[k][l]`, `k, l ≤ 2`, on a `201 × 201` grid, by spline-geom.
fn sample(surface: &Surface<f64, f64>) -> Vec<Vec<Vec<f64>>> {
    let g = grid(201);
    g.iter()
        .flat_map(|&u| g.iter().map(move |&v| (u, v)))
        .map(|(u, v)| surface.derivatives(u, v, 2).expect("in the domain"))
        .collect()
}

fn check_costs(fit: &ConstrainedSurfaceFit) {
    assert!(fit.objective >= fit.unconstrained_objective - 1e-9);
    assert!(fit.report.max_constraint < 0.0);
}

#[test]
fn nonnegative_surface_5_5_2() {
    let f = |u: f64, v: f64| u.sin() * v.sin();
    let approx = uniform(20).sign(0, 0, Sign::NonNegative);
    let fit = approx.fit_function((50, 50), f).expect("fit");
    check_costs(&fit);
    let samples = sample(&fit.surface);
    let scale = samples.iter().fold(0.0f64, |m, d| m.max(d[0][0].abs()));
    let worst = samples.iter().fold(f64::INFINITY, |m, d| m.min(d[0][0]));
    assert!(worst >= -1e-12 * scale, "{worst}");
    // The unconstrained fit is negative on half the domain; the constrained one clips it.
    assert!(sample(&fit.unconstrained).iter().any(|d| d[0][0] < -0.9));
    assert!(fit.objective > 100.0 * fit.unconstrained_objective.max(1e-6));
    // Where γ ≥ 0 the fit stays close to it.
    let s = fit.surface.eval(PI / 2.0, PI / 2.0).expect("domain");
    assert!((s - 1.0).abs() < 0.05, "{s}");
    // Fewer coefficients cost more.
    let coarse = uniform(10)
        .sign(0, 0, Sign::NonNegative)
        .fit_function((50, 50), f)
        .expect("coarse fit");
    assert!(coarse.objective > fit.objective);
}

#[test]
fn nondecreasing_in_v_5_5_3() {
    let approx = uniform(20).sign(0, 1, Sign::NonNegative);
    let fit = approx
        .fit_function((50, 50), |u, v| u.cos() * v.sin() + 0.25 * v)
        .expect("fit");
    check_costs(&fit);
    let samples = sample(&fit.surface);
    let scale = samples.iter().fold(0.0f64, |m, d| m.max(d[0][1].abs()));
    let worst = samples.iter().fold(f64::INFINITY, |m, d| m.min(d[0][1]));
    assert!(worst >= -1e-12 * scale, "{worst}");
    assert!(sample(&fit.unconstrained).iter().any(|d| d[0][1] < -0.5));
    let checks = approx.check(&fit.surface, 8).expect("check");
    assert!(checks[0].violation <= 1e-12 * scale);
    assert!(approx.check(&fit.unconstrained, 8).expect("check")[0].violation > 0.5);
}

fn convex_target(u: f64, v: f64) -> f64 {
    u.sin() * v.sin() + 0.05 * ((u - 2.0 * PI).powi(2) + (v - 2.0 * PI).powi(2))
}

/// The smallest of `s_uu`, `s_vv` and `s_uu s_vv − s_uv²` over dense samples, relative to
/// the largest `s_uu` (squared for the determinant), by spline-geom.
fn convexity_margin(surface: &Surface<f64, f64>) -> (f64, f64, f64) {
    let samples = sample(surface);
    let scale = samples.iter().fold(0.0f64, |m, d| m.max(d[2][0].abs()));
    let min =
        |f: &dyn Fn(&Vec<Vec<f64>>) -> f64| samples.iter().map(f).fold(f64::INFINITY, f64::min);
    (
        min(&|d| d[2][0]) / scale,
        min(&|d| d[0][2]) / scale,
        min(&|d| d[2][0] * d[0][2] - d[1][1] * d[1][1]) / (scale * scale),
    )
}

#[test]
fn convex_surface_5_6() {
    let approx = uniform(10).convex();
    let fit = approx.fit_function((40, 40), convex_target).expect("fit");
    check_costs(&fit);
    let (suu, svv, det) = convexity_margin(&fit.surface);
    assert!(
        suu >= -1e-9 && svv >= -1e-9 && det >= -1e-9,
        "{suu} {svv} {det}"
    );
    let (_, _, det_ls) = convexity_margin(&fit.unconstrained);
    assert!(
        det_ls < -0.1,
        "the unconstrained fit is not convex: {det_ls}"
    );
    assert!(approx.check(&fit.surface, 8).expect("check")[0].violation <= 1e-9);
    assert_eq!(fit.num_constraints.0, 8 * 10);
    assert!(fit.num_constraints.1 > 0);
    // Fewer coefficients cost more.
    let coarse = uniform(6)
        .convex()
        .fit_function((40, 40), convex_target)
        .expect("coarse fit");
    assert!(coarse.objective > fit.objective);
}

#[test]
fn concave_fit_of_the_opposite_is_the_opposite_of_the_convex_fit() {
    let convex = uniform(6)
        .convex()
        .fit_function((30, 30), convex_target)
        .expect("convex fit");
    let concave = uniform(6)
        .concave()
        .fit_function((30, 30), |u, v| -convex_target(u, v))
        .expect("concave fit");
    assert!(
        (convex.objective - concave.objective).abs() <= 1e-6 * convex.objective,
        "{} vs {}",
        convex.objective,
        concave.objective
    );
    for (a, b) in convex
        .surface
        .control_points()
        .iter()
        .zip(concave.surface.control_points())
    {
        assert!((a + b).abs() < 1e-3 * (1.0 + a.abs()), "{a} vs {b}");
    }
}

#[test]
fn determinant_control_points_form_the_hessian_determinant() {
    // ½ xᵀ H_k x are the control points of a spline equal to s_uu s_vv − s_uv², which
    // spline-geom's surface derivatives give independently.
    let approx = uniform(7);
    let (forms, ku, kv) = approx.determinant_map(None).expect("map");
    let x: Vec<f64> = (0..49)
        .map(|i| (0.37 * f64::from(i)).sin() + 0.01 * f64::from(i))
        .collect();
    let surface = Surface::new(
        approx.knots().0.clone(),
        approx.knots().1.clone(),
        x.clone(),
    )
    .expect("surface");
    let coefficients: Vec<f64> = forms
        .apply(&x, &x)
        .expect("apply")
        .iter()
        .map(|v| 0.5 * v)
        .collect();
    let det = Surface::new(ku, kv, coefficients).expect("determinant spline");
    for &u in &grid(23) {
        for &v in &grid(19) {
            let d = surface.derivatives(u, v, 2).expect("domain");
            let expected = d[2][0] * d[0][2] - d[1][1] * d[1][1];
            let got = det.eval(u, v).expect("domain");
            assert!(
                (got - expected).abs() <= 1e-10 * (1.0 + expected.abs()),
                "({u}, {v}): {got} vs {expected}"
            );
        }
    }
}

fn dense(m: &CsrMatrix<f64>) -> nalgebra::DMatrix<f64> {
    nalgebra::DMatrix::from_fn(m.nrows(), m.ncols(), |i, j| {
        m.get_entry(i, j)
            .map_or(0.0, nalgebra_sparse::SparseEntry::into_value)
    })
}

#[test]
fn convexity_gradients_and_hessians_match_central_differences() {
    let approx = uniform(5).convex().refinement(2);
    let us = grid(12);
    let values: Vec<f64> = us
        .iter()
        .flat_map(|&u| us.iter().map(move |&v| convex_target(u, v)))
        .collect();
    let problem = approx.problem(&us, &us, &values).expect("problem");
    let n = problem.dimension();
    assert_eq!(n, 25);
    let m = problem.num_constraints();
    assert_eq!(
        m,
        problem.num_linear_constraints() + problem.num_quadratic_constraints()
    );
    let x = DVector::from_fn(n, |i, _| {
        (0.9 * f64::from(u32::try_from(i).expect("small"))).cos()
    });
    let jac = dense(&problem.constraint_jacobian(&x));
    let h = 1e-5;
    let unit = |j: usize| {
        let mut e = DVector::zeros(n);
        e[j] = h;
        e
    };
    for j in 0..n {
        let e = unit(j);
        let fd = (problem.constraints(&(&x + &e)) - problem.constraints(&(&x - &e))) / (2.0 * h);
        let err = (&fd - jac.column(j)).amax();
        assert!(err < 1e-7 * (1.0 + fd.amax()), "column {j}: {err:e}");
    }
    // Σ w_k ∇²f_k against differences of Σ w_k ∇f_k.
    let w = DVector::from_fn(m, |k, _| {
        1.0 + 0.1 * f64::from(u32::try_from(k % 7).expect("small"))
    });
    let hess = dense(
        &problem
            .weighted_constraint_hessian(&x, &w)
            .expect("quadratic constraints"),
    );
    assert!((&hess - hess.transpose()).amax() < 1e-12 * (1.0 + hess.amax()));
    for j in 0..n {
        let e = unit(j);
        let gp = dense(&problem.constraint_jacobian(&(&x + &e))).transpose() * &w;
        let gm = dense(&problem.constraint_jacobian(&(&x - &e))).transpose() * &w;
        let fd = (gp - gm) / (2.0 * h);
        let err = (&fd - hess.column(j)).amax();
        assert!(err < 1e-6 * (1.0 + fd.amax()), "column {j}: {err:e}");
    }
}

#[test]
fn sign_constraints_on_a_region_and_refinement() {
    let f = |u: f64, v: f64| u.sin() * v.sin();
    let region = ((0.0, 2.0 * PI), (0.0, 2.0 * PI));
    let approx = SurfaceApproximation::uniform((3, 3), (8, 8), DOMAIN, DOMAIN)
        .expect("knots")
        .sign_on(0, 0, Sign::NonNegative, region)
        .refinement(2);
    let fit = approx.fit_function((30, 30), f).expect("fit");
    let g = grid(101);
    let mut worst_inside = f64::INFINITY;
    let mut lowest_outside = f64::INFINITY;
    for &u in &g {
        for &v in &g {
            let s = fit.surface.eval(u, v).expect("domain");
            if u <= 2.0 * PI && v <= 2.0 * PI {
                worst_inside = worst_inside.min(s);
            } else {
                lowest_outside = lowest_outside.min(s);
            }
        }
    }
    assert!(worst_inside >= -1e-12, "{worst_inside}");
    assert!(lowest_outside < -0.5, "{lowest_outside}");
    // Refinement: a less conservative condition costs no more than the plain one.
    let plain = SurfaceApproximation::uniform((3, 3), (8, 8), DOMAIN, DOMAIN)
        .expect("knots")
        .sign_on(0, 0, Sign::NonNegative, region)
        .fit_function((30, 30), f)
        .expect("plain fit");
    assert!(fit.objective <= plain.objective + 1e-9);
}

#[test]
fn bad_input_is_an_error() {
    let approx = uniform(6).sign(0, 0, Sign::NonNegative);
    let us = grid(20);
    let values = vec![0.5; 400];
    let kind = |a: &SurfaceApproximation, u: &[f64], v: &[f64], z: &[f64]| {
        a.fit_grid(u, v, z).expect_err("an error").kind()
    };
    assert_eq!(
        kind(&approx, &us, &us, &values[1..]),
        ErrorKind::InvalidLength
    );
    assert_eq!(kind(&approx, &[], &us, &[]), ErrorKind::InvalidLength);
    let mut nan = values.clone();
    nan[7] = f64::NAN;
    assert_eq!(kind(&approx, &us, &us, &nan), ErrorKind::NonFinite);
    let mut outside = us.clone();
    outside[3] = 20.0;
    assert_eq!(
        kind(&approx, &outside, &us, &values),
        ErrorKind::OutOfDomain
    );
    assert_eq!(
        kind(&approx, &us[..3], &us, &values[..60]),
        ErrorKind::SchoenbergWhitney
    );
    let high = uniform(6).sign(4, 0, Sign::NonNegative);
    assert_eq!(kind(&high, &us, &us, &values), ErrorKind::OrderTooHigh);
    let linear = SurfaceApproximation::uniform((1, 3), (6, 6), DOMAIN, DOMAIN)
        .expect("knots")
        .convex();
    assert_eq!(kind(&linear, &us, &us, &values), ErrorKind::OrderTooHigh);
    // Issue 26: the constraint, and (degree, order) of the first direction too high.
    let err = linear.fit_grid(&us, &us, &values).unwrap_err();
    assert_eq!(
        (err.index(), err.counts()),
        (Some(0), Some((1, 2))),
        "{err}"
    );
    assert!(
        err.to_string().contains("exceed the degrees (1, 3)"),
        "{err}"
    );
    let region = uniform(6).sign_on(0, 0, Sign::NonNegative, ((1.0, 0.5), (0.0, 1.0)));
    assert_eq!(kind(&region, &us, &us, &values), ErrorKind::OutOfDomain);
    let refinement = uniform(6).refinement(0);
    assert_eq!(
        kind(&refinement, &us, &us, &values),
        ErrorKind::InvalidArgument
    );
    let inconsistent = uniform(6)
        .sign(0, 0, Sign::NonNegative)
        .sign(0, 0, Sign::NonPositive);
    assert_eq!(
        kind(&inconsistent, &us, &us, &values),
        ErrorKind::NoConvergence
    );
    assert_eq!(
        approx
            .fit_function((1, 5), |u, v| u + v)
            .expect_err("too few")
            .kind(),
        ErrorKind::TooFewPoints
    );
}
