//! Offset surfaces against closed forms: spheres, planes and surfaces of revolution with a
//! straight or circular meridian (cylinders, cones, tori) exactly, other surfaces of
//! revolution and an ellipsoid (with its singular poles) within the tolerance, folds refused.

use nalgebra::Vector3;
use spline_core::ErrorKind;
use spline_geom::{Axis, BSpline, NurbsCurve, NurbsSurface, Surface};
use spline_shape::{ExactOffset, OffsetOptions, SurfaceOffsetShape, offset_surface};

/// A grid of `n × n` parameters over the domain, ends included.
fn grid(domain: ((f64, f64), (f64, f64)), n: u32) -> Vec<(f64, f64)> {
    let ((a, b), (c, d)) = domain;
    let at = |lo: f64, hi: f64, k: u32| lo + (hi - lo) * f64::from(k) / f64::from(n - 1);
    (0..n)
        .flat_map(|i| (0..n).map(move |j| (at(a, b, i), at(c, d, j))))
        .collect()
}

fn eval(shape: &SurfaceOffsetShape<f64>, u: f64, v: f64) -> Vector3<f64> {
    match shape {
        SurfaceOffsetShape::Polynomial(s) => s.eval(u, v).unwrap(),
        SurfaceOffsetShape::Rational(s) => s.eval(u, v).unwrap(),
    }
}

#[test]
fn offsets_of_a_sphere_are_concentric_spheres() {
    let centre = Vector3::new(1.0, -2.0, 0.5);
    let sphere = NurbsSurface::sphere(centre, 2.0).unwrap();
    for (distance, radius) in [(0.5, 2.5), (-1.5, 0.5), (-3.0, 1.0)] {
        let offset = offset_surface(&sphere, distance, &OffsetOptions::default()).unwrap();
        assert_eq!(offset.exact, ExactOffset::Sphere);
        assert_eq!(offset.max_error, 0.0);
        assert!(matches!(offset.surface, SurfaceOffsetShape::Rational(_)));
        for (u, v) in grid(sphere.domain(), 17) {
            let p = eval(&offset.surface, u, v);
            let q = sphere.eval(u, v).unwrap();
            assert!(((p - centre).norm() - radius).abs() <= 1e-13, "({u}, {v})");
            // On the same ray from the centre (through it for d < −r).
            let along = (p - centre).dot(&(q - centre)).signum();
            assert_eq!(along, (2.0 + distance).signum(), "({u}, {v})");
        }
    }
    let err = offset_surface(&sphere, -2.0, &OffsetOptions::default()).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::DegenerateGeometry);
    assert!(err.to_string().contains("collapses"), "{err}");
}

#[test]
fn a_plane_is_translated_along_its_normal() {
    // A bicubic patch of the plane z = 0 with uneven control points (normal +z).
    let ku = spline_core::KnotVector::clamped(3, 0.0, 1.0, &[0.4]).unwrap();
    let kv = spline_core::KnotVector::clamped(2, 0.0, 2.0, &[]).unwrap();
    let net: Vec<Vector3<f64>> = (0..5)
        .flat_map(|i| {
            (0..3).map(move |j| {
                let (x, y) = (f64::from(i), f64::from(j));
                Vector3::new(x + 0.1 * y * y, y + 0.05 * x * x, 0.0)
            })
        })
        .collect();
    let plane = Surface::new(ku, kv, net).unwrap();
    let offset = offset_surface(&plane, 0.3, &OffsetOptions::default()).unwrap();
    assert_eq!(offset.exact, ExactOffset::Plane);
    for (u, v) in grid(plane.domain(), 9) {
        let diff = eval(&offset.surface, u, v) - plane.eval(u, v).unwrap();
        assert!(
            (diff - Vector3::new(0.0, 0.0, 0.3)).norm() <= 1e-15,
            "({u}, {v}): {diff}"
        );
    }
}

#[test]
fn the_offset_of_a_torus_is_the_torus_of_a_larger_tube() {
    let torus = NurbsSurface::torus(Vector3::zeros(), Vector3::z(), 2.0, 0.5).unwrap();
    let tolerance = 1e-6;
    let options = OffsetOptions {
        degree: 3,
        tolerance,
    };
    let offset = offset_surface(&torus, 0.2, &options).unwrap();
    // The revolution of the concentric tube circle: exact.
    assert_eq!(offset.exact, ExactOffset::Revolution);
    assert_eq!(offset.max_error, 0.0);
    for (u, v) in grid(torus.domain(), 41) {
        let p = eval(&offset.surface, u, v);
        let tube = (p.x.hypot(p.y) - 2.0).hypot(p.z);
        assert!(
            (tube - 0.7).abs() <= 1e-14,
            "({u}, {v}): tube radius {tube}"
        );
        // On the same parameters: the offset point is S + d n there.
        let s = torus.eval(u, v).unwrap();
        let ring = Vector3::new(s.x, s.y, 0.0).normalize() * 2.0;
        let n = (s - ring).normalize();
        assert!((p - (s + n * 0.2)).norm() <= 1e-13, "({u}, {v})");
    }
    // Inwards, the tube of radius 0.2.
    let inward = offset_surface(&torus, -0.3, &options).unwrap();
    assert_eq!(inward.exact, ExactOffset::Revolution);
    for (u, v) in grid(torus.domain(), 17) {
        let p = eval(&inward.surface, u, v);
        let tube = (p.x.hypot(p.y) - 2.0).hypot(p.z);
        assert!(
            (tube - 0.2).abs() <= 1e-14,
            "({u}, {v}): tube radius {tube}"
        );
    }
    for (u, v) in grid(torus.domain(), 41) {
        let p = eval(&offset.surface, u, v);
        let tube = (p.x.hypot(p.y) - 2.0).hypot(p.z);
        assert!(
            (tube - 0.7).abs() <= tolerance,
            "({u}, {v}): tube radius {tube}"
        );
    }
    // Inwards by more than the tube's radius the offset folds: refused, with the place.
    let err = offset_surface(&torus, -0.6, &options).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::DegenerateGeometry);
    assert!(err.to_string().contains("folds"), "{err}");
}

