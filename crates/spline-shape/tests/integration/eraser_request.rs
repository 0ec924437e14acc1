//! Smoothing requests as the front ends make them (`SmoothRequest`): the options in words
//! with their checks and messages in either spelling, the one call that chooses between
//! `smooth`, `smooth_to_tolerance` and `smooth_fewest_extrema`, and the result as the front
//! ends hand it out (the output curve, its control points, the summary line).

use crate::airfoils::airfoil;
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result};
use spline_shape::{
    AllowedExtrema, ControlPoints, ExtremaCount, Extremum, MAX_CURVATURE_EXTREMA, Objective,
    OptionSpelling, SmoothRequest, SmoothSummary, SmoothWords, SmoothedCurve, SmoothingOptions,
    smooth, smooth_fewest_extrema, smooth_to_tolerance,
};

/// Words with `control_points` and everything else at the front ends' defaults.
fn words(control_points: Option<usize>) -> SmoothWords<'static> {
    SmoothWords {
        control_points,
        max_deviation: None,
        degree: 3,
        curvature_extrema: None,
        extrema: &[],
        objective: "max",
        thorough: false,
        knot_search: false,
        closed: false,
        knot_exponents: None,
    }
}

/// The message of a request that must fail, in the tool's spelling.
fn flags_error(words: SmoothWords<'_>) -> Error {
    SmoothRequest::from_words(words, OptionSpelling::Flags).unwrap_err()
}

/// The same curve, deviations and extrema (the runs are deterministic).
fn assert_same(a: &SmoothedCurve, b: &SmoothedCurve) {
    assert_eq!(a.curve, b.curve);
    assert_eq!(a.periodic, b.periodic);
    assert_eq!(a.deviation.to_curve.max, b.deviation.to_curve.max);
    assert_eq!(a.deviation.to_data, b.deviation.to_data);
    assert_eq!(a.extrema, b.extrema);
    assert_eq!(a.warnings, b.warnings);
}

#[test]
fn a_request_runs_the_function_it_asks_for() {
    let points = airfoil("clarkv");
    // A count of control points and the default extremum: `smooth`.
    let request = SmoothRequest::new(ControlPoints::Count(16));
    assert_eq!(request.extrema, AllowedExtrema::Count(1));
    assert_same(
        &request.run(&points).unwrap(),
        &smooth(&points, &SmoothingOptions::new(16)).unwrap(),
    );
    // The fewest control points within a deviation: `smooth_to_tolerance`.
    let request = SmoothRequest::new(ControlPoints::Fewest {
        max_deviation: 1e-3,
    });
    let fewest = request.run(&points).unwrap();
    assert_same(
        &fewest,
        &smooth_to_tolerance(&points, 1e-3, &SmoothingOptions::new(0)).unwrap(),
    );
    assert!(fewest.deviation.to_curve.max <= 1e-3);
    // The fewest extrema: `smooth_fewest_extrema`, with and without a tolerance.
    for max_deviation in [None, Some(2e-3)] {
        let mut request = SmoothRequest::new(ControlPoints::Count(20));
        request.extrema = AllowedExtrema::Auto { max_deviation };
        assert_same(
            &request.run(&points).unwrap(),
            &smooth_fewest_extrema(&points, max_deviation, &SmoothingOptions::new(20)).unwrap(),
        );
    }
    // Extrema given, the other settings passed on.
    let given: Vec<Extremum> = vec!["max".parse().unwrap(), "min".parse().unwrap()];
    let mut request = SmoothRequest::new(ControlPoints::Count(20));
    request.extrema = AllowedExtrema::Given(given.clone());
    request.objective = Objective::LeastSquares;
    request.knot_exponents = vec![0.5];
    let mut options = SmoothingOptions::new(20);
    options.extrema = given;
    options.objective = Objective::LeastSquares;
    options.knot_exponents = vec![0.5];
    assert_same(
        &request.run(&points).unwrap(),
        &smooth(&points, &options).unwrap(),
    );
    // A count of extrema is the alternating list.
    let mut request = SmoothRequest::new(ControlPoints::Count(20));
    request.extrema = AllowedExtrema::Count(2);
    assert_same(
        &request.run(&points).unwrap(),
        &smooth(&points, &options_with(20, 2)).unwrap(),
    );
}

