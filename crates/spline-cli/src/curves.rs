//! Subcommands on B-spline curves: basis, eval, insert, refine, remove, elevate, split,
//! bezier, derivative, plot. NURBS curves and surfaces are handed to [`crate::surfaces`].

use crate::io::{self, Curve, Json, Object, Pt};
use clap::{Args, ValueEnum};
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::BSpline;
use spline_geom::export::SvgPlot;

/// A parametric direction of a surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Direction {
    /// The first parameter.
    U,
    /// The second parameter.
    V,
}

/// A structural operation, applied to curves here and to NURBS and surfaces in
/// [`crate::surfaces`].
#[derive(Clone, Debug)]
pub enum Operation {
    /// Insert `knot` `times` times.
    Insert { knot: f64, times: usize },
    /// Insert all `knots`.
    Refine { knots: Vec<f64> },
    /// Remove `knot` `times` times within the relative `tolerance`.
    Remove {
        knot: f64,
        times: usize,
        tolerance: f64,
    },
    /// Raise the degree by `times`.
    Elevate { times: usize },
    /// Split at `at`.
    Split { at: f64 },
    /// Bézier segments.
    Bezier,
    /// Derivative curve of order `order`.
    Derivative { order: usize },
}

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
}

#[derive(Args)]
pub struct ObjectArgs {
    /// Object file (JSON), or - for standard input.
    pub object: String,
}

#[derive(Args)]
pub struct InsertArgs {
    /// Object file (JSON), or - for standard input.
    object: String,
    /// The knot U to insert.
    #[arg(long, allow_hyphen_values = true)]
    knot: f64,
    /// How many times.
    #[arg(long, default_value_t = 1)]
    times: usize,
    /// Parametric direction (surfaces only; default u).
    #[arg(long, value_enum)]
    direction: Option<Direction>,
}

#[derive(Args)]
pub struct RefineArgs {
    /// Object file (JSON), or - for standard input.
    object: String,
    /// Knots to insert, as a JSON array.
    #[arg(long)]
    knots: String,
    /// Parametric direction (surfaces only; default u).
    #[arg(long, value_enum)]
    direction: Option<Direction>,
}

#[derive(Args)]
pub struct RemoveArgs {
    /// Object file (JSON), or - for standard input.
    object: String,
    /// The interior knot U to remove.
    #[arg(long, allow_hyphen_values = true)]
    knot: f64,
    /// How many times.
    #[arg(long, default_value_t = 1)]
    times: usize,
    /// Largest allowed change of the shape, relative to the size of the control polygon.
    #[arg(long, default_value_t = spline_geom::DEFAULT_REMOVAL_TOLERANCE)]
    tolerance: f64,
    /// Parametric direction (surfaces only; default u).
    #[arg(long, value_enum)]
    direction: Option<Direction>,
}

#[derive(Args)]
pub struct ElevateArgs {
    /// Object file (JSON), or - for standard input.
    object: String,
    /// By how many degrees.
    #[arg(long, default_value_t = 1)]
    times: usize,
    /// Parametric direction (surfaces only; default u).
    #[arg(long, value_enum)]
    direction: Option<Direction>,
}

#[derive(Args)]
pub struct SplitArgs {
    /// Object file (JSON), or - for standard input.
    object: String,
    /// The parameter U strictly inside the domain.
    #[arg(long, allow_hyphen_values = true)]
    at: f64,
    /// Parametric direction (surfaces only; default u).
    #[arg(long, value_enum)]
    direction: Option<Direction>,
}

#[derive(Args)]
pub struct DerivativeArgs {
    /// Object file (JSON), or - for standard input.
    object: String,
    /// Derivative order K (at most the degree).
    #[arg(long, default_value_t = 1)]
    order: usize,
}

