//! The evaluation subcommands: `basis` and `eval` (curves of every kind and surfaces).

use crate::io::{self, Pt};
use crate::objects::{Object, read_object};
use clap::Args;
use spline_core::{KnotVector, Result};
use spline_geom::{ParamCurve, ParamSurface};

#[derive(Args)]
pub struct BasisArgs {
    /// Degree p.
    #[arg(long)]
    degree: usize,
    /// Knot vector as a JSON array.
    #[arg(long)]
    knots: String,
    /// Parameters as a JSON array.
    #[arg(long)]
    at: String,
    /// Highest derivative order K.
    #[arg(long, default_value_t = 0)]
    derivatives: usize,
}

#[derive(Args)]
pub struct EvalArgs {
    /// Object file (JSON), or - for standard input.
    object: String,
    /// Parameters: [u, ...] for curves, [[u, v], ...] for surfaces.
    #[arg(long)]
    at: String,
    /// Highest derivative order K.
    #[arg(long, default_value_t = 0)]
    derivatives: usize,
    /// Curves: evaluate outside the domain as scipy does (on: the end pieces continue; off:
    /// NaN there; periodic: the spline repeats). Without it, parameters outside are an error.
    #[arg(long, value_parser = crate::functions::extrapolate_parser())]
    extrapolate: Option<spline_geom::Extrapolate>,
}

pub fn basis(args: &BasisArgs) -> Result<()> {
    let knots: Vec<f64> = io::parse_arg("--knots", &args.knots)?;
    let params: Vec<f64> = io::parse_arg("--at", &args.at)?;
    let knots = KnotVector::new(args.degree, knots).map_err(|e| e.context("--knots"))?;
    check_order("--derivatives", args.derivatives)?;
    io::check_output_size(
        "basis",
        &[params.len(), args.derivatives + 1, knots.num_basis()],
    )?;
    let rows = params
        .iter()
        .enumerate()
        .map(|(i, &u)| {
            knots
                .dense_basis_derivatives(u, args.derivatives)
                .map_err(|e| e.context(format_args!("--at entry {i}")))
        })
        .collect::<Result<Vec<_>>>()?;
    io::print_json(&rows)
}

/// Checks a derivative order given on the command line against
/// [`spline_core::MAX_DERIVATIVE_ORDER`].
fn check_order(option: &str, order: usize) -> Result<()> {
    spline_core::check_derivative_order(order).map_err(|e| e.context(option))
}

/// `[param][k][coord]` for a curve of any kind; points unpadded to `dim`. The order and the
/// size of the output are checked before anything is computed.
fn eval_curve<C: ParamCurve<f64, Point = Pt>>(
    curve: &C,
    dim: usize,
    params: &[f64],
    order: usize,
) -> Result<Vec<Vec<Vec<f64>>>> {
    check_order("--derivatives", order)?;
    io::check_output_size("eval", &[params.len(), order + 1, dim])?;
    let mut ders = vec![Pt::zeros(); order + 1];
    params
        .iter()
        .enumerate()
        .map(|(i, &u)| {
            curve
                .derivatives_into(u, &mut ders)
                .map_err(|e| e.context(format_args!("--at entry {i}")))?;
            Ok(ders.iter().map(|p| io::unpad(p, dim)).collect())
        })
        .collect()
}

/// `[param][k][l][coord]` partial derivatives of a surface of any kind, `k, l = 0..=order`.
fn eval_surface<S: ParamSurface<f64, Point = Pt>>(
    surface: &S,
    dim: usize,
    params: &[[f64; 2]],
    order: usize,
) -> Result<Vec<Vec<Vec<Vec<f64>>>>> {
    check_order("--derivatives", order)?;
    let width = order + 1;
    io::check_output_size("eval", &[params.len(), width, width, dim])?;
    let mut flat = vec![Pt::zeros(); width * width];
    params
        .iter()
        .enumerate()
        .map(|(i, &[u, v])| {
            surface
                .derivatives_into(u, v, order, &mut flat)
                .map_err(|e| e.context(format_args!("--at entry {i}")))?;
            Ok(flat
                .chunks_exact(width)
                .map(|row| row.iter().map(|p| io::unpad(p, dim)).collect())
                .collect())
        })
        .collect()
}

pub fn eval(args: &EvalArgs) -> Result<()> {
    let order = args.derivatives;
    let curve_params = || io::parse_arg::<Vec<f64>>("--at", &args.at);
    let surface_params = || io::parse_arg::<Vec<[f64; 2]>>("--at", &args.at);
    let object = read_object(&args.object)?;
    if let Some(mode) = args.extrapolate {
        return crate::functions::eval_extrapolated(object, &curve_params()?, order, mode);
    }
    match object {
        Object::Curve(c) => io::print_json(&eval_curve(&c.value, c.dim, &curve_params()?, order)?),
        Object::Nurbs(c) => io::print_json(&eval_curve(&c.value, c.dim, &curve_params()?, order)?),
        Object::Surface(s) => {
            io::print_json(&eval_surface(&s.value, s.dim, &surface_params()?, order)?)
        }
        Object::NurbsSurface(s) => {
            io::print_json(&eval_surface(&s.value, s.dim, &surface_params()?, order)?)
        }
    }
}
