//! `spline export` and `spline import`: CAD files (STEP, IGES) through `spline-io`.

use crate::io;
use crate::objects::{Object, read_object};
use clap::Args;
use nalgebra::{Vector2, Vector3};
use serde_json::{Value, json};
use spline_core::{Error, ErrorKind, Result};
use spline_io::{Geometry, Item};
use std::path::Path;

#[derive(Args)]
pub struct ExportArgs {
    /// The file to write: FILE.step or FILE.stp (STEP AP214), FILE.igs or FILE.iges (IGES 5.3).
    #[arg(value_name = "FILE")]
    out: String,
    /// The objects to write (files in the exchange format, or - for standard input); each
    /// entity is named after its file's stem.
    #[arg(value_name = "OBJECT", required = true)]
    objects: Vec<String>,
}

#[derive(Args)]
pub struct ImportArgs {
    /// A STEP (.step, .stp) or IGES (.igs, .iges) file.
    #[arg(value_name = "FILE")]
    file: String,
}

/// The item of an object: curves in 2-D or 3-D, surfaces in 3-D.
fn item_of(object: Object, path: &str) -> Result<Item> {
    let v2 = |p: &io::Pt| Vector2::new(p[0], p[1]);
    let v3 = |p: &io::Pt| Vector3::new(p[0], p[1], p[2]);
    let dims = |dim: usize, allowed: &[usize], what: &str| {
        if allowed.contains(&dim) {
            Ok(())
        } else {
            Err(Error::new(
                ErrorKind::DimensionMismatch,
                format!("{path}: CAD files hold {what}, got points of dimension {dim}"),
            ))
        }
    };
    let geometry = match object {
        Object::Curve(c) => {
            dims(c.dim, &[2, 3], "curves in 2-D or 3-D")?;
            if c.dim == 2 {
                Geometry::Curve2(c.value.map_control_points(v2))
            } else {
                Geometry::Curve3(c.value.map_control_points(v3))
            }
        }
        Object::Nurbs(c) => {
            dims(c.dim, &[2, 3], "curves in 2-D or 3-D")?;
            if c.dim == 2 {
                Geometry::NurbsCurve2(c.value.map_control_points::<2>(v2))
            } else {
                Geometry::NurbsCurve3(c.value.map_control_points::<3>(v3))
            }
        }
        Object::Surface(s) => {
            dims(s.dim, &[3], "surfaces in 3-D")?;
            Geometry::Surface(s.value.map_control_points(v3))
        }
        Object::NurbsSurface(s) => {
            dims(s.dim, &[3], "surfaces in 3-D")?;
            Geometry::NurbsSurface(s.value.map_control_points::<3>(v3))
        }
    };
    let name = Path::new(path)
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    Ok(Item {
        id: 0,
        name,
        entity: String::new(),
        geometry,
    })
}

/// `spline export FILE OBJECT...`.
pub fn export(args: &ExportArgs) -> Result<()> {
    let items = args
        .objects
        .iter()
        .map(|path| item_of(read_object(path)?, path))
        .collect::<Result<Vec<_>>>()?;
    spline_io::write_file(Path::new(&args.out), &items)
}

/// `spline import FILE`: `[{"id", "name", "entity", "object"}, …]`.
pub fn import(args: &ImportArgs) -> Result<()> {
    io::check_stdout_open()?;
    let items = spline_io::read_file(Path::new(&args.file))?;
    let records = items
        .iter()
        .map(|item| {
            json!({
                "id": item.id,
                "name": item.name,
                "entity": item.entity,
                "object": item.geometry.to_exchange(),
            })
        })
        .collect::<Vec<Value>>();
    io::print_json(&records)
}