#[derive(Args)]
pub struct PlotArgs {
    /// Object files (JSON): planar curves, NURBS curves.
    #[arg(required = true)]
    objects: Vec<String>,
    /// Output SVG file.
    #[arg(short, long)]
    output: String,
    /// Add a curvature comb.
    #[arg(long)]
    comb: bool,
    /// Mark inflections and curvature extrema.
    #[arg(long)]
    features: bool,
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
pub fn check_order(option: &str, order: usize) -> Result<()> {
    spline_core::check_derivative_order(order).map_err(|e| e.context(option))
}

/// `[param][k][coord]`: `derivatives_into(u, out)` writes the derivatives of orders
/// `0..=order` of a curve (polynomial or rational) at `u`; points are unpadded to `dim`.
/// The order and the size of the output are checked before anything is computed.
pub fn derivative_rows(
    params: &[f64],
    order: usize,
    dim: usize,
    mut derivatives_into: impl FnMut(f64, &mut [Pt]) -> Result<()>,
) -> Result<Vec<Vec<Vec<f64>>>> {
    check_order("--derivatives", order)?;
    io::check_output_size("eval", &[params.len(), order + 1, dim])?;
    let mut ders = vec![Pt::zeros(); order + 1];
    params
        .iter()
        .enumerate()
        .map(|(i, &u)| {
            derivatives_into(u, &mut ders)
                .map_err(|e| e.context(format_args!("--at entry {i}")))?;
            Ok(ders.iter().map(|p| io::unpad(p, dim)).collect::<Vec<_>>())
        })
        .collect()
}

/// `[param][k][coord]` for a curve.
pub fn eval_curve(curve: &Curve, params: &[f64], order: usize) -> Result<Vec<Vec<Vec<f64>>>> {
    derivative_rows(params, order, curve.dim, |u, out| {
        curve.curve.derivatives_into(u, out)
    })
}

pub fn eval(args: &EvalArgs) -> Result<()> {
    match io::read_object(&args.object)? {
        Object::Curve(curve) => {
            let params: Vec<f64> = io::parse_arg("--at", &args.at)?;
            io::print_json(&eval_curve(&curve, &params, args.derivatives)?)
        }
        Object::Nurbs(nurbs) => {
            let params: Vec<f64> = io::parse_arg("--at", &args.at)?;
            io::print_json(&crate::surfaces::eval_nurbs(
                &nurbs,
                &params,
                args.derivatives,
            )?)
        }
        Object::Surface(surface) => {
            let params: Vec<[f64; 2]> = io::parse_arg("--at", &args.at)?;
            io::print_json(&crate::surfaces::eval_surface(
                &surface,
                &params,
                args.derivatives,
            )?)
        }
    }
}

/// The structural operations of the tool on one kind of curve (polynomial here, rational
/// in [`crate::surfaces`]), so that [`apply_operation`] dispatches them once for both.
pub trait CurveOperations: Sized {
    /// Inserts the knot `u` `times` times.
    fn insert_knot(&self, u: f64, times: usize) -> Result<Self>;
    /// Inserts all the knots.
    fn refine(&self, knots: &[f64]) -> Result<Self>;
    /// Removes the knot `u` `times` times within a relative tolerance.
    fn remove_knot(&self, u: f64, times: usize, relative_tolerance: f64) -> Result<Self>;
    /// Raises the degree by `times`.
    fn elevate_degree(&self, times: usize) -> Result<Self>;
    /// Splits at `u` into two curves clamped there.
    fn split(&self, u: f64) -> Result<(Self, Self)>;
    /// Hands the Bézier segments, each a clamped curve on its span, to `f` one by one.
    fn for_each_bezier_piece(&self, f: &mut dyn FnMut(Self) -> Result<()>) -> Result<()>;
    /// The derivative curve of order `order`, where the kind of curve has one.
    fn derivative_curve(&self, order: usize) -> Result<Self>;
}

impl CurveOperations for BSpline<f64, Pt> {
    fn insert_knot(&self, u: f64, times: usize) -> Result<Self> {
        BSpline::insert_knot(self, u, times)
    }

    fn refine(&self, knots: &[f64]) -> Result<Self> {
        BSpline::refine(self, knots)
    }

    fn remove_knot(&self, u: f64, times: usize, relative_tolerance: f64) -> Result<Self> {
        BSpline::remove_knot(self, u, times, relative_tolerance)
    }

    fn elevate_degree(&self, times: usize) -> Result<Self> {
        BSpline::elevate_degree(self, times)
    }

    fn split(&self, u: f64) -> Result<(Self, Self)> {
        BSpline::split(self, u)
    }

    fn for_each_bezier_piece(&self, f: &mut dyn FnMut(Self) -> Result<()>) -> Result<()> {
        for b in self.bezier_segments() {
            f(b.to_bspline()?)?;
        }
        Ok(())
    }

