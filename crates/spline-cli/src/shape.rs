//! Shape subcommands: smooth (the selective eraser of curvature extrema), one airfoil or a
//! whole directory of them.

use crate::io;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use nalgebra::Vector2;
use rayon::prelude::*;
use serde_json::{Value, json};
use spline_core::{Error, ErrorKind, Result};
use spline_io::airfoil::parse_airfoil;
use spline_io::exchange::CurveRecord;
use spline_shape::{
    AdaptiveOptions, Extremum, Objective, SmoothedCurve, SmoothingOptions,
    optimise_perimeter_over_area, smooth as erase, smooth_fewest_extrema, smooth_to_tolerance,
};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Args)]
pub struct SmoothArgs {
    /// Planar points: airfoil coordinate files (Selig or Lednicer .dat), JSON arrays of
    /// [x, y], or directories of .dat files; `-` reads standard input.
    #[arg(required = true, value_name = "FILE|DIR")]
    inputs: Vec<String>,
    /// Number of control points of the curve.
    #[arg(long)]
    control_points: Option<usize>,
    /// Instead of a number of control points: the fewest that bring every data point within
    /// this distance of the curve. With --curvature-extrema auto: the tolerance of the
    /// extrema (with --control-points).
    #[arg(long, value_name = "D")]
    max_deviation: Option<f64>,
    /// Degree of the curve (at least 3).
    #[arg(long, default_value_t = 3)]
    degree: usize,
    /// Number of curvature extrema the curve may have (alternating maximum, minimum, …,
    /// placed automatically), or `auto`: the fewest (1, 2, …; closed 2, 4, …, up to 8) that
    /// bring every data point within --max-deviation (default 0.2 % of the diagonal of the
    /// data's bounding box, 2 mm on a 1 m chord); --extremum gives them one by one instead.
    #[arg(long, value_name = "K|auto")]
    curvature_extrema: Option<String>,
    /// An allowed extremum: max, min, max@U or min@U (U in (0, 1)); repeat, in the order of
    /// the data. Default: one maximum (the nose of an airfoil).
    #[arg(long = "extremum", value_name = "KIND[@U]")]
    extrema: Vec<String>,
    /// What is minimised: the largest deviation (max) or the sum of squared distances
    /// (least-squares).
    #[arg(long, default_value = "max", value_name = "max|least-squares")]
    objective: String,
    /// Try every knot density and keep the closest curve (slower).
    #[arg(long)]
    thorough: bool,
    /// The data are a closed contour: the result is a closed (periodic) curve, written as
    /// an unclamped curve whose last p control points repeat the first p (as `interpolate
    /// --closed`); the extrema alternate round it, as many maxima as minima (--curvature-extrema
    /// K with K even).
    #[arg(long)]
    closed: bool,
    /// Exponents β of the knot density |C′| (κ L + c)^β tried in turn, as JSON (default
    /// [0.3, 0.5, 0.7]; 0 gives knots uniform in arc length).
    #[arg(long, value_name = "JSON")]
    knot_exponents: Option<String>,
    /// Directory for one NAME.json per input and summary.jsonl (needed for several inputs).
    #[arg(long, value_name = "DIR")]
    out: Option<String>,
    /// Parallel jobs for several inputs (default: every core).
    #[arg(long, value_name = "J")]
    jobs: Option<usize>,
}

/// Whether the extrema are `auto`.
fn auto_extrema(args: &SmoothArgs) -> bool {
    args.curvature_extrema.as_deref().map(str::trim) == Some("auto")
}

