//! Tensor-product surfaces checked against independent facts: invariance of the surface
//! under every structural operation (sampled), finite differences and dual numbers for the
//! partial derivatives, closed forms for the differential geometry, and error cases.

use nalgebra::Vector3;
use num_dual::HyperDual64;
use proptest::prelude::*;
use spline_core::{ErrorKind, KnotVector};
use spline_geom::{Direction, Surface};
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
