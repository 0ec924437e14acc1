//! Tensor-product surfaces checked against independent facts: invariance of the surface
//! under every structural operation (sampled), finite differences and dual numbers for the
//! partial derivatives, closed forms for the differential geometry, and error cases.

use nalgebra::{Vector3, Vector4};
use num_dual::{Dual64, HyperDual64};
use proptest::prelude::*;
use spline_core::{ErrorKind, KnotVector, Scalar, cast, to_f64};
use spline_geom::{BSpline, Direction, Surface};
use spline_testing::strategies::knot_vector;

type S3 = Surface<f64, Vector3<f64>>;

fn net_strategy(knots: (KnotVector<f64>, KnotVector<f64>)) -> impl Strategy<Value = S3> {
    let n = knots.0.num_basis() * knots.1.num_basis();
    proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), n).prop_map(move |pts| {
        Surface::new(
            knots.0.clone(),
            knots.1.clone(),
            pts.into_iter()
                .map(|(x, y, z)| Vector3::new(x, y, z))
                .collect(),
        )
        .unwrap()
    })
}

fn surface_strategy(
    max_degree: usize,
    extra: usize,
    discontinuous: bool,
) -> impl Strategy<Value = S3> {
    (
        knot_vector(max_degree, extra, 1.0, discontinuous),
        knot_vector(max_degree, extra, 1.0, discontinuous),
    )
        .prop_flat_map(net_strategy)
}

/// Parameters covering a domain, including every knot in it.
fn samples(knots: &KnotVector<f64>, count: usize) -> Vec<f64> {
    let (a, b) = knots.domain();
    let mut us: Vec<f64> = (0..=count)
        .map(|i| a + (b - a) * i as f64 / count as f64)
        .collect();
    us.extend(knots.knots().iter().copied().filter(|&k| k >= a && k <= b));
    us.sort_by(f64::total_cmp);
    us
}

fn assert_same_surface(
    a: &S3,
    b: &S3,
    us: &[f64],
    vs: &[f64],
    tol: f64,
) -> Result<(), TestCaseError> {
    for &u in us {
        for &v in vs {
            let (pa, pb) = (a.eval(u, v).unwrap(), b.eval(u, v).unwrap());
            prop_assert!(
                (pa - pb).norm() < tol,
                "(u, v) = ({}, {}): {:?} vs {:?}",
                u,
                v,
                pa,
                pb
            );
        }
    }
    Ok(())
}

