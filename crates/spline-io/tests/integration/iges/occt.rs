//! Files written by Open CASCADE read, and files for Open CASCADE to read written.

use super::{Numbers, item, knots};
use nalgebra::{Vector2, Vector3};
use spline_geom::{BSpline, NurbsCurve3, NurbsSurface3, Surface};
use spline_io::iges::{read_iges_bytes, write_iges};
use spline_io::{Geometry, Item};

/// Files written by Open CASCADE 8.0 (`tests/data/iges/occt_write.py`).
fn occt_file(name: &str) -> Vec<Item> {
    let path = format!("{}/tests/data/iges/{name}", env!("CARGO_MANIFEST_DIR"));
    read_iges_bytes(&std::fs::read(path).unwrap()).unwrap()
}

#[test]
fn occt_bspline_curve_and_surface() {
    let items = occt_file("occt_bspline.igs");
    let kinds: Vec<_> = items.iter().map(|i| (i.id, i.entity.as_str())).collect();
    assert_eq!(
        kinds,
        [
            (5, "128"),
            (11, "126"),
            (15, "126"),
            (17, "126"),
            (19, "126"),
            (21, "110"),
            (23, "110"),
            (25, "110"),
            (27, "110"),
            (29, "126")
        ]
    );
    // The face: P(i, j) = (i, j, i j + i²/10), degrees (2, 1); the point at (0.3, 0.7)
    // printed by the script (Geom_BSplineSurface::Value).
    let Geometry::Surface(s) = &items[0].geometry else {
        panic!()
    };
    assert_eq!((s.degrees(), s.net_size()), ((2, 1), (4, 3)));
    for i in 0..4 {
        for j in 0..3 {
            let (x, y) = (i as f64, j as f64);
            assert!(
                (s.control_point(i, j) - Vector3::new(x, y, x * y + 0.1 * x * x)).norm() < 1e-15
            );
        }
    }
    assert_eq!(s.knots_u().knots(), [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]);
    let occt = Vector3::new(1.02, 1.4, 1.5659999999999998);
    assert!((s.eval(0.3, 0.7).unwrap() - occt).norm() < 1e-14);
    // The edge: the rational cubic of the script, its point at 0.3 from
    // Geom_BSplineCurve::Value.
    let Geometry::NurbsCurve3(c) = &items[9].geometry else {
        panic!()
    };
    assert_eq!(c.weights(), [1.0, 0.5, 2.0, 1.5, 0.75, 1.0]);
    assert_eq!(
        c.knots().knots(),
        [0.0, 0.0, 0.0, 0.0, 0.4, 0.4, 1.0, 1.0, 1.0, 1.0]
    );
    assert_eq!(c.control_points()[3], Vector3::new(3.0, 0.5, 1.0));
    let occt = Vector3::new(2.089731729879741, -0.641073080481036, 0.37049028677150786);
    assert!((c.eval(0.3).unwrap() - occt).norm() < 1e-14);
}

#[test]
fn occt_box_with_a_fillet_and_a_cylinder() {
    // 186/514/510/508/504/502 B-rep, planes (190), cylinders (192), points and
    // directions (116, 123) skipped; lines and arcs (with 124 matrices) read.
    let items = occt_file("occt_fillet_box.igs");
    let count = |e: &str| items.iter().filter(|i| i.entity == e).count();
    assert_eq!((count("110"), count("100"), items.len()), (22, 4, 26));
    let arcs: Vec<_> = items
        .iter()
        .filter_map(|i| match &i.geometry {
            Geometry::NurbsCurve3(c) if i.entity == "100" => Some(c),
            _ => None,
        })
        .collect();
    // The fillet of radius 2 about the edge x = y = 0 of the box 10 × 20 × 30: quarter
    // arcs about (2, 2, z) from (0, 2, z) to (2, 0, z), z = 0 and 30 (OCCT writes about
    // ten digits); the cylinder: circles of radius 3 about (50, 0, z), z = 0 and 7.
    for (arc, center, radius) in [
        (arcs[0], Vector3::new(2.0, 2.0, 30.0), 2.0),
        (arcs[1], Vector3::new(2.0, 2.0, 0.0), 2.0),
        (arcs[2], Vector3::new(50.0, 0.0, 7.0), 3.0),
        (arcs[3], Vector3::new(50.0, 0.0, 0.0), 3.0),
    ] {
        for t in [0.0, 0.1, 0.5, 0.77, 1.0] {
            let p = arc.eval(t).unwrap();
            assert!(((p - center).norm() - radius).abs() < 1e-9, "{p:?}");
        }
    }
    assert!((arcs[0].eval(0.0).unwrap() - Vector3::new(0.0, 2.0, 30.0)).norm() < 1e-9);
    assert!((arcs[0].eval(1.0).unwrap() - Vector3::new(2.0, 0.0, 30.0)).norm() < 1e-9);
}

