//! The spline-algebra subcommand `product` (with `--jacobian`).

use crate::io;
use crate::objects::{Object, read_object};
use clap::Args;
use serde_json::{Value, json};
use spline_algebra::{CsrMatrix, product_with_jacobians};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::BSpline;
use spline_io::exchange::CurveRecord;

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

/// A scalar B-spline function from an object file.
fn read_function(path: &str) -> Result<BSpline<f64, f64>> {
    match read_object(path)? {
        Object::Curve(c) if c.dim == 1 => Ok(c.value.map_control_points(|p| p[0])),
        Object::Curve(c) => Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!(
                "{path}: product needs B-spline functions (1-D control points), got {}-D points",
                c.dim
            ),
        )),
        Object::Nurbs(_) => Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("{path}: product needs non-rational B-spline functions, got a NURBS curve"),
        )
        .with_file(path)),
        Object::Surface(_) | Object::NurbsSurface(_) => Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("{path}: product needs B-spline functions, got a surface"),
        )
        .with_file(path)),
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
    if args.jacobian {
        let c = product_with_jacobians(&a, &b)?;
        io::print_json(&json!({
            "product": CurveRecord::from_bspline(&c.product),
            "jacobian_a": matrix_json(&c.jacobian_a),
            "jacobian_b": matrix_json(&c.jacobian_b),
        }))
    } else {
        io::print_json(&CurveRecord::from_bspline(&spline_algebra::product(
            &a, &b,
        )?))
    }
}
