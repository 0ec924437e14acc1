//! The NURBS curves and surfaces on the seeds' examples and closed forms, in other scalar types, and their
//! error cases (the properties under every operation are in `nurbs`).

use nalgebra::{SVector, Vector2, Vector3};
use num_dual::Dual64;
use spline_core::{ErrorKind, KnotVector, Scalar, cast, to_f64};
use spline_geom::{BSpline, Homogeneous, NurbsCurve, NurbsSurface};

/// A rational curve whose weights are all equal is its polynomial B-spline.
#[test]
fn equal_weights_give_the_polynomial_curve() {
    let knots = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0]).unwrap();
    let pts: Vec<Vector2<f64>> = (0..5)
        .map(|i| Vector2::new(f64::from(i), f64::from((i * i) % 3)))
        .collect();
    let b = BSpline::new(knots.clone(), pts.clone()).unwrap();
    let n = NurbsCurve::new(knots, pts, vec![2.5; 5]).unwrap();
    assert!(n.is_polynomial());
    assert_eq!(n.to_bspline().unwrap().control_points(), b.control_points());
    for i in 0..=50 {
        let u = f64::from(i) / 50.0;
        let (dn, db) = (n.derivatives(u, 4).unwrap(), b.derivatives(u, 4).unwrap());
        for (x, y) in dn.iter().zip(&db) {
            assert!((x - y).norm() < 1e-12 * (1.0 + y.norm()));
        }
    }
    assert_eq!(NurbsCurve::from_bspline(&b).weights(), vec![1.0; 5]);
}

/// Seed 004 (6.1): U = [0,0,0,1,1,1], W = [1,1,2] and P = (1,0), (1,1), (0,1) give
/// C(t) = ((1 − t²)/(1 + t²), 2t/(1 + t²)); its derivatives are closed forms too.
#[test]
fn quarter_circle_of_the_notes() {
    let c = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(1.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(0.0, 1.0),
        ],
        vec![1.0, 1.0, 2.0],
    )
    .unwrap();
    for i in 0..=100 {
        let t = f64::from(i) / 100.0;
        let q = 1.0 + t * t;
        let d = c.derivatives(t, 2).unwrap();
        assert!((d[0] - Vector2::new((1.0 - t * t) / q, 2.0 * t / q)).norm() < 1e-15);
        assert!(
            (d[1] - Vector2::new(-4.0 * t / (q * q), 2.0 * (1.0 - t * t) / (q * q))).norm() < 1e-14
        );
        let ddx = (12.0 * t * t - 4.0) / (q * q * q);
        let ddy = (4.0 * t * t * t - 12.0 * t) / (q * q * q);
        assert!((d[2] - Vector2::new(ddx, ddy)).norm() < 1e-13);
        assert!((c.signed_curvature(t).unwrap() - 1.0).abs() < 1e-14);
    }
}

#[test]
fn bad_weights_are_errors() {
    let knots = KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0]).unwrap();
    let pts = vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)];
    for w in [0.0, -1.0, f64::NAN, f64::INFINITY, -0.0] {
        let e = NurbsCurve::new(knots.clone(), pts.clone(), vec![1.0, w]).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidWeight, "weight {w}");
        assert!(e.message().contains("weight 1"), "{e}");
        let e = NurbsSurface::new(
            knots.clone(),
            knots.clone(),
            vec![Vector2::zeros(); 4],
            vec![1.0, 1.0, w, 1.0],
        )
        .unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidWeight);
        assert!(e.message().contains("(1, 0)"), "{e}");
        // The homogeneous form is checked too.
        let h = BSpline::new(
            knots.clone(),
            vec![
                Homogeneous::new(Vector2::zeros(), 1.0),
                Homogeneous::new(Vector2::zeros(), w),
            ],
        );
        match h {
            Ok(h) => assert_eq!(
                NurbsCurve::from_homogeneous(h).unwrap_err().kind(),
                ErrorKind::InvalidWeight
            ),
            // A weight that is not a number is already refused by the container.
            Err(e) => {
                assert_eq!(e.kind(), ErrorKind::NonFinite);
                assert!(!w.is_finite());
            }
        }
        assert_eq!(
            Homogeneous::from_cartesian(Vector2::new(1.0, 1.0), w)
                .unwrap_err()
                .kind(),
            ErrorKind::InvalidWeight
        );
    }
    // Wrong numbers of weights.
    assert_eq!(
        NurbsCurve::new(knots.clone(), pts.clone(), vec![1.0])
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidLength
    );
    assert_eq!(
        NurbsSurface::new(
            knots.clone(),
            knots.clone(),
            vec![Vector2::zeros(); 4],
            vec![1.0; 3]
        )
        .unwrap_err()
        .kind(),
        ErrorKind::InvalidLength
    );
}

