//! Pictures of the NURBS constructions for `docs/` (`cargo xtask docs`): the two full circles
//! of the course notes with their control polygons, conic arcs of the three types, and
//! meshed, shaded NURBS spheres and tori.

use nalgebra::{Vector2, Vector3};
use spline::geom::{CircleConstruction, Frame, NurbsCurve, NurbsSurface};
use spline::io::svg::{MeshView, SvgPlot, mesh_svg};
use spline::{Error, Result};
use std::path::Path;

/// Parameters with `per_span` steps in every knot span of the curve.
fn samples(curve: &NurbsCurve<f64, 2>, per_span: usize) -> Vec<f64> {
    spline::ParamCurve::sample_params(curve.homogeneous(), per_span)
}

/// Draws a planar NURBS curve (class `class`) with its control polygon and control points.
fn add_nurbs(svg: &mut SvgPlot, curve: &NurbsCurve<f64, 2>, class: &str) -> Result<()> {
    let polygon = curve.control_points();
    svg.add_polyline(polygon, "polygon");
    svg.add_markers(polygon, "control");
    svg.add_polyline(&curve.eval_many(&samples(curve, 64))?, class);
    Ok(())
}

fn circle_picture(construction: CircleConstruction, title: &str) -> Result<String> {
    let frame = Frame::planar(Vector2::zeros());
    let circle = NurbsCurve::circle(&frame, 1.0, construction)?;
    let mut svg = SvgPlot::new();
    svg.set_width(520.0);
    svg.set_title(title);
    add_nurbs(&mut svg, &circle, "curve")?;
    // The joints of the rational quadratic arcs (the knots).
    let joints: Vec<f64> = circle
        .knots()
        .breakpoints()
        .iter()
        .map(|&(k, _)| k)
        .collect();
    svg.add_markers(&circle.eval_many(&joints)?, "data");
    Ok(svg.render())
}

fn conics_picture() -> Result<String> {
    let (p0, p1, p2) = (
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 1.6),
        Vector2::new(2.0, 0.0),
    );
    let mut svg = SvgPlot::new();
    svg.set_width(520.0);
    svg.set_title(
        "Conic arcs (6.6): w1 = 0.5 ellipse (red), 1 parabola (blue), 2 hyperbola (green)",
    );
    for (w1, class) in [(0.5, "curve2"), (1.0, "curve"), (2.0, "curve3")] {
        let arc = NurbsCurve::conic_arc(p0, p1, p2, w1)?;
        add_nurbs(&mut svg, &arc, class)?;
    }
    Ok(svg.render())
}

fn mesh_picture(
    surface: &NurbsSurface<f64, 3>,
    segments: (usize, usize),
    view: &MeshView,
) -> Result<String> {
    Ok(mesh_svg(&surface.tessellate(segments.0, segments.1)?, view))
}

/// Writes `circle_square.svg`, `circle_triangle.svg`, `conics.svg`, `sphere.svg` and
/// `torus.svg` into `out_dir` (created if needed).
///
/// # Errors
/// A message if a file cannot be written (or, which would be a bug, a construction fails).
pub(crate) fn render(out_dir: &Path) -> std::result::Result<(), String> {
    std::fs::create_dir_all(out_dir)
        .map_err(|e| format!("cannot create {}: {e}", out_dir.display()))?;
    let failed = |e: Error| format!("docs_surfaces: {e}");
    let square = circle_picture(
        CircleConstruction::Square,
        "Full circle: 9 control points on a square, knots (6.9), weights (6.10)",
    )
    .map_err(failed)?;
    crate::docs_output::write_doc(out_dir, "circle_square.svg", &square)?;
    let triangle = circle_picture(
        CircleConstruction::Triangle,
        "Full circle: 7 control points on a triangle, weights [1, 1/2, 1, 1/2, 1, 1/2, 1]",
    )
    .map_err(failed)?;
    crate::docs_output::write_doc(out_dir, "circle_triangle.svg", &triangle)?;
    crate::docs_output::write_doc(out_dir, "conics.svg", &conics_picture().map_err(failed)?)?;
    let sphere = NurbsSurface::sphere(Vector3::zeros(), 1.0).map_err(failed)?;
    let view = MeshView {
        title: Some("NURBS sphere (6.13)-(6.14): 5 x 9 control points, 24 x 48 mesh".into()),
        ..MeshView::default()
    };
    crate::docs_output::write_doc(
        out_dir,
        "sphere.svg",
        &mesh_picture(&sphere, (24, 48), &view).map_err(failed)?,
    )?;
    let torus = NurbsSurface::torus(Vector3::zeros(), Vector3::z(), 2.0, 0.6).map_err(failed)?;
    let view = MeshView {
        elevation: 35.0,
        color: [200, 120, 60],
        title: Some("NURBS torus: 9 x 9 control points, 24 x 64 mesh".into()),
        ..MeshView::default()
    };
    crate::docs_output::write_doc(
        out_dir,
        "torus.svg",
        &mesh_picture(&torus, (24, 64), &view).map_err(failed)?,
    )?;
    Ok(())
}
