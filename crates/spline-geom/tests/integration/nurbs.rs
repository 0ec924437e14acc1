//! NURBS curves and surfaces checked against independent facts: the rational derivatives
//! against finite differences and dual numbers, invariance under every structural operation
//! (done in homogeneous space), closed forms, weight validation.

use nalgebra::Vector3;
use num_dual::{Dual2_64, Dual64, HyperDual64};
use proptest::prelude::*;
use spline_core::{ErrorKind, KnotVector, Scalar};
use spline_geom::StructuralSurface;
use spline_geom::{Direction, NurbsCurve, NurbsSurface};
use spline_testing::strategies::knot_vector;

type N3 = NurbsCurve<f64, 3>;
type NS3 = NurbsSurface<f64, 3>;

fn curve_strategy(
    max_degree: usize,
    extra: usize,
    discontinuous: bool,
) -> impl Strategy<Value = N3> {
    knot_vector(max_degree, extra, 1.0, discontinuous).prop_flat_map(|knots| {
        let n = knots.num_basis();
        (
            proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), n),
            proptest::collection::vec(0.2f64..3.0, n),
        )
            .prop_map(move |(pts, w)| {
                NurbsCurve::new(
                    knots.clone(),
                    pts.into_iter()
                        .map(|(x, y, z)| Vector3::new(x, y, z))
                        .collect(),
                    w,
                )
                .unwrap()
            })
    })
}

fn surface_strategy(max_degree: usize, extra: usize) -> impl Strategy<Value = NS3> {
    (
        knot_vector(max_degree, extra, 1.0, false),
        knot_vector(max_degree, extra, 1.0, false),
    )
        .prop_flat_map(|(ku, kv)| {
            let n = ku.num_basis() * kv.num_basis();
            (
                proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), n),
                proptest::collection::vec(0.2f64..3.0, n),
            )
                .prop_map(move |(pts, w)| {
                    NurbsSurface::new(
                        ku.clone(),
                        kv.clone(),
                        pts.into_iter()
                            .map(|(x, y, z)| Vector3::new(x, y, z))
                            .collect(),
                        w,
                    )
                    .unwrap()
                })
        })
}

fn samples(knots: &KnotVector<f64>, count: usize) -> Vec<f64> {
    let (a, b) = knots.domain();
    let mut us: Vec<f64> = (0..=count)
        .map(|i| a + (b - a) * i as f64 / count as f64)
        .collect();
    us.extend(knots.knots().iter().copied().filter(|&k| k >= a && k <= b));
    us.sort_by(f64::total_cmp);
    us
}

fn same_curve(a: &N3, b: &N3, tol: f64) -> Result<(), TestCaseError> {
    for u in samples(a.knots(), 40) {
        let (p, q) = (a.eval(u).unwrap(), b.eval(u).unwrap());
        prop_assert!((p - q).norm() < tol, "u = {}: {:?} vs {:?}", u, p, q);
    }
    Ok(())
}

fn same_surface(a: &NS3, b: &NS3, tol: f64) -> Result<(), TestCaseError> {
    for u in samples(a.knots_u(), 8) {
        for v in samples(a.knots_v(), 8) {
            let (p, q) = (a.eval(u, v).unwrap(), b.eval(u, v).unwrap());
            prop_assert!((p - q).norm() < tol, "({}, {}): {:?} vs {:?}", u, v, p, q);
        }
    }
    Ok(())
}

