//! `SpanTable` against the binary search of `KnotVector::find_span`: every parameter kind —
//! random, knots, the ends, the floating-point neighbours of knots — on random knot vectors
//! (clamped and unclamped, repeated knots, one span, many spans, clustered knots, any
//! scale and offset).

use proptest::prelude::*;
use spline_core::strategies::knot_vector;
use spline_core::{KnotVector, SpanTable};

/// The floating-point numbers just below and just above `x` (finite `x`).
fn neighbours(x: f64) -> [f64; 2] {
    if x == 0.0 {
        let tiny = f64::from_bits(1);
        return [-tiny, tiny];
    }
    let (smaller, larger) = (
        f64::from_bits(x.to_bits() - 1),
        f64::from_bits(x.to_bits() + 1),
    );
    if x > 0.0 {
        [smaller, larger]
    } else {
        [larger, smaller]
    }
}

/// Every knot in the domain, its two floating-point neighbours, and `ts` mapped to it.
fn probes(knots: &KnotVector<f64>, ts: &[f64]) -> Vec<f64> {
    let (a, b) = knots.domain();
    let mut us: Vec<f64> = ts.iter().map(|t| a + (b - a) * t).collect();
    for &k in knots.knots() {
        let [below, above] = neighbours(k);
        for u in [k, below, above] {
            if u >= a && u <= b {
                us.push(u);
            }
        }
    }
    us
}

fn check(knots: &KnotVector<f64>, ts: &[f64]) -> Result<(), TestCaseError> {
    let table = SpanTable::new(knots);
    for u in probes(knots, ts) {
        prop_assert_eq!(
            table.span(knots, u),
            knots.find_span(u).unwrap(),
            "u = {:e}, knots {:?}",
            u,
            knots.knots()
        );
    }
    Ok(())
}

/// Random knots (not on a grid): sorted uniform numbers on `[offset, offset + width]`,
/// a few of them repeated.
fn random_knots() -> impl Strategy<Value = KnotVector<f64>> {
    (
        0usize..=5,
        proptest::collection::vec((0.0f64..1.0, 1usize..=3), 0..40),
        -1e3f64..1e3,
        prop_oneof![Just(1e-6), Just(1.0), Just(1e5)],
        any::<bool>(),
    )
        .prop_filter_map("a valid knot vector", |(p, raw, offset, width, clamped)| {
            let mut interior: Vec<f64> = Vec::new();
            for (x, m) in raw {
                interior.extend(std::iter::repeat_n(offset + width * x, m.min(p.max(1))));
            }
            interior.sort_by(f64::total_cmp);
            let mut knots = Vec::new();
            if clamped {
                knots.extend(std::iter::repeat_n(offset - width * 0.01, p + 1));
                knots.extend(&interior);
                knots.extend(std::iter::repeat_n(offset + width * 1.01, p + 1));
            } else {
                knots.extend((0..=p).map(|j| offset - width * 0.01 * (p + 1 - j) as f64));
                knots.extend(&interior);
                knots.extend((0..=p).map(|j| offset + width * (1.01 + 0.01 * j as f64)));
            }
            KnotVector::new(p, knots).ok()
        })
}

proptest! {
    #[test]
    fn grid_knots(knots in knot_vector(5, 30, 1.0, true), ts in proptest::collection::vec(0.0f64..=1.0, 0..40)) {
        check(&knots, &ts)?;
    }

    #[test]
    fn scaled_grid_knots(knots in knot_vector(4, 20, 37.3, true), ts in proptest::collection::vec(0.0f64..=1.0, 0..40)) {
        check(&knots, &ts)?;
    }

    #[test]
    fn random_knots_any_offset_and_width(knots in random_knots(), ts in proptest::collection::vec(0.0f64..=1.0, 0..40)) {
        check(&knots, &ts)?;
    }
}

#[test]
fn one_span_many_spans_and_clusters() {
    let ts: Vec<f64> = (0..=1000).map(|i| f64::from(i) / 1000.0).collect();
    for p in 0..=5 {
        // One span.
        check(
            &KnotVector::clamped_uniform(p, p + 1, 0.0, 1.0).unwrap(),
            &ts,
        )
        .unwrap();
        // Many spans, uniform (knots on bucket edges) and unclamped.
        check(
            &KnotVector::clamped_uniform(p, 5000, -3.0, 7.0).unwrap(),
            &ts,
        )
        .unwrap();
        check(&KnotVector::uniform(p, 777, 0.1, 0.2).unwrap(), &ts).unwrap();
    }
    // Clustered knots: many in one bucket, then a long empty stretch.
    let mut knots = vec![0.0; 4];
    knots.extend((1..200).map(|i| 0.5 + f64::from(i) * 1e-9));
    knots.extend([0.75, 0.75, 0.75]);
    knots.extend(vec![1.0; 4]);
    let clustered = KnotVector::new(3, knots).unwrap();
    let mut us = ts.clone();
    us.extend((0..400).map(|i| 0.5 + f64::from(i) * 0.5e-9));
    check(&clustered, &us).unwrap();
    // A discontinuity (multiplicity p + 1) inside an unclamped vector.
    let jump = KnotVector::new(2, vec![-0.2, -0.1, 0.0, 0.4, 0.4, 0.4, 1.0, 1.1, 1.2]).unwrap();
    check(&jump, &ts).unwrap();
}
