//! Fitting subcommands: interpolate, natural, approximate (`docs/exchange-format.md`,
//! "Fitting conventions").

use crate::io::{Pt, pad, parse_arg, print_json, read_points, write_stdout};
use crate::objects::Sized;
use clap::Args;
use clap::builder::{PossibleValuesParser, TypedValueParser};
use serde_json::{Value, json};
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_fit::{
    CorrectionOptions, CurveFit, InterpolationOptions, InterpolationRequest, KnotChoice,
    LeastSquaresRequest, LsqKnots, LsqMethod, Parametrization, fit_interpolation,
    fit_least_squares, natural_spline,
};

#[derive(Args)]
pub struct InterpolateArgs {
    /// Points file (JSON array of arrays or whitespace/comma text), or - for standard input.
    points: String,
    /// Degree p.
    #[arg(long)]
    degree: usize,
    /// uniform, chordal, centripetal (normalised to [0, 1]), or a JSON array of parameters
    /// (one per point, strictly increasing; with --closed one more, for the return to the
    /// first point).
    #[arg(long, default_value = "chordal")]
    parametrization: String,
    /// averaging (seed 004 (7.6)), uniform, nurbs-book (The NURBS Book (9.68)), or a JSON
    /// array of knots (default: averaging). Not with --closed.
    #[arg(long)]
    knots: Option<String>,
    /// Interpolate by a closed (periodic) curve through the points and back to the first
    /// (do not repeat the first point at the end): an unclamped curve whose last p control
    /// points repeat the first p.
    #[arg(long)]
    closed: bool,
    /// First derivative at the first point, as a JSON array (adds a control point).
    #[arg(long, value_name = "JSON")]
    start_derivative: Option<String>,
    /// First derivative at the last point, as a JSON array (adds a control point).
    #[arg(long, value_name = "JSON")]
    end_derivative: Option<String>,
    /// Print {"curve", "params", "max_deviation", "max_index", "rms"} instead of the curve.
    #[arg(long)]
    report: bool,
}

#[derive(Args)]
pub struct NaturalArgs {
    /// Abscissae as a JSON array (strictly increasing).
    #[arg(long)]
    x: String,
    /// Ordinates as a JSON array of numbers (a function) or of arrays (a curve x ↦ y(x)).
    #[arg(long)]
    y: String,
    /// Even order m = 2q of the natural spline (degree 2q − 1): 4 is the natural cubic
    /// spline, 2 the broken line, 6 the natural quintic.
    #[arg(long, default_value_t = 4)]
    order: usize,
}

/// `--method`: the library's names ([`LsqMethod::NAMES`]).
fn method_parser() -> impl TypedValueParser<Value = LsqMethod> {
    PossibleValuesParser::new(LsqMethod::NAMES).try_map(|name| LsqMethod::from_name(&name))
}

#[derive(Args)]
pub struct ApproximateArgs {
    /// Points file (JSON array of arrays or whitespace/comma text), or - for standard input.
    points: String,
    /// Degree p.
    #[arg(long)]
    degree: usize,
    /// Number of control points (interior knots by The NURBS Book (9.68)).
    #[arg(long, conflicts_with = "knots", required_unless_present = "knots")]
    control_points: Option<usize>,
    /// Knot vector as a JSON array.
    #[arg(long)]
    knots: Option<String>,
    /// uniform, chordal, centripetal (normalised to [0, 1]), or a JSON array of parameters
    /// (one per point, non-decreasing).
    #[arg(long, default_value = "chordal")]
    parametrization: String,
    /// Weights of the points as a JSON array: residual k is multiplied by w_k, as in scipy's
    /// make_lsq_spline.
    #[arg(long)]
    weights: Option<String>,
    /// Run parameter correction (seed 003) for at most ITER sweeps.
    #[arg(long, value_name = "ITER")]
    correct_parameters: Option<usize>,
    /// Angle tolerance ε in radians of the parameter correction's stopping test
    /// |π/2 − α| < ε.
    #[arg(long, default_value_t = 1e-3, value_name = "EPS")]
    angle_tolerance: f64,
    /// Make the first and last control points the first and last points (clamped knots).
    #[arg(long)]
    pin_ends: bool,
    /// Fixed control-point coordinates as a JSON array of [index, coordinate, value]
    /// triples, e.g. '[[0,0,0],[1,0,0],[0,1,0]]' for x_0 = x_1 = y_0 = 0.
    #[arg(long, value_name = "JSON")]
    fix: Option<String>,
    /// Weight λ of the smoothing term λ ∫ ‖C''‖².
    #[arg(long, default_value_t = 0.0, value_name = "LAMBDA")]
    smoothing: f64,
    /// Solver for the least-squares system: normal (banded normal equations and Cholesky,
    /// fastest) or qr (Givens QR of the banded design matrix).
    #[arg(long, default_value = "normal", value_parser = method_parser())]
    method: LsqMethod,
    /// Print {"curve", "params", "max_deviation", "max_index", "rms"} (and "correction")
    /// instead of the curve.
    #[arg(long)]
    report: bool,
}

