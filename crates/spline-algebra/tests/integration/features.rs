//! Inflections and curvature extrema of rational curves, against closed forms and against
//! the sampled signed curvature.

use crate::common;

use nalgebra::Vector2;
use spline_algebra::planar_features;
use spline_geom::NurbsCurve;

/// Two quarters of the ellipse x²/4 + y² = 1 from (2, 0) over (0, 1) to (−2, 0): the
/// curvature has its only interior extremum (a minimum, 1/4 · … at the end of the minor
/// axis) at u = 1, and there is no inflection.
#[test]
fn half_ellipse_has_one_curvature_extremum_at_the_minor_axis() {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let ellipse = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0],
        vec![
            Vector2::new(2.0, 0.0),
            Vector2::new(2.0, 1.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(-2.0, 1.0),
            Vector2::new(-2.0, 0.0),
        ],
        vec![1.0, w, 1.0, w, 1.0],
    )
    .unwrap();
    let f = planar_features(&ellipse, 1e-12).unwrap();
    assert!(f.inflections.is_empty(), "{f:?}");
    assert_eq!(f.curvature_extrema.len(), 1, "{f:?}");
    assert!((f.curvature_extrema[0] - 1.0).abs() < 1e-9, "{f:?}");
    // κ at the end of the minor axis of x²/a² + y²/b² = 1 is b/a² = 1/4.
    assert!((ellipse.signed_curvature(1.0).unwrap() - 0.25).abs() < 1e-12);
}

/// A cubic NURBS curve with uneven weights: every sign change of the sampled signed
/// curvature lies near a reported inflection, every sign change of its sampled derivative
/// near a reported curvature extremum, and conversely.
#[test]
fn rational_features_match_the_sampled_curvature() {
    let curve = NurbsCurve::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.55, 0.8, 1.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 2.0),
            Vector2::new(2.5, -1.0),
            Vector2::new(4.0, 1.5),
            Vector2::new(5.0, -0.5),
            Vector2::new(6.5, 1.0),
            Vector2::new(7.0, 0.0),
        ],
        vec![1.0, 3.0, 0.5, 2.0, 0.7, 1.5, 1.0],
    )
    .unwrap();
    let f = planar_features(&curve, 1e-12).unwrap();
    let n = 20_000;
    let u = |j: usize| j as f64 / n as f64;
    let kappa: Vec<f64> = (0..=n)
        .map(|j| curve.signed_curvature(u(j)).unwrap())
        .collect();
    let crossings = |values: &[f64], offset: f64| -> Vec<f64> {
        (1..values.len())
            .filter(|&j| values[j - 1] * values[j] < 0.0)
            .map(|j| u(j) - offset)
            .collect()
    };
    let inflections = crossings(&kappa, 0.5 / n as f64);
    let slope: Vec<f64> = kappa.windows(2).map(|w| w[1] - w[0]).collect();
    let extrema = crossings(&slope, 0.0);
    let near = |found: &[f64], expected: &[f64], what: &str| {
        assert_eq!(
            found.len(),
            expected.len(),
            "{what}: {found:?} vs {expected:?}"
        );
        for (a, b) in found.iter().zip(expected) {
            assert!(
                (a - b).abs() < 3.0 / n as f64,
                "{what}: {found:?} vs {expected:?}"
            );
        }
    };
    assert!(!f.inflections.is_empty() && !f.curvature_extrema.is_empty());
    near(&f.inflections, &inflections, "inflections");
    near(&f.curvature_extrema, &extrema, "curvature extrema");
}

