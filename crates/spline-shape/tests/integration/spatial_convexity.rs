//! Convexity of a parametric patch whose control points move in all three coordinates
//! (`SpatialConvexity`): the constraints' derivatives against central differences, the
//! fitted patch's Gaussian curvature sampled on the patch itself, and bad input.

use nalgebra::{DMatrix, DVector, Vector3};
use spline_core::{ErrorKind, KnotVector};
use spline_geom::{NurbsSurface, Surface};
use spline_shape::{BarrierProblem, Sign, SpatialConvexity};

/// A cap of the ellipsoid x²/4 + y²/4 + z² = 1, rippled along z, over a sheared and bent
/// parametrisation of the square (so the net is not a grid of x and y).
fn rippled_cap(u: f64, v: f64) -> Vector3<f64> {
    let x = 1.4 * u - 0.7 + 0.15 * v * v;
    let y = 1.4 * v - 0.7 + 0.1 * u;
    let z = (1.0 - (x * x + y * y) / 4.0).sqrt() + 0.02 * (8.0 * x).sin() * (5.0 * y).cos();
    Vector3::new(x, y, z)
}

fn samples(count: usize) -> Vec<f64> {
    (0..count).map(|k| k as f64 / (count - 1) as f64).collect()
}

fn grid(count: usize) -> (Vec<f64>, Vec<f64>, Vec<Vector3<f64>>) {
    let (us, vs) = (samples(count), samples(count));
    let points = us
        .iter()
        .flat_map(|&u| vs.iter().map(move |&v| rippled_cap(u, v)))
        .collect();
    (us, vs, points)
}

/// The smallest Gaussian curvature of a patch at `count²` parameters, from the surface's
/// own derivatives (not from the constraints).
fn min_gaussian(s: &Surface<f64, Vector3<f64>>, count: usize) -> f64 {
    let nurbs = NurbsSurface::from_surface(s);
    let mut least = f64::INFINITY;
    for &u in &samples(count) {
        for &v in &samples(count) {
            let k = nurbs.local_properties(u, v).unwrap().gaussian_curvature;
            least = least.min(k);
        }
    }
    least
}

fn bicubic() -> SpatialConvexity {
    let k = KnotVector::clamped(3, 0.0, 1.0, &[]).unwrap();
    SpatialConvexity::new(k.clone(), k, Sign::NonPositive).unwrap()
}

#[test]
fn constraint_derivatives_match_central_differences() {
    let (us, vs, points) = grid(9);
    let (problem, x_ls) = bicubic().problem(&us, &vs, &points).unwrap();
    let n = problem.dimension();
    assert_eq!(n, 48);
    // Away from the least-squares point, so that no term is special.
    let x = DVector::from_fn(n, |i, _| x_ls[i] + 0.01 * ((i * 7 % 11) as f64 - 5.0) / 5.0);
    let m = problem.num_constraints();
    let weights = DVector::from_fn(m, |k, _| 1.0 + (k % 5) as f64);
    let jac = DMatrix::from(&problem.constraint_jacobian(&x));
    let hessian = DMatrix::from(&problem.weighted_constraint_hessian(&x, &weights).unwrap());
    let h = 1e-5;
    let (mut worst_jac, mut worst_hess) = (0.0f64, 0.0f64);
    let jac_scale = jac.amax();
    let hess_scale = hessian.amax();
    for j in 0..n {
        let (mut plus, mut minus) = (x.clone(), x.clone());
        plus[j] += h;
        minus[j] -= h;
        let dc = (problem.constraints(&plus) - problem.constraints(&minus)) / (2.0 * h);
        for k in 0..m {
            worst_jac = worst_jac.max((dc[k] - jac[(k, j)]).abs());
        }
        let jp = DMatrix::from(&problem.constraint_jacobian(&plus));
        let jm = DMatrix::from(&problem.constraint_jacobian(&minus));
        let column = (jp.transpose() * &weights - jm.transpose() * &weights) / (2.0 * h);
        for i in 0..n {
            worst_hess = worst_hess.max((column[i] - hessian[(i, j)]).abs());
        }
    }
    assert!(jac_scale > 0.0 && hess_scale > 0.0);
    assert!(
        worst_jac <= 1e-6 * jac_scale,
        "Jacobian off by {worst_jac:e} (scale {jac_scale:e})"
    );
    assert!(
        worst_hess <= 1e-6 * hess_scale,
        "Hessian off by {worst_hess:e} (scale {hess_scale:e})"
    );
    // The Hessian is symmetric and couples the coordinates (unlike the heights-only
    // problem, whose constraints are quadratic forms of z alone).
    assert!((&hessian - hessian.transpose()).amax() <= 1e-9 * hess_scale);
    let coupling = hessian.view((0, 16), (16, 16)).amax();
    assert!(coupling > 1e-3 * hess_scale, "x–y coupling {coupling:e}");
}

