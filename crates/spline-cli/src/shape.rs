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
    AdaptiveOptions, ExtremaCount, OptionSpelling, SmoothRequest, SmoothSummary, SmoothWords,
    SmoothedCurve, default_initial_shape, optimise_perimeter_over_area,
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
    /// After the knot densities, move the interior knots one at a time while that brings
    /// the curve closer to the data (open data; tens to hundreds of times slower).
    #[arg(long)]
    knot_search: bool,
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

/// The request of the flags: the numbers and JSON parsed here, the rest checked by the
/// library.
fn request(args: &SmoothArgs) -> Result<SmoothRequest> {
    let words = SmoothWords {
        control_points: args.control_points,
        max_deviation: args.max_deviation,
        degree: args.degree,
        curvature_extrema: args
            .curvature_extrema
            .as_deref()
            .map(|text| match text.trim() {
                "auto" => Ok(ExtremaCount::Auto),
                _ => io::parse_arg("--curvature-extrema", text).map(ExtremaCount::Count),
            }),
        extrema: &args.extrema,
        objective: &args.objective,
        thorough: args.thorough,
        knot_search: args.knot_search,
        closed: args.closed,
        knot_exponents: args
            .knot_exponents
            .as_deref()
            .map(|text| io::parse_arg("--knot-exponents", text)),
    };
    SmoothRequest::from_words(words, OptionSpelling::Flags)
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

fn run_one(path: &str, request: &SmoothRequest) -> Result<SmoothedCurve> {
    request.run(&read_planar(path)?)
}

fn report(result: &SmoothedCurve) -> Value {
    let mut value = json!({
        "curve": CurveRecord::from_bspline(result.output_curve()),
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
        "control_points": result.control_point_count(),
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

/// The line of `summary.jsonl` of one input: the library's record, the input's name and the
/// seconds it took.
fn summary_line(name: &str, input: &str, summary: &SmoothSummary, seconds: f64) -> Value {
    let mut line = json!({
        "name": name,
        "input": input,
        "control_points": summary.control_points,
        "max_deviation": summary.max_deviation,
        "max_deviation_to_data": summary.max_deviation_to_data,
        "extrema": summary.extrema,
        "seconds": seconds,
        "error": summary.error,
    });
    if !summary.warnings.is_empty() {
        line["warnings"] = json!(summary.warnings);
    }
    line
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
    let request = request(args)?;
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
        let result = run_one(&inputs[0], &request)?;
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
    batch(&inputs, Path::new(out), &request, args.jobs)
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
    request: &SmoothRequest,
    jobs: Option<usize>,
) -> Result<()> {
    std::fs::create_dir_all(out)
        .map_err(|e| Error::io(format_args!("create {}", out.display()), e))?;
    let summary_path = out.join("summary.jsonl");
    let summary_name = summary_path.display().to_string();
    let summary_file = io::create_file(&summary_name)?;
    let jobs = jobs.unwrap_or(0);
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
                let outcome = run_one(input, request).and_then(|result| {
                    let mut value = report(&result);
                    value["name"] = json!(name);
                    let path = out.join(format!("{name}.json"));
                    let shown = path.display().to_string();
                    io::write_file(io::create_file(&shown)?, &shown, &io::encode(&value)?)?;
                    Ok(result)
                });
                let seconds = t0.elapsed().as_secs_f64();
                bar.inc(1);
                let line = summary_line(name, input, &SmoothSummary::new(&outcome), seconds);
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
    /// Iterations of optimisation and re-fit (1 to 1000).
    #[arg(long, default_value_t = 8)]
    iterations: usize,
    /// Nelder–Mead iterations per step, at most.
    #[arg(long, default_value_t = 20_000)]
    simplex_iterations: u64,
}

/// Seed 000 §3: minimise J = P²/A by Nelder–Mead on the free ordinates, re-fitting the
/// parametrisation between steps.
pub fn optimize(args: &OptimizeArgs) -> Result<()> {
    let initial = match &args.initial {
        Some(path) => read_planar(path)?,
        None => default_initial_shape(),
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
