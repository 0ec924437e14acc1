//! Every case of `tests/data/reference/{nurbs_eval,surface_eval}.json` (computed by
//! scipy.interpolate, independently of this library) through the library: rational
//! derivatives of NURBS curves and partial derivatives of tensor-product surfaces.

use nalgebra::SVector;
use serde_json::Value;
use spline_core::KnotVector;
use spline_geom::{CircleConstruction, Frame, NurbsCurve, NurbsSurface, Surface};
use spline_testing::compare::assert_close;
use spline_testing::reference::{cases, f64s, flatten};

fn params(v: &Value) -> Vec<f64> {
    flatten(v)
}

/// The points of a JSON array of coordinate arrays.
fn points<const D: usize>(rows: &Value) -> Vec<SVector<f64, D>> {
    rows.as_array()
        .unwrap()
        .iter()
        .map(|r| SVector::from_column_slice(&f64s(r)))
        .collect()
}

/// The number of coordinates of a case's curve (`[[x, …], …]`) or surface (one level more).
fn dimension(v: &Value, surface: bool) -> usize {
    let first = &v["control_points"][0];
    let point = if surface { &first[0] } else { first };
    point.as_array().unwrap().len()
}

/// The weights of a case's curve, unit weights if it has none.
fn curve_weights(v: &Value) -> Vec<f64> {
    v.get("weights").map_or_else(
        || vec![1.0; v["control_points"].as_array().unwrap().len()],
        f64s,
    )
}

/// A case's curve (`{"degree", "knots", "control_points"[, "weights"]}`) as a NURBS curve,
/// built directly (the exchange format's reader is spline-io's).
fn nurbs_curve<const D: usize>(v: &Value) -> NurbsCurve<f64, D> {
    let degree = v["degree"].as_u64().unwrap() as usize;
    let knots = KnotVector::new(degree, f64s(&v["knots"])).unwrap();
    NurbsCurve::new(knots, points(&v["control_points"]), curve_weights(v)).unwrap()
}

/// A case's surface: knot vectors and net.
fn surface_net<const D: usize>(
    v: &Value,
) -> (KnotVector<f64>, KnotVector<f64>, Vec<Vec<SVector<f64, D>>>) {
    let knots = |i: usize| {
        KnotVector::new(
            v["degree"][i].as_u64().unwrap() as usize,
            f64s(&v["knots"][i]),
        )
        .unwrap()
    };
    let net = v["control_points"]
        .as_array()
        .unwrap()
        .iter()
        .map(points)
        .collect();
    (knots(0), knots(1), net)
}

fn check_nurbs<const D: usize>(case: &Value) -> usize {
    let name = case["name"].as_str().unwrap();
    let curve: NurbsCurve<f64, D> = nurbs_curve(&case["curve"]);
    let order = case["derivatives"].as_u64().unwrap() as usize;
    let expected = case["expected"].as_array().unwrap();
    let mut count = 0;
    for (u, exp) in params(&case["params"]).iter().zip(expected) {
        let ders = curve.derivatives(*u, order).unwrap();
        let got: Vec<f64> = ders.iter().flat_map(|p| p.iter().copied()).collect();
        // Relative to the size of each derivative order.
        let exp_flat = flatten(exp);
        let scale = exp_flat.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        assert_close(&got, &exp_flat, 1e-9 * scale, &format!("{name} u={u}"));
        // The point alone and the many-point path agree with the derivatives.
        assert_eq!(curve.eval(*u).unwrap(), ders[0]);
        count += 1;
    }
    let all = curve.eval_many(&params(&case["params"])).unwrap();
    for (p, exp) in all.iter().zip(expected) {
        assert_close(
            p.as_slice(),
            &flatten(&exp[0]),
            1e-12,
            &format!("{name} eval_many"),
        );
    }
    count
}