#[test]
fn rippled_cap_becomes_convex_and_beats_the_heights_only_patch() {
    let (us, vs, points) = grid(13);
    let fit = bicubic().fit_grid(&us, &vs, &points).unwrap();
    let before = min_gaussian(&fit.unconstrained, 41);
    assert!(
        before < -0.02,
        "the ripples should make K negative somewhere: {before}"
    );
    let least = min_gaussian(&fit.surface, 61);
    assert!(
        least >= -1e-9,
        "K = {least:e} somewhere on the constrained patch"
    );
    let heights = fit
        .heights_only_objective
        .expect("the heights-only start was used");
    assert!(
        fit.objective <= heights * (1.0 + 1e-9),
        "{} > {heights}",
        fit.objective
    );
    assert!(fit.objective >= fit.unconstrained_objective);
    let deviation = us
        .iter()
        .flat_map(|&u| vs.iter().map(move |&v| (u, v)))
        .map(|(u, v)| (fit.surface.eval(u, v).unwrap() - rippled_cap(u, v)).norm())
        .fold(0.0f64, f64::max);
    assert!(deviation < 0.05, "deviation {deviation}");
    eprintln!(
        "objective: unconstrained {:.3e}, heights only {heights:.3e}, all coordinates {:.3e}; min K before {before:.2e}, after {least:.2e}; deviation {deviation:.3e}; {} Newton steps",
        fit.unconstrained_objective, fit.objective, fit.report.newton_iterations
    );
}

#[test]
fn bad_input_is_refused() {
    let linear = KnotVector::clamped(1, 0.0, 1.0, &[]).unwrap();
    let cubic = KnotVector::clamped(3, 0.0, 1.0, &[]).unwrap();
    let e = SpatialConvexity::new(linear, cubic.clone(), Sign::NonNegative).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(
        (e.value(), e.interval()),
        (Some(1.0), Some((2.0, f64::INFINITY)))
    );
    let big = KnotVector::clamped(3, 0.0, 1.0, &[0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7]).unwrap();
    let e = SpatialConvexity::new(big.clone(), big, Sign::NonNegative).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    let convex = SpatialConvexity::new(cubic.clone(), cubic, Sign::NonNegative).unwrap();
    let (us, vs, mut points) = grid(5);
    let e = convex.fit_grid(&us, &vs, &points[1..]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    points[3].y = f64::NAN;
    let e = convex.fit_grid(&us, &vs, &points).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    // One row of samples does not determine a bicubic.
    let (us, vs, points) = grid(5);
    let e = convex.fit_grid(&us, &vs[..1], &points[..5]).unwrap_err();
    assert!(
        matches!(
            e.kind(),
            ErrorKind::SchoenbergWhitney | ErrorKind::TooFewPoints | ErrorKind::SingularSystem
        ),
        "{e}"
    );
}

#[test]
fn numerators_agree_with_the_curvature_numerators_of_spline_algebra() {
    // Two patches each way (biquadratic and bicubic): the pipeline's coefficients are the
    // per-patch Bernstein coefficients that `curvature_numerators_with_jacobians` (the
    // product algebra on the surface itself) computes.
    for degree in [2, 3] {
        let k = KnotVector::clamped(degree, 0.0, 1.0, &[0.4]).unwrap();
        let convex = SpatialConvexity::new(k.clone(), k.clone(), Sign::NonPositive).unwrap();
        let (us, vs, points) = grid(9);
        let (problem, x) = convex.problem(&us, &vs, &points).unwrap();
        let (l, gaussian) = problem.numerators(&x);
        let patch = NurbsSurface::from_surface(&problem.patch(x.as_slice()).unwrap());
        let (reference, _) = spline_algebra::curvature_numerators_with_jacobians(&patch).unwrap();
        for (ours, theirs) in [
            (&l, reference.second[0].control_points()),
            (&gaussian, reference.gaussian.control_points()),
        ] {
            assert_eq!(ours.len(), theirs.len());
            let scale = theirs.iter().fold(0.0f64, |m, c| m.max(c.abs()));
            for (a, b) in ours.iter().zip(theirs) {
                assert!((a - b).abs() <= 1e-12 * scale, "{a} vs {b} (scale {scale})");
            }
        }
    }
}