fn options_with(control_points: usize, extrema: usize) -> SmoothingOptions {
    let mut options = SmoothingOptions::new(control_points);
    options.request_extrema(Some(extrema), Vec::new()).unwrap();
    options
}

#[test]
fn requests_that_cannot_run_are_refused() {
    let points = airfoil("clarkv");
    // Two searches at once.
    let mut request = SmoothRequest::new(ControlPoints::Fewest {
        max_deviation: 1e-3,
    });
    request.extrema = AllowedExtrema::Auto {
        max_deviation: None,
    };
    let err = request.run(&points).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
    assert!(err.to_string().contains("fewest"), "{err}");
    // A count no list can hold is refused before the list is made.
    let mut request = SmoothRequest::new(ControlPoints::Count(20));
    request.extrema = AllowedExtrema::Count(usize::MAX);
    let err = request.run(&points).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
    assert_eq!(err.counts(), Some((MAX_CURVATURE_EXTREMA, usize::MAX)));
    // The errors of the functions called come through.
    let mut request = SmoothRequest::new(ControlPoints::Count(20));
    request.degree = 2;
    assert_eq!(
        request.run(&points).unwrap_err().kind(),
        ErrorKind::InvalidArgument
    );
    let mut request = SmoothRequest::new(ControlPoints::Count(20));
    request.extrema = AllowedExtrema::Auto {
        max_deviation: Some(-1.0),
    };
    assert_eq!(
        request.run(&points).unwrap_err().kind(),
        ErrorKind::InvalidTolerance
    );
}

#[test]
fn words_become_the_typed_request() {
    let given = ["max".to_owned(), "min@0.3".to_owned()];
    let request = SmoothRequest::from_words(
        SmoothWords {
            degree: 4,
            extrema: &given,
            curvature_extrema: Some(Ok(ExtremaCount::Count(2))),
            objective: "least-squares",
            thorough: true,
            knot_search: true,
            closed: true,
            knot_exponents: Some(Ok(vec![0.4])),
            ..words(Some(12))
        },
        OptionSpelling::Flags,
    )
    .unwrap();
    assert_eq!(
        request,
        SmoothRequest {
            control_points: ControlPoints::Count(12),
            extrema: AllowedExtrema::Given(vec![
                "max".parse().unwrap(),
                "min@0.3".parse().unwrap()
            ]),
            degree: 4,
            objective: Objective::LeastSquares,
            thorough: true,
            knot_search: true,
            closed: true,
            knot_exponents: vec![0.4],
        }
    );
    // The defaults are those of `SmoothingOptions::new`.
    let defaults = SmoothingOptions::new(0);
    let request = SmoothRequest::from_words(words(Some(20)), OptionSpelling::Flags).unwrap();
    assert_eq!(request.extrema, AllowedExtrema::Count(1));
    assert_eq!(request.knot_exponents, defaults.knot_exponents);
    assert_eq!(request.objective, defaults.objective);
    // A deviation alone: the fewest control points.
    let request = SmoothRequest::from_words(
        SmoothWords {
            max_deviation: Some(1e-3),
            ..words(None)
        },
        OptionSpelling::Keywords,
    )
    .unwrap();
    assert_eq!(
        request.control_points,
        ControlPoints::Fewest {
            max_deviation: 1e-3
        }
    );
    // `auto`, with the deviation as its tolerance or without one.
    for max_deviation in [None, Some(1e-3)] {
        let request = SmoothRequest::from_words(
            SmoothWords {
                max_deviation,
                curvature_extrema: Some("auto".parse()),
                ..words(Some(20))
            },
            OptionSpelling::Flags,
        )
        .unwrap();
        assert_eq!(request.control_points, ControlPoints::Count(20));
        assert_eq!(request.extrema, AllowedExtrema::Auto { max_deviation });
    }
    // The words of a count.
    assert_eq!("auto".parse::<ExtremaCount>().unwrap(), ExtremaCount::Auto);
    assert_eq!(
        " 4 ".parse::<ExtremaCount>().unwrap(),
        ExtremaCount::Count(4)
    );
    for bad in ["", "-1", "2.5", "many"] {
        let err = bad.parse::<ExtremaCount>().unwrap_err();
        assert_eq!(err.kind(), ErrorKind::Parse, "{bad:?}");
    }
}

