//! The lanes against the scalar batch, bit for bit: random curves of degrees 1 to 5 in 1 to 4
//! coordinates (and homogeneous points, projected), clamped or not, with repeated knots, at
//! random parameters in random or sorted order, every knot of the domain, the floating-point
//! numbers on either side of each, and both ends of the domain.

use super::eval_many_map;
use crate::{BSpline, Homogeneous};
use nalgebra::SVector;
use proptest::prelude::*;
use spline_core::strategies::knot_vector;
use spline_core::{ControlPoint, KnotVector};

/// The floating-point number next to `x` below (`-1`) or above (`1`).
fn beside(x: f64, side: i64) -> f64 {
    if x == 0.0 {
        return f64::from_bits(1).copysign(side as f64);
    }
    let step = if x > 0.0 { side } else { -side };
    f64::from_bits(x.to_bits().wrapping_add_signed(step))
}

/// Random parameters mapped to the domain, then every knot in it with its neighbours and
/// both ends; sorted when asked.
fn params(knots: &KnotVector<f64>, ts: &[f64], sorted: bool) -> Vec<f64> {
    let (a, b) = knots.domain();
    let mut us: Vec<f64> = ts.iter().map(|t| a + (b - a) * t).collect();
    for &k in knots.knots() {
        us.extend(
            [beside(k, -1), k, beside(k, 1)]
                .into_iter()
                .filter(|&u| u >= a && u <= b),
        );
    }
    us.extend([a, b, a, beside(b, -1)]);
    if sorted {
        us.sort_by(f64::total_cmp);
    }
    us
}

/// The batch through the lanes and through the scalar path, `map` applied; `None` where the
/// curve has no cached form. The second value says whether the lanes applied.
fn both<P: ControlPoint<f64>, Q: Copy>(
    curve: &BSpline<f64, P>,
    us: &[f64],
    map: impl Fn(P) -> Q,
) -> Option<(Vec<Q>, Vec<Q>, bool)> {
    let pieces = curve.cached_pieces()?;
    let exact = |u: f64| curve.eval_in_span(curve.knots().span_in_domain(u), u);
    let fill = map(curve.control_points()[0]);
    let mut lanes = vec![fill; us.len()];
    let active = eval_many_map(pieces.lanes(), us, &mut lanes, &map, &exact);
    assert_eq!(active, pieces.lanes().is_active());
    let mut scalar = vec![fill; us.len()];
    pieces.eval_many_scalar(curve.knots(), us, &mut scalar, &map, exact);
    if !active {
        lanes.clone_from(&scalar);
    }
    Some((lanes, scalar, active))
}

/// Control points from a seed, with values of every sign and size up to `size`.
fn points<P: ControlPoint<f64>>(knots: &KnotVector<f64>, seed: f64, size: f64) -> Vec<P> {
    (0..knots.num_basis())
        .map(|i| {
            P::from_coords(|d| {
                let x = i as f64 + seed + 0.37 * d as f64;
                size * (1.7 * x).sin() * (0.3 * x + d as f64).cos()
            })
        })
        .collect()
}

fn same_bits<const W: usize>(a: &[SVector<f64, W>], b: &[SVector<f64, W>], us: &[f64]) {
    for ((p, q), u) in a.iter().zip(b).zip(us) {
        for (x, y) in p.iter().zip(q.iter()) {
            assert_eq!(x.to_bits(), y.to_bits(), "at u = {u:e}: {p:?} vs {q:?}");
        }
    }
}

fn check_points<const D: usize>(knots: &KnotVector<f64>, seed: f64, size: f64, us: &[f64]) {
    let curve =
        BSpline::<f64, SVector<f64, D>>::new(knots.clone(), points(knots, seed, size)).unwrap();
    if let Some((lanes, scalar, _)) = both(&curve, us, |p| p) {
        same_bits(&lanes, &scalar, us);
    }
}

fn check_functions(knots: &KnotVector<f64>, seed: f64, size: f64, us: &[f64]) {
    let curve = BSpline::<f64, f64>::new(knots.clone(), points(knots, seed, size)).unwrap();
    if let Some((lanes, scalar, _)) = both(&curve, us, SVector::<f64, 1>::new) {
        same_bits(&lanes, &scalar, us);
    }
}

