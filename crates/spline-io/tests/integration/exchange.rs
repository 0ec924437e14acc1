//! The JSON exchange format: the exact text written for every container, round trips through
//! records and JSON (scipy's reference cases included), the objects the tool reads (reports
//! unwrapped), and one-line errors that name the field.

use nalgebra::{SVector, Vector2, Vector3};
use serde_json::{Value, json};
use spline_core::ErrorKind;
use spline_geom::{BSpline, Bezier, Homogeneous, NurbsCurve, NurbsSurface, Surface};
use spline_io::exchange::{
    self, CurveRecord, Record, SurfaceRecord, from_json, from_value, serde_message, to_json,
    to_value,
};
use spline_testing::reference::{cases, flatten};

type N3 = NurbsCurve<f64, 3>;
type NS3 = NurbsSurface<f64, 3>;

/// The text written for each kind of container, as `docs/exchange-format.md` specifies it
/// (written out by hand here).
#[test]
fn every_container_is_written_as_the_format_says() {
    let curve = BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector2::new(0.0, 0.5), Vector2::new(1.0, -2.0)],
    )
    .unwrap();
    assert_eq!(
        to_json(&curve),
        r#"{"degree":1,"knots":[0.0,0.0,1.0,1.0],"control_points":[[0.0,0.5],[1.0,-2.0]]}"#
    );
    let function = BSpline::from_knots(0, vec![0.0, 1.0], vec![3.0]).unwrap();
    assert_eq!(
        to_json(&function),
        r#"{"degree":0,"knots":[0.0,1.0],"control_points":[[3.0]]}"#
    );
    let nurbs = NurbsCurve::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector2::new(1.0, 0.0), Vector2::new(0.0, 1.0)],
        vec![1.0, 0.5],
    )
    .unwrap();
    assert_eq!(
        to_json(&nurbs),
        r#"{"degree":1,"knots":[0.0,0.0,1.0,1.0],"control_points":[[1.0,0.0],[0.0,1.0]],"weights":[1.0,0.5]}"#
    );
    let surface = Surface::from_knots(
        (1, 0),
        vec![0.0, 0.0, 1.0, 1.0],
        vec![0.0, 1.0],
        vec![
            vec![Vector3::new(0.0, 0.0, 0.0)],
            vec![Vector3::new(1.0, 2.0, 3.0)],
        ],
    )
    .unwrap();
    assert_eq!(
        to_json(&surface),
        r#"{"degree":[1,0],"knots":[[0.0,0.0,1.0,1.0],[0.0,1.0]],"control_points":[[[0.0,0.0,0.0]],[[1.0,2.0,3.0]]]}"#
    );
    let rational = NurbsSurface::from_surface(&surface);
    assert_eq!(
        to_value(&rational)["weights"],
        json!([[1.0], [1.0]]),
        "a NURBS surface has a net of weights"
    );
    // The same text through the records.
    assert_eq!(CurveRecord::from_bspline(&curve).to_json(), to_json(&curve));
    assert_eq!(
        SurfaceRecord::from_surface(&surface).to_json(),
        to_json(&surface)
    );
}

/// A Bézier curve is the clamped B-spline of one segment.
#[test]
fn bezier_curves_are_clamped_single_segments() {
    let b = Bezier::with_interval(
        vec![Vector2::new(0.0, 1.0), Vector2::new(2.0, 3.0)],
        1.0,
        2.0,
    )
    .unwrap();
    let text = to_json(&b);
    assert_eq!(
        text,
        r#"{"degree":1,"knots":[1.0,1.0,2.0,2.0],"control_points":[[0.0,1.0],[2.0,3.0]]}"#
    );
    let back: Bezier<f64, Vector2<f64>> = from_json(&text).unwrap();
    assert_eq!(back, b);
    let two_pieces = r#"{"degree":1,"knots":[0,0,0.5,1,1],"control_points":[[0,0],[1,1],[2,0]]}"#;
    let e = from_json::<Bezier<f64, Vector2<f64>>>(two_pieces).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength, "{e}");
    // Three points on unclamped knots: a uniform quadratic B-spline, not the Bézier curve of
    // these points (its value at the middle of [0, 1] is (P0 + 6 P1 + P2) / 8, not
    // (P0 + 2 P1 + P2) / 4).
    let unclamped = r#"{"degree":2,"knots":[-2,-1,0,1,2,3],"control_points":[[0,0],[1,1],[2,0]]}"#;
    let curve: BSpline<f64, Vector2<f64>> = from_json(unclamped).unwrap();
    assert_eq!(curve.eval(0.5).unwrap(), Vector2::new(1.0, 0.75));
    let e = from_json::<Bezier<f64, Vector2<f64>>>(unclamped).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument, "{e}");
}

