//! Every case of `tests/data/reference/{nurbs_eval,surface_eval}.json` (computed by
//! scipy.interpolate, independently of this library) through the library: rational
//! derivatives of NURBS curves and partial derivatives of tensor-product surfaces.

use nalgebra::SVector;
use serde_json::Value;
use spline_geom::exchange::{CurveRecord, SurfaceRecord};
use spline_geom::{CircleConstruction, Frame, NurbsCurve, NurbsSurface, Surface};
use spline_testing::compare::assert_close;
use spline_testing::reference::{cases, flatten};

fn params(v: &Value) -> Vec<f64> {
    flatten(v)
}

fn check_nurbs<const D: usize>(case: &Value) -> usize {
    let name = case["name"].as_str().unwrap();
    let record: CurveRecord = serde_json::from_value(case["curve"].clone()).unwrap();
    let curve: NurbsCurve<f64, D> = record.to_nurbs().unwrap();
    // Serde goes through the same record.
    let via_serde: NurbsCurve<f64, D> = serde_json::from_value(case["curve"].clone()).unwrap();
    assert_eq!(curve, via_serde);
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
        let record: CurveRecord = serde_json::from_value(case["curve"].clone()).unwrap();
        count += match record.dimension().unwrap() {
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
    let record: CurveRecord = serde_json::from_value(case["curve"].clone()).unwrap();
    let built = NurbsCurve::circle(
        &Frame::planar(nalgebra::Vector2::zeros()),
        1.0,
        CircleConstruction::Square,
    )
    .unwrap();
    assert_eq!(CurveRecord::from_nurbs(&built), record);
}

fn check_surface<const D: usize>(case: &Value) -> usize {
    let name = case["name"].as_str().unwrap();
    let record: SurfaceRecord = serde_json::from_value(case["surface"].clone()).unwrap();
    let rational = record.is_rational();
    let order = case["derivatives"].as_u64().unwrap() as usize;
    let expected = case["expected"].as_array().unwrap();
    let uv = case["params"].as_array().unwrap();
    let nurbs: NurbsSurface<f64, D> = record.to_nurbs_surface().unwrap();
    let plain: Option<Surface<f64, SVector<f64, D>>> =
        (!rational).then(|| record.to_surface().unwrap());
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
        let record: SurfaceRecord = serde_json::from_value(case["surface"].clone()).unwrap();
        count += match record.dimension().unwrap() {
            1 => check_surface::<1>(case),
            2 => check_surface::<2>(case),
            3 => check_surface::<3>(case),
            d => panic!("dimension {d} not covered"),
        };
    }
    assert!(count >= 96);
}

/// Serialising a surface read from a reference case gives back the same JSON object.
#[test]
fn surface_records_round_trip() {
    for case in &cases("surface_eval") {
        let s: Surface<f64, SVector<f64, 3>> =
            serde_json::from_value(case["surface"].clone()).unwrap();
        let back = serde_json::to_value(&s).unwrap();
        assert_eq!(
            flatten(&back["control_points"]),
            flatten(&case["surface"]["control_points"])
        );
        assert_eq!(back["degree"], case["surface"]["degree"]);
        assert_eq!(flatten(&back["knots"]), flatten(&case["surface"]["knots"]));
    }
}