/// Reads points, padded to the tool's point type, with their dimension.
fn read_padded(path: &str) -> Result<(Vec<Pt>, usize)> {
    let rows = read_points(path)?;
    let dim = rows.first().map_or(0, Vec::len);
    let points = rows.iter().map(|r| pad(r)).collect::<Result<Vec<Pt>>>()?;
    Ok((points, dim))
}

fn parametrization(text: &str) -> Result<Parametrization<f64>> {
    if text.trim().starts_with('[') {
        return Ok(Parametrization::Given(parse_arg(
            "--parametrization",
            text,
        )?));
    }
    Parametrization::from_name(text).map_err(|e| e.context("--parametrization (or a JSON array)"))
}

fn knot_choice(text: &str, degree: usize) -> Result<KnotChoice<f64>> {
    if text.trim().starts_with('[') {
        return Ok(KnotChoice::Given(
            KnotVector::new(degree, parse_arg("--knots", text)?)
                .map_err(|e| e.context("--knots"))?,
        ));
    }
    KnotChoice::from_name(text).map_err(|e| e.context("--knots (or a JSON array)"))
}

fn vector(option: &str, text: &str, dim: usize) -> Result<Pt> {
    let v: Vec<f64> = parse_arg(option, text)?;
    if v.len() != dim {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!(
                "{option} has {} coordinates, the points have {dim}",
                v.len()
            ),
        ));
    }
    pad(&v)
}

/// Prints a fit: the curve, or with `report` the curve and its deviation (and `extra`).
fn output(fit: &CurveFit<f64, Pt>, dim: usize, report: bool, extra: Option<Value>) -> Result<()> {
    let record = Sized {
        value: fit.curve.clone(),
        dim,
    }
    .json()?;
    if !report {
        return write_stdout(record.get().as_bytes());
    }
    let mut value = json!({
        "curve": record,
        "params": fit.params,
        "max_deviation": fit.deviation.max,
        "max_index": fit.deviation.max_index,
        "rms": fit.deviation.rms,
    });
    if let Some(extra) = extra {
        value["correction"] = extra;
    }
    print_json(&value)
}

pub fn interpolate(args: &InterpolateArgs) -> Result<()> {
    let (points, dim) = read_padded(&args.points)?;
    let derivative = |option: &str, text: &Option<String>| {
        text.as_deref().map(|t| vector(option, t, dim)).transpose()
    };
    let request = InterpolationRequest {
        degree: args.degree,
        closed: args.closed,
        options: InterpolationOptions {
            parametrization: parametrization(&args.parametrization)?,
            knots: knot_choice(args.knots.as_deref().unwrap_or("averaging"), args.degree)?,
            start_derivative: derivative("--start-derivative", &args.start_derivative)?,
            end_derivative: derivative("--end-derivative", &args.end_derivative)?,
        },
    };
    output(
        &fit_interpolation(&points, &request)?,
        dim,
        args.report,
        None,
    )
}