#[test]
fn removing_an_essential_knot_is_refused() {
    let c = NurbsCurve::from_knots(
        1,
        vec![0.0, 0.0, 0.5, 1.0, 1.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(2.0, 0.0),
        ],
        vec![1.0, 2.0, 1.0],
    )
    .unwrap();
    let e = c.remove_knot(0.5, 1, 1e-9).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::ToleranceExceeded);
    // With a tolerance above the true deviation the removal is accepted and the deviation is
    // within it (the chord replaces the corner: the middle point (1, 1) moves by 1).
    let loose = c.remove_knot_within(0.5, 1, 10.0).unwrap();
    assert_eq!(loose.len(), 2);
    assert!((loose.eval(0.5).unwrap() - c.eval(0.5).unwrap()).norm() <= 10.0);
    assert_eq!(
        c.remove_knot_within(0.5, 1, -1.0).unwrap_err().kind(),
        ErrorKind::InvalidTolerance
    );
    assert_eq!(
        c.remove_knot_within(0.5, 1, f64::NAN).unwrap_err().kind(),
        ErrorKind::InvalidTolerance
    );
}

#[test]
fn out_of_domain_and_degenerate_tangents_are_errors() {
    let c = NurbsCurve::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector2::new(1.0, 1.0); 2],
        vec![1.0, 3.0],
    )
    .unwrap();
    assert_eq!(c.eval(1.1).unwrap_err().kind(), ErrorKind::OutOfDomain);
    assert_eq!(c.eval(f64::NAN).unwrap_err().kind(), ErrorKind::NonFinite);
    assert_eq!(
        c.eval_many(&[0.0, 2.0]).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    assert_eq!(
        c.unit_tangent(0.5).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        c.curvature_magnitude(0.5).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
    assert_eq!(
        c.signed_curvature(0.5).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
    let s = NurbsSurface::new(
        c.knots().clone(),
        c.knots().clone(),
        vec![Vector3::zeros(); 4],
        vec![1.0; 4],
    )
    .unwrap();
    assert_eq!(
        s.eval(0.5, -0.5).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    let mut out = vec![Vector3::zeros(); 5];
    assert_eq!(
        s.derivatives_into(0.5, 0.5, 1, &mut out)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidLength
    );
    assert_eq!(
        s.local_properties(0.5, 0.5).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
}

/// Evaluation and derivatives in `f32`, `f64` and dual numbers agree to the precision of
/// the type, and structural operations work in each.
fn nurbs_in<T: Scalar>(tol: f64) {
    let c = |x: f64| cast::<T>(x);
    let curve = NurbsCurve::from_knots(
        3,
        [0.0, 0.0, 0.0, 0.0, 0.35, 0.6, 1.0, 1.0, 1.0, 1.0]
            .map(c)
            .to_vec(),
        (0..6)
            .map(|i| {
                SVector::<T, 3>::new(
                    c(f64::from(i).sin()),
                    c((f64::from(i) * 0.7).cos()),
                    c(f64::from(i) * 0.1),
                )
            })
            .collect(),
        [1.0, 0.5, 2.0, 0.8, 1.5, 1.0].map(c).to_vec(),
    )
    .unwrap();
    let reference = NurbsCurve::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.35, 0.6, 1.0, 1.0, 1.0, 1.0],
        (0..6)
            .map(|i| {
                Vector3::new(
                    f64::from(i).sin(),
                    (f64::from(i) * 0.7).cos(),
                    f64::from(i) * 0.1,
                )
            })
            .collect(),
        vec![1.0, 0.5, 2.0, 0.8, 1.5, 1.0],
    )
    .unwrap();
    let ops = [
        curve.insert_knot(c(0.5), 2).unwrap(),
        curve.elevate_degree(1).unwrap(),
        curve.refine(&[c(0.1), c(0.9)]).unwrap(),
    ];
    for i in 0..=20 {
        let u = f64::from(i) / 20.0;
        let d = curve.derivatives(c(u), 2).unwrap();
        let r = reference.derivatives(u, 2).unwrap();
        for k in 0..3 {
            for j in 0..3 {
                assert!(
                    (to_f64(d[k][j]) - r[k][j]).abs()
                        <= tol * (1.0 + r[k][j].abs()) * 10f64.powi(k as i32)
                );
            }
        }
        for o in &ops {
            let p = o.eval(c(u)).unwrap();
            for j in 0..3 {
                assert!((to_f64(p[j]) - r[0][j]).abs() <= tol);
            }
        }
    }
}

#[test]
fn nurbs_in_f32() {
    nurbs_in::<f32>(1e-5);
}

#[test]
fn nurbs_in_f64() {
    nurbs_in::<f64>(1e-14);
}

#[test]
fn nurbs_in_dual_numbers() {
    nurbs_in::<Dual64>(1e-14);
}

/// Dual weights: the derivative of R(u) with respect to `w_i` is `R_i(u)(P_i` − R(u)) / `w_i`
/// (differentiating (6.3) with (6.2)).
#[test]
fn derivative_with_respect_to_a_weight() {
    let knots = vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
    let pts = vec![
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 2.0),
        Vector2::new(2.0, -1.0),
        Vector2::new(3.0, 0.5),
    ];
    let w = [1.0, 0.6, 1.8, 1.2];
    let plain = NurbsCurve::from_knots(2, knots.clone(), pts.clone(), w.to_vec()).unwrap();
    let kv = KnotVector::new(2, knots.clone()).unwrap();
    for i in 0..4 {
        let dual = NurbsCurve::from_knots(
            2,
            knots.iter().map(|&k| Dual64::from(k)).collect(),
            pts.iter().map(|p| p.map(Dual64::from)).collect(),
            w.iter()
                .enumerate()
                .map(|(j, &x)| Dual64::new(x, if i == j { 1.0 } else { 0.0 }))
                .collect(),
        )
        .unwrap();
        for s in 0..=10 {
            let u = f64::from(s) / 10.0;
            let r = plain.eval(u).unwrap();
            let denom: f64 = (0..4)
                .map(|j| w[j] * kv.basis_function(j, u).unwrap())
                .sum();
            let ri = w[i] * kv.basis_function(i, u).unwrap() / denom;
            let expected = (pts[i] - r) * (ri / w[i]);
            let got = dual.eval(Dual64::from(u)).unwrap();
            assert!((Vector2::new(got.x.eps, got.y.eps) - expected).norm() < 1e-14);
        }
    }
}

/// Issue 25's reproducer `nurbs_removal.json`: the bound (5.30) says 1.39e-5, the curve moves
/// by 1.7e-6 (Open CASCADE removes the knot at 1e-5). Checked by dense sampling here.
#[test]
fn rational_removal_is_decided_by_the_true_deviation() {
    let c = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.7, -0.2),
            Vector2::new(0.189_189_189_189_189_17, 0.237_837_837_837_837_85),
            Vector2::new(-0.140_622_717_750_786_72, 0.353_125),
            Vector2::new(-0.9, 0.1),
        ],
        vec![1.0, 1.85, 1.6, 0.5],
    )
    .unwrap();
    let removed = c.remove_knot_within(0.5, 1, 1e-5).unwrap();
    assert_eq!(removed.len(), 3);
    let sampled = (0..=20_000)
        .map(|i| {
            let u = f64::from(i) / 20_000.0;
            (c.eval(u).unwrap() - removed.eval(u).unwrap()).norm()
        })
        .fold(0.0, f64::max);
    assert!(sampled > 1e-6 && sampled < 2e-6, "{sampled}");
    // Below the true deviation it is refused, and the message gives that deviation.
    let e = c.remove_knot_within(0.5, 1, 1e-6).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::ToleranceExceeded);
    let reported = e.value().unwrap();
    assert!(
        (reported - sampled).abs() <= 1e-3 * sampled,
        "{reported} vs {sampled}"
    );
}
