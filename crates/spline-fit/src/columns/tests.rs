//! Against scipy 1.17: `reference.py --rust reference_values.rs` wrote the constants (one
//! per section of the script, named after it).

#[allow(dead_code)]
#[path = "reference_values.rs"]
mod reference_values;

use super::*;
use crate::lsq::LsqMethod;
use reference_values as r;
use spline_geom::Extrapolate;

fn close(got: &[f64], want: &[f64], tol: f64) {
    assert_eq!(got.len(), want.len(), "lengths differ: {got:?} vs {want:?}");
    for (i, (&g, &w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= tol * (1.0 + w.abs()),
            "entry {i}: {g} vs {w} (got {got:?})"
        );
    }
}

const XI: [f64; 9] = [0.0, 0.4, 1.0, 1.7, 2.1, 3.0, 3.6, 4.5, 5.0];

/// `yi = [sin x, cos x + x]` of the script.
fn yi() -> Vec<f64> {
    XI.iter().flat_map(|&x| [x.sin(), x.cos() + x]).collect()
}

/// `yp = [sin(2πx/5), cos(2πx/5)]` with the last row equal to the first.
fn yp() -> Vec<f64> {
    let mut y: Vec<f64> = XI
        .iter()
        .flat_map(|&x| {
            let a = x * 2.0 * std::f64::consts::PI / 5.0;
            [a.sin(), a.cos()]
        })
        .collect();
    let n = y.len();
    y[n - 2] = y[0];
    y[n - 1] = y[1];
    y
}

#[test]
fn not_a_knot_interpolation_matches_scipy_for_degrees_1_to_5() {
    let y = yi();
    let want = [
        (r::INTERP_K_1_NOT_A_KNOT_T, r::INTERP_K_1_NOT_A_KNOT_C),
        (r::INTERP_K_2_NOT_A_KNOT_T, r::INTERP_K_2_NOT_A_KNOT_C),
        (r::INTERP_K_3_NOT_A_KNOT_T, r::INTERP_K_3_NOT_A_KNOT_C),
        (r::INTERP_K_4_NOT_A_KNOT_T, r::INTERP_K_4_NOT_A_KNOT_C),
        (r::INTERP_K_5_NOT_A_KNOT_T, r::INTERP_K_5_NOT_A_KNOT_C),
    ];
    for (k, (t, c)) in want.iter().enumerate() {
        let s = make_interp_spline(&XI, &y, 2, k + 1, None, &InterpBc::NotAKnot).unwrap();
        close(s.knots(), t, 1e-15);
        close(s.coefficients(), c, 1e-11);
        // And it interpolates.
        close(&s.eval(&XI, 0, Extrapolate::On).unwrap(), &y, 1e-12);
    }
    // With the knots given: the same spline.
    let s = make_interp_spline(
        &XI,
        &y,
        2,
        3,
        Some(r::INTERP_K_3_NOT_A_KNOT_T),
        &InterpBc::NotAKnot,
    )
    .unwrap();
    close(s.coefficients(), r::INTERP_K_3_NOT_A_KNOT_C, 1e-11);
}

#[test]
fn end_conditions_match_scipy() {
    let y = yi();
    let s = make_interp_spline(&XI, &y, 2, 3, None, &InterpBc::natural(2)).unwrap();
    close(s.knots(), r::INTERP_K_3_NATURAL_T, 1e-15);
    close(s.coefficients(), r::INTERP_K_3_NATURAL_C, 1e-11);
    let s = make_interp_spline(&XI, &y, 2, 3, None, &InterpBc::clamped(2)).unwrap();
    close(s.knots(), r::INTERP_K_3_CLAMPED_T, 1e-15);
    close(s.coefficients(), r::INTERP_K_3_CLAMPED_C, 1e-11);
    // One condition on the left only (scipy's `([(1, [0.5, -1])], None)`).
    let bc = InterpBc::Ends {
        left: vec![(1, vec![0.5, -1.0])],
        right: vec![],
    };
    let s = make_interp_spline(&XI, &y, 2, 2, None, &bc).unwrap();
    close(s.knots(), r::INTERP_K_2_1_0_5_1_NONE_T, 1e-15);
    close(s.coefficients(), r::INTERP_K_2_1_0_5_1_NONE_C, 1e-11);
    // Degree 4, orders 1 and 2 on the left, 3 on the right.
    let bc = InterpBc::Ends {
        left: vec![(1, vec![0.5, -1.0]), (2, vec![0.0, 1.0])],
        right: vec![(3, vec![1.0, 1.0])],
    };
    let s = make_interp_spline(&XI, &y, 2, 4, None, &bc).unwrap();
    close(s.knots(), r::INTERP_K_4_TWO_DERIVATIVES_EACH_END_T, 1e-15);
    close(
        s.coefficients(),
        r::INTERP_K_4_TWO_DERIVATIVES_EACH_END_C,
        1e-10,
    );
    let d3 = s.eval(&[5.0], 3, Extrapolate::On).unwrap();
    close(&d3, &[1.0, 1.0], 1e-9);
}

