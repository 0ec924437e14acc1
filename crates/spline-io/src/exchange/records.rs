//! The records of the exchange format: curves and surfaces as they appear in the JSON, before
//! validation, and their conversions to and from the containers.

use super::decode::{deserialize, json_kind};
use nalgebra::SVector;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, to_f64};
use spline_geom::{BSpline, Bezier, Homogeneous, NurbsCurve, NurbsSurface, Surface};

/// A curve as it appears in the exchange format, before validation (the dimension `d ≥ 1` of
/// the points is only known at run time).
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

    /// The record of a B-spline.
    pub fn from_bspline<T: Scalar, P: ControlPoint<T>>(curve: &BSpline<T, P>) -> Self {
        Self {
            degree: curve.degree(),
            knots: knots_of(curve.knots()),
            control_points: curve.control_points().iter().map(row_of::<T, P>).collect(),
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
        refuse_weights(self.weights.as_ref(), "curve")?;
        let points = points_from_rows::<T, P>(&self.control_points)?;
        BSpline::from_knots(
            self.degree,
            self.knots.iter().map(|&k| cast(k)).collect(),
            points,
        )
    }
}

impl CurveRecord {
    /// The record of a Bézier curve: the clamped B-spline of one segment, knots `p + 1`
    /// copies of `a`, then `p + 1` copies of `b`.
    pub fn from_bezier<T: Scalar, P: ControlPoint<T>>(curve: &Bezier<T, P>) -> Self {
        let n = curve.degree();
        let (a, b) = curve.interval();
        Self {
            degree: n,
            knots: std::iter::repeat_n(to_f64(a), n + 1)
                .chain(std::iter::repeat_n(to_f64(b), n + 1))
                .collect(),
            control_points: curve.control_points().iter().map(row_of::<T, P>).collect(),
            weights: None,
        }
    }

    /// Validates the record as a Bézier curve: `p + 1` control points on the knots
    /// `[a; p + 1] + [b; p + 1]`.
    ///
    /// # Errors
    /// As [`CurveRecord::to_bspline`]; [`ErrorKind::InvalidLength`] unless there are `p + 1`
    /// control points; [`ErrorKind::InvalidArgument`] unless the knots are clamped at both ends.
    pub fn to_bezier<T: Scalar, P: ControlPoint<T>>(&self) -> Result<Bezier<T, P>> {
        let curve: BSpline<T, P> = self.to_bspline()?;
        let p = curve.degree();
        if curve.control_points().len() != p + 1 {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "a Bézier curve of degree {p} has {} control points and knots [a; p+1] + [b; p+1], got {} control points",
                    p + 1,
                    curve.control_points().len()
                ),
            ));
        }
        let knots = curve.knots().knots();
        let (a, b) = curve.domain();
        if knots[..=p].iter().any(|&k| k != a) || knots[p + 1..].iter().any(|&k| k != b) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "a Bézier curve has the knots [a; p+1] + [b; p+1]",
            ));
        }
        Bezier::with_interval(curve.control_points().to_vec(), a, b)
    }
}

impl CurveRecord {
    /// Reads a record from JSON text (no validation beyond the fields; see
    /// [`CurveRecord::dimension`], [`CurveRecord::to_bspline`], [`CurveRecord::to_nurbs`]).
    ///
    /// # Errors
    /// [`ErrorKind::Parse`] with serde_json's message (missing or unknown fields, wrong types,
    /// syntax), which the caller completes with what was read.
    pub fn from_json(text: &str) -> Result<Self> {
        from_json(text)
    }

    /// The record as compact JSON text.
    #[must_use]
    pub fn to_json(&self) -> String {
        to_json(self)
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

// ---------------------------------------------------------------------------------------
// NURBS curves and tensor-product surfaces.

/// A record read from JSON text ([`ErrorKind::Parse`] with serde_json's message and line).
fn from_json<R: DeserializeOwned>(text: &str) -> Result<R> {
    serde_json::from_str(text)
        .map_err(|e| Error::new(ErrorKind::Parse, e.to_string()).with_line(e.line()))
}

/// A record as compact JSON text.
fn to_json<R: Serialize>(record: &R) -> String {
    // A record holds numbers, vectors and options only: serialising cannot fail.
    serde_json::to_string(record).unwrap_or_default()
}

/// [`ErrorKind::InvalidArgument`] if a record of a `what` (curve, surface) read as
/// non-rational has weights.
fn refuse_weights<W>(weights: Option<&W>, what: &str) -> Result<()> {
    match weights {
        Some(_) => Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("the {what} has weights: read it as a NURBS {what}"),
        )),
        None => Ok(()),
    }
}

/// The knots as `f64`.
fn knots_of<T: Scalar>(knots: &KnotVector<T>) -> Vec<f64> {
    knots.knots().iter().map(|&k| to_f64(k)).collect()
}

