//! Knot-vector validation, span search conventions and generators.

use proptest::prelude::*;
use spline_core::{ErrorKind, KnotVector, MAX_DEGREE};

fn kv(p: usize, knots: &[f64]) -> KnotVector<f64> {
    KnotVector::new(p, knots.to_vec()).unwrap()
}

#[test]
fn validation_errors_name_the_problem() {
    let err = |p: usize, knots: Vec<f64>| KnotVector::new(p, knots).unwrap_err();
    let e = err(1, vec![0.0, 0.0, f64::NAN, 1.0, 1.0]);
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    assert!(e.message().contains("knot 2"), "{e}");
    assert_eq!(
        err(1, vec![0.0, 0.0, f64::INFINITY, 1.0]).kind(),
        ErrorKind::NonFinite
    );
    let e = err(1, vec![0.0, 0.0, 0.7, 0.5, 1.0, 1.0]);
    assert_eq!(e.kind(), ErrorKind::UnsortedKnots);
    assert!(e.message().contains("knot 3"), "{e}");
    let e = err(2, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
    assert_eq!(
        err(1, vec![0.0, 0.5, 0.5, 0.5, 1.0, 1.0]).kind(),
        ErrorKind::KnotMultiplicity
    );
    assert_eq!(
        err(3, vec![0.0, 0.0, 1.0, 1.0]).kind(),
        ErrorKind::InvalidLength
    );
    assert_eq!(err(0, vec![0.0]).kind(), ErrorKind::InvalidLength);
    assert_eq!(
        err(1, vec![0.0, 1.0, 1.0, 2.0]).kind(),
        ErrorKind::EmptyDomain
    );
    assert_eq!(
        err(MAX_DEGREE + 1, vec![0.0; 80]).kind(),
        ErrorKind::DegreeTooHigh
    );
}

#[test]
fn span_conventions() {
    // Right limits at interior knots, left limit at the last knot of the domain.
    let k = kv(2, &[0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]);
    assert_eq!(k.find_span(0.0).unwrap(), 2);
    assert_eq!(k.find_span(0.25).unwrap(), 2);
    assert_eq!(k.find_span(0.5).unwrap(), 4);
    assert_eq!(k.find_span(0.75).unwrap(), 4);
    assert_eq!(k.find_span(1.0).unwrap(), 4);
    // Unclamped: domain [u_p, u_n].
    let u = kv(2, &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert_eq!(u.domain(), (2.0, 4.0));
    assert_eq!(u.find_span(2.0).unwrap(), 2);
    assert_eq!(u.find_span(3.0).unwrap(), 3);
    assert_eq!(u.find_span(4.0).unwrap(), 3);
    assert_eq!(
        u.find_span(1.999).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    assert_eq!(
        u.find_span(4.001).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    // Unclamped with repeated knots at the domain ends.
    let r = kv(2, &[0.0, 1.0, 1.0, 2.0, 3.0, 3.0, 4.0]);
    assert_eq!(r.domain(), (1.0, 3.0));
    assert_eq!(r.find_span(1.0).unwrap(), 2);
    assert_eq!(r.find_span(3.0).unwrap(), 3);
}

#[test]
fn sorted_fast_path_agrees_with_bisection() {
    let k = kv(
        3,
        &[
            0.0, 0.0, 0.0, 0.0, 0.1, 0.1, 0.2, 0.5, 0.7, 0.7, 0.7, 1.0, 1.0, 1.0, 1.0,
        ],
    );
    let mut span = 3;
    for i in 0..=1000 {
        let u = f64::from(i) / 1000.0;
        span = k.span_in_domain_from(u, span);
        assert_eq!(span, k.find_span(u).unwrap(), "u = {u}");
    }
    // Out-of-order hints fall back to bisection.
    assert_eq!(k.span_in_domain_from(0.05, 10), k.find_span(0.05).unwrap());
}

#[test]
fn multiplicities_breakpoints_and_greville() {
    let k = kv(3, &[0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 3.0, 3.0, 3.0, 3.0]);
    assert_eq!(k.multiplicity(2.0), 2);
    assert_eq!(k.multiplicity(1.5), 0);
    assert_eq!(
        k.breakpoints(),
        vec![(0.0, 4), (1.0, 1), (2.0, 2), (3.0, 4)]
    );
    assert_eq!(k.interior_breakpoints(), vec![(1.0, 1), (2.0, 2)]);
    assert_eq!(
        k.greville(),
        vec![0.0, 1.0 / 3.0, 1.0, 5.0 / 3.0, 7.0 / 3.0, 8.0 / 3.0, 3.0]
    );
    assert!(k.is_clamped());
    assert!(!kv(1, &[0.0, 1.0, 2.0, 3.0]).is_clamped());
}

#[test]
fn generators() {
    let k = KnotVector::clamped_uniform(3, 6, 0.0, 3.0).unwrap();
    assert_eq!(
        k.knots(),
        &[0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0]
    );
    let u = KnotVector::uniform(2, 5, 0.0, 3.0).unwrap();
    assert_eq!(u.domain(), (0.0, 3.0));
    assert_eq!(u.knots(), &[-2.0, -1.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
    let avg = KnotVector::averaging(3, &[0.0, 0.1, 0.3, 0.6, 0.8, 1.0]).unwrap();
    let expected: [f64; 10] = [
        0.0,
        0.0,
        0.0,
        0.0,
        (0.1 + 0.3 + 0.6) / 3.0,
        (0.3 + 0.6 + 0.8) / 3.0,
        1.0,
        1.0,
        1.0,
        1.0,
    ];
    for (a, b) in avg.knots().iter().zip(expected) {
        assert!((a - b).abs() < 1e-15);
    }
    assert_eq!(
        KnotVector::averaging(3, &[0.0, 0.5, 1.0])
            .unwrap_err()
            .kind(),
        ErrorKind::TooFewPoints
    );
    assert_eq!(
        KnotVector::averaging(1, &[0.0, 0.5, 0.2])
            .unwrap_err()
            .kind(),
        ErrorKind::UnsortedKnots
    );
    assert_eq!(
        KnotVector::clamped_uniform(2, 4, 1.0, 1.0)
            .unwrap_err()
            .kind(),
        ErrorKind::EmptyDomain
    );
    let e = KnotVector::clamped(1, 0.0, 1.0, &[0.5, 1.5]).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(
        e.to_string(),
        "interior knot 1.5 is not strictly inside (0, 1)"
    );
    assert_eq!(
        (e.index(), e.value(), e.interval()),
        (Some(1), Some(1.5), Some((0.0, 1.0)))
    );
    let bez = KnotVector::<f64>::bezier(2, -1.0, 1.0).unwrap();
    assert_eq!(bez.knots(), &[-1.0, -1.0, -1.0, 1.0, 1.0, 1.0]);
}

#[test]
fn insertion_merge_elevation_reversal() {
    let k = kv(2, &[0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]);
    assert_eq!(
        k.with_inserted(0.5, 2).unwrap().knots(),
        &[0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0]
    );
    assert_eq!(
        k.with_inserted(0.5, 3).unwrap_err().kind(),
        ErrorKind::KnotMultiplicity
    );
    assert_eq!(
        k.with_inserted(2.0, 1).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    let other = kv(2, &[0.0, 0.0, 0.0, 0.25, 0.5, 0.5, 1.0, 1.0, 1.0]);
    assert_eq!(k.merged(&other).unwrap().knots(), other.knots());
    assert_eq!(k.elevated(2).unwrap().knots().len(), 7 + 2 * 3);
    assert_eq!(k.elevated(2).unwrap().degree(), 4);
    let r = kv(1, &[0.0, 0.0, 0.2, 1.0, 1.0]).reversed();
    assert_eq!(r.knots(), &[0.0, 0.0, 0.8, 1.0, 1.0]);
    let m = kv(1, &[0.0, 0.0, 0.2, 1.0, 1.0])
        .reparametrized(10.0, 20.0)
        .unwrap();
    assert_eq!(m.knots(), &[10.0, 10.0, 12.0, 20.0, 20.0]);
    assert_eq!(
        k.derivative_knots().unwrap().knots(),
        &[0.0, 0.0, 0.5, 1.0, 1.0]
    );
}

proptest::proptest! {
    /// `check_refinement` (with its fast path for distinct knots) against counting the
    /// multiplicities of the merged knot vector directly.
    #[test]
    fn refinement_check_agrees_with_counting(
        knots in spline_core::strategies::knot_vector(4, 12, 1.0, true),
        picks in proptest::collection::vec((0usize..40, proptest::bool::ANY, 0.0f64..1.0), 0..12),
    ) {
        let (a, b) = knots.domain();
        let existing: Vec<f64> = knots.knots().iter().copied().filter(|&k| k >= a && k <= b).collect();
        let mut new: Vec<f64> = picks
            .iter()
            .map(|&(i, reuse, t)| if reuse { existing[i % existing.len()] } else { a + (b - a) * t })
            .collect();
        new.sort_by(f64::total_cmp);
        let mut merged: Vec<f64> = knots.knots().iter().chain(&new).copied().collect();
        merged.sort_by(f64::total_cmp);
        let too_many = merged
            .chunk_by(|x, y| x == y)
            .any(|run| run.len() > knots.degree() + 1);
        let result = knots.check_refinement(&new);
        proptest::prop_assert_eq!(result.is_err(), too_many, "new {:?} into {:?}", new, knots.knots());
        if let Err(e) = result {
            proptest::prop_assert_eq!(e.kind(), ErrorKind::KnotMultiplicity);
        }
    }
}

proptest! {
    /// `insertion_span` (one search, multiplicity counted next to the span) against the
    /// definitions: the multiplicity by two binary searches over the whole vector, the span
    /// by `span_in_domain`.
    #[test]
    fn insertion_span_agrees_with_multiplicity_and_span(
        knots in spline_core::strategies::knot_vector(4, 12, 1.0, true),
        pick in 0usize..64,
        t in 0.0f64..=1.0,
        times in 1usize..=5,
    ) {
        let (a, b) = knots.domain();
        let candidates: Vec<f64> = knots.knots().iter().copied().chain([a + (b - a) * t, a - 1.0, b + 1.0]).collect();
        let u = candidates[pick % candidates.len()];
        let allowed = u >= a && u <= b && knots.multiplicity(u) + times <= knots.degree() + 1;
        match knots.insertion_span(u, times) {
            Ok(span) => {
                prop_assert!(allowed, "u {} times {} accepted", u, times);
                prop_assert_eq!(span, knots.span_in_domain(u));
            }
            Err(_) => prop_assert!(!allowed, "u {} times {} refused", u, times),
        }
        prop_assert_eq!(knots.check_insertion(u, times).is_ok(), allowed);
    }
}
