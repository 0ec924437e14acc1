//! Knot insertion and refinement in place, the NURBS batch and the fixed-degree surface
//! kernels, checked against independent algorithms: Boehm's single-knot formula written
//! out here, de Boor's algorithm, the knot rules of spline-core, and per-point evaluation.

use nalgebra::{Vector2, Vector3};
use spline_core::{ErrorKind, KnotVector};
use spline_geom::{BSpline, NurbsCurve2, Surface};

/// A deterministic generator of numbers in [0, 1).
fn samples(count: usize, seed: u64) -> Vec<f64> {
    let mut state = seed;
    (0..count)
        .map(|_| {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}

fn curve(degree: usize, n: usize, clamped: bool, seed: u64) -> BSpline<f64, Vector2<f64>> {
    let knots = if clamped {
        KnotVector::clamped_uniform(degree, n, 0.0, 1.0).unwrap()
    } else {
        KnotVector::uniform(degree, n, 0.0, 1.0).unwrap()
    };
    let ys = samples(2 * n, seed);
    let points = (0..n)
        .map(|i| Vector2::new(ys[2 * i], ys[2 * i + 1]))
        .collect();
    BSpline::new(knots, points).unwrap()
}

/// Boehm's insertion of one knot (The NURBS Book (5.10)–(5.11)), written independently of
/// the library's A5.4: new points `α P_i + (1 − α) P_{i−1}` on `k − p + 1 … k`.
fn boehm(c: &BSpline<f64, Vector2<f64>>, u: f64) -> (Vec<f64>, Vec<Vector2<f64>>) {
    let p = c.degree();
    let t = c.knots().knots();
    let pts = c.control_points();
    let k = t.partition_point(|&x| x <= u) - 1;
    let mut q = Vec::with_capacity(pts.len() + 1);
    for i in 0..=pts.len() {
        q.push(if i + p <= k {
            pts[i]
        } else if i > k {
            pts[i - 1]
        } else {
            let a = (u - t[i]) / (t[i + p] - t[i]);
            pts[i] * a + pts[i - 1] * (1.0 - a)
        });
    }
    let mut knots = t.to_vec();
    knots.insert(k + 1, u);
    (knots, q)
}

fn max_gap(a: &BSpline<f64, Vector2<f64>>, b: &BSpline<f64, Vector2<f64>>) -> f64 {
    let (lo, hi) = a.domain();
    (0..=400)
        .map(|i| {
            let u = lo + (hi - lo) * f64::from(i) / 400.0;
            (a.eval(u).unwrap() - b.de_boor(u).unwrap()).amax()
        })
        .fold(0.0, f64::max)
}

#[test]
fn insertion_in_place_matches_boehm_one_knot_at_a_time() {
    for degree in 1..=7 {
        for clamped in [true, false] {
            let original = curve(degree, degree + 9, clamped, 3 + degree as u64);
            let (a, b) = original.domain();
            let mut c = original.clone();
            for (j, t) in samples(40, 11).into_iter().enumerate() {
                // Every fifth knot lands on an existing one (multiplicity grows).
                let u = if j % 5 == 0 {
                    c.knots().knots()[degree + 1 + j % 7]
                } else {
                    a + (b - a) * t
                };
                if c.knots().multiplicity(u) > degree || !(u < b) {
                    continue;
                }
                let (knots, points) = boehm(&c, u);
                c.insert_knot_mut(u, 1).unwrap();
                assert_eq!(c.knots().knots(), &knots[..], "degree {degree}, knot {u}");
                for (x, y) in c.control_points().iter().zip(&points) {
                    assert!((x - y).amax() < 1e-13, "degree {degree}: {x:?} vs {y:?}");
                }
            }
            assert!(max_gap(&c, &original) < 1e-13);
        }
    }
}

#[test]
fn multiple_insertion_and_refinement_agree_with_the_knot_rules() {
    let original = curve(3, 12, true, 5);
    let mut c = original.clone();
    c.insert_knot_mut(0.37, 3).unwrap();
    assert_eq!(c.knots(), &original.knots().with_inserted(0.37, 3).unwrap());
    assert!(max_gap(&c, &original) < 1e-13);
    // Unsorted, repeated knots: the sorted path and the copying path give the same curve.
    let x = [0.9, 0.1, 0.5, 0.1, 0.75, 0.5];
    let mut sorted = x;
    sorted.sort_by(f64::total_cmp);
    let mut r1 = original.clone();
    r1.refine_mut(&x).unwrap();
    let mut r2 = original.clone();
    r2.refine_mut(&sorted).unwrap();
    assert_eq!(r1, r2);
    assert_eq!(r1, original.refine(&x).unwrap());
    assert_eq!(r1.knots(), &original.knots().refined(&x).unwrap());
    assert!(max_gap(&r1, &original) < 1e-13);
}

#[test]
fn bad_insertions_are_refused_and_leave_the_curve_unchanged() {
    let original = curve(2, 6, true, 7);
    let mut c = original.clone();
    let cases: [(f64, usize, ErrorKind); 4] = [
        (1.5, 1, ErrorKind::OutOfDomain),
        (f64::NAN, 1, ErrorKind::NonFinite),
        (0.5, 4, ErrorKind::KnotMultiplicity),
        (0.0, 1, ErrorKind::KnotMultiplicity),
    ];
    for (u, times, kind) in cases {
        let e = c.insert_knot_mut(u, times).unwrap_err();
        assert_eq!(e.kind(), kind, "{u} × {times}: {e}");
        assert!(!e.to_string().contains('\n'));
        assert_eq!(c, original);
    }
    for (x, kind) in [
        (vec![0.2, 2.0], ErrorKind::OutOfDomain),
        (vec![0.2, f64::INFINITY], ErrorKind::NonFinite),
        (vec![0.3, 0.3, 0.3, 0.3], ErrorKind::KnotMultiplicity),
        (vec![0.3, 0.1, 0.3, 0.3, 0.3], ErrorKind::KnotMultiplicity),
    ] {
        let e = c.refine_mut(&x).unwrap_err();
        assert_eq!(e.kind(), kind, "{x:?}: {e}");
        assert_eq!(c, original);
    }
    // Up to the limit is fine: 0.4 three times in a quadratic, 0.5 (a knot) twice more.
    c.refine_mut(&[0.4, 0.5, 0.4, 0.5, 0.4]).unwrap();
    assert_eq!(c.knots().multiplicity(0.4), 3);
    assert_eq!(c.knots().multiplicity(0.5), 3);
    assert!(max_gap(&c, &original) < 1e-14);
}

#[test]
fn nurbs_batch_matches_per_point_evaluation_and_checks_its_input() {
    // The unit circle from four quarter arcs (weights 1, 1/√2 at the corners).
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let corners = [
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (-1.0, 1.0),
        (-1.0, 0.0),
        (-1.0, -1.0),
        (0.0, -1.0),
        (1.0, -1.0),
        (1.0, 0.0),
    ];
    let points = corners.iter().map(|&(x, y)| Vector2::new(x, y)).collect();
    let weights = (0..9).map(|i| if i % 2 == 1 { h } else { 1.0 }).collect();
    let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0];
    let circle = NurbsCurve2::from_knots(2, knots, points, weights).unwrap();
    let mut params: Vec<f64> = samples(5000, 13).into_iter().map(|t| 4.0 * t).collect();
    params.extend([0.0, 1.0, 2.0, 3.0, 4.0]);
    let mut out = vec![Vector2::zeros(); params.len()];
    circle.eval_many_into(&params, &mut out).unwrap();
    for (p, &u) in out.iter().zip(&params) {
        assert!((p - circle.eval(u).unwrap()).amax() < 1e-15);
        assert!((p.norm() - 1.0).abs() < 1e-15);
    }
    assert_eq!(circle.eval_many(&params).unwrap(), out);
    let e = circle.eval_many_into(&params, &mut out[1..]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    let before = out.clone();
    let e = circle
        .eval_many_into(&[1.0, 4.5, 2.0], &mut out[..3])
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::OutOfDomain);
    assert_eq!(out, before, "nothing written on error");
}

#[test]
fn surface_kernels_agree_with_de_boor_and_the_general_derivatives() {
    for (p, q) in [
        (1, 1),
        (2, 2),
        (3, 3),
        (4, 4),
        (5, 5),
        (6, 6),
        (2, 3),
        (3, 1),
    ] {
        let (nu, nv) = (p + 4, q + 3);
        let ku = KnotVector::clamped_uniform(p, nu, 0.0, 1.0).unwrap();
        let kv = KnotVector::uniform(q, nv, -1.0, 2.0).unwrap();
        let zs = samples(3 * nu * nv, (p * 10 + q) as u64);
        let points = (0..nu * nv)
            .map(|k| Vector3::new(zs[3 * k], zs[3 * k + 1], zs[3 * k + 2]))
            .collect();
        let s = Surface::new(ku, kv, points).unwrap();
        let ((ua, ub), (va, vb)) = s.domain();
        let (us, vs) = (samples(60, 17), samples(60, 19));
        for (&a, &b) in us.iter().zip(&vs) {
            let (u, v) = (ua + (ub - ua) * a, va + (vb - va) * b);
            let point = s.eval(u, v).unwrap();
            assert!(
                (point - s.de_boor(u, v).unwrap()).amax() < 1e-13,
                "({p}, {q})"
            );
            let mut d = [Vector3::zeros(); 9];
            s.derivatives_into(u, v, 2, &mut d).unwrap();
            assert!((d[0] - point).amax() < 1e-13);
            for k in 0..=2 {
                for l in 0..=2 {
                    let single = s.derivative_at(u, v, k, l).unwrap();
                    let scale = single.amax().max(1.0);
                    assert!(
                        (d[3 * k + l] - single).amax() < 1e-12 * scale,
                        "({p}, {q}) ∂{k},{l}"
                    );
                }
            }
        }
    }
}

#[cfg(feature = "parallel")]
#[test]
fn parallel_batches_and_grids_equal_the_sequential_ones() {
    let c = curve(3, 60, true, 23);
    let params = samples(50_000, 29);
    let mut seq = vec![Vector2::zeros(); params.len()];
    let mut par = seq.clone();
    c.eval_many_into(&params, &mut seq).unwrap();
    c.par_eval_many_into(&params, &mut par).unwrap();
    assert_eq!(seq, par);
    let mut bad = params.clone();
    bad[30_000] = 1.5;
    assert_eq!(
        c.par_eval_many_into(&bad, &mut par).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    assert_eq!(
        c.par_eval_many_into(&params, &mut par[1..])
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidLength
    );
    let k = KnotVector::clamped_uniform(3, 12, 0.0, 1.0).unwrap();
    let zs = samples(144, 31);
    let s = Surface::new(
        k.clone(),
        k,
        zs.iter()
            .map(|&z| Vector3::new(z, 1.0 - z, z * z))
            .collect(),
    )
    .unwrap();
    let (us, vs) = (samples(300, 37), samples(70, 41));
    let mut g1 = vec![Vector3::zeros(); us.len() * vs.len()];
    let mut g2 = g1.clone();
    s.eval_grid_into(&us, &vs, &mut g1).unwrap();
    s.par_eval_grid_into(&us, &vs, &mut g2).unwrap();
    assert_eq!(g1, g2);
    assert_eq!(
        s.par_eval_grid_into(&us, &vs, &mut g2[1..])
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidLength
    );
}