fn row_of<T: Scalar, P: ControlPoint<T>>(p: &P) -> Vec<f64> {
    (0..P::DIM).map(|i| to_f64(p.coord(i))).collect()
}

fn cast_all<T: Scalar>(values: &[f64]) -> Vec<T> {
    values.iter().map(|&x| cast(x)).collect()
}

impl CurveRecord {
    /// The record of a NURBS curve: Cartesian control points and their weights.
    pub fn from_nurbs<T: Scalar, const D: usize>(curve: &NurbsCurve<T, D>) -> Self {
        Self {
            degree: curve.degree(),
            knots: knots_of(curve.knots()),
            control_points: curve.control_points().iter().map(row_of::<T, _>).collect(),
            weights: Some(curve.weights().iter().map(|&w| to_f64(w)).collect()),
        }
    }

    /// Validates the record as a NURBS curve in `R^D`; a record without weights is read
    /// with unit weights.
    ///
    /// # Errors
    /// [`ErrorKind::DimensionMismatch`] if a point does not have `D` coordinates; the errors
    /// of [`KnotVector::new`] and [`NurbsCurve::new`] (e.g. [`ErrorKind::InvalidWeight`],
    /// [`ErrorKind::InvalidLength`] for a wrong number of weights).
    pub fn to_nurbs<T: Scalar, const D: usize>(&self) -> Result<NurbsCurve<T, D>> {
        let points = points_from_rows::<T, SVector<T, D>>(&self.control_points)?;
        let weights = self
            .weights
            .as_deref()
            .map_or_else(|| vec![T::one(); points.len()], cast_all);
        NurbsCurve::new(
            KnotVector::new(self.degree, cast_all(&self.knots))?,
            points,
            weights,
        )
    }
}

/// A tensor-product surface as it appears in the exchange format, before validation:
/// `{"degree": [p, q], "knots": [[u...], [v...]], "control_points": [[[x, ...], ...], ...]}`
/// with `control_points[i][j]`, `i` along `u`, and for NURBS `"weights": [[w_ij]]`
/// (control points stay Cartesian).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceRecord {
    /// The degrees `[p, q]`.
    pub degree: [usize; 2],
    /// The knot vectors in `u` and `v`.
    pub knots: [Vec<f64>; 2],
    /// The control net: `n_u` rows of `n_v` points of equal dimension `d ≥ 1`.
    pub control_points: Vec<Vec<Vec<f64>>>,
    /// Positive weights of a NURBS surface, in the shape of the net.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<Vec<f64>>>,
}

/// Knot vectors in `u` and `v` and the control net as rows.
type Net<T, P> = (KnotVector<T>, KnotVector<T>, Vec<Vec<P>>);

impl SurfaceRecord {
    /// The common dimension of the control points.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] for an empty net; [`ErrorKind::DimensionMismatch`] if the
    /// points differ in dimension or have none.
    pub fn dimension(&self) -> Result<usize> {
        let first = self.control_points.iter().flatten().next().ok_or_else(|| {
            Error::new(
                ErrorKind::InvalidLength,
                "the surface has no control points",
            )
        })?;
        let d = first.len();
        if d == 0 {
            return Err(Error::new(
                ErrorKind::DimensionMismatch,
                "control point (0, 0) has no coordinates",
            ));
        }
        for (i, row) in self.control_points.iter().enumerate() {
            if let Some(j) = row.iter().position(|p| p.len() != d) {
                return Err(Error::new(
                    ErrorKind::DimensionMismatch,
                    format!(
                        "control point ({i}, {j}) has {} coordinates, the first has {d}",
                        row[j].len()
                    ),
                ));
            }
        }
        Ok(d)
    }

