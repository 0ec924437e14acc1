//! The main job: fit and smooth an airfoil shipped in `data/airfoils/`, print the result and
//! write `docs/airfoil.svg`.
//!
//! 1. Read the UIUC coordinates (Selig order: trailing edge, upper surface, nose, lower
//!    surface, trailing edge).
//! 2. Least squares (chord-length parameters, knots by The NURBS Book (9.68)), then the
//!    parameter correction of seed 003: the best curve of that size, which still wiggles —
//!    its curvature has many extrema.
//! 3. The selective eraser of curvature extrema (thesis ch. 6): the closest curve whose
//!    curvature has a single maximum, at the nose.
//! 4. Report deviations (closest-point distances to the data) and curvature features, and
//!    draw both curves and their curvature graphs.

use nalgebra::Vector2;
use spline::algebra::planar_features;
use spline::fit::{
    CorrectionOptions, LeastSquares, Parametrization, closest_point, correct_parameters,
    nurbs_book_knots, parametrize,
};
use spline::geom::Curve2;
use spline::geom::exchange::parse_points;
use spline::geom::export::SvgPlot;
use spline::shape::{SmoothingOptions, smooth};
use std::path::Path;

const AIRFOIL: &str = "clarkv";
const CONTROL_POINTS: usize = 20;

fn closest_distances(curve: &Curve2, points: &[Vector2<f64>]) -> Result<(f64, f64), String> {
    let mut max = 0.0f64;
    let mut sum = 0.0;
    for p in points {
        let d = closest_point(curve, *p)
            .map_err(|e| e.to_string())?
            .distance;
        max = max.max(d);
        sum += d * d;
    }
    Ok((max, (sum / points.len() as f64).sqrt()))
}

/// Runs the demonstration.
pub(crate) fn run(root: &Path) -> Result<(), String> {
    let started = std::time::Instant::now();
    let path = root.join("data/airfoils").join(format!("{AIRFOIL}.dat"));
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let points: Vec<Vector2<f64>> = parse_points(&text)
        .map_err(|e| e.to_string())?
        .into_iter()
        .map(|p| Vector2::new(p[0], p[1]))
        .collect();
    println!(
        "airfoil {AIRFOIL}: {} points from {}",
        points.len(),
        path.display()
    );

    // Least squares with parameter correction.
    let params = parametrize(&points, &Parametrization::Chordal).map_err(|e| e.to_string())?;
    let knots = nurbs_book_knots(3, CONTROL_POINTS, &params).map_err(|e| e.to_string())?;
    let problem = LeastSquares::new(&points, &params, knots);
    let (fit, report) =
        correct_parameters(&problem, &CorrectionOptions::default()).map_err(|e| e.to_string())?;
    let least_squares = fit.curve;
    let ls_features = planar_features(&least_squares, 1e-10).map_err(|e| e.to_string())?;
    let (ls_max, ls_rms) = closest_distances(&least_squares, &points)?;
    println!(
        "least squares, cubic, {CONTROL_POINTS} control points, parameter correction ({} sweeps): max deviation {:.2} mm, rms {:.2} mm (chord 1 m); {} curvature extrema, {} inflections",
        report.iterations,
        ls_max * 1e3,
        ls_rms * 1e3,
        ls_features.curvature_extrema.len(),
        ls_features.inflections.len()
    );

    // The eraser: one curvature maximum, at the nose.
    let smoothed =
        smooth(&points, &SmoothingOptions::new(CONTROL_POINTS)).map_err(|e| e.to_string())?;
    let nose = smoothed.extrema[0].point;
    println!(
        "smoothed (selective eraser, thesis ch. 6): max deviation {:.2} mm at data point {} (curve to data {:.2} mm), rms {:.2} mm; {} curvature extremum at u = {:.4} (x = {:.4}, y = {:.4}), {} inflection(s)",
        smoothed.deviation.to_curve.max * 1e3,
        smoothed.deviation.to_curve.max_index,
        smoothed.deviation.to_data * 1e3,
        smoothed.deviation.to_curve.rms * 1e3,
        smoothed.extrema.len(),
        smoothed.extrema[0].param,
        nose.x,
        nose.y,
        smoothed.inflections.len(),
    );
    println!("smoothed curve (exchange format):");
    println!(
        "{}",
        serde_json::to_string(&smoothed.curve).map_err(|e| e.to_string())?
    );

    let mut plot = SvgPlot::new();
    plot.set_width(1200.0);
    plot.set_title(format!(
        "{AIRFOIL}: data (orange), least squares (red, {} curvature extrema), smoothed (blue, 1 extremum, green dot)",
        ls_features.curvature_extrema.len()
    ));
    plot.add_curve_styled(&least_squares, "curve2");
    plot.add_curve(&smoothed.curve);
    plot.add_markers(&points, "data");
    plot.add_markers(&[nose], "extremum");
    let out = root.join("docs/airfoil.svg");
    std::fs::write(&out, plot.render()).map_err(|e| format!("{}: {e}", out.display()))?;

    // Signed curvature along the curve, on an asinh scale so that the nose (κ ≈ 10²) and the
    // flat parts (κ ≈ 10⁻¹) are both readable.
    let mut graph = SvgPlot::new();
    graph.set_width(1200.0);
    graph.set_title(
        "asinh(κ)/8 against the parameter: least squares (red) wiggles; smoothed (blue) rises to one maximum at the nose, then falls",
    );
    for (curve, class) in [(&least_squares, "curve2"), (&smoothed.curve, "curve")] {
        let samples: Vec<Vector2<f64>> = (0..=2000)
            .filter_map(|i| {
                let u = f64::from(i) / 2000.0;
                curve
                    .signed_curvature(u)
                    .ok()
                    .map(|k| Vector2::new(u, k.asinh() / 8.0))
            })
            .collect();
        graph.add_polyline(&samples, class);
    }
    graph.add_polyline(&[Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)], "axis");
    let curvature_out = root.join("docs/airfoil_curvature.svg");
    std::fs::write(&curvature_out, graph.render())
        .map_err(|e| format!("{}: {e}", curvature_out.display()))?;
    println!("curvature graph: {}", curvature_out.display());
    println!(
        "picture: {} ({:.1} s)",
        out.display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
