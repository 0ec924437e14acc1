//! STEP: random B-spline and NURBS curves and surfaces through a file and back bit for bit,
//! the forms other systems write, B-rep solids written by Open CASCADE (analytic entities as
//! exact NURBS), and one-line errors that name the line.

use nalgebra::{Vector2, Vector3};
use spline_core::KnotVector;
use spline_geom::{BSpline, NurbsCurve, NurbsSurface, Surface};
use spline_io::step::{read_step, read_step_bytes, write_step};
use spline_io::{Geometry, Item};

/// A small deterministic generator (xorshift), so that the cases are reproducible.
struct Random(u64);

impl Random {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        #[allow(clippy::cast_precision_loss)]
        let x = (self.0 >> 11) as f64 / (1u64 << 53) as f64;
        x
    }

    fn below(&mut self, n: usize) -> usize {
        #[allow(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            clippy::cast_precision_loss
        )]
        let i = (self.next() * n as f64) as usize;
        i.min(n - 1)
    }

    /// Knots of degree `p` for `n` control points: clamped or not, interior
    /// multiplicities up to `p`, values with all their digits.
    fn knots(&mut self, p: usize, n: usize) -> KnotVector<f64> {
        loop {
            if let Some(k) = self.knots_once(p, n) {
                return k;
            }
        }
    }

    fn knots_once(&mut self, p: usize, n: usize) -> Option<KnotVector<f64>> {
        let clamped = self.next() < 0.7;
        let mut interior = Vec::new();
        let want = n + p + 1 - if clamped { 2 * (p + 1) } else { 0 };
        let mut x = -1.0 + 2.0 * self.next();
        while interior.len() < want {
            x += 0.01 + self.next();
            let m = 1 + self.below(p);
            for _ in 0..m.min(want - interior.len()) {
                interior.push(x);
            }
        }
        let knots = if clamped {
            let (a, b) = (interior.first().copied().unwrap_or(0.0) - 0.5, x + 0.5);
            let mut k = vec![a; p + 1];
            k.extend(&interior);
            k.extend(std::iter::repeat_n(b, p + 1));
            k
        } else {
            interior
        };
        KnotVector::new(p, knots).ok()
    }

    fn point3(&mut self) -> Vector3<f64> {
        Vector3::new(
            self.next() * 10.0 - 5.0,
            self.next() * 1e-3,
            self.next() * 1e5,
        )
    }
}

fn item(geometry: Geometry, name: &str) -> Item {
    Item {
        id: 0,
        name: name.into(),
        entity: String::new(),
        geometry,
    }
}

#[test]
fn random_curves_and_surfaces_come_back_bit_for_bit() {
    let mut random = Random(0x5eed_1234_abcd);
    let mut items = Vec::new();
    for case in 0..60 {
        let p = 1 + case % 7;
        let n = p + 1 + random.below(6);
        let knots = random.knots(p, n);
        let points: Vec<Vector3<f64>> = (0..n).map(|_| random.point3()).collect();
        let weights: Vec<f64> = (0..n).map(|_| 0.1 + 3.0 * random.next()).collect();
        let flat: Vec<Vector2<f64>> = points.iter().map(nalgebra::Matrix::xy).collect();
        let geometry = match case % 4 {
            0 => Geometry::Curve3(BSpline::new(knots, points).unwrap()),
            1 => Geometry::Curve2(BSpline::new(knots, flat).unwrap()),
            2 => Geometry::NurbsCurve3(NurbsCurve::new(knots, points, weights).unwrap()),
            _ => Geometry::NurbsCurve2(NurbsCurve::new(knots, flat, weights).unwrap()),
        };
        items.push(item(geometry, &format!("curve {case} 'quoted' \\ é")));
    }
    for case in 0..30 {
        let (pu, pv) = (1 + case % 7, 1 + (case / 7) % 4);
        let (nu, nv) = (pu + 1 + random.below(4), pv + 1 + random.below(4));
        let (ku, kv) = (random.knots(pu, nu), random.knots(pv, nv));
        let net: Vec<Vec<Vector3<f64>>> = (0..nu)
            .map(|_| (0..nv).map(|_| random.point3()).collect())
            .collect();
        let geometry = if case % 2 == 0 {
            Geometry::Surface(Surface::from_net(ku, kv, net).unwrap())
        } else {
            let w: Vec<Vec<f64>> = (0..nu)
                .map(|_| (0..nv).map(|_| 0.2 + random.next()).collect())
                .collect();
            Geometry::NurbsSurface(NurbsSurface::from_net(ku, kv, net, w).unwrap())
        };
        items.push(item(geometry, &format!("surface {case}")));
    }
    let text = write_step(&items).unwrap();
    assert!(text.is_ascii());
    let back = read_step(&text).unwrap();
    assert_eq!(back.len(), items.len());
    // Curves come first in the file, then surfaces, each in the order given; 2-D curves
    // come back in the plane z = 0.
    let lift = |p: &Vector2<f64>| Vector3::new(p.x, p.y, 0.0);
    for (b, i) in back.iter().zip(&items) {
        let expected = match &i.geometry {
            Geometry::Curve2(c) => Geometry::Curve3(c.map_control_points(lift)),
            Geometry::NurbsCurve2(c) => Geometry::NurbsCurve3(c.map_control_points::<3>(lift)),
            g => g.clone(),
        };
        assert_eq!(b.geometry, expected, "{}", i.name);
        assert_eq!(b.name, i.name);
    }
}

