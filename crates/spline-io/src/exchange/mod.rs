//! The JSON exchange format (`docs/exchange-format.md`; feature `serde`).
//!
//! A curve is `{"degree": p, "knots": [...], "control_points": [[x, ...], ...]}`; a NURBS
//! curve adds `"weights"` (control points stay Cartesian). A surface has two degrees, two knot
//! vectors and a net of control points (`control_points[i][j]`, `i` along `u`), and for NURBS
//! a net of weights. Reading validates everything the constructors validate and reports the
//! first problem.
//!
//! - [`CurveRecord`] and [`SurfaceRecord`]: the records as they appear in the JSON, with their
//!   conversions to and from every container of any point type.
//! - [`Exchange`]: the containers with a record ([`BSpline`], [`Bezier`], [`Surface`],
//!   [`NurbsCurve`], [`NurbsSurface`]), written and read by [`to_json`], [`to_value`],
//!   [`from_json`] and [`from_value`].
//! - [`Record`]: an object of either kind read as the tool reads its files, reports of the
//!   tool (an object under `"curve"` or `"surface"`) included.
//! - [`crate::Geometry::to_exchange`] and [`crate::Geometry::from_exchange`]: CAD items.
//! - scipy's objects: [`columns_to_value`] (a `ColumnSpline` as a curve record),
//!   [`nd_to_value`] and [`nd_from_value`] (an `NdSpline`, its coefficients nested one level
//!   per dimension: [`nest`], [`nested_array`]).
//!
//! ```
//! use nalgebra::Vector2;
//! use spline_geom::BSpline;
//! use spline_io::exchange::{from_json, to_json};
//! let curve = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
//!     vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 2.0)])?;
//! let text = to_json(&curve);
//! assert_eq!(text, r#"{"degree":1,"knots":[0.0,0.0,1.0,1.0],"control_points":[[0.0,0.0],[1.0,2.0]]}"#);
//! assert_eq!(from_json::<BSpline<f64, Vector2<f64>>>(&text)?, curve);
//! # Ok::<(), spline_core::Error>(())
//! ```

mod columns;
mod decode;
mod geometry;
mod records;

pub use columns::{columns_to_value, nd_from_value, nd_to_value, nest, nested_array};
pub use decode::serde_message;
pub use records::{CurveRecord, Record, SurfaceRecord, points_from_rows};

use decode::deserialize;
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar};
use spline_geom::{BSpline, Bezier, NurbsCurve, NurbsSurface, Surface};

/// A container with a record in the exchange format.
pub trait Exchange: Sized {
    /// The record: [`CurveRecord`] or [`SurfaceRecord`].
    type Record: Serialize + DeserializeOwned;
    /// What the record holds (`curve` or `surface`), for messages.
    const NAME: &'static str;

    /// The record of the container.
    fn to_record(&self) -> Self::Record;

    /// Validates a record as a container of this type.
    ///
    /// # Errors
    /// The validation errors of the record's conversion (dimensions, knots, weights,
    /// counts).
    fn from_record(record: &Self::Record) -> Result<Self>;
}

impl<T: Scalar, P: ControlPoint<T>> Exchange for BSpline<T, P> {
    type Record = CurveRecord;
    const NAME: &'static str = "curve";

    fn to_record(&self) -> CurveRecord {
        CurveRecord::from_bspline(self)
    }

    fn from_record(record: &CurveRecord) -> Result<Self> {
        record.to_bspline()
    }
}

/// In the exchange format a Bézier curve is the clamped B-spline of one segment: knots
/// `p + 1` copies of `a`, then `p + 1` copies of `b`.
impl<T: Scalar, P: ControlPoint<T>> Exchange for Bezier<T, P> {
    type Record = CurveRecord;
    const NAME: &'static str = "curve";

    fn to_record(&self) -> CurveRecord {
        CurveRecord::from_bezier(self)
    }

    fn from_record(record: &CurveRecord) -> Result<Self> {
        record.to_bezier()
    }
}

impl<T: Scalar, const D: usize> Exchange for NurbsCurve<T, D> {
    type Record = CurveRecord;
    const NAME: &'static str = "curve";

    fn to_record(&self) -> CurveRecord {
        CurveRecord::from_nurbs(self)
    }

    fn from_record(record: &CurveRecord) -> Result<Self> {
        record.to_nurbs()
    }
}

impl<T: Scalar, P: ControlPoint<T>> Exchange for Surface<T, P> {
    type Record = SurfaceRecord;
    const NAME: &'static str = "surface";

    fn to_record(&self) -> SurfaceRecord {
        SurfaceRecord::from_surface(self)
    }

    fn from_record(record: &SurfaceRecord) -> Result<Self> {
        record.to_surface()
    }
}

impl<T: Scalar, const D: usize> Exchange for NurbsSurface<T, D> {
    type Record = SurfaceRecord;
    const NAME: &'static str = "surface";

    fn to_record(&self) -> SurfaceRecord {
        SurfaceRecord::from_nurbs_surface(self)
    }

    fn from_record(record: &SurfaceRecord) -> Result<Self> {
        record.to_nurbs_surface()
    }
}

/// The container's record as a JSON value.
#[must_use]
pub fn to_value<X: Exchange>(object: &X) -> Value {
    // A record holds numbers, vectors and options only: serialising cannot fail (NaN and
    // infinities become `null`).
    serde_json::to_value(object.to_record()).unwrap_or(Value::Null)
}

/// The container's record as compact JSON text.
#[must_use]
pub fn to_json<X: Exchange>(object: &X) -> String {
    // As in `to_value`: serialising a record cannot fail.
    serde_json::to_string(&object.to_record()).unwrap_or_default()
}

/// A container from its record as a JSON value.
///
/// # Errors
/// [`ErrorKind::Parse`] when the value is not a record, naming the field
/// (`malformed curve: field control_points[0]: expected an array, got the number 0.0`); the
/// errors of [`Exchange::from_record`].
pub fn from_value<X: Exchange>(value: Value) -> Result<X> {
    X::from_record(&deserialize(X::NAME, value)?)
}

/// A container from its record as JSON text.
///
/// # Errors
/// [`ErrorKind::Parse`] for text that is not JSON (`not valid JSON: …`); the errors of
/// [`from_value`].
pub fn from_json<X: Exchange>(text: &str) -> Result<X> {
    let value = parse_json(text).map_err(|e| {
        let error = Error::new(
            ErrorKind::Parse,
            format!("not valid JSON: {}", serde_message(e.message())),
        );
        match e.line() {
            Some(line) => error.with_line(line),
            None => error,
        }
    })?;
    from_value(value)
}

/// Parses JSON text into a value.
///
/// # Errors
/// [`ErrorKind::Parse`] with serde_json's message (with its line and column), which the
/// caller completes with what was read (a file, an argument) or rewords with
/// [`serde_message`].
pub fn parse_json(text: &str) -> Result<Value> {
    serde_json::from_str(text)
        .map_err(|e| Error::new(ErrorKind::Parse, e.to_string()).with_line(e.line()))
}
