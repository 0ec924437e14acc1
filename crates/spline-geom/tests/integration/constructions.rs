//! The curve constructions of seed 004 §5.2 and §6 checked for exactness: every sampled point
//! of a circle at the exact radius, curvature 1/r, the control data of the notes, conics of the
//! right type, circular arcs (the surfaces are in `constructions_surfaces`).

use nalgebra::{Vector2, Vector3};
use proptest::prelude::*;
use spline_core::ErrorKind;
use spline_geom::{Axis, CircleConstruction, ConicKind, Frame, NurbsCurve, NurbsSurface};
use std::f64::consts::{FRAC_PI_2, PI, SQRT_2, TAU};

/// A deterministic stream of numbers in [0, 1) (`SplitMix64`), for thousands of parameters.
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    pub(crate) fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

pub(crate) const CONSTRUCTIONS: [CircleConstruction; 2] =
    [CircleConstruction::Square, CircleConstruction::Triangle];

#[test]
fn circles_lie_at_the_exact_radius_with_curvature_one_over_r() {
    let mut rng = Rng(1);
    for construction in CONSTRUCTIONS {
        for (center, r) in [
            (Vector2::new(0.0, 0.0), 1.0),
            (Vector2::new(3.0, -2.0), 0.37),
            (Vector2::new(-1e3, 5e2), 250.0),
        ] {
            let c = NurbsCurve::circle(&Frame::planar(center), r, construction).unwrap();
            let mut worst: f64 = 0.0;
            let mut worst_k: f64 = 0.0;
            for _ in 0..5000 {
                let u = rng.next();
                let p = c.eval(u).unwrap();
                worst = worst.max(((p - center).norm() - r).abs() / r);
                worst_k = worst_k.max((c.signed_curvature(u).unwrap() * r - 1.0).abs());
                assert!((c.curvature_magnitude(u).unwrap() * r - 1.0).abs() < 1e-12);
            }
            assert!(
                worst <= 1e-13,
                "{construction:?} r = {r}: radius error {worst:e}"
            );
            assert!(
                worst_k <= 1e-12,
                "{construction:?} r = {r}: curvature error {worst_k:e}"
            );
            // Knots and domain ends.
            for u in c.knots().knots() {
                assert!((((c.eval(*u).unwrap() - center).norm() - r) / r).abs() <= 1e-15);
            }
        }
    }
}

#[test]
fn circles_in_space_lie_on_their_sphere_and_plane() {
    let mut rng = Rng(2);
    for construction in CONSTRUCTIONS {
        for _ in 0..20 {
            let center = Vector3::new(
                rng.next() * 10.0 - 5.0,
                rng.next() * 10.0 - 5.0,
                rng.next() * 10.0 - 5.0,
            );
            let normal = Vector3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5);
            let r = 0.1 + rng.next() * 5.0;
            let frame = Frame::with_normal(center, normal).unwrap();
            let c = NurbsCurve::circle(&frame, r, construction).unwrap();
            let n = normal.normalize();
            for _ in 0..500 {
                let u = rng.next();
                let p = c.eval(u).unwrap();
                assert!(((p - center).norm() - r).abs() / r <= 1e-13);
                assert!((p - center).dot(&n).abs() / r <= 1e-13);
                assert!((c.curvature_magnitude(u).unwrap() * r - 1.0).abs() <= 1e-12);
            }
            // Counter-clockwise about the normal: x × y = n.
            assert!((frame.x_axis().cross(&frame.y_axis()) - n).norm() < 1e-15);
            let d = c.derivatives(0.0, 1).unwrap()[1];
            assert!(frame.y_axis().dot(&d) > 0.0);
        }
    }
}

