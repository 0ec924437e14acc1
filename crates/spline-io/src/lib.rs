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

use nalgebra::{Vector2, Vector3};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::{BSpline, NurbsCurve2, NurbsCurve3, NurbsSurface3, Surface};
use std::path::Path;

/// The geometry of one imported or exported entity, converted exactly to (rational) B-splines.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// A polynomial B-spline curve in the plane.
    Curve2(BSpline<f64, Vector2<f64>>),
    /// A polynomial B-spline curve in space.
    Curve3(BSpline<f64, Vector3<f64>>),
    /// A rational (NURBS) curve in the plane.
    NurbsCurve2(NurbsCurve2<f64>),
    /// A rational (NURBS) curve in space.
    NurbsCurve3(NurbsCurve3<f64>),
    /// A polynomial tensor-product B-spline surface in space.
    Surface(Surface<f64, Vector3<f64>>),
    /// A rational (NURBS) tensor-product surface in space.
    NurbsSurface(NurbsSurface3<f64>),
}

impl Geometry {
    /// Every coordinate of the Cartesian control points, point after point.
    pub(crate) fn coordinates(&self) -> Box<dyn Iterator<Item = f64> + '_> {
        fn flat<const D: usize>(
            points: &[nalgebra::SVector<f64, D>],
        ) -> Box<dyn Iterator<Item = f64> + '_> {
            Box::new(points.iter().flat_map(|p| p.iter().copied()))
        }
        match self {
            Geometry::Curve2(c) => flat(c.control_points()),
            Geometry::Curve3(c) => flat(c.control_points()),
            Geometry::NurbsCurve2(c) => flat(c.control_points()),
            Geometry::NurbsCurve3(c) => flat(c.control_points()),
            Geometry::Surface(s) => flat(s.control_points()),
            Geometry::NurbsSurface(s) => flat(s.control_points()),
        }
    }
}

/// One entity of a CAD file: its geometry, with the name and identifier the file gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    /// The entity's identifier in the file: the STEP instance number (`#12` → 12), or the IGES
    /// directory-entry sequence number. Writers number entities themselves and ignore it.
    pub id: u64,
    /// The entity's name (STEP: the `name` attribute, or the name of the face or edge that
    /// holds the geometry; IGES: the entity label); empty when the file gives none.
    pub name: String,
    /// The entity type the geometry was read from (`B_SPLINE_CURVE_WITH_KNOTS`,
    /// `CYLINDRICAL_SURFACE`, `126`, …); writers ignore it.
    pub entity: String,
    /// The geometry.
    pub geometry: Geometry,
}

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
                "{}: unknown CAD format (the extension must be .step, .stp, .igs or .iges)",
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
