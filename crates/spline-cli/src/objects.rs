//! The objects of the tool: curves, NURBS curves and surfaces of run-time dimension, read
//! from the exchange format and written back. Points are padded to [`MAX_DIM`]
//! coordinates (zeros stay zero under every affine combination and under the rational
//! projection), so one instantiation of the library serves every dimension.

use crate::io::{self, MAX_DIM, Pt};
use serde::Serialize;
use serde_json::Value;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::{BSpline, NurbsCurve, NurbsSurface, Surface};
use spline_io::exchange::{CurveRecord, Record, SurfaceRecord};

/// A B-spline curve with padded points.
pub type Curve = BSpline<f64, Pt>;
/// A NURBS curve with padded points.
pub type Nurbs = NurbsCurve<f64, MAX_DIM>;
/// A B-spline surface with padded points.
pub type Surf = Surface<f64, Pt>;
/// A NURBS surface with padded points.
pub type NurbsSurf = NurbsSurface<f64, MAX_DIM>;

/// An object with the number of meaningful coordinates of its points.
#[derive(Clone, Debug)]
pub struct Sized<X> {
    /// The object, with points padded to [`MAX_DIM`] coordinates.
    pub value: X,
    /// The number of meaningful coordinates.
    pub dim: usize,
}

impl<X> Sized<X> {
    /// Another object of the same dimension.
    pub fn with<Y>(&self, value: Y) -> Sized<Y> {
        Sized {
            value,
            dim: self.dim,
        }
    }
}

/// What an object file holds, validated.
pub enum Object {
    /// A non-rational curve.
    Curve(Sized<Curve>),
    /// A NURBS curve (a record with weights).
    Nurbs(Sized<Nurbs>),
    /// A non-rational tensor-product surface.
    Surface(Sized<Surf>),
    /// A NURBS surface.
    NurbsSurface(Sized<NurbsSurf>),
}

/// The exchange-format record of an object, with its points cut to their dimension.
pub trait ToRecord {
    /// The record.
    fn record(&self, dim: usize) -> impl Serialize;
}

fn cut_rows(rows: &mut [Vec<f64>], dim: usize) {
    for row in rows {
        row.truncate(dim);
    }
}

impl ToRecord for Curve {
    fn record(&self, dim: usize) -> impl Serialize {
        let mut record = CurveRecord::from_bspline(self);
        cut_rows(&mut record.control_points, dim);
        record
    }
}

impl ToRecord for Nurbs {
    fn record(&self, dim: usize) -> impl Serialize {
        let mut record = CurveRecord::from_nurbs(self);
        cut_rows(&mut record.control_points, dim);
        record
    }
}

impl ToRecord for Surf {
    fn record(&self, dim: usize) -> impl Serialize {
        let mut record = SurfaceRecord::from_surface(self);
        for row in &mut record.control_points {
            cut_rows(row, dim);
        }
        record
    }
}

impl ToRecord for NurbsSurf {
    fn record(&self, dim: usize) -> impl Serialize {
        let mut record = SurfaceRecord::from_nurbs_surface(self);
        for row in &mut record.control_points {
            cut_rows(row, dim);
        }
        record
    }
}

impl<X: ToRecord> Sized<X> {
    /// The record of the object as encoded JSON.
    ///
    /// # Errors
    /// As [`io::raw`].
    pub fn json(&self) -> Result<io::Json> {
        io::raw(&self.value.record(self.dim))
    }
}

/// Reads an object file and tells curves, NURBS curves and surfaces apart: a surface has a
/// pair of degrees, a NURBS object has weights. Every error names the file.
///
/// # Errors
/// [`ErrorKind::Io`] or [`ErrorKind::Parse`] for unreadable files; the errors of the
/// constructors for invalid objects.
pub fn read_object(path: &str) -> Result<Object> {
    let value = io::read_json(path)?;
    classify(value).map_err(|e| e.context(path))
}

/// Classifies and validates a JSON object (see [`read_object`];
/// [`Record::from_value`] reads the record, reports of the tool included).
///
/// # Errors
/// As [`read_object`].
pub fn classify(value: Value) -> Result<Object> {
    match Record::from_value(value)? {
        Record::Curve(record) => curve_from_record(&record),
        Record::Surface(record) => surface_from_record(&record),
    }
}

