//! Pictures of the curve algorithms: basis functions, curves with control polygons, knot
//! insertion, degree elevation, splitting, Bézier subdivision, curvature combs.

use nalgebra::Vector2;
use spline::core::KnotVector;
use spline::geom::{BSpline, Bezier, Curve2};
use spline::io::svg::SvgPlot;
use std::path::Path;

fn write(out: &Path, name: &str, plot: &SvgPlot) -> Result<(), String> {
    crate::docs_output::write_doc(out, name, &plot.render())
}

fn seed_curve() -> Curve2 {
    BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0],
        vec![
            Vector2::new(0.41705, 0.10673),
            Vector2::new(0.28802, 0.60088),
            Vector2::new(0.90553, 0.46053),
            Vector2::new(1.3203, 0.79678),
            Vector2::new(1.8041, 0.63012),
            Vector2::new(1.477, 0.13012),
        ],
    )
    .expect("valid curve")
}

fn curve_points(curve: &Curve2) -> Vec<Vector2<f64>> {
    curve
        .eval_many(&spline::ParamCurve::sample_params(curve, 64))
        .expect("in domain")
}

/// Writes every curve picture into `out`.
pub(crate) fn render(out: &Path) -> Result<(), String> {
    // FIG. 1 of seed 000: the cubic basis on [0,0,0,0,1,2,3,3,3,3].
    let knots = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0])
        .map_err(|e| e.to_string())?;
    let mut plot = SvgPlot::new();
    plot.set_title("Cubic B-spline basis, knots [0,0,0,0,1,2,3,3,3,3] (seed 000, FIG. 1)");
    let us: Vec<f64> = (0..=600).map(|i| 3.0 * f64::from(i) / 600.0).collect();
    for i in 0..knots.num_basis() {
        let pts: Vec<Vector2<f64>> = us
            .iter()
            .map(|&u| Vector2::new(u, knots.basis_function(i, u).expect("in domain")))
            .collect();
        plot.add_polyline(&pts, &format!("c{i}"));
    }
    plot.add_polyline(&[Vector2::new(0.0, 0.0), Vector2::new(3.0, 0.0)], "axis");
    write(out, "basis.svg", &plot)?;

    // The example curve of seed 000 §2.3.3 with its control polygon.
    let curve = seed_curve();
    let mut plot = SvgPlot::new();
    plot.set_title("Cubic B-spline curve and control polygon (seed 000 §2.3.3)");
    plot.add_curve(&curve);
    write(out, "curve.svg", &plot)?;

    // Knot insertion at 1.5 (FIG. 7): the new polygon in colour.
    let inserted = curve.insert_knot(1.5, 1).map_err(|e| e.to_string())?;
    let mut plot = SvgPlot::new();
    plot.set_title("Knot insertion at u = 1.5: old polygon dashed, new polygon red");
    plot.add_curve(&curve);
    plot.add_polyline(inserted.control_points(), "curve2");
    plot.add_markers(inserted.control_points(), "inflection");
    write(out, "insertion.svg", &plot)?;

    // Degree elevation to 4 and 7 (FIG. 8 and 9).
    let mut plot = SvgPlot::new();
    plot.set_title("Degree elevation: degree 3 (dashed), 4 (red), 7 (green)");
    plot.add_curve(&curve);
    for (times, class) in [(1, "curve2"), (4, "curve3")] {
        let e = curve.elevate_degree(times).map_err(|e| e.to_string())?;
        plot.add_polyline(e.control_points(), class);
    }
    write(out, "elevation.svg", &plot)?;

    // Split at 2.5 (FIG. 6): knots [0,0,0,0,1,2,3,4,5,6,6,6,6].
    let wave: Curve2 = BSpline::from_knots(
        3,
        vec![
            0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 6.0, 6.0, 6.0,
        ],
        (0..9)
            .map(|i| Vector2::new(f64::from(i), if i % 2 == 0 { 0.0 } else { 2.0 }))
            .collect(),
    )
    .map_err(|e| e.to_string())?;
    let (left, right) = wave.split(2.5).map_err(|e| e.to_string())?;
    let mut plot = SvgPlot::new();
    plot.set_title("Subdivision at u = 2.5 (seed 000, FIG. 6): two independent curves");
    plot.add_curve_styled(&left, "curve");
    plot.add_curve_styled(&right, "curve2");
    write(out, "split.svg", &plot)?;

    // Bézier subdivision (seed 004, FIG. 23): three levels of halving.
    let bezier = Bezier::new(vec![
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 2.0),
        Vector2::new(3.0, 2.0),
        Vector2::new(4.0, 0.0),
    ])
    .map_err(|e| e.to_string())?;
    let mut plot = SvgPlot::new();
    plot.set_title(
        "De Casteljau subdivision: polygons of 1, 2, 4 and 8 pieces converge to the curve",
    );
    let mut pieces = vec![bezier.clone()];
    for (level, class) in ["polygon", "c1", "c2", "c3"].iter().enumerate() {
        for piece in &pieces {
            plot.add_polyline(piece.control_points(), class);
        }
        if level < 3 {
            pieces = pieces
                .iter()
                .flat_map(|b| {
                    let (a, c) = b.interval();
                    let (l, r) = b.subdivide(0.5 * (a + c)).expect("interior");
                    [l, r]
                })
                .collect();
        }
    }
    let dense = bezier.to_bspline().map_err(|e| e.to_string())?;
    plot.add_polyline(&curve_points(&dense), "curve");
    write(out, "bezier_subdivision.svg", &plot)?;

    // Curvature comb of the example curve.
    let mut plot = SvgPlot::new();
    plot.set_title("Curvature comb (teeth along the normal, length ∝ signed curvature)");
    plot.add_curve(&curve);
    plot.add_curvature_comb(&curve, 300);
    write(out, "curvature_comb.svg", &plot)?;
    Ok(())
}
