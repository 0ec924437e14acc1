//! Errors, not garbage: every invalid input gets its error kind and a message that says
//! what is wrong where.

#![allow(clippy::needless_range_loop, clippy::cast_lossless)]

use nalgebra::Vector2;
use spline_core::{ErrorKind, KnotVector};
use spline_fit::{
    CorrectionOptions, InterpolationOptions, KnotChoice, LeastSquares, MAX_CORRECTION_ITERATIONS,
    Parametrization, approximate, bezier_interpolate, correct_parameters, curvature_knots_with,
    interpolate, interpolate_closed, interpolate_function, interpolate_with_knots, make_ndbspl,
    natural_cubic, natural_spline, parametrize,
};

fn v(x: f64, y: f64) -> Vector2<f64> {
    Vector2::new(x, y)
}

fn pts() -> Vec<Vector2<f64>> {
    vec![
        v(0.0, 0.0),
        v(1.0, 1.0),
        v(2.0, 0.5),
        v(3.0, 2.0),
        v(4.0, 0.0),
    ]
}

#[test]
fn schoenberg_whitney_violations_name_the_basis_function_and_the_empty_span() {
    // Interpolation: N_2 (support [0.3, 0.7]) vanishes at ū_2 = 0.2.
    let knots = KnotVector::new(1, vec![0.0, 0.0, 0.3, 0.5, 0.7, 1.0, 1.0]).unwrap();
    let params = [0.0, 0.1, 0.2, 0.9, 1.0];
    let e = interpolate_with_knots(&knots, &params, &pts()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::SchoenbergWhitney);
    assert!(e.message().contains("N_2"), "{e}");
    assert!(e.message().contains("support [0.3, 0.7]"), "{e}");
    assert!(e.message().contains("[0.3, 0.5] holds no data"), "{e}");
    // Least squares: the same knots, the data skip the span [0.3, 0.7].
    let e = LeastSquares::new(&pts(), &params, knots.clone())
        .solve()
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::SchoenbergWhitney);
    assert!(e.message().contains("N_2"), "{e}");
    assert!(e.message().contains("[0.3, 0.5] holds no data"), "{e}");
    // With smoothing the problem is well posed again.
    let fit = LeastSquares::new(&pts(), &params, knots.clone())
        .smoothing(1e-6)
        .solve();
    // Degree 1 has no second derivative: still singular, reported as such.
    assert_eq!(fit.unwrap_err().kind(), ErrorKind::SingularSystem);
    let cubic = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.4, 0.5, 1.0, 1.0, 1.0, 1.0]).unwrap();
    let many: Vec<f64> = (0..20)
        .map(|k| {
            if k < 10 {
                f64::from(k) * 0.03
            } else {
                0.6 + f64::from(k - 10) * 0.04
            }
        })
        .collect();
    let data: Vec<Vector2<f64>> = many.iter().map(|&t| v(t, t * t)).collect();
    // Span [0.4, 0.5] is empty but every basis function still gets a parameter: fine.
    assert!(
        LeastSquares::new(&data, &many, cubic.clone())
            .solve()
            .is_ok()
    );
    // Uniform knots on uneven parameters can violate the conditions for interpolation.
    let clustered = [0.0, 0.01, 0.02, 0.03, 1.0];
    let e = interpolate(
        &pts(),
        2,
        &InterpolationOptions {
            parametrization: Parametrization::Given(clustered.to_vec()),
            knots: KnotChoice::Uniform,
            ..InterpolationOptions::default()
        },
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::SchoenbergWhitney, "{e}");
}

#[test]
fn duplicate_consecutive_points_under_chordal_parameters() {
    let mut p = pts();
    p[2] = p[1];
    for kind in [Parametrization::Chordal, Parametrization::Centripetal] {
        let e = parametrize(&p, &kind).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::DegenerateGeometry);
        assert!(e.message().contains("points 1 and 2 coincide"), "{e}");
        let e = interpolate(
            &p,
            3,
            &InterpolationOptions {
                parametrization: kind.clone(),
                ..InterpolationOptions::default()
            },
        )
        .unwrap_err();
        assert_eq!(e.kind(), ErrorKind::DegenerateGeometry);
    }
    // Uniform parameters do not mind.
    assert!(parametrize(&p, &Parametrization::Uniform).is_ok());
    // Closed curves also look at the closing chord.
    let mut q = pts();
    q.push(q[0]);
    let e = interpolate_closed(&q, 3, &Parametrization::Chordal).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::DegenerateGeometry);
    assert!(e.message().contains("points 5 and 0"), "{e}");
}