#[test]
fn nurbs_curve_rational_derivatives() {
    let all = cases("nurbs_eval");
    assert!(all.len() >= 13);
    let mut count = 0;
    for case in &all {
        count += match dimension(&case["curve"], false) {
            1 => check_nurbs::<1>(case),
            2 => check_nurbs::<2>(case),
            3 => check_nurbs::<3>(case),
            4 => check_nurbs::<4>(case),
            d => panic!("dimension {d} not covered"),
        };
    }
    assert!(count > 100);
}

/// The case `circle-9` is exactly the 9-point circle of the notes (6.9)–(6.10), as built by
/// the library.
#[test]
fn circle_9_is_the_square_construction() {
    let case = cases("nurbs_eval")
        .into_iter()
        .find(|c| c["name"] == "circle-9")
        .expect("circle-9");
    let built = NurbsCurve::circle(
        &Frame::planar(nalgebra::Vector2::zeros()),
        1.0,
        CircleConstruction::Square,
    )
    .unwrap();
    let expected = &case["curve"];
    assert_eq!(built.degree() as u64, expected["degree"].as_u64().unwrap());
    assert_eq!(built.knots().knots(), f64s(&expected["knots"]).as_slice());
    let cartesian: Vec<f64> = built
        .control_points()
        .iter()
        .flat_map(|p| p.iter().copied())
        .collect();
    assert_eq!(cartesian, flatten(&expected["control_points"]));
    assert_eq!(built.weights(), f64s(&expected["weights"]));
}

fn check_surface<const D: usize>(case: &Value) -> usize {
    let name = case["name"].as_str().unwrap();
    let v = &case["surface"];
    let rational = v.get("weights").is_some();
    let order = case["derivatives"].as_u64().unwrap() as usize;
    let expected = case["expected"].as_array().unwrap();
    let uv = case["params"].as_array().unwrap();
    let (ku, kv, net) = surface_net::<D>(v);
    let weights = match v.get("weights") {
        Some(w) => w.as_array().unwrap().iter().map(f64s).collect(),
        None => net.iter().map(|row| vec![1.0; row.len()]).collect(),
    };
    let nurbs = NurbsSurface::from_net(ku.clone(), kv.clone(), net.clone(), weights).unwrap();
    let plain: Option<Surface<f64, SVector<f64, D>>> =
        (!rational).then(|| Surface::from_net(ku, kv, net).unwrap());
    let mut count = 0;
    for (p, exp) in uv.iter().zip(expected) {
        let (u, v) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
        let exp_flat = flatten(exp);
        let scale = exp_flat.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        let what = format!("{name} (u, v) = ({u}, {v})");
        let rat: Vec<f64> = nurbs
            .derivatives(u, v, order)
            .unwrap()
            .iter()
            .flatten()
            .flat_map(|p| p.iter().copied())
            .collect();
        assert_close(&rat, &exp_flat, 1e-9 * scale, &format!("{what} (as NURBS)"));
        if let Some(s) = &plain {
            let got: Vec<f64> = s
                .derivatives(u, v, order)
                .unwrap()
                .iter()
                .flatten()
                .flat_map(|p| p.iter().copied())
                .collect();
            assert_close(&got, &exp_flat, 1e-9 * scale, &what);
            let point = flatten(&exp[0][0]);
            assert_close(s.eval(u, v).unwrap().as_slice(), &point, 1e-12, &what);
            assert_close(s.de_boor(u, v).unwrap().as_slice(), &point, 1e-12, &what);
            let grid = s.eval_grid(&[u], &[v]).unwrap();
            assert_close(grid[0].as_slice(), &point, 1e-12, &what);
        }
        count += 1;
    }
    count
}

#[test]
fn surface_partial_derivatives() {
    let all = cases("surface_eval");
    assert!(all.len() >= 12);
    let mut count = 0;
    for case in &all {
        count += match dimension(&case["surface"], true) {
            1 => check_surface::<1>(case),
            2 => check_surface::<2>(case),
            3 => check_surface::<3>(case),
            d => panic!("dimension {d} not covered"),
        };
    }
    assert!(count >= 96);
}
