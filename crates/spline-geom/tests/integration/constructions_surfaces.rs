//! The surface constructions of seed 004 §6 checked for exactness: spheres and tori at the
//! exact radius, extrusions, ruled, conical and revolved surfaces exactly where they must be,
//! the errors of degenerate input, and the constructions in f32, f64 and dual numbers.

use crate::constructions::{CONSTRUCTIONS, Rng};
use nalgebra::{SVector, Vector2, Vector3};
use num_dual::Dual64;
use spline_core::{ErrorKind, KnotVector, Scalar, cast, to_f64};
use spline_geom::StructuralSurface;
use spline_geom::{
    Axis, BSpline, CircleConstruction, Direction, Frame, NurbsCurve, NurbsSurface, Surface,
};
use std::f64::consts::{FRAC_PI_2, PI, SQRT_2, TAU};

/// The sphere of (6.13)–(6.14): the 5 × 9 net of the notes, every point at the radius.
#[test]
fn sphere_of_the_notes() {
    let center = Vector3::new(1.0, -2.0, 0.5);
    let r = 3.0;
    let s = NurbsSurface::sphere(center, r).unwrap();
    assert_eq!(s.degrees(), (2, 2));
    assert_eq!(s.net_size(), (5, 9));
    assert_eq!(
        s.knots_u().knots(),
        &[0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]
    );
    assert_eq!(
        s.knots_v().knots(),
        &[
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0
        ]
    );
    let h = SQRT_2 / 2.0;
    let w = [1.0, h, 1.0, h, 1.0];
    let wv = [1.0, h, 1.0, h, 1.0, h, 1.0, h, 1.0];
    for (i, wi) in w.iter().enumerate() {
        for (j, wj) in wv.iter().enumerate() {
            assert!((s.weight(i, j) - wi * wj).abs() < 1e-15);
        }
    }
    // The half circle (6.13) at v = 0 and the poles on the axis.
    let profile = s.curve_at_v(0.0).unwrap();
    for (p, e) in profile.control_points().iter().zip([
        (0.0, 1.0),
        (1.0, 1.0),
        (1.0, 0.0),
        (1.0, -1.0),
        (0.0, -1.0),
    ]) {
        assert!((p - (center + Vector3::new(e.0, 0.0, e.1) * r)).norm() < 1e-14);
    }
    for j in 0..9 {
        assert!((s.control_point(0, j) - (center + Vector3::z() * r)).norm() < 1e-15);
        assert!((s.control_point(4, j) - (center - Vector3::z() * r)).norm() < 1e-15);
    }
    let mut rng = Rng(3);
    let mut worst: f64 = 0.0;
    for _ in 0..10000 {
        let (u, v) = (rng.next(), rng.next());
        worst = worst.max(((s.eval(u, v).unwrap() - center).norm() - r).abs() / r);
    }
    assert!(worst <= 1e-13, "sphere radius error {worst:e}");
    // Curvatures: K = 1/r², H = −1/r with the outward normal.
    for _ in 0..500 {
        let (u, v) = (0.02 + 0.96 * rng.next(), rng.next());
        let props = s.local_properties(u, v).unwrap();
        let p = s.eval(u, v).unwrap();
        assert!((props.normal - (p - center) / r).norm() < 1e-12);
        assert!((props.gaussian_curvature * r * r - 1.0).abs() < 1e-11);
        assert!((props.mean_curvature * r + 1.0).abs() < 1e-11);
        assert!(
            (props.max_curvature * r + 1.0).abs() < 1e-6
                && (props.min_curvature * r + 1.0).abs() < 1e-6
        );
    }
    // The poles are singular points of the parametrisation.
    assert_eq!(
        s.local_properties(0.0, 0.3).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
}

#[test]
fn torus_points_are_at_the_tube_radius() {
    let mut rng = Rng(4);
    for _ in 0..10 {
        let center = Vector3::new(
            rng.next() * 4.0 - 2.0,
            rng.next() * 4.0 - 2.0,
            rng.next() * 4.0 - 2.0,
        );
        let axis = Vector3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5);
        let minor = 0.1 + rng.next();
        let major = minor * (1.1 + rng.next() * 3.0);
        let t = NurbsSurface::torus(center, axis, major, minor).unwrap();
        assert_eq!(t.net_size(), (9, 9));
        let a = axis.normalize();
        let mut worst: f64 = 0.0;
        for _ in 0..2000 {
            let (u, v) = (rng.next(), rng.next());
            let p = t.eval(u, v).unwrap() - center;
            let h = p.dot(&a);
            let rho = (p - a * h).norm();
            worst = worst.max((((rho - major).powi(2) + h * h).sqrt() - minor).abs() / minor);
        }
        assert!(worst <= 1e-13, "torus error {worst:e}");
        // K = cos φ / (r (R + r cos φ)) = (ρ − R) / (r² ρ); H = −(1/r + (ρ − R)/(r ρ))/2
        // with the outward normal.
        for _ in 0..200 {
            let (u, v) = (rng.next(), rng.next());
            let props = t.local_properties(u, v).unwrap();
            let p = props.point - center;
            let h = p.dot(&a);
            let rho = (p - a * h).norm();
            let k = (rho - major) / (minor * minor * rho);
            let mean = -(1.0 / minor + (rho - major) / (minor * rho)) / 2.0;
            assert!((props.gaussian_curvature - k).abs() < 1e-10 * (1.0 + k.abs()));
            assert!((props.mean_curvature - mean).abs() < 1e-10 * (1.0 + mean.abs()));
            // Outward: away from the tube's center circle.
            let tube_center = (p - a * h) * (major / rho);
            assert!(props.normal.dot(&(p - tube_center)) > 0.0);
            // The principal direction with curvature −1/r lies in the meridian plane
            // (perpendicular to a × p); the other is along the parallel.
            let parallel = a.cross(&p).normalize();
            let (meridian_dir, parallel_dir) = if (props.min_curvature + 1.0 / minor).abs()
                < (props.max_curvature + 1.0 / minor).abs()
            {
                (props.min_direction, props.max_direction)
            } else {
                (props.max_direction, props.min_direction)
            };
            assert!(meridian_dir.dot(&parallel).abs() < 1e-8);
            assert!((parallel_dir.dot(&parallel).abs() - 1.0).abs() < 1e-8);
        }
    }
}