    /// Whether the record has weights.
    #[must_use]
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }

    /// The validated knot vectors in `u` and `v`.
    ///
    /// # Errors
    /// The errors of [`KnotVector::new`], with the direction in the message.
    pub fn knot_vectors<T: Scalar>(&self) -> Result<(KnotVector<T>, KnotVector<T>)> {
        let ku = KnotVector::new(self.degree[0], cast_all(&self.knots[0]))
            .map_err(|e| e.context("knots in u"))?;
        let kv = KnotVector::new(self.degree[1], cast_all(&self.knots[1]))
            .map_err(|e| e.context("knots in v"))?;
        Ok((ku, kv))
    }

    /// The control net as points of type `P`, checked against the knot vectors.
    fn net<T: Scalar, P: ControlPoint<T>>(&self) -> Result<Net<T, P>> {
        let (ku, kv) = self.knot_vectors()?;
        let net = self
            .control_points
            .iter()
            .enumerate()
            .map(|(i, row)| {
                points_from_rows::<T, P>(row).map_err(|e| e.context(format_args!("row {i}")))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok((ku, kv, net))
    }

    /// The record of a non-rational surface.
    pub fn from_surface<T: Scalar, P: ControlPoint<T>>(surface: &Surface<T, P>) -> Self {
        Self {
            degree: [surface.degrees().0, surface.degrees().1],
            knots: [knots_of(surface.knots_u()), knots_of(surface.knots_v())],
            control_points: surface
                .control_net()
                .iter()
                .map(|row| row.iter().map(row_of::<T, P>).collect())
                .collect(),
            weights: None,
        }
    }

    /// Validates the record as a non-rational surface with control points of type `P`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] if the record has weights;
    /// [`ErrorKind::DimensionMismatch`]; [`ErrorKind::InvalidLength`] if the net does not
    /// match the knot vectors; the errors of [`KnotVector::new`].
    pub fn to_surface<T: Scalar, P: ControlPoint<T>>(&self) -> Result<Surface<T, P>> {
        refuse_weights(self.weights.as_ref(), "surface")?;
        let (ku, kv, net) = self.net::<T, P>()?;
        Surface::from_net(ku, kv, net)
    }

    /// The record of a NURBS surface: Cartesian control points and weights.
    pub fn from_nurbs_surface<T: Scalar, const D: usize>(surface: &NurbsSurface<T, D>) -> Self {
        let mut record = Self::from_surface(
            &surface
                .homogeneous()
                .map_control_points(Homogeneous::project),
        );
        let nv = surface.net_size().1;
        record.weights = Some(
            surface
                .weights()
                .chunks_exact(nv)
                .map(|row| row.iter().map(|&w| to_f64(w)).collect())
                .collect(),
        );
        record
    }

    /// Validates the record as a NURBS surface in `R^D` (unit weights if it has none).
    ///
    /// # Errors
    /// As [`SurfaceRecord::to_surface`]; [`ErrorKind::InvalidLength`] if the weights do not
    /// have the shape of the net; [`ErrorKind::InvalidWeight`].
    pub fn to_nurbs_surface<T: Scalar, const D: usize>(&self) -> Result<NurbsSurface<T, D>> {
        let (ku, kv, net) = self.net::<T, SVector<T, D>>()?;
        let weights = match &self.weights {
            Some(w) => w.iter().map(|row| cast_all(row)).collect(),
            None => net.iter().map(|row| vec![T::one(); row.len()]).collect(),
        };
        NurbsSurface::from_net(ku, kv, net, weights)
    }
}

impl SurfaceRecord {
    /// Reads a record from JSON text (no validation beyond the fields; see
    /// [`SurfaceRecord::dimension`], [`SurfaceRecord::to_surface`],
    /// [`SurfaceRecord::to_nurbs_surface`]).
    ///
    /// # Errors
    /// [`ErrorKind::Parse`] with serde_json's message, which the caller completes with what
    /// was read.
    pub fn from_json(text: &str) -> Result<Self> {
        from_json(text)
    }

    /// The record as compact JSON text.
    #[must_use]
    pub fn to_json(&self) -> String {
        to_json(self)
    }
}

/// An object of the exchange format, curve or surface, before validation.
#[derive(Clone, Debug, PartialEq)]
pub enum Record {
    /// A curve (a NURBS curve if it has weights).
    Curve(CurveRecord),
    /// A tensor-product surface (a NURBS surface if it has weights).
    Surface(SurfaceRecord),
}

impl Record {
    /// Reads an object of the exchange format: a surface has a pair of degrees, anything
    /// else is read as a curve. The reports of the tool (`spline smooth`, `offset`,
    /// `reduce`, …) hold their object under `"curve"` or `"surface"`: an object without
    /// `"knots"` that has one of these fields is read as that field, so every reader accepts
    /// what the tool writes.
    ///
    /// # Errors
    /// [`ErrorKind::Parse`] for a value that is not a JSON object
    /// (`expected a JSON object with degree, knots and control_points, got an array`) or not
    /// a record (the message names the field: `malformed curve: field knots: …`).
    pub fn from_value(value: Value) -> Result<Self> {
        if !value.is_object() {
            return Err(Error::new(
                ErrorKind::Parse,
                format!(
                    "expected a JSON object with degree, knots and control_points, got {}",
                    json_kind(&value)
                ),
            ));
        }
        if value.get("knots").is_none() {
            for key in ["curve", "surface"] {
                if let Some(inner) = value.get(key).filter(|v| v.is_object()) {
                    return Self::from_value(inner.clone());
                }
            }
        }
        if value.get("degree").is_some_and(Value::is_array) {
            Ok(Self::Surface(deserialize("surface", value)?))
        } else {
            Ok(Self::Curve(deserialize("curve", value)?))
        }
    }
}