#[test]
fn too_few_points() {
    let three = &pts()[..3];
    for (e, needle) in [
        (
            interpolate(three, 3, &InterpolationOptions::default()).unwrap_err(),
            "at least 4",
        ),
        (
            approximate(
                three,
                2,
                4,
                &Parametrization::Chordal,
                &KnotChoice::NurbsBook,
            )
            .unwrap_err(),
            "at least 4",
        ),
        (
            interpolate_function(&[0.0, 1.0], &[1.0, 2.0], 2).unwrap_err(),
            "at least 3",
        ),
        (
            natural_cubic::<f64, f64>(&[0.0], &[1.0]).unwrap_err(),
            "at least 2",
        ),
        (
            natural_spline(&[0.0, 1.0], &[1.0, 2.0], 6).unwrap_err(),
            "at least 3",
        ),
        (
            bezier_interpolate(&three[..1], &Parametrization::Uniform, (0.0, 1.0)).unwrap_err(),
            "at least 2",
        ),
        (
            interpolate_closed(&three[..2], 3, &Parametrization::Uniform).unwrap_err(),
            "at least 4",
        ),
    ] {
        assert_eq!(e.kind(), ErrorKind::TooFewPoints, "{e}");
        assert!(e.message().contains(needle), "{e}");
    }
}

