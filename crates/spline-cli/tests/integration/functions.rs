//! scipy's spline-function operations through the tool (`antiderivative`, `integrate`,
//! `roots`, `eval --extrapolate`, `nd-eval`, `nd-interpolate`): values from scipy 1.17 on the
//! same data (`BSpline(t, c, 3)` with the knots and coefficients below; `make_ndbspl` on the
//! grid below), and the error contract.

use crate::common::{spline, temp_file};
use serde_json::{Value, json};

const CURVE: &str = r#"{"degree": 3, "knots": [0,0,0,0,1,2.5,4,4,4,4],
  "control_points": [[1,0.5],[-0.5,2],[0.8,-1],[-1.2,0.3],[0.6,1.1],[-0.3,-0.7]]}"#;
const FUNCTION: &str = r#"{"degree": 3, "knots": [0,0,0,0,1,2.5,4,4,4,4],
  "control_points": [[1],[-0.5],[0.8],[-1.2],[0.6],[-0.3]]}"#;

fn numbers(value: &Value) -> Vec<f64> {
    match value {
        Value::Array(items) => items.iter().flat_map(numbers).collect(),
        Value::Number(x) => vec![x.as_f64().unwrap()],
        other => panic!("not numbers: {other}"),
    }
}

fn close(got: &Value, want: &[f64], tol: f64) {
    let got = numbers(got);
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g - w).abs() <= tol * (1.0 + w.abs()),
            "{got:?} vs {want:?}"
        );
    }
}

#[test]
fn antiderivative_integrals_and_extrapolation_match_scipy() {
    let curve = temp_file("curve.json", CURVE);
    let a = spline(&["antiderivative", &curve]).json();
    assert_eq!(a["degree"], json!(4));
    close(
        &a["knots"],
        &[0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2.5, 4.0, 4.0, 4.0, 4.0, 4.0],
        0.0,
    );
    let want = [
        0.0, 0.0, 0.25, 0.125, -0.0625, 1.375, 0.7375, 0.375, -0.4625, 0.675, -0.0125, 1.5, -0.125,
        1.2375,
    ];
    close(&a["control_points"], &want, 1e-14);
    // Its derivative is the curve again.
    let anti = temp_file("anti.json", &a.to_string());
    let back = spline(&["derivative", &anti]).json();
    let c = [
        1.0, 0.5, -0.5, 2.0, 0.8, -1.0, -1.2, 0.3, 0.6, 1.1, -0.3, -0.7,
    ];
    close(&back["control_points"], &c, 1e-13);

    let i = spline(&["integrate", &curve, "--from", "0.5", "--to", "3.7"]).json();
    close(&i, &[-0.2480374999999999, 0.7838874999999997], 1e-13);
    let i = spline(&[
        "integrate",
        &curve,
        "--from",
        "-1",
        "--to",
        "5.5",
        "--extrapolate",
        "on",
    ])
    .json();
    close(&i, &[-0.4073749999999974, -13.248593749999998], 1e-12);
    let i = spline(&[
        "integrate",
        &curve,
        "--from",
        "-1",
        "--to",
        "9.5",
        "--extrapolate",
        "periodic",
    ])
    .json();
    close(&i, &[-0.027486111111111017, 3.5878877314814814], 1e-12);
    // Limits outside the domain need --extrapolate.
    let e = spline(&["integrate", &curve, "--from", "-1", "--to", "2"]).assert_clean_error();
    assert!(e.contains("outside the domain"), "{e}");

    let v = spline(&[
        "eval",
        &curve,
        "--at",
        "[-0.5, 4.5]",
        "--derivatives",
        "1",
        "--extrapolate",
        "on",
    ])
    .json();
    close(
        &v,
        &[
            5.0685,
            -4.188750000000001,
            -12.381,
            15.082500000000003,
            -1.897222222222222,
            -3.313194444444444,
            -4.783333333333333,
            -7.012499999999999,
        ],
        1e-12,
    );
    let v = spline(&[
        "eval",
        &curve,
        "--at",
        "[5.0, -1.0]",
        "--extrapolate",
        "periodic",
    ])
    .json();
    close(
        &v,
        &[
            0.132,
            0.21000000000000016,
            -0.12222222222222216,
            0.6055555555555556,
        ],
        1e-12,
    );
    let e = spline(&["eval", &curve, "--at", "[5.0]", "--extrapolate", "off"]).assert_clean_error();
    assert!(e.contains("outside the domain"), "{e}");
}

