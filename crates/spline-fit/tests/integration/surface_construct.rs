//! Surfaces through curves: skinning, sweeps, Coons and Gordon surfaces, interpolation with
//! boundary derivatives; rotation-minimising frames against the helix's closed form.

// Grid indices become coordinates: small integer counts, exact as f64.
#![allow(clippy::cast_lossless)]

use nalgebra::Vector3;
use spline_core::KnotVector;
use spline_fit::{
    Parametrization, SurfaceEnds, gordon, interpolate_surface_with_derivatives, skin, sweep,
};
use spline_geom::{
    BSpline, ErrorKind, Frame, Homogeneous, NurbsCurve, NurbsSurface, Surface,
    rotation_minimizing_frames,
};

type V3 = Vector3<f64>;

fn lcg(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn random_curve(rand: &mut impl FnMut() -> f64, p: usize, n: usize, z: f64) -> BSpline<f64, V3> {
    let interior: Vec<f64> = {
        let mut k: Vec<f64> = (0..n - p - 1).map(|_| 0.05 + 0.9 * rand()).collect();
        k.sort_by(f64::total_cmp);
        k
    };
    let knots = KnotVector::clamped(
        p,
        0.0,
        2.0 + rand(),
        &interior.iter().map(|x| x * 2.0).collect::<Vec<_>>(),
    )
    .unwrap();
    let pts = (0..n)
        .map(|i| V3::new(i as f64 + 0.3 * rand(), rand(), z + 0.3 * rand()))
        .collect();
    BSpline::new(knots, pts).unwrap()
}

/// Sections of different degrees, knots and domains: the skinned surface contains each one
/// exactly (sections are compared at their own parameters, mapped onto the common domain).
#[test]
fn skinning_interpolates_the_sections() {
    let mut rand = lcg(11);
    for case in 0..10 {
        let sections: Vec<_> = (0..3 + case % 3)
            .map(|k| {
                let z = k as f64 * (1.0 + rand());
                random_curve(&mut rand, 1 + (k + case) % 3, 5 + k % 3, z)
            })
            .collect();
        let skinned = skin(&sections, 3, None).unwrap();
        let s = &skinned.surface;
        let ((a, b), _) = s.domain();
        assert_eq!(skinned.params.len(), sections.len());
        for (c, &v) in sections.iter().zip(&skinned.params) {
            let (c0, c1) = c.domain();
            let mut worst: f64 = 0.0;
            for j in 0..=100 {
                let t = j as f64 / 100.0;
                let on_surface = s.eval(a + (b - a) * t, v).unwrap();
                worst = worst.max((on_surface - c.eval(c0 + (c1 - c0) * t).unwrap()).norm());
            }
            assert!(worst < 1e-12, "case {case}: section off by {worst}");
        }
    }
}

/// Circles of different radii and heights, skinned as NURBS (homogeneous sections): the
/// surface passes through the circles exactly (a closed form: radius and height).
#[test]
fn skinning_rational_sections() {
    let circle = |r: f64, z: f64| {
        NurbsCurve::circle(
            &Frame::with_normal(V3::new(0.0, 0.0, z), V3::new(0.0, 0.0, 1.0)).unwrap(),
            r,
            spline_geom::CircleConstruction::Square,
        )
        .unwrap()
    };
    let circles = [
        circle(1.0, 0.0),
        circle(2.0, 1.0),
        circle(1.5, 2.5),
        circle(0.5, 3.0),
    ];
    let sections: Vec<BSpline<f64, Homogeneous<f64, 3>>> =
        circles.iter().map(|c| c.homogeneous().clone()).collect();
    let skinned = skin(&sections, 2, None).unwrap();
    let s = NurbsSurface::from_homogeneous(skinned.surface).unwrap();
    for ((r, z), &v) in [(1.0, 0.0), (2.0, 1.0), (1.5, 2.5), (0.5, 3.0)]
        .iter()
        .zip(&skinned.params)
    {
        for j in 0..=64 {
            let p = s.eval(j as f64 / 64.0, v).unwrap();
            assert!((V3::new(p.x, p.y, 0.0).norm() - r).abs() < 1e-12);
            assert!((p.z - z).abs() < 1e-12);
        }
    }
}

/// A network cut from a known bicubic surface along iso-curves: the Gordon surface
/// reproduces every curve of the network (and the surface, which lies in its space).
#[test]
fn gordon_reproduces_the_network() {
    let mut rand = lcg(5);
    let ku = KnotVector::clamped(3, 0.0, 1.0, &[0.4]).unwrap();
    let kv = KnotVector::clamped(3, 0.0, 1.0, &[0.3, 0.7]).unwrap();
    let net: Vec<V3> = (0..ku.num_basis() * kv.num_basis())
        .map(|k| {
            V3::new(
                (k / kv.num_basis()) as f64,
                (k % kv.num_basis()) as f64,
                rand() - 0.5,
            )
        })
        .collect();
    let base = Surface::new(ku, kv, net).unwrap();
    let (us, vs) = ([0.0, 0.25, 0.6, 1.0], [0.0, 0.2, 0.5, 0.8, 1.0]);
    let u_curves: Vec<_> = vs.iter().map(|&v| base.curve_at_v(v).unwrap()).collect();
    let v_curves: Vec<_> = us.iter().map(|&u| base.curve_at_u(u).unwrap()).collect();
    let g = gordon(&u_curves, &v_curves, (3, 3), 1e-9).unwrap();
    for (a, b) in g.params_u.iter().zip(&us) {
        assert!((a - b).abs() < 1e-9, "crossing parameter {a} vs {b}");
    }
    assert!(g.crossing_gap < 1e-12);
    let mut worst: f64 = 0.0;
    for j in 0..=50 {
        let t = j as f64 / 50.0;
        for (c, &v) in u_curves.iter().zip(&g.params_v) {
            worst = worst.max((g.surface.eval(t, v).unwrap() - c.eval(t).unwrap()).norm());
        }
        for (c, &u) in v_curves.iter().zip(&g.params_u) {
            worst = worst.max((g.surface.eval(u, t).unwrap() - c.eval(t).unwrap()).norm());
        }
    }
    assert!(worst < 1e-9, "network reproduced to {worst}");
    // A network whose curves do not cross is refused with the pair named.
    let mut moved = v_curves.clone();
    moved[2] = moved[2].map_control_points(|p| p + V3::new(0.0, 0.0, 0.1));
    let e = gordon(&u_curves, &moved, (3, 3), 1e-6).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::DegenerateGeometry);
    assert!(e.message().contains("v-curve 2"), "{e}");
    let e = gordon(&u_curves[..1], &v_curves, (3, 3), 1e-6).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::TooFewPoints);
}