/// The control data of the notes: (6.9), (6.10) for the square; the triangle with weights
/// [1, ½, 1, ½, 1, ½, 1]; control points on the square (corners at r√2, side midpoints at r)
/// and on the equilateral triangle (vertices at 2r, side midpoints at r, sides tangent).
#[test]
fn the_two_circles_of_the_notes() {
    let r = 2.0;
    let square = NurbsCurve::circle(
        &Frame::planar(Vector2::zeros()),
        r,
        CircleConstruction::Square,
    )
    .unwrap();
    assert_eq!(
        square.knots().knots(),
        &[
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0
        ]
    );
    let s = SQRT_2 / 2.0;
    for (w, e) in square
        .weights()
        .iter()
        .zip([1.0, s, 1.0, s, 1.0, s, 1.0, s, 1.0])
    {
        assert!((w - e).abs() < 1e-16);
    }
    let pts = square.control_points();
    assert_eq!(pts.len(), 9);
    assert_eq!(pts[0], pts[8]);
    for (i, p) in pts.iter().enumerate() {
        let expected = if i % 2 == 1 { r * SQRT_2 } else { r };
        assert!((p.norm() - expected).abs() < 1e-14, "point {i}");
        assert!(
            (p.x.abs().max(p.y.abs()) - r).abs() < 1e-15,
            "point {i} on the square"
        );
    }

    let triangle = NurbsCurve::circle(
        &Frame::planar(Vector2::zeros()),
        r,
        CircleConstruction::Triangle,
    )
    .unwrap();
    let k = triangle.knots().knots();
    assert_eq!(k.len(), 10);
    for (x, e) in k.iter().zip([
        0.0,
        0.0,
        0.0,
        1.0 / 3.0,
        1.0 / 3.0,
        2.0 / 3.0,
        2.0 / 3.0,
        1.0,
        1.0,
        1.0,
    ]) {
        assert!((x - e).abs() < 1e-16);
    }
    assert_eq!(triangle.weights(), vec![1.0, 0.5, 1.0, 0.5, 1.0, 0.5, 1.0]);
    let pts = triangle.control_points();
    for (i, p) in pts.iter().enumerate() {
        let expected = if i % 2 == 1 { 2.0 * r } else { r };
        assert!((p.norm() - expected).abs() < 1e-14, "point {i}");
    }
    // Each side runs from vertex to vertex through a tangency point, perpendicular to the radius there.
    for i in (1..6).step_by(2) {
        let (a, b) = (pts[i], pts[(i + 2) % 6]);
        let m = pts[i + 1];
        assert!(((a + b) / 2.0 - m).norm() < 1e-14);
        assert!((b - a).dot(&m) < 1e-13);
        assert!(((b - a).norm() - 2.0 * r * 3f64.sqrt()).abs() < 1e-13); // side of the triangle
    }
}

