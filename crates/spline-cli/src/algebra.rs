//! Spline-algebra subcommands: `product` (with `--jacobian`), `curvature`, `features`; and
//! the features of `plot --features`.

use crate::curves::{ObjectArgs, planar};
use crate::io::{self, Curve, Object};
use clap::Args;
use serde_json::{Value, json};
use spline_algebra::{CsrMatrix, ProductMap};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::BSpline;
use spline_geom::exchange::CurveRecord;

/// Root accuracy of `features`, relative to the length of the domain.
const RELATIVE_ACCURACY: f64 = 1e-12;

#[derive(Args)]
pub struct ProductArgs {
    /// First factor: a B-spline function (1-D control points), file or - for standard input.
    a: String,
    /// Second factor: a B-spline function on the same domain.
    b: String,
    /// Also print the Jacobians of the product's coefficients with respect to those of A and
    /// of B: {"product": OBJ, "jacobian_a": M, "jacobian_b": M} with
    /// M = {"rows": r, "cols": c, "entries": [[i, j, value], ...]}.
    #[arg(long)]
    jacobian: bool,
}

#[derive(Args)]
pub struct CurvatureArgs {
    /// A planar curve (JSON; B-spline or NURBS), or - for standard input.
    object: String,
    /// Parameters as a JSON array.
    #[arg(long)]
    at: String,
}

/// Parameters of the inflections and curvature extrema of a planar curve.
pub struct PlanarFeatures {
    /// Parameters of the inflections.
    pub inflections: Vec<f64>,
    /// Parameters of the curvature extrema.
    pub curvature_extrema: Vec<f64>,
}

/// Finds inflections and curvature extrema (located to `1e-12` times the domain length).
pub fn planar_features(curve: &spline_geom::Curve2) -> Result<PlanarFeatures> {
    let (a, b) = curve.domain();
    let features = spline_algebra::planar_features(curve, RELATIVE_ACCURACY * (b - a))?;
    Ok(PlanarFeatures {
        inflections: features.inflections,
        curvature_extrema: features.curvature_extrema,
    })
}

/// A scalar B-spline function from an object file.
fn read_function(path: &str) -> Result<BSpline<f64, f64>> {
    match io::read_object(path)? {
        Object::Curve(Curve { curve, dim: 1 }) => Ok(curve.map_control_points(|p| p[0])),
        Object::Curve(Curve { dim, .. }) => Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!(
                "{path}: product needs B-spline functions (1-D control points), got {dim}-D points"
            ),
        )),
        Object::Nurbs(_) => Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("{path}: product needs non-rational B-spline functions, got a NURBS curve"),
        )),
        Object::Surface(_) => Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("{path}: product needs B-spline functions, got a surface"),
        )),
    }
}

fn function_record(f: &BSpline<f64, f64>) -> CurveRecord {
    CurveRecord {
        degree: f.degree(),
        knots: f.knots().knots().to_vec(),
        control_points: f.control_points().iter().map(|&c| vec![c]).collect(),
        weights: None,
    }
}

fn matrix_json(m: &CsrMatrix<f64>) -> Value {
    let entries: Vec<Value> = m
        .triplet_iter()
        .filter(|(_, _, v)| **v != 0.0)
        .map(|(i, j, v)| json!([i, j, v]))
        .collect();
    json!({"rows": m.nrows(), "cols": m.ncols(), "entries": entries})
}

pub fn product(args: &ProductArgs) -> Result<()> {
    let a = read_function(&args.a)?;
    let b = read_function(&args.b)?;
    let map = ProductMap::new(a.knots(), b.knots())?;
    let c = map.product(&a, &b)?;
    if args.jacobian {
        let ja = map.jacobian_left(b.control_points())?;
        let jb = map.jacobian_right(a.control_points())?;
        io::print_json(&json!({
            "product": function_record(&c),
            "jacobian_a": matrix_json(&ja),
            "jacobian_b": matrix_json(&jb),
        }))
    } else {
        io::print_json(&function_record(&c))
    }
}

pub fn curvature(args: &CurvatureArgs) -> Result<()> {
    let params: Vec<f64> = io::parse_arg("--at", &args.at)?;
    let values = match io::read_object(&args.object)? {
        Object::Curve(curve) => {
            let c = planar(&curve).map_err(|e| e.context(&args.object))?;
            params
                .iter()
                .enumerate()
                .map(|(i, &u)| {
                    c.signed_curvature(u)
                        .map_err(|e| e.context(format_args!("--at entry {i}")))
                })
                .collect::<Result<Vec<f64>>>()?
        }
        Object::Nurbs(nurbs) => {
            let c = nurbs.planar().map_err(|e| e.context(&args.object))?;
            params
                .iter()
                .enumerate()
                .map(|(i, &u)| {
                    c.signed_curvature(u)
                        .map_err(|e| e.context(format_args!("--at entry {i}")))
                })
                .collect::<Result<Vec<f64>>>()?
        }
        Object::Surface(_) => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "{}: curvature needs a planar curve, got a surface",
                    args.object
                ),
            ));
        }
    };
    io::print_json(&values)
}

pub fn features(args: &ObjectArgs) -> Result<()> {
    let curve = match io::read_object(&args.object)? {
        Object::Curve(curve) => planar(&curve).map_err(|e| e.context(&args.object))?,
        Object::Nurbs(_) => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "{}: features of NURBS curves are not supported (only non-rational B-spline curves)",
                    args.object
                ),
            ));
        }
        Object::Surface(_) => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "{}: features need a planar curve, got a surface",
                    args.object
                ),
            ));
        }
    };
    let features = planar_features(&curve).map_err(|e| e.context(&args.object))?;
    io::print_json(&json!({
        "inflections": features.inflections,
        "curvature_extrema": features.curvature_extrema,
    }))
}
