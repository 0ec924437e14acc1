//! Basis functions checked against independent definitions: the divided-difference definition
//! of seed 004 §2.3, closed forms, dual numbers and finite differences.

use approx::assert_relative_eq;
use num_dual::Dual64;
use proptest::prelude::*;
use spline_core::{ErrorKind, KnotVector, bernstein, bernstein_all};
use spline_testing::strategies::knot_vector;

/// `(t)_+^e` with the right-continuous convention `(0)_+^0 = 1`.
fn truncated_power(t: f64, e: usize) -> f64 {
    if t < 0.0 {
        0.0
    } else if e == 0 {
        1.0
    } else {
        t.powi(e as i32)
    }
}

/// `d^j/du^j (x − u)_+^{m−1}`.
fn truncated_power_derivative(x: f64, u: f64, m: usize, j: usize) -> f64 {
    if j > m - 1 {
        return 0.0;
    }
    let falling: f64 = (0..j).map(|r| (m - 1 - r) as f64).product();
    let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
    sign * falling * truncated_power(x - u, m - 1 - j)
}

/// The generalised (Hermite) divided difference `[u_0, …, u_k] f` of `f(u) = (x − u)_+^{m−1}`
/// for sorted nodes, by the recurrence (2.4) and `f^{(k)}(u_0)/k!` for coincident nodes.
fn divided_difference(nodes: &[f64], x: f64, m: usize) -> f64 {
    let k = nodes.len() - 1;
    if nodes[0] == nodes[k] {
        let factorial: f64 = (1..=k).map(|r| r as f64).product();
        return truncated_power_derivative(x, nodes[0], m, k) / factorial;
    }
    (divided_difference(&nodes[1..], x, m) - divided_difference(&nodes[..k], x, m))
        / (nodes[k] - nodes[0])
}

/// The normalised B-spline of seed 004 (2.9) and (2.15): `N_i^m = (u_{i+m} − u_i) Q_i^m`,
/// `Q_i^m = (−1)^m [u_i … u_{i+m}] (x − u)_+^{m−1}`, order `m = p + 1`.
fn basis_by_divided_differences(knots: &[f64], degree: usize, i: usize, x: f64) -> f64 {
    let m = degree + 1;
    let nodes = &knots[i..=i + m];
    if nodes[0] == nodes[m] {
        return 0.0;
    }
    let sign = if m % 2 == 0 { 1.0 } else { -1.0 };
    (nodes[m] - nodes[0]) * sign * divided_difference(nodes, x, m)
}