#[test]
fn the_offset_of_an_ellipsoid_through_its_singular_poles() {
    // x² + y² + (z / 0.5)² = 1 from the unit sphere (poles where S_u × S_v = 0).
    let sphere = NurbsSurface::sphere(Vector3::zeros(), 1.0).unwrap();
    let ellipsoid = sphere.map_control_points(|p| Vector3::new(p.x, p.y, 0.5 * p.z));
    let (distance, tolerance) = (0.1, 1e-6);
    let options = OffsetOptions {
        degree: 3,
        tolerance,
    };
    let offset = offset_surface(&ellipsoid, distance, &options).unwrap();
    assert_eq!(offset.exact, ExactOffset::Approximate);
    for (u, v) in grid(ellipsoid.domain(), 33) {
        let s = ellipsoid.eval(u, v).unwrap();
        // The outward normal of the implicit surface: the gradient (x, y, 4 z).
        let n = Vector3::new(s.x, s.y, 4.0 * s.z).normalize();
        let e = (eval(&offset.surface, u, v) - (s + n * distance)).norm();
        assert!(e <= tolerance, "({u}, {v}): {e:e}");
    }
}

#[test]
fn bad_distances_and_tolerances_are_refused() {
    let sphere = NurbsSurface::sphere(Vector3::zeros(), 1.0).unwrap();
    let torus = NurbsSurface::torus(Vector3::zeros(), Vector3::z(), 2.0, 0.5).unwrap();
    for d in [f64::NAN, f64::INFINITY] {
        let err = offset_surface(&sphere, d, &OffsetOptions::default()).unwrap_err();
        assert_eq!(err.kind(), ErrorKind::NonFinite);
    }
    for tolerance in [0.0, -1.0, f64::NAN] {
        let options = OffsetOptions {
            degree: 3,
            tolerance,
        };
        let err = offset_surface(&torus, 0.1, &options).unwrap_err();
        assert_eq!(err.kind(), ErrorKind::InvalidTolerance, "{err}");
    }
}

/// A NURBS surface of revolution about the z axis of the planar profile `points` (in the
/// x–z plane), turned by `angle`.
fn revolved(profile: &NurbsCurve<f64, 3>, angle: f64) -> NurbsSurface<f64, 3> {
    let axis = Axis::new(Vector3::zeros(), Vector3::z()).unwrap();
    NurbsSurface::revolution(profile, &axis, angle).unwrap()
}

#[test]
fn cylinders_and_cones_have_exact_offsets() {
    let line = |a: [f64; 3], b: [f64; 3]| {
        let c = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0], vec![a.into(), b.into()]).unwrap();
        NurbsCurve::from_bspline(&c)
    };
    let options = OffsetOptions::default();
    // A cylinder of radius 2 (full turn) and a cone from radius 1 at z = 0 to 3 at z = 2
    // (three quarters of a turn).
    let cylinder = revolved(
        &line([2.0, 0.0, 0.0], [2.0, 0.0, 3.0]),
        std::f64::consts::TAU,
    );
    let cone = revolved(
        &line([1.0, 0.0, 0.0], [3.0, 0.0, 2.0]),
        1.5 * std::f64::consts::PI,
    );
    for (surface, d) in [
        (&cylinder, 0.5),
        (&cylinder, -0.7),
        (&cone, 0.4),
        (&cone, -0.3),
    ] {
        let offset = offset_surface(surface, d, &options).unwrap();
        assert_eq!(offset.exact, ExactOffset::Revolution);
        assert_eq!(offset.max_error, 0.0);
        for (u, v) in grid(surface.domain(), 17) {
            let mut derivatives = [Vector3::zeros(); 4];
            surface.derivatives_into(u, v, 1, &mut derivatives).unwrap();
            let n = derivatives[2].cross(&derivatives[1]).normalize();
            let s = derivatives[0];
            let e = (eval(&offset.surface, u, v) - (s + n * d)).norm();
            assert!(e <= 1e-13, "d = {d}, ({u}, {v}): {e:e}");
        }
    }
}

#[test]
fn other_surfaces_of_revolution_offset_through_their_meridian() {
    // A wavy cubic meridian (not a line, not an arc) half a turn about z.
    let profile = BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0],
        vec![
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(1.6, 0.0, 0.5),
            Vector3::new(1.2, 0.0, 1.0),
            Vector3::new(1.8, 0.0, 1.6),
            Vector3::new(1.5, 0.0, 2.0),
        ],
    )
    .unwrap();
    let surface = revolved(&NurbsCurve::from_bspline(&profile), std::f64::consts::PI);
    let (d, tolerance) = (0.05, 1e-7);
    let options = OffsetOptions {
        degree: 3,
        tolerance,
    };
    let offset = offset_surface(&surface, d, &options).unwrap();
    assert_eq!(offset.exact, ExactOffset::Approximate);
    assert!(offset.max_error <= tolerance);
    assert!(matches!(offset.surface, SurfaceOffsetShape::Rational(_)));
    for (u, v) in grid(surface.domain(), 33) {
        let mut derivatives = [Vector3::zeros(); 4];
        surface.derivatives_into(u, v, 1, &mut derivatives).unwrap();
        let n = derivatives[2].cross(&derivatives[1]).normalize();
        let e = (eval(&offset.surface, u, v) - (derivatives[0] + n * d)).norm();
        assert!(e <= tolerance, "({u}, {v}): {e:e}");
    }
}