fn options(args: &SmoothArgs) -> Result<SmoothingOptions> {
    let auto = auto_extrema(args);
    let control = match (args.control_points, args.max_deviation) {
        (Some(n), None) => n,
        (Some(n), Some(_)) if auto => n,
        (None, Some(_)) if auto => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "--curvature-extrema auto needs --control-points N",
            ));
        }
        (None, Some(_)) => 0,
        (None, None) => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "give --control-points N or --max-deviation D",
            ));
        }
        (Some(_), Some(_)) => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "give --control-points N or --max-deviation D, not both (both only with --curvature-extrema auto)",
            ));
        }
    };
    let mut options = SmoothingOptions::new(control);
    options.degree = args.degree;
    options.thorough = args.thorough;
    options.closed = args.closed;
    if let Some(text) = &args.knot_exponents {
        options.knot_exponents = io::parse_arg("--knot-exponents", text)?;
    }
    options.objective = args
        .objective
        .parse::<Objective>()
        .map_err(|e| e.context("--objective"))?;
    let given = args
        .extrema
        .iter()
        .map(|t| t.parse::<Extremum>().map_err(|e| e.context("--extremum")))
        .collect::<Result<_>>()?;
    let count = match args.curvature_extrema.as_deref() {
        Some(_) if auto => None,
        Some(text) => Some(io::parse_arg::<usize>("--curvature-extrema", text)?),
        None => None,
    };
    if auto && !args.extrema.is_empty() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "--curvature-extrema auto chooses the extrema: give no --extremum",
        ));
    }
    options
        .request_extrema(count, given)
        .map_err(|e| e.context("--curvature-extrema"))?;
    Ok(options)
}

/// Reads planar points: a JSON array of pairs, or an airfoil file.
fn read_planar(path: &str) -> Result<Vec<Vector2<f64>>> {
    let text = io::read_text(path)?;
    if text.trim_start().starts_with('[') {
        let rows = spline_io::points::parse_points(&text).map_err(|e| e.context(path))?;
        rows.iter()
            .enumerate()
            .map(|(i, r)| match r.as_slice() {
                [x, y] => Ok(Vector2::new(*x, *y)),
                _ => Err(Error::new(
                    ErrorKind::DimensionMismatch,
                    format!(
                        "{path}: point {i} has {} coordinates; smoothing needs planar points",
                        r.len()
                    ),
                )),
            })
            .collect()
    } else {
        Ok(parse_airfoil(&text).map_err(|e| e.context(path))?.points)
    }
}

fn run_one(
    path: &str,
    options: &SmoothingOptions,
    tolerance: Option<f64>,
    auto: bool,
) -> Result<SmoothedCurve> {
    let points = read_planar(path)?;
    match tolerance {
        _ if auto => smooth_fewest_extrema(&points, tolerance, options),
        Some(d) => smooth_to_tolerance(&points, d, options),
        None => erase(&points, options),
    }
}

fn report(result: &SmoothedCurve) -> Value {
    // A closed curve is written as its wrapped container (the same points on [0, 1]).
    let curve = result
        .periodic
        .as_ref()
        .map_or(&result.curve, |periodic| periodic.wrapped());
    let mut value = json!({
        "curve": CurveRecord::from_bspline(curve),
        "closed": result.periodic.is_some(),
        "first_point": result.first_point,
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
        "control_points": result
            .periodic
            .as_ref()
            .map_or(result.curve.control_points().len(), spline_geom::PeriodicBSpline::len),
        "degree": result.curve.degree(),
        "refinements": result.refinements,
        "conditions": result.conditions,
        "least_squares_curvature_extrema": result.start_extrema,
        "newton_steps": result.newton_steps,
        "levels": result.levels,
    });
    // Only when there is something to say (the reports of curves that follow the data stay
    // as they were).
    if !result.warnings.is_empty() {
        value["warnings"] = json!(result.warnings);
    }
    value
}

/// The `.dat` files of a directory, sorted.
fn dat_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let entries = std::fs::read_dir(dir)
        .map_err(|e| Error::io(format_args!("read the directory {}", dir.display()), e))?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dat")))
        .collect();
    files.sort();
    Ok(files)
}