/// Knot vectors on a dyadic grid (exact in binary) with repeated knots.
fn grid_knot_vector() -> impl Strategy<Value = KnotVector<f64>> {
    (
        0usize..=5,
        0usize..=6,
        any::<bool>(),
        proptest::collection::vec(1u32..16, 0..=6),
        proptest::collection::vec(1usize..=3, 0..=6),
    )
        .prop_filter_map("valid knots", |(p, extra, clamped, raw, mults)| {
            let mut interior: Vec<f64> = Vec::new();
            for (j, &r) in raw.iter().enumerate() {
                let m = mults.get(j).copied().unwrap_or(1).min(p.max(1));
                interior.extend(std::iter::repeat_n(f64::from(r) / 16.0, m));
            }
            interior.truncate(extra);
            interior.sort_by(f64::total_cmp);
            let mut knots = Vec::new();
            if clamped {
                knots.extend(std::iter::repeat_n(0.0, p + 1));
                knots.extend(&interior);
                knots.extend(std::iter::repeat_n(1.0, p + 1));
            } else {
                knots.extend((0..=p).map(|j| -((p - j) as f64) / 8.0));
                knots.extend(&interior);
                knots.extend((0..=p).map(|j| 1.0 + j as f64 / 8.0));
            }
            KnotVector::new(p, knots).ok()
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn cox_de_boor_matches_divided_differences(knots in grid_knot_vector(), t in 0.0f64..1.0, at_knot in any::<prop::sample::Index>(), use_knot in any::<bool>()) {
        let (a, b) = knots.domain();
        let inner: Vec<f64> = knots.knots().iter().copied().filter(|&k| k >= a && k < b).collect();
        let x = if use_knot { inner[at_knot.index(inner.len())] } else { a + (b - a) * t };
        let row = knots.dense_basis(x).unwrap();
        for (i, &value) in row.iter().enumerate() {
            let expected = basis_by_divided_differences(knots.knots(), knots.degree(), i, x);
            prop_assert!((value - expected).abs() < 1e-9, "N_{} ({}) = {} vs {} for {:?}", i, x, value, expected, knots.knots());
        }
    }

    #[test]
    fn partition_of_unity_and_non_negativity(knots in knot_vector(7, 8, 1.0, true), t in 0.0f64..=1.0) {
        let (a, b) = knots.domain();
        let u = a + (b - a) * t;
        let row = knots.dense_basis(u).unwrap();
        prop_assert!(row.iter().all(|&v| v >= 0.0));
        prop_assert!((row.iter().sum::<f64>() - 1.0).abs() < 1e-13);
    }

    #[test]
    fn scaled_knot_vectors_give_the_same_basis(knots in knot_vector(5, 6, 1.0, false), t in 0.0f64..=1.0, exponent in prop::sample::select(vec![-6i32, 6])) {
        let scale = 10f64.powi(exponent);
        let scaled = KnotVector::new(knots.degree(), knots.knots().iter().map(|k| k * scale).collect()).unwrap();
        let (a, b) = knots.domain();
        let u = a + (b - a) * t;
        let row = knots.dense_basis_derivatives(u, 2).unwrap();
        let scaled_row = scaled.dense_basis_derivatives(u * scale, 2).unwrap();
        for k in 0..=2 {
            // d/d(su) = (1/s) d/du.
            let factor = scale.powi(k as i32);
            for (x, y) in row[k].iter().zip(&scaled_row[k]) {
                let tol = 1e-9 * (1.0 + x.abs());
                prop_assert!((x - y * factor).abs() <= tol, "k={} {} vs {}", k, x, y * factor);
            }
        }
    }

    #[test]
    fn derivatives_match_dual_numbers(knots in knot_vector(6, 6, 1.0, false), t in 0.0f64..=1.0) {
        let (a, b) = knots.domain();
        let u = a + (b - a) * t;
        let span = knots.find_span(u).unwrap();
        let p = knots.degree();
        let mut table = vec![0.0; 2 * (p + 1)];
        knots.basis_derivatives(span, u, 1, &mut table);
        // The same basis in dual numbers, seeded with du = 1, in the same span.
        let dual = KnotVector::new(p, knots.knots().iter().map(|&k| Dual64::from(k)).collect()).unwrap();
        let mut values = vec![Dual64::from(0.0); p + 1];
        dual.basis_values(span, Dual64::from(u).derivative(), &mut values);
        for r in 0..=p {
            prop_assert!((values[r].re - table[r]).abs() < 1e-12);
            let d = table[p + 1 + r];
            prop_assert!((values[r].eps - d).abs() <= 1e-9 * (1.0 + d.abs()), "{} vs {}", values[r].eps, d);
        }
    }

    #[test]
    fn derivatives_match_finite_differences(knots in knot_vector(6, 6, 1.0, false), t in 0.05f64..0.95) {
        let (a, b) = knots.domain();
        let u = a + (b - a) * t;
        let span = knots.find_span(u).unwrap();
        let (lo, hi): (f64, f64) = (knots.knots()[span], knots.knots()[span + 1]);
        let h = 1e-6 * (hi - lo);
        prop_assume!(u - h > lo && u + h < hi);
        let p = knots.degree();
        let order = p.min(3);
        let mut table = vec![0.0; (order + 1) * (p + 1)];
        knots.basis_derivatives(span, u, order, &mut table);
        let mut lower = vec![0.0; (order + 1) * (p + 1)];
        let mut upper = vec![0.0; (order + 1) * (p + 1)];
        knots.basis_derivatives(span, u - h, order, &mut lower);
        knots.basis_derivatives(span, u + h, order, &mut upper);
        for k in 1..=order {
            for r in 0..=p {
                let fd = (upper[(k - 1) * (p + 1) + r] - lower[(k - 1) * (p + 1) + r]) / (2.0 * h);
                let exact = table[k * (p + 1) + r];
                let scale = table[(k - 1) * (p + 1)..k * (p + 1)].iter().fold(1.0f64, |m, x| m.max(x.abs())) / (hi - lo);
                prop_assert!((fd - exact).abs() <= 1e-5 * scale.max(exact.abs()), "k={} r={} fd={} exact={}", k, r, fd, exact);
            }
        }
    }

    #[test]
    fn f32_and_f64_agree(knots in knot_vector(5, 6, 1.0, false), t in 0.0f64..=1.0) {
        let single = KnotVector::new(knots.degree(), knots.knots().iter().map(|&k| k as f32).collect());
        prop_assume!(single.is_ok());
        let single = single.unwrap();
        let (a, b) = knots.domain();
        let u = a + (b - a) * t;
        let uf = u as f32;
        prop_assume!(single.find_span(uf).is_ok() && single.find_span(uf).unwrap() == knots.find_span(f64::from(uf)).unwrap());
        let row32 = single.dense_basis(uf).unwrap();
        let row64 = knots.dense_basis(f64::from(uf)).unwrap();
        for (x, y) in row32.iter().zip(&row64) {
            prop_assert!((f64::from(*x) - y).abs() < 1e-4, "{} vs {}", x, y);
        }
    }
}

#[test]
fn figure_1_of_seed_000() {
    // Degree 3, knots [0,0,0,0,1,2,3,3,3,3]: 6 basis functions (n = m − d − 1 = 5).
    let knots = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0]).unwrap();
    assert_eq!(knots.num_basis(), 6);
    let expect = |u: f64, values: [f64; 6]| {
        let row = knots.dense_basis(u).unwrap();
        for (i, (x, y)) in row.iter().zip(values).enumerate() {
            assert_relative_eq!(*x, y, epsilon = 1e-15);
            let dd = basis_by_divided_differences(knots.knots(), 3, i, u);
            if u < 3.0 {
                assert_relative_eq!(*x, dd, epsilon = 1e-12);
            }
        }
    };
    expect(0.0, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    expect(1.0, [0.0, 0.25, 7.0 / 12.0, 1.0 / 6.0, 0.0, 0.0]);
    expect(
        1.5,
        [0.0, 1.0 / 32.0, 15.0 / 32.0, 15.0 / 32.0, 1.0 / 32.0, 0.0],
    );
    expect(2.0, [0.0, 0.0, 1.0 / 6.0, 7.0 / 12.0, 0.25, 0.0]);
    expect(3.0, [0.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
    // N_0(u) = (1 − u)³ on [0, 1].
    let row = knots.dense_basis(0.5).unwrap();
    assert_relative_eq!(row[0], 0.125, epsilon = 1e-15);
}

#[test]
fn uniform_reference_values_of_seed_004() {
    // N^3(1) = N^3(2) = 1/2, N^4(1) = N^4(3) = 1/6, N^4(2) = 2/3 (orders 3 and 4 on integers).
    let quadratic = KnotVector::new(2, (0..8).map(f64::from).collect()).unwrap();
    // N_0 of order 3 lives on [0, 3]; sample it at 1 and 2 through N_2 on [2, 5] at 3 and 4.
    assert_relative_eq!(
        quadratic.basis_function(2, 3.0).unwrap(),
        0.5,
        epsilon = 1e-15
    );
    assert_relative_eq!(
        quadratic.basis_function(2, 4.0).unwrap(),
        0.5,
        epsilon = 1e-15
    );
    let cubic = KnotVector::new(3, (0..10).map(f64::from).collect()).unwrap();
    assert_relative_eq!(
        cubic.basis_function(3, 4.0).unwrap(),
        1.0 / 6.0,
        epsilon = 1e-15
    );
    assert_relative_eq!(
        cubic.basis_function(3, 5.0).unwrap(),
        2.0 / 3.0,
        epsilon = 1e-15
    );
    assert_relative_eq!(
        cubic.basis_function(3, 6.0).unwrap(),
        1.0 / 6.0,
        epsilon = 1e-15
    );
}

#[test]
fn derivatives_above_the_degree_are_zero() {
    let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]).unwrap();
    let rows = knots.dense_basis_derivatives(0.3, 5).unwrap();
    assert_eq!(rows.len(), 6);
    for row in &rows[3..] {
        assert!(row.iter().all(|&v| v == 0.0));
    }
    // Second derivatives of a quadratic are piecewise constant.
    assert_relative_eq!(rows[2].iter().sum::<f64>(), 0.0, epsilon = 1e-12);
}

#[test]
fn bernstein_polynomials() {
    let mut all = [0.0; 6];
    bernstein_all(5, 0.3, &mut all);
    assert_relative_eq!(all.iter().sum::<f64>(), 1.0, epsilon = 1e-15);
    let bezier = KnotVector::<f64>::bezier(5, 0.0, 1.0).unwrap();
    let row = bezier.dense_basis(0.3).unwrap();
    for i in 0..=5 {
        let closed =
            [1.0, 5.0, 10.0, 10.0, 5.0, 1.0][i] * 0.3f64.powi(i as i32) * 0.7f64.powi(5 - i as i32);
        assert_relative_eq!(all[i], closed, epsilon = 1e-15);
        assert_relative_eq!(bernstein(5, i, 0.3), closed, epsilon = 1e-15);
        assert_relative_eq!(row[i], closed, epsilon = 1e-15);
    }
}

#[test]
fn basis_errors() {
    let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).unwrap();
    assert_eq!(
        knots.eval_basis(1.5).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    assert_eq!(
        knots.eval_basis(-1e-300).unwrap_err().kind(),
        ErrorKind::OutOfDomain
    );
    assert_eq!(
        knots.eval_basis(f64::NAN).unwrap_err().kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(
        knots
            .dense_basis_derivatives(f64::INFINITY, 1)
            .unwrap_err()
            .kind(),
        ErrorKind::NonFinite
    );
    let e = knots.basis_function(3, 0.5).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::IndexOutOfRange);
    assert_eq!(e.index(), Some(3));
}

proptest! {
    #[test]
    fn batch_tables_agree_with_the_exact_routine(knots in knot_vector(5, 10, 1.0, true), ts in proptest::collection::vec(0.0f64..=1.0, 1..50)) {
        prop_assume!(knots.degree() >= 1);
        let batch = spline_core::BatchBasis::new(&knots);
        let (a, b) = knots.domain();
        let mut us: Vec<f64> = ts.iter().map(|t| a + (b - a) * t).collect();
        us.extend(knots.knots().iter().copied().filter(|&k| k >= a && k <= b));
        for u in us {
            let span = knots.find_span(u).unwrap();
            prop_assert_eq!(batch.span(&knots, u), span, "u = {}", u);
            let mut exact = vec![0.0; knots.degree() + 1];
            knots.basis_values(span, u, &mut exact);
            let values: Vec<f64> = match knots.degree() {
                1 => batch.eval_fixed::<2>(&knots, u).1.to_vec(),
                2 => batch.eval_fixed::<3>(&knots, u).1.to_vec(),
                3 => batch.eval_fixed::<4>(&knots, u).1.to_vec(),
                4 => batch.eval_fixed::<5>(&knots, u).1.to_vec(),
                _ => batch.eval_fixed::<6>(&knots, u).1.to_vec(),
            };
            for (x, y) in values.iter().zip(&exact) {
                prop_assert!((x - y).abs() < 1e-13, "{} vs {}", x, y);
            }
        }
    }
}
