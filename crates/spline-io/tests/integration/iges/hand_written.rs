//! Hand-written files: parameter ranges, the u-fastest order of 128, lines, arcs, surfaces
//! of revolution and tabulated cylinders, transformation matrices, name properties.

use super::{Hand, QUARTER, ROTATE_Z, SHIFT_X, hand_file, one};
use nalgebra::Vector3;
use spline_io::Geometry;
use spline_io::iges::read_iges;
use std::f64::consts::{FRAC_PI_2, PI};

#[test]
fn hand_written_quarter_circle_restricted_to_its_range() {
    let text = hand_file(&[Hand(126, 0, 0, "ARC1", QUARTER)]);
    let item = one(&text);
    assert_eq!(
        (item.id, item.name.as_str(), item.entity.as_str()),
        (1, "ARC1", "126")
    );
    let Geometry::NurbsCurve3(c) = item.geometry else {
        panic!()
    };
    assert_eq!(c.domain(), (0.25, 0.75));
    for t in [0.25, 0.3, 0.5, 0.6, 0.75] {
        let want = Vector3::new((1.0 - t * t) / (1.0 + t * t), 2.0 * t / (1.0 + t * t), 0.0);
        assert!((c.eval(t).unwrap() - want).norm() < 1e-15, "t = {t}");
    }
    // The full range reads the curve as written.
    let full = QUARTER.replace("0.25,0.75", "0.,1.");
    let Geometry::NurbsCurve3(c) = one(&hand_file(&[Hand(126, 0, 0, "", &full)])).geometry else {
        panic!()
    };
    assert_eq!(c.weights(), [1.0, 1.0, 2.0]);
    assert_eq!(c.control_points()[1], Vector3::new(1.0, 1.0, 0.0));
}

#[test]
fn hand_written_surface_has_the_u_index_fastest() {
    // K1 = 1, K2 = 2, M1 = 1, M2 = 2: P(i, j) = (i, j, 10 i + j), listed i fastest, so
    // S(u, v) = (u, 2v, 10u + 2v).
    let params = "128,1,2,1,2,0,0,1,0,0,0.,0.,1.,1.,0.,0.,0.,1.,1.,1.,\
                  1.,1.,1.,1.,1.,1.,\
                  0.,0.,0.,1.,0.,10.,0.,1.,1.,1.,1.,11.,0.,2.,2.,1.,2.,12.,\
                  0.,1.,0.,1.;";
    let item = one(&hand_file(&[Hand(128, 0, 0, "PATCH", params)]));
    let Geometry::Surface(s) = item.geometry else {
        panic!()
    };
    assert_eq!(s.net_size(), (2, 3));
    assert_eq!(s.control_point(1, 2), Vector3::new(1.0, 2.0, 12.0));
    let (u, v) = (0.3, 0.6);
    assert!((s.eval(u, v).unwrap() - Vector3::new(u, 2.0 * v, 10.0 * u + 2.0 * v)).norm() < 1e-14);
    // A range narrower in v restricts the surface exactly.
    let narrow = params.replace("0.,1.,0.,1.;", "0.,1.,0.5,1.;");
    let Geometry::Surface(s) = one(&hand_file(&[Hand(128, 0, 0, "", &narrow)])).geometry else {
        panic!()
    };
    assert_eq!(s.domain(), ((0.0, 1.0), (0.5, 1.0)));
    assert!((s.eval(u, 0.75).unwrap() - Vector3::new(u, 1.5, 10.0 * u + 1.5)).norm() < 1e-14);
}

#[test]
fn lines_arcs_and_transformations() {
    let text = hand_file(&[
        Hand(124, 0, 5, "", SHIFT_X), // 1: shift by x, then the matrix at 5
        Hand(110, 0, 1, "L1", "110,0.,0.,0.,1.,2.,3.;"), // 3
        Hand(124, 0, 0, "", ROTATE_Z), // 5
        Hand(100, 0, 0, "A1", "100,5.,1.,1.,2.,1.,1.,2.;"), // 7: quarter arc at z = 5
        Hand(100, 0, 0, "C1", "100,0.,0.,0.,2.,0.,2.,0.;"), // 9: full circle r = 2
        Hand(314, 0, 0, "", "314,50.,50.,50.;"), // 11: a colour, skipped
        Hand(110, 1, 0, "", "110,0.,0.,0.,1.,0.,0.;"), // 13: a ray, skipped
    ]);
    let items = read_iges(&text).unwrap();
    let ids: Vec<_> = items
        .iter()
        .map(|i| (i.id, i.entity.as_str(), i.name.as_str()))
        .collect();
    assert_eq!(ids, [(3, "110", "L1"), (7, "100", "A1"), (9, "100", "C1")]);
    // The line: x ↦ R(x + (1, 0, 0)), R the rotation by 90° about z.
    let Geometry::Curve3(line) = &items[0].geometry else {
        panic!()
    };
    assert_eq!(
        line.control_points(),
        [Vector3::new(0.0, 1.0, 0.0), Vector3::new(-2.0, 2.0, 3.0)]
    );
    let Geometry::NurbsCurve3(arc) = &items[1].geometry else {
        panic!()
    };
    let center = Vector3::new(1.0, 1.0, 5.0);
    for t in [0.0, 0.2, 0.5, 0.9, 1.0] {
        let p = arc.eval(t).unwrap();
        assert!(((p - center).norm() - 1.0).abs() < 1e-15);
    }
    assert!((arc.eval(0.0).unwrap() - Vector3::new(2.0, 1.0, 5.0)).norm() < 1e-15);
    assert!((arc.eval(1.0).unwrap() - Vector3::new(1.0, 2.0, 5.0)).norm() < 1e-15);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!((arc.eval(0.5).unwrap() - (center + Vector3::new(h, h, 0.0))).norm() < 1e-15);
    let Geometry::NurbsCurve3(circle) = &items[2].geometry else {
        panic!()
    };
    for t in [0.0, 0.1, 0.37, 0.5, 0.81] {
        assert!((circle.eval(t).unwrap().norm() - 2.0).abs() < 1e-15);
    }
    assert!((circle.eval(0.25).unwrap() - Vector3::new(0.0, 2.0, 0.0)).norm() < 1e-15);
    assert_eq!(circle.eval(1.0).unwrap(), Vector3::new(2.0, 0.0, 0.0));
}