#[test]
fn periodic_interpolation_matches_scipy() {
    let y = yp();
    let want = [
        (r::INTERP_K_1_PERIODIC_T, r::INTERP_K_1_PERIODIC_C),
        (r::INTERP_K_2_PERIODIC_T, r::INTERP_K_2_PERIODIC_C),
        (r::INTERP_K_3_PERIODIC_T, r::INTERP_K_3_PERIODIC_C),
        (r::INTERP_K_4_PERIODIC_T, r::INTERP_K_4_PERIODIC_C),
        (r::INTERP_K_5_PERIODIC_T, r::INTERP_K_5_PERIODIC_C),
    ];
    for (k, (t, c)) in want.iter().enumerate() {
        let s = make_interp_spline(&XI, &y, 2, k + 1, None, &InterpBc::Periodic).unwrap();
        close(s.knots(), t, 1e-14);
        close(s.coefficients(), c, 1e-11);
    }
    let mut bad = y.clone();
    bad[0] += 0.1;
    let e = make_interp_spline(&XI, &bad, 2, 3, None, &InterpBc::Periodic).unwrap_err();
    assert!(
        e.message().contains("First and last points does not match"),
        "{e}"
    );
}

#[test]
fn interpolation_errors_use_scipy_words() {
    let y = yi();
    let msg = |x: &[f64], y: &[f64], k: usize, bc: &InterpBc| {
        make_interp_spline(x, y, 2, k, None, bc)
            .unwrap_err()
            .message()
            .to_string()
    };
    let mut x = XI;
    x[3] = x[2];
    assert!(msg(&x, &y, 3, &InterpBc::NotAKnot).contains("Expect x to not have duplicates"));
    x[3] = 0.5;
    assert!(msg(&x, &y, 3, &InterpBc::NotAKnot).contains("Expect x to be a 1D strictly"));
    assert!(msg(&XI, &y[..10], 3, &InterpBc::NotAKnot).contains("Shapes of x"));
    assert!(msg(&XI, &y, 5, &InterpBc::natural(2)).contains("number of derivatives"));
    assert!(msg(&XI, &y, 1, &InterpBc::natural(2)).contains("Too much info for k=1"));
    let bc = InterpBc::Ends {
        left: vec![(4, vec![0.0, 0.0])],
        right: vec![],
    };
    assert!(msg(&XI, &y, 3, &bc).contains("Bad boundary conditions at 0.0"));
    let e =
        make_interp_spline(&XI, &y, 2, 3, Some(&[0.0, 1.0, 0.5]), &InterpBc::NotAKnot).unwrap_err();
    assert!(e.message().contains("Expect t to be a 1-D sorted"), "{e}");
    let e = make_interp_spline(&XI, &y, 2, 3, Some(&[0.0; 8]), &InterpBc::NotAKnot).unwrap_err();
    assert!(e.message().contains("need at least 13"), "{e}");
    let t: Vec<f64> = (0..13).map(|i| f64::from(i) * 0.3).collect();
    let e = make_interp_spline(&XI, &y, 2, 3, Some(&t), &InterpBc::NotAKnot).unwrap_err();
    assert!(e.message().contains("Out of bounds"), "{e}");
}

/// The least-squares data of the script, `len(x) × 5`.
fn lsq_data() -> (
    &'static [f64],
    &'static [f64],
    &'static [f64],
    &'static [f64],
) {
    (r::LSQ_X, r::LSQ_Y, r::LSQ_W, r::LSQ_T)
}

#[test]
fn least_squares_matches_scipy_with_weights_and_five_columns() {
    let (x, y, w, t) = lsq_data();
    for (method, want) in [
        (LsqMethod::Qr, r::LSQ_K_3_WEIGHTED_QR_C),
        (LsqMethod::NormalEquations, r::LSQ_K_3_WEIGHTED_NORM_EQ_C),
    ] {
        let s = make_lsq_spline(x, y, 5, t, 3, Some(w), method).unwrap();
        assert_eq!(s.knots(), t);
        close(s.coefficients(), want, 1e-10);
    }
    let y0: Vec<f64> = y.chunks_exact(5).map(|row| row[0]).collect();
    let s = make_lsq_spline(x, &y0, 1, t, 3, None, LsqMethod::Qr).unwrap();
    close(s.coefficients(), r::LSQ_K_3_UNWEIGHTED_COLUMN_0_C, 1e-10);
}