/// Extrusion (5.14)–(5.15): S(u, v) = C(u) + v V exactly, for B-splines and NURBS.
#[test]
fn extrusions_are_exact() {
    let curve = BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        vec![
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 2.0, 0.0),
            Vector3::new(2.0, -1.0, 1.0),
            Vector3::new(3.0, 0.0, 0.0),
            Vector3::new(4.0, 1.0, 2.0),
        ],
    )
    .unwrap();
    let v_vec = Vector3::new(0.5, -1.0, 2.0);
    let s = Surface::extrusion(&curve, v_vec).unwrap();
    assert_eq!(s.degrees(), (3, 1));
    let circle = NurbsCurve::circle(
        &Frame::with_normal(Vector3::zeros(), Vector3::new(0.0, 1.0, 1.0)).unwrap(),
        2.0,
        CircleConstruction::Square,
    )
    .unwrap();
    let cyl = NurbsSurface::extrusion(&circle, v_vec).unwrap();
    for i in 0..=50 {
        for j in 0..=10 {
            let (u, v) = (f64::from(i) / 50.0, f64::from(j) / 10.0);
            assert!((s.eval(u, v).unwrap() - (curve.eval(u).unwrap() + v_vec * v)).norm() < 1e-14);
            assert!(
                (cyl.eval(u, v).unwrap() - (circle.eval(u).unwrap() + v_vec * v)).norm() < 1e-14
            );
        }
    }
    assert_eq!(
        Surface::extrusion(&curve, Vector3::zeros())
            .unwrap_err()
            .kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        NurbsSurface::extrusion(&circle, Vector3::zeros())
            .unwrap_err()
            .kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        NurbsSurface::extrusion(&circle, Vector3::new(f64::NAN, 0.0, 0.0))
            .unwrap_err()
            .kind(),
        ErrorKind::NonFinite
    );
}

