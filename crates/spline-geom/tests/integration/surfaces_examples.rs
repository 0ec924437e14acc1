//! The tensor-product surfaces on the seeds' examples and closed forms, in other scalar types, and their
//! error cases (the properties under every operation are in `surfaces`).

use nalgebra::{Vector3, Vector4};
use num_dual::Dual64;
use spline_core::{ErrorKind, KnotVector, Scalar, cast, to_f64};
use spline_geom::{BSpline, Direction, Surface};

#[test]
fn derivatives_above_the_degrees_are_zero() {
    let s = Surface::bezier(vec![
        vec![
            Vector3::new(0.0, 0.0, 1.0),
            Vector3::new(0.0, 1.0, 2.0),
            Vector3::new(0.0, 2.0, 0.0),
        ],
        vec![
            Vector3::new(1.0, 0.0, 3.0),
            Vector3::new(1.0, 1.0, -1.0),
            Vector3::new(1.0, 2.0, 2.0),
        ],
    ])
    .unwrap();
    let d = s.derivatives(0.3, 0.6, 4).unwrap();
    for (k, row) in d.iter().enumerate() {
        for (l, x) in row.iter().enumerate() {
            if k > 1 || l > 2 {
                assert_eq!(*x, Vector3::zeros(), "k = {k}, l = {l}");
            } else {
                assert_ne!(*x, Vector3::zeros(), "k = {k}, l = {l}");
            }
        }
    }
}

/// The corners of a clamped surface are the corners of its net (seed 004 (5.9)) and the
/// boundary curves are the boundary rows of the net (5.4)–(5.8).
#[test]
fn clamped_surfaces_interpolate_corners_and_boundary_curves() {
    let ku = KnotVector::new(2, vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0]).unwrap();
    let kv = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.5, 2.0, 2.0, 2.0, 2.0]).unwrap();
    let net: Vec<Vec<Vector3<f64>>> = (0..4)
        .map(|i| {
            (0..5)
                .map(|j| Vector3::new(f64::from(i), f64::from(j), f64::from((i * 7 + j * 3) % 5)))
                .collect()
        })
        .collect();
    let s = Surface::from_net(ku.clone(), kv.clone(), net.clone()).unwrap();
    assert_eq!(s.eval(0.0, 0.0).unwrap(), net[0][0]);
    assert_eq!(s.eval(1.0, 0.0).unwrap(), net[3][0]);
    assert_eq!(s.eval(0.0, 2.0).unwrap(), net[0][4]);
    assert_eq!(s.eval(1.0, 2.0).unwrap(), net[3][4]);
    let first_column = BSpline::new(ku, net.iter().map(|r| r[0]).collect()).unwrap();
    let last_row = BSpline::new(kv, net[3].clone()).unwrap();
    for i in 0..=20 {
        let t = f64::from(i) / 20.0;
        assert!((s.eval(t, 0.0).unwrap() - first_column.eval(t).unwrap()).norm() < 1e-15);
        assert!((s.eval(1.0, 2.0 * t).unwrap() - last_row.eval(2.0 * t).unwrap()).norm() < 1e-15);
    }
    // Tangent plane at a corner (5.10)–(5.11): P'_u(u0, v0) = p/(u_{p+1} − u_1)(P10 − P00).
    let d = s.derivatives(0.0, 0.0, 1).unwrap();
    assert!((d[1][0] - (net[1][0] - net[0][0]) * (2.0 / 0.4)).norm() < 1e-14);
    assert!((d[0][1] - (net[0][1] - net[0][0]) * (3.0 / 0.5)).norm() < 1e-14);
}

/// The bilinear patch z = u v: K = −1/(1 + u² + v²)², H = −u v/(1 + u² + v²)^{3/2}, normal
/// (−v, −u, 1)/√(1 + u² + v²) (closed forms of a Monge patch).
#[test]
fn saddle_curvatures_match_closed_forms() {
    let s = Surface::bezier(vec![
        vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 1.0, 0.0)],
        vec![Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 1.0, 1.0)],
    ])
    .unwrap();
    for i in 0..=10 {
        for j in 0..=10 {
            let (u, v) = (f64::from(i) / 10.0, f64::from(j) / 10.0);
            let props = s.local_properties(u, v).unwrap();
            let w = 1.0 + u * u + v * v;
            assert!((props.gaussian_curvature + 1.0 / (w * w)).abs() < 1e-14);
            assert!((props.mean_curvature + u * v / w.powf(1.5)).abs() < 1e-14);
            assert!((props.normal - Vector3::new(-v, -u, 1.0) / w.sqrt()).norm() < 1e-14);
            assert!(
                (props.max_curvature * props.min_curvature - props.gaussian_curvature).abs()
                    < 1e-14
            );
            // Principal directions: unit, tangent, orthogonal, with normal curvatures κ1, κ2.
            for (d, k) in [
                (props.max_direction, props.max_curvature),
                (props.min_direction, props.min_curvature),
            ] {
                assert!((d.norm() - 1.0).abs() < 1e-14);
                assert!(d.dot(&props.normal).abs() < 1e-14);
                // Write d = a S_u + b S_v and compare II(a, b)/I(a, b) with κ.
                let (e, f, g) = (
                    props.first_form.uu,
                    props.first_form.uv,
                    props.first_form.vv,
                );
                let (du, dv) = (d.dot(&props.du), d.dot(&props.dv));
                let det = e * g - f * f;
                let (a, b) = ((g * du - f * dv) / det, (e * dv - f * du) / det);
                assert!((props.normal_curvature(a, b).unwrap() - k).abs() < 1e-13);
            }
            assert!(props.max_direction.dot(&props.min_direction).abs() < 1e-14);
        }
    }
}