#[test]
fn roots_match_scipy() {
    let function = temp_file("function.json", FUNCTION);
    let r = spline(&["roots", &function]).json();
    let want = [
        0.4187089129506392,
        0.7303416401463766,
        1.6078155670714231,
        3.1959508605348446,
        3.765690533588967,
    ];
    close(&r, &want, 1e-12);
    let curve = temp_file("curve.json", CURVE);
    let e = spline(&["roots", &curve]).assert_clean_error();
    assert!(e.contains("--coordinate"), "{e}");
    let r = spline(&["roots", &curve, "--coordinate", "0"]).json();
    close(&r, &want, 1e-12);
    let e = spline(&["roots", &curve, "--coordinate", "2"]).assert_clean_error();
    assert!(e.contains("column 2"), "{e}");
}

#[test]
fn nd_interpolation_and_evaluation_match_scipy() {
    let x = [0.0_f64, 1.0, 2.0, 3.0, 4.0];
    let y = [0.0_f64, 1.5, 2.5, 4.0];
    let values: Vec<Vec<f64>> = x
        .iter()
        .map(|&a| y.iter().map(|&b| a.sin() * b.cos() + 0.1 * a).collect())
        .collect();
    let s = spline(&[
        "nd-interpolate",
        "--grid",
        &json!([x, y]).to_string(),
        "--values",
        &json!(values).to_string(),
    ])
    .json();
    assert_eq!(s["degree"], json!([3, 3]));
    assert_eq!(s["knots"][0].as_array().unwrap().len(), 9);
    assert_eq!(s["knots"][1].as_array().unwrap().len(), 8);
    let file = temp_file("nd.json", &s.to_string());
    let v = spline(&["nd-eval", &file, "--at", "[[0.5, 0.7], [3.3, 3.9], [2, 2]]"]).json();
    close(
        &v,
        &[0.4242005609049399, 0.4480156469170303, -0.16471492423837011],
        1e-12,
    );
    let v = spline(&[
        "nd-eval",
        &file,
        "--at",
        "[[0.5, 0.7], [3.3, 3.9]]",
        "--nu",
        "[1, 1]",
    ])
    .json();
    close(&v, &[-0.5588525483062965, -0.9490703422130465], 1e-11);
    // Errors: a point of the wrong dimension, outside without extrapolation, ragged values.
    let e = spline(&["nd-eval", &file, "--at", "[[0.5]]"]).assert_clean_error();
    assert!(e.contains("2 dimensions"), "{e}");
    let e = spline(&["nd-eval", &file, "--at", "[[5, 1]]", "--extrapolate", "off"])
        .assert_clean_error();
    assert!(e.contains("outside"), "{e}");
    // scipy's NdBSpline has no periodic extrapolation: refused, not taken for `on`.
    let e = spline(&[
        "nd-eval",
        &file,
        "--at",
        "[[5, 1]]",
        "--extrapolate",
        "periodic",
    ]);
    assert_eq!(e.status, 2, "{}", e.stderr);
    assert!(
        e.stdout.is_empty() && e.stderr.contains("periodic"),
        "{}",
        e.stderr
    );
    let e = spline(&[
        "nd-interpolate",
        "--grid",
        "[[0,1,2,3],[0,1,2,3]]",
        "--values",
        "[[1,2,3,4],[1,2,3]]",
    ])
    .assert_clean_error();
    assert!(e.contains("regular array"), "{e}");
}

#[test]
fn rational_curves_are_refused() {
    let nurbs = temp_file(
        "nurbs.json",
        r#"{"degree": 2, "knots": [0,0,0,1,1,1], "control_points": [[1,0],[1,1],[0,1]], "weights": [1,0.7,1]}"#,
    );
    let e = spline(&["antiderivative", &nurbs]).assert_clean_error();
    assert!(e.contains("non-rational"), "{e}");
}