/// Constant curvature has no extrema, a straight segment no inflections: the numerators
/// vanish identically and what the arithmetic leaves of them is rounding, whose sign
/// changes are not features. A slightly flattened circle keeps its four vertices.
#[test]
fn circles_and_straight_segments_have_no_features() {
    use spline_geom::{CircleConstruction, Frame};
    for construction in [CircleConstruction::Square, CircleConstruction::Triangle] {
        for (center, radius) in [((0.0, 0.0), 1.0), ((3.7, -1.1), 0.013), ((-2e3, 5e2), 7e4)] {
            let frame = Frame::planar(Vector2::new(center.0, center.1));
            let circle = NurbsCurve::circle(&frame, radius, construction).unwrap();
            let f = planar_features(&circle, 1e-12).unwrap();
            assert!(
                f.curvature_extrema.is_empty() && f.inflections.is_empty(),
                "{construction:?} {radius}: {f:?}"
            );
            // Squeezed by 1e-6 in y: an ellipse, with vertices at u = 0, ¼, ½, ¾ (the one
            // at the seam u = 0 found as the closed curve's: its end meets its start).
            let ellipse = NurbsCurve::from_knots(
                2,
                circle.knots().knots().to_vec(),
                circle
                    .control_points()
                    .iter()
                    .map(|p| Vector2::new(p.x, center.1 + (p.y - center.1) * (1.0 - 1e-6)))
                    .collect(),
                circle.weights().to_vec(),
            )
            .unwrap();
            let f = planar_features(&ellipse, 1e-12).unwrap();
            assert_eq!(
                f.curvature_extrema.len(),
                4,
                "{construction:?} {radius}: {f:?}"
            );
            assert_eq!(f.curvature_extrema[0], 0.0);
        }
    }
    // A rational parabola-like curve with collinear control points: a straight segment.
    let segment = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.1, 0.3),
            Vector2::new(0.7, 0.9),
            Vector2::new(1.9, 2.1),
            Vector2::new(2.2, 2.4),
        ],
        vec![1.0, 3.0, 0.2, 1.0],
    )
    .unwrap();
    let f = planar_features(&segment, 1e-12).unwrap();
    assert!(
        f.inflections.is_empty() && f.curvature_extrema.is_empty(),
        "{f:?}"
    );
}

/// Circles report their constant curvature `1/r` (signed by the orientation), straight
/// segments `0`, and neither an extremum.
#[test]
fn constant_curvature_is_reported_as_such() {
    use spline_geom::{CircleConstruction, Frame};
    for (radius, construction) in [
        (1.0, CircleConstruction::Square),
        (0.013, CircleConstruction::Triangle),
        (7e4, CircleConstruction::Square),
    ] {
        let circle = NurbsCurve::circle(
            &Frame::planar(Vector2::new(0.3, -2.0)),
            radius,
            construction,
        )
        .unwrap();
        let f = planar_features(&circle, 1e-12).unwrap();
        let kappa: f64 = f
            .constant_curvature
            .expect("a circle has constant curvature");
        assert!(
            (kappa.abs() * radius - 1.0).abs() < 1e-9,
            "{radius}: {kappa}"
        );
        assert!(f.curvature_extrema.is_empty() && f.inflections.is_empty());
    }
    // A straight line as a polynomial cubic with exactly collinear points.
    let line = spline_geom::BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 2.0),
            Vector2::new(1.5, 3.0),
            Vector2::new(4.0, 8.0),
            Vector2::new(5.0, 10.0),
        ],
    )
    .unwrap();
    let f = planar_features(&line, 1e-12).unwrap();
    assert_eq!(f.constant_curvature, Some(0.0));
    // A curve of varying curvature reports none.
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let arc = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(2.0, 0.0),
            Vector2::new(2.0, 1.0),
            Vector2::new(0.0, 1.0),
        ],
        vec![1.0, w, 1.0],
    )
    .unwrap();
    assert_eq!(
        planar_features(&arc, 1e-12).unwrap().constant_curvature,
        None
    );
}

/// A full ellipse (a NURBS circle turned by 45° so that no vertex is at the seam, then
/// squeezed to semi-axes 1 and ½): exactly four curvature extrema, each on an axis, and no
/// inflection.
#[test]
fn an_ellipse_has_its_four_vertices_on_its_axes() {
    use spline_geom::{CircleConstruction, Frame};
    for construction in [CircleConstruction::Square, CircleConstruction::Triangle] {
        let circle =
            NurbsCurve::circle(&Frame::planar(Vector2::zeros()), 1.0, construction).unwrap();
        let (s, c) = std::f64::consts::FRAC_PI_4.sin_cos();
        let ellipse = circle
            .map_control_points(|p| Vector2::new(c * p.x - s * p.y, 0.5 * (s * p.x + c * p.y)));
        let f = planar_features(&ellipse, 1e-13).unwrap();
        assert!(
            f.inflections.is_empty() && f.constant_curvature.is_none(),
            "{f:?}"
        );
        assert_eq!(f.curvature_extrema.len(), 4, "{construction:?}: {f:?}");
        let mut on_x = 0;
        for &u in &f.curvature_extrema {
            let p = ellipse.eval(u).unwrap();
            // Closed form: the vertices (±1, 0) and (0, ±½).
            if p.y.abs() < 1e-10 {
                assert!((p.x.abs() - 1.0).abs() < 1e-10, "{p}");
                on_x += 1;
            } else {
                assert!(p.x.abs() < 1e-10 && (p.y.abs() - 0.5).abs() < 1e-10, "{p}");
            }
        }
        assert_eq!(on_x, 2);
    }
}

