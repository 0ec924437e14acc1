//! The library side of issue 9: public functions return `Err` (never panic, abort or wrap)
//! on absurd counts, and scale-invariant computations give the unscaled answers at scales
//! of 1e±150 and beyond.

use nalgebra::{Vector2, Vector3};
use spline::core::{ErrorKind, KnotVector, MAX_DERIVATIVE_ORDER};
use spline::geom::{BSpline, Frame, NurbsCurve, NurbsSurface};

fn cubic(scale: f64) -> BSpline<f64, Vector2<f64>> {
    let points = [
        (0.41705, 0.10673),
        (0.28802, 0.60088),
        (0.90553, 0.46053),
        (1.3203, 0.79678),
        (1.8041, 0.63012),
        (1.477, 0.13012),
    ];
    BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0],
        points
            .iter()
            .map(|&(x, y)| Vector2::new(x * scale, y * scale))
            .collect(),
    )
    .unwrap()
}

const ABSURD: [usize; 4] = [usize::MAX, usize::MAX - 1, 1 << 62, 1_000_000_000];

#[test]
fn absurd_counts_are_errors() {
    let c = cubic(1.0);
    for n in ABSURD {
        assert_eq!(
            c.derivatives(1.5, n).unwrap_err().kind(),
            ErrorKind::InvalidArgument
        );
        assert_eq!(
            c.knots()
                .dense_basis_derivatives(1.5, n)
                .unwrap_err()
                .kind(),
            ErrorKind::InvalidArgument
        );
        assert_eq!(
            c.insert_knot(1.5, n).unwrap_err().kind(),
            ErrorKind::KnotMultiplicity
        );
        assert_eq!(
            c.elevate_degree(n).unwrap_err().kind(),
            ErrorKind::DegreeTooHigh
        );
        assert!(c.knots().elevated(n).is_err());
        assert!(c.derivative(n).is_err());
        assert!(c.remove_knot(1.0, n, 1.0).is_err());
        assert!(spline::algebra::SplineMap::elevation(c.knots(), n).is_err());
        let sphere = NurbsSurface::sphere(Vector3::new(0.0, 0.0, 0.0), 1.0).unwrap();
        assert!(sphere.tessellate(n, 4).is_err());
        assert!(sphere.derivatives(0.5, 0.5, n).is_err());
        let nurbs = NurbsCurve::from_bspline(&c);
        assert!(nurbs.derivatives(1.5, n).is_err());
    }
    // The largest order allowed works, and costs nothing above the degree.
    let d = c.derivatives(1.5, MAX_DERIVATIVE_ORDER).unwrap();
    assert_eq!(d.len(), MAX_DERIVATIVE_ORDER + 1);
    assert!(d[4..].iter().all(|v| *v == Vector2::zeros()));
    // Elevation to exactly the maximum degree is fine, one more is not.
    assert_eq!(c.elevate_degree(29).unwrap().degree(), 32);
    assert!(c.elevate_degree(30).is_err());
}

#[test]
fn arcs_with_too_many_pieces_are_errors() {
    let frame = Frame::planar(Vector2::new(0.0, 0.0));
    let tau = std::f64::consts::TAU;
    for piece in [1e-21, 1e-8, tau / 1001.0] {
        let e = NurbsCurve::arc_with_max_piece(&frame, 1.0, 0.0, tau, piece).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    }
    let arc = NurbsCurve::arc_with_max_piece(&frame, 1.0, 0.0, tau, tau / 1000.0).unwrap();
    assert_eq!(arc.control_points().len(), 2001);
}

#[test]
fn rational_derivatives_overflow_into_an_error() {
    let frame = Frame::planar(Vector2::new(0.0, 0.0));
    let circle = NurbsCurve::circle(&frame, 1.0, spline::geom::CircleConstruction::Square).unwrap();
    let e = circle.derivatives(0.3, 1000).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    // Every derivative below the overflow is finite.
    let d = circle.derivatives(0.3, 100).unwrap();
    assert!(d.iter().all(|v| v.iter().all(|x: &f64| x.is_finite())));
}

#[test]
fn overflowing_polynomial_derivatives_are_errors() {
    // Coordinates 1e300 on a domain of length 1e-9: C' is about 1e309.
    let c = BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1e-9, 1e-9],
        vec![Vector2::new(0.0, 0.0), Vector2::new(1e300, 0.0)],
    )
    .unwrap();
    assert_eq!(
        c.derivatives(0.5e-9, 1).unwrap_err().kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(c.derivative(1).unwrap_err().kind(), ErrorKind::NonFinite);
}

