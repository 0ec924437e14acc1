//! Pictures of curvature features of surfaces for `docs/` (`cargo xtask docs`): a torus with
//! its two parabolic circles, an ellipsoid with its four umbilics, and a bell-like surface of
//! revolution before and after the control of its parabolic circles through the meridian.

use nalgebra::Vector3;
use spline::algebra::{parabolic_lines, surface_feature_lines};
use spline::geom::{Axis, NurbsCurve, NurbsSurface};
use spline::io::svg::{MeshView, feature_overlays, mesh_svg_with};
use spline::shape::{ParabolicCircles, Sign, control_parabolic_circles, revolution_surface};
use spline::{Error, Result};
use std::path::Path;

/// The surface shaded, with its parabolic lines and umbilics drawn over it
/// ([`feature_overlays`] without the ridges); the number of each.
fn picture(
    surface: &NurbsSurface<f64, 3>,
    segments: (usize, usize),
    view: &MeshView,
) -> Result<(String, usize, usize)> {
    // Parabolic lines and umbilics only (the ridges have their own pictures, docs_ridges).
    let mut lines = surface_feature_lines(surface, 16)?;
    lines.red_ridges.clear();
    lines.blue_ridges.clear();
    let overlays = feature_overlays(&lines);
    let umbilics = lines.umbilics.len();
    let mesh = surface.tessellate(segments.0, segments.1)?;
    Ok((
        mesh_svg_with(&mesh, view, &overlays),
        overlays.len() - umbilics,
        umbilics,
    ))
}

/// Writes `torus_parabolic.svg`, `ellipsoid_umbilics.svg`, `bell_before.svg` and
/// `bell_after.svg` into `out_dir`.
///
/// # Errors
/// A message if a file cannot be written (or, which would be a bug, a computation fails).
pub(crate) fn render(out_dir: &Path) -> std::result::Result<(), String> {
    let failed = |e: Error| format!("docs_surface_features: {e}");
    // Three quarters of a torus, so that the bottom circle shows through the cut.
    let profile = NurbsCurve::circle(
        &spline::geom::Frame::new(Vector3::new(2.0, 0.0, 0.0), Vector3::x(), Vector3::z())
            .map_err(failed)?,
        0.8,
        spline::geom::CircleConstruction::Square,
    )
    .map_err(failed)?;
    let axis = Axis::new(Vector3::zeros(), Vector3::z()).map_err(failed)?;
    let torus =
        NurbsSurface::revolution(&profile, &axis, 1.5 * std::f64::consts::PI).map_err(failed)?;
    let view = MeshView {
        elevation: 30.0,
        azimuth: 10.0,
        wireframe: false,
        color: [90, 140, 200],
        title: Some(
            "Torus (three quarters): parabolic lines K = 0 (orange) = its top and bottom circles"
                .into(),
        ),
        ..MeshView::default()
    };
    let (svg, n, _) = picture(&torus, (48, 64), &view).map_err(failed)?;
    assert_eq!(n, 2, "the torus has two parabolic circles");
    crate::docs_output::write_doc(out_dir, "torus_parabolic.svg", &svg)?;

    let sphere = NurbsSurface::sphere(Vector3::zeros(), 1.0).map_err(failed)?;
    let ellipsoid = sphere.map_control_points(|p| Vector3::new(1.5 * p.x, 2.0 * p.y, p.z));
    let view = MeshView {
        elevation: 10.0,
        azimuth: 35.0,
        wireframe: false,
        color: [120, 170, 110],
        title: Some("Ellipsoid 1.5 x 2 x 1: its four umbilics (yellow; one behind)".into()),
        ..MeshView::default()
    };
    let (svg, _, u) = picture(&ellipsoid, (48, 64), &view).map_err(failed)?;
    assert_eq!(u, 4, "the ellipsoid has four umbilics");
    crate::docs_output::write_doc(out_dir, "ellipsoid_umbilics.svg", &svg)?;

    // A bell-like meridian with a wiggle: three parabolic circles, one wanted.
    let z: Vec<f64> = (0..=24).map(|k| f64::from(k) / 24.0).collect();
    let r: Vec<f64> = z
        .iter()
        .map(|&z| 1.0 - 0.4 * z * z + 0.4 * z * z * z + 0.02 * (9.0 * z).sin())
        .collect();
    let meridian = spline::fit::interpolate_function(&z, &r, 3).map_err(failed)?;
    let view = |title: String| MeshView {
        elevation: 15.0,
        wireframe: false,
        color: [190, 150, 90],
        title: Some(title),
        ..MeshView::default()
    };
    let before = revolution_surface(&meridian).map_err(failed)?;
    let n = parabolic_lines(&before, 16).map_err(failed)?.curves.len();
    let title = format!("Surface of revolution: {n} parabolic circles (one wanted)");
    let (svg, _, _) = picture(&before, (64, 48), &view(title)).map_err(failed)?;
    crate::docs_output::write_doc(out_dir, "bell_before.svg", &svg)?;
    let one = ParabolicCircles {
        first: Sign::NonPositive,
        allowed: vec![(0.25, 0.45)],
    };
    let controlled = control_parabolic_circles(&meridian, &one, 300, 1).map_err(failed)?;
    let after = revolution_surface(&controlled.meridian).map_err(failed)?;
    let title = format!(
        "Controlled through the meridian: one parabolic circle, max radius change {:.1e}",
        controlled.max_deviation
    );
    let (svg, n, _) = picture(&after, (64, 48), &view(title)).map_err(failed)?;
    assert_eq!(n, 1, "one parabolic circle after the control");
    crate::docs_output::write_doc(out_dir, "bell_after.svg", &svg)?;
    Ok(())
}
