//! Pictures of ridges of parametric surfaces for `docs/` (`cargo xtask docs`): the triaxial
//! ellipsoid with its ridges (its three principal sections, red where `κ₂` is extremal, blue
//! where `κ₁` is, changing colour at the four umbilics), and the spheroid whose two umbilics
//! are its poles.

use nalgebra::Vector3;
use spline::Error;
use spline::algebra::{surface_feature_lines, surface_ridges, umbilics};
use spline::geom::NurbsSurface;
use spline::io::svg::{MeshView, feature_overlays, mesh_svg_with};
use std::path::Path;

/// Writes `ellipsoid_ridges.svg` and `spheroid_umbilics.svg` into `out_dir`.
///
/// # Errors
/// A message if a file cannot be written (or, which would be a bug, a computation fails).
pub(crate) fn render(out_dir: &Path) -> std::result::Result<(), String> {
    let failed = |e: Error| format!("docs_ridges: {e}");
    let sphere = NurbsSurface::sphere(Vector3::zeros(), 1.0).map_err(failed)?;
    let ellipsoid = sphere.map_control_points(|p| Vector3::new(1.5 * p.x, 2.0 * p.y, p.z));
    let ridges = surface_ridges(&ellipsoid, 16).map_err(failed)?;
    assert_eq!(ridges.umbilics.len(), 4, "the ellipsoid has four umbilics");
    let view = MeshView {
        elevation: 25.0,
        azimuth: 40.0,
        wireframe: false,
        color: [200, 200, 190],
        title: Some("Ellipsoid 1.5 x 2 x 1: ridges (red κ2, blue κ1), 4 umbilics (yellow)".into()),
        ..MeshView::default()
    };
    let overlays = feature_overlays(&surface_feature_lines(&ellipsoid, 16).map_err(failed)?);
    let svg = mesh_svg_with(
        &ellipsoid.tessellate(48, 64).map_err(failed)?,
        &view,
        &overlays,
    );
    crate::docs_output::write_doc(out_dir, "ellipsoid_ridges.svg", &svg)?;

    let spheroid = sphere.map_control_points(|p| Vector3::new(1.5 * p.x, 1.5 * p.y, p.z));
    let found = umbilics(&spheroid).map_err(failed)?;
    assert_eq!(
        found.poles.len(),
        2,
        "the spheroid's umbilics are its poles"
    );
    let view = MeshView {
        elevation: 30.0,
        azimuth: 20.0,
        wireframe: false,
        color: [200, 190, 150],
        title: Some("Spheroid 1.5 x 1.5 x 1: umbilics at its poles, ridge at the equator".into()),
        ..MeshView::default()
    };
    let overlays = feature_overlays(&surface_feature_lines(&spheroid, 16).map_err(failed)?);
    let svg = mesh_svg_with(
        &spheroid.tessellate(48, 64).map_err(failed)?,
        &view,
        &overlays,
    );
    crate::docs_output::write_doc(out_dir, "spheroid_umbilics.svg", &svg)?;
    Ok(())
}