/// Ruled surfaces (5.16) of curves of different degrees, knots and domains:
/// S(u, v) = (1 − v) C1(u) + v C2(ū) with ū the affine image of u on the domain of C2.
#[test]
fn ruled_surfaces_join_the_curves_by_segments() {
    let c1 = BSpline::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 0.3, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(2.0, 0.0),
            Vector2::new(3.0, 1.0),
        ],
    )
    .unwrap();
    let c2 = BSpline::from_knots(
        3,
        vec![2.0, 2.0, 2.0, 2.0, 3.0, 4.0, 6.0, 6.0, 6.0, 6.0],
        (0..6)
            .map(|i| Vector2::new(f64::from(i), 3.0 + f64::from(i % 2)))
            .collect(),
    )
    .unwrap();
    let s = Surface::ruled(&c1, &c2).unwrap();
    assert_eq!(s.degrees(), (3, 1));
    assert_eq!(s.domain().0, (0.0, 1.0));
    for i in 0..=100 {
        for j in 0..=4 {
            let (u, v) = (f64::from(i) / 100.0, f64::from(j) / 4.0);
            let expected = c1.eval(u).unwrap() * (1.0 - v) + c2.eval(2.0 + 4.0 * u).unwrap() * v;
            assert!(
                (s.eval(u, v).unwrap() - expected).norm() < 1e-13,
                "({u}, {v})"
            );
        }
    }
    // Rational curves: the point lies on the segment from R1(u) to R2(u).
    let r1 = NurbsCurve::circle(
        &Frame::with_normal(Vector3::zeros(), Vector3::z()).unwrap(),
        1.0,
        CircleConstruction::Square,
    )
    .unwrap();
    let r2 = NurbsCurve::circle(
        &Frame::with_normal(Vector3::new(0.0, 0.0, 2.0), Vector3::z()).unwrap(),
        2.0,
        CircleConstruction::Triangle,
    )
    .unwrap();
    let rs = NurbsSurface::ruled(&r1, &r2).unwrap();
    for i in 0..=100 {
        let u = f64::from(i) / 100.0;
        let (a, b) = (r1.eval(u).unwrap(), r2.eval(u).unwrap());
        assert!((rs.eval(u, 0.0).unwrap() - a).norm() < 1e-13);
        assert!((rs.eval(u, 1.0).unwrap() - b).norm() < 1e-13);
        for j in 1..4 {
            let p = rs.eval(u, f64::from(j) / 4.0).unwrap();
            assert!((p - a).cross(&(b - a)).norm() < 1e-12);
            let t = (p - a).dot(&(b - a)) / (b - a).norm_squared();
            assert!(t > 0.0 && t < 1.0);
        }
    }
}

/// Conical surfaces (5.17): S(u, v) on the segment from C(u) to the apex, S(u, 1) = apex.
#[test]
fn cones_join_the_curve_to_the_apex() {
    let apex = Vector3::new(0.0, 0.0, 3.0);
    let circle = NurbsCurve::circle(
        &Frame::with_normal(Vector3::zeros(), Vector3::z()).unwrap(),
        1.5,
        CircleConstruction::Square,
    )
    .unwrap();
    let cone = NurbsSurface::cone(&circle, apex).unwrap();
    let curve = BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector3::new(1.0, 0.0, 0.0), Vector3::new(0.0, 1.0, 0.0)],
    )
    .unwrap();
    let flat = Surface::cone(&curve, apex).unwrap();
    for i in 0..=100 {
        let u = f64::from(i) / 100.0;
        assert!((cone.eval(u, 1.0).unwrap() - apex).norm() < 1e-14);
        assert!((flat.eval(u, 1.0).unwrap() - apex).norm() < 1e-14);
        let c = circle.eval(u).unwrap();
        for j in 0..=8 {
            let v = f64::from(j) / 8.0;
            let p = cone.eval(u, v).unwrap();
            // A right circular cone: radius proportional to the height below the apex.
            let height = apex.z - p.z;
            assert!((Vector2::new(p.x, p.y).norm() - 1.5 * height / 3.0).abs() < 1e-13);
            assert!((p - c).cross(&(apex - c)).norm() < 1e-12);
            assert!(
                (flat.eval(u, v).unwrap() - (curve.eval(u).unwrap() * (1.0 - v) + apex * v)).norm()
                    < 1e-14
            );
        }
    }
    assert_eq!(
        NurbsSurface::cone(&circle, Vector3::new(f64::INFINITY, 0.0, 0.0))
            .unwrap_err()
            .kind(),
        ErrorKind::NonFinite
    );
}

