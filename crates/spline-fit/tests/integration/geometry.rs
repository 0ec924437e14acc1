//! Closest points, closed curves, end derivatives, surfaces, smoothing, other scalars.

#![allow(clippy::needless_range_loop, clippy::cast_lossless)]

use nalgebra::{Vector2, Vector3};
use num_dual::Dual64;
use spline_core::KnotVector;
use spline_fit::{
    InterpolationOptions, KnotChoice, LeastSquares, LsqMethod, Parametrization,
    approximate_surface_grid, approximate_surface_scattered, closest_point, interpolate,
    interpolate_closed, interpolate_with_knots, natural_cubic,
};
use spline_geom::BSpline;

fn v(x: f64, y: f64) -> Vector2<f64> {
    Vector2::new(x, y)
}

/// Brute force: the closest of a million samples, refined by ternary search around it.
fn brute_force(curve: &BSpline<f64, Vector2<f64>>, q: Vector2<f64>) -> f64 {
    let (a, b) = curve.domain();
    let m = 200_000;
    let h = (b - a) / f64::from(m);
    let mut best = (f64::INFINITY, a);
    for k in 0..=m {
        let t = a + h * f64::from(k);
        let d = (curve.eval(t).unwrap() - q).norm();
        if d < best.0 {
            best = (d, t);
        }
    }
    let (mut lo, mut hi) = ((best.1 - h).max(a), (best.1 + h).min(b));
    for _ in 0..200 {
        let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if (curve.eval(m1).unwrap() - q).norm() < (curve.eval(m2).unwrap() - q).norm() {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    (curve.eval(0.5 * (lo + hi)).unwrap() - q).norm()
}

#[test]
fn closest_point_near_a_cusp_and_far_away() {
    // A planar cubic with a cusp: control polygon folding back on itself, C'(0.5) = 0.
    let cusp = BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        vec![v(0.0, 0.0), v(1.0, 1.0), v(0.0, 1.0), v(1.0, 0.0)],
    )
    .unwrap();
    let d = cusp.derivatives(0.5, 1).unwrap()[1];
    assert!(d.norm() < 1e-12, "cusp at 0.5: {d}");
    let tip = cusp.eval(0.5).unwrap();
    let targets = [
        tip,
        tip + v(1e-7, 0.0),
        tip + v(0.0, 0.01),
        tip + v(-0.05, 0.02),
        v(0.5, 0.5),
        v(100.0, -50.0),
        v(-1e6, 3e6),
        v(0.2, 0.1),
    ];
    for q in targets {
        let hit = closest_point(&cusp, q).unwrap();
        let reference = brute_force(&cusp, q);
        assert!(
            hit.distance <= reference * (1.0 + 1e-12) + 1e-13,
            "{q}: {} vs brute force {reference}",
            hit.distance
        );
        assert!((hit.point - cusp.eval(hit.param).unwrap()).norm() < 1e-12);
        assert!(((hit.point - q).norm() - hit.distance).abs() < 1e-9);
    }
    assert!(closest_point(&cusp, tip).unwrap().distance < 1e-12);
}

#[test]
fn closest_point_on_a_circle_like_curve_and_a_spiral() {
    // Interpolated circle: the closest point to an outside point is along the ray.
    let pts: Vec<Vector2<f64>> = (0..16)
        .map(|k| {
            let a = std::f64::consts::TAU * f64::from(k) / 16.0;
            v(a.cos(), a.sin())
        })
        .collect();
    let circle = interpolate_closed(&pts, 3, &Parametrization::Chordal)
        .unwrap()
        .curve;
    for angle in [0.1f64, 1.0, 2.5, 4.0, 6.0] {
        let q = v(3.0 * angle.cos(), 3.0 * angle.sin());
        let hit = closest_point(&circle, q).unwrap();
        let bf = brute_force(&circle, q);
        assert!(
            (hit.distance - bf).abs() < 1e-10,
            "{} {} {}",
            hit.distance,
            bf,
            hit.param
        );
        let dir = hit.point.normalize();
        assert!((dir - q.normalize()).norm() < 1e-3);
        // First-order optimality: the residual is orthogonal to the tangent.
        let tangent = circle.derivatives(hit.param, 1).unwrap()[1];
        assert!((q - hit.point).dot(&tangent).abs() < 1e-9 * tangent.norm() * hit.distance);
    }
}

#[test]
fn closed_interpolation_is_periodic_for_odd_and_even_degrees() {
    let pts = [
        v(2.0, 0.0),
        v(0.5, 1.0),
        v(-1.0, 0.7),
        v(-1.5, -0.5),
        v(0.3, -1.2),
        v(1.4, -0.6),
    ];
    for degree in 1..=5 {
        for kind in [
            Parametrization::Uniform,
            Parametrization::Chordal,
            Parametrization::Centripetal,
        ] {
            let fit = interpolate_closed(&pts, degree, &kind).unwrap();
            assert!(
                fit.deviation.max < 1e-12,
                "degree {degree}: {}",
                fit.deviation.max
            );
            let (a, b) = fit.curve.domain();
            let start = fit.curve.derivatives(a, degree - 1).unwrap();
            let end = fit.curve.derivatives(b, degree - 1).unwrap();
            for k in 0..degree {
                let scale = start[k].norm().max(1.0);
                assert!(
                    (start[k] - end[k]).norm() < 1e-9 * scale,
                    "degree {degree} C^{k}"
                );
            }
            let cp = fit.curve.control_points();
            for k in 0..degree {
                assert_eq!(cp[k], cp[pts.len() + k]);
            }
        }
    }
}

#[test]
fn end_derivatives_are_met() {
    let pts = [
        v(0.0, 0.0),
        v(1.0, 2.0),
        v(3.0, 2.5),
        v(4.0, 0.0),
        v(6.0, 1.0),
    ];
    for degree in 2..=4 {
        let options = InterpolationOptions {
            start_derivative: Some(v(5.0, 0.0)),
            end_derivative: Some(v(0.0, -4.0)),
            ..InterpolationOptions::default()
        };
        let fit = interpolate(&pts, degree, &options).unwrap();
        assert_eq!(fit.curve.control_points().len(), 7);
        assert!(fit.deviation.max < 1e-12);
        let d0 = fit.curve.derivatives(0.0, 1).unwrap()[1];
        let d1 = fit.curve.derivatives(1.0, 1).unwrap()[1];
        assert!((d0 - v(5.0, 0.0)).norm() < 1e-10, "{d0}");
        assert!((d1 - v(0.0, -4.0)).norm() < 1e-10, "{d1}");
        // The NURBS Book (9.22) knots when both are given.
        let u = &fit.params;
        let k = fit.curve.knots().knots();
        let p = degree;
        for j in 0..=(u.len() - 1 - p + 1) {
            let mean: f64 = u[j..j + p].iter().sum::<f64>() / p as f64;
            assert!((k[j + p + 1] - mean).abs() < 1e-14);
        }
    }
    // Only one end.
    let options = InterpolationOptions {
        end_derivative: Some(v(1.0, 1.0)),
        ..InterpolationOptions::default()
    };
    let fit = interpolate(&pts, 3, &options).unwrap();
    assert_eq!(fit.curve.control_points().len(), 6);
    assert!((fit.curve.derivatives(1.0, 1).unwrap()[1] - v(1.0, 1.0)).norm() < 1e-10);
}

#[test]
fn least_squares_variants() {
    let params: Vec<f64> = (0..=60).map(|k| f64::from(k) / 60.0).collect();
    let pts: Vec<Vector2<f64>> = params
        .iter()
        .map(|&t| v(t + 0.1 * (9.0 * t).sin(), (5.0 * t).cos()))
        .collect();
    let knots = spline_fit::nurbs_book_knots(3, 12, &params).unwrap();
    let free = LeastSquares::new(&pts, &params, knots.clone())
        .solve()
        .unwrap();
    let qr = LeastSquares::new(&pts, &params, knots.clone())
        .method(LsqMethod::Qr)
        .solve()
        .unwrap();
    for (a, b) in free
        .curve
        .control_points()
        .iter()
        .zip(qr.curve.control_points())
    {
        assert!((a - b).norm() < 1e-10);
    }
    // Pinned ends interpolate the end points and cost a little accuracy.
    let pinned = LeastSquares::new(&pts, &params, knots.clone())
        .pin_ends()
        .solve()
        .unwrap();
    let cp = pinned.curve.control_points();
    assert_eq!((cp[0], cp[cp.len() - 1]), (pts[0], pts[60]));
    assert!((pinned.curve.eval(1.0).unwrap() - pts[60]).norm() < 1e-15);
    assert!(pinned.deviation.sum_squares >= free.deviation.sum_squares);
    // Smoothing lowers the bending energy and raises the residual, monotonically in λ.
    let energy = |c: &BSpline<f64, Vector2<f64>>| -> f64 {
        (0..=2000)
            .map(|k| c.derivatives(f64::from(k) / 2000.0, 2).unwrap()[2].norm_squared())
            .sum::<f64>()
            / 2001.0
    };
    let mut last = (energy(&free.curve), free.deviation.sum_squares);
    for lambda in [1e-6, 1e-4, 1e-2] {
        for method in [LsqMethod::NormalEquations, LsqMethod::Qr] {
            let s = LeastSquares::new(&pts, &params, knots.clone())
                .smoothing(lambda)
                .method(method)
                .solve()
                .unwrap();
            let e = energy(&s.curve);
            assert!(
                e < last.0 && s.deviation.sum_squares > last.1,
                "λ = {lambda}"
            );
            if method == LsqMethod::Qr {
                last = (e, s.deviation.sum_squares);
            }
        }
    }
    // The report names the worst point.
    let worst = free
        .deviation
        .distances
        .iter()
        .enumerate()
        .fold((0, 0.0), |m, (k, &d)| if d > m.1 { (k, d) } else { m });
    assert_eq!(free.deviation.max_index, worst.0);
    let rms = (free.deviation.distances.iter().map(|d| d * d).sum::<f64>() / 61.0).sqrt();
    assert!((free.deviation.rms - rms).abs() < 1e-15);
}

#[test]
fn surfaces_from_grids_and_scattered_points() {
    let f = |u: f64, w: f64| (2.0 * u).sin() * (1.0 + w * w);
    let (rows, cols) = (25, 30);
    let grid: Vec<Vector3<f64>> = (0..rows)
        .flat_map(|k| {
            (0..cols).map(move |l| {
                let (u, w) = (k as f64 / (rows - 1) as f64, l as f64 / (cols - 1) as f64);
                Vector3::new(u, w, f(u, w))
            })
        })
        .collect();
    let fit = approximate_surface_grid(
        &grid,
        rows,
        cols,
        3,
        3,
        8,
        9,
        &Parametrization::Chordal,
        &Parametrization::Chordal,
    )
    .unwrap();
    assert_eq!(fit.surface.control_points().len(), 72);
    assert!(fit.deviation.max < 5e-3, "{}", fit.deviation.max);
    // The two passes solve the tensor-product least-squares problem exactly: compare with
    // the dense solution A_u⁺ Q (A_v⁺)ᵀ.
    let dense = |k: &KnotVector<f64>, params: &[f64]| {
        let rows: Vec<Vec<f64>> = params.iter().map(|&t| k.dense_basis(t).unwrap()).collect();
        nalgebra::DMatrix::from_fn(rows.len(), rows[0].len(), |i, j| rows[i][j])
    };
    let au = dense(fit.surface.knots_u(), &fit.params_u);
    let av = dense(fit.surface.knots_v(), &fit.params_v);
    let pinv =
        |a: &nalgebra::DMatrix<f64>| (a.transpose() * a).try_inverse().unwrap() * a.transpose();
    let (pu, pv) = (pinv(&au), pinv(&av));
    for c in 0..3 {
        let q = nalgebra::DMatrix::from_fn(rows, cols, |k, l| grid[k * cols + l][c]);
        let x = &pu * q * pv.transpose();
        for i in 0..8 {
            for j in 0..9 {
                let got = fit.surface.control_points()[i * 9 + j][c];
                assert!((got - x[(i, j)]).abs() < 1e-9, "({i}, {j}) coordinate {c}");
            }
        }
    }
    // Scattered points on [0, 1]² (a deterministic low-discrepancy set).
    let count = 600;
    let uv: Vec<(f64, f64)> = (0..count)
        .map(|k| {
            let k = k as f64;
            ((k * 0.618_033_988_7).fract(), (k * 0.754_877_666_2).fract())
        })
        .collect();
    let pts: Vec<f64> = uv.iter().map(|&(u, w)| f(u, w)).collect();
    let ku = KnotVector::clamped_uniform(3, 7, 0.0, 1.0).unwrap();
    let kv = KnotVector::clamped_uniform(2, 6, 0.0, 1.0).unwrap();
    let s = approximate_surface_scattered(&uv, &pts, &ku, &kv, 0.0).unwrap();
    assert!(s.deviation.max < 5e-3, "{}", s.deviation.max);
    // A polynomial in the spline space is reproduced exactly.
    let g = |u: f64, w: f64| 1.0 + u * u * u - u * w * w;
    let gp: Vec<f64> = uv.iter().map(|&(u, w)| g(u, w)).collect();
    let s = approximate_surface_scattered(&uv, &gp, &ku, &kv, 0.0).unwrap();
    assert!(s.surface.eval(0.37, 0.81).unwrap() - g(0.37, 0.81) < 1e-11);
    assert!(s.deviation.max < 1e-11);
    // Data in one corner only: singular without smoothing, fine with it.
    let corner: Vec<(f64, f64)> = uv.iter().map(|&(u, w)| (0.3 * u, 0.3 * w)).collect();
    let e = approximate_surface_scattered(&corner, &pts, &ku, &kv, 0.0).unwrap_err();
    assert_eq!(e.kind(), spline_core::ErrorKind::SingularSystem);
    assert!(e.message().contains("control point ("), "{e}");
    assert!(approximate_surface_scattered(&corner, &pts, &ku, &kv, 1e-4).is_ok());
}

#[test]
fn works_in_f32() {
    let x: Vec<f32> = (0..20).map(|k| k as f32 / 19.0).collect();
    let y: Vec<f32> = x.iter().map(|t| (3.0 * t).sin()).collect();
    let s: BSpline<f32, f32> = natural_cubic(&x, &y).unwrap();
    for (t, v) in x.iter().zip(&y) {
        assert!((s.eval(*t).unwrap() - v).abs() < 1e-5);
    }
    let pts: Vec<Vector2<f32>> = x
        .iter()
        .zip(&y)
        .map(|(&a, &b)| Vector2::new(a, b))
        .collect();
    let fit = interpolate(&pts, 3, &InterpolationOptions::default()).unwrap();
    assert!(fit.deviation.max < 1e-5);
}

#[test]
fn dual_numbers_give_exact_sensitivities_of_the_control_points() {
    // d(control points)/d(y_3) by dual numbers equals a finite difference.
    let x = [0.0, 0.3, 0.45, 0.7, 1.0];
    let y = [0.2, -0.4, 0.1, 0.9, 0.0];
    let knots = KnotVector::averaging(3, &x).unwrap();
    let xd: Vec<Dual64> = x.iter().map(|&t| Dual64::from_re(t)).collect();
    let kd = KnotVector::averaging(3, &xd).unwrap();
    let yd: Vec<Dual64> = y
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            if k == 3 {
                Dual64::from_re(t).derivative()
            } else {
                Dual64::from_re(t)
            }
        })
        .collect();
    let sd = interpolate_with_knots(&kd, &xd, &yd).unwrap();
    let h = 1e-6;
    let mut yp = y;
    yp[3] += h;
    let mut ym = y;
    ym[3] -= h;
    let sp = interpolate_with_knots(&knots, &x, &yp).unwrap();
    let sm = interpolate_with_knots(&knots, &x, &ym).unwrap();
    for i in 0..5 {
        let fd = (sp.control_points()[i] - sm.control_points()[i]) / (2.0 * h);
        let ad = sd.control_points()[i].eps;
        assert!((fd - ad).abs() < 1e-7, "{i}: {fd} vs {ad}");
        assert!(
            (sd.control_points()[i].re - (sp.control_points()[i] + sm.control_points()[i]) / 2.0)
                .abs()
                < 1e-9
        );
    }
    // Least squares and the knot choice: unused variants stay available for duals too.
    let lsq = LeastSquares::new(
        &yd,
        &xd,
        KnotVector::bezier(2, Dual64::from_re(0.0), Dual64::from_re(1.0)).unwrap(),
    )
    .solve()
    .unwrap();
    assert!(lsq.deviation.max.re.is_finite());
    let _ = KnotChoice::<f64>::Averaging;
}

