//! The Möbius reparametrization of NURBS curves (the same points at the mapped parameters,
//! the end weights it promises) and the Coons patch of rational boundaries (every boundary
//! reproduced, corner weights that disagree, the blends it refuses).

use crate::constructions::Rng;
use nalgebra::Vector3;
use spline_core::ErrorKind;
use spline_geom::{BSpline, NurbsCurve3, NurbsSurface3, Surface};

/// A random clamped NURBS curve of degree `p` with `n` control points from `a` to `b`,
/// interior knots and weights drawn from `rng` (weights in [0.3, 3]).
fn random_curve(
    rng: &mut Rng,
    p: usize,
    n: usize,
    a: Vector3<f64>,
    b: Vector3<f64>,
) -> NurbsCurve3 {
    let mut interior: Vec<f64> = (0..n - p - 1).map(|_| 0.05 + 0.9 * rng.next()).collect();
    interior.sort_by(f64::total_cmp);
    let mut knots = vec![0.0; p + 1];
    knots.extend(interior);
    knots.extend(vec![1.0; p + 1]);
    let points = (0..n)
        .map(|i| {
            let t = i as f64 / (n - 1) as f64;
            let wobble = Vector3::new(rng.next(), rng.next(), rng.next()) - Vector3::repeat(0.5);
            match i {
                0 => a,
                _ if i == n - 1 => b,
                _ => a + (b - a) * t + wobble,
            }
        })
        .collect();
    let weights = (0..n).map(|_| 0.3 + 2.7 * rng.next()).collect();
    NurbsCurve3::from_knots(p, knots, points, weights).unwrap()
}

/// `φ(s) = s / (c (1 − s) + s)`.
fn phi(c: f64, s: f64) -> f64 {
    s / (c * (1.0 - s) + s)
}

#[test]
fn mobius_reparametrization_keeps_the_points_at_the_mapped_parameters() {
    let mut rng = Rng(7);
    for case in 0..40 {
        let p = 1 + case % 5;
        let n = p + 1 + case % 7;
        let curve = random_curve(
            &mut rng,
            p,
            n,
            Vector3::zeros(),
            Vector3::new(3.0, 1.0, 2.0),
        );
        let c = (4.0 * rng.next() - 2.0).exp();
        let moved = curve.mobius_reparametrized(c).unwrap();
        assert_eq!(moved.degree(), p);
        assert_eq!(moved.len(), n);
        // The end weights: the first times c^p, the last kept.
        let w = curve.weights();
        let v = moved.weights();
        assert!(
            (v[0] - w[0] * c.powi(p as i32)).abs() <= 1e-13 * v[0],
            "case {case}"
        );
        assert!(
            (v[n - 1] - w[n - 1]).abs() <= 1e-13 * w[n - 1],
            "case {case}"
        );
        for k in 0..=50 {
            let s = f64::from(k) / 50.0;
            let gap = (moved.eval(s).unwrap() - curve.eval(phi(c, s)).unwrap()).norm();
            assert!(
                gap < 1e-12,
                "case {case}: p = {p}, c = {c}, s = {s}: {gap:e}"
            );
        }
    }
}

#[test]
fn mobius_reparametrization_on_another_domain_and_by_one() {
    let mut rng = Rng(11);
    let curve = random_curve(
        &mut rng,
        3,
        7,
        Vector3::zeros(),
        Vector3::new(1.0, 2.0, 3.0),
    );
    let shifted = curve.reparametrized(-2.0, 5.0).unwrap();
    let moved = shifted.mobius_reparametrized(0.25).unwrap();
    assert_eq!(moved.domain(), (-2.0, 5.0));
    for k in 0..=20 {
        let x = f64::from(k) / 20.0;
        let want = curve.eval(phi(0.25, x)).unwrap();
        assert!((moved.eval(-2.0 + 7.0 * x).unwrap() - want).norm() < 1e-12);
    }
    let same = curve.mobius_reparametrized(1.0).unwrap();
    for (a, b) in same.weights().iter().zip(curve.weights()) {
        assert!((a - b).abs() <= 1e-15 * b);
    }
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = curve.mobius_reparametrized(bad).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidArgument, "{bad}");
    }
}

