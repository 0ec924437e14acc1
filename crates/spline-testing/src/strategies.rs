//! Proptest strategies for spline spaces and splines, which shrink towards few knots, low
//! degrees and simple values. The knot-vector strategies of spline-core
//! ([`knot_vector`], [`param_in`]) are re-exported.

use nalgebra::{SVector, Vector2};
use proptest::collection::vec;
use proptest::prelude::*;
use spline_core::KnotVector;
pub use spline_core::strategies::{knot_vector, param_in};
use spline_geom::BSpline;

/// A pool of breakpoints in `(0, 1)`: the coarse grid `k/8`, up to four random values on a
/// grid of `1e-6`, and a pair only `1e-4` apart (close knots stress every algorithm).
pub fn pool() -> impl Strategy<Value = Vec<f64>> {
    (vec(10_000u32..990_000, 0..=4), 50_000u32..950_000).prop_map(|(random, near)| {
        let mut pool: Vec<f64> = (1..8).map(|k| f64::from(k) / 8.0).collect();
        pool.extend(random.into_iter().map(|x| f64::from(x) / 1e6));
        let near = f64::from(near) / 1e6;
        pool.push(near);
        pool.push(near + 1e-4);
        pool.sort_by(f64::total_cmp);
        pool.dedup();
        pool
    })
}

/// A knot vector of degree `p` on `[0, 1]` whose interior knots are drawn from `pool`, with
/// multiplicities up to `p + 1` (`discontinuous`) or `p`, clamped or with knots outside
/// the domain.
pub fn knots_from(
    pool: &[f64],
    p: usize,
    discontinuous: bool,
) -> impl Strategy<Value = KnotVector<f64>> + use<> {
    let pool = pool.to_vec();
    let max_mult = if discontinuous { p + 1 } else { p.max(1) };
    (vec(0..=max_mult, pool.len()), proptest::bool::weighted(0.6)).prop_map(
        move |(mults, clamped)| {
            let mut knots = Vec::new();
            if clamped {
                knots.extend(std::iter::repeat_n(0.0, p + 1));
            } else {
                knots.extend((1..=p).rev().map(|j| -0.13 * j as f64));
                knots.push(0.0);
            }
            for (&x, &m) in pool.iter().zip(&mults) {
                knots.extend(std::iter::repeat_n(x, m));
            }
            if clamped {
                knots.extend(std::iter::repeat_n(1.0, p + 1));
            } else {
                knots.push(1.0);
                knots.extend((1..=p).map(|j| 1.0 + 0.11 * j as f64));
            }
            KnotVector::new(p, knots).expect("valid knots by construction")
        },
    )
}

/// A B-spline function on `knots` with coefficients in `[−1, 1]`.
pub fn function_on(knots: KnotVector<f64>) -> impl Strategy<Value = BSpline<f64, f64>> {
    vec(-1.0f64..=1.0, knots.num_basis())
        .prop_map(move |c| BSpline::new(knots.clone(), c).expect("as many values as functions"))
}

/// A planar B-spline curve on `knots` with control points in `[−1, 1]²`.
pub fn planar_curve_on(
    knots: KnotVector<f64>,
) -> impl Strategy<Value = BSpline<f64, Vector2<f64>>> {
    points::<2>(knots.num_basis())
        .prop_map(move |c| BSpline::new(knots.clone(), c).expect("as many points as functions"))
}

/// `n` points in `[−1, 1]^D`.
pub fn points<const D: usize>(n: usize) -> impl Strategy<Value = Vec<SVector<f64, D>>> {
    vec(vec(-1.0f64..=1.0, D), n)
        .prop_map(|rows| rows.iter().map(|r| SVector::from_column_slice(r)).collect())
}

/// Two knot vectors of degrees up to `max_p` and `max_q` whose knots come from one pool (so
/// that they share some breakpoints and not others), each possibly discontinuous, with the
/// pool.
pub fn two_spaces(
    max_p: usize,
    max_q: usize,
) -> impl Strategy<Value = (Vec<f64>, KnotVector<f64>, KnotVector<f64>)> {
    (
        pool(),
        0..=max_p,
        0..=max_q,
        proptest::bool::weighted(0.3),
        proptest::bool::weighted(0.3),
    )
        .prop_flat_map(|(pool, p, q, da, db)| {
            (
                Just(pool.clone()),
                knots_from(&pool, p, da),
                knots_from(&pool, q, db),
            )
        })
}

