//! Shape subcommands: smooth (the selective eraser of curvature extrema).

use crate::io;
use clap::Args;
use nalgebra::Vector2;
use serde_json::{Value, json};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::exchange::CurveRecord;
use spline_shape::{Extremum, Objective, SmoothedCurve, SmoothingOptions, smooth as erase};

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
    /// Number of curvature extrema the curve may have (alternating maximum, minimum, …,
    /// placed automatically); --extremum gives them one by one instead.
    #[arg(long)]
    curvature_extrema: Option<usize>,
    /// An allowed extremum: max, min, max@U or min@U (U in (0, 1)); repeat in the order of
    /// the data.
    #[arg(long = "extremum", value_name = "KIND[@U]")]
    extrema: Vec<String>,
    /// What is minimised: the largest deviation (default) or the sum of squares.
    #[arg(long, default_value = "max")]
    objective: String,
    /// Rounds of constrained solve and parameter correction, at most.
    #[arg(long, default_value_t = 40)]
    rounds: usize,
    /// Exponent β of the knot density |C′| (κ L + c)^β (0: knots uniform in arc length).
    #[arg(long, default_value_t = 0.5)]
    knot_exponent: f64,
    /// Floor c of the knot density.
    #[arg(long, default_value_t = 0.6)]
    knot_floor: f64,
    /// Stop after this many rounds without improvement.
    #[arg(long, default_value_t = 6)]
    patience: usize,
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
    let mut options = SmoothingOptions::new(args.control_points);
    options.degree = args.degree;
    options.max_rounds = args.rounds;
    options.knot_exponent = args.knot_exponent;
    options.knot_floor = args.knot_floor;
    options.patience = args.patience;
    options.objective = match args.objective.as_str() {
        "max" => Objective::MaxDeviation,
        "lsq" | "least-squares" => Objective::LeastSquares,
        other => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!("--objective: unknown choice {other:?} (max or least-squares)"),
            ));
        }
    };
    if !args.extrema.is_empty() {
        options.extrema = args
            .extrema
            .iter()
            .map(|t| t.parse::<Extremum>())
            .collect::<Result<_>>()?;
    } else if let Some(k) = args.curvature_extrema {
        options.extrema = (0..k)
            .map(|i| {
                if i % 2 == 0 {
                    Extremum::maximum()
                } else {
                    Extremum::minimum()
                }
            })
            .collect();
    }
    let result = erase(&points, &options)?;
    io::print_json(&report(&result))
}

fn report(result: &SmoothedCurve) -> Value {
    json!({
        "curve": CurveRecord::from_bspline(&result.curve),
        "max_deviation": result.deviation.to_curve.max,
        "max_deviation_index": result.deviation.to_curve.max_index,
        "max_deviation_to_data": result.deviation.to_data,
        "rms": result.deviation.to_curve.rms,
        "curvature_extrema": result.extrema.iter().map(|e| e.param).collect::<Vec<_>>(),
        "extrema": result.extrema.iter().map(|e| json!({
            "u": e.param,
            "point": [e.point.x, e.point.y],
            "kind": e.kind.to_string(),
        })).collect::<Vec<_>>(),
        "inflections": result.inflections,
        "control_points": result.curve.control_points().len(),
        "refinements": result.refinements,
        "rounds": result.rounds,
        "start_extrema": result.start_extrema,
        "conditions": result.conditions,
        "newton_steps": result.newton_steps,
    })
}