/// Degenerate axes, normals, frames and other bad input are errors, never NaN.
#[test]
fn degenerate_input_is_an_error() {
    let p = Vector3::new(1.0, 2.0, 3.0);
    assert_eq!(
        Axis::new(p, Vector3::zeros()).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        Axis::new(p, Vector3::new(f64::NAN, 0.0, 1.0))
            .unwrap_err()
            .kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(
        Frame::with_normal(p, Vector3::zeros()).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        Frame::new(p, Vector3::x(), Vector3::x() * 2.0)
            .unwrap_err()
            .kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        Frame::new(p, Vector3::zeros(), Vector3::y())
            .unwrap_err()
            .kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        Frame::new(
            SVector::<f64, 1>::zeros(),
            SVector::<f64, 1>::new(1.0),
            SVector::<f64, 1>::new(1.0)
        )
        .unwrap_err()
        .kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        NurbsSurface::torus(p, Vector3::zeros(), 2.0, 1.0)
            .unwrap_err()
            .kind(),
        ErrorKind::DegenerateGeometry
    );
    let e = NurbsSurface::torus(p, Vector3::z(), 1.0, 1.0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(
        (e.value(), e.interval()),
        (Some(1.0), Some((1.0, f64::INFINITY)))
    );
    assert_eq!(
        NurbsSurface::torus(p, Vector3::z(), 2.0, 0.0)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        NurbsSurface::sphere(p, -1.0).unwrap_err().kind(),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        NurbsSurface::sphere(p, f64::NAN).unwrap_err().kind(),
        ErrorKind::NonFinite
    );
    let frame = Frame::planar(Vector2::zeros());
    assert_eq!(
        NurbsCurve::circle(&frame, 0.0, CircleConstruction::Square)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    for sweep in [0.0, 7.0, -6.3] {
        assert_eq!(
            NurbsCurve::arc(&frame, 1.0, 0.0, sweep).unwrap_err().kind(),
            ErrorKind::InvalidArgument,
            "sweep {sweep}"
        );
    }
    assert_eq!(
        NurbsCurve::arc(&frame, 1.0, 0.0, f64::NAN)
            .unwrap_err()
            .kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(
        NurbsCurve::arc_with_max_piece(&frame, 1.0, 0.0, 1.0, PI)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    let (a, b, c) = (
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 1.0),
        Vector2::new(2.0, 0.0),
    );
    for w in [0.0, -2.0, f64::NAN, f64::INFINITY] {
        assert_eq!(
            NurbsCurve::conic_arc(a, b, c, w).unwrap_err().kind(),
            ErrorKind::InvalidWeight
        );
    }
    assert_eq!(
        NurbsCurve::conic_arc(a, Vector2::new(1.0, 0.0), c, 1.0)
            .unwrap_err()
            .kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        NurbsCurve::conic_arc(a, b, a, 1.0).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        NurbsCurve::conic_shoulder_weight(a, b, c, Vector2::new(3.0, 3.0))
            .unwrap_err()
            .kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        NurbsCurve::conic_shoulder_weight(a, b, c, b)
            .unwrap_err()
            .kind(),
        ErrorKind::DegenerateGeometry
    );
    let profile = NurbsCurve::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 0.0, 1.0)],
        vec![1.0, 1.0],
    )
    .unwrap();
    let axis = Axis::new(Vector3::zeros(), Vector3::z()).unwrap();
    for angle in [0.0, 7.0, f64::NAN] {
        assert!(NurbsSurface::revolution(&profile, &axis, angle).is_err());
    }
}

/// A full revolution uses the 9-point circle; negative angles turn the other way; profile
/// points on the axis stay there.
#[test]
fn revolution_of_a_segment_gives_a_cylinder_and_a_disc() {
    let axis = Axis::new(Vector3::new(0.0, 0.0, -1.0), Vector3::new(0.0, 0.0, 5.0)).unwrap();
    let wall = NurbsCurve::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector3::new(2.0, 0.0, 0.0), Vector3::new(2.0, 0.0, 1.0)],
        vec![1.0, 1.0],
    )
    .unwrap();
    let cyl = NurbsSurface::revolution(&wall, &axis, TAU).unwrap();
    assert_eq!(cyl.net_size(), (2, 9));
    assert_eq!(
        cyl.knots_v().knots(),
        &[
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0
        ]
    );
    let back = NurbsSurface::revolution(&wall, &axis, -FRAC_PI_2).unwrap();
    assert_eq!(back.net_size(), (2, 3));
    assert!((back.eval(0.0, 1.0).unwrap() - Vector3::new(0.0, -2.0, 0.0)).norm() < 1e-15);
    let fwd = NurbsSurface::revolution(&wall, &axis, FRAC_PI_2).unwrap();
    assert!((fwd.eval(0.0, 1.0).unwrap() - Vector3::new(0.0, 2.0, 0.0)).norm() < 1e-15);
    let disc_profile = NurbsCurve::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 0.0, 0.0)],
        vec![1.0, 1.0],
    )
    .unwrap();
    let disc = NurbsSurface::revolution(&disc_profile, &axis, TAU).unwrap();
    for j in 0..9 {
        assert_eq!(disc.control_point(0, j), Vector3::zeros());
    }
    let mut rng = Rng(5);
    for _ in 0..2000 {
        let (u, v) = (rng.next(), rng.next());
        let p = cyl.eval(u, v).unwrap();
        assert!((Vector2::new(p.x, p.y).norm() - 2.0).abs() < 2e-13 * 2.0);
        assert!((p.z - u).abs() < 1e-14);
        let q = disc.eval(u, v).unwrap();
        assert!((q.norm() - u).abs() < 1e-13 && q.z == 0.0);
    }
}

