//! Issue 26: errors say what failed in fields a program can read (the value, the allowed
//! range, the index, the counts) and in specific kinds where a caller would act differently.

use nalgebra::Vector2;
use spline_algebra::{
    PlanarInvariants, ProductMap, SegmentCurvature, SparseBilinear, TensorMap, TensorProductMap,
    planar_features, rational_planar_numerators, revolution_features, ridge_polynomials,
    sign_change_params, zeros,
};
use spline_core::{ErrorKind, KnotVector};
use spline_geom::{BSpline, NurbsCurve, Surface};

const POSITIVE: (f64, f64) = (2.0, f64::INFINITY);

fn line() -> BSpline<f64, Vector2<f64>> {
    BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0)],
    )
    .unwrap()
}

fn surface(degrees: (usize, usize)) -> Surface<f64, f64> {
    let ku = KnotVector::clamped(degrees.0, 0.0, 1.0, &[]).unwrap();
    let kv = KnotVector::clamped(degrees.1, 0.0, 1.0, &[]).unwrap();
    let n = ku.num_basis() * kv.num_basis();
    Surface::new(ku, kv, vec![1.0; n]).unwrap()
}

#[test]
fn a_bad_accuracy_is_a_bad_tolerance() {
    let f = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0], vec![-1.0, 1.0]).unwrap();
    for accuracy in [0.0, -1e-12, f64::INFINITY] {
        let e = zeros(&f, accuracy).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidTolerance, "{accuracy}");
        assert_eq!(e.value(), Some(accuracy));
        assert_eq!(e.interval(), Some((0.0, f64::INFINITY)));
        let e = sign_change_params(&f, accuracy).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidTolerance);
    }
    assert_eq!(
        zeros(&f, 0.0).unwrap_err().to_string(),
        "the accuracy must be positive and finite, got 0"
    );
    // Through the curve features too.
    let cubic = line().elevate_degree(2).unwrap();
    let e = planar_features(&cubic, -1.0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidTolerance);
}

#[test]
fn degrees_below_the_minimum_name_the_degree_and_the_allowed_range() {
    let e = PlanarInvariants::<f64>::new(line().knots()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!((e.value(), e.interval()), (Some(1.0), Some(POSITIVE)));
    assert!(e.to_string().contains("got 1"), "{e}");
    let e = rational_planar_numerators(&NurbsCurve::from_bspline(&line())).unwrap_err();
    assert_eq!((e.value(), e.interval()), (Some(1.0), Some(POSITIVE)));
    let quadratic = line().elevate_degree(1).unwrap();
    let e = SegmentCurvature::<f64>::new(quadratic.knots()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(
        (e.value(), e.interval()),
        (Some(2.0), Some((3.0, f64::INFINITY)))
    );
    let e = ridge_polynomials(&surface((3, 1))).unwrap_err();
    assert_eq!((e.value(), e.interval()), (Some(1.0), Some(POSITIVE)));
}

#[test]
fn meridians_that_cannot_be_analysed_say_why() {
    let quadratic =
        BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![1.0, 2.0, 1.0]).unwrap();
    let e = revolution_features(&quadratic, 1e-12).unwrap_err();
    assert_eq!(
        (e.value(), e.interval()),
        (Some(2.0), Some((3.0, f64::INFINITY)))
    );
    // r(z) = z − 0.5 (a cubic) reaches zero at z = 0.5.
    let crossing = BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        vec![-0.5, -0.5 + 1.0 / 3.0, -0.5 + 2.0 / 3.0, 0.5],
    )
    .unwrap();
    let e = revolution_features(&crossing, 1e-12).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    let z = e.value().expect("the height");
    assert!((z - 0.5).abs() < 1e-9, "{e}");
}

#[test]
fn an_entry_outside_the_argument_range_is_an_index_error() {
    let e =
        SparseBilinear::from_rows(2, 3, vec![vec![(0, 1, 1.0)], vec![(1, 3, 2.0)]]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::IndexOutOfRange);
    assert_eq!(e.index(), Some(3));
    assert_eq!(
        e.to_string(),
        "row 1: entry (1, 3) outside the 2×3 argument range"
    );
    let e = SparseBilinear::<f64>::from_rows(2, 3, vec![vec![(2, 0, 1.0)]]).unwrap_err();
    assert_eq!((e.kind(), e.index()), (ErrorKind::IndexOutOfRange, Some(2)));
}

#[test]
fn operands_on_other_spaces_are_a_space_mismatch() {
    let cubic = KnotVector::clamped(3, 0.0, 1.0, &[0.5]).unwrap();
    let other = KnotVector::clamped(3, 0.0, 1.0, &[0.25]).unwrap();
    let f = BSpline::new(other.clone(), vec![1.0; other.num_basis()]).unwrap();
    let g = BSpline::new(cubic.clone(), vec![1.0; cubic.num_basis()]).unwrap();
    let product = ProductMap::new(&cubic, &cubic).unwrap();
    let e = product.product(&f, &g).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::SpaceMismatch);
    assert_eq!(
        e.to_string(),
        "the factors are not on the knot vectors this product was prepared for"
    );
    let s = surface((3, 3));
    let t = surface((2, 3));
    let tensor =
        TensorProductMap::new((s.knots_u(), s.knots_v()), (s.knots_u(), s.knots_v())).unwrap();
    assert_eq!(
        tensor.product(&s, &t).unwrap_err().kind(),
        ErrorKind::SpaceMismatch
    );
    let map = TensorMap::partial_derivative(s.knots_u(), s.knots_v(), 1, 0).unwrap();
    assert_eq!(map.apply(&t).unwrap_err().kind(), ErrorKind::SpaceMismatch);
}
