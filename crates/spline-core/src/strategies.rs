//! Proptest strategies for knot vectors and parameters, shared by the crates' tests.

use crate::KnotVector;
use proptest::prelude::*;
use std::collections::BTreeMap;

/// Random valid knot vectors of degree `0..=max_degree` with up to `extra` interior knots
/// (so `p + 1 ..= p + 1 + extra` basis functions) on `[0, 1]` times `scale`: clamped, or
/// unclamped with `p` extra knots outside each end; interior knots on a grid of `1/1000`,
/// repeated up to multiplicity `p` (or `p + 1` when `allow_discontinuity`).
///
/// # Panics
/// Never for `scale > 0`: the generated knots are valid by construction.
pub fn knot_vector(
    max_degree: usize,
    extra: usize,
    scale: f64,
    allow_discontinuity: bool,
) -> impl Strategy<Value = KnotVector<f64>> {
    (
        0..=max_degree,
        any::<bool>(),
        proptest::collection::vec((1u32..1000, 1usize..=4), 0..=extra),
    )
        .prop_map(move |(p, clamped, raw)| {
            let max_mult = if allow_discontinuity { p + 1 } else { p.max(1) };
            let mut distinct: BTreeMap<u32, usize> = BTreeMap::new();
            for (v, m) in raw {
                let e = distinct.entry(v).or_insert(0);
                *e = (*e).max(m.min(max_mult));
            }
            let mut interior: Vec<f64> = Vec::new();
            for (v, m) in distinct {
                interior.extend(std::iter::repeat_n(f64::from(v) / 1000.0, m));
            }
            interior.truncate(extra);
            let mut knots: Vec<f64> = Vec::with_capacity(interior.len() + 2 * p + 2);
            if clamped {
                knots.extend(std::iter::repeat_n(0.0, p + 1));
                knots.extend(&interior);
                knots.extend(std::iter::repeat_n(1.0, p + 1));
            } else {
                knots.extend((0..p).map(|j| -0.1 * (p - j) as f64));
                knots.push(0.0);
                knots.extend(&interior);
                knots.push(1.0);
                knots.extend((1..=p).map(|j| 1.0 + 0.1 * j as f64));
            }
            KnotVector::new(p, knots.into_iter().map(|k| k * scale).collect())
                .expect("strategy builds valid knot vectors")
        })
}

/// A parameter in the domain of `knots`, biased to hit knots and domain ends.
pub fn param_in(knots: &KnotVector<f64>) -> impl Strategy<Value = f64> + use<> {
    let (a, b) = knots.domain();
    let special: Vec<f64> = knots
        .knots()
        .iter()
        .copied()
        .filter(|&k| k >= a && k <= b)
        .collect();
    prop_oneof![
        3 => (0.0f64..=1.0).prop_map(move |t| a + (b - a) * t),
        1 => proptest::sample::select(special),
    ]
}
