//! Proptest strategies for knot vectors and parameters, shared by the crates' tests.

use crate::KnotVector;
use proptest::prelude::*;

/// Random valid knot vectors of degree `0..=max_degree` with `p + 1 ..= p + 1 + extra` basis
/// functions on `[0, 1]` (scaled by `scale`): clamped or unclamped, with repeated interior
/// knots (up to multiplicity `p`, or `p + 1` when `allow_discontinuity`).
pub fn knot_vector(
    max_degree: usize,
    extra: usize,
    scale: f64,
    allow_discontinuity: bool,
) -> impl Strategy<Value = KnotVector<f64>> {
    (
        0..=max_degree,
        0..=extra,
        any::<bool>(),
        proptest::collection::vec((0.0f64..1.0, 1usize..4), 0..=extra),
    )
        .prop_map(move |(p, extra, clamped, raw)| {
            let n = p + 1 + extra;
            let max_mult = if allow_discontinuity { p + 1 } else { p.max(1) };
            let interior_count = n - p - 1;
            let mut interior = Vec::new();
            for &(x, m) in raw.iter().cycle().take(raw.len().max(1) * 8) {
                if interior.len() >= interior_count {
                    break;
                }
                let x = (x * 1e6).round() / 1e6;
                if x <= 0.0 || x >= 1.0 {
                    continue;
                }
                let m = m.min(max_mult).min(interior_count - interior.len());
                interior.extend(std::iter::repeat_n(x, m));
            }
            let mut k = 1;
            while interior.len() < interior_count {
                interior.push(k as f64 / (interior_count + 1) as f64);
                k += 1;
            }
            interior.sort_by(f64::total_cmp);
            // Cap multiplicities that merged values may have created.
            let mut capped: Vec<f64> = Vec::new();
            for x in interior {
                let count = capped.iter().filter(|&&y| y == x).count();
                if count < max_mult {
                    capped.push(x);
                } else {
                    let mut y = x;
                    while capped.contains(&y) || y >= 1.0 {
                        y = (y + 1e-3).min(0.999_999);
                    }
                    capped.push(y);
                    capped.sort_by(f64::total_cmp);
                }
            }
            let knots: Vec<f64> = if clamped {
                let mut v = vec![0.0; p + 1];
                v.extend(&capped);
                v.extend(vec![1.0; p + 1]);
                v
            } else {
                // Unclamped: spread p knots below 0 and above 1.
                let mut v: Vec<f64> = (0..p).map(|j| -((p - j) as f64) * 0.1).collect();
                v.push(0.0);
                v.extend(&capped);
                v.push(1.0);
                v.extend((1..=p).map(|j| 1.0 + j as f64 * 0.1));
                v
            };
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