#[test]
fn nan_input() {
    let mut p = pts();
    p[3] = v(f64::NAN, 1.0);
    let e = interpolate(&p, 2, &InterpolationOptions::default()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    assert!(e.message().contains("data point 3"), "{e}");
    let params = [0.0, 0.25, 0.5, 0.75, 1.0];
    let knots = KnotVector::averaging(2, &params).unwrap();
    let e = interpolate_with_knots(&knots, &params, &p).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    let e = LeastSquares::new(&p, &params, knots.clone())
        .solve()
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    let bad = [0.0, 0.25, f64::NAN, 0.75, 1.0];
    let e = interpolate_with_knots(&knots, &bad, &pts()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    let e = natural_cubic(&[0.0, 1.0, f64::INFINITY], &[1.0, 2.0, 3.0]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    let w = [1.0, 1.0, f64::NAN, 1.0, 1.0];
    let e = LeastSquares::new(&pts(), &params, knots.clone())
        .weights(&w)
        .solve()
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidWeight);
    let w = [1.0, 0.0, 1.0, 1.0, 1.0];
    let e = LeastSquares::new(&pts(), &params, knots)
        .weights(&w)
        .solve()
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidWeight);
    assert!(e.message().contains("weight 1"), "{e}");
}

#[test]
fn unsorted_or_repeated_given_parameters() {
    let unsorted = Parametrization::Given(vec![0.0, 0.5, 0.4, 0.8, 1.0]);
    let e = interpolate(
        &pts(),
        2,
        &InterpolationOptions {
            parametrization: unsorted.clone(),
            ..InterpolationOptions::default()
        },
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
    assert!(
        e.message()
            .contains("parameter 2 (0.4) < parameter 1 (0.5)"),
        "{e}"
    );
    let e = approximate(&pts(), 1, 3, &unsorted, &KnotChoice::NurbsBook).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
    // Interpolation needs strictly increasing parameters.
    let repeated = Parametrization::Given(vec![0.0, 0.5, 0.5, 0.8, 1.0]);
    let e = interpolate(
        &pts(),
        2,
        &InterpolationOptions {
            parametrization: repeated,
            ..InterpolationOptions::default()
        },
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
    assert!(e.message().contains("increase strictly"), "{e}");
    // Wrong count.
    let e = parametrize(&pts(), &Parametrization::Given(vec![0.0, 1.0])).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    let e = natural_cubic(&[0.0, 2.0, 1.0], &[0.0, 1.0, 2.0]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
}

#[test]
fn singular_systems_are_reported() {
    // Two parameters one ulp apart: the collocation matrix is numerically singular.
    let next = f64::from_bits(0.5f64.to_bits() + 1);
    let params = [0.0, 0.5, next, 1.0];
    let knots = KnotVector::bezier(3, 0.0, 1.0).unwrap();
    let e = interpolate_with_knots(&knots, &params, &pts()[..4]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::SingularSystem, "{e}");
    // Least squares with more control points than distinct data in a region, once
    // smoothing has switched the data check off and the degree gives no smoothing.
    let knots = KnotVector::new(1, vec![0.0, 0.0, 0.2, 0.4, 0.6, 1.0, 1.0]).unwrap();
    let params = [0.0, 0.1, 0.7, 0.8, 1.0];
    let e = LeastSquares::new(&pts(), &params, knots)
        .smoothing(1.0)
        .solve()
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::SingularSystem);
    assert!(e.message().contains("control point"), "{e}");
}

#[test]
fn other_argument_errors() {
    let params = [0.0, 0.25, 0.5, 0.75, 1.0];
    let knots = KnotVector::averaging(2, &params).unwrap();
    let e = LeastSquares::new(&pts(), &params, knots.clone())
        .fix_coordinate(7, 0, 1.0)
        .solve()
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::IndexOutOfRange);
    assert_eq!(e.index(), Some(7));
    let e = LeastSquares::new(&pts(), &params, knots.clone())
        .fix_point(1, v(f64::NAN, 0.0))
        .solve()
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    assert_eq!(e.index(), Some(1));
    let e = LeastSquares::new(&pts(), &params[..4], knots.clone())
        .solve()
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    let outside = [0.0, 0.25, 0.5, 0.75, 1.5];
    let e = LeastSquares::new(&pts(), &outside, knots.clone())
        .solve()
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::OutOfDomain);
    assert!(e.message().contains("parameter 4"), "{e}");
    let e = LeastSquares::new(&pts(), &params, knots.clone())
        .smoothing(-1.0)
        .solve()
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    // The offending value and the allowed range, for a program to read.
    assert_eq!(e.value(), Some(-1.0));
    assert_eq!(e.interval(), Some((0.0, f64::INFINITY)));
    let e = natural_spline(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0], 3).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(e.value(), Some(3.0));
    let short = KnotVector::averaging(2, &params[..4]).unwrap();
    let e = interpolate_with_knots(&short, &params, &pts()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
}

#[test]
fn argument_errors_carry_their_fields() {
    // Parameter correction: a bad angle tolerance is a tolerance error; too many sweeps
    // give the maximum and the number asked.
    let params = [0.0, 0.25, 0.5, 0.75, 1.0];
    let knots = KnotVector::clamped_uniform(2, 3, 0.0, 1.0).unwrap();
    let points = pts();
    let problem = LeastSquares::new(&points, &params, knots);
    let options = CorrectionOptions {
        angle_tolerance: -1.0,
        ..CorrectionOptions::default()
    };
    let e = correct_parameters(&problem, &options).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidTolerance);
    assert_eq!(e.message(), "the angle tolerance must be positive, got -1");
    assert_eq!(
        (e.value(), e.interval()),
        (Some(-1.0), Some((0.0, f64::INFINITY)))
    );
    let options = CorrectionOptions {
        max_halvings: MAX_CORRECTION_ITERATIONS + 1,
        ..CorrectionOptions::default()
    };
    let e = correct_parameters(&problem, &options).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(
        e.counts(),
        Some((MAX_CORRECTION_ITERATIONS, MAX_CORRECTION_ITERATIONS + 1))
    );
    // Grid interpolation: as many degrees as dimensions, and degrees of at least 1.
    let x: &[f64] = &[0.0, 1.0, 2.0, 3.0];
    let values = [0.0; 16];
    let e = make_ndbspl(&[x, x], &values, &[1], 1).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    assert_eq!(e.counts(), Some((2, 1)));
    let e = make_ndbspl(&[x, x], &values, &[1, 0], 1).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(
        (e.index(), e.value(), e.interval()),
        (Some(1), Some(0.0), Some((1.0, f64::INFINITY)))
    );
    // Knots that follow the curvature: a prescribed knot outside the domain.
    let curve =
        interpolate_function(&[0.0, 0.5, 1.0, 1.5, 2.0], &[0.0, 1.0, 0.0, 1.0, 0.0], 3).unwrap();
    let e = curvature_knots_with(&curve, 3, 8, 1.0, 0.0, &[(0.5, 1), (3.0, 1)]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(
        (e.index(), e.value(), e.interval()),
        (Some(1), Some(3.0), Some((0.0, 2.0)))
    );
}
