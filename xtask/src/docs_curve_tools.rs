//! Pictures of the curve tools: an offset family with its cusps, intersections marked, a
//! smoothing spline with λ chosen by generalised cross-validation, a closed contour smoothed by
//! the eraser.

use nalgebra::Vector2;
use spline::algebra::{intersect_curves, offset_cusps, self_intersections};
use spline::fit::{
    Parametrization, SmoothingParameter, least_squares_periodic, offset_curve, parametrize,
    smoothing_spline,
};
use spline::geom::{BSpline, Curve2, PeriodicBSpline};
use spline::io::svg::SvgPlot;
use spline::shape::{SmoothingOptions, smooth};
use std::path::Path;

fn wave() -> Result<Curve2, String> {
    BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0],
        vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(0.5, 1.0),
            Vector2::new(1.2, -0.6),
            Vector2::new(2.0, 0.9),
            Vector2::new(2.7, -0.4),
            Vector2::new(3.2, 0.5),
        ],
    )
    .map_err(|e| e.to_string())
}

fn points(curve: &Curve2) -> Result<Vec<Vector2<f64>>, String> {
    curve
        .eval_many(&spline::ParamCurve::sample_params(curve, 80))
        .map_err(|e| e.to_string())
}

/// Writes the pictures into `out`.
pub(crate) fn render(out: &Path) -> Result<(), String> {
    // An offset family on both sides; beyond the radius of curvature the offsets turn back
    // at cusps (κ d = 1), marked.
    let curve = wave()?;
    let mut plot = SvgPlot::new();
    plot.set_title("Offsets at d = ±0.1 … ±0.4 within 1e-6, cusps (κ d = 1) marked");
    plot.add_curve(&curve);
    let mut cusp_points = Vec::new();
    for k in 1..=4 {
        for side in [1.0, -1.0] {
            let d = side * 0.1 * f64::from(k);
            let cusps = offset_cusps(&curve, d, 1e-12).map_err(|e| e.to_string())?;
            let at: Vec<f64> = cusps
                .iter()
                .filter(|c| c.sign_change)
                .map(|c| c.u)
                .collect();
            let fit = offset_curve(&curve, d, 3, 1e-6, &at).map_err(|e| e.to_string())?;
            plot.add_polyline(
                &points(&fit.curve)?,
                if side > 0.0 { "curve2" } else { "curve3" },
            );
            cusp_points.extend(cusps.iter().map(|c| c.point));
        }
    }
    plot.add_markers(&cusp_points, "inflection");
    crate::docs_output::write_doc(out, "offsets.svg", &plot.render())?;

    // Intersections of the wave with a loop, and the loop's self-intersection.
    let other = BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(0.2, -0.8),
            Vector2::new(3.5, 1.2),
            Vector2::new(0.8, 1.4),
            Vector2::new(2.4, -1.0),
            Vector2::new(3.1, -0.3),
        ],
    )
    .map_err(|e| e.to_string())?;
    let mut plot = SvgPlot::new();
    plot.set_title("All intersections (red) and self-intersections (green), refined to 1e-12");
    plot.add_curve(&curve);
    plot.add_curve_styled(&other, "curve2");
    let hits = intersect_curves(&curve, &other, 1e-9).map_err(|e| e.to_string())?;
    plot.add_markers(
        &hits.points.iter().map(|h| h.point).collect::<Vec<_>>(),
        "inflection",
    );
    let loops = self_intersections(&other, 1e-9).map_err(|e| e.to_string())?;
    plot.add_markers(
        &loops.points.iter().map(|h| h.point).collect::<Vec<_>>(),
        "extremum",
    );
    crate::docs_output::write_doc(out, "intersections.svg", &plot.render())?;

    // Noisy samples of sin(2πx) smoothed with λ by generalised cross-validation.
    let n = 120;
    let x: Vec<f64> = (0..n).map(|i| f64::from(i) / f64::from(n - 1)).collect();
    // A fixed pseudo-random noise (a linear congruential sequence), amplitude 0.25.
    let mut state: u64 = 12345;
    let y: Vec<f64> = x
        .iter()
        .map(|t| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let r = (state >> 11) as f64 / (1u64 << 53) as f64;
            (std::f64::consts::TAU * t).sin() + 0.5 * (r - 0.5)
        })
        .collect();
    let fit = smoothing_spline(&x, &y, None, SmoothingParameter::Gcv).map_err(|e| e.to_string())?;
    let mut plot = SvgPlot::new();
    plot.set_title(format!(
        "Smoothing spline (red), λ = {:.3e} by GCV as scipy's make_smoothing_spline; sin 2πx grey; x drawn 3×",
        fit.lambda
    ));
    let data: Vec<Vector2<f64>> = x
        .iter()
        .zip(&y)
        .map(|(&a, &b)| Vector2::new(3.0 * a, b))
        .collect();
    plot.add_markers(&data, "extremum");
    let us: Vec<f64> = (0..=400).map(|i| f64::from(i) / 400.0).collect();
    let smooth: Vec<Vector2<f64>> = us
        .iter()
        .map(|&u| fit.spline.eval(u).map(|v| Vector2::new(3.0 * u, v)))
        .collect::<Result<_, _>>()
        .map_err(|e| e.to_string())?;
    plot.add_polyline(&smooth, "curve2");
    let truth: Vec<Vector2<f64>> = us
        .iter()
        .map(|&u| Vector2::new(3.0 * u, (std::f64::consts::TAU * u).sin()))
        .collect();
    plot.add_polyline(&truth, "axis");
    crate::docs_output::write_doc(out, "smoothing_gcv.svg", &plot.render())?;
    closed_contour(out)
}

