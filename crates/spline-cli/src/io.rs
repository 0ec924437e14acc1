//! Reading objects and points, writing JSON: the tool's side of the exchange format.

use nalgebra::SVector;
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;
use spline_core::{Error, ErrorKind, Result};
use spline_geom::BSpline;
use spline_geom::exchange::{CurveRecord, parse_points};
use std::io::Read;

/// The largest number of coordinates the tool accepts for control points and data points.
pub const MAX_DIM: usize = 8;

/// The tool's point type: coordinates padded with zeros to [`MAX_DIM`]. Zero coordinates
/// stay zero under every affine combination and do not change lengths or angles, so one
/// instantiation of the library serves every dimension `1 ≤ d ≤ MAX_DIM` exactly.
pub type Pt = SVector<f64, MAX_DIM>;

/// Reads a whole file, or standard input for `-`.
pub fn read_text(path: &str) -> Result<String> {
    if path == "-" {
        let mut text = String::new();
        std::io::stdin().read_to_string(&mut text).map_err(|e| {
            Error::new(ErrorKind::Parse, format!("cannot read standard input: {e}"))
        })?;
        Ok(text)
    } else {
        std::fs::read_to_string(path)
            .map_err(|e| Error::new(ErrorKind::Parse, format!("cannot read {path}: {e}")))
    }
}

/// Reads a JSON document from a file or `-`.
pub fn read_json(path: &str) -> Result<Value> {
    let text = read_text(path)?;
    serde_json::from_str(&text)
        .map_err(|e| Error::new(ErrorKind::Parse, format!("{path} is not valid JSON: {e}")))
}

/// Parses the JSON value of a command-line option.
pub fn parse_arg<T: DeserializeOwned>(option: &str, text: &str) -> Result<T> {
    serde_json::from_str(text).map_err(|e| {
        Error::new(
            ErrorKind::Parse,
            format!("{option}: cannot read {text:?} as expected: {e}"),
        )
    })
}

/// Deserialises a JSON value into a record type, with the file name in the message.
pub fn from_value<T: DeserializeOwned>(what: &str, value: Value) -> Result<T> {
    serde_json::from_value(value)
        .map_err(|e| Error::new(ErrorKind::Parse, format!("malformed {what}: {e}")))
}

/// Prints a value as one line of JSON; refuses to print non-finite numbers.
pub fn print_json(value: &impl Serialize) -> Result<()> {
    let value = serde_json::to_value(value).map_err(|e| {
        Error::new(
            ErrorKind::InvalidArgument,
            format!("cannot encode output: {e}"),
        )
    })?;
    if contains_null(&value) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            "the computation produced non-finite numbers; refusing to print them",
        ));
    }
    println!("{value}");
    Ok(())
}

fn contains_null(value: &Value) -> bool {
    match value {
        Value::Null => true,
        Value::Array(items) => items.iter().any(contains_null),
        Value::Object(map) => map.values().any(contains_null),
        _ => false,
    }
}

/// Pads a point to [`MAX_DIM`] coordinates.
pub fn pad(row: &[f64]) -> Result<Pt> {
    if row.is_empty() || row.len() > MAX_DIM {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!(
                "points must have 1 to {MAX_DIM} coordinates, got {}",
                row.len()
            ),
        ));
    }
    let mut p = Pt::zeros();
    p.as_mut_slice()[..row.len()].copy_from_slice(row);
    Ok(p)
}

/// The first `dim` coordinates of a padded point.
pub fn unpad(p: &Pt, dim: usize) -> Vec<f64> {
    p.as_slice()[..dim].to_vec()
}

/// A B-spline curve of run-time dimension.
#[derive(Clone, Debug)]
pub struct Curve {
    /// The curve with padded control points.
    pub curve: BSpline<f64, Pt>,
    /// The number of meaningful coordinates.
    pub dim: usize,
}

impl Curve {
    /// Validates a record (without weights).
    pub fn from_record(record: &CurveRecord) -> Result<Self> {
        let dim = record.dimension()?;
        let points = record
            .control_points
            .iter()
            .map(|r| pad(r))
            .collect::<Result<Vec<_>>>()?;
        Ok(Self {
            curve: BSpline::from_knots(record.degree, record.knots.clone(), points)?,
            dim,
        })
    }

    /// A curve of the same dimension.
    pub fn with(&self, curve: BSpline<f64, Pt>) -> Self {
        Self {
            curve,
            dim: self.dim,
        }
    }

    /// The exchange-format record.
    pub fn to_record(&self) -> CurveRecord {
        CurveRecord {
            degree: self.curve.degree(),
            knots: self.curve.knots().knots().to_vec(),
            control_points: self
                .curve
                .control_points()
                .iter()
                .map(|p| unpad(p, self.dim))
                .collect(),
            weights: None,
        }
    }
}

/// What an object file holds.
pub enum Object {
    /// A non-rational curve.
    Curve(Curve),
    /// A NURBS curve (record with weights).
    Nurbs(CurveRecord),
    /// A tensor-product surface (rational or not), as JSON.
    Surface(Value),
}

/// Reads an object file and tells curves, NURBS curves and surfaces apart: a surface has a
/// pair of degrees, a NURBS curve has weights.
pub fn read_object(path: &str) -> Result<Object> {
    let value = read_json(path)?;
    classify(value).map_err(|e| e.context(path))
}

/// Classifies a JSON object (see [`read_object`]).
pub fn classify(value: Value) -> Result<Object> {
    if !value.is_object() {
        return Err(Error::new(
            ErrorKind::Parse,
            "expected a JSON object with degree, knots and control_points",
        ));
    }
    if value.get("degree").is_some_and(Value::is_array) {
        return Ok(Object::Surface(value));
    }
    let record: CurveRecord = from_value("curve", value)?;
    if record.weights.is_some() {
        Ok(Object::Nurbs(record))
    } else {
        Ok(Object::Curve(Curve::from_record(&record)?))
    }
}

/// Reads a point file (JSON array of arrays, or text; see
/// [`spline_geom::exchange::parse_points`]).
#[allow(dead_code)] // used by the fitting subcommands
pub fn read_points(path: &str) -> Result<Vec<Vec<f64>>> {
    parse_points(&read_text(path)?).map_err(|e| e.context(path))
}