/// The values of `--y`: a JSON array of numbers (1-D) or of points of one dimension, padded,
/// with their dimension.
///
/// # Errors
/// [`ErrorKind::Parse`] for bad JSON; [`ErrorKind::DimensionMismatch`] for points of
/// different dimensions; the errors of [`pad`].
pub fn read_values(text: &str) -> Result<(Vec<Pt>, usize)> {
    let rows: Vec<Vec<f64>> = match parse_arg::<Value>("--y", text)? {
        Value::Array(items) if items.iter().all(Value::is_number) => {
            parse_arg::<Vec<f64>>("--y", text)?
                .into_iter()
                .map(|v| vec![v])
                .collect()
        }
        _ => parse_arg("--y", text)?,
    };
    let dim = rows.first().map_or(1, Vec::len);
    if let Some(k) = rows.iter().position(|r| r.len() != dim) {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!(
                "--y: value {k} has {} coordinates, value 0 has {dim}",
                rows[k].len()
            ),
        ));
    }
    Ok((
        rows.iter().map(|r| pad(r)).collect::<Result<Vec<Pt>>>()?,
        dim,
    ))
}

pub fn natural(args: &NaturalArgs) -> Result<()> {
    let x: Vec<f64> = parse_arg("--x", &args.x)?;
    let (values, dim) = read_values(&args.y)?;
    let curve = natural_spline(&x, &values, args.order)?;
    write_stdout(Sized { value: curve, dim }.json()?.get().as_bytes())
}

fn fixes(text: &str, dim: usize) -> Result<Vec<(usize, usize, f64)>> {
    let triples: Vec<(f64, f64, f64)> = parse_arg("--fix", text)?;
    triples
        .into_iter()
        .enumerate()
        .map(|(k, (i, c, v))| {
            let index = |x: f64| {
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                (x >= 0.0 && x.fract() == 0.0 && x < 1e15).then_some(x as usize)
            };
            match (index(i), index(c)) {
                (Some(i), Some(c)) if c < dim => Ok((i, c, v)),
                _ => Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!(
                        "--fix: entry {k} must be [index, coordinate < {dim}, value] with non-negative integer index and coordinate"
                    ),
                )
                .with_index(k)),
            }
        })
        .collect()
}

pub fn approximate(args: &ApproximateArgs) -> Result<()> {
    let (points, dim) = read_padded(&args.points)?;
    let knots = match (&args.knots, args.control_points) {
        (Some(text), _) => LsqKnots::Given(
            KnotVector::new(args.degree, parse_arg("--knots", text)?)
                .map_err(|e| e.context("--knots"))?,
        ),
        (None, Some(n)) => LsqKnots::ControlPoints(n),
        (None, None) => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "give --control-points N or --knots JSON",
            ));
        }
    };
    let weights: Option<Vec<f64>> = args
        .weights
        .as_deref()
        .map(|t| parse_arg("--weights", t))
        .transpose()?;
    let request = LeastSquaresRequest {
        parametrization: parametrization(&args.parametrization)?,
        weights: weights.as_deref(),
        pin_ends: args.pin_ends,
        fixed: args
            .fix
            .as_deref()
            .map_or(Ok(Vec::new()), |t| fixes(t, dim))?,
        smoothing: args.smoothing,
        method: args.method,
        correction: args.correct_parameters.map(|iterations| CorrectionOptions {
            max_iterations: iterations,
            angle_tolerance: args.angle_tolerance,
            ..CorrectionOptions::default()
        }),
        ..LeastSquaresRequest::new(args.degree, knots)
    };
    let answer = fit_least_squares(&points, &request)?;
    let extra = answer.correction.map(|report| {
        json!({
            "iterations": report.iterations,
            "converged": report.converged,
            "angles": report.angles,
            "errors": report.errors,
        })
    });
    output(&answer.fit, dim, args.report, extra)
}
