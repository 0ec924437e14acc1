//! The normal equations of a large fit assembled in chunks on every core (`parallel`
//! feature) agree with a direct sequential sum over the data to 1e-12 relative, and the
//! Schoenberg–Whitney check still names the basis function left without data.
#![cfg(feature = "parallel")]

use nalgebra::Vector2;
use spline_core::{ErrorKind, KnotVector};
use spline_fit::{LeastSquares, PARALLEL_MIN_POINTS};

fn data(m: usize) -> (Vec<Vector2<f64>>, Vec<f64>, Vec<f64>) {
    let params: Vec<f64> = (0..m).map(|k| k as f64 / (m - 1) as f64).collect();
    let points = params
        .iter()
        .map(|&u| Vector2::new((7.0 * u).sin() + u, (3.0 * u).cos() * u))
        .collect();
    let weights = params.iter().map(|&u| 0.5 + u * u).collect();
    (points, params, weights)
}

#[test]
fn chunked_normal_equations_equal_the_direct_sums() {
    let m = 3 * PARALLEL_MIN_POINTS + 17;
    let (points, params, weights) = data(m);
    for degree in [1, 3, 5] {
        let knots = KnotVector::uniform(degree, 40, 0.0, 1.0).expect("knots");
        let normal = LeastSquares::new(&points, &params, knots.clone())
            .weights(&weights)
            .normal_equations()
            .expect("assembled");
        // Direct sums, point by point, with the basis functions of spline-core.
        let n = knots.num_basis();
        let mut gram = vec![0.0; n * n];
        let mut rhs = vec![Vector2::zeros(); n];
        let mut basis = vec![0.0; degree + 1];
        for ((&u, q), &w) in params.iter().zip(&points).zip(&weights) {
            let span = knots.find_span(u).expect("in the domain");
            knots.basis_values(span, u, &mut basis);
            for a in 0..=degree {
                rhs[span - degree + a] += q * (w * w * basis[a]);
                for b in 0..=degree {
                    gram[(span - degree + a) * n + span - degree + b] +=
                        w * w * basis[a] * basis[b];
                }
            }
        }
        let scale = gram.iter().fold(0.0f64, |s, g| s.max(g.abs()));
        let rhs_scale = rhs.iter().fold(0.0f64, |s, r| s.max(r.amax()));
        for i in 0..n {
            assert!(
                (normal.rhs()[i] - rhs[i]).amax() <= 1e-12 * rhs_scale,
                "rhs {i}"
            );
            for j in i.saturating_sub(degree)..(i + degree + 1).min(n) {
                let d = (normal.gram(i, j) - gram[i * n + j]).abs();
                assert!(
                    d <= 1e-12 * scale,
                    "degree {degree}: G[{i},{j}] off by {d:e}"
                );
            }
        }
        // The solution of the chunked system fits as well as the direct one.
        let fit = LeastSquares::new(&points, &params, knots)
            .weights(&weights)
            .solve()
            .expect("solved");
        assert!(fit.deviation.max < 1e-2, "{}", fit.deviation.max);
    }
}

#[test]
fn chunked_assembly_still_checks_schoenberg_whitney() {
    let m = 2 * PARALLEL_MIN_POINTS;
    let (points, params, _) = data(m);
    // No data in (0.5, 0.7): the basis functions living there have no point.
    let (points, params): (Vec<_>, Vec<_>) = points
        .into_iter()
        .zip(params)
        .filter(|&(_, u)| !(u > 0.5 && u < 0.7))
        .unzip();
    let knots = KnotVector::uniform(3, 40, 0.0, 1.0).expect("knots");
    let err = LeastSquares::new(&points, &params, knots)
        .solve()
        .expect_err("a basis function without data");
    assert_eq!(err.kind(), ErrorKind::SchoenbergWhitney, "{err}");
}

/// Runs `f` on a rayon pool of `threads` threads.
fn on_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
        .install(f)
}

/// Scattered surface data: parameters by a low-discrepancy sequence, a smooth height.
fn scattered(m: usize) -> (Vec<(f64, f64)>, Vec<nalgebra::Vector3<f64>>) {
    let params: Vec<(f64, f64)> = (0..m)
        .map(|k| {
            let k = k as f64;
            (
                (k * 0.618_033_988_749_895).fract(),
                (k * 0.754_877_666_246_693).fract(),
            )
        })
        .collect();
    let points = params
        .iter()
        .map(|&(u, v)| nalgebra::Vector3::new(u, v, (5.0 * u).sin() * (3.0 * v).cos() + u * v))
        .collect();
    (params, points)
}