#[test]
fn surfaces_of_revolution_and_tabulated_cylinders() {
    let text = hand_file(&[
        Hand(110, 0, 0, "AXIS", "110,0.,0.,0.,0.,0.,1.;"), // 1
        Hand(110, 0, 0, "GEN", "110,1.,0.,0.,1.,0.,2.;"),  // 3
        Hand(120, 0, 0, "REV", &format!("120,1,3,{FRAC_PI_2:?},{PI:?};")), // 5
        Hand(122, 0, 0, "TAB", "122,3,4.,5.,0.;"),         // 7
    ]);
    let items = read_iges(&text).unwrap();
    let ids: Vec<_> = items.iter().map(|i| (i.id, i.entity.as_str())).collect();
    assert_eq!(ids, [(1, "110"), (3, "110"), (5, "120"), (7, "122")]);
    // The half-cylinder x² + y² = 1, 0 ≤ z ≤ 2, from angle π/2 to π.
    let Geometry::NurbsSurface(rev) = &items[2].geometry else {
        panic!()
    };
    for (u, v) in [(0.0, 0.0), (0.5, 0.3), (1.0, 1.0), (0.25, 0.5)] {
        let p = rev.eval(u, v).unwrap();
        assert!((p.x.hypot(p.y) - 1.0).abs() < 1e-15);
        assert!((p.z - 2.0 * u).abs() < 1e-15);
    }
    assert!((rev.eval(0.5, 0.0).unwrap() - Vector3::new(0.0, 1.0, 1.0)).norm() < 1e-15);
    assert!((rev.eval(0.5, 1.0).unwrap() - Vector3::new(-1.0, 0.0, 1.0)).norm() < 1e-15);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!((rev.eval(0.5, 0.5).unwrap() - Vector3::new(-h, h, 1.0)).norm() < 1e-15);
    // The generatrix swept to (4, 5, 0): S(u, v) = G(u) + v ((4, 5, 0) − (1, 0, 0)).
    let Geometry::Surface(tab) = &items[3].geometry else {
        panic!()
    };
    let (u, v) = (0.3, 0.7);
    let want = Vector3::new(1.0, 0.0, 2.0 * u) + v * Vector3::new(3.0, 5.0, 0.0);
    assert!((tab.eval(u, v).unwrap() - want).norm() < 1e-15);
}

#[test]
fn transformations_of_rational_curves_and_surfaces() {
    // The quarter circle rotated by 90° about z after a shift by x: R(C(t) + (1, 0, 0)).
    let surface = "128,1,1,1,1,0,0,0,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,2.,1.,4.,\
                   0.,0.,0.,1.,0.,0.,0.,1.,0.,1.,1.,1.,0.,1.,0.,1.;";
    let text = hand_file(&[
        Hand(124, 0, 3, "", SHIFT_X),
        Hand(124, 0, 0, "", ROTATE_Z),
        Hand(126, 0, 1, "Q", &QUARTER.replace("0.25,0.75", "0.,1.")),
        Hand(128, 0, 1, "S", surface),
    ]);
    let items = read_iges(&text).unwrap();
    assert_eq!(items.len(), 2);
    let Geometry::NurbsCurve3(c) = &items[0].geometry else {
        panic!()
    };
    let Geometry::NurbsSurface(s) = &items[1].geometry else {
        panic!()
    };
    let r = |p: Vector3<f64>| Vector3::new(-p.y, p.x + 1.0, p.z);
    for t in [0.0, 0.4, 1.0] {
        let q = Vector3::new((1.0 - t * t) / (1.0 + t * t), 2.0 * t / (1.0 + t * t), 0.0);
        assert!((c.eval(t).unwrap() - r(q)).norm() < 1e-15, "t = {t}");
    }
    // The patch with P(1,1) = (1, 1, 1), the other corners those of the unit square,
    // weights W(0,0) = 1, W(1,0) = 2, W(0,1) = 1, W(1,1) = 4
    // (listed u fastest): w(u, v) = (1 − u)(1 − v) + 2u(1 − v) + (1 − u)v + 4uv.
    let (u, v) = (0.25, 0.5);
    let w = (1.0 - u) * (1.0 - v) + 2.0 * u * (1.0 - v) + (1.0 - u) * v + 4.0 * u * v;
    let q = Vector3::new(
        (2.0 * u * (1.0 - v) + 4.0 * u * v) / w,
        ((1.0 - u) * v + 4.0 * u * v) / w,
        4.0 * u * v / w,
    );
    assert!(
        (s.eval(u, v).unwrap() - r(q)).norm() < 1e-15,
        "{:?} {:?}",
        s.eval(u, v),
        r(q)
    );
}

#[test]
fn a_name_property_names_the_entity() {
    let params = QUARTER.replace("0.,0.,1.;", "0.,0.,1.,1,3,1,5;");
    let text = hand_file(&[
        Hand(126, 0, 0, "LABEL", &params),
        Hand(402, 1, 0, "", "402,1,1;"),
        Hand(406, 15, 0, "", "406,1,18HNamed, with; marks;"),
    ]);
    let item = one(&text);
    assert_eq!(item.name, "Named, with; marks");
}