pub fn smooth(args: &SmoothArgs) -> Result<()> {
    let options = options(args)?;
    let mut inputs: Vec<String> = Vec::new();
    let mut directory = false;
    for input in &args.inputs {
        let path = Path::new(input);
        if input != "-" && path.is_dir() {
            directory = true;
            inputs.extend(dat_files(path)?.iter().map(|p| p.display().to_string()));
        } else {
            inputs.push(input.clone());
        }
    }
    if inputs.len() == 1 && !directory && args.out.is_none() {
        io::check_stdout_open()?;
        let result = run_one(&inputs[0], &options, args.max_deviation, auto_extrema(args))?;
        for warning in &result.warnings {
            eprintln!("spline: warning: {warning}");
        }
        return io::print_json(&report(&result));
    }
    let Some(out) = &args.out else {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{} inputs: give --out DIR for one NAME.json each and summary.jsonl",
                inputs.len()
            ),
        ));
    };
    batch(&inputs, Path::new(out), &options, args)
}

/// The output name of each input: its file stem, made unique by `-2`, `-3`, … for inputs
/// whose stems repeat (`d/a.dat` and `e/a.dat` give `a` and `a-2`), so that no output
/// overwrites another.
fn unique_names(inputs: &[String]) -> Vec<String> {
    let mut taken = std::collections::HashSet::new();
    inputs
        .iter()
        .map(|input| {
            let stem = Path::new(input)
                .file_stem()
                .map_or_else(|| input.clone(), |s| s.to_string_lossy().into_owned());
            let mut name = stem.clone();
            let mut k = 2;
            while !taken.insert(name.to_ascii_lowercase()) {
                name = format!("{stem}-{k}");
                k += 1;
            }
            name
        })
        .collect()
}

/// Smooths every input in parallel, writing `DIR/NAME.json` and `DIR/summary.jsonl`; goes on
/// after failures and reports them at the end.
fn batch(
    inputs: &[String],
    out: &Path,
    options: &SmoothingOptions,
    args: &SmoothArgs,
) -> Result<()> {
    std::fs::create_dir_all(out)
        .map_err(|e| Error::io(format_args!("create {}", out.display()), e))?;
    let summary_path = out.join("summary.jsonl");
    let summary_name = summary_path.display().to_string();
    let summary_file = io::create_file(&summary_name)?;
    let jobs = args.jobs.unwrap_or(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| Error::new(ErrorKind::InvalidArgument, format!("--jobs: {e}")))?;
    let bar = if std::io::stderr().is_terminal() {
        let bar = ProgressBar::new(inputs.len() as u64);
        if let Ok(style) = ProgressStyle::with_template(
            "{bar:40} {pos}/{len} airfoils, {elapsed} ({eta} left) {msg}",
        ) {
            bar.set_style(style);
        }
        bar
    } else {
        ProgressBar::hidden()
    };
    let started = Instant::now();
    let names = unique_names(inputs);
    let lines: Vec<(String, bool)> = pool.install(|| {
        inputs
            .par_iter()
            .zip(names.par_iter())
            .map(|(input, name)| {
                let t0 = Instant::now();
                let auto = auto_extrema(args);
                let outcome =
                    run_one(input, options, args.max_deviation, auto).and_then(|result| {
                        let mut value = report(&result);
                        value["name"] = json!(name);
                        let path = out.join(format!("{name}.json"));
                        let shown = path.display().to_string();
                        io::write_file(io::create_file(&shown)?, &shown, &io::encode(&value)?)?;
                        Ok(result)
                    });
                let seconds = t0.elapsed().as_secs_f64();
                bar.inc(1);
                let mut line = match &outcome {
                    Ok(r) => json!({
                        "name": name,
                        "input": input,
                        "control_points": r.curve.control_points().len(),
                        "max_deviation": r.deviation.to_curve.max,
                        "max_deviation_to_data": r.deviation.to_data,
                        "extrema": r.extrema.len(),
                        "seconds": seconds,
                        "error": null,
                    }),
                    Err(e) => json!({
                        "name": name,
                        "input": input,
                        "control_points": null,
                        "max_deviation": null,
                        "max_deviation_to_data": null,
                        "extrema": null,
                        "seconds": seconds,
                        "error": e.to_string(),
                    }),
                };
                if let Ok(r) = &outcome
                    && !r.warnings.is_empty()
                {
                    line["warnings"] = json!(r.warnings);
                }
                (line.to_string(), outcome.is_ok())
            })
            .collect()
    });
    bar.finish_and_clear();
    let mut text = String::new();
    for (line, _) in &lines {
        text.push_str(line);
        text.push('\n');
    }
    io::write_file(summary_file, &summary_name, text.as_bytes())?;
    let failed = lines.iter().filter(|(_, ok)| !ok).count();
    let message = format!(
        "smoothed {} of {} inputs in {:.1} s; summary in {summary_name}",
        lines.len() - failed,
        lines.len(),
        started.elapsed().as_secs_f64()
    );
    if failed > 0 {
        Err(Error::new(
            ErrorKind::NoConvergence,
            format!("{message}; {failed} failed (their \"error\" field says why)"),
        ))
    } else {
        eprintln!("spline: {message}");
        Ok(())
    }
}