    fn derivative_curve(&self, order: usize) -> Result<Self> {
        self.derivative(order)
    }
}

/// Applies a structural operation to a curve; `one` encodes a resulting curve as JSON.
pub fn apply_operation<C: CurveOperations>(
    c: &C,
    operation: &Operation,
    one: impl Fn(C) -> Result<Json>,
) -> Result<Json> {
    match operation {
        Operation::Insert { knot, times } => one(c.insert_knot(*knot, *times)?),
        Operation::Refine { knots } => one(c.refine(knots)?),
        Operation::Remove {
            knot,
            times,
            tolerance,
        } => one(c.remove_knot(*knot, *times, *tolerance)?),
        Operation::Elevate { times } => one(c.elevate_degree(*times)?),
        Operation::Split { at } => {
            let (left, right) = c.split(*at)?;
            io::raw(&[one(left)?, one(right)?])
        }
        Operation::Bezier => {
            let mut pieces = Vec::new();
            c.for_each_bezier_piece(&mut |piece| {
                pieces.push(one(piece)?);
                Ok(())
            })?;
            io::raw(&pieces)
        }
        Operation::Derivative { order } => one(c.derivative_curve(*order)?),
    }
}

/// Applies a structural operation to a curve.
pub fn apply_to_curve(curve: &Curve, operation: &Operation) -> Result<Json> {
    apply_operation(&curve.curve, operation, |b| {
        io::raw(&curve.with(b).to_record())
    })
}

/// Writes the Bézier segments of a curve as they are made: a large curve's segments are never
/// held whole, neither as curves nor as text.
pub fn stream_bezier<C: CurveOperations>(c: &C, one: impl Fn(C) -> Result<Json>) -> Result<()> {
    io::write_stdout_stream(|write| {
        write(b"[")?;
        let mut first = true;
        c.for_each_bezier_piece(&mut |piece| {
            if !first {
                write(b",")?;
            }
            first = false;
            write(one(piece)?.get().as_bytes())
        })?;
        write(b"]")
    })
}

fn apply(object: &str, operation: &Operation, direction: Option<Direction>) -> Result<()> {
    if matches!(operation, Operation::Bezier) {
        match io::read_object(object)? {
            Object::Curve(curve) => {
                return stream_bezier(&curve.curve, |b| io::raw(&curve.with(b).to_record()));
            }
            Object::Nurbs(nurbs) => return crate::surfaces::stream_nurbs_bezier(&nurbs),
            Object::Surface(surface) => {
                let value = crate::surfaces::apply_to_surface(&surface, operation, direction)?;
                return io::write_stdout(value.get().as_bytes());
            }
        }
    }
    let value = match io::read_object(object)? {
        Object::Curve(curve) => {
            if direction.is_some() {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    "--direction applies to surfaces only",
                ));
            }
            apply_to_curve(&curve, operation)?
        }
        Object::Nurbs(record) => {
            if direction.is_some() {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    "--direction applies to surfaces only",
                ));
            }
            crate::surfaces::apply_to_nurbs(&record, operation)?
        }
        Object::Surface(surface) => {
            crate::surfaces::apply_to_surface(&surface, operation, direction)?
        }
    };
    io::write_stdout(value.get().as_bytes())
}

pub fn insert(args: &InsertArgs) -> Result<()> {
    apply(
        &args.object,
        &Operation::Insert {
            knot: args.knot,
            times: args.times,
        },
        args.direction,
    )
}

pub fn refine(args: &RefineArgs) -> Result<()> {
    let knots: Vec<f64> = io::parse_arg("--knots", &args.knots)?;
    apply(&args.object, &Operation::Refine { knots }, args.direction)
}

pub fn remove(args: &RemoveArgs) -> Result<()> {
    let operation = Operation::Remove {
        knot: args.knot,
        times: args.times,
        tolerance: args.tolerance,
    };
    apply(&args.object, &operation, args.direction)
}

pub fn elevate(args: &ElevateArgs) -> Result<()> {
    apply(
        &args.object,
        &Operation::Elevate { times: args.times },
        args.direction,
    )
}

pub fn split(args: &SplitArgs) -> Result<()> {
    apply(
        &args.object,
        &Operation::Split { at: args.at },
        args.direction,
    )
}

pub fn bezier(args: &ObjectArgs) -> Result<()> {
    apply(&args.object, &Operation::Bezier, None)
}

pub fn derivative(args: &DerivativeArgs) -> Result<()> {
    apply(
        &args.object,
        &Operation::Derivative { order: args.order },
        None,
    )
}

/// A planar curve from a tool-level curve.
pub fn planar(curve: &Curve) -> Result<spline_geom::Curve2> {
    if curve.dim != 2 {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("expected a planar curve (2 coordinates), got {}", curve.dim),
        ));
    }
    Ok(curve
        .curve
        .map_control_points(|p| nalgebra::Vector2::new(p[0], p[1])))
}

pub fn plot(args: &PlotArgs) -> Result<()> {
    let file = io::create_file(&args.output)?;
    let mut svg = SvgPlot::new();
    for path in &args.objects {
        match io::read_object(path)? {
            Object::Curve(curve) => {
                let c = planar(&curve).map_err(|e| e.context(path))?;
                svg.add_curve(&c);
                if args.comb {
                    svg.add_curvature_comb(&c, 200);
                }
                if args.features {
                    let features =
                        crate::algebra::planar_features(&c).map_err(|e| e.context(path))?;
                    svg.add_markers(&c.eval_many(&features.inflections)?, "inflection");
                    svg.add_markers(&c.eval_many(&features.curvature_extrema)?, "extremum");
                }
            }
            Object::Nurbs(nurbs) => crate::surfaces::plot_nurbs(&mut svg, &nurbs, args.comb)
                .map_err(|e| e.context(path))?,
            Object::Surface(_) => {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!("{path}: plot draws curves; use `spline mesh` for surfaces"),
                ));
            }
        }
    }
    io::write_file(file, &args.output, svg.render().as_bytes())
}
