//! `spline`: the command-line tool of the `spline` library.
//!
//! Every subcommand reads objects in the JSON exchange format (`docs/exchange-format.md`)
//! from a file or `-` (standard input) and prints JSON on standard output. Invalid input
//! gives a one-line message on standard error and exit status 2, never a panic or NaN.

#![allow(unreachable_pub)]
// The doc comments of the commands and their arguments are the tool's `--help` texts, read in
// a terminal: JSON in them (`[0,0,1]`, `[param][k][coord]`) is data, not an intra-doc link.
#![allow(rustdoc::broken_intra_doc_links)]

mod algebra;
mod cad;
mod curves;
mod eval;
mod fitting;
mod functions;
mod io;
mod make;
mod mesh;
mod objects;
mod plot;
mod shape;
mod structural;
#[cfg(feature = "studio")]
mod studio;
mod surface_features;
mod surfaces;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// B-spline and NURBS curves and surfaces from the command line.
#[derive(Parser)]
#[command(name = "spline", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// All basis functions N_i^(k)(u) at the parameters: [param][k][i].
    Basis(eval::BasisArgs),
    /// Evaluate a curve ([param][k][coord]) or surface ([param][k][l][coord]) with derivatives.
    Eval(eval::EvalArgs),
    /// Insert a knot (times R) without changing the shape.
    Insert(structural::InsertArgs),
    /// Insert many knots at once (knot refinement).
    Refine(structural::RefineArgs),
    /// Remove a knot if the shape moves by at most the tolerance.
    Remove(structural::RemoveArgs),
    /// Raise the degree; every distinct knot's multiplicity rises by the same amount.
    Elevate(structural::ElevateArgs),
    /// Split at a parameter into [left, right], both clamped there.
    Split(structural::SplitArgs),
    /// The Bézier segments of a curve, each clamped on its span.
    Bezier(structural::ObjectArgs),
    /// The derivative curve of order K (degree p - K).
    Derivative(structural::DerivativeArgs),
    /// The antiderivative of order K of a curve or function (degree p + K, zero at the first knot; scipy's splantider).
    Antiderivative(functions::AntiderivativeArgs),
    /// The definite integral of every coordinate over [FROM, TO] (scipy's BSpline.integrate).
    Integrate(functions::IntegrateArgs),
    /// The zeros of a scalar function in its domain (scipy's sproot / PPoly.roots).
    Roots(functions::RootsArgs),
    /// Evaluate an N-dimensional tensor-product spline (scipy's NdBSpline): [point][coord].
    NdEval(functions::NdEvalArgs),
    /// Interpolate values on a grid by an N-dimensional spline (scipy's make_ndbspl).
    NdInterpolate(functions::NdInterpolateArgs),
    /// Draw curves with their control polygons as SVG.
    Plot(plot::PlotArgs),
    /// Product of two B-spline functions, optionally with Jacobians.
    Product(algebra::ProductArgs),
    /// Signed curvature of a planar curve at parameters.
    Curvature(plot::CurvatureArgs),
    /// Inflections and curvature extrema of a planar curve; curvature extrema and torsion
    /// zeros of a 3-D curve (B-spline or NURBS); constant curvature reported as such.
    Features(structural::ObjectArgs),
    /// Interpolate points with a B-spline curve.
    Interpolate(fitting::InterpolateArgs),
    /// The natural cubic spline function through (x, y) data.
    Natural(fitting::NaturalArgs),
    /// Least-squares approximation of points by a B-spline curve.
    Approximate(fitting::ApproximateArgs),
    /// Smooth points with a curve that has only the allowed curvature extrema.
    Smooth(shape::SmoothArgs),
    /// Shape optimisation with adaptive parametrisation (seed 000 §3): minimise perimeter²/area.
    Optimize(shape::OptimizeArgs),
    /// Build circles, arcs, conics, extrusions, ruled, conical, revolved surfaces, spheres, tori.
    Make(make::MakeArgs),
    /// Triangulate a surface into an OBJ or OFF mesh.
    Mesh(mesh::MeshArgs),
    /// Closest points on a curve or a surface: [{"u"[, "v"], "point", "distance"}].
    Closest(surfaces::ClosestArgs),
    /// Intersections: curve–curve (one curve: self-intersections), curve–surface, surface–surface.
    Intersect(surfaces::IntersectArgs),
    /// Least-squares surface through scattered points or a mesh, with parameter correction.
    ApproximateSurface(surfaces::ApproximateSurfaceArgs),
    /// Parabolic lines (K = 0) and umbilics of a surface (ridges of a function s(u, v)),
    /// as polylines in (u, v) and in space.
    SurfaceFeatures(surface_features::SurfaceFeaturesArgs),
    /// The offset of a planar curve within a tolerance, with its cusps.
    Offset(curves::OffsetArgs),
    /// Arc length: the length, parameters at lengths, or the curve by arc length.
    Arclength(curves::ArclengthArgs),
    /// Lower the degree of a curve within a tolerance.
    Reduce(curves::ReduceArgs),
    /// Smoothing spline of data: lambda given or by GCV (scipy), or a residual target (FITPACK).
    Smoothing(curves::SmoothingArgs),
    /// Write curves and surfaces to a CAD file: FILE.step/.stp (STEP AP214) or FILE.igs/.iges (IGES 5.3).
    Export(cad::ExportArgs),
    /// Read the B-spline curves and surfaces of a STEP or IGES file: [{"id", "name", "entity", "object"}].
    Import(cad::ImportArgs),
    /// Serve the interactive curve-design page (seed 003's labs) on 127.0.0.1; prints its URL.
    #[cfg(feature = "studio")]
    Studio(studio::StudioArgs),
}

