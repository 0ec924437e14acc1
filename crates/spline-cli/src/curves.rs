//! The curve subcommands of the second wave: curve–curve `intersect` (two curves, or one
//! with itself; reached through the surfaces module's `intersect`), `offset`, `arclength`, `reduce` and `smoothing` (scipy's `make_smoothing_spline` and
//! FITPACK's residual target).

use crate::fitting::read_values;
use crate::io::{Pt, parse_arg, print_json};
use crate::objects::Object;
use crate::objects::{Sized, read_curve, read_object};
use crate::plot::{Planar, planar_of};
use clap::Args;
use nalgebra::{SVector, Vector3};
use serde_json::{Value, json};
use spline_algebra::{
    CurveEvent, CurveIntersections, DEFAULT_RELATIVE_CONTACT, intersect_curves,
    intersect_curves_relative, self_intersections, self_intersections_relative,
};
use spline_core::{Error, ErrorKind, Result};
use spline_fit::{
    SmoothingParameter, reduce_degree, reparametrize_by_arc_length, smoothing_spline,
    smoothing_to_residual,
};
use spline_geom::{ArcLengthTable, BSpline, PlanarCurve};
use spline_shape::{
    CurveOffset, ExactOffset, OffsetOptions, OffsetShape, SurfaceOffset, SurfaceOffsetShape,
    offset_planar_curve, offset_space_curve, offset_surface,
};

#[derive(Args)]
pub struct OffsetArgs {
    /// A curve (JSON: B-spline or NURBS, planar or 3-D with --direction) or a surface in
    /// 3-D (B-spline or NURBS), or - for standard input.
    curve: String,
    /// Signed distance: positive to the left of the direction of travel (planar curves),
    /// along T × V (3-D curves), or along the unit normal S_u × S_v (surfaces).
    #[arg(long, allow_hyphen_values = true)]
    distance: f64,
    /// The reference direction V of a 3-D curve's offset, as x,y,z or a JSON array: the
    /// point moves by the distance along T × V / |T × V| (Open CASCADE's offset curves).
    #[arg(long, allow_hyphen_values = true)]
    direction: Option<String>,
    /// Largest distance between the result and the exact offset (absolute, in the units of
    /// the points).
    #[arg(long, default_value_t = 1e-6)]
    tolerance: f64,
    /// Degree of the result.
    #[arg(long, default_value_t = 3)]
    degree: usize,
}

#[derive(Args)]
pub struct ArclengthArgs {
    /// A curve (JSON; B-spline or NURBS, any dimension), or - for standard input.
    curve: String,
    /// Arc lengths (JSON array) at which to give the parameters.
    #[arg(long)]
    at_length: Option<String>,
    /// Give the curve parametrised by arc length instead (within --tolerance).
    #[arg(long)]
    reparametrize: bool,
    /// Relative accuracy of lengths (a fraction of the length: the same digits at every
    /// scale); with --reparametrize, the absolute tolerance of the reparametrised curve (in
    /// the units of the points).
    #[arg(long, default_value_t = 1e-9)]
    tolerance: f64,
}

#[derive(Args)]
pub struct ReduceArgs {
    /// A curve (JSON; B-spline or NURBS, any dimension), or - for standard input.
    curve: String,
    /// How much to lower the degree.
    #[arg(long, default_value_t = 1)]
    times: usize,
    /// Largest distance between the result and the curve (absolute, in the units of the
    /// points).
    #[arg(long)]
    tolerance: f64,
    /// Add knots where the curve's own knots do not reach the tolerance.
    #[arg(long)]
    refine: bool,
}

#[derive(Args)]
pub struct SmoothingArgs {
    /// Abscissae (JSON array, increasing).
    #[arg(long)]
    x: String,
    /// Values (JSON array of numbers, or of points).
    #[arg(long)]
    y: String,
    /// Weights of the data (JSON array, positive).
    #[arg(long)]
    weights: Option<String>,
    /// A given weight of the roughness penalty.
    #[arg(long, group = "how")]
    lambda: Option<f64>,
    /// Choose λ by generalised cross-validation (scipy's make_smoothing_spline).
    #[arg(long, group = "how")]
    gcv: bool,
    /// FITPACK's residual target s (splrep): knots placed automatically.
    #[arg(long, group = "how")]
    residual: Option<f64>,
    /// Degree for --residual (1 to 5).
    #[arg(long, default_value_t = 3)]
    degree: usize,
}