/// The Jacobians of the rational numerators with respect to the weighted control points
/// against dual numbers (every column) and central differences.
#[test]
fn rational_numerator_jacobians_agree_with_dual_numbers_and_differences() {
    use num_dual::Dual64;
    use spline_algebra::rational_planar_numerators;
    use spline_geom::{BSpline, Homogeneous};
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0];
    let hom: Vec<[f64; 3]> = vec![
        [0.0, 0.0, 1.0],
        [1.2, 2.4, 1.2],
        [1.25, -0.5, 0.5],
        [6.0, 3.0, 2.0],
        [5.0, 0.0, 1.0],
    ];
    let curve_of = |h: &[[f64; 3]]| {
        NurbsCurve::from_homogeneous(
            BSpline::from_knots(
                3,
                knots.clone(),
                h.iter()
                    .map(|q| Homogeneous::new(Vector2::new(q[0], q[1]), q[2]))
                    .collect(),
            )
            .unwrap(),
        )
        .unwrap()
    };
    let n = rational_planar_numerators(&curve_of(&hom)).unwrap();
    let jd = common::dense(&n.curvature_extremum.jacobian);
    let jdet = common::dense(&n.inflection.jacobian);
    assert_eq!(jd[0].len(), 15);
    for col in 0..15 {
        let dual = NurbsCurve::from_homogeneous(
            BSpline::from_knots(
                3,
                knots.iter().map(|&k| Dual64::from(k)).collect(),
                hom.iter()
                    .enumerate()
                    .map(|(i, q)| {
                        let d =
                            |k: usize| Dual64::new(q[k], if 3 * i + k == col { 1.0 } else { 0.0 });
                        Homogeneous::new(Vector2::new(d(0), d(1)), d(2))
                    })
                    .collect(),
            )
            .unwrap(),
        )
        .unwrap();
        let nd = rational_planar_numerators(&dual).unwrap();
        for (which, jac, values) in [
            ("G", &jd, nd.curvature_extremum.value.control_points()),
            ("D", &jdet, nd.inflection.value.control_points()),
        ] {
            let scale = values
                .iter()
                .fold(0.0f64, |m, v| m.max(v.eps.abs()))
                .max(1.0);
            for (r, v) in values.iter().enumerate() {
                assert!(
                    (jac[r][col] - v.eps).abs() < 1e-10 * scale,
                    "{which} row {r} col {col}: {} vs {}",
                    jac[r][col],
                    v.eps
                );
            }
        }
        // Central differences on the same column.
        let h = 1e-6;
        let shifted = |s: f64| {
            let mut q = hom.clone();
            q[col / 3][col % 3] += s;
            rational_planar_numerators(&curve_of(&q)).unwrap()
        };
        let (plus, minus) = (shifted(h), shifted(-h));
        let gp = plus.curvature_extremum.value.control_points();
        let gm = minus.curvature_extremum.value.control_points();
        let scale = gp.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        for r in 0..gp.len() {
            let fd = (gp[r] - gm[r]) / (2.0 * h);
            assert!(
                (fd - jd[r][col]).abs() < 1e-5 * scale,
                "fd row {r} col {col}"
            );
        }
    }
}