fn run(command: Command) -> spline_core::Result<()> {
    match command {
        Command::Basis(args) => eval::basis(&args),
        Command::Eval(args) => eval::eval(&args),
        Command::Insert(args) => structural::insert(&args),
        Command::Refine(args) => structural::refine(&args),
        Command::Remove(args) => structural::remove(&args),
        Command::Elevate(args) => structural::elevate(&args),
        Command::Split(args) => structural::split(&args),
        Command::Bezier(args) => structural::bezier(&args),
        Command::Derivative(args) => structural::derivative(&args),
        Command::Antiderivative(args) => functions::antiderivative(&args),
        Command::Integrate(args) => functions::integrate(&args),
        Command::Roots(args) => functions::roots(&args),
        Command::NdEval(args) => functions::nd_eval(&args),
        Command::NdInterpolate(args) => functions::nd_interpolate(&args),
        Command::Plot(args) => plot::plot(&args),
        Command::Product(args) => algebra::product(&args),
        Command::Curvature(args) => plot::curvature(&args),
        Command::Features(args) => plot::features(&args),
        Command::Interpolate(args) => fitting::interpolate(&args),
        Command::Natural(args) => fitting::natural(&args),
        Command::Approximate(args) => fitting::approximate(&args),
        Command::Smooth(args) => shape::smooth(&args),
        Command::Optimize(args) => shape::optimize(&args),
        Command::Make(args) => make::make(&args),
        Command::Mesh(args) => mesh::mesh(&args),
        Command::Closest(args) => surfaces::closest(&args),
        Command::Intersect(args) => surfaces::intersect(&args),
        Command::ApproximateSurface(args) => surfaces::approximate_surface(&args),
        Command::SurfaceFeatures(args) => surface_features::surface_features(&args),
        Command::Offset(args) => curves::offset(&args),
        Command::Arclength(args) => curves::arclength(&args),
        Command::Reduce(args) => curves::reduce(&args),
        Command::Smoothing(args) => curves::smoothing(&args),
        Command::Export(args) => cad::export(&args),
        Command::Import(args) => cad::import(&args),
        #[cfg(feature = "studio")]
        Command::Studio(args) => studio::studio(&args),
    }
}

/// The exit status of a tool whose reader went away (128 + SIGPIPE), as the shell reports
/// for Unix tools stopped by a closed pipe.
const CLOSED_PIPE: u8 = 141;

fn main() -> ExitCode {
    let cli = match parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(&e),
    };
    if let Err(e) = io::check_stdout_open() {
        eprintln!("spline: {e}");
        return ExitCode::from(2);
    }
    match run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of a pipe has gone (`spline ... | head -c 1`): end quietly.
        Err(_) if io::output_closed() => ExitCode::from(CLOSED_PIPE),
        Err(e) => {
            eprintln!("spline: {e}");
            ExitCode::from(2)
        }
    }
}

/// The command line, with negative numbers taken as values wherever a value is expected
/// (an option of one value takes whatever follows it, `-1e-3` included): `--tolerance -1` reaches the subcommand, which says what is wrong with it (issue 25:
/// clap's "unexpected argument '-1'" told users to write `-- -1`).
fn parse() -> Result<Cli, clap::Error> {
    use clap::{CommandFactory, FromArgMatches};
    fn negative_numbers(command: clap::Command) -> clap::Command {
        command
            .mut_args(|arg| {
                let single = arg.get_num_args().is_none_or(|n| n.max_values() == 1);
                if !arg.get_action().takes_values() {
                    arg
                } else if single && !arg.is_positional() {
                    // `--tolerance -1e-3`: an option's one value is whatever follows it.
                    arg.allow_hyphen_values(true)
                } else {
                    arg.allow_negative_numbers(true)
                }
            })
            .mut_subcommands(negative_numbers)
    }
    let matches = negative_numbers(Cli::command()).try_get_matches()?;
    Cli::from_arg_matches(&matches)
}

/// Prints help and version as asked, and every usage error as one line with exit status 2.
fn usage_error(e: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            return match e.print() {
                Ok(()) => ExitCode::SUCCESS,
                Err(_) => ExitCode::from(CLOSED_PIPE),
            };
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            eprintln!("spline: {}", missing_subcommand());
            return ExitCode::from(2);
        }
        _ => {}
    }
    // One line: the message and its details (e.g. the missing arguments, a suggestion),
    // without usage.
    let text = e.render().to_string();
    let first = text
        .lines()
        .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" ");
    let first = first.trim_start_matches("error: ");
    eprintln!("spline: {first} (see spline --help)");
    ExitCode::from(2)
}

/// The one-line message for a command given without its subcommand (`spline`,
/// `spline make`): the choices, from the command-line definition.
fn missing_subcommand() -> String {
    use clap::CommandFactory;
    let mut command = Cli::command();
    let mut path = vec!["spline".to_string()];
    for arg in std::env::args().skip(1) {
        match command.find_subcommand(&arg) {
            Some(sub) => {
                path.push(arg.clone());
                command = sub.clone();
            }
            None => break,
        }
    }
    let choices: Vec<&str> = command
        .get_subcommands()
        .map(clap::Command::get_name)
        .filter(|name| *name != "help")
        .collect();
    let path = path.join(" ");
    format!(
        "{path} needs one of: {} (see {path} --help)",
        choices.join(", ")
    )
}