/// The points and the overlaps (`"overlap": true`, intervals on both curves), in one array
/// in the library's order ([`CurveIntersections::events`]).
fn hits_json(hits: &CurveIntersections<f64>) -> Value {
    let events = hits.events().into_iter().map(|event| match event {
        CurveEvent::Point(h) => json!({"u": h.u, "v": h.v, "point": [h.point.x, h.point.y],
                                       "tangential": h.tangential, "gap": h.gap}),
        CurveEvent::Overlap(o) => {
            let (p, q) = o.points;
            json!({"overlap": true, "u": [o.u.0, o.u.1], "v": [o.v.0, o.v.1],
                   "reversed": o.reversed, "points": [[p.x, p.y], [q.x, q.y]]})
        }
    });
    Value::Array(events.collect())
}

/// A contact tolerance as given (`--tolerance`, absolute) or by default (relative to size).
#[derive(Clone, Copy)]
enum Contact {
    Absolute(f64),
    Relative(f64),
}

fn pair<A: PlanarCurve<f64>>(
    a: &A,
    b: &Planar,
    contact: Contact,
) -> Result<CurveIntersections<f64>> {
    match (b, contact) {
        (Planar::Polynomial(b), Contact::Absolute(t)) => intersect_curves(a, b, t),
        (Planar::Rational(b), Contact::Absolute(t)) => intersect_curves(a, b, t),
        (Planar::Polynomial(b), Contact::Relative(t)) => intersect_curves_relative(a, b, t),
        (Planar::Rational(b), Contact::Relative(t)) => intersect_curves_relative(a, b, t),
    }
}

/// Curve–curve intersections for `spline intersect A [B]` (the command lives with the
/// surface intersections, which dispatch here when neither object is a surface): all
/// intersections of two planar curves, or the self-intersections of one, at the contact
/// tolerance `tolerance` (default [`DEFAULT_RELATIVE_CONTACT`], relative to their size).
/// The objects are read once by the caller (a path `-` is standard input, which can be read
/// only once); `a` and `b` pair each with the path it came from, for messages.
pub fn intersect_curve_objects(
    a: (Object, &str),
    b: Option<(Object, &str)>,
    tolerance: Option<f64>,
) -> Result<()> {
    // Without --tolerance: relative to the curves' size (the same answer at every scale).
    let contact = match tolerance {
        Some(t) => Contact::Absolute(t),
        None => Contact::Relative(DEFAULT_RELATIVE_CONTACT),
    };
    let first = planar_of(a.0, a.1, "intersect")?;
    let hits = match b {
        Some((object, path)) => {
            let second = planar_of(object, path, "intersect")?;
            match &first {
                Planar::Polynomial(x) => pair(x, &second, contact)?,
                Planar::Rational(x) => pair(x, &second, contact)?,
            }
        }
        None => match (&first, contact) {
            (Planar::Polynomial(x), Contact::Absolute(t)) => self_intersections(x, t)?,
            (Planar::Rational(x), Contact::Absolute(t)) => self_intersections(x, t)?,
            (Planar::Polynomial(x), Contact::Relative(t)) => self_intersections_relative(x, t)?,
            (Planar::Rational(x), Contact::Relative(t)) => self_intersections_relative(x, t)?,
        },
    };
    print_json(&hits_json(&hits))
}

