//! Periodic FITPACK smoothing (`make_splrep`, `make_splprep`, `generate_knots` with
//! `periodic`, scipy's `bc_type="periodic"`) against scipy 1.17's replica (the constants of
//! `reference.rs`, printed by `reference.py`), the invariants of a periodic fit on random
//! data (the ends agree to derivative `k − 1`, wrapped knots and coefficients, the residual
//! recomputed from the data meets `s`) and the error contract.

mod reference;

use nalgebra::Vector2;
use reference::*;
use spline_core::ErrorKind;
use spline_fit::{ResidualFit, SplrepOptions, generate_knots, make_splprep, make_splrep};
use spline_geom::BSpline;

fn periodic(s: f64, k: usize) -> SplrepOptions<'static, f64> {
    SplrepOptions {
        s,
        k,
        periodic: true,
        ..Default::default()
    }
}

/// `|a − b| ≤ tol (1 + |b|)` entry by entry, with the same length.
fn close(got: &[f64], want: &[f64], tol: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: lengths {got:?} vs {want:?}");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= tol * (1.0 + w.abs()),
            "{what}[{i}]: {g} vs {w} (difference {:e})",
            g - w
        );
    }
}

/// The residual $\sum_{i < m-1} (w_i (g(x_i) - y_i))^2$ evaluated afresh.
fn residual(spline: &BSpline<f64, f64>, x: &[f64], y: &[f64], w: Option<&[f64]>) -> f64 {
    let m = x.len();
    (0..m - 1)
        .map(|i| {
            let r = w.map_or(1.0, |w| w[i]) * (spline.eval(x[i]).unwrap() - y[i]);
            r * r
        })
        .sum()
}

/// The invariants of a periodic spline on `[xb, xe]`: wrapped knots, the last `k`
/// coefficients equal to the first `k`, and the values and derivatives up to `k − 1` equal
/// at the two ends (relative to the size of each derivative).
fn assert_periodic(spline: &BSpline<f64, f64>, (xb, xe): (f64, f64), what: &str) {
    let k = spline.degree();
    let t = spline.knots().knots();
    let n = t.len();
    let per = xe - xb;
    assert_eq!((t[k], t[n - k - 1]), (xb, xe), "{what}: the period");
    for j in 1..=k {
        assert!(
            (t[k - j] - (t[n - k - 1 - j] - per)).abs() <= 1e-12 * per,
            "{what}"
        );
        assert!(
            (t[n - k - 1 + j] - (t[k + j] + per)).abs() <= 1e-12 * per,
            "{what}"
        );
    }
    let c = spline.control_points();
    let n7 = c.len() - k;
    for j in 0..k {
        assert_eq!(c[n7 + j], c[j], "{what}: coefficient {}", n7 + j);
    }
    let left = spline.derivatives(xb, k - 1).unwrap();
    let right = spline.derivatives(xe, k - 1).unwrap();
    let scale = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (d, (a, b)) in left.iter().zip(&right).enumerate() {
        // Derivative d scales like (1 / smallest knot interval)^d.
        let h = t[k..n - k]
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        let tol = 1e-10 * scale * h.powi(-i32::try_from(d).unwrap());
        assert!((a - b).abs() <= tol, "{what}: derivative {d}: {a} vs {b}");
    }
}

fn fit(s: f64, k: usize, w: Option<&'static [f64]>) -> ResidualFit<f64, f64> {
    let options = SplrepOptions {
        weights: w,
        ..periodic(s, k)
    };
    make_splrep(&X, &Y, &options).unwrap()
}

/// A reference case: name, `s`, `k`, weights, knots, coefficients, residual.
type Case = (
    &'static str,
    f64,
    usize,
    Option<&'static [f64]>,
    &'static [f64],
    &'static [f64],
    f64,
);

