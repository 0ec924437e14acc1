//! Spline functions as scipy has them (`BSpline` and `NdBSpline`): `antiderivative`,
//! `integrate`, `roots`, evaluation with extrapolation, and N-dimensional tensor-product
//! splines (`nd-eval`, `nd-interpolate`). The coordinates of a curve are the columns of one
//! [`ColumnSpline`] on its knots; the numerics are the library's.

use crate::io::{self, Pt};
use crate::objects::{Curve, Object, Sized, read_object};
use clap::builder::{PossibleValuesParser, TypedValueParser};
use clap::{Args, ValueEnum};
use serde_json::Value;
use spline_core::{Error, ErrorKind, Result};
use spline_fit::make_ndbspl;
use spline_geom::{ColumnSpline, Extrapolate, NdSpline};
use spline_io::exchange::{columns_to_value, nd_from_value, nd_to_value, nested_array};

/// `--extrapolate` (scipy's `extrapolate`): the library's names ([`Extrapolate::NAMES`]).
pub fn extrapolate_parser() -> impl TypedValueParser<Value = Extrapolate> {
    PossibleValuesParser::new(Extrapolate::NAMES).try_map(|name| Extrapolate::from_name(&name))
}

#[derive(Args)]
pub struct AntiderivativeArgs {
    /// Curve or scalar function file (JSON, non-rational), or - for standard input.
    object: String,
    /// Order K of the antiderivative (degree p + K), zero at the first knot.
    #[arg(long, default_value_t = 1)]
    order: usize,
}

#[derive(Args)]
pub struct IntegrateArgs {
    /// Curve or scalar function file (JSON, non-rational), or - for standard input.
    object: String,
    /// Lower limit.
    #[arg(long, allow_hyphen_values = true)]
    from: f64,
    /// Upper limit (below the lower one: the negative integral).
    #[arg(long, allow_hyphen_values = true)]
    to: f64,
    /// Outside the domain: continue the end pieces (on), take zero (off) or repeat the
    /// spline (periodic). Without it the limits must lie in the domain.
    #[arg(long, value_parser = extrapolate_parser())]
    extrapolate: Option<Extrapolate>,
}

#[derive(Args)]
pub struct RootsArgs {
    /// Scalar function file (JSON, a curve with 1-D control points), or - for standard input.
    object: String,
    /// For a curve of several coordinates: the coordinate whose zeros are wanted.
    #[arg(long)]
    coordinate: Option<usize>,
}

#[derive(Args)]
pub struct NdEvalArgs {
    /// N-dimensional spline file: {"degree": [k…], "knots": [[…]…], "coefficients": nested
    /// arrays, one level per dimension, of points} (a surface file works too), or -.
    object: String,
    /// Points as a JSON array of [x1, …, xd].
    #[arg(long)]
    at: String,
    /// Partial derivative orders, one per dimension (JSON).
    #[arg(long)]
    nu: Option<String>,
    /// Outside the base box: continue the end pieces (on, the default), or refuse points
    /// there (off).
    #[arg(long, value_enum, default_value_t = NdMode::On)]
    extrapolate: NdMode,
}

/// scipy's `NdBSpline(extrapolate=…)`: a flag (no periodic mode).
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum NdMode {
    /// The end pieces' polynomials continue outside the base box.
    On,
    /// Points outside the base box are refused.
    Off,
}

#[derive(Args)]
pub struct NdInterpolateArgs {
    /// The grid: one JSON array of increasing abscissae per dimension.
    #[arg(long)]
    grid: String,
    /// Values on the grid: nested JSON arrays (one level per dimension) of numbers or points.
    #[arg(long)]
    values: String,
    /// Degree in every dimension (not-a-knot knots, scipy's make_ndbspl).
    #[arg(long, default_value_t = 3)]
    degree: usize,
}

/// The coordinates of a non-rational curve as the columns of one spline on its knots.
fn columns_of(object: Object, what: &str) -> Result<ColumnSpline> {
    match object {
        Object::Curve(Sized { value, dim }) => columns(&value, dim),
        _ => Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{what} needs a non-rational curve or scalar function (a B-spline with control points and no weights)"
            ),
        )),
    }
}

fn columns(curve: &Curve, dim: usize) -> Result<ColumnSpline> {
    let c: Vec<f64> = curve
        .control_points()
        .iter()
        .flat_map(|p: &Pt| io::unpad(p, dim))
        .collect();
    ColumnSpline::new(curve.knots().knots().to_vec(), c, curve.degree(), dim)
}