/// `spline offset CURVE --distance D [--direction X,Y,Z]`: one call of
/// `spline_shape::offset_planar_curve` (planar curves) or `offset_space_curve` (3-D curves,
/// along the direction), printing its record.
pub fn offset(args: &OffsetArgs) -> Result<()> {
    let options = OffsetOptions {
        degree: args.degree,
        tolerance: args.tolerance,
    };
    let object = read_object(&args.curve)?;
    let dim = match &object {
        Object::Curve(c) => c.dim,
        Object::Nurbs(c) => c.dim,
        Object::Surface(s) => {
            return offset_of_surface(s.dim, args, |to3| {
                offset_surface(&s.value.map_control_points(to3), args.distance, &options)
            });
        }
        Object::NurbsSurface(s) => {
            return offset_of_surface(s.dim, args, |to3| {
                offset_surface(&s.value.map_control_points(to3), args.distance, &options)
            });
        }
    };
    match (dim, &args.direction) {
        (2, None) => {
            let offset = match planar_of(object, &args.curve, "offset")? {
                Planar::Polynomial(c) => offset_planar_curve(&c, args.distance, &options)?,
                Planar::Rational(c) => offset_planar_curve(&c, args.distance, &options)?,
            };
            print_offset(&offset)
        }
        (3, Some(text)) => {
            let direction = Vector3::from(parse_direction(text)?);
            let to3 = |p: &Pt| Vector3::new(p[0], p[1], p[2]);
            let offset = match object {
                Object::Curve(c) => offset_space_curve(
                    &c.value.map_control_points(to3),
                    args.distance,
                    &direction,
                    &options,
                )?,
                Object::Nurbs(c) => offset_space_curve(
                    &c.value.map_control_points(to3),
                    args.distance,
                    &direction,
                    &options,
                )?,
                Object::Surface(_) | Object::NurbsSurface(_) => {
                    unreachable!("surfaces return above")
                }
            };
            print_offset(&offset)
        }
        (3, None) => Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{}: the offset of a 3-D curve needs --direction X,Y,Z (the point moves along T × V)",
                args.curve
            ),
        )
        .with_file(&args.curve)),
        (2, Some(_)) => Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{}: --direction is for 3-D curves; a planar curve is offset in its plane",
                args.curve
            ),
        )
        .with_file(&args.curve)),
        (other, _) => Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!(
                "{}: offset needs a curve in 2-D or 3-D, got {other} coordinates",
                args.curve
            ),
        )),
    }
}

/// `--direction`: `x,y,z` or a JSON array.
fn parse_direction(text: &str) -> Result<[f64; 3]> {
    let trimmed = text.trim();
    if trimmed.starts_with('[') {
        parse_arg("--direction", trimmed)
    } else {
        parse_arg("--direction", &format!("[{trimmed}]"))
    }
}

/// The offset of a surface in space (`offset` computes it from the surface's points in
/// 3-D) printed as its record: the surface, whether it is exact, the error bound.
fn offset_of_surface(
    dim: usize,
    args: &OffsetArgs,
    offset: impl FnOnce(&dyn Fn(&Pt) -> Vector3<f64>) -> Result<SurfaceOffset<f64>>,
) -> Result<()> {
    if dim != 3 {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!(
                "{}: the offset of a surface needs a surface in 3-D, got {dim} coordinates",
                args.curve
            ),
        ));
    }
    if args.direction.is_some() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{}: --direction is for 3-D curves; a surface is offset along its normal",
                args.curve
            ),
        )
        .with_file(&args.curve));
    }
    let result = offset(&|p: &Pt| Vector3::new(p[0], p[1], p[2]))?;
    let pad = |q: &Vector3<f64>| Pt::from_fn(|i, _| if i < 3 { q[i] } else { 0.0 });
    let record = match &result.surface {
        SurfaceOffsetShape::Polynomial(s) => Sized {
            value: s.map_control_points(pad),
            dim: 3,
        }
        .json()?,
        SurfaceOffsetShape::Rational(s) => Sized {
            value: s.map_control_points(pad),
            dim: 3,
        }
        .json()?,
    };
    let exact = match result.exact {
        ExactOffset::Approximate => "approximate",
        ExactOffset::Plane => "plane",
        ExactOffset::Sphere => "sphere",
        ExactOffset::Revolution => "revolution",
    };
    print_json(&json!({
        "surface": record,
        "exact": exact,
        "max_error": result.max_error,
    }))
}

