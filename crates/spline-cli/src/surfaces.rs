//! NURBS curves and tensor-product surfaces in the tool: evaluation, structural operations,
//! `make` constructions and `mesh`.

use crate::curves::{Direction, Operation};
use clap::Args;
use serde_json::Value;
use spline_core::{Error, ErrorKind, Result};
use spline_geom::exchange::CurveRecord;
use spline_geom::export::SvgPlot;

fn not_yet(what: &str) -> Error {
    Error::new(
        ErrorKind::InvalidArgument,
        format!("{what} is not supported yet"),
    )
}

#[derive(Args)]
pub struct MakeArgs {
    /// What to build: circle, arc, conic, extrude, ruled, cone, revolve, sphere, torus.
    kind: String,
}

#[derive(Args)]
pub struct MeshArgs {
    /// Surface file (JSON), or - for standard input.
    surface: String,
    /// Output mesh: FILE.obj or FILE.off.
    #[arg(short, long)]
    output: String,
}

/// `[param][k][coord]` rational derivatives of a NURBS curve.
pub fn eval_nurbs(_record: &CurveRecord, _params: &[f64], _order: usize) -> Result<Value> {
    Err(not_yet("NURBS evaluation"))
}

/// `[param][k][l][coord]` partial derivatives of a surface.
pub fn eval_surface(_surface: Value, _params: &[[f64; 2]], _order: usize) -> Result<Value> {
    Err(not_yet("surface evaluation"))
}

/// A structural operation on a NURBS curve.
pub fn apply_to_nurbs(_record: &CurveRecord, _operation: &Operation) -> Result<Value> {
    Err(not_yet("this operation on NURBS curves"))
}

/// A structural operation on a surface in one direction.
pub fn apply_to_surface(
    _surface: Value,
    _operation: &Operation,
    _direction: Option<Direction>,
) -> Result<Value> {
    Err(not_yet("this operation on surfaces"))
}

/// Draws a NURBS curve.
pub fn plot_nurbs(_svg: &mut SvgPlot, _record: &CurveRecord, _comb: bool) -> Result<()> {
    Err(not_yet("plotting NURBS curves"))
}

pub fn make(args: &MakeArgs) -> Result<()> {
    Err(not_yet(&format!("make {}", args.kind)))
}

pub fn mesh(args: &MeshArgs) -> Result<()> {
    Err(not_yet(&format!(
        "meshing {} into {}",
        args.surface, args.output
    )))
}