#[test]
fn curvature_and_features_are_scale_invariant() {
    let reference = cubic(1.0);
    let features = spline::algebra::planar_features(&reference, 1e-12).unwrap();
    assert!(!features.curvature_extrema.is_empty());
    for scale in [1e150, 1e-150, 1e80, 1e-100, 1e300, 1e-300] {
        let c = cubic(scale);
        for u in [0.0, 0.7, 1.5, 3.0] {
            let want = reference.signed_curvature(u).unwrap() / scale;
            let got = c.signed_curvature(u).unwrap();
            assert!(
                ((got - want) / want).abs() < 1e-12,
                "scale {scale}, u {u}: {got} vs {want}"
            );
            let t = c.unit_tangent(u).unwrap();
            assert!((t - reference.unit_tangent(u).unwrap()).norm() < 1e-14);
        }
        let f = spline::algebra::planar_features(&c, 1e-12).unwrap();
        assert_eq!(
            f.curvature_extrema.len(),
            features.curvature_extrema.len(),
            "scale {scale}"
        );
        assert_eq!(
            f.inflections.len(),
            features.inflections.len(),
            "scale {scale}"
        );
        for (a, b) in f.curvature_extrema.iter().zip(&features.curvature_extrema) {
            assert!((a - b).abs() < 1e-9, "scale {scale}: {a} vs {b}");
        }
    }
}

#[test]
fn fitting_is_scale_invariant() {
    let base = [[0.0, 0.0], [3.0, 4.0], [3.0, 10.0], [11.0, 16.0]];
    for scale in [1e154, 1e-200, 1e300, 1e-300] {
        let points: Vec<Vector2<f64>> = base
            .iter()
            .map(|p| Vector2::new(p[0] * scale, p[1] * scale))
            .collect();
        let u = spline::fit::parametrize(&points, &spline::fit::Parametrization::Chordal).unwrap();
        let want = [0.0, 5.0 / 21.0, 11.0 / 21.0, 1.0];
        for (a, b) in u.iter().zip(want) {
            assert!((a - b).abs() < 1e-15, "scale {scale}: {a} vs {b}");
        }
        let c =
            spline::fit::parametrize(&points, &spline::fit::Parametrization::Centripetal).unwrap();
        // Centripetal: square roots of 5, 6, 10.
        let total = 5f64.sqrt() + 6f64.sqrt() + 10f64.sqrt();
        assert!((c[1] - 5f64.sqrt() / total).abs() < 1e-15);
    }
}

#[test]
fn tiny_steps_next_to_huge_ones_are_not_coincidences() {
    // Chord lengths 1 and 1e300 − 1: the middle parameter is 1e-300, not 0.
    let points = [
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 0.0),
        Vector2::new(1e300, 0.0),
    ];
    let u: Vec<f64> =
        spline::fit::parametrize(&points, &spline::fit::Parametrization::Chordal).unwrap();
    assert!(((u[1] - 1e-300) / 1e-300).abs() < 1e-12, "{u:?}");
}

#[test]
fn natural_splines_accept_any_spacing() {
    let y = [0.0, 1.0, 0.5, 2.0, 1.0];
    let unit = spline::fit::natural_spline(&[0.0, 1.0, 2.0, 3.0, 4.0], &y, 6).unwrap();
    for spacing in [1e-12, 1e-6, 1e6, 1e12, 1e-300, 1e300] {
        let x: Vec<f64> = (0..5).map(|k| f64::from(k) * spacing).collect();
        for order in [4, 6] {
            let s = spline::fit::natural_spline(&x, &y, order).unwrap();
            for (xk, yk) in x.iter().zip(y) {
                assert!(
                    (s.eval(*xk).unwrap() - yk).abs() < 1e-12,
                    "spacing {spacing}"
                );
            }
        }
        // The coefficients do not depend on the spacing (the knots scale with it).
        let s = spline::fit::natural_spline(&x, &y, 6).unwrap();
        for (a, b) in s.control_points().iter().zip(unit.control_points()) {
            assert!((a - b).abs() < 1e-12, "spacing {spacing}: {a} vs {b}");
        }
    }
}

#[test]
fn parameter_correction_sweeps_are_limited() {
    let points: Vec<Vector2<f64>> = (0..10)
        .map(|k| {
            let t = f64::from(k) / 9.0;
            Vector2::new(t, t * t)
        })
        .collect();
    let params = spline::fit::parametrize(&points, &spline::fit::Parametrization::Chordal).unwrap();
    let knots = KnotVector::clamped_uniform(3, 5, 0.0, 1.0).unwrap();
    let problem = spline::fit::LeastSquares::new(&points, &params, knots);
    let options = spline::fit::CorrectionOptions {
        max_iterations: spline::fit::MAX_CORRECTION_ITERATIONS + 1,
        ..Default::default()
    };
    let e = spline::fit::correct_parameters(&problem, &options).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
}

#[test]
fn large_spheres_have_finite_meshes() {
    for r in [1e155, 1e300, 1e-300] {
        let s = NurbsSurface::sphere(Vector3::new(0.0, 0.0, 0.0), r).unwrap();
        let p = s.eval(0.3, 0.7).unwrap();
        let p: Vector3<f64> = p / r;
        assert!((p.norm() - 1.0).abs() < 1e-14, "radius {r}");
        let mesh = s.tessellate(8, 8).unwrap();
        assert!(mesh.normals.iter().all(|n| (n.norm() - 1.0).abs() < 1e-12));
        assert!(
            mesh.triangles.len() > 100,
            "radius {r}: {}",
            mesh.triangles.len()
        );
    }
}