#[test]
fn nurbs_records_round_trip() {
    let c = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector3::new(1.0, 0.0, 0.5),
            Vector3::new(1.0, 1.0, 0.0),
            Vector3::new(0.0, 1.0, -0.5),
        ],
        vec![1.0, 0.25, 3.0],
    )
    .unwrap();
    let value = to_value(&c);
    assert_eq!(value["weights"], json!([1.0, 0.25, 3.0]));
    assert_eq!(value["control_points"][1], json!([1.0, 1.0, 0.0]));
    assert_eq!(from_value::<N3>(value).unwrap(), c);
    // A record without weights reads as unit weights.
    let plain = r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0], [1, 2]]}"#;
    assert_eq!(
        from_json::<NurbsCurve<f64, 2>>(plain).unwrap().weights(),
        vec![1.0, 1.0]
    );
    let s = NurbsSurface::extrusion(&c, Vector3::new(0.0, 0.0, 2.0)).unwrap();
    let value = to_value(&s);
    assert_eq!(value["degree"], json!([2, 1]));
    assert_eq!(
        value["weights"],
        json!([[1.0, 1.0], [0.25, 0.25], [3.0, 3.0]])
    );
    let back: NS3 = from_value(value).unwrap();
    for (p, q) in back.control_points().iter().zip(s.control_points()) {
        assert!((p - q).norm() < 1e-15);
    }
    // Homogeneous containers are written with their homogeneous coordinates.
    let h: &Surface<f64, Homogeneous<f64, 3>> = s.homogeneous();
    assert_eq!(
        to_value(h)["control_points"][1][0],
        json!([0.25, 0.25, 0.0, 0.25])
    );
}

#[test]
fn bad_weights_and_nets_are_refused() {
    for w in [0.0, -1.0, f64::NAN, f64::INFINITY, -0.0] {
        let record = CurveRecord {
            degree: 1,
            knots: vec![0.0, 0.0, 1.0, 1.0],
            control_points: vec![vec![0.0, 0.0], vec![1.0, 0.0]],
            weights: Some(vec![w, 1.0]),
        };
        assert_eq!(
            record.to_nurbs::<f64, 2>().unwrap_err().kind(),
            ErrorKind::InvalidWeight
        );
        let record = SurfaceRecord {
            degree: [1, 1],
            knots: [vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]],
            control_points: vec![vec![vec![0.0, 0.0, 0.0]; 2]; 2],
            weights: Some(vec![vec![1.0, 1.0], vec![1.0, w]]),
        };
        assert_eq!(
            record.to_nurbs_surface::<f64, 3>().unwrap_err().kind(),
            ErrorKind::InvalidWeight
        );
    }
    let record = SurfaceRecord {
        degree: [1, 1],
        knots: [vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]],
        control_points: vec![vec![vec![0.0, 0.0, 0.0]; 2]; 2],
        weights: Some(vec![vec![1.0, 1.0], vec![1.0]]),
    };
    let e = record.to_nurbs_surface::<f64, 3>().unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    assert!(e.message().contains("weights"), "{e}");
    // Mismatched net sizes.
    let record = SurfaceRecord {
        weights: None,
        control_points: vec![vec![vec![0.0, 0.0, 0.0]; 3]; 2],
        ..record
    };
    assert_eq!(
        record.to_surface::<f64, Vector3<f64>>().unwrap_err().kind(),
        ErrorKind::InvalidLength
    );
    let record = SurfaceRecord {
        control_points: vec![vec![vec![0.0, 0.0, 0.0]; 2], vec![vec![0.0, 0.0]; 2]],
        ..record
    };
    assert_eq!(
        record.dimension().unwrap_err().kind(),
        ErrorKind::DimensionMismatch
    );
    // A record with weights is not a plain surface, and bad weights are refused.
    let text = r#"{"degree": [1, 1], "knots": [[0,0,1,1],[0,0,1,1]], "control_points": [[[0,0,0],[0,1,0]],[[1,0,0],[1,1,0]]], "weights": [[1,1],[1,0]]}"#;
    let e = from_json::<NS3>(text).unwrap_err();
    assert!(e.to_string().contains("weights must be positive"), "{e}");
    let e = from_json::<Surface<f64, Vector3<f64>>>(text).unwrap_err();
    assert!(e.to_string().contains("read it as a NURBS surface"), "{e}");
}