#[test]
fn knots_coefficients_and_residual_match_scipy() {
    let cases: [Case; 7] = [
        ("S1", 1.0, 3, None, &KNOTS_S1, &COEF_S1, FP_S1),
        ("S01", 0.1, 3, None, &KNOTS_S01, &COEF_S01, FP_S01),
        ("S001", 0.01, 3, None, &KNOTS_S001, &COEF_S001, FP_S001),
        ("K2", 0.05, 2, None, &KNOTS_K2, &COEF_K2, FP_K2),
        ("K5", 0.02, 5, None, &KNOTS_K5, &COEF_K5, FP_K5),
        ("W", 0.2, 3, Some(&W), &KNOTS_W, &COEF_W, FP_W),
        ("K1", 0.05, 1, None, &KNOTS_K1, &COEF_K1, FP_K1),
    ];
    for (tag, s, k, w, knots, coef, fp) in cases {
        let fit = fit(s, k, w);
        let spline = &fit.spline;
        close(
            spline.knots().knots(),
            knots,
            1e-15,
            &format!("{tag} knots"),
        );
        close(
            spline.control_points(),
            coef,
            1e-12,
            &format!("{tag} coefficients"),
        );
        close(&[fit.residual], &[fp], 1e-10, &format!("{tag} residual"));
        // The residual reported is the one of the data (but the last), and meets s.
        close(&[residual(spline, &X, &Y, w)], &[fit.residual], 1e-12, tag);
        assert!(
            fit.converged && (fit.residual - s).abs() < 1e-3 * s,
            "{tag}"
        );
        assert!(fit.smoothing.is_some_and(|p| p > 0.0), "{tag}");
        assert_periodic(spline, (X[0], X[39]), tag);
    }
}

#[test]
fn degree_six_as_scipy() {
    // Above FITPACK's degrees (scipy's replica has no limit).
    let fit = fit(0.05, 6, None);
    close(fit.spline.knots().knots(), &KNOTS_K6, 1e-15, "knots");
    close(fit.spline.control_points(), &COEF_K6, 1e-11, "coefficients");
    assert_periodic(&fit.spline, (X[0], X[39]), "k = 6");
}

#[test]
fn degree_six_not_periodic_as_scipy() {
    let options = SplrepOptions {
        s: 0.05,
        k: 6,
        ..Default::default()
    };
    let fit = make_splrep(&X, &Y, &options).unwrap();
    close(fit.spline.knots().knots(), &KNOTS_NP_K6, 1e-15, "knots");
    close(
        fit.spline.control_points(),
        &COEF_NP_K6,
        1e-10,
        "coefficients",
    );
    assert!(fit.converged && (fit.residual - 0.05).abs() < 5e-5);
}

#[test]
fn given_knots_smooth_without_placing_knots() {
    let options = SplrepOptions {
        t: Some(&GIVEN_T),
        ..periodic(0.03, 3)
    };
    let fit = make_splrep(&X, &Y, &options).unwrap();
    assert_eq!(fit.spline.knots().knots(), &GIVEN_T);
    close(
        fit.spline.control_points(),
        &GIVEN_COEF,
        1e-12,
        "coefficients",
    );
    assert!(fit.converged && (fit.residual - 0.03).abs() < 3e-5);
}

#[test]
fn knot_sequence_and_interpolation_knots() {
    let seq = generate_knots(&X, &Y, &periodic(0.01, 3)).unwrap();
    let lengths: Vec<usize> = seq.iter().map(Vec::len).collect();
    assert_eq!(lengths, SEQ_LENGTHS);
    close(&seq[1], &SEQ_SECOND, 1e-15, "second knot vector");
    // The last vector is the one make_splrep smooths on.
    close(seq.last().unwrap(), &KNOTS_S001, 1e-15, "last knot vector");
    for (k, want) in [(3, &INTERP_KNOTS_K3[..]), (4, &INTERP_KNOTS_K4[..])] {
        let seq = generate_knots(&X, &Y, &periodic(0.0, k)).unwrap();
        assert_eq!(seq.len(), 1);
        close(
            &seq[0],
            want,
            1e-15,
            &format!("interpolation knots, k = {k}"),
        );
    }
}

#[test]
fn large_target_gives_the_weighted_mean() {
    let options = SplrepOptions {
        weights: Some(&W),
        ..periodic(100.0, 3)
    };
    let fit = make_splrep(&X, &Y, &options).unwrap();
    close(fit.spline.knots().knots(), &KNOTS_CONST, 1e-15, "knots");
    close(
        fit.spline.control_points(),
        &COEF_CONST,
        1e-13,
        "coefficients",
    );
    // Closed form: the least-squares constant is Σ w² y / Σ w² over the data but the last.
    let (num, den) = (0..39).fold((0.0, 0.0), |(n, d), i| {
        (n + W[i] * W[i] * Y[i], d + W[i] * W[i])
    });
    for c in fit.spline.control_points() {
        assert!((c - num / den).abs() < 1e-14);
    }
    assert!(fit.smoothing.is_none() && fit.residual <= 100.0);
}