/// Homogeneous points with positive weights, projected (the NURBS batch).
fn check_rational<const D: usize>(knots: &KnotVector<f64>, seed: f64, us: &[f64]) {
    let hom: Vec<Homogeneous<f64, D>> = points::<SVector<f64, D>>(knots, seed, 3.0)
        .into_iter()
        .enumerate()
        .map(|(i, p)| {
            let w = 0.5 + (i as f64 * 0.71 + seed).sin().abs();
            Homogeneous::new(p * w, w)
        })
        .collect();
    let curve = BSpline::new(knots.clone(), hom).unwrap();
    if let Some((lanes, scalar, _)) = both(&curve, us, |h| h.project()) {
        same_bits(&lanes, &scalar, us);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn lanes_equal_the_scalar_batch_bit_for_bit(
        knots in knot_vector(5, 30, 1.0, true),
        shift in prop_oneof![Just(0.0), Just(-7.5), Just(1.0e6)],
        stretch in prop_oneof![Just(1.0), Just(1.0e-3), Just(250.0)],
        seed in 0.0f64..10.0,
        size in prop_oneof![Just(1.0), Just(1.0e-6), Just(1.0e5)],
        ts in proptest::collection::vec(0.0f64..=1.0, 0..80),
        sorted in any::<bool>(),
    ) {
        prop_assume!(knots.degree() >= 1);
        let knots = KnotVector::new(
            knots.degree(),
            knots.knots().iter().map(|k| shift + stretch * k).collect(),
        ).unwrap();
        let us = params(&knots, &ts, sorted);
        check_functions(&knots, seed, size, &us);
        check_points::<1>(&knots, seed, size, &us);
        check_points::<2>(&knots, seed, size, &us);
        check_points::<3>(&knots, seed, size, &us);
        check_points::<4>(&knots, seed, size, &us);
        check_rational::<2>(&knots, seed, &us);
        check_rational::<3>(&knots, seed, &us);
    }
}

/// The lanes apply to the curves of the benchmarks (uniform and non-uniform knots, every
/// dimension up to 4, homogeneous points), and the gate refuses what it must: a bucket
/// with several distinct knots, five coordinates, `f32`.
#[test]
fn lanes_apply_where_they_should() {
    let uniform = KnotVector::clamped_uniform(3, 100, 0.0, 1.0).unwrap();
    let us: Vec<f64> = (0..1000).map(|i| f64::from(i) / 999.0).collect();
    let active = |knots: &KnotVector<f64>, dim: usize| -> bool {
        fn of<const D: usize>(knots: &KnotVector<f64>, us: &[f64]) -> bool {
            let curve =
                BSpline::<f64, SVector<f64, D>>::new(knots.clone(), points(knots, 0.2, 1.0))
                    .unwrap();
            both(&curve, us, |p| p).unwrap().2
        }
        match dim {
            1 => {
                both(
                    &BSpline::<f64, f64>::new(knots.clone(), points(knots, 0.2, 1.0)).unwrap(),
                    &us,
                    |x| x,
                )
                .unwrap()
                .2
            }
            2 => of::<2>(knots, &us),
            3 => of::<3>(knots, &us),
            4 => of::<4>(knots, &us),
            _ => of::<5>(knots, &us),
        }
    };
    for dim in 1..=4 {
        assert!(active(&uniform, dim), "dimension {dim}");
    }
    assert!(!active(&uniform, 5));
    let graded = KnotVector::new(
        2,
        [
            0.0, 0.0, 0.0, 0.01, 0.04, 0.09, 0.16, 0.25, 0.36, 0.49, 0.64, 0.81, 1.0, 1.0, 1.0,
        ]
        .to_vec(),
    )
    .unwrap();
    assert!(active(&graded, 2));
    // 0.5 and 0.5001 share a bucket: the scalar path walks them.
    let clustered =
        KnotVector::new(2, [0.0, 0.0, 0.0, 0.5, 0.5001, 1.0, 1.0, 1.0].to_vec()).unwrap();
    assert!(!active(&clustered, 2));
    let single = BSpline::<f32, SVector<f32, 2>>::new(
        KnotVector::clamped_uniform(3, 100, 0.0f32, 1.0).unwrap(),
        vec![SVector::<f32, 2>::new(0.5, -1.0); 100],
    )
    .unwrap();
    assert!(!single.cached_pieces().unwrap().lanes().is_active());
}
