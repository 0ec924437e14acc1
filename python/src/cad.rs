//! CAD files (STEP, IGES) through `spline::io`: items pass as exchange-format JSON, which the
//! Python layer turns into `BSpline`, `NurbsCurve` and `NurbsSurface` objects.

use crate::{IntoPy, bad_input};
use pyo3::prelude::*;
use spline::io::exchange::Record;
use spline::io::{Geometry, Item};
use std::path::Path;

/// An item of a CAD file: its id, name, entity type and geometry as exchange-format JSON.
type CadItem = (u64, String, String, String);

/// The B-spline curves and surfaces of a STEP or IGES file (by its extension).
#[pyfunction]
fn read_cad(py: Python<'_>, path: &str) -> PyResult<Vec<CadItem>> {
    let items = py.detach(|| spline::io::read_file(Path::new(path))).py()?;
    Ok(items
        .into_iter()
        .map(|i| (i.id, i.name, i.entity, i.geometry.to_exchange().to_string()))
        .collect())
}

/// Writes `(name, exchange-format JSON)` pairs to a STEP or IGES file (by its extension).
#[pyfunction]
fn write_cad(py: Python<'_>, path: &str, items: Vec<(String, String)>) -> PyResult<()> {
    let items = items
        .into_iter()
        .enumerate()
        .map(|(k, (name, text))| {
            let value = spline::io::exchange::parse_json(&text)
                .map_err(|e| bad_input(format!("object {k}: not JSON: {e}")))?;
            let geometry = Geometry::from_exchange(&value).py()?;
            Ok(Item {
                id: 0,
                name,
                entity: String::new(),
                geometry,
            })
        })
        .collect::<PyResult<Vec<Item>>>()?;
    py.detach(|| spline::io::write_file(Path::new(path), &items))
        .py()
}

/// The kind of an exchange-format object, as spline-io reads it (`Record::from_value`):
/// `"surface"` (a pair of degrees), `"nurbs"` (a curve with weights) or `"curve"`.
#[pyfunction]
fn exchange_kind(text: &str) -> PyResult<&'static str> {
    let value =
        spline::io::exchange::parse_json(text).map_err(|e| bad_input(format!("not JSON: {e}")))?;
    Ok(match Record::from_value(value).py()? {
        Record::Surface(_) => "surface",
        Record::Curve(c) if c.weights.is_some() => "nurbs",
        Record::Curve(_) => "curve",
    })
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(exchange_kind, m)?)?;
    m.add_function(wrap_pyfunction!(read_cad, m)?)?;
    m.add_function(wrap_pyfunction!(write_cad, m)?)?;
    Ok(())
}
