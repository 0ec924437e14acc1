//! Fitting subcommands: interpolate, natural, approximate.

use clap::Args;
use spline_core::{Error, ErrorKind, Result};

fn not_yet(what: &str) -> Error {
    Error::new(
        ErrorKind::InvalidArgument,
        format!("{what} is not supported yet"),
    )
}

#[derive(Args)]
pub struct InterpolateArgs {
    /// Points file (JSON array of arrays or whitespace/comma text), or - for standard input.
    points: String,
    /// Degree p.
    #[arg(long)]
    degree: usize,
    /// uniform, chordal, centripetal, or a JSON array of parameters.
    #[arg(long, default_value = "chordal")]
    parametrization: String,
    /// averaging, uniform, or a JSON array of knots.
    #[arg(long, default_value = "averaging")]
    knots: String,
}

#[derive(Args)]
pub struct NaturalArgs {
    /// Abscissae as a JSON array (strictly increasing).
    #[arg(long)]
    x: String,
    /// Ordinates as a JSON array.
    #[arg(long)]
    y: String,
}

#[derive(Args)]
pub struct ApproximateArgs {
    /// Points file (JSON array of arrays or whitespace/comma text), or - for standard input.
    points: String,
    /// Degree p.
    #[arg(long)]
    degree: usize,
    /// Number of control points (interior knots by The NURBS Book (9.68)).
    #[arg(long, conflicts_with = "knots")]
    control_points: Option<usize>,
    /// Knot vector as a JSON array.
    #[arg(long)]
    knots: Option<String>,
    /// uniform, chordal, centripetal, or a JSON array of parameters.
    #[arg(long, default_value = "chordal")]
    parametrization: String,
    /// Weights of the points as a JSON array.
    #[arg(long)]
    weights: Option<String>,
    /// Run parameter correction for at most ITER iterations.
    #[arg(long, value_name = "ITER")]
    correct_parameters: Option<usize>,
}

pub fn interpolate(args: &InterpolateArgs) -> Result<()> {
    Err(not_yet(&format!("interpolate {}", args.points)))
}

pub fn natural(_args: &NaturalArgs) -> Result<()> {
    Err(not_yet("natural"))
}

pub fn approximate(args: &ApproximateArgs) -> Result<()> {
    Err(not_yet(&format!("approximate {}", args.points)))
}