pub fn antiderivative(args: &AntiderivativeArgs) -> Result<()> {
    let s = columns_of(read_object(&args.object)?, "antiderivative")?;
    io::print_json(&columns_to_value(&s.antiderivative(args.order)?))
}

pub fn integrate(args: &IntegrateArgs) -> Result<()> {
    let s = columns_of(read_object(&args.object)?, "integrate")?;
    let mode = match args.extrapolate {
        Some(mode) => mode,
        None => {
            let (a, b) = s.domain();
            for (name, v) in [("--from", args.from), ("--to", args.to)] {
                if !(v >= a && v <= b) {
                    return Err(Error::new(
                        ErrorKind::OutOfDomain,
                        format!("{name} {v} is outside the domain [{a}, {b}] (give --extrapolate on|off|periodic to integrate beyond it)"),
                    )
                    .with_value(v)
                    .with_interval(a, b));
                }
            }
            Extrapolate::On
        }
    };
    io::print_json(&s.integrate(args.from, args.to, mode)?)
}

pub fn roots(args: &RootsArgs) -> Result<()> {
    let s = columns_of(read_object(&args.object)?, "roots")?;
    let column = match (args.coordinate, s.columns()) {
        (Some(j), _) => j,
        (None, 1) => 0,
        (None, m) => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!("the curve has {m} coordinates: say which with --coordinate J"),
            ));
        }
    };
    io::print_json(&s.roots(column)?)
}

/// Evaluation with scipy's extrapolation (`eval --extrapolate`): `[param][k][coord]`.
pub fn eval_extrapolated(
    object: Object,
    at: &[f64],
    order: usize,
    mode: Extrapolate,
) -> Result<()> {
    let s = columns_of(object, "eval --extrapolate")?;
    let m = s.columns();
    io::check_output_size("eval", &[at.len(), order + 1, m])?;
    let by_order = (0..=order)
        .map(|nu| s.eval(at, nu, mode))
        .collect::<Result<Vec<_>>>()?;
    if let Some(i) = (0..at.len()).find(|&i| by_order[0][i * m].is_nan()) {
        let (a, b) = s.domain();
        return Err(Error::new(
            ErrorKind::OutOfDomain,
            format!(
                "parameter {} is outside the domain [{a}, {b}] (--extrapolate off)",
                at[i]
            ),
        )
        .with_value(at[i])
        .with_interval(a, b));
    }
    let rows: Vec<Vec<&[f64]>> = (0..at.len())
        .map(|i| by_order.iter().map(|v| &v[i * m..(i + 1) * m]).collect())
        .collect();
    io::print_json(&rows)
}

fn read_nd(path: &str) -> Result<NdSpline> {
    nd_from_value(&io::read_json(path)?)
}

pub fn nd_eval(args: &NdEvalArgs) -> Result<()> {
    let s = read_nd(&args.object)?;
    let points: Vec<Vec<f64>> = io::parse_arg("--at", &args.at)?;
    let d = s.ndim();
    if let Some(p) = points.iter().find(|p| p.len() != d) {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!(
                "--at: the spline has {d} dimensions, a point has {}",
                p.len()
            ),
        ));
    }
    let nu: Vec<usize> = match &args.nu {
        Some(text) => io::parse_arg("--nu", text)?,
        None => vec![0; d],
    };
    let flat: Vec<f64> = points.concat();
    let extrapolate = matches!(args.extrapolate, NdMode::On);
    let mut out = vec![0.0; points.len() * s.columns()];
    let nan = s.eval_into(&flat, &nu, extrapolate, &mut out)?;
    if nan > 0 {
        return Err(Error::new(
            ErrorKind::OutOfDomain,
            format!(
                "{nan} point(s) lie outside the base box (give --extrapolate on to continue the end pieces)"
            ),
        ));
    }
    let m = s.columns();
    let rows: Vec<&[f64]> = out.chunks_exact(m).collect();
    io::print_json(&rows)
}

pub fn nd_interpolate(args: &NdInterpolateArgs) -> Result<()> {
    let grid: Vec<Vec<f64>> = io::parse_arg("--grid", &args.grid)?;
    let values: Value = io::parse_arg("--values", &args.values)?;
    let (shape, m, y) = nested_array(&values, grid.len(), "--values")?;
    let sizes: Vec<usize> = grid.iter().map(Vec::len).collect();
    if shape != sizes {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("--values has shape {shape:?}, the grid {sizes:?}"),
        ));
    }
    let k = vec![args.degree; grid.len()];
    let points: Vec<&[f64]> = grid.iter().map(Vec::as_slice).collect();
    let s = make_ndbspl(&points, &y, &k, m)?;
    io::print_json(&nd_to_value(&s))
}