fn curve_from_record(record: &CurveRecord) -> Result<Object> {
    let dim = record.dimension()?;
    let points = record
        .control_points
        .iter()
        .map(|r| io::pad(r))
        .collect::<Result<Vec<_>>>()?;
    let knots = KnotVector::new(record.degree, record.knots.clone())?;
    Ok(match &record.weights {
        None => Object::Curve(Sized {
            value: BSpline::new(knots, points)?,
            dim,
        }),
        Some(weights) => Object::Nurbs(Sized {
            value: NurbsCurve::new(knots, points, weights.clone())?,
            dim,
        }),
    })
}

fn surface_from_record(record: &SurfaceRecord) -> Result<Object> {
    let dim = record.dimension()?;
    let (ku, kv) = record.knot_vectors::<f64>()?;
    let net = record
        .control_points
        .iter()
        .map(|row| row.iter().map(|p| io::pad(p)).collect::<Result<Vec<_>>>())
        .collect::<Result<Vec<_>>>()?;
    Ok(match &record.weights {
        None => Object::Surface(Sized {
            value: Surface::from_net(ku, kv, net)?,
            dim,
        }),
        Some(weights) => Object::NurbsSurface(Sized {
            value: NurbsSurface::from_net(ku, kv, net, weights.clone())?,
            dim,
        }),
    })
}

/// An object as a curve: NURBS curves as they are, B-spline curves with unit weights
/// (`rational` tells which).
pub struct AnyCurve {
    /// The curve as a NURBS curve.
    pub curve: Sized<Nurbs>,
    /// Whether the file held weights.
    pub rational: bool,
}

impl AnyCurve {
    /// The polynomial curve behind a unit-weight NURBS curve.
    ///
    /// # Panics
    /// If the curve was rational (a programmer error).
    pub fn polynomial(&self) -> Curve {
        self.curve
            .value
            .to_bspline()
            .expect("a B-spline read as NURBS has unit weights")
    }
}

/// Reads a curve of either kind (see [`AnyCurve`]).
///
/// # Errors
/// As [`read_object`]; [`ErrorKind::InvalidArgument`] for a surface.
pub fn read_curve(path: &str) -> Result<AnyCurve> {
    match read_object(path)? {
        Object::Curve(c) => Ok(AnyCurve {
            curve: c.with(NurbsCurve::from_bspline(&c.value)),
            rational: false,
        }),
        Object::Nurbs(c) => Ok(AnyCurve {
            curve: c,
            rational: true,
        }),
        Object::Surface(_) | Object::NurbsSurface(_) => Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("{path}: expected a curve, got a surface"),
        )
        .with_file(path)),
    }
}

/// The first `D` coordinates of the points of a curve of dimension `D` (planar curves for
/// curvature, features and pictures).
///
/// # Errors
/// [`ErrorKind::DimensionMismatch`] unless the points have `D` coordinates.
pub fn check_dim(dim: usize, wanted: usize, what: &str) -> Result<()> {
    if dim == wanted {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("expected {what} ({wanted} coordinates), got {dim}"),
        ))
    }
}

/// The 3-D surface in an object read from `path`, as a NURBS surface (a B-spline surface
/// with unit weights); `what` says what needs it, for messages.
pub fn surface3(object: &Object, path: &str, what: &str) -> Result<spline_geom::NurbsSurface3> {
    let to3 = |p: &Pt| nalgebra::Vector3::new(p[0], p[1], p[2]);
    let (dim, surface) = match object {
        Object::Surface(s) => (
            s.dim,
            NurbsSurface::from_surface(&s.value.map_control_points(to3)),
        ),
        Object::NurbsSurface(s) => (s.dim, s.value.map_control_points(to3)),
        Object::Curve(_) | Object::Nurbs(_) => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "{path}: {what} needs a surface (degree [p, q]); use `spline features` for curves"
                ),
            )
            .with_file(path));
        }
    };
    if dim != 3 {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("{path}: {what} needs a surface in 3-D space, got {dim} coordinates"),
        ));
    }
    Ok(surface)
}
