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