/// Prints the record of an offset: the curve, the cusps and their points, the error bound.
fn print_offset<const D: usize>(offset: &CurveOffset<f64, D>) -> Result<()> {
    let pad = |q: &SVector<f64, D>| Pt::from_fn(|i, _| if i < D { q[i] } else { 0.0 });
    let record = match &offset.curve {
        OffsetShape::Polynomial(c) => Sized {
            value: c.map_control_points(pad),
            dim: D,
        }
        .json()?,
        OffsetShape::Rational(c) => Sized {
            value: c.map_control_points(pad),
            dim: D,
        }
        .json()?,
    };
    print_json(&json!({
        "curve": record,
        "cusps": offset.cusps.iter().map(|c| c.u).collect::<Vec<_>>(),
        "cusp_points": offset
            .cusps
            .iter()
            .map(|c| c.point.iter().copied().collect::<Vec<_>>())
            .collect::<Vec<_>>(),
        "max_error": offset.max_error,
    }))
}

/// `spline arclength CURVE`.
pub fn arclength(args: &ArclengthArgs) -> Result<()> {
    let any = read_curve(&args.curve)?;
    let curve = &any.curve.value;
    if args.reparametrize {
        let fit = reparametrize_by_arc_length(curve, 3, args.tolerance)?;
        let record = any.curve.with(fit.curve).json()?;
        return print_json(&json!({"curve": record, "max_error": fit.max_error}));
    }
    let table = ArcLengthTable::new(curve, args.tolerance)?;
    let params = match &args.at_length {
        None => Vec::new(),
        Some(text) => {
            let lengths: Vec<f64> = parse_arg("--at-length", text)?;
            lengths
                .iter()
                .map(|&s| table.param_at(s))
                .collect::<Result<Vec<f64>>>()?
        }
    };
    print_json(&json!({"length": table.total(), "params": params}))
}

/// `spline reduce CURVE --tolerance T`.
pub fn reduce(args: &ReduceArgs) -> Result<()> {
    let any = read_curve(&args.curve)?;
    let p = any.curve.value.degree();
    if args.times == 0 || args.times >= p {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "--times {}: a degree-{p} curve can be lowered by 1 to {}",
                args.times,
                p.saturating_sub(1)
            ),
        )
        .with_value(args.times as f64)
        .with_interval(1.0, p.saturating_sub(1) as f64));
    }
    let fit = reduce_degree(
        &any.curve.value,
        p - args.times,
        args.tolerance,
        args.refine,
    )?;
    let record = any.curve.with(fit.curve).json()?;
    print_json(&json!({"curve": record, "max_error": fit.max_error}))
}

/// `spline smoothing --x JSON --y JSON (--lambda L | --gcv | --residual S)`.
pub fn smoothing(args: &SmoothingArgs) -> Result<()> {
    let x: Vec<f64> = parse_arg("--x", &args.x)?;
    let (y, dim) = read_values(&args.y)?;
    let weights: Option<Vec<f64>> = args
        .weights
        .as_deref()
        .map(|t| parse_arg("--weights", t))
        .transpose()?;
    let record = |spline: BSpline<f64, Pt>| Sized { value: spline, dim }.json();
    if let Some(s) = args.residual {
        let fit = smoothing_to_residual(&x, &y, weights.as_deref(), args.degree, s)?;
        let mut out = json!({
            "curve": record(fit.spline)?,
            "residual": fit.residual,
            "converged": fit.converged,
        });
        if let Some(p) = fit.smoothing {
            out["smoothing"] = json!(p);
        }
        return print_json(&out);
    }
    let parameter = match (args.lambda, args.gcv) {
        (Some(l), _) => SmoothingParameter::Lambda(l),
        (None, true) => SmoothingParameter::Gcv,
        (None, false) => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "give --lambda L, --gcv or --residual S",
            ));
        }
    };
    let fit = smoothing_spline(&x, &y, weights.as_deref(), parameter)?;
    print_json(&json!({
        "curve": record(fit.spline)?,
        "lambda": fit.lambda,
        "gcv": fit.gcv,
        "trace": fit.trace,
        "residual": fit.residual,
    }))
}