/// A cylinder of radius r as an extrusion of a rational circle: K = 0, |H| = 1/(2r); the
/// rulings are the direction of zero curvature.
#[test]
fn cylinder_curvatures() {
    use spline_geom::{CircleConstruction, Frame, NurbsCurve, NurbsSurface};
    let r = 1.7;
    let circle = NurbsCurve::circle(
        &Frame::with_normal(Vector3::zeros(), Vector3::z()).unwrap(),
        r,
        CircleConstruction::Triangle,
    )
    .unwrap();
    let cyl = NurbsSurface::extrusion(&circle, Vector3::new(0.0, 0.0, 3.0)).unwrap();
    for i in 0..=40 {
        for j in 0..=4 {
            let (u, v) = (f64::from(i) / 40.0, f64::from(j) / 4.0);
            let props = cyl.local_properties(u, v).unwrap();
            assert!(
                props.gaussian_curvature.abs() < 1e-13,
                "K = {}",
                props.gaussian_curvature
            );
            assert!((props.mean_curvature.abs() - 0.5 / r).abs() < 1e-13);
            // The zero principal curvature belongs to the ruling (the z axis).
            let zero_dir = if props.max_curvature.abs() < props.min_curvature.abs() {
                props.max_direction
            } else {
                props.min_direction
            };
            assert!((zero_dir.z.abs() - 1.0).abs() < 1e-12);
        }
    }
}