fn direction(u: bool) -> Direction {
    if u { Direction::U } else { Direction::V }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn insertion_keeps_the_surface(s in surface_strategy(4, 5, false), t in 0.0f64..=1.0, times in 1usize..3, in_u: bool) {
        let d = direction(in_u);
        let (a, b) = s.knots(d).domain();
        let x = a + (b - a) * t;
        let room = s.degree(d) + 1 - s.knots(d).multiplicity(x);
        match s.insert_knot(d, x, times) {
            Ok(r) => {
                prop_assert!(times <= room);
                prop_assert_eq!(r.knots(d).multiplicity(x), s.knots(d).multiplicity(x) + times);
                prop_assert_eq!(r.knots(d.other()), s.knots(d.other()));
                assert_same_surface(&s, &r, &samples(s.knots_u(), 12), &samples(s.knots_v(), 12), 1e-12)?;
            }
            Err(e) => {
                prop_assert!(times > room);
                prop_assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
            }
        }
    }

    #[test]
    fn refinement_matches_repeated_insertion(s in surface_strategy(4, 4, false), ts in proptest::collection::vec(0.0f64..1.0, 1..5), in_u: bool) {
        let d = direction(in_u);
        let (a, b) = s.knots(d).domain();
        let xs: Vec<f64> = ts.iter().map(|t| a + (b - a) * ((t * 32.0).round() / 32.0)).collect();
        let k = s.knots(d);
        let too_many = xs.iter().any(|&x| k.multiplicity(x) + xs.iter().filter(|&&y| y == x).count() > k.degree() + 1);
        match s.refine(d, &xs) {
            Ok(r) => {
                let mut one_by_one = s.clone();
                for &x in &xs {
                    one_by_one = one_by_one.insert_knot(d, x, 1).unwrap();
                }
                prop_assert_eq!(r.knots(d), one_by_one.knots(d));
                for (p, q) in r.control_points().iter().zip(one_by_one.control_points()) {
                    prop_assert!((p - q).norm() < 1e-12);
                }
                assert_same_surface(&s, &r, &samples(s.knots_u(), 10), &samples(s.knots_v(), 10), 1e-12)?;
            }
            Err(e) => {
                prop_assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
                prop_assert!(too_many);
            }
        }
    }

    #[test]
    fn removal_undoes_insertion(s in surface_strategy(4, 4, false), t in 0.05f64..0.95, in_u: bool) {
        let d = direction(in_u);
        let (a, b) = s.knots(d).domain();
        let x = a + (b - a) * ((t * 1000.0).round() / 1000.0);
        prop_assume!(s.knots(d).multiplicity(x) == 0 && s.degree(d) >= 1);
        let inserted = s.insert_knot(d, x, 1).unwrap();
        let back = inserted.remove_knot(d, x, 1, 1e-9).unwrap();
        prop_assert_eq!(back.knots(d), s.knots(d));
        for (p, q) in back.control_points().iter().zip(s.control_points()) {
            prop_assert!((p - q).norm() < 1e-9);
        }
    }

    #[test]
    fn elevation_keeps_the_surface(s in surface_strategy(3, 4, true), times in 1usize..3, in_u: bool) {
        let d = direction(in_u);
        let e = s.elevate_degree(d, times).unwrap();
        prop_assert_eq!(e.degree(d), s.degree(d) + times);
        prop_assert_eq!(e.degree(d.other()), s.degree(d.other()));
        for (k, m) in s.knots(d).interior_breakpoints() {
            prop_assert_eq!(e.knots(d).multiplicity(k), m + times);
        }
        assert_same_surface(&s, &e, &samples(s.knots_u(), 10), &samples(s.knots_v(), 10), 1e-11)?;
    }

    #[test]
    fn splitting_gives_two_halves(s in surface_strategy(4, 4, false), t in 0.01f64..0.99, in_u: bool) {
        let d = direction(in_u);
        let (a, b) = s.knots(d).domain();
        let x = a + (b - a) * t;
        let (left, right) = s.split(d, x).unwrap();
        prop_assert_eq!(left.knots(d).domain(), (a, x));
        prop_assert_eq!(right.knots(d).domain(), (x, b));
        prop_assert_eq!(left.knots(d).multiplicity(x), s.degree(d) + 1);
        let others = samples(s.knots(d.other()), 8);
        for i in 0..=10 {
            let (ul, ur) = if i == 10 { (x, b) } else { (a + (x - a) * f64::from(i) / 10.0, x + (b - x) * f64::from(i) / 10.0) };
            for &w in &others {
                let (pl, pr) = match d {
                    Direction::U => ((left.eval(ul, w).unwrap(), s.eval(ul, w).unwrap()), (right.eval(ur, w).unwrap(), s.eval(ur, w).unwrap())),
                    Direction::V => ((left.eval(w, ul).unwrap(), s.eval(w, ul).unwrap()), (right.eval(w, ur).unwrap(), s.eval(w, ur).unwrap())),
                };
                prop_assert!((pl.0 - pl.1).norm() < 1e-11 || i == 10);
                prop_assert!((pr.0 - pr.1).norm() < 1e-11 || i == 0);
            }
        }
    }

    #[test]
    fn clamping_reversal_transposition_and_reparametrisation(s in surface_strategy(4, 4, false)) {
        let us = samples(s.knots_u(), 9);
        let vs = samples(s.knots_v(), 9);
        let c = s.clamped();
        prop_assert!(c.knots_u().is_clamped() && c.knots_v().is_clamped());
        // Left limits at the domain end are where clamping may differ from right limits only
        // at knots of multiplicity p + 1, which the strategy excludes here.
        assert_same_surface(&s, &c, &us, &vs, 1e-11)?;
        let ((a, b), (c0, d0)) = s.domain();
        let r = s.reversed(Direction::U);
        let t = s.transposed();
        let p = s.reparametrized(Direction::V, -2.0, 5.0).unwrap();
        for &u in &us {
            for &v in &vs {
                let x = s.eval(u, v).unwrap();
                prop_assert!((r.eval(a + b - u, v).unwrap() - x).norm() < 1e-11 || u == a || u == b || s.knots_u().multiplicity(u) > 0);
                prop_assert!((t.eval(v, u).unwrap() - x).norm() < 1e-14);
                let w = -2.0 + (v - c0) / (d0 - c0) * 7.0;
                prop_assert!((p.eval(u, w.clamp(-2.0, 5.0)).unwrap() - x).norm() < 1e-10);
            }
        }
    }

    #[test]
    fn bezier_patches_tile_the_surface(s in surface_strategy(3, 4, false)) {
        let patches = s.bezier_patches();
        let spans = |k: &KnotVector<f64>| {
            let (a, b) = k.domain();
            let mut bps = vec![a];
            bps.extend(k.interior_breakpoints().iter().map(|x| x.0));
            bps.push(b);
            bps
        };
        let (bu, bv) = (spans(s.knots_u()), spans(s.knots_v()));
        prop_assert_eq!(patches.len(), bu.len() - 1);
        for (a, row) in patches.iter().enumerate() {
            prop_assert_eq!(row.len(), bv.len() - 1);
            for (b, patch) in row.iter().enumerate() {
                prop_assert_eq!(patch.net_size(), (s.degrees().0 + 1, s.degrees().1 + 1));
                prop_assert_eq!(patch.domain(), ((bu[a], bu[a + 1]), (bv[b], bv[b + 1])));
                for i in 0..=4 {
                    for j in 0..=4 {
                        let u = bu[a] + (bu[a + 1] - bu[a]) * (0.05 + 0.9 * f64::from(i) / 4.0);
                        let v = bv[b] + (bv[b + 1] - bv[b]) * (0.05 + 0.9 * f64::from(j) / 4.0);
                        prop_assert!((patch.eval(u, v).unwrap() - s.eval(u, v).unwrap()).norm() < 1e-11);
                    }
                }
            }
        }
    }

    #[test]
    fn grid_de_boor_and_iso_curves_agree_with_eval(s in surface_strategy(5, 5, true)) {
        let us = samples(s.knots_u(), 7);
        let vs = samples(s.knots_v(), 7);
        let grid = s.eval_grid(&us, &vs).unwrap();
        // Parameters in decreasing order take the bisection path.
        let rev_us: Vec<f64> = us.iter().rev().copied().collect();
        let rev = s.eval_grid(&rev_us, &vs).unwrap();
        for (a, &u) in us.iter().enumerate() {
            let cu = s.curve_at_u(u).unwrap();
            for (b, &v) in vs.iter().enumerate() {
                let p = s.eval(u, v).unwrap();
                prop_assert!((grid[a * vs.len() + b] - p).norm() < 1e-13);
                prop_assert!((rev[(us.len() - 1 - a) * vs.len() + b] - p).norm() < 1e-13);
                prop_assert!((s.de_boor(u, v).unwrap() - p).norm() < 1e-12);
                prop_assert!((cu.eval(v).unwrap() - p).norm() < 1e-12);
                prop_assert!((s.curve_at_v(v).unwrap().eval(u).unwrap() - p).norm() < 1e-12);
            }
        }
    }

    #[test]
    fn derivative_surfaces_match_partial_derivatives(s in surface_strategy(4, 4, false), k in 0usize..3, l in 0usize..3) {
        let (p, q) = s.degrees();
        match s.derivative_surface(k, l) {
            Ok(ds) => {
                prop_assert!(k <= p && l <= q);
                prop_assert_eq!(ds.degrees(), (p - k, q - l));
                for &u in &samples(s.knots_u(), 6) {
                    for &v in &samples(s.knots_v(), 6) {
                        let d = s.derivatives(u, v, 2).unwrap();
                        let x = ds.eval(u, v).unwrap();
                        let scale = 1.0 + d[k][l].norm();
                        prop_assert!((x - d[k][l]).norm() < 1e-9 * scale, "({}, {}) k={} l={}: {:?} vs {:?}", u, v, k, l, x, d[k][l]);
                    }
                }
            }
            Err(e) => {
                prop_assert!(k > p || l > q);
                prop_assert_eq!(e.kind(), ErrorKind::OrderTooHigh);
            }
        }
    }

    #[test]
    fn partial_derivatives_agree_with_dual_numbers(s in surface_strategy(5, 4, false), t in 0.0f64..=1.0, r in 0.0f64..=1.0) {
        let ((a, b), (c, d)) = s.domain();
        let (u, v) = (a + (b - a) * t, c + (d - c) * r);
        let ders = s.derivatives(u, v, 2).unwrap();
        // Hyper-dual parameters: eps1 seeds u, eps2 seeds v, eps1eps2 gives ∂²/∂u∂v.
        let hyper_points: Vec<Vector3<HyperDual64>> = s.control_points().iter().map(|p| p.map(HyperDual64::from)).collect();
        let hyper = Surface::new(
            KnotVector::new(s.degrees().0, s.knots_u().knots().iter().map(|&x| HyperDual64::from(x)).collect()).unwrap(),
            KnotVector::new(s.degrees().1, s.knots_v().knots().iter().map(|&x| HyperDual64::from(x)).collect()).unwrap(),
            hyper_points,
        ).unwrap();
        let value = hyper.eval(HyperDual64::new(u, 1.0, 0.0, 0.0), HyperDual64::new(v, 0.0, 1.0, 0.0)).unwrap();
        for i in 0..3 {
            let scale = 1.0 + ders[1][1][i].abs() + ders[1][0][i].abs() + ders[0][1][i].abs();
            prop_assert!((value[i].re - ders[0][0][i]).abs() < 1e-13);
            prop_assert!((value[i].eps1 - ders[1][0][i]).abs() < 1e-10 * scale);
            prop_assert!((value[i].eps2 - ders[0][1][i]).abs() < 1e-10 * scale);
            prop_assert!((value[i].eps1eps2 - ders[1][1][i]).abs() < 1e-10 * scale);
        }
        // The same seed twice in u gives ∂²/∂u².
        let uu = hyper.eval(HyperDual64::new(u, 1.0, 1.0, 0.0), HyperDual64::from(v)).unwrap();
        for i in 0..3 {
            prop_assert!((uu[i].eps1eps2 - ders[2][0][i]).abs() < 1e-10 * (1.0 + ders[2][0][i].abs()));
        }
    }

    #[test]
    fn partial_derivatives_agree_with_finite_differences(s in surface_strategy(4, 3, false), t in 0.05f64..0.95, r in 0.05f64..0.95) {
        let ((a, b), (c, d)) = s.domain();
        let (u, v) = (a + (b - a) * t, c + (d - c) * r);
        // Stay away from knots, where derivatives may jump.
        let near_knot = |k: &KnotVector<f64>, x: f64| k.knots().iter().any(|&y| (x - y).abs() < 1e-3);
        prop_assume!(!near_knot(s.knots_u(), u) && !near_knot(s.knots_v(), v));
        let ders = s.derivatives(u, v, 1).unwrap();
        let h = 1e-6;
        let fu = (s.eval(u + h, v).unwrap() - s.eval(u - h, v).unwrap()) / (2.0 * h);
        let fv = (s.eval(u, v + h).unwrap() - s.eval(u, v - h).unwrap()) / (2.0 * h);
        let fuv = (s.eval(u + h, v + h).unwrap() - s.eval(u + h, v - h).unwrap() - s.eval(u - h, v + h).unwrap() + s.eval(u - h, v - h).unwrap()) / (4.0 * h * h);
        prop_assert!((fu - ders[1][0]).norm() < 1e-5 * (1.0 + ders[1][0].norm()));
        prop_assert!((fv - ders[0][1]).norm() < 1e-5 * (1.0 + ders[0][1].norm()));
        prop_assert!((fuv - ders[1][1]).norm() < 1e-2 * (1.0 + ders[1][1].norm()));
    }
}

