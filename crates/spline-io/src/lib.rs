//! Every file format of the `spline` library, read and written in one place: the tool, the
//! studio and the Python package call these readers and writers and parse no file text
//! themselves.
//!
//! | format | module | read | write |
//! |---|---|---|---|
//! | JSON exchange format (curves, NURBS curves, surfaces) | [`exchange`] (feature `serde`) | records, [`exchange::from_json`], [`exchange::Record`] | [`exchange::to_json`] |
//! | point files (JSON arrays, text columns) | [`points`] | [`points::parse_points`] | — |
//! | airfoil coordinates (Selig, Lednicer `.dat`) | [`airfoil`] | [`airfoil::parse_airfoil`] | — |
//! | Wavefront OBJ meshes | [`obj`] | [`obj::read_obj`] | [`obj::write_obj`] |
//! | OFF meshes (geomview) | [`off`] | [`off::read_off`] | [`off::write_off`] |
//! | SVG pictures of planar curves and of meshes | [`svg`] | — | [`svg::SvgPlot`], [`svg::mesh_svg`] |
//! | gnuplot data | [`gnuplot`] | — | [`gnuplot::gnuplot_curve`], [`gnuplot::gnuplot_polygon`] |
//! | STEP (ISO 10303-21, AP214/AP242 geometry) | [`step`] | [`step::read_step`] | [`step::write_step`] |
//! | IGES 5.3 | [`iges`] | [`iges::read_iges`] | [`iges::write_iges`] |
//!
//! The CAD formats read into and write from the same [`Item`]s: a piece of geometry
//! ([`Geometry`]: a B-spline or NURBS curve in 2-D or 3-D, a B-spline or NURBS surface) with the
//! name and the identifier the file gives it (a STEP instance `#id`, an IGES directory-entry
//! sequence number); [`read_file`] and [`write_file`] choose the format by the extension.
//!
//! The geometry itself (tessellation into a [`spline_geom::TriangleMesh`], sampling, the
//! curvature features drawn over a surface) is computed by the lower crates; this crate only
//! turns it into text and back.
//!
//! # Feature flags
//! - `serde` (default): the JSON exchange format ([`exchange`]) and JSON point files.

pub mod airfoil;
#[cfg(feature = "serde")]
pub mod exchange;
pub mod gnuplot;
pub mod iges;
pub mod obj;
pub mod off;
pub mod points;
mod real;
pub mod step;
pub mod svg;

mod item;

pub use item::{Geometry, Item};
use spline_core::{Error, ErrorKind, Result};
use std::path::Path;

/// The format of a CAD file, from its extension.
fn format_of(path: &Path) -> Result<&'static str> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match extension.as_str() {
        "step" | "stp" | "p21" => Ok("step"),
        "igs" | "iges" => Ok("iges"),
        _ => Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{}: unknown CAD format (the extension must be .step, .stp, .p21, .igs or .iges)",
                path.display()
            ),
        )
        .with_file(path.display())),
    }
}

/// The items of a STEP or IGES file, by its extension ([`step::read_step`],
/// [`iges::read_iges`]).
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for another extension; [`ErrorKind::Io`] when the file
/// cannot be read; the reader's errors, prefixed with the path.
pub fn read_file(path: &Path) -> Result<Vec<Item>> {
    let format = format_of(path)?;
    let bytes =
        std::fs::read(path).map_err(|e| Error::io(format!("read {}", path.display()), e))?;
    let items = if format == "step" {
        step::read_step_bytes(&bytes)
    } else {
        iges::read_iges_bytes(&bytes)
    };
    items.map_err(|e| e.context(path.display()).with_file(path.display()))
}

/// Writes the items to a STEP or IGES file, by its extension ([`step::write_step`],
/// [`iges::write_iges`]).
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for another extension; [`ErrorKind::Io`] when the file
/// cannot be written; the writer's errors.
pub fn write_file(path: &Path, items: &[Item]) -> Result<()> {
    let text = if format_of(path)? == "step" {
        step::write_step(items)?
    } else {
        iges::write_iges(items)?
    };
    std::fs::write(path, text).map_err(|e| Error::io(format!("write {}", path.display()), e))
}