/// Constructions in f32 and with dual numbers: a dual radius gives the derivative of the
/// circle with respect to its radius, the unit radial vector.
fn circle_in<T: Scalar>(tol: f64) {
    let frame = Frame::planar(Vector2::new(cast::<T>(0.5), cast::<T>(-0.25)));
    for construction in CONSTRUCTIONS {
        let c = NurbsCurve::circle(&frame, cast::<T>(1.5), construction).unwrap();
        for i in 0..=200 {
            let p = c.eval(cast::<T>(f64::from(i) / 200.0)).unwrap() - frame.origin();
            assert!((to_f64(p.norm()) - 1.5).abs() <= tol * 1.5);
        }
    }
    let s = NurbsSurface::sphere(
        Vector3::new(cast::<T>(1.0), cast(2.0), cast(3.0)),
        cast::<T>(0.5),
    )
    .unwrap();
    for i in 0..=20 {
        for j in 0..=20 {
            let p = s
                .eval(
                    cast::<T>(f64::from(i) / 20.0),
                    cast::<T>(f64::from(j) / 20.0),
                )
                .unwrap();
            let d = p - Vector3::new(cast::<T>(1.0), cast(2.0), cast(3.0));
            assert!((to_f64(d.norm()) - 0.5).abs() <= tol * 0.5);
        }
    }
}

#[test]
fn constructions_in_f32() {
    circle_in::<f32>(2e-6);
}

#[test]
fn constructions_in_f64() {
    circle_in::<f64>(1e-13);
}

#[test]
fn constructions_in_dual_numbers() {
    circle_in::<Dual64>(1e-13);
    let frame = Frame::planar(Vector2::new(Dual64::from(1.0), Dual64::from(2.0)));
    let c =
        NurbsCurve::circle(&frame, Dual64::new(3.0, 1.0), CircleConstruction::Triangle).unwrap();
    for i in 0..=100 {
        let p = c.eval(Dual64::from(f64::from(i) / 100.0)).unwrap();
        let radial = Vector2::new(p.x.re - 1.0, p.y.re - 2.0) / 3.0;
        assert!((Vector2::new(p.x.eps, p.y.eps) - radial).norm() < 1e-14);
    }
}

/// Structural operations (in homogeneous space) keep every point of a sphere on it.
#[test]
fn structural_operations_keep_a_sphere_on_the_sphere() {
    let s = NurbsSurface::sphere(Vector3::zeros(), 1.0).unwrap();
    let ops = [
        s.insert_knot(Direction::U, 0.3, 2).unwrap(),
        s.refine(Direction::V, &[0.1, 0.6, 0.6]).unwrap(),
        s.elevate_degree(Direction::V, 1).unwrap(),
        s.elevate_degree(Direction::U, 2).unwrap(),
        s.split(Direction::U, 0.4).unwrap().1,
        s.bezier_patches().unwrap()[1][2].clone(),
    ];
    let mut rng = Rng(6);
    for o in &ops {
        let ((a, b), (c, d)) = o.domain();
        for _ in 0..1000 {
            let (u, v) = (a + (b - a) * rng.next(), c + (d - c) * rng.next());
            assert!((o.eval(u, v).unwrap().norm() - 1.0).abs() < 1e-13);
        }
    }
    let k = KnotVector::new(2, vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]).unwrap();
    assert_eq!(ops[0].knots_v(), s.knots_v());
    assert_eq!(s.knots_u(), &k);
}