#[test]
fn zero_target_interpolates_periodically() {
    let fit = make_splrep(&X, &Y, &periodic(0.0, 3)).unwrap();
    // The knots are generate_knots' (scipy's _periodic_knots), bit for bit.
    assert_eq!(fit.spline.knots().knots(), &INTERP_KNOTS_K3);
    close(
        fit.spline.control_points(),
        &INTERP_COEF_K3,
        1e-12,
        "coefficients",
    );
    let values = fit.spline.eval_many(&X).unwrap();
    close(&values, &Y, 1e-12, "values at the data");
    assert_periodic(&fit.spline, (X[0], X[39]), "interpolation");
}

#[test]
fn closed_curve_matches_scipy() {
    let points: Vec<Vector2<f64>> = CURVE_X
        .iter()
        .zip(&CURVE_Y)
        .map(|(&x, &y)| Vector2::new(x, y))
        .collect();
    let (fit, u) = make_splprep(&points, None, &periodic(0.002, 3)).unwrap();
    close(&u, &CURVE_U, 1e-15, "parameters");
    close(fit.spline.knots().knots(), &CURVE_KNOTS, 1e-15, "knots");
    let coef: Vec<f64> = fit
        .spline
        .control_points()
        .iter()
        .flat_map(|p| [p.x, p.y])
        .collect();
    close(&coef, &CURVE_COEF, 1e-12, "coefficients");
    assert!(fit.converged && (fit.residual - 0.002).abs() < 2e-6);
    // Closed: the end points and tangents agree.
    let a = fit.spline.derivatives(0.0, 2).unwrap();
    let b = fit.spline.derivatives(1.0, 2).unwrap();
    for (d, (p, q)) in a.iter().zip(&b).enumerate() {
        assert!((p - q).norm() < 1e-9 * (1.0 + p.norm()), "derivative {d}");
    }
}

/// A small deterministic generator (SplitMix64) for the random cases.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        // 53 random bits in [0, 1).
        #[allow(clippy::cast_precision_loss)]
        let v = (z >> 11) as f64 / (1u64 << 53) as f64;
        v
    }
}

#[test]
fn random_periodic_fits_keep_the_invariants() {
    let mut rng = Rng(20_260_723);
    let (mut smoothed, mut unconverged) = (0, 0);
    for case in 0..40 {
        let m = 8 + (rng.next() * 90.0) as usize;
        let per = 0.5 + 5.0 * rng.next();
        let xb = -2.0 + 4.0 * rng.next();
        let mut x: Vec<f64> = (0..m - 2).map(|_| xb + per * rng.next()).collect();
        x.sort_by(f64::total_cmp);
        x.dedup();
        x.insert(0, xb);
        x.push(xb + per);
        let m = x.len();
        let (a, b) = (rng.next() * 3.0, rng.next());
        let tau = std::f64::consts::TAU / per;
        let mut y: Vec<f64> = x
            .iter()
            .map(|&t| {
                let th = tau * (t - xb);
                th.sin() + a * (2.0 * th).cos() + b * (5.0 * th).sin() + 0.1 * (rng.next() - 0.5)
            })
            .collect();
        y[m - 1] = y[0];
        let w: Vec<f64> = (0..m).map(|_| 0.5 + rng.next()).collect();
        let k = 1 + case % 5;
        let s = (m as f64) * 1e-3 * 10f64.powf(3.0 * rng.next() - 1.5);
        let weights = (case % 3 == 0).then_some(&w[..]);
        let options = SplrepOptions {
            weights,
            ..periodic(s, k)
        };
        let what = format!("case {case}: m = {m}, k = {k}, s = {s:e}");
        let fit = make_splrep(&x, &y, &options).expect(&what);
        assert_periodic(&fit.spline, (x[0], x[m - 1]), &what);
        let r = residual(&fit.spline, &x, &y, weights);
        assert!((r - fit.residual).abs() <= 1e-12 * (1.0 + r), "{what}");
        if fit.converged {
            assert!(
                (r - s).abs() < 1e-3 * s || fit.smoothing.is_none() && r <= s,
                "{what}"
            );
        }
        // The knots of the fit are the last of the sequence.
        let seq = generate_knots(&x, &y, &options).unwrap();
        assert_eq!(seq.last().unwrap(), fit.spline.knots().knots(), "{what}");
        smoothed += usize::from(fit.smoothing.is_some());
        unconverged += usize::from(!fit.converged);
    }
    // Most cases reach the second stage (interior knots and a smoothing factor), and FITPACK's
    // iteration meets the target.
    assert!(
        smoothed >= 30 && unconverged <= 2,
        "{smoothed} smoothed, {unconverged} not converged"
    );
}