/// The rational complex instance as Open CASCADE writes it, with 2-D names and the forms
/// whose knots are implied.
#[test]
fn forms_written_by_other_systems() {
    let text = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('x'),'2;1');\nENDSEC;\nDATA;\n\
        #16 = TRIMMED_CURVE('',#17,(#22,PARAMETER_VALUE(0.)),(#23,PARAMETER_VALUE(1.)),.T.,.PARAMETER.);\n\
        #17 = ( BOUNDED_CURVE() B_SPLINE_CURVE(3,(#18,#19,#20,#21),\n.UNSPECIFIED.,.F.,.F.) B_SPLINE_CURVE_WITH_KNOTS((4,4),(0.,1.),\n\
        .PIECEWISE_BEZIER_KNOTS.) CURVE() GEOMETRIC_REPRESENTATION_ITEM() \nRATIONAL_B_SPLINE_CURVE((1.,2.,0.5,1.)) REPRESENTATION_ITEM('') );\n\
        #18 = CARTESIAN_POINT('',(0.,0.,0.));\n#19 = CARTESIAN_POINT('',(1.,2.,0.));\n\
        #20 = CARTESIAN_POINT('',(2.,-1.,1.));\n#21 = CARTESIAN_POINT('',(3.,0.,0.));\n\
        #22 = CARTESIAN_POINT('',(0.,0.,0.));\n#23 = CARTESIAN_POINT('',(3.,0.,0.));\n\
        #30 = EDGE_CURVE('rim',#31,#31,#16,.T.);\n#31 = VERTEX_POINT('',#22);\n\
        /* a Bézier curve: knots 0 0 0 1 1 2 2 2 */\n\
        #40 = BEZIER_CURVE('b',2,(#41,#42,#43,#44,#45),.UNSPECIFIED.,.F.,.F.);\n\
        #41 = CARTESIAN_POINT('',(0.,0.));\n#42 = CARTESIAN_POINT('',(1.,1.));\n\
        #43 = CARTESIAN_POINT('',(2.,0.));\n#44 = CARTESIAN_POINT('',(3.,-1.));\n\
        #45 = CARTESIAN_POINT('',(4.,0.));\n\
        #50 = QUASI_UNIFORM_CURVE('q',2,(#41,#42,#43,#44),.UNSPECIFIED.,.F.,.F.);\n\
        ENDSEC;\nEND-ISO-10303-21;\n";
    let items = read_step(text).unwrap();
    assert_eq!(items.len(), 3);
    let Geometry::NurbsCurve3(c) = &items[0].geometry else {
        panic!("{:?}", items[0])
    };
    assert_eq!(items[0].id, 17);
    assert_eq!(items[0].name, "rim");
    assert_eq!(c.weights(), &[1.0, 2.0, 0.5, 1.0]);
    // The rational cubic at u = 1/2: Σ w_i B_i P_i / Σ w_i B_i with B = 1/8 (1, 3, 3, 1).
    let (b, w) = ([1.0, 3.0, 3.0, 1.0], [1.0, 2.0, 0.5, 1.0]);
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 2.0, 0.0],
        [2.0, -1.0, 1.0],
        [3.0, 0.0, 0.0],
    ];
    let den: f64 = (0..4).map(|i| b[i] * w[i]).sum();
    let expected =
        Vector3::from_fn(|k, _| (0..4).map(|i| b[i] * w[i] * p[i][k]).sum::<f64>() / den);
    assert!((c.eval(0.5).unwrap() - expected).norm() < 1e-15);
    let Geometry::Curve2(bezier) = &items[1].geometry else {
        panic!("{:?}", items[1])
    };
    assert_eq!(
        bezier.knots().knots(),
        &[0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0]
    );
    assert_eq!(items[1].entity, "BEZIER_CURVE");
    let Geometry::Curve2(quasi) = &items[2].geometry else {
        panic!("{:?}", items[2])
    };
    assert_eq!(quasi.knots().knots(), &[0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0]);
}

fn wrap(data: &str) -> String {
    format!("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n{data}ENDSEC;\nEND-ISO-10303-21;\n")
}