#[test]
fn least_squares_errors_use_scipy_words() {
    let (x, y, _, t) = lsq_data();
    let msg = |x: &[f64], y: &[f64], t: &[f64], method| {
        make_lsq_spline(x, y, 5, t, 3, None, method)
            .unwrap_err()
            .message()
            .to_string()
    };
    assert!(msg(&x[..3], &y[..15], t, LsqMethod::Qr).contains("Need more x points"));
    let mut bad_t = t.to_vec();
    bad_t.swap(5, 6);
    assert!(msg(x, y, &bad_t, LsqMethod::Qr).contains("Expect t to be a 1D strictly"));
    assert!(msg(x, &y[..10], t, LsqMethod::Qr).contains("Shapes of x"));
    let mut xs = x.to_vec();
    xs[5] = xs[4];
    assert!(msg(&xs, y, t, LsqMethod::NormalEquations).contains("Expect x to be a 1D strictly"));
    xs[5] = xs[0];
    assert!(msg(&xs, y, t, LsqMethod::Qr).contains("non-decreasing"));
    // Knots 2.31 … 2.35 between the data at 2.13 and 2.44: a basis function without data
    // (scipy returns NaN coefficients there).
    let mut tt = t.to_vec();
    for (i, v) in [2.31, 2.32, 2.33, 2.34, 2.35].into_iter().enumerate() {
        tt.insert(8 + i, v);
    }
    let e = make_lsq_spline(x, y, 5, &tt, 3, None, LsqMethod::Qr).unwrap_err();
    assert!(e.message().contains("Schoenberg-Whitney"), "{e}");
    let mut xo = x.to_vec();
    xo[0] = -1.0;
    assert!(msg(&xo, y, t, LsqMethod::Qr).contains("Out of bounds"));
}

#[test]
fn periodic_interpolation_with_fewer_points_than_the_degree() {
    // scipy 1.17: make_interp_spline([0, 1, 2.5, 4], [1, 2, -1, 1], k, bc_type="periodic")
    // (scipy's dense path for n <= k), `.t` and `.c`.
    let x = [0.0, 1.0, 2.5, 4.0];
    let y = [1.0, 2.0, -1.0, 1.0];
    let cases: [(usize, &[f64], &[f64]); 3] = [
        (
            3,
            &[-4.0, -3.0, -1.5, 0.0, 1.0, 2.5, 4.0, 5.0, 6.5, 8.0],
            &[
                -2.7857142857142856,
                0.8650793650793649,
                3.087301587301587,
                -2.7857142857142856,
                0.8650793650793649,
                3.087301587301587,
            ],
        ),
        (
            4,
            &[
                -6.25, -4.0, -3.5, -2.25, 0.0, 0.5, 1.75, 4.0, 4.5, 5.75, 8.0, 8.5,
            ],
            &[
                2.594881866971787,
                -4.284332304905125,
                2.172059955321265,
                2.594881866971789,
                -4.284332304905125,
                2.1720599553212647,
                2.594881866971788,
            ],
        ),
        (
            5,
            &[
                -7.0, -5.5, -4.0, -3.0, -1.5, 0.0, 1.0, 2.5, 4.0, 5.0, 6.5, 8.0, 9.0, 10.5,
            ],
            &[
                4.602665165165167,
                -4.003003003003003,
                0.8109984984984988,
                4.602665165165164,
                -4.003003003003004,
                0.8109984984984987,
                4.602665165165165,
                -4.003003003003003,
            ],
        ),
    ];
    for (k, t, c) in cases {
        let s = make_interp_spline(&x, &y, 1, k, None, &InterpBc::Periodic).unwrap();
        close(s.knots(), t, 1e-15);
        close(s.coefficients(), c, 1e-10);
    }
}

/// Degree 0 (scipy: `make_interp_spline(x, y, k=0)` has `t = [x…, x[-1]]`, `c = y`, and
/// gives `y[-1]` at `x[-1]` and beyond, `y[0]` below `x[0]`).
#[test]
fn degree_zero_interpolation_is_scipys_step_function() {
    let y = yi();
    let s = make_interp_spline(&XI, &y, 2, 0, None, &InterpBc::NotAKnot).unwrap();
    let mut t = XI.to_vec();
    t.push(5.0);
    assert_eq!(s.knots(), &t[..]);
    close(s.coefficients(), &y, 0.0);
    close(&s.eval(&XI, 0, Extrapolate::On).unwrap(), &y, 0.0);
    let got = s.eval(&[-1.0, 0.2, 6.0], 0, Extrapolate::On).unwrap();
    close(&got, &[y[0], y[1], y[0], y[1], y[16], y[17]], 0.0);
}
