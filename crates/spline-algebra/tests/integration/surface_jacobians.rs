//! Jacobians of the curvature numerators of surfaces with respect to the homogeneous control
//! points, against central differences (polynomial and rational bicubics), and the
//! numerators against pointwise curvature.

use nalgebra::{DMatrix, Vector3};
use spline_algebra::curvature_numerators_with_jacobians;
use spline_core::KnotVector;
use spline_geom::NurbsSurface;

/// A deterministic pseudo-random sequence in `[0, 1)`.
fn sequence(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A bicubic net of 4 × 5 points over the unit square with random heights and, when
/// `rational`, random weights.
fn surface(seed: u64, rational: bool) -> NurbsSurface<f64, 3> {
    let mut r = sequence(seed);
    let ku = KnotVector::clamped(3, 0.0, 1.0, &[]).unwrap();
    let kv = KnotVector::clamped(3, 0.0, 1.0, &[0.5]).unwrap();
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..4 {
        for j in 0..5 {
            points.push(Vector3::new(
                f64::from(i) / 3.0 + 0.05 * r(),
                f64::from(j) / 4.0 + 0.05 * r(),
                0.4 * r() - 0.2,
            ));
            weights.push(if rational { 0.6 + r() } else { 1.0 });
        }
    }
    NurbsSurface::new(ku, kv, points, weights).unwrap()
}

/// The surface with homogeneous variable `index` ([w x, w y, w z, w] per point) moved by `h`.
fn moved(s: &NurbsSurface<f64, 3>, index: usize, h: f64) -> NurbsSurface<f64, 3> {
    let (i, c) = (index / 4, index % 4);
    let mut points = s.control_points().to_vec();
    let mut weights = s.weights().to_vec();
    let mut homogeneous = points[i] * weights[i];
    if c < 3 {
        homogeneous[c] += h;
    } else {
        weights[i] += h;
    }
    points[i] = homogeneous / weights[i];
    NurbsSurface::new(s.knots_u().clone(), s.knots_v().clone(), points, weights).unwrap()
}

#[test]
fn numerator_jacobians_match_central_differences() {
    for (seed, rational) in [(1, false), (3, true)] {
        let s = surface(seed, rational);
        let (values, jacobians) = curvature_numerators_with_jacobians(&s).unwrap();
        let variables = 4 * s.control_points().len();
        let gaussian = DMatrix::from(&jacobians.gaussian);
        let mean = DMatrix::from(&jacobians.mean);
        assert_eq!(gaussian.ncols(), variables);
        assert_eq!(gaussian.nrows(), values.gaussian.control_points().len());
        let h = 1e-6;
        let mut checked = 0;
        // Every variable kind at every fifth point (the whole net costs seconds per surface).
        for index in (0..variables).filter(|i| (i / 4) % 5 == seed as usize % 5 || i / 4 == 7) {
            // A polynomial surface uses the polynomial formulas: its weights are not variables
            // (moving one would make the surface rational).
            if !rational && index % 4 == 3 {
                assert!((0..gaussian.nrows()).all(|r| gaussian[(r, index)] == 0.0));
                continue;
            }
            let (plus, _) = curvature_numerators_with_jacobians(&moved(&s, index, h)).unwrap();
            let (minus, _) = curvature_numerators_with_jacobians(&moved(&s, index, -h)).unwrap();
            for (name, jac, p, m) in [
                ("gaussian", &gaussian, &plus.gaussian, &minus.gaussian),
                ("mean", &mean, &plus.mean, &minus.mean),
            ] {
                let scale = p
                    .control_points()
                    .iter()
                    .fold(1.0f64, |a, v| a.max(v.abs()));
                for (row, (a, b)) in p
                    .control_points()
                    .iter()
                    .zip(m.control_points())
                    .enumerate()
                {
                    let fd = (a - b) / (2.0 * h);
                    assert!(
                        (fd - jac[(row, index)]).abs() < 1e-5 * scale,
                        "seed {seed} {name} coefficient {row} variable {index}: {fd} vs {}",
                        jac[(row, index)]
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 300, "{checked}");
        // The numerators themselves (not normalised) keep the sign of K and H.
        for (u, v) in [(0.2, 0.3), (0.7, 0.6), (0.45, 0.9)] {
            let local = s.local_properties(u, v).unwrap();
            let k = values.gaussian.eval(u, v).unwrap();
            if local.gaussian_curvature.abs() > 1e-6 {
                assert_eq!(k.signum(), local.gaussian_curvature.signum(), "seed {seed}");
            }
        }
    }
}