#[test]
fn high_degrees_match_dense_solutions() {
    // Degrees above the unrolled kernels (≤ 5) and the small-array basis (< 8) take the
    // general paths: compare with dense systems solved by nalgebra.
    for degree in [6usize, 7, 9] {
        let m = 14;
        let params: Vec<f64> = (0..m)
            .map(|k| (k as f64 / (m - 1) as f64).powf(1.3))
            .collect();
        let y: Vec<f64> = params.iter().map(|&t| (4.0 * t).sin() + t).collect();
        let knots = KnotVector::averaging(degree, &params).unwrap();
        let f = interpolate_with_knots(&knots, &params, &y).unwrap();
        let a = nalgebra::DMatrix::from_fn(m, m, |i, j| knots.dense_basis(params[i]).unwrap()[j]);
        let x = a
            .clone()
            .lu()
            .solve(&nalgebra::DVector::from_column_slice(&y))
            .unwrap();
        for i in 0..m {
            assert!(
                (f.control_points()[i] - x[i]).abs() < 1e-8 * x[i].abs().max(1.0),
                "degree {degree}"
            );
        }
        // Least squares with fewer control points.
        let n = degree + 3;
        let dense: Vec<f64> = (0..60).map(|k| k as f64 / 59.0).collect();
        let z: Vec<f64> = dense.iter().map(|&t| (3.0 * t).cos()).collect();
        let kn = spline_fit::nurbs_book_knots(degree, n, &dense).unwrap();
        let fit = LeastSquares::new(&z, &dense, kn.clone()).solve().unwrap();
        let b = nalgebra::DMatrix::from_fn(60, n, |i, j| kn.dense_basis(dense[i]).unwrap()[j]);
        let sol = (b.transpose() * &b)
            .lu()
            .solve(&(b.transpose() * nalgebra::DVector::from_column_slice(&z)))
            .unwrap();
        for i in 0..n {
            assert!(
                (fit.curve.control_points()[i] - sol[i]).abs() < 1e-7 * sol[i].abs().max(1.0),
                "lsq degree {degree}"
            );
        }
    }
}
