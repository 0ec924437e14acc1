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
    // x² + y² + (z / 0.5)² = 1 from the unit sphere (poles where S_u × S_v = 0), about the
    // origin and 10³ away (where the poles' S_v is the rounding of the position: the normal
    // there is the limit S_u × S_uv, not the rounding's direction).
    for centre in [Vector3::zeros(), Vector3::new(1e3, -2e2, 5e2)] {
        let sphere = NurbsSurface::sphere(Vector3::zeros(), 1.0).unwrap();
        let ellipsoid = sphere.map_control_points(|p| centre + Vector3::new(p.x, p.y, 0.5 * p.z));
        let (distance, tolerance) = (0.1, 1e-6);
        let options = OffsetOptions {
            degree: 3,
            tolerance,
        };
        let offset = offset_surface(&ellipsoid, distance, &options).unwrap();
        assert_eq!(offset.exact, ExactOffset::Approximate);
        for (u, v) in grid(ellipsoid.domain(), 33) {
            let s = ellipsoid.eval(u, v).unwrap() - centre;
            // The outward normal of the implicit surface: the gradient (x, y, 4 z).
            let n = Vector3::new(s.x, s.y, 4.0 * s.z).normalize();
            let e = (eval(&offset.surface, u, v) - centre - (s + n * distance)).norm();
            assert!(e <= tolerance, "{centre:?} ({u}, {v}): {e:e}");
        }
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

/// A xorshift generator of uniform numbers in `[0, 1)` (reproducible).
fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn spheres_anywhere_and_of_any_size_are_offset_exactly() {
    // The OCCT geometry suite's reproducer: about (−3, −1, −1), the rounding of the position
    // made S_u × S_v at the poles look regular, with a radius of curvature of 6e-15, and the
    // curvature-based centre was missed: "folds near (u, v) = (0, 0.27)".
    let sphere = NurbsSurface::sphere(Vector3::new(-3.0, -1.0, -1.0), 0.7).unwrap();
    let options = OffsetOptions {
        degree: 3,
        tolerance: 3.7e-6,
    };
    let offset = offset_surface(&sphere, 0.1, &options).unwrap();
    assert_eq!(offset.exact, ExactOffset::Sphere);
    // Random centres up to 10³ away, radii 10⁻³ to 10³, random axes, in and out.
    let mut next = uniform(0x9e37_79b9_7f4a_7c15);
    for k in 0..90 {
        let far = [1.0, 1e3, 1e-3][k % 3];
        let centre = Vector3::new(next() - 0.5, next() - 0.5, next() - 0.5) * (2.0 * far);
        let radius = 10f64.powf(6.0 * next() - 3.0);
        let axis = Vector3::new(next() - 0.5, next() - 0.5, next() - 0.5);
        let sphere = NurbsSurface::sphere_about(centre, radius, axis).unwrap();
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        let distance = sign * radius * (0.05 + 0.9 * next());
        let case = format!("centre {centre:?}, radius {radius:e}, distance {distance:e}");
        let options = OffsetOptions {
            degree: 3,
            tolerance: 1e-6 * radius,
        };
        let offset = offset_surface(&sphere, distance, &options).unwrap();
        assert_eq!(offset.exact, ExactOffset::Sphere, "{case}");
        assert_eq!(offset.max_error, 0.0, "{case}");
        let scale = radius + centre.norm();
        for (u, v) in grid(sphere.domain(), 17) {
            let p = eval(&offset.surface, u, v);
            let q = sphere.eval(u, v).unwrap();
            // S + d n with the outward normal n = (S − c) / r.
            let want = q + (q - centre) * (distance / radius);
            let e = (p - want).norm();
            // To 10⁻¹² of the size, and beyond the rounding of the position only.
            assert!(e <= 1e-12 * scale, "{case} at ({u}, {v}): {e:e}");
            assert!(
                e <= 1e-12 * radius + 32.0 * f64::EPSILON * centre.norm(),
                "{case} at ({u}, {v}): {e:e}"
            );
        }
    }
}

#[test]
fn a_slightly_perturbed_sphere_is_not_a_sphere() {
    let mut next = uniform(0x2545_f491_4f6c_dd1d);
    for k in 0..6 {
        let far = [1.0, 1e3][k % 2];
        let centre = Vector3::new(next() - 0.5, next() - 0.5, next() - 0.5) * (2.0 * far);
        let radius = [1e-3, 1.0, 1e3][k % 3];
        let sphere = NurbsSurface::sphere(centre, radius).unwrap();
        // A smooth non-affine map of the net by 10⁻⁶ of the radius (the poles stay poles).
        let bent = sphere.map_control_points(|p| {
            let x = (p.x - centre.x) / radius;
            p + Vector3::new(1e-6 * radius * x * x, 0.0, 0.0)
        });
        let options = OffsetOptions {
            degree: 3,
            tolerance: 1e-4 * radius,
        };
        let case = format!("centre {centre:?}, radius {radius:e}");
        // The sphere itself is one; the perturbed net is approximated.
        let exact = offset_surface(&sphere, 0.2 * radius, &options).unwrap();
        assert_eq!(exact.exact, ExactOffset::Sphere, "{case}");
        let offset = offset_surface(&bent, 0.2 * radius, &options).unwrap();
        assert_eq!(offset.exact, ExactOffset::Approximate, "{case}");
        assert!(offset.max_error <= options.tolerance, "{case}");
    }
    // Nearly flat: z = 10⁻⁶ (x² + y²) + 10⁻⁹ x³ on [−1, 1]² is within 10⁻⁹ of a sphere of
    // radius 5·10⁵, i.e. 2·10⁻¹⁵ of its radius: the check is relative to the piece's size,
    // not the radius. The Bézier net: x, y linear in the control points, z the Bernstein
    // coefficients b_i = Σ_k C(i, k) / C(3, k) a_k of the polynomials in s = (x + 1) / 2.
    let bernstein = |a: [f64; 4]| -> [f64; 4] {
        let choose = |n: usize, k: usize| -> f64 {
            (0..k).fold(1.0, |c, j| c * (n - j) as f64 / (j + 1) as f64)
        };
        std::array::from_fn(|i| (0..=i).map(|k| choose(i, k) / choose(3, k) * a[k]).sum())
    };
    // x² = 4 s² − 4 s + 1, x³ = 8 s³ − 12 s² + 6 s − 1.
    let g = bernstein([1e-6 - 1e-9, -4e-6 + 6e-9, 4e-6 - 12e-9, 8e-9]);
    let h = bernstein([1e-6, -4e-6, 4e-6, 0.0]);
    let net: Vec<Vec<Vector3<f64>>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let at = |k: usize| -1.0 + 2.0 * k as f64 / 3.0;
                    Vector3::new(at(i), at(j), g[i] + h[j])
                })
                .collect()
        })
        .collect();
    let shallow = Surface::bezier(net).unwrap();
    let z = shallow.eval(0.25, 0.75).unwrap();
    let (x, y) = (-0.5, 0.5);
    assert!((z.z - (1e-6 * (x * x + y * y) + 1e-9 * x * x * x)).abs() <= 1e-20);
    let offset = offset_surface(&shallow, 0.1, &OffsetOptions::default()).unwrap();
    assert_eq!(offset.exact, ExactOffset::Approximate);
}