/// scipy's reference cases (`tests/data/reference/`) read and written back: the same
/// numbers, whichever way the record is read.
#[test]
fn reference_cases_go_both_ways() {
    let mut count = 0;
    for case in &cases("surface_eval") {
        let surface = &case["surface"];
        let record: SurfaceRecord = serde_json::from_value(surface.clone()).unwrap();
        if record.dimension().unwrap() != 3 || record.is_rational() {
            continue;
        }
        let s: Surface<f64, SVector<f64, 3>> = from_value(surface.clone()).unwrap();
        let back = to_value(&s);
        assert_eq!(
            flatten(&back["control_points"]),
            flatten(&surface["control_points"])
        );
        assert_eq!(back["degree"], surface["degree"]);
        assert_eq!(flatten(&back["knots"]), flatten(&surface["knots"]));
        assert_eq!(record.to_surface::<f64, SVector<f64, 3>>().unwrap(), s);
        count += 1;
    }
    for case in &cases("nurbs_eval") {
        let curve = &case["curve"];
        let record = CurveRecord::from_json(&curve.to_string()).unwrap();
        if record.dimension().unwrap() != 2 {
            continue;
        }
        let c: NurbsCurve<f64, 2> = from_value(curve.clone()).unwrap();
        assert_eq!(record.to_nurbs::<f64, 2>().unwrap(), c);
        let back = to_value(&c);
        assert_eq!(flatten(&back["knots"]), flatten(&curve["knots"]));
        count += 1;
    }
    assert!(count >= 5, "{count}");
}

/// Objects as the tool reads them: surfaces by their pair of degrees, reports unwrapped.
#[test]
fn records_of_either_kind_and_reports() {
    let curve = json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]});
    let surface =
        json!({"degree": [0, 0], "knots": [[0, 1], [0, 1]], "control_points": [[[1, 2]]]});
    assert!(matches!(
        Record::from_value(curve.clone()),
        Ok(Record::Curve(_))
    ));
    assert!(matches!(
        Record::from_value(surface.clone()),
        Ok(Record::Surface(_))
    ));
    let report = json!({"curve": curve, "closed": false, "max_deviation": 0.5});
    assert_eq!(
        Record::from_value(report).unwrap(),
        Record::from_value(curve.clone()).unwrap()
    );
    let report = json!({"surface": surface, "rms": 0.0});
    assert!(matches!(Record::from_value(report), Ok(Record::Surface(_))));
    let message = |value: Value| Record::from_value(value).unwrap_err().to_string();
    assert_eq!(
        message(json!([1, 2])),
        "expected a JSON object with degree, knots and control_points, got an array"
    );
    assert_eq!(
        message(json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [0, 1]})),
        "malformed curve: field control_points[0]: expected an array, got the number 0"
    );
    assert_eq!(
        message(json!({"degree": [1, 1], "knots": [[0, 0, 1, 1]], "control_points": []})),
        "malformed surface: field knots: invalid length 1, expected an array of length 2"
    );
    assert_eq!(
        message(json!({"degree": 1, "knots": [0, 1], "control_points": [[0]], "closed": true})),
        "malformed curve: field closed: unknown field closed, expected one of degree, knots, control_points, weights"
    );
}

#[test]
fn json_errors_are_one_line() {
    let e = from_json::<BSpline<f64, Vector2<f64>>>("{\"degree\": 1,\n").unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Parse);
    assert!(e.message().starts_with("not valid JSON: "), "{e}");
    assert!(!e.message().contains('\n'));
    let e = CurveRecord::from_json(r#"{"degree": 1}"#).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Parse);
    assert!(e.message().contains("missing field `knots`"), "{e}");
    let e = exchange::parse_json("[1, 2").unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Parse);
    assert_eq!(
        serde_message("invalid type: floating point `0`, expected a sequence at line 1 column 1"),
        "expected an array, got the number 0"
    );
    assert_eq!(
        serde_message("invalid type: string \"x\", expected f64"),
        "expected a number, got the string \"x\""
    );
    assert_eq!(
        serde_message("invalid type: map, expected usize"),
        "expected a non-negative integer, got an object"
    );
    assert_eq!(
        serde_message("EOF while parsing a list at line 3 column 0"),
        "EOF while parsing a list at line 3 column 0"
    );
}

