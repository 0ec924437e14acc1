//! gnuplot data and SVG pictures of planar curves.

use nalgebra::Vector2;
use spline_geom::{BSpline, Curve2, NurbsCurve};
use spline_io::gnuplot::{gnuplot_curve, gnuplot_polygon};
use spline_io::svg::SvgPlot;

/// The cubic of seed 000 §2.3.3.
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
    .unwrap()
}

#[test]
fn gnuplot_data() {
    let c = seed_curve();
    let polygon = gnuplot_polygon(&c);
    assert_eq!(polygon.lines().count(), 6);
    assert_eq!(polygon.lines().next().unwrap(), "0.41705 0.10673");
    let dat = gnuplot_curve(&c, 10);
    assert_eq!(dat.lines().count(), 3 * 10 + 1);
    let rows: Vec<Vec<f64>> = dat
        .lines()
        .map(|l| l.split(' ').map(|x| x.parse().unwrap()).collect())
        .collect();
    // A clamped curve starts and ends at its end control points, and u = 1 (the 11th
    // sample) is the blossom value (P1 + 4 P2 + P3) / 6 … here checked by evaluation.
    assert_eq!(rows[0], vec![0.41705, 0.10673]);
    assert_eq!(rows[30], vec![1.477, 0.13012]);
    let at_one = c.eval(1.0).unwrap();
    assert_eq!(rows[10], vec![at_one.x, at_one.y]);
}

#[test]
fn svg_plots_of_planar_curves() {
    let c = seed_curve();
    let mut plot = SvgPlot::new();
    plot.set_title("seed <cubic> & comb");
    plot.add_curve(&c);
    plot.add_curvature_comb(&c, 50);
    plot.add_markers(&[Vector2::new(1.0, 0.5)], "inflection");
    let quarter = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector2::new(1.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(0.0, 1.0),
        ],
        vec![1.0, 1.0, 2.0],
    )
    .unwrap();
    plot.add_curve_styled(&quarter, "curve2");
    let svg = plot.render();
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"800\""));
    assert!(svg.ends_with("</svg>\n"));
    assert!(svg.contains("seed &lt;cubic&gt; &amp; comb"));
    // Two polygons, two curves and the comb's ends; the comb's teeth as one path.
    assert_eq!(svg.matches("<polyline class=\"polygon\"").count(), 2);
    assert_eq!(svg.matches("<polyline class=\"curve\"").count(), 1);
    assert_eq!(svg.matches("<polyline class=\"curve2\"").count(), 1);
    assert_eq!(svg.matches("<path class=\"comb\"").count(), 1);
    // Control points of both curves and the marker.
    assert_eq!(svg.matches("<circle class=\"control\"").count(), 6 + 3);
    assert_eq!(svg.matches("<circle class=\"inflection\"").count(), 1);
    let numbers = svg.replace("inflection", "");
    assert!(!numbers.contains("NaN") && !numbers.contains("inf"));
    // An empty picture is still a picture.
    assert!(SvgPlot::new().render().contains("</svg>"));
}