/// Writes `$IGES_OUT/ours.igs` and `$IGES_OUT/ours.json` (the values) for
/// `tests/data/iges/occt_check.py`, which reads the file with Open CASCADE and compares.
#[test]
#[ignore = "writes files for the Open CASCADE check"]
fn write_files_for_occt() {
    let dir = std::env::var("IGES_OUT").unwrap();
    let mut rng = Numbers(9);
    let kv = knots(3, true);
    let n = kv.num_basis();
    let points: Vec<_> = (0..n).map(|_| rng.point3()).collect();
    let weights: Vec<_> = (0..n).map(|_| rng.weight()).collect();
    let rational = NurbsCurve3::new(kv.clone(), points.clone(), weights).unwrap();
    let poly = BSpline::new(
        knots(5, true),
        (0..knots(5, true).num_basis())
            .map(|_| rng.point3())
            .collect(),
    )
    .unwrap();
    let planar = BSpline::new(kv, points.iter().map(|p| Vector2::new(p.x, p.y)).collect()).unwrap();
    let (ku, kv) = (knots(3, true), knots(2, true));
    let count = ku.num_basis() * kv.num_basis();
    let net: Vec<_> = (0..count).map(|_| rng.point3()).collect();
    let w: Vec<_> = (0..count).map(|_| rng.weight()).collect();
    let surface = Surface::new(ku.clone(), kv.clone(), net.clone()).unwrap();
    let nurbs = NurbsSurface3::new(ku, kv, net, w).unwrap();
    let items = [
        item("rational cubic", Geometry::NurbsCurve3(rational.clone())),
        item("quintic", Geometry::Curve3(poly.clone())),
        item("planar", Geometry::Curve2(planar.clone())),
        item("surface", Geometry::Surface(surface.clone())),
        item("nurbs surface", Geometry::NurbsSurface(nurbs.clone())),
    ];
    std::fs::write(format!("{dir}/ours.igs"), write_iges(&items).unwrap()).unwrap();
    let v3 = |p: &[Vector3<f64>]| p.iter().map(|q| vec![q.x, q.y, q.z]).collect::<Vec<_>>();
    let json = format!(
        "{{\"curves\": [[{:?}, {:?}, {:?}], [{:?}, {:?}, null], [{:?}, {:?}, null]], \"surfaces\": [[{:?}, {:?}, {:?}, {:?}, null], [{:?}, {:?}, {:?}, {:?}, {:?}]]}}",
        rational.knots().knots(), v3(rational.control_points()), rational.weights(),
        poly.knots().knots(), v3(poly.control_points()),
        planar.knots().knots(), v3(&planar.control_points().iter().map(|p| Vector3::new(p.x, p.y, 0.0)).collect::<Vec<_>>()),
        surface.knots_u().knots(), surface.knots_v().knots(), surface.net_size(), v3(surface.control_points()),
        nurbs.knots_u().knots(), nurbs.knots_v().knots(), nurbs.net_size(), v3(nurbs.control_points()), nurbs.weights(),
    )
    .replace('(', "[")
    .replace(')', "]");
    std::fs::write(format!("{dir}/ours.json"), json).unwrap();
}
