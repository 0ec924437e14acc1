//! Surface–surface intersection curves as B-splines (issue 25 item 9): the curve in space and
//! both parameter-space images against closed forms (circles on a sphere) and against the
//! surfaces themselves (S_A(p_A(t)) = S_B(p_B(t)) = C(t) within the tolerance), pieces at the
//! seam of a closed surface, and the errors.

use nalgebra::{Vector2, Vector3};
use spline_core::KnotVector;
use spline_fit::{IntersectionSpline, Tolerances, intersect_surfaces, intersection_splines};
use spline_geom::{BSpline, ErrorKind, NurbsSurface, ParamSurface, Surface};

type V3 = Vector3<f64>;

fn plane(corners: [[f64; 3]; 4]) -> Surface<f64, V3> {
    let [a, b, c, d] = corners.map(V3::from);
    Surface::bezier(vec![vec![a, b], vec![c, d]]).unwrap()
}

/// The largest distance, at 400 parameters, between the curve, the first surface at the
/// first image and the second surface at the second image.
fn consistency<A, B>(a: &A, b: &B, piece: &IntersectionSpline<f64>) -> f64
where
    A: ParamSurface<f64, Point = V3>,
    B: ParamSurface<f64, Point = V3>,
{
    let at = |s: &dyn Fn(f64, f64) -> V3, p: &BSpline<f64, Vector2<f64>>, t: f64| {
        let q = p.eval(t).unwrap();
        s(q.x, q.y)
    };
    (0..=400)
        .map(|k| {
            let t = f64::from(k) / 400.0;
            let c = piece.curve.eval(t).unwrap();
            let on_a = at(&|u, v| a.eval(u, v).unwrap(), &piece.pcurve_a, t);
            let on_b = at(&|u, v| b.eval(u, v).unwrap(), &piece.pcurve_b, t);
            (c - on_a).norm().max((c - on_b).norm())
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_horizontal_circle_on_a_sphere_is_one_closed_cubic() {
    let sphere = NurbsSurface::sphere(V3::zeros(), 2.0).unwrap();
    let cut = plane([
        [-3.0, -3.0, 1.0],
        [-3.0, 3.0, 1.0],
        [3.0, -3.0, 1.0],
        [3.0, 3.0, 1.0],
    ]);
    let traced = intersect_surfaces(&sphere, &cut, &Tolerances::default()).unwrap();
    assert_eq!(traced.len(), 1);
    for tolerance in [1e-5, 1e-8] {
        let pieces = intersection_splines(&sphere, &cut, &traced[0], tolerance).unwrap();
        assert_eq!(pieces.len(), 1, "one piece at {tolerance:e}");
        let piece = &pieces[0];
        assert!(piece.max_error <= tolerance, "{:e}", piece.max_error);
        assert_eq!(piece.curve.degree(), 3);
        // The circle of radius √3 at z = 1, closed.
        for k in 0..=1000 {
            let p = piece.curve.eval(f64::from(k) / 1000.0).unwrap();
            let off = (p.xy().norm() - 3f64.sqrt()).abs().max((p.z - 1.0).abs());
            assert!(off <= tolerance, "{tolerance:e}: {off:e}");
        }
        let ends = piece.curve.eval(0.0).unwrap() - piece.curve.eval(1.0).unwrap();
        assert!(ends.norm() <= tolerance);
        assert!(consistency(&sphere, &cut, piece) <= 2.0 * tolerance);
    }
    let e = intersection_splines(&sphere, &cut, &traced[0], 0.0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidTolerance);
    let e = intersection_splines(&sphere, &cut, &traced[0], f64::NAN).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidTolerance);
}

#[test]
fn a_circle_across_the_seam_comes_in_pieces_that_meet() {
    // The plane x = 1 cuts the unit-radius-2 sphere in a circle through its seam meridian.
    let sphere = NurbsSurface::sphere(V3::zeros(), 2.0).unwrap();
    let cut = plane([
        [1.0, -3.0, -3.0],
        [1.0, -3.0, 3.0],
        [1.0, 3.0, -3.0],
        [1.0, 3.0, 3.0],
    ]);
    let traced = intersect_surfaces(&sphere, &cut, &Tolerances::default()).unwrap();
    let tolerance = 1e-7;
    let mut pieces = Vec::new();
    for curve in &traced {
        pieces.extend(intersection_splines(&sphere, &cut, curve, tolerance).unwrap());
    }
    assert!(!pieces.is_empty());
    let mut length = 0.0;
    for piece in &pieces {
        assert!(piece.max_error <= tolerance, "{:e}", piece.max_error);
        assert!(consistency(&sphere, &cut, piece) <= 2.0 * tolerance);
        let mut previous = piece.curve.eval(0.0).unwrap();
        for k in 1..=2000 {
            let p = piece.curve.eval(f64::from(k) / 2000.0).unwrap();
            let radius = (p.y * p.y + p.z * p.z).sqrt();
            assert!((p.x - 1.0).abs() <= tolerance && (radius - 3f64.sqrt()).abs() <= tolerance);
            length += (p - previous).norm();
            previous = p;
        }
        // Each image stays inside its surface's domain (no jump smeared across it).
        for k in 0..=200 {
            let q = piece.pcurve_a.eval(f64::from(k) / 200.0).unwrap();
            assert!((-1e-9..=1.0 + 1e-9).contains(&q.x) && (-1e-9..=1.0 + 1e-9).contains(&q.y));
        }
    }
    // Together the pieces are the whole circle, once.
    let circumference = 2.0 * std::f64::consts::PI * 3f64.sqrt();
    assert!(
        (length - circumference).abs() < 1e-5,
        "{length} / {circumference}"
    );
}

#[test]
fn a_wavy_bicubic_against_a_tilted_plane_agrees_with_both_surfaces() {
    let k = KnotVector::clamped(3, 0.0, 1.0, &[0.3, 0.6]).unwrap();
    let n = k.num_basis();
    let heights = [0.3, -0.2, 0.5, -0.4, 0.1, 0.2, -0.3, 0.4, -0.1, 0.3];
    let points = (0..n * n)
        .map(|i| {
            V3::new(
                (i / n) as f64 * 4.0 / (n - 1) as f64,
                (i % n) as f64 * 4.0 / (n - 1) as f64,
                heights[(3 * i) % heights.len()],
            )
        })
        .collect();
    let wavy = Surface::new(k.clone(), k, points).unwrap();
    let tilted = plane([
        [-1.0, -1.0, -0.3],
        [-1.0, 5.0, 0.3],
        [5.0, -1.0, -0.1],
        [5.0, 5.0, 0.5],
    ]);
    let traced = intersect_surfaces(&wavy, &tilted, &Tolerances::default()).unwrap();
    assert!(!traced.is_empty());
    for curve in &traced {
        for piece in intersection_splines(&wavy, &tilted, curve, 1e-6).unwrap() {
            assert!(piece.max_error <= 1e-6, "{:e}", piece.max_error);
            assert!(consistency(&wavy, &tilted, &piece) <= 2e-6);
            // The ends are the traced ends.
            let first = piece.curve.eval(0.0).unwrap();
            assert!(curve.points.iter().any(|p| (p - first).norm() < 1e-9));
        }
    }
}

/// The same circle at every scale from 1e-300 to 1e300: the traced curve and its B-splines
/// scale with the surfaces (before, no curve was found at 1e-150 and beyond, and at 1e150 the
/// trace ran out of points).
#[test]
fn the_circle_at_other_scales() {
    for scale in [1e-300, 1e-150, 1e-3, 1e3, 1e150, 1e300] {
        let sphere = NurbsSurface::sphere(V3::zeros(), 2.0 * scale).unwrap();
        let cut = plane([
            [-3.0 * scale, -3.0 * scale, scale],
            [-3.0 * scale, 3.0 * scale, scale],
            [3.0 * scale, -3.0 * scale, scale],
            [3.0 * scale, 3.0 * scale, scale],
        ]);
        let traced = intersect_surfaces(&sphere, &cut, &Tolerances::default()).unwrap();
        assert_eq!(traced.len(), 1, "{scale:e}");
        assert!(traced[0].closed, "{scale:e}");
        let tolerance = 1e-6 * scale;
        let pieces = intersection_splines(&sphere, &cut, &traced[0], tolerance).unwrap();
        assert_eq!(pieces.len(), 1, "{scale:e}");
        assert!(pieces[0].max_error <= tolerance, "{scale:e}");
        for k in 0..=100 {
            let p = pieces[0].curve.eval(f64::from(k) / 100.0).unwrap() / scale;
            let off = (p.xy().norm() - 3f64.sqrt()).abs().max((p.z - 1.0).abs());
            assert!(off <= 1e-6, "{scale:e}: {off:e}");
        }
    }
}