#[test]
fn derivatives_above_the_degrees_are_zero() {
    let s = Surface::bezier(vec![
        vec![
            Vector3::new(0.0, 0.0, 1.0),
            Vector3::new(0.0, 1.0, 2.0),
            Vector3::new(0.0, 2.0, 0.0),
        ],
        vec![
            Vector3::new(1.0, 0.0, 3.0),
            Vector3::new(1.0, 1.0, -1.0),
            Vector3::new(1.0, 2.0, 2.0),
        ],
    ])
    .unwrap();
    let d = s.derivatives(0.3, 0.6, 4).unwrap();
    for (k, row) in d.iter().enumerate() {
        for (l, x) in row.iter().enumerate() {
            if k > 1 || l > 2 {
                assert_eq!(*x, Vector3::zeros(), "k = {k}, l = {l}");
            } else {
                assert_ne!(*x, Vector3::zeros(), "k = {k}, l = {l}");
            }
        }
    }
}

/// The corners of a clamped surface are the corners of its net (seed 004 (5.9)) and the
/// boundary curves are the boundary rows of the net (5.4)–(5.8).
#[test]
fn clamped_surfaces_interpolate_corners_and_boundary_curves() {
    let ku = KnotVector::new(2, vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0]).unwrap();
    let kv = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.5, 2.0, 2.0, 2.0, 2.0]).unwrap();
    let net: Vec<Vec<Vector3<f64>>> = (0..4)
        .map(|i| {
            (0..5)
                .map(|j| Vector3::new(f64::from(i), f64::from(j), f64::from((i * 7 + j * 3) % 5)))
                .collect()
        })
        .collect();
    let s = Surface::from_net(ku.clone(), kv.clone(), net.clone()).unwrap();
    assert_eq!(s.eval(0.0, 0.0).unwrap(), net[0][0]);
    assert_eq!(s.eval(1.0, 0.0).unwrap(), net[3][0]);
    assert_eq!(s.eval(0.0, 2.0).unwrap(), net[0][4]);
    assert_eq!(s.eval(1.0, 2.0).unwrap(), net[3][4]);
    let first_column = BSpline::new(ku, net.iter().map(|r| r[0]).collect()).unwrap();
    let last_row = BSpline::new(kv, net[3].clone()).unwrap();
    for i in 0..=20 {
        let t = f64::from(i) / 20.0;
        assert!((s.eval(t, 0.0).unwrap() - first_column.eval(t).unwrap()).norm() < 1e-15);
        assert!((s.eval(1.0, 2.0 * t).unwrap() - last_row.eval(2.0 * t).unwrap()).norm() < 1e-15);
    }
    // Tangent plane at a corner (5.10)–(5.11): P'_u(u0, v0) = p/(u_{p+1} − u_1)(P10 − P00).
    let d = s.derivatives(0.0, 0.0, 1).unwrap();
    assert!((d[1][0] - (net[1][0] - net[0][0]) * (2.0 / 0.4)).norm() < 1e-14);
    assert!((d[0][1] - (net[0][1] - net[0][0]) * (3.0 / 0.5)).norm() < 1e-14);
}