/// Coons patches reproduce their four boundary curves; on straight boundaries of a
/// parallelogram they are the bilinear patch.
#[test]
fn coons_patches() {
    let mut rand = lcg(3);
    let corners = [
        V3::new(0.0, 0.0, 0.0),
        V3::new(3.0, 0.0, 0.5),
        V3::new(0.0, 2.0, -0.5),
        V3::new(3.2, 2.1, 1.0),
    ];
    // Random curves between given corners (end control points pinned).
    let mut between = |a: V3, b: V3, p: usize, n: usize| {
        let mut c = random_curve(&mut rand, p, n, 0.0);
        let last = c.len() - 1;
        c.control_points_mut()[0] = a;
        c.control_points_mut()[last] = b;
        c
    };
    let bottom = between(corners[0], corners[1], 3, 6);
    let top = between(corners[2], corners[3], 2, 4);
    let left = between(corners[0], corners[2], 2, 5);
    let right = between(corners[1], corners[3], 1, 3);
    let s = Surface::coons(&bottom, &top, &left, &right).unwrap();
    let at = |c: &BSpline<f64, V3>, t: f64| {
        let (a, b) = c.domain();
        c.eval(a + (b - a) * t).unwrap()
    };
    let mut worst: f64 = 0.0;
    for j in 0..=100 {
        let t = j as f64 / 100.0;
        worst = worst.max((s.eval(t, 0.0).unwrap() - at(&bottom, t)).norm());
        worst = worst.max((s.eval(t, 1.0).unwrap() - at(&top, t)).norm());
        worst = worst.max((s.eval(0.0, t).unwrap() - at(&left, t)).norm());
        worst = worst.max((s.eval(1.0, t).unwrap() - at(&right, t)).norm());
    }
    assert!(worst < 1e-13, "boundaries reproduced to {worst}");
    // Straight boundaries: the bilinear interpolant of the corners.
    let line = |a: V3, b: V3| BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0], vec![a, b]).unwrap();
    let flat = Surface::coons(
        &line(corners[0], corners[1]).elevate_degree(2).unwrap(),
        &line(corners[2], corners[3]),
        &line(corners[0], corners[2]),
        &line(corners[1], corners[3]),
    )
    .unwrap();
    for (u, v) in [(0.3, 0.7), (0.5, 0.5), (0.9, 0.1)] {
        let bilinear = corners[0] * (1.0 - u) * (1.0 - v)
            + corners[1] * u * (1.0 - v)
            + corners[2] * (1.0 - u) * v
            + corners[3] * u * v;
        assert!((flat.eval(u, v).unwrap() - bilinear).norm() < 1e-14);
    }
    // Curves that do not meet at a corner are refused.
    let e = Surface::coons(
        &bottom,
        &top,
        &line(corners[0] + V3::new(0.0, 0.0, 0.01), corners[2]),
        &right,
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::DegenerateGeometry);
    assert!(e.message().contains("bottom and left"), "{e}");
}