/// Both circles are traversed once, counter-clockwise: the polar angle increases with u
/// and turns by 2π.
#[test]
fn circles_turn_once() {
    for construction in CONSTRUCTIONS {
        let c = NurbsCurve::circle(&Frame::planar(Vector2::zeros()), 1.0, construction).unwrap();
        let mut total = 0.0;
        let mut last = c.eval(0.0).unwrap();
        for i in 1..=1000 {
            let p = c.eval(f64::from(i) / 1000.0).unwrap();
            let step = last.x * p.y - last.y * p.x;
            assert!(step > 0.0);
            total += step.atan2(last.dot(&p));
            last = p;
        }
        assert!((total - TAU).abs() < 1e-12);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Arcs of any sweep and start, with 90° or 120° pieces: at the radius, from the start
    /// angle to the end angle, the angle monotone in u.
    #[test]
    fn arcs_of_any_sweep(start in -7.0f64..7.0, sweep in -TAU..TAU, r in 0.01f64..100.0, third in any::<bool>()) {
        prop_assume!(sweep.abs() > 1e-6);
        let max_piece = if third { TAU / 3.0 } else { FRAC_PI_2 };
        let c = NurbsCurve::arc_with_max_piece(&Frame::planar(Vector2::new(1.0, 2.0)), r, start, sweep, max_piece).unwrap();
        let pieces = ((sweep.abs() / max_piece) * (1.0 - 1e-12)).ceil().max(1.0) as usize;
        prop_assert_eq!(c.len(), 2 * pieces + 1);
        for w in c.weights().iter().skip(1).step_by(2) {
            prop_assert!((w - (sweep / pieces as f64 / 2.0).cos()).abs() < 1e-15);
        }
        let at = |u: f64| c.eval(u).unwrap() - Vector2::new(1.0, 2.0);
        prop_assert!((at(0.0) - Vector2::new(start.cos(), start.sin()) * r).norm() < 1e-13 * r);
        let end = start + sweep;
        prop_assert!((at(1.0) - Vector2::new(end.cos(), end.sin()) * r).norm() < 1e-13 * r);
        let mut total = 0.0;
        let mut last = at(0.0);
        for i in 1..=400 {
            let p = at(f64::from(i) / 400.0);
            prop_assert!((p.norm() - r).abs() <= 1e-13 * r);
            let step = (last.x * p.y - last.y * p.x).atan2(last.dot(&p));
            prop_assert!(step * sweep.signum() > 0.0);
            total += step;
            last = p;
        }
        prop_assert!((total - sweep).abs() < 1e-11);
    }

    /// Conic arcs (6.6): the type of Proposition 6.1, checked on the implicit equation
    /// through sampled points; (6.7) recovers w1 from the shoulder point; the end tangents
    /// are P0P1 and P1P2.
    #[test]
    fn conic_arcs_have_the_type_of_proposition_6_1(x1 in -2.0f64..2.0, y1 in 0.5f64..3.0, x2 in 0.5f64..3.0, w1 in 0.05f64..5.0) {
        let (p0, p1, p2) = (Vector2::new(0.0, 0.0), Vector2::new(x1, y1), Vector2::new(x2, 0.0));
        let arc = NurbsCurve::conic_arc(p0, p1, p2, w1).unwrap();
        let kind = arc.conic_kind().unwrap();
        prop_assert_eq!(kind, if w1 < 1.0 { ConicKind::Ellipse } else if w1 > 1.0 { ConicKind::Hyperbola } else { ConicKind::Parabola });
        // Implicit conic A x² + B xy + C y² + D x + E y + F = 0 through 5 points (null vector
        // of the 5 × 6 system), then the sign of B² − 4AC.
        let rows: Vec<[f64; 6]> = [0.1, 0.3, 0.5, 0.7, 0.9].iter().map(|&u| {
            let p = arc.eval(u).unwrap();
            [p.x * p.x, p.x * p.y, p.y * p.y, p.x, p.y, 1.0]
        }).collect();
        let m = nalgebra::DMatrix::from_fn(6, 6, |i, j| if i < 5 { rows[i][j] } else { 0.0 });
        let svd = m.svd(true, true);
        let v_t = svd.v_t.unwrap();
        let (imin, _) = svd.singular_values.iter().enumerate().fold((0, f64::MAX), |best, (i, &s)| if s < best.1 { (i, s) } else { best });
        let q: Vec<f64> = v_t.row(imin).iter().copied().collect();
        let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        let disc = (q[1] * q[1] - 4.0 * q[0] * q[2]) / (norm * norm);
        for i in 0..=20 {
            let p = arc.eval(f64::from(i) / 20.0).unwrap();
            let value = q[0] * p.x * p.x + q[1] * p.x * p.y + q[2] * p.y * p.y + q[3] * p.x + q[4] * p.y + q[5];
            prop_assert!(value.abs() / norm < 1e-9);
        }
        if (w1 - 1.0).abs() > 0.05 {
            prop_assert_eq!(disc < 0.0, w1 < 1.0, "w1 = {}, B² − 4AC = {}", w1, disc);
        }
        let s = arc.eval(0.5).unwrap();
        let w = NurbsCurve::conic_shoulder_weight(p0, p1, p2, s).unwrap();
        prop_assert!((w - w1).abs() < 1e-12 * (1.0 + w1));
        let through = NurbsCurve::conic_arc_through(p0, p1, p2, s).unwrap();
        prop_assert!((through.eval(0.3).unwrap() - arc.eval(0.3).unwrap()).norm() < 1e-12);
        // R'(0) = 2 w1 (P1 − P0) and R'(1) = 2 w1 (P2 − P1) (the end derivatives of §6).
        prop_assert!((arc.derivatives(0.0, 1).unwrap()[1] - (p1 - p0) * (2.0 * w1)).norm() < 1e-12 * (1.0 + w1));
        prop_assert!((arc.derivatives(1.0, 1).unwrap()[1] - (p2 - p1) * (2.0 * w1)).norm() < 1e-12 * (1.0 + w1));
    }

    /// Revolution of a random rational, non-planar profile about a random axis through a
    /// random angle: each point is the profile point rotated rigidly about the axis.
    #[test]
    fn revolution_rotates_the_profile(seed in 0u64..1_000_000, angle_fraction in -1.0f64..1.0) {
        prop_assume!(angle_fraction.abs() > 1e-3);
        let mut rng = Rng(seed);
        let mut rand3 = || Vector3::new(rng.next() * 4.0 - 2.0, rng.next() * 4.0 - 2.0, rng.next() * 4.0 - 2.0);
        let profile = NurbsCurve::from_knots(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.4, 0.7, 1.0, 1.0, 1.0, 1.0],
            (0..6).map(|_| rand3()).collect(),
            vec![1.0, 0.4, 2.0, 1.3, 0.7, 1.0],
        ).unwrap();
        let axis = Axis::new(rand3(), rand3()).unwrap();
        let angle = TAU * angle_fraction;
        let s = NurbsSurface::revolution(&profile, &axis, angle).unwrap();
        prop_assert_eq!(s.degrees(), (3, 2));
        let a = axis.direction();
        let mut last_angle = [0.0; 11];
        for j in 0..=10 {
            let v = f64::from(j) / 10.0;
            let mut turn: Option<f64> = None;
            for (i, last) in last_angle.iter_mut().enumerate() {
                let u = i as f64 / 10.0;
                let (c, p) = (profile.eval(u).unwrap(), s.eval(u, v).unwrap());
                let (oc, op) = (axis.project(&c), axis.project(&p));
                let (rc, rp) = (c - oc, p - op);
                // Same height along the axis, same distance from it.
                prop_assert!((oc - op).norm() < 1e-12);
                prop_assert!((rc.norm() - rp.norm()).abs() < 1e-12 * (1.0 + rc.norm()));
                // The same rotation angle for every u: a rigid rotation.
                if rc.norm() > 1e-3 {
                    let phi = a.dot(&rc.cross(&rp)).atan2(rc.dot(&rp));
                    let phi = if (phi - *last).abs() > PI { phi + TAU * (*last - phi).signum() } else { phi };
                    *last = phi;
                    if let Some(t) = turn {
                        prop_assert!((t - phi).abs() < 1e-10, "u = {}, v = {}: {} vs {}", u, v, t, phi);
                    }
                    turn = Some(phi);
                }
            }
            if j == 10 {
                if let Some(t) = turn {
                    let expected = if angle.abs() > PI + 1e-9 { angle - TAU * angle.signum() } else { angle };
                    prop_assert!((t - expected).abs() < 1e-9 || (t - angle).abs() < 1e-9, "turn {} vs angle {}", t, angle);
                }
            }
        }
        // At v = 0 the surface is the profile.
        for i in 0..=10 {
            let u = f64::from(i) / 10.0;
            prop_assert!((s.eval(u, 0.0).unwrap() - profile.eval(u).unwrap()).norm() < 1e-12);
        }
    }
}