/// The bilinear patch z = u v: K = −1/(1 + u² + v²)², H = −u v/(1 + u² + v²)^{3/2}, normal
/// (−v, −u, 1)/√(1 + u² + v²) (closed forms of a Monge patch).
#[test]
fn saddle_curvatures_match_closed_forms() {
    let s = Surface::bezier(vec![
        vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 1.0, 0.0)],
        vec![Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 1.0, 1.0)],
    ])
    .unwrap();
    for i in 0..=10 {
        for j in 0..=10 {
            let (u, v) = (f64::from(i) / 10.0, f64::from(j) / 10.0);
            let props = s.local_properties(u, v).unwrap();
            let w = 1.0 + u * u + v * v;
            assert!((props.gaussian_curvature + 1.0 / (w * w)).abs() < 1e-14);
            assert!((props.mean_curvature + u * v / w.powf(1.5)).abs() < 1e-14);
            assert!((props.normal - Vector3::new(-v, -u, 1.0) / w.sqrt()).norm() < 1e-14);
            assert!(
                (props.max_curvature * props.min_curvature - props.gaussian_curvature).abs()
                    < 1e-14
            );
            // Principal directions: unit, tangent, orthogonal, with normal curvatures κ1, κ2.
            for (d, k) in [
                (props.max_direction, props.max_curvature),
                (props.min_direction, props.min_curvature),
            ] {
                assert!((d.norm() - 1.0).abs() < 1e-14);
                assert!(d.dot(&props.normal).abs() < 1e-14);
                // Write d = a S_u + b S_v and compare II(a, b)/I(a, b) with κ.
                let (e, f, g) = (
                    props.first_form.uu,
                    props.first_form.uv,
                    props.first_form.vv,
                );
                let (du, dv) = (d.dot(&props.du), d.dot(&props.dv));
                let det = e * g - f * f;
                let (a, b) = ((g * du - f * dv) / det, (e * dv - f * du) / det);
                assert!((props.normal_curvature(a, b).unwrap() - k).abs() < 1e-13);
            }
            assert!(props.max_direction.dot(&props.min_direction).abs() < 1e-14);
        }
    }
}