/// The normal equations of a scattered least-squares surface assembled in one chunk per
/// thread on two threads give the control net of the sequential assembly (one thread) to
/// 1e-10 relative, with and without the thin-plate term: the assembled equations agree to
/// 1e-12 relative (the unit test in `surface.rs`), the solve amplifies that by the
/// system's condition (1.9e-12 seen here).
#[test]
fn chunked_surface_normal_equations_equal_the_sequential_ones() {
    let m = 2 * PARALLEL_MIN_POINTS + 5;
    let (params, points) = scattered(m);
    let ku = KnotVector::uniform(3, 12, 0.0, 1.0).expect("knots");
    let kv = KnotVector::uniform(2, 9, 0.0, 1.0).expect("knots");
    for smoothing in [0.0, 1e-6] {
        let fit = |threads| {
            on_threads(threads, || {
                spline_fit::approximate_surface_scattered(&params, &points, &ku, &kv, smoothing)
                    .expect("fitted")
            })
        };
        let (serial, chunked) = (fit(1), fit(2));
        let scale = serial
            .surface
            .control_points()
            .iter()
            .fold(0.0f64, |s, p| s.max(p.amax()));
        for (a, b) in serial
            .surface
            .control_points()
            .iter()
            .zip(chunked.surface.control_points())
        {
            assert!(
                (a - b).amax() <= 1e-10 * scale,
                "λ = {smoothing}: {a} vs {b}"
            );
        }
        assert!(serial.deviation.max < 1e-2, "{}", serial.deviation.max);
    }
}

/// A grid fit large enough to solve its grid lines on every core: the same net bit for bit
/// (the lines are independent), and a failing line is still named in order.
#[test]
fn grid_surface_lines_in_parallel_equal_the_sequential_ones() {
    let (rows, cols) = (130, 131);
    assert!(rows * cols >= PARALLEL_MIN_POINTS);
    let grid: Vec<nalgebra::Vector3<f64>> = (0..rows)
        .flat_map(|i| {
            (0..cols).map(move |j| {
                let (u, v) = (i as f64 / 129.0, j as f64 / 130.0);
                nalgebra::Vector3::new(u, v, (4.0 * u).sin() * v + (2.0 * v).cos())
            })
        })
        .collect();
    let fit = |threads| {
        on_threads(threads, || {
            spline_fit::approximate_surface_grid(
                &grid,
                rows,
                cols,
                3,
                3,
                20,
                24,
                &spline_fit::Parametrization::Chordal,
                &spline_fit::Parametrization::Chordal,
            )
            .expect("fitted")
        })
    };
    assert_eq!(fit(1), fit(2));
    let interpolated = |threads| {
        on_threads(threads, || {
            spline_fit::interpolate_surface(
                &grid,
                rows,
                cols,
                3,
                3,
                &spline_fit::Parametrization::Chordal,
                &spline_fit::Parametrization::Chordal,
            )
            .expect("interpolated")
        })
    };
    assert_eq!(interpolated(1), interpolated(2));
    // A non-finite point: the error names the first grid column, as sequentially.
    let mut bad = grid.clone();
    bad[5 * cols + 7].z = f64::NAN;
    bad[9 * cols + 3].z = f64::NAN;
    let err = |threads| {
        on_threads(threads, || {
            spline_fit::approximate_surface_grid(
                &bad,
                rows,
                cols,
                3,
                3,
                20,
                24,
                &spline_fit::Parametrization::Uniform,
                &spline_fit::Parametrization::Uniform,
            )
            .expect_err("not finite")
            .to_string()
        })
    };
    assert_eq!(err(1), err(2));
}

#[test]
fn bad_data_is_named_as_the_sequential_checks_name_it() {
    // The data are validated in chunks on every core; a failed chunk falls back to the
    // sequential checks, whose messages name the first bad entry.
    let m = 2 * PARALLEL_MIN_POINTS + 5;
    let (points, params, _) = data(m);
    let knots = KnotVector::uniform(3, 40, 0.0, 1.0).expect("knots");
    let fit = |points: &[Vector2<f64>], params: &[f64]| {
        on_threads(2, || {
            LeastSquares::new(points, params, knots.clone())
                .control_points()
                .map(|_| ())
        })
    };
    assert!(fit(&points, &params).is_ok());
    let mut outside = params.clone();
    // The last parameter, so that they stay sorted.
    outside[m - 1] = 2.0;
    let e = fit(&points, &outside).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::OutOfDomain);
    assert!(
        e.to_string().contains(&format!("parameter {}", m - 1)),
        "{e}"
    );
    let mut unsorted = params.clone();
    // Across the boundary of two chunks (of at least 4096 parameters).
    unsorted.swap(4 * 4096 - 1, 4 * 4096);
    let e = fit(&points, &unsorted).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::UnsortedKnots, "{e}");
    let mut nan_point = points.clone();
    nan_point[20_000].y = f64::NAN;
    let e = fit(&nan_point, &params).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    assert!(e.to_string().contains("data point 20000"), "{e}");
    let mut nan_param = params.clone();
    nan_param[30_000] = f64::NAN;
    let e = fit(&points, &nan_param).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    assert!(e.to_string().contains("parameter 30000"), "{e}");

    let (pairs, values) = scattered(m);
    let surface = |pairs: &[(f64, f64)]| {
        on_threads(2, || {
            spline_fit::approximate_surface_scattered(pairs, &values, &knots, &knots, 0.0)
                .map(|_| ())
        })
    };
    assert!(surface(&pairs).is_ok());
    let mut bad = pairs.clone();
    bad[m - 10].1 = f64::NAN;
    let e = surface(&bad).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    assert!(e.to_string().contains(&format!("point {}", m - 10)), "{e}");
}