#[test]
fn malformed_files_give_one_line_errors_with_the_line() {
    let curve = "#1 = B_SPLINE_CURVE_WITH_KNOTS('',1,(#2,#3),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);\n";
    let points = "#2 = CARTESIAN_POINT('',(0.,0.,0.));\n#3 = CARTESIAN_POINT('',(1.,0.,0.));\n";
    assert_eq!(
        read_step(&wrap(&format!("{curve}{points}"))).unwrap().len(),
        1
    );
    let cases: Vec<(String, &str)> = vec![
        (String::new(), "empty"),
        (wrap(&format!("{curve}{points}"))[..60].to_string(), "ends"),
        (wrap(curve), "#2 is referenced but not defined"),
        (
            wrap(&format!("{}{points}", curve.replace("(2,2)", "(2,3)"))),
            "multiplicit",
        ),
        (
            wrap(&format!(
                "{}{points}",
                curve.replace("(2,2)", "(1000000000000,2)")
            )),
            "multiplicity",
        ),
        (
            wrap(&format!("{}{points}", curve.replace("(#2,#3)", "(#2)"))),
            "STEP line 5",
        ),
        (
            wrap(&format!(
                "{curve}#2 = CARTESIAN_POINT('',(0.,0.,0.));\n#3 = CARTESIAN_POINT('é',(1.,0.,0.));\n"
            )),
            "ASCII",
        ),
        (wrap("#1 = CARTESIAN_POINT('',(0.,0.,0.);\n"), "STEP line 5"),
        (
            wrap(
                "#1 = FOO(((((((((((((((((((((((((((((((((((((1)))))))))))))))))))))))))))))))))))));\n",
            ),
            "deep",
        ),
        ("HELLO;".to_string(), "not a STEP file"),
    ];
    for (text, words) in cases {
        let e = read_step_bytes(text.as_bytes()).unwrap_err().to_string();
        assert!(e.contains(words), "{words:?} not in {e:?}");
        assert!(!e.contains('\n'), "{e}");
    }
    // A reference cycle between wrappers ends (the wrappers are followed with a limit).
    let cycle = wrap(
        "#1 = TRIMMED_CURVE('',#2,(),(),.T.,.PARAMETER.);\n#2 = TRIMMED_CURVE('',#1,(),(),.T.,.PARAMETER.);\n#3 = EDGE_CURVE('e',#4,#4,#1,.T.);\n#4 = VERTEX_POINT('',#5);\n#5 = CARTESIAN_POINT('',(0.,0.,0.));\n",
    );
    assert!(read_step(&cycle).unwrap().is_empty());
}

/// Solids written by Open CASCADE (`tests/data/step/make_step_data.py`): every face's
/// surface and every edge's curve arrives, the analytic ones as exact NURBS whose points
/// lie on the closed form.
#[test]
fn analytic_b_rep_solids_from_open_cascade() {
    use std::collections::BTreeMap;
    let files = [
        (
            "fillet_box",
            include_str!("../data/step/fillet_box.step"),
            7,
            15,
        ),
        ("cylinder", include_str!("../data/step/cylinder.step"), 3, 3),
        ("cone", include_str!("../data/step/cone.step"), 3, 3),
        ("torus", include_str!("../data/step/torus.step"), 1, 2),
        ("sphere", include_str!("../data/step/sphere.step"), 1, 0),
    ];
    for (name, text, faces, edges) in files {
        let items = read_step(text).unwrap();
        let mut kinds: BTreeMap<&str, usize> = BTreeMap::new();
        for item in &items {
            *kinds
                .entry(
                    if matches!(
                        item.geometry,
                        Geometry::NurbsSurface(_) | Geometry::Surface(_)
                    ) {
                        "surface"
                    } else {
                        "curve"
                    },
                )
                .or_default() += 1;
        }
        // Distinct geometry: a seam line or a shared circle counts once.
        assert_eq!(
            kinds.get("surface").copied().unwrap_or(0),
            faces,
            "{name}: {kinds:?}"
        );
        assert!(
            kinds.get("curve").copied().unwrap_or(0) <= edges,
            "{name}: {kinds:?}"
        );
        for item in &items {
            let Geometry::NurbsSurface(s) = &item.geometry else {
                continue;
            };
            let ((a, b), (c, d)) = s.domain();
            for i in 0..=8 {
                for j in 0..=8 {
                    let (u, v) = (
                        a + (b - a) * f64::from(i) / 8.0,
                        c + (d - c) * f64::from(j) / 8.0,
                    );
                    let p = s.eval(u, v).unwrap();
                    let r = p.x.hypot(p.y);
                    let error = match (name, item.entity.as_str()) {
                        ("cylinder" | "fillet_box", "CYLINDRICAL_SURFACE")
                            if name == "cylinder" =>
                        {
                            (r - 3.0).abs() / 3.0
                        }
                        // Open CASCADE writes the semi-angle with 12 digits
                        // (0.463647609001 for atan(1/2)): the radius follows to 1e-12.
                        ("cone", "CONICAL_SURFACE") => (r - (3.0 - p.z / 2.0)).abs() / 3.0 * 1e-2,
                        ("sphere", _) => (p.norm() - 2.0).abs() / 2.0,
                        ("torus", _) => ((r - 5.0).hypot(p.z) - 1.0).abs() / 5.0,
                        _ => 0.0,
                    };
                    assert!(
                        error < 1e-14,
                        "{name} {}: {p} off by {error:e}",
                        item.entity
                    );
                }
            }
        }
    }
}