/// The parameter of `top` nearest to `q` (dense sampling refined by golden sections) and
/// the distance there.
fn nearest_on(curve: &NurbsCurve3, q: Vector3<f64>) -> (f64, f64) {
    let d = |s: f64| (curve.eval(s).unwrap() - q).norm();
    let samples = 2000;
    let best = (0..=samples)
        .map(|k| f64::from(k) / f64::from(samples))
        .min_by(|a, b| d(*a).total_cmp(&d(*b)))
        .unwrap();
    let (mut lo, mut hi) = (
        (best - 1.0 / f64::from(samples)).max(0.0),
        (best + 1.0 / f64::from(samples)).min(1.0),
    );
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let (x1, x2) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
        if d(x1) <= d(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    let s = 0.5 * (lo + hi);
    (s, d(s))
}

#[test]
fn rational_coons_reproduces_every_boundary() {
    let mut rng = Rng(3);
    for case in 0..12 {
        let corners = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(4.0, 0.0, 0.5),
            Vector3::new(0.0, 4.0, -0.5),
            Vector3::new(4.0, 4.0, 1.0),
        ];
        let (p, q) = (1 + case % 3, 2 + case % 2);
        let bottom = random_curve(&mut rng, p, p + 3, corners[0], corners[1]);
        let top = random_curve(&mut rng, p + 1, p + 4, corners[2], corners[3]);
        let left = random_curve(&mut rng, q, q + 2, corners[0], corners[2]);
        let right = random_curve(&mut rng, q, q + 3, corners[1], corners[3]);
        let patch = NurbsSurface3::coons(&bottom, &top, &left, &right).unwrap();
        let mut previous = 0.0;
        for k in 0..=40 {
            let t = f64::from(k) / 40.0;
            let at = |u: f64, v: f64| patch.eval(u, v).unwrap();
            assert!(
                (at(t, 0.0) - bottom.eval(t).unwrap()).norm() < 1e-12,
                "case {case}"
            );
            assert!(
                (at(0.0, t) - left.eval(t).unwrap()).norm() < 1e-12,
                "case {case}"
            );
            assert!(
                (at(1.0, t) - right.eval(t).unwrap()).norm() < 1e-12,
                "case {case}"
            );
            // The top is traversed in order, at reparametrized parameters.
            let (s, gap) = nearest_on(&top, at(t, 1.0));
            assert!(gap < 1e-11, "case {case}: top at {t}: {gap:e}");
            assert!(
                s >= previous - 1e-9,
                "case {case}: the top runs backwards at {t}"
            );
            previous = s;
        }
        assert!((patch.eval(1.0, 1.0).unwrap() - corners[3]).norm() < 1e-12);
    }
}

#[test]
fn rational_coons_of_polynomial_curves_is_the_polynomial_patch() {
    let mut rng = Rng(5);
    let corners = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(2.0, 0.0, 0.0),
        Vector3::new(0.0, 3.0, 1.0),
        Vector3::new(2.0, 3.0, 0.0),
    ];
    let unit = |c: NurbsCurve3| -> BSpline<f64, Vector3<f64>> {
        let ones = vec![1.0; c.len()];
        let c = NurbsCurve3::new(c.knots().clone(), c.control_points().to_vec(), ones).unwrap();
        c.to_bspline().unwrap()
    };
    let b = unit(random_curve(&mut rng, 3, 6, corners[0], corners[1]));
    let t = unit(random_curve(&mut rng, 2, 4, corners[2], corners[3]));
    let l = unit(random_curve(&mut rng, 3, 5, corners[0], corners[2]));
    let r = unit(random_curve(&mut rng, 1, 3, corners[1], corners[3]));
    let plain = Surface::coons(&b, &t, &l, &r).unwrap();
    let nurbs = |c: &BSpline<f64, Vector3<f64>>| NurbsCurve3::from_bspline(c);
    let rational = NurbsSurface3::coons(&nurbs(&b), &nurbs(&t), &nurbs(&l), &nurbs(&r)).unwrap();
    assert_eq!(rational.net_size(), plain.net_size());
    assert!(rational.weights().iter().all(|&w| (w - 1.0).abs() < 1e-15));
    for (a, b) in rational.control_points().iter().zip(plain.control_points()) {
        assert!((a - b).norm() < 1e-14);
    }
}

#[test]
fn rational_coons_weights_stay_positive_and_corners_must_meet() {
    let h = 0.05;
    let arc = |a: Vector3<f64>, m: Vector3<f64>, b: Vector3<f64>| {
        NurbsCurve3::from_knots(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![a, m, b],
            vec![1.0, h, 1.0],
        )
        .unwrap()
    };
    let (a, b, c, d) = (
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0, 0.0, 0.0),
        Vector3::new(0.0, 1.0, 0.0),
        Vector3::new(1.0, 1.0, 0.0),
    );
    let up = Vector3::new(0.0, 0.0, 1.0);
    // Middle weights of 0.05 against corner weights of 1: a linear blend of the weights
    // would give 0.05 + 0.05 − 1 < 0 in the middle; the blend of their logarithms is
    // 0.05² = 0.0025.
    let sides = [
        arc(a, (a + b) / 2.0 + up, b),
        arc(c, (c + d) / 2.0 + up, d),
        arc(a, (a + c) / 2.0 + up, c),
        arc(b, (b + d) / 2.0 + up, d),
    ];
    let patch = NurbsSurface3::coons(&sides[0], &sides[1], &sides[2], &sides[3]).unwrap();
    assert!(patch.weights().iter().all(|&w| w > 0.0));
    assert!((patch.weights()[4] - h * h).abs() < 1e-15);
    for k in 0..=10 {
        let t = f64::from(k) / 10.0;
        for (uv, curve) in [((t, 0.0), 0), ((t, 1.0), 1), ((0.0, t), 2), ((1.0, t), 3)] {
            let gap = (patch.eval(uv.0, uv.1).unwrap() - sides[curve].eval(t).unwrap()).norm();
            assert!(gap < 1e-14, "boundary {curve} at {t}: {gap:e}");
        }
    }
    // Curves that miss a corner.
    let e = NurbsSurface3::coons(
        &arc(a, (a + b) / 2.0, b),
        &arc(c, (c + d) / 2.0, d + Vector3::new(0.0, 0.0, 1e-3)),
        &arc(a, (a + c) / 2.0, c),
        &arc(b, (b + d) / 2.0, d),
    )
    .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::DegenerateGeometry);
    assert!(e.to_string().contains("top and right"), "{e}");
}
