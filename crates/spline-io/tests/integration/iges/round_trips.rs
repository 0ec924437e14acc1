//! Curves and surfaces of every degree through a file and back bit for bit.

use super::{Numbers, bits, bits3, item, knots, one};
use nalgebra::{Vector2, Vector3};
use spline_core::ErrorKind;
use spline_geom::{BSpline, NurbsCurve2, NurbsCurve3, NurbsSurface3, Surface};
use spline_io::Geometry;
use spline_io::iges::{read_iges, write_iges};

#[test]
fn polynomial_curves_round_trip_bit_for_bit() {
    let mut rng = Numbers(1);
    for p in 1..=7 {
        for clamped in [true, false] {
            let kv = knots(p, clamped);
            let points: Vec<_> = (0..kv.num_basis()).map(|_| rng.point3()).collect();
            let curve = BSpline::new(kv, points).unwrap();
            let text = write_iges(&[item("c", Geometry::Curve3(curve.clone()))]).unwrap();
            assert!(text.lines().all(|l| l.len() == 80));
            let back = one(&text);
            // Unclamped curves come back clamped: the same curve on the same parameters.
            let curve = curve.clamped();
            assert_eq!(back.entity, "126");
            assert_eq!(back.id, 1);
            assert_eq!(back.name, "c");
            let Geometry::Curve3(c) = back.geometry else {
                panic!("degree {p}: not a polynomial curve");
            };
            assert_eq!(bits(c.knots().knots()), bits(curve.knots().knots()));
            assert_eq!(bits3(c.control_points()), bits3(curve.control_points()));
            assert_eq!(c.degree(), p);
        }
    }
}

#[test]
fn rational_curves_round_trip_bit_for_bit() {
    let mut rng = Numbers(2);
    for p in 1..=7 {
        let kv = knots(p, p % 2 == 0);
        let n = kv.num_basis();
        let points: Vec<_> = (0..n).map(|_| rng.point3()).collect();
        let weights: Vec<_> = (0..n).map(|_| rng.weight()).collect();
        let curve = NurbsCurve3::new(kv, points, weights).unwrap();
        let text = write_iges(&[item("r", Geometry::NurbsCurve3(curve.clone()))]).unwrap();
        let Geometry::NurbsCurve3(c) = one(&text).geometry else {
            panic!("degree {p}: not rational");
        };
        let curve = curve.clamped();
        assert_eq!(bits(c.knots().knots()), bits(curve.knots().knots()));
        assert_eq!(bits(c.weights()), bits(curve.weights()));
        assert_eq!(bits3(c.control_points()), bits3(curve.control_points()));
        // Written again, the text is the same (the file's numbers are a fixed point).
        let again = write_iges(&[item("r", Geometry::NurbsCurve3(c))]).unwrap();
        let strip = |t: &str| {
            t.lines()
                .filter(|l| !l.contains('G'))
                .map(|l| l[..72].to_string())
                .collect::<Vec<_>>()
        };
        assert_eq!(strip(&again)[1..], strip(&text)[1..]);
    }
}

#[test]
fn planar_curves_are_written_in_z_0_and_read_as_3d() {
    let mut rng = Numbers(3);
    let kv = knots(3, true);
    let n = kv.num_basis();
    let points: Vec<_> = (0..n)
        .map(|_| Vector2::new(rng.next(), rng.next()))
        .collect();
    let weights: Vec<_> = (0..n).map(|_| rng.weight()).collect();
    let poly = BSpline::new(kv.clone(), points.clone()).unwrap();
    let rational = NurbsCurve2::new(kv, points, weights).unwrap();
    let text = write_iges(&[
        item("p", Geometry::Curve2(poly.clone())),
        item("q", Geometry::NurbsCurve2(rational.clone())),
    ])
    .unwrap();
    // PROP1 = 1 (planar), normal (0, 0, 1) before the terminator.
    assert!(text.contains("126,9,3,1,0,1,0,"));
    assert!(text.contains("0.0,0.0,1.0;"));
    let items = read_iges(&text).unwrap();
    assert_eq!((items[0].id, items[1].id), (1, 3));
    let Geometry::Curve3(c) = &items[0].geometry else {
        panic!()
    };
    assert!(c.control_points().iter().all(|p| p.z.to_bits() == 0));
    let xy: Vec<_> = c
        .control_points()
        .iter()
        .map(|p| [p.x.to_bits(), p.y.to_bits()])
        .collect();
    let want: Vec<_> = poly
        .control_points()
        .iter()
        .map(|p| [p.x.to_bits(), p.y.to_bits()])
        .collect();
    assert_eq!(xy, want);
    let Geometry::NurbsCurve3(r) = &items[1].geometry else {
        panic!()
    };
    assert_eq!(bits(r.weights()), bits(rational.weights()));
    let xy: Vec<_> = r
        .control_points()
        .iter()
        .map(|p| [p.x.to_bits(), p.y.to_bits()])
        .collect();
    let want: Vec<_> = rational
        .control_points()
        .iter()
        .map(|p| [p.x.to_bits(), p.y.to_bits()])
        .collect();
    assert_eq!(xy, want);
}

#[test]
fn surfaces_round_trip_bit_for_bit() {
    let mut rng = Numbers(4);
    for (p, q) in [(1, 1), (3, 2), (2, 5), (7, 1)] {
        let (ku, kv) = (knots(p, true), knots(q, false));
        let count = ku.num_basis() * kv.num_basis();
        let points: Vec<_> = (0..count).map(|_| rng.point3()).collect();
        let weights: Vec<_> = (0..count).map(|_| rng.weight()).collect();
        let poly = Surface::new(ku.clone(), kv.clone(), points.clone()).unwrap();
        let rational = NurbsSurface3::new(ku, kv, points, weights).unwrap();
        let text = write_iges(&[
            item("s", Geometry::Surface(poly.clone())),
            item("n", Geometry::NurbsSurface(rational.clone())),
        ])
        .unwrap();
        let items = read_iges(&text).unwrap();
        let (poly, rational) = (poly.clamped(), rational.clamped());
        assert_eq!(items[0].entity, "128");
        let Geometry::Surface(s) = &items[0].geometry else {
            panic!()
        };
        assert_eq!(s.net_size(), poly.net_size());
        assert_eq!(bits(s.knots_u().knots()), bits(poly.knots_u().knots()));
        assert_eq!(bits(s.knots_v().knots()), bits(poly.knots_v().knots()));
        assert_eq!(bits3(s.control_points()), bits3(poly.control_points()));
        let Geometry::NurbsSurface(r) = &items[1].geometry else {
            panic!()
        };
        assert_eq!(bits(r.weights()), bits(rational.weights()));
        assert_eq!(bits3(r.control_points()), bits3(rational.control_points()));
    }
}

#[test]
fn names_go_to_the_label_and_a_name_property() {
    let c = BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector3::zeros(), Vector3::x()],
    )
    .unwrap();
    let text = write_iges(&[
        item("short", Geometry::Curve3(c.clone())),
        item(
            "a name longer than eight characters",
            Geometry::Curve3(c.clone()),
        ),
        item("", Geometry::Curve3(c)),
    ])
    .unwrap();
    assert!(text.contains("35Ha name longer than eight characters;"));
    let items = read_iges(&text).unwrap();
    let names: Vec<_> = items.iter().map(|i| (i.id, i.name.as_str())).collect();
    assert_eq!(
        names,
        [
            (1, "short"),
            (3, "a name longer than eight characters"),
            (7, "")
        ]
    );
    let bad = item("é", items[0].geometry.clone());
    let e = write_iges(&[items[0].clone(), bad]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(e.index(), Some(1));
}
