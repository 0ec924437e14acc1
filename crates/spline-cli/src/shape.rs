//! Shape subcommands: smooth (the selective eraser of curvature extrema).

use crate::io;
use clap::Args;
use nalgebra::Vector2;
use serde_json::json;
use spline_core::{Error, ErrorKind, Result};
use spline_geom::exchange::CurveRecord;
use spline_shape::{EraserOptions, erase_curvature_extrema};

#[derive(Args)]
pub struct SmoothArgs {
    /// Planar points: a JSON array of [x, y], or a text file (e.g. a UIUC airfoil .dat file).
    points: String,
    /// Number of control points of the curve.
    #[arg(long)]
    control_points: usize,
    /// Degree of the curve (at least 3).
    #[arg(long, default_value_t = 3)]
    degree: usize,
    /// Number of curvature extrema the curve may have.
    #[arg(long)]
    curvature_extrema: usize,
    /// Where the extrema sit, as a JSON array of chord-length parameters in (0, 1); by default
    /// the strongest extrema of the least-squares fit.
    #[arg(long)]
    extremum_at: Option<String>,
    /// Whether the curvature increases on the first piece (default: as in the least-squares
    /// fit).
    #[arg(long)]
    increasing_first: Option<bool>,
}

pub fn smooth(args: &SmoothArgs) -> Result<()> {
    let rows = io::read_points(&args.points)?;
    let points = rows
        .iter()
        .map(|r| match r.as_slice() {
            [x, y] => Ok(Vector2::new(*x, *y)),
            _ => Err(Error::new(
                ErrorKind::DimensionMismatch,
                format!(
                    "smooth needs planar points (2 coordinates), got {}",
                    r.len()
                ),
            )),
        })
        .collect::<Result<Vec<_>>>()?;
    let mut options = EraserOptions::new(args.control_points, args.curvature_extrema);
    options.degree = args.degree;
    options.increasing_first = args.increasing_first;
    if let Some(text) = &args.extremum_at {
        options.extremum_params = Some(io::parse_arg("--extremum-at", text)?);
    }
    let result = erase_curvature_extrema(&points, &options)?;
    io::print_json(&json!({
        "curve": CurveRecord::from_bspline(&result.curve),
        "max_deviation": result.max_deviation,
        "max_deviation_index": result.max_deviation_index,
        "rms_deviation": result.rms_deviation,
        "curvature_extrema": result.curvature_extrema,
        "inflections": result.inflections,
        "extremum_params": result.extremum_params,
        "least_squares_curvature_extrema": result.least_squares_extrema,
    }))
}