/// A helix (approximated by interpolation, then checked against its own tangent): the
/// rotation-minimising frame turns against the Frenet frame at the rate of the torsion,
/// `θ(s) = −τ s` (closed form for a helix of radius `a` and pitch `2πc`: `τ = c / (a² + c²)`).
#[test]
fn rotation_minimizing_frames_of_a_helix() {
    let (a, c) = (2.0, 0.5);
    let helix = |t: f64| V3::new(a * t.cos(), a * t.sin(), c * t);
    let ts: Vec<f64> = (0..=200).map(|k| k as f64 * 0.05).collect();
    let points: Vec<V3> = ts.iter().map(|&t| helix(t)).collect();
    let fit =
        spline_fit::interpolate_with_knots(&KnotVector::averaging(5, &ts).unwrap(), &ts, &points)
            .unwrap();
    let stations: Vec<f64> = (0..=10).map(|k| k as f64).collect();
    // Start with the Frenet normal (towards the axis).
    let frames =
        rotation_minimizing_frames(&fit, &stations, Some(V3::new(-1.0, 0.0, 0.0))).unwrap();
    let speed = (a * a + c * c).sqrt();
    let tau = c / (a * a + c * c);
    for (f, &t) in frames.iter().zip(&stations) {
        let frenet_n = V3::new(-t.cos(), -t.sin(), 0.0);
        let tangent = V3::new(-a * t.sin(), a * t.cos(), c) / speed;
        let frenet_b = tangent.cross(&frenet_n);
        assert!(
            (f.tangent - tangent).norm() < 1e-6,
            "tangent {}",
            (f.tangent - tangent).norm()
        );
        let angle = f.normal.dot(&frenet_b).atan2(f.normal.dot(&frenet_n));
        let expected = -tau * speed * t;
        let diff = (angle - expected + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
            - std::f64::consts::PI;
        assert!(diff.abs() < 1e-7, "at t = {t}: {angle} vs {expected}");
    }
}

/// A circle swept along a curved path: every section is a circle of the profile's radius
/// centred on the path, in the plane normal to it (computed from the path alone).
#[test]
fn sweep_of_a_circle() {
    let path = BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        vec![
            V3::new(0.0, 0.0, 0.0),
            V3::new(0.0, 0.0, 2.0),
            V3::new(2.0, 1.0, 3.0),
            V3::new(4.0, 0.0, 3.0),
            V3::new(5.0, 2.0, 5.0),
        ],
    )
    .unwrap();
    // A polynomial approximation of a circle of radius 0.5 in the plane z = 0 (normal to the
    // path's start tangent), by interpolation of 24 points.
    let pts: Vec<V3> = (0..=24)
        .map(|k| {
            let t = k as f64 / 24.0 * std::f64::consts::TAU;
            V3::new(0.5 * t.cos(), 0.5 * t.sin(), 0.0)
        })
        .collect();
    let profile = spline_fit::interpolate(&pts, 3, &spline_fit::InterpolationOptions::default())
        .unwrap()
        .curve;
    let swept = sweep(&profile, &path, 12, None).unwrap();
    for &v in &swept.params {
        let d = path.derivatives(v, 1).unwrap();
        let (x, t) = (d[0], d[1].normalize());
        for j in 0..=24 {
            let u = j as f64 / 24.0;
            let p = swept.surface.eval(u, v).unwrap();
            let q = profile.eval(u).unwrap();
            assert!(
                ((p - x).norm() - q.norm()).abs() < 1e-12,
                "distance from the path"
            );
            assert!((p - x).dot(&t).abs() < 1e-12, "in the normal plane");
        }
    }
    let e = sweep(&profile, &path, 1, None).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::TooFewPoints);
    let e = sweep(&profile, &path, 1_000_000, None).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
}