#[derive(Args)]
pub struct OptimizeArgs {
    /// The initial shape: planar points from (0, 0) to (1, 0) (JSON or text); default: half
    /// an ellipse of height 0.3.
    #[arg(value_name = "POINTS")]
    initial: Option<String>,
    /// Degree of the curve.
    #[arg(long, default_value_t = 3)]
    degree: usize,
    /// Control points of the curve (n + 1).
    #[arg(long, default_value_t = 11)]
    control_points: usize,
    /// Sample points of the adaptive re-fit (N + 1).
    #[arg(long, default_value_t = 11)]
    samples: usize,
    /// Iterations of optimisation and re-fit.
    #[arg(long, default_value_t = 8)]
    iterations: usize,
    /// Nelder–Mead iterations per step, at most.
    #[arg(long, default_value_t = 20_000)]
    simplex_iterations: u64,
}

/// The largest number of iterations `optimize` accepts.
const MAX_OPTIMIZE_ITERATIONS: usize = 1000;

/// Seed 000 §3: minimise J = P²/A by Nelder–Mead on the free ordinates, re-fitting the
/// parametrisation between steps.
pub fn optimize(args: &OptimizeArgs) -> Result<()> {
    if args.iterations == 0 || args.iterations > MAX_OPTIMIZE_ITERATIONS {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "--iterations must be 1 to {MAX_OPTIMIZE_ITERATIONS}, got {}",
                args.iterations
            ),
        )
        .with_value(args.iterations as f64)
        .with_interval(1.0, MAX_OPTIMIZE_ITERATIONS as f64));
    }
    if args.samples > 100_000 || args.control_points > 1000 || args.simplex_iterations > 10_000_000
    {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "at most 100000 samples, 1000 control points and 10000000 simplex iterations",
        ));
    }
    let initial = match &args.initial {
        Some(path) => read_planar(path)?,
        None => (0..41)
            .map(|i| {
                let t = std::f64::consts::PI * f64::from(i) / 40.0;
                if i == 40 {
                    Vector2::new(1.0, 0.0)
                } else {
                    Vector2::new(0.5 - 0.5 * t.cos(), 0.3 * t.sin())
                }
            })
            .collect(),
    };
    let options = AdaptiveOptions {
        degree: args.degree,
        control_points: args.control_points,
        samples: args.samples,
        iterations: args.iterations,
        max_simplex_iterations: args.simplex_iterations,
        ..AdaptiveOptions::default()
    };
    io::check_stdout_open()?;
    let history = optimise_perimeter_over_area(&initial, &options)?;
    let last = history.last().ok_or_else(|| {
        Error::new(
            ErrorKind::NoConvergence,
            "the optimisation made no iteration",
        )
    })?;
    io::print_json(&json!({
        "curve": CurveRecord::from_bspline(&last.curve),
        "criterion": last.criterion,
        "iterations": history.iter().map(|h| json!({
            "criterion": h.criterion,
            "perimeter": h.perimeter,
            "area": h.area,
            "simplex_iterations": h.simplex_iterations,
        })).collect::<Vec<_>>(),
    }))
}
