//! The batch across SIMD lanes through the public API (issue 27): `eval_many_into` against the
//! evaluator's one-point calls, which take the scalar path (the same span and Horner's scheme,
//! one point at a time), bit for bit; and against the dense basis functions of spline-core,
//! an evaluation that shares nothing with the cached form, to the rounding of Horner's scheme.
//! The curves are the benchmarks' (a planar cubic with 100 control points, the NURBS unit
//! circle), a space quintic on graded knots and a scalar function.

use nalgebra::{SVector, Vector2, Vector3};
use spline_core::{ControlPoint, KnotVector};
use spline_geom::{BSpline, CircleConstruction, Frame, NurbsCurve};

/// Parameters in random order (xorshift), every knot of the domain and both ends.
fn params(knots: &KnotVector<f64>, count: usize) -> Vec<f64> {
    let (a, b) = knots.domain();
    let mut state = 0x9E37_79B9_7F4A_7C15_u64;
    let mut us: Vec<f64> = (0..count)
        .map(|_| {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            let t = (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64;
            a + (b - a) * t
        })
        .collect();
    us.extend(knots.knots().iter().copied().filter(|&k| k >= a && k <= b));
    us.extend([b, a, b]);
    us
}

/// `Σ N_i(u) P_i` from the dense basis.
fn dense<P: ControlPoint<f64>>(curve: &BSpline<f64, P>, u: f64) -> P {
    let basis = curve.knots().dense_basis(u).unwrap();
    curve
        .control_points()
        .iter()
        .zip(&basis)
        .fold(P::origin(), |acc, (&p, &n)| acc + p * n)
}

fn check<P: ControlPoint<f64>>(curve: &BSpline<f64, P>, tolerance: f64) {
    let us = params(curve.knots(), 5000);
    let mut batch = vec![P::origin(); us.len()];
    curve.eval_many_into(&us, &mut batch).unwrap();
    let evaluator = curve.evaluator();
    for (&u, q) in us.iter().zip(&batch) {
        let one = evaluator.eval(u).unwrap();
        for d in 0..P::DIM {
            assert_eq!(q.coord(d).to_bits(), one.coord(d).to_bits(), "at {u}");
        }
        let exact = dense(curve, u);
        assert!(
            (*q - exact).max_abs() <= tolerance,
            "at {u}: {q:?} vs {exact:?}"
        );
    }
}

#[test]
fn batch_equals_the_one_point_path_bit_for_bit() {
    let knots = KnotVector::clamped_uniform(3, 100, 0.0, 1.0).unwrap();
    let cubic = BSpline::new(
        knots.clone(),
        (0..100)
            .map(|i| Vector2::new(f64::from(i) / 100.0, (0.37 * f64::from(i)).sin()))
            .collect(),
    )
    .unwrap();
    check(&cubic, 1e-14);
    let function = BSpline::new(
        knots,
        (0..100).map(|i| (0.21 * f64::from(i)).cos()).collect(),
    )
    .unwrap();
    check(&function, 1e-14);
    let graded: Vec<f64> = (0..=20)
        .map(|i| 3.0 + (f64::from(i) / 20.0).powi(2))
        .collect();
    let mut k = vec![3.0; 5];
    k.extend(&graded);
    k.extend([4.0; 5]);
    let quintic = BSpline::new(
        KnotVector::new(5, k).unwrap(),
        (0..25)
            .map(|i| {
                let x = f64::from(i);
                Vector3::new(x.cos(), (0.5 * x).sin(), 0.1 * x)
            })
            .collect(),
    )
    .unwrap();
    check(&quintic, 1e-13);
    let four = BSpline::new(
        KnotVector::clamped_uniform(2, 40, -1.0, 1.0).unwrap(),
        (0..40)
            .map(|i| SVector::<f64, 4>::from_fn(|d, _| (f64::from(i) + d as f64).sin()))
            .collect(),
    )
    .unwrap();
    check(&four, 1e-14);
}

#[test]
fn nurbs_batch_equals_the_one_point_path_bit_for_bit() {
    let circle = NurbsCurve::circle(
        &Frame::planar(Vector2::new(0.5, -2.0)),
        3.0,
        CircleConstruction::Square,
    )
    .unwrap();
    let us = params(circle.knots(), 5000);
    let mut batch = vec![Vector2::zeros(); us.len()];
    circle.eval_many_into(&us, &mut batch).unwrap();
    let evaluator = circle.evaluator();
    for (&u, q) in us.iter().zip(&batch) {
        let one = evaluator.eval(u).unwrap();
        assert_eq!(
            (q.x.to_bits(), q.y.to_bits()),
            (one.x.to_bits(), one.y.to_bits()),
            "at {u}"
        );
        let radius = (q - Vector2::new(0.5, -2.0)).norm();
        assert!((radius - 3.0).abs() < 1e-14, "at {u}: radius {radius}");
    }
}