/// The curve with every number turned into a dual number of another kind.
fn lift<T: Scalar, const D: usize>(
    c: &NurbsCurve<f64, D>,
    f: impl Fn(f64) -> T,
) -> NurbsCurve<T, D> {
    NurbsCurve::from_knots(
        c.degree(),
        c.knots().knots().iter().map(|&k| f(k)).collect(),
        c.control_points().iter().map(|p| p.map(&f)).collect(),
        c.weights().iter().map(|&w| f(w)).collect(),
    )
    .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn rational_derivatives_agree_with_dual_numbers(c in curve_strategy(5, 6, false), t in 0.0f64..=1.0) {
        let (a, b) = c.domain();
        let u = a + (b - a) * t;
        let ders = c.derivatives(u, 2).unwrap();
        let first = lift(&c, Dual64::from).eval(Dual64::new(u, 1.0)).unwrap();
        let second = lift(&c, Dual2_64::from).eval(Dual2_64::new(u, 1.0, 0.0)).unwrap();
        for i in 0..3 {
            prop_assert!((first[i].re - ders[0][i]).abs() < 1e-14 * (1.0 + ders[0][i].abs()));
            prop_assert!((first[i].eps - ders[1][i]).abs() < 1e-10 * (1.0 + ders[1][i].abs()));
            prop_assert!((second[i].v2 - ders[2][i]).abs() < 1e-9 * (1.0 + ders[2][i].abs()), "{} vs {}", second[i].v2, ders[2][i]);
        }
    }

    #[test]
    fn rational_derivatives_agree_with_finite_differences(c in curve_strategy(4, 4, false), t in 0.05f64..0.95) {
        let (a, b) = c.domain();
        let u = a + (b - a) * t;
        prop_assume!(c.knots().knots().iter().all(|&k| (k - u).abs() > 1e-3));
        // Up to order 4, above the degree too: rational derivatives do not vanish there.
        let ders = c.derivatives(u, 4).unwrap();
        let h = 1e-5;
        let lower = |k: usize, x: f64| c.derivatives(x, k).unwrap()[k];
        for k in 1..=4 {
            let fd = (lower(k - 1, u + h) - lower(k - 1, u - h)) / (2.0 * h);
            let scale = 1.0 + ders[k].norm() + ders[k - 1].norm();
            prop_assert!((fd - ders[k]).norm() < 1e-5 * scale, "k = {}: {:?} vs {:?}", k, fd, ders[k]);
        }
    }

    #[test]
    fn surface_rational_derivatives_agree_with_hyper_dual_numbers(s in surface_strategy(3, 3), t in 0.0f64..=1.0, r in 0.0f64..=1.0) {
        let ((a, b), (c, d)) = s.domain();
        let (u, v) = (a + (b - a) * t, c + (d - c) * r);
        let ders = s.derivatives(u, v, 2).unwrap();
        let lift = |x: f64| HyperDual64::from(x);
        let hyper = NurbsSurface::new(
            KnotVector::new(s.degrees().0, s.knots_u().knots().iter().map(|&x| lift(x)).collect()).unwrap(),
            KnotVector::new(s.degrees().1, s.knots_v().knots().iter().map(|&x| lift(x)).collect()).unwrap(),
            s.control_points().iter().map(|p| p.map(lift)).collect(),
            s.weights().iter().map(|&w| lift(w)).collect(),
        ).unwrap();
        let mixed = hyper.eval(HyperDual64::new(u, 1.0, 0.0, 0.0), HyperDual64::new(v, 0.0, 1.0, 0.0)).unwrap();
        let uu = hyper.eval(HyperDual64::new(u, 1.0, 1.0, 0.0), lift(v)).unwrap();
        let vv = hyper.eval(lift(u), HyperDual64::new(v, 1.0, 1.0, 0.0)).unwrap();
        for i in 0..3 {
            let close = |x: f64, y: f64| (x - y).abs() < 1e-9 * (1.0 + y.abs());
            prop_assert!(close(mixed[i].re, ders[0][0][i]));
            prop_assert!(close(mixed[i].eps1, ders[1][0][i]));
            prop_assert!(close(mixed[i].eps2, ders[0][1][i]));
            prop_assert!(close(mixed[i].eps1eps2, ders[1][1][i]), "{} vs {}", mixed[i].eps1eps2, ders[1][1][i]);
            prop_assert!(close(uu[i].eps1eps2, ders[2][0][i]));
            prop_assert!(close(vv[i].eps1eps2, ders[0][2][i]));
        }
    }

    #[test]
    fn surface_rational_derivatives_agree_with_finite_differences(s in surface_strategy(3, 3), t in 0.05f64..0.95, r in 0.05f64..0.95) {
        let ((a, b), (c, d)) = s.domain();
        let (u, v) = (a + (b - a) * t, c + (d - c) * r);
        let far = |k: &KnotVector<f64>, x: f64| k.knots().iter().all(|&y| (x - y).abs() > 1e-3);
        prop_assume!(far(s.knots_u(), u) && far(s.knots_v(), v));
        let ders = s.derivatives(u, v, 3).unwrap();
        let h = 1e-5;
        // ∂/∂u of every [k][l] with k < 3 against the next order, and the same in v.
        for k in 0..3 {
            for l in 0..3 {
                let du = (s.derivatives(u + h, v, 3).unwrap()[k][l] - s.derivatives(u - h, v, 3).unwrap()[k][l]) / (2.0 * h);
                let dv = (s.derivatives(u, v + h, 3).unwrap()[k][l] - s.derivatives(u, v - h, 3).unwrap()[k][l]) / (2.0 * h);
                let su = 1.0 + ders[k + 1][l].norm() + ders[k][l].norm();
                let sv = 1.0 + ders[k][l + 1].norm() + ders[k][l].norm();
                prop_assert!((du - ders[k + 1][l]).norm() < 1e-4 * su, "d/du of [{}][{}]", k, l);
                prop_assert!((dv - ders[k][l + 1]).norm() < 1e-4 * sv, "d/dv of [{}][{}]", k, l);
            }
        }
    }

    #[test]
    fn curve_structural_operations_keep_the_curve(c in curve_strategy(5, 6, false), t in 0.01f64..0.99, times in 1usize..3) {
        let (a, b) = c.domain();
        let u = a + (b - a) * ((t * 512.0).round() / 512.0);
        let room = |x: f64| c.degree() + 1 - c.knots().multiplicity(x);
        match c.insert_knot(u, times) {
            Ok(r) => {
                same_curve(&c, &r, 1e-12)?;
                // ... and removing the inserted knots gives the curve back.
                if c.knots().multiplicity(u) == 0 {
                    let back = r.remove_knot(u, times, 1e-9).unwrap();
                    prop_assert_eq!(back.knots(), c.knots());
                    for (w, x) in back.weights().iter().zip(c.weights()) {
                        prop_assert!((w - x).abs() < 1e-9);
                    }
                    same_curve(&c, &back, 1e-9)?;
                }
            }
            // Only a knot already there too often is refused.
            Err(e) => {
                prop_assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
                prop_assert!(times > room(u));
            }
        }
        let mid = u * 0.5 + a * 0.5;
        match c.refine(&[u, mid, u]) {
            Ok(r) => same_curve(&c, &r, 1e-12)?,
            Err(e) => {
                prop_assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
                prop_assert!(2 > room(u) || (mid != u && 1 > room(mid)));
            }
        }
        let e = c.elevate_degree(times).unwrap();
        prop_assert_eq!(e.degree(), c.degree() + times);
        same_curve(&c, &e, 1e-11)?;
        let cl = c.clamped();
        prop_assert!(cl.knots().is_clamped());
        same_curve(&c, &cl, 1e-11)?;
        if u > a && u < b {
            let (left, right) = c.split(u).unwrap();
            for i in 0..=20 {
                let x = a + (u - a) * f64::from(i) / 20.0;
                let y = u + (b - u) * f64::from(i) / 20.0;
                prop_assert!((left.eval(x.min(u)).unwrap() - c.eval(x.min(u)).unwrap()).norm() < 1e-11 || i == 20);
                prop_assert!((right.eval(y.min(b)).unwrap() - c.eval(y.min(b)).unwrap()).norm() < 1e-11);
            }
        }
        let rev = c.reversed();
        for i in 1..20 {
            let x = a + (b - a) * f64::from(i) / 20.0;
            if c.knots().multiplicity(x) == 0 {
                prop_assert!((rev.eval(a + b - x).unwrap() - c.eval(x).unwrap()).norm() < 1e-11);
            }
        }
        for seg in c.bezier_segments().unwrap() {
            let (s0, s1) = seg.domain();
            prop_assert_eq!(seg.len(), c.degree() + 1);
            for i in 0..=8 {
                let x = s0 + (s1 - s0) * (0.01 + 0.98 * f64::from(i) / 8.0);
                prop_assert!((seg.eval(x).unwrap() - c.eval(x).unwrap()).norm() < 1e-11);
            }
        }
    }

    #[test]
    fn surface_structural_operations_keep_the_surface(s in surface_strategy(3, 3), t in 0.01f64..0.99, in_u: bool) {
        let d = if in_u { Direction::U } else { Direction::V };
        let (a, b) = s.knots(d).domain();
        let x = a + (b - a) * ((t * 512.0).round() / 512.0);
        let room = s.degree(d) + 1 - s.knots(d).multiplicity(x);
        match s.insert_knot(d, x, 1) {
            Ok(r) => {
                same_surface(&s, &r, 1e-12)?;
                if s.knots(d).multiplicity(x) == 0 && s.degree(d) > 0 {
                    let back = r.remove_knot(d, x, 1, 1e-9).unwrap();
                    prop_assert_eq!(back.knots(d), s.knots(d));
                    same_surface(&s, &back, 1e-9)?;
                }
            }
            Err(e) => {
                prop_assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
                prop_assert_eq!(room, 0);
            }
        }
        match s.refine(d, &[x, x]) {
            Ok(r) => same_surface(&s, &r, 1e-12)?,
            Err(e) => {
                prop_assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
                prop_assert!(room < 2);
            }
        }
        same_surface(&s, &s.elevate_degree(d, 2).unwrap(), 1e-11)?;
        same_surface(&s, &s.clamped(), 1e-11)?;
        let (left, right) = s.split(d, x).unwrap();
        for i in 0..=6 {
            for j in 0..=6 {
                let along = |lo: f64, hi: f64| lo + (hi - lo) * (0.01 + 0.98 * f64::from(i) / 6.0);
                let other = s.knots(d.other()).domain();
                let w = other.0 + (other.1 - other.0) * f64::from(j) / 6.0;
                for (half, lo, hi) in [(&left, a, x), (&right, x, b)] {
                    let y = along(lo, hi);
                    let (p, q) = match d {
                        Direction::U => (half.eval(y, w).unwrap(), s.eval(y, w).unwrap()),
                        Direction::V => (half.eval(w, y).unwrap(), s.eval(w, y).unwrap()),
                    };
                    prop_assert!((p - q).norm() < 1e-11);
                }
            }
        }
        for (a_idx, row) in s.bezier_patches().unwrap().iter().enumerate() {
            for patch in row {
                let ((u0, u1), (v0, v1)) = patch.domain();
                let (u, v) = ((u0 + u1) / 2.0, (v0 + v1) / 2.0);
                prop_assert!((patch.eval(u, v).unwrap() - s.eval(u, v).unwrap()).norm() < 1e-11, "patch row {}", a_idx);
            }
        }
        let tr = s.transposed();
        prop_assert!((tr.eval(0.3, 0.6).unwrap() - s.eval(0.6, 0.3).unwrap()).norm() < 1e-14);
        // Iso-curves are NURBS curves on the surface.
        let cu = s.curve_at_u(0.37).unwrap();
        let cv = s.curve_at_v(0.71).unwrap();
        for i in 0..=10 {
            let y = f64::from(i) / 10.0;
            prop_assert!((cu.eval(y).unwrap() - s.eval(0.37, y).unwrap()).norm() < 1e-12);
            prop_assert!((cv.eval(y).unwrap() - s.eval(y, 0.71).unwrap()).norm() < 1e-12);
        }
    }
}
