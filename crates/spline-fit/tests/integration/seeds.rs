//! The tests the source documents call for: seed 003 (TD2 uniform vs chordal Bézier
//! interpolation, TD3 least squares and parameter correction), seed 000 §3.3 (FIG. 15:
//! least squares with fixed coordinates through a half circle), seed 004 §7 (functions,
//! surfaces by two passes, natural splines).

#![allow(clippy::needless_range_loop, clippy::cast_lossless)]

use nalgebra::{DMatrix, DVector, Vector2, Vector3};
use spline_core::KnotVector;
use spline_fit::{
    CorrectionOptions, LeastSquares, Parametrization, bezier_interpolate, bezier_least_squares,
    correct_parameters, correct_parameters_bezier, interpolate_function, interpolate_surface,
    natural_cubic, natural_spline, parametrize,
};
use spline_geom::{BSpline, Bezier};

/// Length of a polyline through many samples of a Bézier curve.
fn sampled_length(curve: &Bezier<f64, Vector2<f64>>) -> f64 {
    let (a, b) = curve.interval();
    let pts: Vec<Vector2<f64>> = (0..=2000)
        .map(|k| curve.eval(a + (b - a) * f64::from(k) / 2000.0).unwrap())
        .collect();
    pts.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
}

/// Largest distance of the samples of `curve` from the polyline `poly`.
fn distance_to_polyline(curve: &Bezier<f64, Vector2<f64>>, poly: &[Vector2<f64>]) -> f64 {
    let (a, b) = curve.interval();
    (0..=2000)
        .map(|k| {
            let x = curve.eval(a + (b - a) * f64::from(k) / 2000.0).unwrap();
            poly.windows(2)
                .map(|w| {
                    let d = w[1] - w[0];
                    let t = ((x - w[0]).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
                    (x - (w[0] + d * t)).norm()
                })
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

#[test]
fn seed003_td2_uniform_and_chordal_bezier_interpolation_of_the_same_points() {
    // Unevenly spaced points: two short chords, then a long one, then a short one.
    let points = [
        Vector2::new(0.0, 0.0),
        Vector2::new(0.3, 0.4),
        Vector2::new(0.6, 0.5),
        Vector2::new(4.0, 0.8),
        Vector2::new(4.2, 0.2),
    ];
    let interval = (0.0, 1.0);
    let uniform = bezier_interpolate(&points, &Parametrization::Uniform, interval).unwrap();
    let chordal = bezier_interpolate(&points, &Parametrization::Chordal, interval).unwrap();
    // Parameters: i/n for uniform, cumulative chord lengths for chordal (closed forms).
    for (i, &t) in uniform.params.iter().enumerate() {
        assert!((t - i as f64 / 4.0).abs() < 1e-15);
    }
    let chords: Vec<f64> = points.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    let total: f64 = chords.iter().sum();
    let mut acc = 0.0;
    for (i, &t) in chordal.params.iter().enumerate() {
        assert!((t - acc / total).abs() < 1e-14, "chordal parameter {i}");
        if i < chords.len() {
            acc += chords[i];
        }
    }
    // Both interpolate: checked by de Casteljau evaluation (independent of the solver).
    for fit in [&uniform, &chordal] {
        assert_eq!(fit.curve.degree(), 4);
        for (t, q) in fit.params.iter().zip(&points) {
            assert!((fit.curve.eval(*t).unwrap() - q).norm() < 1e-12);
        }
    }
    // What the TD asks to observe: with uneven spacing, equally spaced parameters make the
    // curve swing far from the data polygon (longer, with overshoot); chord-length
    // parameters follow it.
    let (lu, lc) = (
        sampled_length(&uniform.curve),
        sampled_length(&chordal.curve),
    );
    let polygon: f64 = total;
    assert!(lu > lc, "uniform {lu} should be longer than chordal {lc}");
    assert!(lc < 1.2 * polygon, "chordal {lc} vs polygon {polygon}");
    let (du, dc) = (
        distance_to_polyline(&uniform.curve, &points),
        distance_to_polyline(&chordal.curve, &points),
    );
    assert!(du > 2.0 * dc, "uniform strays {du}, chordal {dc}");
}

/// Points of the curve (3t, sin 4t²) at unevenly spaced t: uniform parameters are a poor
/// first guess, which parameter correction improves.
fn uneven_samples(count: usize) -> Vec<Vector2<f64>> {
    (0..count)
        .map(|k| {
            let t = k as f64 / (count - 1) as f64;
            let s = t * t;
            Vector2::new(3.0 * s, (4.0 * s).sin())
        })
        .collect()
}

#[test]
fn seed003_td3_parameter_correction_lowers_the_error_and_stops_on_the_angle() {
    let points = uneven_samples(30);
    let params = parametrize(&points, &Parametrization::Uniform).unwrap();
    let options = CorrectionOptions {
        max_iterations: 200,
        angle_tolerance: 1e-2,
        max_halvings: 30,
    };
    let (fit, report) =
        correct_parameters_bezier(&points, &params, 5, (0.0, 1.0), &options).unwrap();
    // The error of the least-squares fit never increases, and drops substantially.
    let e = &report.errors;
    assert_eq!(e.len(), report.iterations + 1);
    assert!(e.windows(2).all(|w| w[1] <= w[0] * (1.0 + 1e-12)), "{e:?}");
    assert!(e[e.len() - 1] < 0.2 * e[0], "{e:?}");
    // It stopped on the angle criterion |π/2 − α| < ε, not on L, and not earlier.
    assert!(report.converged);
    assert!(report.iterations < options.max_iterations);
    let half_pi = std::f64::consts::FRAC_PI_2;
    let (last, before) = report.angles.split_last().unwrap();
    assert!((half_pi - last).abs() < options.angle_tolerance);
    assert!(
        before
            .iter()
            .all(|a| (half_pi - a).abs() >= options.angle_tolerance)
    );
    // Independent check of the reported error: the Bézier curve evaluated by de Casteljau.
    let direct: f64 = fit
        .params
        .iter()
        .zip(&points)
        .map(|(t, q)| (fit.curve.eval(*t).unwrap() - q).norm_squared())
        .sum();
    assert!((direct - e[e.len() - 1]).abs() <= 1e-9 * direct.max(1e-300));
    // Parameters stay ordered and in [a, b].
    assert!(fit.params.windows(2).all(|w| w[0] <= w[1]));
    assert!(fit.params.iter().all(|t| (0.0..=1.0).contains(t)));
}

#[test]
fn seed003_parameter_correction_with_bspline_least_squares_and_a_budget() {
    let points = uneven_samples(60);
    let params = parametrize(&points, &Parametrization::Uniform).unwrap();
    let knots = spline_fit::nurbs_book_knots(3, 8, &params).unwrap();
    // L = 3: stops on the iteration limit.
    let options = CorrectionOptions {
        max_iterations: 3,
        angle_tolerance: 1e-9,
        max_halvings: 30,
    };
    let problem = LeastSquares::new(&points, &params, knots);
    let (fit, report) = correct_parameters(&problem, &options).unwrap();
    assert_eq!(report.iterations, 3);
    assert!(!report.converged);
    assert!(report.errors.windows(2).all(|w| w[1] <= w[0]));
    assert!(report.errors[3] < report.errors[0]);
    assert!((fit.deviation.sum_squares - report.errors[3]).abs() < 1e-12);
}

#[test]
fn seed003_td3_bezier_least_squares_matches_dense_normal_equations() {
    let points = uneven_samples(25);
    let fit =
        bezier_least_squares(&points, 4, &Parametrization::Chordal, (0.0, 2.0), None).unwrap();
    // Dense Bernstein normal equations, solved by nalgebra.
    let n = 4;
    let mut a = DMatrix::<f64>::zeros(points.len(), n + 1);
    for (k, &t) in fit.params.iter().enumerate() {
        for i in 0..=n {
            a[(k, i)] = spline_core::bernstein(n, i, t / 2.0);
        }
    }
    let ata = a.transpose() * &a;
    for c in 0..2 {
        let b = DVector::from_iterator(points.len(), points.iter().map(|p| p[c]));
        let x = ata.clone().lu().solve(&(a.transpose() * b)).unwrap();
        for i in 0..=n {
            let got = fit.curve.control_points()[i][c];
            assert!((got - x[i]).abs() < 1e-9 * x[i].abs().max(1.0), "{i} {c}");
        }
    }
}

#[test]
fn seed000_fig15_least_squares_with_fixed_coordinates_follows_the_half_circle() {
    // 11 points of the upper half of the circle of centre (½, 0) and radius ½, from (0, 0)
    // to (1, 0); n = 10 (11 control points), d = 3, chord-length parameters.
    let points: Vec<Vector2<f64>> = (0..=10)
        .map(|k| {
            let phi = std::f64::consts::PI * f64::from(k) / 10.0;
            Vector2::new(0.5 - 0.5 * phi.cos(), 0.5 * phi.sin())
        })
        .collect();
    let params = parametrize(&points, &Parametrization::Chordal).unwrap();
    let knots = KnotVector::averaging(3, &params).unwrap();
    assert_eq!(knots.num_basis(), 11);
    let n = 10;
    // x_0 = x_1 = y_0 = y_n = 0, x_n = 1.
    let fit = LeastSquares::new(&points, &params, knots.clone())
        .fix_coordinate(0, 0, 0.0)
        .fix_coordinate(1, 0, 0.0)
        .fix_coordinate(0, 1, 0.0)
        .fix_coordinate(n, 1, 0.0)
        .fix_coordinate(n, 0, 1.0)
        .solve()
        .unwrap();
    let cp = fit.curve.control_points();
    assert_eq!(
        (cp[0][0], cp[1][0], cp[0][1], cp[n][1], cp[n][0]),
        (0.0, 0.0, 0.0, 0.0, 1.0)
    );
    // Within 1e-3 of the circle everywhere.
    let centre = Vector2::new(0.5, 0.0);
    let worst = (0..=4000)
        .map(|k| {
            let c = fit.curve.eval(f64::from(k) / 4000.0).unwrap();
            ((c - centre).norm() - 0.5).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst < 1e-3, "distance to the circle {worst}");
    // Vertical tangent at (0, 0): x_0 = x_1.
    let d = fit.curve.derivatives(0.0, 1).unwrap()[1];
    assert!(d[0].abs() < 1e-15 && d[1] > 0.0);
    // The systems (13) of seed 000, built densely and solved by nalgebra.
    let rows: Vec<Vec<f64>> = params
        .iter()
        .map(|&t| knots.dense_basis(t).unwrap())
        .collect();
    let solve = |cols: std::ops::Range<usize>, rhs: &dyn Fn(usize) -> f64| -> DVector<f64> {
        let a = DMatrix::from_fn(rows.len(), cols.len(), |k, j| rows[k][cols.start + j]);
        let w = DVector::from_fn(rows.len(), |k, _| rhs(k));
        (a.transpose() * &a)
            .lu()
            .solve(&(a.transpose() * w))
            .unwrap()
    };
    let x = solve(2..n, &|k| points[k][0] - rows[k][n]);
    let y = solve(1..n, &|k| points[k][1]);
    for j in 2..n {
        assert!((cp[j][0] - x[j - 2]).abs() < 1e-10, "x_{j}");
    }
    for j in 1..n {
        assert!((cp[j][1] - y[j - 1]).abs() < 1e-10, "y_{j}");
    }
}

#[test]
fn seed004_function_interpolation_uses_the_knots_7_8() {
    let x = [0.0, 0.5, 1.5, 2.0, 3.5, 4.0, 5.0];
    let y: Vec<f64> = x.iter().map(|&t: &f64| (t * 0.7).cos()).collect();
    let f = interpolate_function(&x, &y, 3).unwrap();
    // (7.8): x_0 ×4, (x_{k+1} + x_{k+2} + x_{k+3})/3, x_n ×4.
    let expected = [
        0.0,
        0.0,
        0.0,
        0.0,
        (0.5 + 1.5 + 2.0) / 3.0,
        (1.5 + 2.0 + 3.5) / 3.0,
        (2.0 + 3.5 + 4.0) / 3.0,
        5.0,
        5.0,
        5.0,
        5.0,
    ];
    for (a, b) in f.knots().knots().iter().zip(expected) {
        assert!((a - b).abs() < 1e-15);
    }
    for (t, v) in x.iter().zip(&y) {
        assert!((f.eval(*t).unwrap() - v).abs() < 1e-13);
    }
    // Cubic polynomials are reproduced.
    let cubic = |t: f64| 1.0 - 2.0 * t + 0.5 * t * t * t;
    let g = interpolate_function(&x, &x.map(cubic), 3).unwrap();
    for k in 0..=50 {
        let t = 5.0 * f64::from(k) / 50.0;
        assert!((g.eval(t).unwrap() - cubic(t)).abs() < 1e-12);
    }
}

#[test]
fn seed004_surface_interpolation_by_two_passes_reproduces_bicubic_polynomials() {
    let us = [0.0, 0.2, 0.35, 0.6, 0.8, 1.0];
    let vs = [0.0, 0.1, 0.4, 0.5, 0.9, 1.0];
    let f = |u: f64, v: f64| 1.0 + u - 2.0 * v * v + u * u * u * v - 0.5 * u * v * v * v;
    let grid: Vec<Vector3<f64>> = us
        .iter()
        .flat_map(|&u| vs.iter().map(move |&v| Vector3::new(u, v, f(u, v))))
        .collect();
    let fit = interpolate_surface(
        &grid,
        us.len(),
        vs.len(),
        3,
        3,
        &Parametrization::Given(us.to_vec()),
        &Parametrization::Given(vs.to_vec()),
    )
    .unwrap();
    assert!(fit.deviation.max < 1e-12);
    assert_eq!(fit.surface.control_points().len(), 36);
    for k in 0..=10 {
        for l in 0..=10 {
            let (u, v) = (f64::from(k) / 10.0, f64::from(l) / 10.0);
            let s = fit.surface.eval(u, v).unwrap();
            assert!(
                (s - Vector3::new(u, v, f(u, v))).norm() < 1e-12,
                "({u}, {v})"
            );
        }
    }
}

/// ∫ σ''² over the domain by Simpson's rule on a fine grid.
fn bending_energy(f: &BSpline<f64, f64>) -> f64 {
    let (a, b) = f.domain();
    let m = 20_000;
    let h = (b - a) / f64::from(m);
    (0..=m)
        .map(|k| {
            let t = a + h * f64::from(k);
            let w = if k == 0 || k == m {
                1.0
            } else if k % 2 == 1 {
                4.0
            } else {
                2.0
            };
            let d2 = f.derivatives(t, 2).unwrap()[2];
            w * d2 * d2
        })
        .sum::<f64>()
        * h
        / 3.0
}

#[test]
fn seed004_natural_cubic_spline_minimises_the_bending_energy() {
    let x = [0.0, 0.7, 1.0, 2.2, 3.0, 4.1];
    let y = [0.3, -0.2, 0.5, 1.0, -0.4, 0.0];
    let natural: BSpline<f64, f64> = natural_cubic(&x, &y).unwrap();
    // σ''(x_0) = σ''(x_n) = 0, σ(x_j) = y_j.
    for end in [x[0], x[5]] {
        assert!(natural.derivatives(end, 2).unwrap()[2].abs() < 1e-12);
    }
    for (t, v) in x.iter().zip(&y) {
        assert!((natural.eval(*t).unwrap() - v).abs() < 1e-13);
    }
    // (7.9): any other C² interpolant bends more.
    let other = interpolate_function(&x, &y, 3).unwrap();
    assert!(bending_energy(&natural) < bending_energy(&other));
}

#[test]
fn seed004_natural_splines_of_even_order() {
    let x = [0.0, 0.4, 1.0, 1.7, 2.0, 3.1, 3.5];
    // Order 6 (quintic): polynomials of degree < q = 3 are natural splines, so reproduced.
    let quad = |t: f64| 2.0 - t + 0.75 * t * t;
    let s = natural_spline(&x, &x.map(quad), 6).unwrap();
    assert_eq!(s.degree(), 5);
    for k in 0..=70 {
        let t = 3.5 * f64::from(k) / 70.0;
        assert!((s.eval(t).unwrap() - quad(t)).abs() < 1e-11);
    }
    // Derivatives q … 2q − 2 vanish at both ends for any data.
    let y = [1.0, -1.0, 0.5, 0.0, 2.0, -0.5, 0.3];
    let s = natural_spline(&x, &y, 6).unwrap();
    for end in [0.0, 3.5] {
        let d = s.derivatives(end, 4).unwrap();
        assert!(d[3].abs() < 1e-9 && d[4].abs() < 1e-8, "{d:?}");
    }
    for (t, v) in x.iter().zip(&y) {
        assert!((s.eval(*t).unwrap() - v).abs() < 1e-12);
    }
    // Order 2: the broken line.
    let s = natural_spline(&x, &y, 2).unwrap();
    assert_eq!(s.degree(), 1);
    assert!((s.eval(0.2).unwrap() - 0.0).abs() < 1e-15); // midway between 1 and −1
}