/// A bicubic polynomial graph sampled on a grid, with exact boundary derivatives and
/// twists: the interpolant is the polynomial itself (it lies in the spline space).
#[test]
fn interpolation_with_boundary_derivatives() {
    let f = |x: f64, y: f64| x * x * x * y - 2.0 * x * y * y * y + x * y + 0.5 * y * y;
    let fx = |x: f64, y: f64| 3.0 * x * x * y - 2.0 * y * y * y + y;
    let fy = |x: f64, y: f64| x * x * x - 6.0 * x * y * y + x + y;
    let fxy = |x: f64, y: f64| 3.0 * x * x - 6.0 * y * y + 1.0;
    let xs = [0.0, 0.2, 0.5, 0.9, 1.0];
    let ys = [0.0, 0.3, 0.6, 1.0];
    let grid: Vec<V3> = xs
        .iter()
        .flat_map(|&x| ys.iter().map(move |&y| V3::new(x, y, f(x, y))))
        .collect();
    let du = |x: f64| {
        ys.iter()
            .map(|&y| V3::new(1.0, 0.0, fx(x, y)))
            .collect::<Vec<_>>()
    };
    let dv = |y: f64| {
        xs.iter()
            .map(|&x| V3::new(0.0, 1.0, fy(x, y)))
            .collect::<Vec<_>>()
    };
    let tw = |x: f64, y: f64| V3::new(0.0, 0.0, fxy(x, y));
    let ends = SurfaceEnds {
        du: Some((du(0.0), du(1.0))),
        dv: Some((dv(0.0), dv(1.0))),
        twists: Some([tw(0.0, 0.0), tw(1.0, 0.0), tw(0.0, 1.0), tw(1.0, 1.0)]),
    };
    let given = |v: &[f64]| Parametrization::Given(v.to_vec());
    let fit =
        interpolate_surface_with_derivatives(&grid, 5, 4, (3, 3), &given(&xs), &given(&ys), &ends)
            .unwrap();
    assert_eq!(fit.surface.net_size(), (7, 6));
    for (x, y) in [(0.1, 0.9), (0.45, 0.45), (0.77, 0.12), (1.0, 0.5)] {
        let d = fit.surface.derivatives(x, y, 1).unwrap();
        assert!((d[0][0] - V3::new(x, y, f(x, y))).norm() < 1e-13);
        assert!((d[1][0].z - fx(x, y)).abs() < 1e-12);
        assert!((d[0][1].z - fy(x, y)).abs() < 1e-12);
    }
    // Errors: twists missing, wrong lengths.
    let missing = SurfaceEnds {
        twists: None,
        ..ends.clone()
    };
    let e = interpolate_surface_with_derivatives(
        &grid,
        5,
        4,
        (3, 3),
        &given(&xs),
        &given(&ys),
        &missing,
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    let short = SurfaceEnds {
        du: Some((du(0.0)[..2].to_vec(), du(1.0))),
        dv: None,
        twists: None,
    };
    let e =
        interpolate_surface_with_derivatives(&grid, 5, 4, (3, 3), &given(&xs), &given(&ys), &short)
            .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
}

#[test]
fn skinning_errors() {
    let mut rand = lcg(1);
    let c = random_curve(&mut rand, 2, 4, 0.0);
    assert_eq!(
        skin(std::slice::from_ref(&c), 2, None).unwrap_err().kind(),
        ErrorKind::TooFewPoints
    );
    assert_eq!(
        skin(&[c.clone(), c.clone()], 2, None).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
    let d = random_curve(&mut rand, 2, 4, 1.0);
    assert_eq!(
        skin(&[c.clone(), d.clone()], 2, Some(&[0.0]))
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidLength
    );
    assert_eq!(
        skin(&[c.clone(), d.clone()], 2, Some(&[1.0, 0.0]))
            .unwrap_err()
            .kind(),
        ErrorKind::UnsortedKnots
    );
    assert_eq!(
        skin(&[c.clone(), d.clone()], 0, None).unwrap_err().kind(),
        ErrorKind::InvalidArgument
    );
    // Given parameters are kept.
    let s = skin(&[c, d], 1, Some(&[2.0, 5.0])).unwrap();
    assert_eq!(s.params, vec![2.0, 5.0]);
}
