//! `spline export` and `spline import`: CAD files (STEP, IGES) through `spline-io`.

use crate::io;
use clap::Args;
use serde_json::{Value, json};
use spline_core::Result;
use spline_io::exchange::Record;
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

/// The item of an object file (a record of the exchange format, or a report of the tool
/// holding one): curves in 2-D or 3-D, surfaces in 3-D ([`Geometry::from_record`]).
fn item_of(path: &str) -> Result<Item> {
    let record = Record::from_value(io::read_json(path)?).map_err(|e| e.context(path))?;
    let geometry = Geometry::from_record(&record).map_err(|e| e.context(path))?;
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
        .map(|path| item_of(path))
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