/// The Hessians of the rational numerators against hyper-dual numbers (second derivatives
/// of the values, independent of the Jacobian code) on every pair of variables of two
/// control points, and symmetric.
#[test]
fn rational_numerator_hessians_agree_with_hyper_dual_numbers() {
    use num_dual::HyperDual64;
    use spline_algebra::{rational_planar_hessians, rational_planar_numerators};
    use spline_geom::{BSpline, Homogeneous};
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0];
    let hom: Vec<[f64; 3]> = vec![
        [0.0, 0.0, 1.0],
        [1.2, 2.4, 1.2],
        [1.25, -0.5, 0.5],
        [6.0, 3.0, 2.0],
        [5.0, 0.0, 1.0],
    ];
    let curve = NurbsCurve::from_homogeneous(
        BSpline::from_knots(
            3,
            knots.clone(),
            hom.iter()
                .map(|q| Homogeneous::new(Vector2::new(q[0], q[1]), q[2]))
                .collect(),
        )
        .unwrap(),
    )
    .unwrap();
    let [hd, hg] = rational_planar_hessians(&curve).unwrap();
    let dense = |h: &spline_algebra::SparseBilinear<f64>, k: usize| common::dense(&h.matrix(k));
    let rows = rational_planar_numerators(&curve)
        .unwrap()
        .curvature_extremum
        .value
        .control_points()
        .len();
    let mut checked = 0;
    for a in 3..9 {
        for b in a..9 {
            let hyper = NurbsCurve::from_homogeneous(
                BSpline::from_knots(
                    3,
                    knots.iter().map(|&k| HyperDual64::from(k)).collect(),
                    hom.iter()
                        .enumerate()
                        .map(|(i, q)| {
                            let d = |k: usize| {
                                let j = 3 * i + k;
                                HyperDual64::new(
                                    q[k],
                                    if j == a { 1.0 } else { 0.0 },
                                    if j == b { 1.0 } else { 0.0 },
                                    0.0,
                                )
                            };
                            Homogeneous::new(Vector2::new(d(0), d(1)), d(2))
                        })
                        .collect(),
                )
                .unwrap(),
            )
            .unwrap();
            let n = rational_planar_numerators(&hyper).unwrap();
            for (which, h, values) in [
                ("G", &hg, n.curvature_extremum.value.control_points()),
                ("D", &hd, n.inflection.value.control_points()),
            ] {
                let scale = values.iter().fold(1.0f64, |m, v| m.max(v.eps1eps2.abs()));
                for (k, v) in values.iter().enumerate() {
                    let m = dense(h, k);
                    assert!(
                        (m[a][b] - v.eps1eps2).abs() < 1e-10 * scale,
                        "{which} row {k} ({a}, {b}): {} vs {}",
                        m[a][b],
                        v.eps1eps2
                    );
                    assert!((m[a][b] - m[b][a]).abs() < 1e-10 * scale);
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(hg.nrows(), rows);
    assert!(checked > 100);
}

/// An ellipse with a vertex at the seam (a NURBS circle stretched along its first axis, as
/// `spline make circle` then a scaling gives): the closed curve's four vertices, the one at
/// the start included (issue 25: three were reported); an open arc of the same ellipse keeps
/// only its interior vertices.
#[test]
fn a_closed_curve_has_its_feature_at_the_seam() {
    use spline_geom::{CircleConstruction, Frame};
    for construction in [CircleConstruction::Square, CircleConstruction::Triangle] {
        let circle =
            NurbsCurve::circle(&Frame::planar(Vector2::zeros()), 1.0, construction).unwrap();
        let ellipse: NurbsCurve<f64, 2> =
            circle.map_control_points(|p| Vector2::new(2.0 * p.x, p.y));
        let f = planar_features(&ellipse, 1e-13).unwrap();
        assert_eq!(f.curvature_extrema.len(), 4, "{construction:?}: {f:?}");
        for &u in &f.curvature_extrema {
            let p = ellipse.eval(u).unwrap();
            // Closed form: the vertices (±2, 0) and (0, ±1).
            let p: Vector2<f64> = p;
            let on_x = p.y.abs() < 1e-10 && (p.x.abs() - 2.0).abs() < 1e-10;
            let on_y = p.x.abs() < 1e-10 && (p.y.abs() - 1.0).abs() < 1e-10;
            assert!(on_x || on_y, "{p}");
        }
        assert!(f.inflections.is_empty());
        // The same ellipse cut open before its end: no seam, the vertex at u = 0 is an end.
        let (a, b) = ellipse.domain();
        let (open, _) = ellipse.split(a + 0.9 * (b - a)).unwrap();
        let f = planar_features(&open, 1e-13).unwrap();
        assert!(f.curvature_extrema.iter().all(|&u| u > a), "{f:?}");
    }
}
