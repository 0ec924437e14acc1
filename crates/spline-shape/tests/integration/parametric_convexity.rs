//! Convexity of a parametric patch over a curved planar parametrisation: the Gaussian
//! curvature of the fitted patch, evaluated pointwise on the patch itself (not through the
//! constraints), is nowhere negative, where the unconstrained fit's is.

use nalgebra::Vector2;
use spline_core::KnotVector;
use spline_geom::Surface;
use spline_shape::{ParametricConvexity, Sign};

/// X = u + 0.3 v², Y = v + 0.2 u − 0.1 u² on [0, 1]² (bicubic, two spans each way, exact).
fn base() -> Surface<f64, Vector2<f64>> {
    let k = KnotVector::clamped(3, 0.0, 1.0, &[0.5]).unwrap();
    let g = k.greville();
    // Quadratics through Greville abscissae are not exact; interpolate the net instead by
    // the blossom: for degree 3 on these knots, u² has coefficients t_{i+1}t_{i+2} + … / 3.
    let knots = k.knots().to_vec();
    let square = |i: usize| {
        let (a, b, c) = (knots[i + 1], knots[i + 2], knots[i + 3]);
        (a * b + a * c + b * c) / 3.0
    };
    let n = g.len();
    let points = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .map(|(i, j)| Vector2::new(g[i] + 0.3 * square(j), g[j] + 0.2 * g[i] - 0.1 * square(i)))
        .collect();
    Surface::new(k.clone(), k, points).unwrap()
}

/// The smallest Gaussian curvature on a grid of `m × m` parameters.
fn smallest_k(s: &Surface<f64, nalgebra::Vector3<f64>>, m: usize) -> f64 {
    let mut smallest = f64::INFINITY;
    for a in 0..=m {
        for b in 0..=m {
            let (u, v) = (a as f64 / m as f64, b as f64 / m as f64);
            let k = s.local_properties(u, v).unwrap().gaussian_curvature;
            smallest = smallest.min(k);
        }
    }
    smallest
}

#[test]
fn a_rippled_bowl_becomes_convex() {
    let b = base();
    // The base is what it claims: X(u, v) = u + 0.3 v² exactly.
    let p = b.eval(0.3, 0.7).unwrap();
    assert!((p.x - (0.3 + 0.3 * 0.49)).abs() < 1e-12);
    assert!((p.y - (0.7 + 0.06 - 0.009)).abs() < 1e-12);
    let convex = ParametricConvexity::new(b, Sign::NonNegative).unwrap();
    let f = |x: f64, y: f64| 0.6 * (x * x + y * y) + 0.03 * (9.0 * x).sin();
    let fit = convex.fit_function((14, 14), f).unwrap();
    assert!(
        smallest_k(&fit.unconstrained, 60) < -0.01,
        "the ripples are not convex"
    );
    let after = smallest_k(&fit.surface, 60);
    assert!(after >= -1e-9, "K = {after}");
    assert!(fit.objective >= fit.unconstrained_objective);
    // Close to the data: every sample within 0.05.
    for a in 0..=14 {
        for c in 0..=14 {
            let (u, v) = (f64::from(a) / 14.0, f64::from(c) / 14.0);
            let p = fit.surface.eval(u, v).unwrap();
            assert!((p.z - f(p.x, p.y)).abs() < 0.05, "{u} {v}");
        }
    }
    assert!(fit.num_constraints.1 > 0);
}

#[test]
fn bad_patches_are_refused() {
    let k1 = KnotVector::clamped(1, 0.0, 1.0, &[]).unwrap();
    let k3 = KnotVector::clamped(3, 0.0, 1.0, &[]).unwrap();
    let flat = Surface::new(k1, k3, vec![Vector2::zeros(); 8]).unwrap();
    let err = ParametricConvexity::new(flat, Sign::NonNegative).unwrap_err();
    // Issue 26: the degree below 2 and the allowed degrees.
    assert_eq!(err.kind(), spline_core::ErrorKind::InvalidArgument);
    assert_eq!(
        (err.value(), err.interval()),
        (Some(1.0), Some((2.0, f64::INFINITY)))
    );
    let convex = ParametricConvexity::new(base(), Sign::NonNegative).unwrap();
    assert!(convex.fit_grid(&[0.5], &[0.5], &[]).is_err());
    assert!(convex.fit_grid(&[0.5], &[0.5], &[f64::NAN]).is_err());
}