#[test]
fn the_checks_of_the_words_name_the_options_as_each_front_end_spells_them() {
    let max = ["max".to_owned()];
    let top = ["top".to_owned()];
    let cases: Vec<(SmoothWords<'_>, ErrorKind, &str, &str)> = vec![
        (
            words(None),
            ErrorKind::InvalidArgument,
            "give --control-points N or --max-deviation D",
            "give control_points or max_deviation",
        ),
        (
            SmoothWords {
                max_deviation: Some(1e-3),
                ..words(Some(20))
            },
            ErrorKind::InvalidArgument,
            "give --control-points N or --max-deviation D, not both (both only with --curvature-extrema auto)",
            "give control_points or max_deviation, not both (both only with curvature_extrema=\"auto\")",
        ),
        (
            SmoothWords {
                max_deviation: Some(1e-3),
                curvature_extrema: Some(Ok(ExtremaCount::Auto)),
                ..words(None)
            },
            ErrorKind::InvalidArgument,
            "--curvature-extrema auto needs --control-points N",
            "curvature_extrema=\"auto\" needs control_points",
        ),
        (
            SmoothWords {
                curvature_extrema: Some(Ok(ExtremaCount::Auto)),
                extrema: &max,
                ..words(Some(20))
            },
            ErrorKind::InvalidArgument,
            "--curvature-extrema auto chooses the extrema: give no --extremum",
            "curvature_extrema=\"auto\" chooses the extrema: give no extrema",
        ),
        (
            SmoothWords {
                objective: "bogus",
                ..words(Some(20))
            },
            ErrorKind::InvalidArgument,
            "--objective: unknown choice \"bogus\" (max or least-squares)",
            "objective: unknown choice \"bogus\" (max or least-squares)",
        ),
        (
            SmoothWords {
                extrema: &top,
                ..words(Some(20))
            },
            ErrorKind::Parse,
            "--extremum: extremum \"top\": expected max, min, max@U or min@U",
            "extrema: extremum \"top\": expected max, min, max@U or min@U",
        ),
        (
            SmoothWords {
                curvature_extrema: Some(Ok(ExtremaCount::Count(2))),
                extrema: &max,
                ..words(Some(20))
            },
            ErrorKind::InvalidLength,
            "--curvature-extrema: 2 disagrees with the 1 extrema given",
            "curvature_extrema: 2 disagrees with the 1 extrema given",
        ),
        (
            SmoothWords {
                curvature_extrema: Some(Ok(ExtremaCount::Count(2000))),
                ..words(Some(20))
            },
            ErrorKind::InvalidArgument,
            "--curvature-extrema: at most 1000 extrema can be allowed, got 2000",
            "curvature_extrema: at most 1000 extrema can be allowed, got 2000",
        ),
    ];
    for (words, kind, flags, keywords) in cases {
        let a = flags_error(words.clone());
        let b = SmoothRequest::from_words(words, OptionSpelling::Keywords).unwrap_err();
        assert_eq!((a.kind(), a.to_string().as_str()), (kind, flags));
        assert_eq!((b.kind(), b.to_string().as_str()), (kind, keywords));
        assert_eq!(a.counts(), b.counts());
    }
    // The structured facts of the counts.
    let err = flags_error(SmoothWords {
        curvature_extrema: Some(Ok(ExtremaCount::Count(2))),
        extrema: &max,
        ..words(Some(20))
    });
    assert_eq!(err.counts(), Some((1, 2)));
    let err = flags_error(SmoothWords {
        curvature_extrema: Some(Ok(ExtremaCount::Count(2000))),
        ..words(Some(20))
    });
    assert_eq!(err.counts(), Some((MAX_CURVATURE_EXTREMA, 2000)));
}

