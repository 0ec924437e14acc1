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
            ErrorKind::OrderTooHigh
        );
        assert_eq!(
            c.knots()
                .dense_basis_derivatives(1.5, n)
                .unwrap_err()
                .kind(),
            ErrorKind::OrderTooHigh
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

/// Found by `cargo xtask fuzz` (operations case 0x10000063250): a surface collapsed to one
/// point put its mesh cells at `i64::MAX`, and looking at the neighbour cell overflowed.
#[test]
fn a_surface_collapsed_to_a_point_has_a_mesh() {
    use spline::geom::Surface;
    let ku = KnotVector::new(0, vec![0.0, 1.0]).unwrap();
    let kv = KnotVector::bezier(1, 0.0, 1.0).unwrap();
    let p = Vector3::new(6.275_481_539_090_808e79, 7.285_165_608_120_564e79, 0.0);
    let s = Surface::from_net(ku, kv, vec![vec![p, p]]).unwrap();
    let mesh = s.tessellate(3, 2).unwrap();
    assert_eq!(mesh.vertices.len(), 1);
    assert!(mesh.triangles.is_empty());
}

#[test]
fn degree_zero_surfaces_take_absurd_counts() {
    use spline::geom::Surface;
    let ku = KnotVector::new(0, vec![0.0, 1.0]).unwrap();
    let kv = KnotVector::bezier(1, 0.0, 1.0).unwrap();
    let s = Surface::from_net(
        ku,
        kv,
        vec![vec![
            Vector3::new(1.0, 2.0, 0.0),
            Vector3::new(1.0, 2.0, 1.0),
        ]],
    )
    .unwrap();
    for n in ABSURD.into_iter().chain([0, 1, 2, 1000, 1001]) {
        let _ = s.derivatives(1.0, 0.5, n);
        for m in [0, 1, 2, 1000, 1001, usize::MAX] {
            let _ = s.tessellate(n, m);
        }
    }
}

/// Found by `cargo xtask fuzz` (operations case 0xf5000007cfc2): elevating a NURBS curve
/// whose weights span 600 orders of magnitude made a weight leave the range of floating point
/// (a debug assertion, and undefined points in release builds). Now: positive finite weights,
/// or an `InvalidWeight` error. (Since elevation is done by blossoming, which never divides by
/// differences of close knots, every elevation of this curve succeeds.)
#[test]
fn weights_that_leave_the_range_are_an_error() {
    let knots = KnotVector::new(
        5,
        vec![
            -2.0, -2.0, -2.0, -2.0, -2.0, -2.0, -1.3, -1.3, -1.3, -0.6, 5.0, 5.0, 5.0, 5.0, 5.0,
            5.0,
        ],
    )
    .unwrap();
    let points = [
        (0.584_564_149_505_611_8, 0.269_047_655_355_222_35),
        (0.324_126_350_058_802_1, 0.446_212_907_402_325_33),
        (0.895_256_530_188_131_8, 0.941_150_212_758_212_4),
        (0.076_976_864_072_404_9, 0.896_335_813_287_530_2),
        (0.876_777_052_572_013_3, 0.707_735_555_205_347_8),
        (0.674_213_683_811_411_1, 0.034_425_094_519_878_63),
        (0.113_401_170_826_119_34, 0.333_544_603_118_668_6),
        (0.465_652_026_483_341_6, 0.213_695_720_394_528_44),
        (0.655_520_542_152_885_4, 0.201_742_102_698_170_6),
        (0.623_188_927_541_590_4, 0.930_874_767_981_53),
    ];
    let weights = vec![1.0, 1e-300, 1.0, 1e-300, 1e300, 2.0, 2.0, 0.5, 1e-300, 1.0];
    let c = NurbsCurve::new(
        knots,
        points.iter().map(|&(x, y)| Vector2::new(x, y)).collect(),
        weights,
    )
    .unwrap();
    for times in 1..=27 {
        match c.elevate_degree(times) {
            Ok(r) => assert!(r.weights().iter().all(|w: &f64| *w > 0.0 && w.is_finite())),
            Err(e) => assert_eq!(e.kind(), ErrorKind::InvalidWeight, "{e}"),
        }
    }
}
