//! The main job: fit and smooth an airfoil shipped in `data/airfoils/`, print the result and
//! draw it.
//!
//! 1. Read the UIUC coordinates (Selig order: trailing edge, upper surface, nose, lower
//!    surface, trailing edge).
//! 2. Least squares (chord-length parameters, knots by The NURBS Book (9.68)) with the
//!    parameter correction of seed 003: the best curve of that size, which still wiggles —
//!    its curvature has many extrema.
//! 3. The selective eraser of curvature extrema (thesis ch. 6): the closest curve whose
//!    curvature has a single maximum, at the nose.
//! 4. Report deviations both ways and the curvature features (checked by dense sampling),
//!    and draw both curves and their curvature graphs.
//!
//! `cargo xtask demo` writes its pictures under `target/demo/` (the work tree stays clean);
//! `cargo xtask docs` writes the same pictures into `docs/`.

use nalgebra::Vector2;
use spline::algebra::planar_features;
use spline::fit::{
    CorrectionOptions, LeastSquares, Parametrization, correct_parameters, nurbs_book_knots,
    parametrize, two_sided_deviation,
};
use spline::geom::Curve2;
use spline::io::airfoil::parse_airfoil;
use spline::io::svg::SvgPlot;
use spline::shape::{SmoothedCurve, SmoothingOptions, sampled_curvature_extrema, smooth};
use std::path::Path;

const AIRFOIL: &str = "clarkv";
const CONTROL_POINTS: usize = 20;

/// The least-squares fit with parameter correction and the smoothed curve of the demo.
struct Demo {
    points: Vec<Vector2<f64>>,
    least_squares: Curve2<f64>,
    sweeps: usize,
    smoothed: SmoothedCurve,
}

fn compute(root: &Path) -> Result<Demo, String> {
    let path = root.join("data/airfoils").join(format!("{AIRFOIL}.dat"));
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let points = parse_airfoil(&text).map_err(|e| e.to_string())?.points;
    let params = parametrize(&points, &Parametrization::Chordal).map_err(|e| e.to_string())?;
    let knots = nurbs_book_knots(3, CONTROL_POINTS, &params).map_err(|e| e.to_string())?;
    let problem = LeastSquares::new(&points, &params, knots);
    let (fit, report) =
        correct_parameters(&problem, &CorrectionOptions::default()).map_err(|e| e.to_string())?;
    let smoothed =
        smooth(&points, &SmoothingOptions::new(CONTROL_POINTS)).map_err(|e| e.to_string())?;
    Ok(Demo {
        points,
        least_squares: fit.curve,
        sweeps: report.iterations,
        smoothed,
    })
}

/// Draws the two curves over the data, and their curvature graphs, into `out`.
fn draw(demo: &Demo, ls_extrema: usize, out: &Path) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let mut plot = SvgPlot::new();
    plot.set_width(1200.0);
    plot.set_title(format!(
        "{AIRFOIL}: data (orange), least squares (red, {ls_extrema} curvature extrema), smoothed (blue, 1 extremum, green dot)"
    ));
    plot.add_curve_styled(&demo.least_squares, "curve2");
    plot.add_curve(&demo.smoothed.curve);
    plot.add_markers(&demo.points, "data");
    let nose: Vec<Vector2<f64>> = demo.smoothed.extrema.iter().map(|e| e.point).collect();
    plot.add_markers(&nose, "extremum");
    crate::docs_output::write_doc(out, "airfoil.svg", &plot.render())?;
    // Signed curvature along the curve, on an asinh scale so that the nose (κ ≈ 10²) and the
    // flat parts (κ ≈ 10⁻¹) are both readable.
    let mut graph = SvgPlot::new();
    graph.set_width(1200.0);
    graph.set_title(
        "asinh(κ)/8 against the parameter: least squares (red) wiggles; smoothed (blue) rises to one maximum at the nose, then falls",
    );
    for (curve, class) in [
        (&demo.least_squares, "curve2"),
        (&demo.smoothed.curve, "curve"),
    ] {
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
    crate::docs_output::write_doc(out, "airfoil_curvature.svg", &graph.render())
}

/// The pictures of the demo, for `cargo xtask docs`.
pub(crate) fn render(root: &Path, out: &Path) -> Result<(), String> {
    let demo = compute(root)?;
    let ls = planar_features(&demo.least_squares, 1e-10).map_err(|e| e.to_string())?;
    draw(&demo, ls.curvature_extrema.len(), out)
}

/// Runs the demonstration: prints the result, draws it under `target/demo/`.
pub(crate) fn run(root: &Path) -> Result<(), String> {
    let started = std::time::Instant::now();
    let demo = compute(root)?;
    println!(
        "airfoil {AIRFOIL}: {} points (data/airfoils/{AIRFOIL}.dat, chord 1 m)",
        demo.points.len()
    );
    let ls = planar_features(&demo.least_squares, 1e-10).map_err(|e| e.to_string())?;
    let ls_dev =
        two_sided_deviation(&demo.least_squares, &demo.points).map_err(|e| e.to_string())?;
    println!(
        "least squares, cubic, {CONTROL_POINTS} control points, parameter correction ({} sweeps): max deviation {:.2} mm, rms {:.2} mm; {} curvature extrema, {} inflections",
        demo.sweeps,
        ls_dev.to_curve.max * 1e3,
        ls_dev.to_curve.rms * 1e3,
        ls.curvature_extrema.len(),
        ls.inflections.len()
    );
    let s = &demo.smoothed;
    let nose = s
        .extrema
        .first()
        .ok_or("the smoothed curve has no extremum")?;
    println!(
        "smoothed (selective eraser, thesis ch. 6): max deviation {:.2} mm (curve to data polyline {:.2} mm), rms {:.2} mm; {} curvature {} at u = {:.3} (x = {:.4}, y = {:.4}), {} inflection(s)",
        s.deviation.to_curve.max * 1e3,
        s.deviation.to_data * 1e3,
        s.deviation.to_curve.rms * 1e3,
        s.extrema.len(),
        nose.kind,
        nose.param,
        nose.point.x,
        nose.point.y,
        s.inflections.len(),
    );
    let turns =
        sampled_curvature_extrema(&s.curve, s.orientation, 400, 1e-9).map_err(|e| e.to_string())?;
    println!(
        "check by dense sampling of the curvature (both one-sided limits at every knot): {} turning point(s)",
        turns.len()
    );
    println!("smoothed curve (exchange format):");
    println!("{}", spline::io::exchange::to_json(&s.curve));
    let out = crate::bench::target_dir(root).join("demo");
    draw(&demo, ls.curvature_extrema.len(), &out)?;
    eprintln!(
        "pictures: {} and airfoil_curvature.svg ({:.1} s)",
        out.join("airfoil.svg").display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