#[test]
fn bad_nets_and_parameters_are_errors() {
    let ku = KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0]).unwrap();
    let kv = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).unwrap();
    let p = Vector3::new(1.0, 2.0, 3.0);
    // 2 × 3 net needed.
    let e = Surface::new(ku.clone(), kv.clone(), vec![p; 5]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    let e = Surface::from_net(ku.clone(), kv.clone(), vec![vec![p; 3]; 3]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    let e = Surface::from_net(ku.clone(), kv.clone(), vec![vec![p; 3], vec![p; 2]]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    assert!(e.message().contains("row 1"), "{e}");
    let e = Surface::from_net(
        ku.clone(),
        kv.clone(),
        vec![vec![p; 3], vec![p, Vector3::new(f64::NAN, 0.0, 0.0), p]],
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    assert_eq!(
        Surface::<f64, f64>::bezier(vec![]).unwrap_err().kind(),
        ErrorKind::InvalidLength
    );
    let e = Surface::<f64, f64>::from_knots(
        (1, 1),
        vec![0.0, 1.0, 0.5, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        vec![vec![0.0; 2]; 2],
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
    assert!(e.message().contains("knots in u"));

    let s = Surface::from_net(ku, kv, vec![vec![p; 3]; 2]).unwrap();
    assert_eq!(s.eval(1.5, 0.5).unwrap_err().kind(), ErrorKind::OutOfDomain);
    assert_eq!(
        s.eval(0.5, f64::NAN).unwrap_err().kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(
        s.eval_grid(&[0.5], &[0.2, -0.1]).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    let mut out = vec![Vector3::zeros(); 3];
    assert_eq!(
        s.derivatives_into(0.5, 0.5, 1, &mut out)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidLength
    );
    assert_eq!(
        s.split(Direction::U, 1.0).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    assert_eq!(
        s.split(Direction::V, f64::NAN).unwrap_err().kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(
        s.insert_knot(Direction::V, 0.5, 4).unwrap_err().kind(),
        ErrorKind::KnotMultiplicity
    );
    assert_eq!(
        s.remove_knot(Direction::U, 0.5, 1, 1e-9)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        s.derivative_surface(2, 0).unwrap_err().kind(),
        ErrorKind::OrderTooHigh
    );
    // A flat degenerate surface has no normal.
    assert_eq!(
        s.local_properties(0.5, 0.5).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
    // Essential knots are not removed.
    let wavy = Surface::from_knots(
        (1, 1),
        vec![0.0, 0.0, 0.5, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        vec![vec![0.0, 1.0], vec![3.0, -1.0], vec![0.0, 2.0]],
    )
    .unwrap();
    assert_eq!(
        wavy.remove_knot(Direction::U, 0.5, 1, 1e-9)
            .unwrap_err()
            .kind(),
        ErrorKind::ToleranceExceeded
    );
}

/// The same structural operations in any scalar type: the values agree with `f64` to the
/// precision of the type.
fn structural_operations_in<T: Scalar>(tol: f64) {
    let ku = KnotVector::new(
        3,
        [0.0, 0.0, 0.0, 0.0, 0.3, 0.7, 1.0, 1.0, 1.0, 1.0]
            .map(cast::<T>)
            .to_vec(),
    )
    .unwrap();
    let kv = KnotVector::new(
        2,
        [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0].map(cast::<T>).to_vec(),
    )
    .unwrap();
    let points: Vec<Vector3<T>> = (0..24)
        .map(|k| {
            let x = f64::from(k);
            Vector3::new(
                cast((x * 0.7).sin()),
                cast((x * 1.3).cos()),
                cast((x * 0.37).sin() * 2.0),
            )
        })
        .collect();
    let s = Surface::new(ku, kv, points).unwrap();
    let t: T = cast(0.45);
    let ops: Vec<Surface<T, Vector3<T>>> = vec![
        s.insert_knot(Direction::U, t, 2).unwrap(),
        s.insert_knot(Direction::V, t, 1).unwrap(),
        s.refine(Direction::V, &[cast(0.1), cast(0.8), cast(0.8)])
            .unwrap(),
        s.elevate_degree(Direction::U, 1).unwrap(),
        s.elevate_degree(Direction::V, 2).unwrap(),
        s.insert_knot(Direction::U, t, 1)
            .unwrap()
            .remove_knot(Direction::U, t, 1, cast(1e-3))
            .unwrap(),
    ];
    let (left, right) = s.split(Direction::V, t).unwrap();
    for i in 0..=8 {
        for j in 0..=8 {
            let (u, v) = (cast::<T>(f64::from(i) / 8.0), cast::<T>(f64::from(j) / 8.0));
            let x = s.eval(u, v).unwrap();
            let grid = s.eval_grid(&[u], &[v]).unwrap()[0];
            assert!(to_f64((grid - x).norm()) <= tol);
            for o in &ops {
                let y = o.eval(u, v).unwrap();
                assert!(
                    to_f64((y - x).norm()) <= tol,
                    "{} vs {}",
                    to_f64(y.x),
                    to_f64(x.x)
                );
            }
            let half = if v <= t { &left } else { &right };
            assert!(to_f64((half.eval(u, v).unwrap() - x).norm()) <= tol);
        }
    }
}

#[test]
fn structural_operations_in_f32() {
    structural_operations_in::<f32>(2e-5);
}

#[test]
fn structural_operations_in_f64() {
    structural_operations_in::<f64>(1e-13);
}

#[test]
fn structural_operations_in_dual_numbers() {
    structural_operations_in::<Dual64>(1e-13);
}

/// Dual numbers through the control points: the derivative of S(u, v) with respect to
/// `P_ij` is the product of basis functions `N_i(u)` `N_j(v)`.
#[test]
fn dual_control_points_give_tensor_basis_functions() {
    let ku = KnotVector::new(2, vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0]).unwrap();
    let kv = KnotVector::new(1, vec![0.0, 0.0, 0.5, 1.0, 1.0]).unwrap();
    let (nu, nv) = (4, 3);
    for (i, j) in [(0, 0), (1, 2), (2, 1), (3, 2)] {
        let points: Vec<Dual64> = (0..nu * nv)
            .map(|k| Dual64::new(k as f64, if k == i * nv + j { 1.0 } else { 0.0 }))
            .collect();
        let dual_ku =
            KnotVector::new(2, ku.knots().iter().map(|&x| Dual64::from(x)).collect()).unwrap();
        let dual_kv =
            KnotVector::new(1, kv.knots().iter().map(|&x| Dual64::from(x)).collect()).unwrap();
        let s = Surface::new(dual_ku, dual_kv, points).unwrap();
        for (u, v) in [(0.1, 0.2), (0.4, 0.5), (0.77, 0.9), (1.0, 1.0)] {
            let value = s.eval(Dual64::from(u), Dual64::from(v)).unwrap();
            let expected = ku.basis_function(i, u).unwrap() * kv.basis_function(j, v).unwrap();
            assert!((value.eps - expected).abs() < 1e-15);
        }
    }
}

#[test]
fn surfaces_with_four_coordinates_cannot_be_meshed() {
    let s = Surface::bezier(vec![vec![Vector4::new(0.0, 0.0, 0.0, 1.0); 2]; 2]).unwrap();
    assert_eq!(
        s.tessellate(4, 4).unwrap_err().kind(),
        ErrorKind::DimensionMismatch
    );
}

#[test]
fn control_curves_mapped_onto_different_knots_are_a_space_mismatch() {
    let s = Surface::bezier(vec![
        vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 1.0, 0.0)],
        vec![Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 1.0, 1.0)],
    ])
    .unwrap();
    let mut calls = 0;
    let e = s
        .map_curves(Direction::U, |c| {
            calls += 1;
            if calls == 2 {
                c.insert_knot(0.5, 1)
            } else {
                Ok(c.clone())
            }
        })
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::SpaceMismatch);
    assert_eq!(
        e.message(),
        "the control curves ended with different knot vectors"
    );
    assert_eq!(e.index(), Some(1));
}