/// Two B-spline functions on [`two_spaces`], with the pool of their knots.
pub fn functions_on_a_pool(
    max_p: usize,
    max_q: usize,
) -> impl Strategy<Value = (Vec<f64>, BSpline<f64, f64>, BSpline<f64, f64>)> {
    two_spaces(max_p, max_q)
        .prop_flat_map(|(pool, ka, kb)| (Just(pool), function_on(ka), function_on(kb)))
}

/// Two B-spline functions on [`two_spaces`].
pub fn two_functions(
    max_p: usize,
    max_q: usize,
) -> impl Strategy<Value = (BSpline<f64, f64>, BSpline<f64, f64>)> {
    functions_on_a_pool(max_p, max_q).prop_map(|(_, a, b)| (a, b))
}

/// Two continuous planar curves of degrees `1..=max_p` and `1..=max_q` on knots from one
/// pool.
pub fn two_planar_curves(
    max_p: usize,
    max_q: usize,
) -> impl Strategy<Value = (BSpline<f64, Vector2<f64>>, BSpline<f64, Vector2<f64>>)> {
    (pool(), 1..=max_p, 1..=max_q)
        .prop_flat_map(|(pool, p, q)| (knots_from(&pool, p, false), knots_from(&pool, q, false)))
        .prop_flat_map(|(ka, kb)| (planar_curve_on(ka), planar_curve_on(kb)))
}

/// A continuous planar curve of degree `min_p..=max_p` on knots from a [`pool`] (or from
/// the grid of eighths only, without nearly coincident knots, when `regular`).
pub fn planar_curve(
    min_p: usize,
    max_p: usize,
    regular: bool,
) -> impl Strategy<Value = BSpline<f64, Vector2<f64>>> {
    (pool(), min_p..=max_p)
        .prop_flat_map(move |(pool, p)| {
            let pool = if regular {
                (1..8).map(|k| f64::from(k) / 8.0).collect()
            } else {
                pool
            };
            knots_from(&pool, p, false)
        })
        .prop_flat_map(planar_curve_on)
}

/// One B-spline function of degree `min_p..=max_p` on knots from a [`pool`].
pub fn function(
    min_p: usize,
    max_p: usize,
    discontinuous: bool,
) -> impl Strategy<Value = BSpline<f64, f64>> {
    (pool(), min_p..=max_p)
        .prop_flat_map(move |(pool, p)| knots_from(&pool, p, discontinuous))
        .prop_flat_map(function_on)
}

/// Parameters in the domain of `knots` from unit `samples` (values in `[0, 1)`), plus every
/// knot in the domain, points `1e-9` beside each, and both ends: the places where
/// algorithms break.
#[must_use]
pub fn parameters(knots: &KnotVector<f64>, samples: &[f64]) -> Vec<f64> {
    let (a, b) = knots.domain();
    let mut out: Vec<f64> = samples.iter().map(|t| a + (b - a) * t).collect();
    for &k in knots.knots() {
        if k >= a && k <= b {
            out.push(k);
            out.push((k - 1e-9).max(a));
            out.push((k + 1e-9).min(b));
        }
    }
    out.push(a);
    out.push(b);
    out
}

/// A curve in space on a knot vector of [`knot_vector`] (degree up to `max_degree`, up to
/// `extra` interior knots on `[0, 1]`, clamped or not, possibly discontinuous), control
/// points in `[−1, 1]³`.
pub fn spatial_curve(
    max_degree: usize,
    extra: usize,
    discontinuous: bool,
) -> impl Strategy<Value = BSpline<f64, nalgebra::Vector3<f64>>> {
    knot_vector(max_degree, extra, 1.0, discontinuous).prop_flat_map(|knots| {
        points::<3>(knots.num_basis())
            .prop_map(move |c| BSpline::new(knots.clone(), c).expect("as many points as functions"))
    })
}

/// `n + 1` equally spaced parameters from `a` to `b`, both ends exact (dense sampling).
#[must_use]
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n)
        .map(|i| {
            if i == n {
                b
            } else {
                a + (b - a) * i as f64 / n as f64
            }
        })
        .collect()
}
