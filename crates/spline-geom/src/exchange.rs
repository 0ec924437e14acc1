//! The JSON exchange format (`docs/exchange-format.md`): serde for the containers.
//!
//! A curve is `{"degree": p, "knots": [...], "control_points": [[x, ...], ...]}`; a NURBS
//! curve adds `"weights"` (control points stay Cartesian). Deserialisation validates
//! everything the constructors validate and reports the first problem.

use crate::bspline::BSpline;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, to_f64};

/// A curve as it appears in the exchange format, before validation. The `spline` tool works
/// on this record so that curves of any dimension `d ≥ 1` are accepted.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CurveRecord {
    /// The degree `p`.
    pub degree: usize,
    /// `n + p + 1` non-decreasing knots.
    pub knots: Vec<f64>,
    /// `n` points of equal dimension `d ≥ 1` (Cartesian, also for NURBS).
    pub control_points: Vec<Vec<f64>>,
    /// Positive weights of a NURBS curve.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<f64>>,
}

impl CurveRecord {
    /// The common dimension of the control points.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] without control points; [`ErrorKind::DimensionMismatch`]
    /// if the points differ in dimension or have none.
    pub fn dimension(&self) -> Result<usize> {
        let first = self.control_points.first().ok_or_else(|| {
            Error::new(ErrorKind::InvalidLength, "the curve has no control points")
        })?;
        let d = first.len();
        if d == 0 {
            return Err(Error::new(
                ErrorKind::DimensionMismatch,
                "control point 0 has no coordinates",
            ));
        }
        if let Some(i) = self.control_points.iter().position(|p| p.len() != d) {
            return Err(Error::new(
                ErrorKind::DimensionMismatch,
                format!(
                    "control point {i} has {} coordinates, control point 0 has {d}",
                    self.control_points[i].len()
                ),
            ));
        }
        Ok(d)
    }

    /// The validated knot vector.
    ///
    /// # Errors
    /// The errors of [`KnotVector::new`].
    pub fn knot_vector(&self) -> Result<KnotVector<f64>> {
        KnotVector::new(self.degree, self.knots.clone())
    }

    /// The curve as one B-spline function per coordinate, all on the same knots: the form in
    /// which the tool applies structural operations to curves of any dimension.
    ///
    /// # Errors
    /// The errors of [`CurveRecord::dimension`], [`KnotVector::new`] and [`BSpline::new`].
    pub fn coordinate_functions(&self) -> Result<Vec<BSpline<f64, f64>>> {
        let d = self.dimension()?;
        let knots = self.knot_vector()?;
        (0..d)
            .map(|c| {
                BSpline::new(
                    knots.clone(),
                    self.control_points.iter().map(|p| p[c]).collect(),
                )
            })
            .collect()
    }

    /// Reassembles coordinate functions (same knots) into a record.
    ///
    /// # Panics
    /// If `functions` is empty or their sizes differ.
    #[must_use]
    pub fn from_coordinate_functions(functions: &[BSpline<f64, f64>]) -> Self {
        let first = &functions[0];
        let n = first.control_points().len();
        Self {
            degree: first.degree(),
            knots: first.knots().knots().to_vec(),
            control_points: (0..n)
                .map(|i| functions.iter().map(|f| f.control_points()[i]).collect())
                .collect(),
            weights: None,
        }
    }

    /// The record of a B-spline.
    pub fn from_bspline<T: Scalar, P: ControlPoint<T>>(curve: &BSpline<T, P>) -> Self {
        Self {
            degree: curve.degree(),
            knots: curve.knots().knots().iter().map(|&k| to_f64(k)).collect(),
            control_points: curve
                .control_points()
                .iter()
                .map(|p| (0..P::DIM).map(|i| to_f64(p.coord(i))).collect())
                .collect(),
            weights: None,
        }
    }

    /// Validates the record as a non-rational B-spline with control points of type `P`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] if the record has weights;
    /// [`ErrorKind::DimensionMismatch`] if a point does not have `P::DIM` coordinates; the
    /// errors of [`BSpline::from_knots`].
    pub fn to_bspline<T: Scalar, P: ControlPoint<T>>(&self) -> Result<BSpline<T, P>> {
        if self.weights.is_some() {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "the curve has weights: read it as a NURBS curve",
            ));
        }
        let points = points_from_rows::<T, P>(&self.control_points)?;
        BSpline::from_knots(
            self.degree,
            self.knots.iter().map(|&k| cast(k)).collect(),
            points,
        )
    }
}

/// Converts rows of coordinates into points of type `P`, checking dimensions.
///
/// # Errors
/// [`ErrorKind::DimensionMismatch`] if a row does not have `P::DIM` coordinates.
pub fn points_from_rows<T: Scalar, P: ControlPoint<T>>(rows: &[Vec<f64>]) -> Result<Vec<P>> {
    rows.iter()
        .enumerate()
        .map(|(i, row)| {
            if row.len() == P::DIM {
                Ok(P::from_coords(|c| cast(row[c])))
            } else {
                Err(Error::new(
                    ErrorKind::DimensionMismatch,
                    format!(
                        "point {i} has {} coordinates, expected {}",
                        row.len(),
                        P::DIM
                    ),
                ))
            }
        })
        .collect()
}

impl<T: Scalar, P: ControlPoint<T>> Serialize for BSpline<T, P> {
    fn serialize<S: Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        CurveRecord::from_bspline(self).serialize(serializer)
    }
}

impl<'de, T: Scalar, P: ControlPoint<T>> Deserialize<'de> for BSpline<T, P> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> std::result::Result<Self, D::Error> {
        let record = CurveRecord::deserialize(deserializer)?;
        record.to_bspline().map_err(serde::de::Error::custom)
    }
}
