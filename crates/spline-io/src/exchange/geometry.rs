//! [`Geometry`] in the JSON exchange format, the form in which the tool and the Python
//! package pass CAD items on.

use super::records::{CurveRecord, Record, SurfaceRecord};
use crate::Geometry;
use nalgebra::{Vector2, Vector3};
use serde_json::Value;
use spline_core::{Error, ErrorKind, Result};

impl Geometry {
    /// The geometry as a record of the exchange format: a curve
    /// `{"degree", "knots", "control_points"[, "weights"]}` or a surface with two degrees
    /// and two knot vectors.
    #[must_use]
    pub fn to_exchange(&self) -> Value {
        let value = match self {
            Self::Curve2(c) => serde_json::to_value(CurveRecord::from_bspline(c)),
            Self::Curve3(c) => serde_json::to_value(CurveRecord::from_bspline(c)),
            Self::NurbsCurve2(c) => serde_json::to_value(CurveRecord::from_nurbs(c)),
            Self::NurbsCurve3(c) => serde_json::to_value(CurveRecord::from_nurbs(c)),
            Self::Surface(s) => serde_json::to_value(SurfaceRecord::from_surface(s)),
            Self::NurbsSurface(s) => serde_json::to_value(SurfaceRecord::from_nurbs_surface(s)),
        };
        // The records hold numbers, vectors and options only: serialising cannot fail.
        value.unwrap_or(Value::Null)
    }

    /// Geometry from a record of the exchange format: curves in 2-D or 3-D (with weights: a
    /// NURBS curve), surfaces in 3-D.
    ///
    /// # Errors
    /// [`ErrorKind::Parse`] for JSON that is not such a record; [`ErrorKind::DimensionMismatch`]
    /// for curves outside 2-D and 3-D or surfaces outside 3-D; the containers' validation
    /// errors (knots, weights, counts).
    pub fn from_exchange(value: &Value) -> Result<Self> {
        let parse = |e: serde_json::Error| {
            Error::new(
                ErrorKind::Parse,
                format!("not an object of the exchange format: {e}"),
            )
        };
        let record = if value.get("degree").is_some_and(Value::is_array) {
            Record::Surface(serde_json::from_value(value.clone()).map_err(parse)?)
        } else {
            Record::Curve(serde_json::from_value(value.clone()).map_err(parse)?)
        };
        Self::from_record(&record)
    }

    /// Geometry from a record already read ([`Record::from_value`], which also takes the
    /// tool's reports): curves in 2-D or 3-D (with weights: a NURBS curve), surfaces in 3-D.
    ///
    /// # Errors
    /// [`ErrorKind::DimensionMismatch`] for curves outside 2-D and 3-D or surfaces outside
    /// 3-D; the containers' validation errors (knots, weights, counts).
    pub fn from_record(record: &Record) -> Result<Self> {
        match record {
            Record::Surface(record) => {
                if record.dimension()? != 3 {
                    return Err(Error::new(
                        ErrorKind::DimensionMismatch,
                        format!(
                            "CAD files hold surfaces in 3-D, got points of dimension {}",
                            record.dimension()?
                        ),
                    ));
                }
                Ok(if record.is_rational() {
                    Self::NurbsSurface(record.to_nurbs_surface::<f64, 3>()?)
                } else {
                    Self::Surface(record.to_surface::<f64, Vector3<f64>>()?)
                })
            }
            Record::Curve(record) => {
                let rational = record.weights.is_some();
                Ok(match (record.dimension()?, rational) {
                    (2, false) => Self::Curve2(record.to_bspline::<f64, Vector2<f64>>()?),
                    (3, false) => Self::Curve3(record.to_bspline::<f64, Vector3<f64>>()?),
                    (2, true) => Self::NurbsCurve2(record.to_nurbs::<f64, 2>()?),
                    (3, true) => Self::NurbsCurve3(record.to_nurbs::<f64, 3>()?),
                    (d, _) => {
                        return Err(Error::new(
                            ErrorKind::DimensionMismatch,
                            format!(
                                "CAD files hold curves in 2-D or 3-D, got points of dimension {d}"
                            ),
                        ));
                    }
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::Geometry;
    use serde_json::json;

    #[test]
    fn records_go_both_ways_and_bad_ones_are_refused() {
        for value in [
            json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0], [1, 2]]}),
            json!({"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control_points": [[1, 0, 0], [1, 1, 0], [0, 1, 0]], "weights": [1, 0.5, 1]}),
            json!({"degree": [1, 1], "knots": [[0, 0, 1, 1], [0, 0, 1, 1]], "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]], "weights": [[1, 2], [1, 1]]}),
        ] {
            let geometry = Geometry::from_exchange(&value).unwrap();
            let back = Geometry::from_exchange(&geometry.to_exchange()).unwrap();
            assert_eq!(back, geometry);
        }
        for bad in [
            json!({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}),
            json!({"degree": 1, "knots": [0, 0, 1, 1]}),
            json!([1, 2]),
        ] {
            let e = Geometry::from_exchange(&bad).unwrap_err().to_string();
            assert!(!e.contains('\n'), "{e}");
        }
    }
}