/// The cubic periodic knot vector on `[0, per]` with the interior knots `inner`.
fn wrapped(inner: &[f64], per: f64) -> Vec<f64> {
    let mut period = vec![0.0];
    period.extend_from_slice(inner);
    period.push(per);
    let p = period.len();
    let mut t: Vec<f64> = (1..=3).rev().map(|j| period[p - 1 - j] - per).collect();
    t.extend_from_slice(&period);
    t.extend((1..=3).map(|j| period[j] + per));
    t
}

#[test]
fn errors_name_the_problem() {
    let err = |r: spline_core::Result<ResidualFit<f64, f64>>| r.expect_err("an error");
    // The data must be periodic (numpy.allclose(y[0], y[-1], atol=1e-15)).
    let mut y = Y;
    y[39] = y[0] * (1.0 + 2e-5);
    let e = err(make_splrep(&X, &y, &periodic(0.1, 3)));
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert!(e.to_string().contains("First and last points"), "{e}");
    y[39] = y[0] * (1.0 + 5e-6);
    assert!(make_splrep(&X, &y, &periodic(0.1, 3)).is_ok());
    // One datum; degrees 0 and above the maximum.
    let e = err(make_splrep(&[0.0], &[1.0], &periodic(0.1, 3)));
    assert_eq!(e.kind(), ErrorKind::TooFewPoints);
    for k in [0, spline_core::MAX_DEGREE + 1] {
        assert_eq!(
            err(make_splrep(&X, &Y, &periodic(0.1, k))).kind(),
            ErrorKind::InvalidArgument
        );
    }
    // Two data and a constant: fine (nothing to place).
    let fit = make_splrep(&[0.0, 1.0], &[5.0, 5.0], &periodic(1e-50, 1)).unwrap();
    assert_eq!(fit.spline.control_points(), &[5.0; 2]);
    // Given knots: too many, repeated inside the period, violating Schoenberg–Whitney.
    let many: Vec<f64> = (0..60).map(f64::from).collect();
    let options = SplrepOptions {
        t: Some(&many),
        ..periodic(0.1, 3)
    };
    let e = err(make_splrep(&X, &Y, &options));
    assert_eq!(e.kind(), ErrorKind::InvalidLength);
    assert!(e.to_string().contains("Need k+1 <= n-k-1 <= m+k-1"), "{e}");
    let repeated = wrapped(&[1.0, 2.0, 2.0, 4.0], X[39]);
    let options = SplrepOptions {
        t: Some(&repeated),
        ..periodic(0.1, 3)
    };
    assert_eq!(
        err(make_splrep(&X, &Y, &options)).kind(),
        ErrorKind::KnotMultiplicity
    );
    // Six knots between two data (X[18] < 2.955 … 2.9575 < X[19]): the support of a cubic
    // basis function holds no datum.
    let crowded = wrapped(
        &[1.0, 2.955, 2.9555, 2.956, 2.9565, 2.957, 2.9575, 4.0],
        X[39],
    );
    let options = SplrepOptions {
        t: Some(&crowded),
        ..periodic(0.1, 3)
    };
    assert_eq!(
        err(make_splrep(&X, &Y, &options)).kind(),
        ErrorKind::SchoenbergWhitney
    );
    // scipy's argument checks: nest too small, t or w with s = 0, negative s and weights.
    let options = SplrepOptions {
        nest: Some(7),
        ..periodic(0.1, 3)
    };
    assert_eq!(
        err(make_splrep(&X, &Y, &options)).kind(),
        ErrorKind::InvalidArgument
    );
    let options = SplrepOptions {
        weights: Some(&W),
        ..periodic(0.0, 3)
    };
    assert_eq!(
        err(make_splrep(&X, &Y, &options)).kind(),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        err(make_splrep(&X, &Y, &periodic(-1.0, 3))).kind(),
        ErrorKind::InvalidArgument
    );
    let mut w = W;
    w[3] = -1.0;
    let options = SplrepOptions {
        weights: Some(&w),
        ..periodic(0.1, 3)
    };
    assert_eq!(
        err(make_splrep(&X, &Y, &options)).kind(),
        ErrorKind::InvalidWeight
    );
}