/// Seed 004 (6.8): w1 = cos θ with θ = angle P1 P0 P2: θ = π/4 gives w1 = √2/2, θ = π/3
/// gives w1 = ½; the arcs are circular (equidistant from the center of the circle tangent
/// to P0P1 at P0).
#[test]
fn circular_arcs_from_isosceles_polygons() {
    for (theta, w1) in [
        (PI / 4.0, SQRT_2 / 2.0),
        (PI / 3.0, 0.5),
        (0.2, 0.2f64.cos()),
        (1.4, 1.4f64.cos()),
    ] {
        // The polygon of the unit circle: P0 and P2 at angles 0 and 2θ, P1 where the
        // tangents meet.
        let p0 = Vector2::new(1.0, 0.0);
        let p2 = Vector2::new((2.0 * theta).cos(), (2.0 * theta).sin());
        let p1 = Vector2::new(1.0, theta.tan());
        let arc = NurbsCurve::circular_arc_from_polygon(p0, p1, p2).unwrap();
        assert!((arc.weights()[1] - w1).abs() < 1e-15, "θ = {theta}");
        assert_eq!(arc.conic_kind(), Some(ConicKind::Ellipse));
        for i in 0..=1000 {
            let p = arc.eval(f64::from(i) / 1000.0).unwrap();
            assert!((p.norm() - 1.0).abs() < 1e-14);
        }
    }
    // Not isosceles, or flat.
    let e = NurbsCurve::circular_arc_from_polygon(
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 1.0),
        Vector2::new(3.0, 0.0),
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::DegenerateGeometry);
    let e = NurbsCurve::circular_arc_from_polygon(
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 0.0),
        Vector2::new(2.0, 0.0),
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::DegenerateGeometry);
    // A sweep or a piece outside its range says which value and which range, in fields.
    let frame = Frame::planar(Vector2::zeros());
    let e = NurbsCurve::arc(&frame, 1.0, 0.0, 7.0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!((e.value(), e.interval()), (Some(7.0), Some((-TAU, TAU))));
    let e = NurbsCurve::arc_with_max_piece(&frame, 1.0, 0.0, 1.0, 4.0).unwrap_err();
    assert_eq!((e.value(), e.interval()), (Some(4.0), Some((0.0, PI))));
}