/// A wobbly closed contour: its periodic least-squares fit (left, curvature comb with every
/// wiggle) and the eraser's closed curve with four curvature extrema (right).
fn closed_contour(out: &Path) -> Result<(), String> {
    let err = |e: spline::core::Error| e.to_string();
    let count = 120;
    let points: Vec<Vector2<f64>> = (0..count)
        .map(|k| {
            let t = 0.3 + std::f64::consts::TAU * f64::from(k) / f64::from(count);
            let r = 1.0 + 0.04 * (7.0 * t).sin();
            Vector2::new(1.6 * r * t.cos(), r * t.sin())
        })
        .collect();
    let mut options = SmoothingOptions::new(24);
    options.closed = true;
    options.extrema = ["min", "max", "min", "max"]
        .iter()
        .map(|k| k.parse())
        .collect::<Result<_, _>>()
        .map_err(err)?;
    let smoothed = smooth(&points, &options).map_err(err)?;
    // The periodic least-squares fit of the same size, for comparison.
    let params = {
        let mut closed = points.clone();
        closed.push(points[0]);
        let mut u = parametrize(&closed, &Parametrization::Centripetal).map_err(err)?;
        u.pop();
        u
    };
    let knots: Vec<f64> = (0..24).map(|i| f64::from(i) / 24.0).collect();
    let space = PeriodicBSpline::new(3, knots, 1.0, vec![Vector2::zeros(); 24]).map_err(err)?;
    let fit = least_squares_periodic(&points, &params, &space, None, 0.0).map_err(err)?;
    let shift = Vector2::new(-4.4, 0.0);
    let moved_fit = fit
        .open_at(0.0)
        .map_err(err)?
        .map_control_points(|p| p + shift);
    let moved_points: Vec<Vector2<f64>> = points.iter().map(|p| p + shift).collect();
    let mut plot = SvgPlot::new();
    plot.set_title(format!(
        "Closed contour: least squares (left, {} curvature extrema), eraser with 4 (right, deviation {:.2})",
        smoothed.start_extrema,
        smoothed.deviation.to_curve.max
    ));
    plot.add_curvature_comb(&moved_fit, 400);
    plot.add_curve(&moved_fit);
    plot.add_markers(&moved_points, "data");
    plot.add_curvature_comb(&smoothed.curve, 400);
    plot.add_curve(&smoothed.curve);
    plot.add_markers(&points, "data");
    let extrema: Vec<Vector2<f64>> = smoothed.extrema.iter().map(|e| e.point).collect();
    plot.add_markers(&extrema, "extremum");
    crate::docs_output::write_doc(out, "closed_smoothing.svg", &plot.render())
}
