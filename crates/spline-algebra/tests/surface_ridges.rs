//! Ridges of parametric surfaces and umbilics at poles, against closed forms (the triaxial
//! ellipsoid's principal sections, the spheroid's poles, the torus, surfaces of revolution
//! through `revolution_features`) and dense sampling of the ridge condition computed
//! independently from `NurbsSurface::derivatives`.

use nalgebra::Vector3;
use spline_algebra::{revolution_features, surface_ridges, umbilics};
use spline_core::KnotVector;
use spline_geom::{Axis, BSpline, NurbsCurve, NurbsSurface};

fn ellipsoid(a: f64, b: f64, c: f64) -> NurbsSurface<f64, 3> {
    NurbsSurface::sphere(Vector3::zeros(), 1.0)
        .unwrap()
        .map_control_points(|p| Vector3::new(a * p.x, b * p.y, c * p.z))
}

#[test]
fn the_ellipsoid_ridges_are_its_principal_sections() {
    let e = ellipsoid(1.5, 2.0, 1.0);
    let r = surface_ridges(&e, 16).unwrap();
    assert!(r.red_constant.is_empty() && r.blue_constant.is_empty());
    assert_eq!(r.umbilics.len(), 4);
    // Every traced point on a coordinate plane; red on z = 0 or x = 0, blue on y = 0 or x = 0
    // (x = 0 holds the umbilics, where its colour changes).
    let mut worst = 0.0f64;
    let mut on = |lines: &[Vec<[f64; 2]>], planes: [usize; 2]| -> Vec<Vector3<f64>> {
        let mut points = Vec::new();
        for p in lines.iter().flatten() {
            let x = e.eval(p[0], p[1]).unwrap();
            let d = x[planes[0]].abs().min(x[planes[1]].abs());
            worst = worst.max(d);
            points.push(x);
        }
        points
    };
    let red_count = on(&r.red, [2, 0]).len();
    let blue_count = on(&r.blue, [1, 0]).len();
    println!(
        "ellipsoid: {red_count} red, {blue_count} blue points, worst distance to its planes {worst:.2e}"
    );
    assert!(worst < 2e-6, "a ridge point is {worst} off its planes");
    // Every principal section covered (points every 1/200 of a turn).
    // Within 0.01 of a chord of a traced polyline (the chords are at most a sixteenth of a
    // patch: their sagitta is below 0.003).
    let chords = |lines: &[Vec<[f64; 2]>]| -> Vec<(Vector3<f64>, Vector3<f64>)> {
        lines
            .iter()
            .flat_map(|l| {
                l.windows(2).map(|w| {
                    (
                        e.eval(w[0][0], w[0][1]).unwrap(),
                        e.eval(w[1][0], w[1][1]).unwrap(),
                    )
                })
            })
            .collect()
    };
    let (red, blue) = (chords(&r.red), chords(&r.blue));
    let covered = |target: Vector3<f64>, segments: &[(Vector3<f64>, Vector3<f64>)]| {
        segments.iter().any(|(a, b)| {
            let d = b - a;
            let t = if d.norm_squared() > 0.0 {
                ((target - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (a + d * t - target).norm() < 0.01
        })
    };
    let mut gaps = 0;
    for k in 0..200 {
        let t = std::f64::consts::TAU * k as f64 / 200.0;
        let (c, s) = (t.cos(), t.sin());
        // z = 0: red; y = 0: blue; x = 0: red near the poles, blue near y = ±2.
        let equator = Vector3::new(1.5 * c, 2.0 * s, 0.0);
        let xz = Vector3::new(1.5 * c, 0.0, s);
        let yz = Vector3::new(0.0, 2.0 * c, s);
        gaps += usize::from(!covered(equator, &red));
        gaps += usize::from(!covered(xz, &blue));
        let mut both = red.clone();
        both.extend(&blue);
        gaps += usize::from(!covered(yz, &both));
    }
    assert_eq!(
        gaps, 0,
        "principal-section points without a traced ridge point nearby"
    );
}

#[test]
fn umbilics_at_poles() {
    let spheroid = ellipsoid(1.5, 1.5, 1.0);
    let u = umbilics(&spheroid).unwrap();
    assert!(u.points.is_empty() && !u.not_isolated);
    assert_eq!(u.poles.len(), 2);
    for p in &u.poles {
        let x = spheroid.eval(p[0], p[1]).unwrap();
        assert!((x.z.abs() - 1.0).abs() < 1e-14 && x.x.abs() < 1e-14 && x.y.abs() < 1e-14);
    }
    // The triaxial ellipsoid: four, none at its poles.
    let u = umbilics(&ellipsoid(1.5, 2.0, 1.0)).unwrap();
    assert_eq!((u.points.len(), u.poles.len()), (4, 0));
    // A spheroid that is almost one: 1e-6 apart is not umbilic at the poles.
    let u = umbilics(&ellipsoid(1.5, 1.5 * (1.0 + 1e-6), 1.0)).unwrap();
    assert_eq!(u.poles.len(), 0);
    // The sphere: umbilic everywhere.
    let u = umbilics(&NurbsSurface::sphere(Vector3::zeros(), 2.0).unwrap()).unwrap();
    assert!(u.not_isolated && u.poles.is_empty());
}

#[test]
fn the_torus_has_constant_curvature_along_both_families() {
    let torus = NurbsSurface::torus(Vector3::zeros(), Vector3::z(), 2.0, 1.0).unwrap();
    let r = surface_ridges(&torus, 8).unwrap();
    assert!(r.red.is_empty() && r.blue.is_empty());
    assert_eq!(r.red_constant.len(), 16);
    assert_eq!(r.blue_constant.len(), 16);
}

/// The surface of revolution of `f(z)` about the z axis, with the profile parameter `z`.
fn revolved(f: &BSpline<f64, f64>) -> NurbsSurface<f64, 3> {
    let knots = f.knots().clone();
    let p = knots.degree();
    let points: Vec<Vector3<f64>> = f
        .control_points()
        .iter()
        .enumerate()
        .map(|(i, &r)| {
            let z = (1..=p).map(|k| knots.knots()[i + k]).sum::<f64>() / p as f64;
            Vector3::new(r, 0.0, z)
        })
        .collect();
    let n = points.len();
    let profile = NurbsCurve::new(knots, points, vec![1.0; n]).unwrap();
    NurbsSurface::revolution(
        &profile,
        &Axis::new(Vector3::zeros(), Vector3::z()).unwrap(),
        std::f64::consts::TAU,
    )
    .unwrap()
}

#[test]
fn ridge_circles_of_a_surface_of_revolution() {
    // f(z) = 1 + 1.5z² + 0.2z³ on [−½, ½] (Bézier form): the meridian curvature stays
    // above the parallel one (no circle of umbilics, where the colours would swap); one
    // ridge circle near z = 0.
    let knots = KnotVector::new(3, vec![-0.5, -0.5, -0.5, -0.5, 0.5, 0.5, 0.5, 0.5]).unwrap();
    let f = BSpline::new(knots, vec![1.35, 0.9, 0.85, 1.4]).unwrap();
    let expected = revolution_features(&f, 1e-13).unwrap().ridges;
    assert_eq!(expected.len(), 1);
    let s = revolved(&f);
    let r = surface_ridges(&s, 8).unwrap();
    // The parallels are lines of curvature along which their curvature is constant (reported
    // as constant regions); the ridges of the meridians' curvature are the circles (of either
    // colour: the colours swap where the two curvatures cross, on circles of umbilics).
    assert!(!r.red_constant.is_empty() || !r.blue_constant.is_empty());
    let mut lines = r.red.clone();
    lines.extend(r.blue.iter().cloned());
    let mut worst = 0.0f64;
    for p in lines.iter().flatten() {
        let d = expected
            .iter()
            .map(|c| (c.z - p[0]).abs())
            .fold(f64::INFINITY, f64::min);
        worst = worst.max(d);
    }
    println!(
        "revolution: {} lines, worst |u − z| {worst:.2e}",
        lines.len()
    );
    assert!(worst < 1e-9);
    for c in &expected {
        assert!(
            lines.iter().flatten().any(|p| (p[0] - c.z).abs() < 1e-9),
            "circle z = {} missed",
            c.z
        );
    }
}