#[test]
fn of_several_problems_the_first_in_the_order_of_the_checks_is_reported() {
    let parse_error = |what: &str| -> Error { Error::new(ErrorKind::Parse, what.to_owned()) };
    let bad_knots = || Some(Err::<Vec<f64>, _>(parse_error("knots")));
    let bad_count = || Some(Err::<ExtremaCount, _>(parse_error("count")));
    let top = ["top".to_owned()];
    let order: Vec<(SmoothWords<'_>, &str)> = vec![
        // The control points come first, before the front end's parse errors.
        (
            SmoothWords {
                knot_exponents: bad_knots(),
                curvature_extrema: bad_count(),
                ..words(None)
            },
            "give --control-points",
        ),
        // Then the knot exponents, before the objective.
        (
            SmoothWords {
                knot_exponents: bad_knots(),
                objective: "bogus",
                ..words(Some(20))
            },
            "knots",
        ),
        // The objective, the extrema one by one, then their number.
        (
            SmoothWords {
                objective: "bogus",
                extrema: &top,
                curvature_extrema: bad_count(),
                ..words(Some(20))
            },
            "--objective",
        ),
        (
            SmoothWords {
                extrema: &top,
                curvature_extrema: bad_count(),
                ..words(Some(20))
            },
            "--extremum",
        ),
        (
            SmoothWords {
                curvature_extrema: bad_count(),
                ..words(Some(20))
            },
            "count",
        ),
    ];
    for (words, first) in order {
        let message = flags_error(words).to_string();
        assert!(message.starts_with(first), "{message} (expected {first})");
    }
}

/// Points of an ellipse 2 × 1 with a deterministic jitter.
fn ellipse(count: usize) -> Vec<Vector2<f64>> {
    (0..count)
        .map(|k| {
            let t = 0.3 + std::f64::consts::TAU * k as f64 / count as f64;
            let noise = 1e-3 * (((k * 7919) % 13) as f64 / 6.0 - 1.0);
            Vector2::new(2.0 * t.cos() + noise, t.sin() - noise)
        })
        .collect()
}

#[test]
fn the_result_as_the_front_ends_hand_it_out() -> Result<()> {
    // Open: the curve itself, the control points asked for.
    let open = SmoothRequest::new(ControlPoints::Count(20)).run(&airfoil("clarkv"))?;
    assert!(std::ptr::eq(open.output_curve(), &open.curve));
    assert_eq!(open.control_point_count(), 20);
    let summary = open.summary();
    assert_eq!(
        summary,
        SmoothSummary {
            control_points: Some(20),
            max_deviation: Some(open.deviation.to_curve.max),
            max_deviation_to_data: Some(open.deviation.to_data),
            extrema: Some(open.extrema.len()),
            error: None,
            warnings: open.warnings.clone(),
        }
    );
    assert_eq!(SmoothSummary::new(&Ok(open)), summary);
    // Closed: the wrapped container of the periodic curve and its distinct control points;
    // the summary counts those of the opened curve (as `summary.jsonl` always has).
    let mut request = SmoothRequest::new(ControlPoints::Count(16));
    request.closed = true;
    request.extrema = AllowedExtrema::Count(4);
    let closed = request.run(&ellipse(80))?;
    let periodic = closed.periodic.as_ref().expect("a closed result");
    assert!(std::ptr::eq(closed.output_curve(), periodic.wrapped()));
    assert_eq!(closed.control_point_count(), 16);
    assert_eq!(periodic.wrapped().control_points().len(), 16 + 3);
    assert_eq!(
        closed.summary().control_points,
        Some(closed.curve.control_points().len())
    );
    assert_eq!(closed.curve.control_points().len(), 16 + 3);
    // A failure: its message and no numbers.
    let failed = SmoothSummary::new(&Err(Error::new(ErrorKind::TooFewPoints, "too few")));
    assert_eq!(
        failed,
        SmoothSummary {
            error: Some("too few".to_owned()),
            ..SmoothSummary::default()
        }
    );
    Ok(())
}