/// A cylinder of radius r as an extrusion of a rational circle: K = 0, |H| = 1/(2r); the
/// rulings are the direction of zero curvature.
#[test]
fn cylinder_curvatures() {
    use spline_geom::{CircleConstruction, Frame, NurbsCurve, NurbsSurface};
    let r = 1.7;
    let circle = NurbsCurve::circle(
        &Frame::with_normal(Vector3::zeros(), Vector3::z()).unwrap(),
        r,
        CircleConstruction::Triangle,
    )
    .unwrap();
    let cyl = NurbsSurface::extrusion(&circle, Vector3::new(0.0, 0.0, 3.0)).unwrap();
    for i in 0..=40 {
        for j in 0..=4 {
            let (u, v) = (f64::from(i) / 40.0, f64::from(j) / 4.0);
            let props = cyl.local_properties(u, v).unwrap();
            assert!(
                props.gaussian_curvature.abs() < 1e-13,
                "K = {}",
                props.gaussian_curvature
            );
            assert!((props.mean_curvature.abs() - 0.5 / r).abs() < 1e-13);
            // The zero principal curvature belongs to the ruling (the z axis).
            let zero_dir = if props.max_curvature.abs() < props.min_curvature.abs() {
                props.max_direction
            } else {
                props.min_direction
            };
            assert!((zero_dir.z.abs() - 1.0).abs() < 1e-12);
        }
    }
}

