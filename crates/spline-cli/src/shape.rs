//! Shape subcommands: smooth.

use clap::Args;
use spline_core::{Error, ErrorKind, Result};

#[derive(Args)]
pub struct SmoothArgs {
    /// Points file (JSON array of arrays or whitespace/comma text).
    points: String,
    /// Number of control points.
    #[arg(long)]
    control_points: usize,
    /// Degree p.
    #[arg(long, default_value_t = 3)]
    degree: usize,
    /// Number of allowed curvature extrema.
    #[arg(long)]
    curvature_extrema: usize,
    /// Parameters at which the extrema sit, as a JSON array.
    #[arg(long)]
    extremum_at: Option<String>,
}

pub fn smooth(args: &SmoothArgs) -> Result<()> {
    Err(Error::new(
        ErrorKind::InvalidArgument,
        format!("smooth {} is not supported yet", args.points),
    ))
}
