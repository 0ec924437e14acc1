//! The structural subcommands — insert, refine, remove, elevate, split, bezier,
//! derivative — for every kind of object: parse the arguments into an
//! [`Operation`], let the library apply it ([`StructuralCurve`], [`StructuralSurface`]),
//! print the [`Outcome`].

use crate::io::{self, Json};
use crate::objects::{Object, Sized, ToRecord, read_object};
use clap::{Args, ValueEnum};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::{Operation, Outcome, StructuralCurve, StructuralSurface};

/// A parametric direction of a surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Direction {
    /// The first parameter.
    U,
    /// The second parameter.
    V,
}

impl From<Direction> for spline_geom::Direction {
    fn from(d: Direction) -> Self {
        match d {
            Direction::U => Self::U,
            Direction::V => Self::V,
        }
    }
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

/// The printed outcome of an operation: objects as records, pairs and lists as arrays,
/// the partial derivatives of a surface as `{"du", "dv"}`, grids of patches as nested
/// arrays. Bézier segments of curves are written as they are encoded, never held whole
/// as text.
fn print<X: ToRecord>(object: &Sized<X>, outcome: Outcome<X>, derivative: bool) -> Result<()> {
    let one = |x: X| object.with(x).json();
    match outcome {
        Outcome::One(x) => io::write_stdout(one(x)?.get().as_bytes()),
        Outcome::Pair(a, b) if derivative => io::print_json(&serde_json::json!({
            "du": one(a)?,
            "dv": one(b)?,
        })),
        Outcome::Pair(a, b) => io::print_json(&[one(a)?, one(b)?]),
        Outcome::List(pieces) => io::write_stdout_stream(|write| {
            write(b"[")?;
            for (i, piece) in pieces.into_iter().enumerate() {
                if i > 0 {
                    write(b",")?;
                }
                write(one(piece)?.get().as_bytes())?;
            }
            write(b"]")
        }),
        Outcome::Grid(rows) => {
            let rows = rows
                .into_iter()
                .map(|row| row.into_iter().map(one).collect::<Result<Vec<Json>>>())
                .collect::<Result<Vec<_>>>()?;
            io::print_json(&rows)
        }
    }
}

fn curves_only(direction: Option<Direction>) -> Result<()> {
    match direction {
        Some(_) => Err(Error::new(
            ErrorKind::InvalidArgument,
            "--direction applies to surfaces only",
        )),
        None => Ok(()),
    }
}

/// Applies an operation to the object in `path` and prints the outcome.
fn apply(path: &str, operation: &Operation<f64>, direction: Option<Direction>) -> Result<()> {
    let derivative = matches!(operation, Operation::Derivative { .. });
    let surface_direction = direction.map(spline_geom::Direction::from);
    match read_object(path)? {
        Object::Curve(c) => {
            curves_only(direction)?;
            print(&c, c.value.apply(operation)?, false)
        }
        Object::Nurbs(c) => {
            curves_only(direction)?;
            print(&c, c.value.apply(operation)?, false)
        }
        Object::Surface(s) => print(&s, s.value.apply(operation, surface_direction)?, derivative),
        Object::NurbsSurface(s) => {
            print(&s, s.value.apply(operation, surface_direction)?, derivative)
        }
    }
}

pub fn insert(args: &InsertArgs) -> Result<()> {
    let operation = Operation::Insert {
        knot: args.knot,
        times: args.times,
    };
    apply(&args.object, &operation, args.direction)
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
    let operation = Operation::Elevate { times: args.times };
    apply(&args.object, &operation, args.direction)
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
    let operation = Operation::Derivative { order: args.order };
    apply(&args.object, &operation, None)
}