#[test]
fn bad_nets_and_parameters_are_errors() {
    let ku = KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0]).unwrap();
    let kv = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).unwrap();
    let p = Vector3::new(1.0, 2.0, 3.0);
    // 2 × 3 net needed.
    let e = Surface::new(ku.clone(), kv.clone(), vec![p; 5]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    let e = Surface::from_net(ku.clone(), kv.clone(), vec![vec![p; 3]; 3]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    let e = Surface::from_net(ku.clone(), kv.clone(), vec![vec![p; 3], vec![p; 2]]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    assert!(e.message().contains("row 1"), "{e}");
    let e = Surface::from_net(
        ku.clone(),
        kv.clone(),
        vec![vec![p; 3], vec![p, Vector3::new(f64::NAN, 0.0, 0.0), p]],
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    assert_eq!(
        Surface::<f64, f64>::bezier(vec![]).unwrap_err().kind(),
        ErrorKind::InvalidLength
    );
    let e = Surface::<f64, f64>::from_knots(
        (1, 1),
        vec![0.0, 1.0, 0.5, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        vec![vec![0.0; 2]; 2],
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
    assert!(e.message().contains("knots in u"));

    let s = Surface::from_net(ku, kv, vec![vec![p; 3]; 2]).unwrap();
    assert_eq!(s.eval(1.5, 0.5).unwrap_err().kind(), ErrorKind::OutOfDomain);
    assert_eq!(
        s.eval(0.5, f64::NAN).unwrap_err().kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(
        s.eval_grid(&[0.5], &[0.2, -0.1]).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    let mut out = vec![Vector3::zeros(); 3];
    assert_eq!(
        s.derivatives_into(0.5, 0.5, 1, &mut out)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidLength
    );
    assert_eq!(
        s.split(Direction::U, 1.0).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    assert_eq!(
        s.split(Direction::V, f64::NAN).unwrap_err().kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(
        s.insert_knot(Direction::V, 0.5, 4).unwrap_err().kind(),
        ErrorKind::KnotMultiplicity
    );
    assert_eq!(
        s.remove_knot(Direction::U, 0.5, 1, 1e-9)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        s.derivative_surface(2, 0).unwrap_err().kind(),
        ErrorKind::OrderTooHigh
    );
    // A flat degenerate surface has no normal.
    assert_eq!(
        s.local_properties(0.5, 0.5).unwrap_err().kind(),
        ErrorKind::DegenerateGeometry
    );
    // Essential knots are not removed.
    let wavy = Surface::from_knots(
        (1, 1),
        vec![0.0, 0.0, 0.5, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        vec![vec![0.0, 1.0], vec![3.0, -1.0], vec![0.0, 2.0]],
    )
    .unwrap();
    assert_eq!(
        wavy.remove_knot(Direction::U, 0.5, 1, 1e-9)
            .unwrap_err()
            .kind(),
        ErrorKind::ToleranceExceeded
    );
}

/// The same structural operations in any scalar type: the values agree with `f64` to the
/// precision of the type.
fn structural_operations_in<T: Scalar>(tol: f64) {
    let ku = KnotVector::new(
        3,
        [0.0, 0.0, 0.0, 0.0, 0.3, 0.7, 1.0, 1.0, 1.0, 1.0]
            .map(cast::<T>)
            .to_vec(),
    )
    .unwrap();
    let kv = KnotVector::new(
        2,
        [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0].map(cast::<T>).to_vec(),
    )
    .unwrap();
    let points: Vec<Vector3<T>> = (0..24)
        .map(|k| {
            let x = f64::from(k);
            Vector3::new(
                cast((x * 0.7).sin()),
                cast((x * 1.3).cos()),
                cast((x * 0.37).sin() * 2.0),
            )
        })
        .collect();
    let s = Surface::new(ku, kv, points).unwrap();
    let t: T = cast(0.45);
    let ops: Vec<Surface<T, Vector3<T>>> = vec![
        s.insert_knot(Direction::U, t, 2).unwrap(),
        s.insert_knot(Direction::V, t, 1).unwrap(),
        s.refine(Direction::V, &[cast(0.1), cast(0.8), cast(0.8)])
            .unwrap(),
        s.elevate_degree(Direction::U, 1).unwrap(),
        s.elevate_degree(Direction::V, 2).unwrap(),
        s.insert_knot(Direction::U, t, 1)
            .unwrap()
            .remove_knot(Direction::U, t, 1, cast(1e-3))
            .unwrap(),
    ];
    let (left, right) = s.split(Direction::V, t).unwrap();
    for i in 0..=8 {
        for j in 0..=8 {
            let (u, v) = (cast::<T>(f64::from(i) / 8.0), cast::<T>(f64::from(j) / 8.0));
            let x = s.eval(u, v).unwrap();
            let grid = s.eval_grid(&[u], &[v]).unwrap()[0];
            assert!(to_f64((grid - x).norm()) <= tol);
            for o in &ops {
                let y = o.eval(u, v).unwrap();
                assert!(
                    to_f64((y - x).norm()) <= tol,
                    "{} vs {}",
                    to_f64(y.x),
                    to_f64(x.x)
                );
            }
            let half = if v <= t { &left } else { &right };
            assert!(to_f64((half.eval(u, v).unwrap() - x).norm()) <= tol);
        }
    }
}

#[test]
fn structural_operations_in_f32() {
    structural_operations_in::<f32>(2e-5);
}

#[test]
fn structural_operations_in_f64() {
    structural_operations_in::<f64>(1e-13);
}

#[test]
fn structural_operations_in_dual_numbers() {
    structural_operations_in::<Dual64>(1e-13);
}

/// Dual numbers through the control points: the derivative of S(u, v) with respect to
/// `P_ij` is the product of basis functions `N_i(u)` `N_j(v)`.
#[test]
fn dual_control_points_give_tensor_basis_functions() {
    let ku = KnotVector::new(2, vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0]).unwrap();
    let kv = KnotVector::new(1, vec![0.0, 0.0, 0.5, 1.0, 1.0]).unwrap();
    let (nu, nv) = (4, 3);
    for (i, j) in [(0, 0), (1, 2), (2, 1), (3, 2)] {
        let points: Vec<Dual64> = (0..nu * nv)
            .map(|k| Dual64::new(k as f64, if k == i * nv + j { 1.0 } else { 0.0 }))
            .collect();
        let dual_ku =
            KnotVector::new(2, ku.knots().iter().map(|&x| Dual64::from(x)).collect()).unwrap();
        let dual_kv =
            KnotVector::new(1, kv.knots().iter().map(|&x| Dual64::from(x)).collect()).unwrap();
        let s = Surface::new(dual_ku, dual_kv, points).unwrap();
        for (u, v) in [(0.1, 0.2), (0.4, 0.5), (0.77, 0.9), (1.0, 1.0)] {
            let value = s.eval(Dual64::from(u), Dual64::from(v)).unwrap();
            let expected = ku.basis_function(i, u).unwrap() * kv.basis_function(j, v).unwrap();
            assert!((value.eps - expected).abs() < 1e-15);
        }
    }
}

#[test]
fn surfaces_with_four_coordinates_cannot_be_meshed() {
    let s = Surface::bezier(vec![vec![Vector4::new(0.0, 0.0, 0.0, 1.0); 2]; 2]).unwrap();
    assert_eq!(
        s.tessellate(4, 4).unwrap_err().kind(),
        ErrorKind::DimensionMismatch
    );
}