/// scipy's objects: nested arrays both ways, `NdSpline` and `ColumnSpline` records (the
/// keys of a JSON value in sorted order), against values written out by hand.
#[test]
fn nested_arrays_and_scipy_objects() {
    use spline_geom::{ColumnSpline, NdSpline};
    use spline_io::exchange::{columns_to_value, nd_from_value, nd_to_value, nest, nested_array};
    let (shape, m, values) = nested_array(&json!([[1, 2, 3], [4, 5, 6]]), 2, "v").unwrap();
    assert_eq!((shape.clone(), m), (vec![2, 3], 1));
    assert_eq!(values, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert_eq!(
        nest(&values, &shape, m),
        json!([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])
    );
    let points = json!([[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]]);
    let (shape, m, values) = nested_array(&points, 1, "v").unwrap();
    assert_eq!((shape.clone(), m), (vec![3], 2));
    assert_eq!(nest(&values, &shape, m), points);
    for (value, depth, message) in [
        (
            json!([[1, 2], [3]]),
            2,
            "v: not a regular array of shape [2, 2] of numbers",
        ),
        (
            json!([[1, 2], [3, "x"]]),
            2,
            "v: not a regular array of shape [2, 2] of numbers",
        ),
        (
            json!([[1, 2], [3]]),
            1,
            "v: not a regular array of shape [2] of points of 2 numbers",
        ),
        (json!(5), 1, "v: level 0 is a number, not an array"),
        (json!([]), 1, "v: level 0 is empty"),
    ] {
        let e = nested_array(&value, depth, "v").unwrap_err();
        assert_eq!(e.kind(), ErrorKind::Parse);
        assert_eq!(e.message(), message);
    }
    let e = nested_array(&json!([[]]), 2, "v").unwrap_err();
    assert_eq!((e.message(), e.index()), ("v: level 1 is empty", Some(1)));
    // The bilinear spline with coefficients c_ij = 2 i + j on [0, 1]²: f(x, y) = 2x + y.
    let bilinear = json!({
        "degree": [1, 1],
        "knots": [[0, 0, 1, 1], [0, 0, 1, 1]],
        "coefficients": [[0, 1], [2, 3]]
    });
    let s: NdSpline = nd_from_value(&bilinear).unwrap();
    let mut out = [0.0; 2];
    s.eval_into(&[0.25, 0.5, 1.0, 0.0], &[0, 0], true, &mut out)
        .unwrap();
    assert_eq!(out, [1.0, 2.0]);
    assert_eq!(
        nd_to_value(&s).to_string(),
        r#"{"coefficients":[[0.0,1.0],[2.0,3.0]],"degree":[1,1],"knots":[[0.0,0.0,1.0,1.0],[0.0,0.0,1.0,1.0]]}"#
    );
    // A surface record (control points, no weights) reads as the same spline.
    let surface = json!({
        "degree": [1, 1],
        "knots": [[0, 0, 1, 1], [0, 0, 1, 1]],
        "control_points": [[[0], [1]], [[2], [3]]]
    });
    assert_eq!(
        nd_to_value(&nd_from_value(&surface).unwrap()),
        nd_to_value(&s)
    );
    let e = nd_from_value(&json!({"degree": [1], "knots": [[0, 0, 1, 1]]})).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Parse);
    assert!(
        e.message()
            .contains("needs \"degree\", \"knots\" and \"coefficients\""),
        "{e}"
    );
    let e = nd_from_value(&json!({"degree": 1, "knots": [], "coefficients": []})).unwrap_err();
    assert_eq!(
        e.message(),
        "malformed degree: expected an array, got the number 1"
    );
    // A spline of two columns: the rows its knots need, FITPACK's padding dropped.
    let columns = ColumnSpline::new(
        vec![0.0, 0.0, 1.0, 1.0],
        vec![1.0, 2.0, 3.0, 4.0, 0.0, 0.0],
        1,
        2,
    )
    .unwrap();
    assert_eq!(
        columns_to_value(&columns).to_string(),
        r#"{"control_points":[[1.0,2.0],[3.0,4.0]],"degree":1,"knots":[0.0,0.0,1.0,1.0]}"#
    );
}
