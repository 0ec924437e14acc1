//! NURBS curves and tensor-product surfaces in the tool: evaluation, structural operations,
//! `make` constructions and `mesh`.
//!
//! Like curves, NURBS curves and surfaces are read with their points padded to
//! [`io::MAX_DIM`] coordinates (zeros stay zero under every affine combination and under
//! the rational projection), so one instantiation of the library serves every dimension.

use crate::curves::{CurveOperations, Direction, Operation, apply_operation, derivative_rows};
use crate::io::{self, Json, MAX_DIM, Object, Pt};
use clap::{Args, Subcommand, ValueEnum};
use nalgebra::{SVector, Vector2, Vector3};
use serde_json::{Value, json};
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::exchange::{CurveRecord, SurfaceRecord};
use spline_geom::export::{SvgPlot, sample_params};
use spline_geom::{
    Axis, BSpline, CircleConstruction, Frame, MeshView, NurbsCurve, NurbsSurface, Surface,
    TriangleMesh,
};

/// A NURBS curve with padded points.
type Nurbs = NurbsCurve<f64, MAX_DIM>;
/// A NURBS surface with padded points.
type NurbsSurf = NurbsSurface<f64, MAX_DIM>;
/// A B-spline surface with padded points.
type Surf = Surface<f64, Pt>;

fn library_direction(direction: Direction) -> spline_geom::Direction {
    match direction {
        Direction::U => spline_geom::Direction::U,
        Direction::V => spline_geom::Direction::V,
    }
}

fn invalid(message: impl Into<String>) -> Error {
    Error::new(ErrorKind::InvalidArgument, message)
}

// ---------------------------------------------------------------------------------------
// Reading and writing NURBS curves and surfaces.

/// A validated NURBS curve of the tool, with the dimension of its points.
pub struct NurbsObject {
    curve: Nurbs,
    dim: usize,
}

impl NurbsObject {
    /// The curve as a planar NURBS curve.
    ///
    /// # Errors
    /// [`ErrorKind::DimensionMismatch`] unless the points have 2 coordinates.
    pub fn planar(&self) -> Result<NurbsCurve<f64, 2>> {
        if self.dim != 2 {
            return Err(Error::new(
                ErrorKind::DimensionMismatch,
                format!("expected a planar curve (2 coordinates), got {}", self.dim),
            ));
        }
        Ok(self.curve.map_control_points(|p| Vector2::new(p[0], p[1])))
    }
}

/// A validated surface of the tool (rational or not), with the dimension of its points.
pub struct SurfaceObject {
    surface: ToolSurface,
    dim: usize,
}

/// Reads a NURBS curve record (weights optional).
pub fn nurbs_from_record(record: &CurveRecord) -> Result<NurbsObject> {
    let (curve, dim) = nurbs_parts(record)?;
    Ok(NurbsObject { curve, dim })
}

/// Reads a NURBS curve record (weights optional) into a padded curve and its dimension.
fn nurbs_parts(record: &CurveRecord) -> Result<(Nurbs, usize)> {
    let dim = record.dimension()?;
    let points = record
        .control_points
        .iter()
        .map(|r| io::pad(r))
        .collect::<Result<Vec<_>>>()?;
    let weights = record
        .weights
        .clone()
        .unwrap_or_else(|| vec![1.0; points.len()]);
    let knots = KnotVector::new(record.degree, record.knots.clone())?;
    Ok((NurbsCurve::new(knots, points, weights)?, dim))
}

/// The exchange-format record of a padded NURBS curve.
fn nurbs_record(curve: &Nurbs, dim: usize) -> CurveRecord {
    CurveRecord {
        degree: curve.degree(),
        knots: curve.knots().knots().to_vec(),
        control_points: curve
            .control_points()
            .iter()
            .map(|p| io::unpad(p, dim))
            .collect(),
        weights: Some(curve.weights()),
    }
}

fn nurbs_json(curve: &Nurbs, dim: usize) -> Value {
    json!(nurbs_record(curve, dim))
}

/// A surface of the tool: rational or not, with its dimension.
enum ToolSurface {
    Plain(Surf),
    Rational(NurbsSurf),
}

/// Reads a surface object (see [`io::classify`]).
pub fn surface_from_value(value: Value) -> Result<SurfaceObject> {
    let (surface, dim) = surface_parts(value)?;
    Ok(SurfaceObject { surface, dim })
}

fn surface_parts(value: Value) -> Result<(ToolSurface, usize)> {
    let record: SurfaceRecord = io::from_value("surface", value)?;
    let dim = record.dimension()?;
    let (ku, kv) = record.knot_vectors::<f64>()?;
    let net = record
        .control_points
        .iter()
        .map(|row| row.iter().map(|p| io::pad(p)).collect::<Result<Vec<_>>>())
        .collect::<Result<Vec<_>>>()?;
    let surface = match record.weights {
        None => ToolSurface::Plain(Surface::from_net(ku, kv, net)?),
        Some(weights) => ToolSurface::Rational(NurbsSurface::from_net(ku, kv, net, weights)?),
    };
    Ok((surface, dim))
}

fn surface_record(surface: &Surf, dim: usize) -> SurfaceRecord {
    let (p, q) = surface.degrees();
    SurfaceRecord {
        degree: [p, q],
        knots: [
            surface.knots_u().knots().to_vec(),
            surface.knots_v().knots().to_vec(),
        ],
        control_points: surface
            .control_net()
            .iter()
            .map(|row| row.iter().map(|pt| io::unpad(pt, dim)).collect())
            .collect(),
        weights: None,
    }
}

fn nurbs_surface_record(surface: &NurbsSurf, dim: usize) -> SurfaceRecord {
    let cartesian = surface
        .homogeneous()
        .map_control_points(spline_geom::Homogeneous::project);
    let mut record = surface_record(&cartesian, dim);
    let nv = surface.net_size().1;
    record.weights = Some(
        surface
            .weights()
            .chunks_exact(nv)
            .map(<[f64]>::to_vec)
            .collect(),
    );
    record
}

fn surface_json(surface: &ToolSurface, dim: usize) -> Value {
    match surface {
        ToolSurface::Plain(s) => json!(surface_record(s, dim)),
        ToolSurface::Rational(s) => json!(nurbs_surface_record(s, dim)),
    }
}

// ---------------------------------------------------------------------------------------
// eval, structural operations, plot.

/// `[param][k][coord]` rational derivatives of a NURBS curve.
pub fn eval_nurbs(nurbs: &NurbsObject, params: &[f64], order: usize) -> Result<Vec<Vec<Vec<f64>>>> {
    derivative_rows(params, order, nurbs.dim, |u, out| {
        nurbs.curve.derivatives_into(u, out)
    })
}

/// `[param][k][l][coord]` partial derivatives of a surface, `k, l = 0..=order`.
pub fn eval_surface(
    surface: &SurfaceObject,
    params: &[[f64; 2]],
    order: usize,
) -> Result<Vec<Vec<Vec<Vec<f64>>>>> {
    crate::curves::check_order("--derivatives", order)?;
    let width = order + 1;
    io::check_output_size("eval", &[params.len(), width, width, surface.dim])?;
    let mut flat = vec![Pt::zeros(); width * width];
    params
        .iter()
        .enumerate()
        .map(|(i, &[u, v])| {
            match &surface.surface {
                ToolSurface::Plain(s) => s.derivatives_into(u, v, order, &mut flat),
                ToolSurface::Rational(s) => s.derivatives_into(u, v, order, &mut flat),
            }
            .map_err(|e| e.context(format_args!("--at entry {i}")))?;
            Ok(flat
                .chunks_exact(width)
                .map(|row| {
                    row.iter()
                        .map(|p| io::unpad(p, surface.dim))
                        .collect::<Vec<_>>()
                })
                .collect::<Vec<_>>())
        })
        .collect()
}

/// Structural operations on NURBS curves run in homogeneous space.
impl CurveOperations for Nurbs {
    fn insert_knot(&self, u: f64, times: usize) -> Result<Self> {
        NurbsCurve::insert_knot(self, u, times)
    }

    fn refine(&self, knots: &[f64]) -> Result<Self> {
        NurbsCurve::refine(self, knots)
    }

    fn remove_knot(&self, u: f64, times: usize, relative_tolerance: f64) -> Result<Self> {
        NurbsCurve::remove_knot(self, u, times, relative_tolerance)
    }

    fn elevate_degree(&self, times: usize) -> Result<Self> {
        NurbsCurve::elevate_degree(self, times)
    }

    fn split(&self, u: f64) -> Result<(Self, Self)> {
        NurbsCurve::split(self, u)
    }

    fn for_each_bezier_piece(&self, f: &mut dyn FnMut(Self) -> Result<()>) -> Result<()> {
        for piece in self.bezier_segments()? {
            f(piece)?;
        }
        Ok(())
    }

    fn derivative_curve(&self, _order: usize) -> Result<Self> {
        Err(invalid(
            "the derivative of a NURBS curve is not a NURBS curve on the same knots; use `spline eval --derivatives K` for rational derivatives",
        ))
    }
}

/// A structural operation on a NURBS curve (in homogeneous space).
pub fn apply_to_nurbs(nurbs: &NurbsObject, operation: &Operation) -> Result<Json> {
    apply_operation(&nurbs.curve, operation, |curve| {
        io::raw(&nurbs_record(&curve, nurbs.dim))
    })
}

/// Writes the Bézier segments of a NURBS curve as they are made.
pub fn stream_nurbs_bezier(nurbs: &NurbsObject) -> Result<()> {
    crate::curves::stream_bezier(&nurbs.curve, |curve| {
        io::raw(&nurbs_record(&curve, nurbs.dim))
    })
}

/// A structural operation on a surface in one direction.
pub fn apply_to_surface(
    object: &SurfaceObject,
    operation: &Operation,
    direction: Option<Direction>,
) -> Result<Json> {
    let (surface, dim) = (&object.surface, object.dim);
    // The direction defaults to u, as the optional `[--direction u|v]` of the contract.
    let needs_direction = || -> Result<spline_geom::Direction> {
        Ok(library_direction(direction.unwrap_or(Direction::U)))
    };
    let one = |s: ToolSurface| surface_json(&s, dim);
    match operation {
        Operation::Bezier | Operation::Derivative { .. } if direction.is_some() => {
            return Err(invalid("--direction is not used by this operation"));
        }
        _ => {}
    }
    let value = match (surface, operation) {
        (ToolSurface::Plain(s), Operation::Insert { knot, times }) => one(ToolSurface::Plain(
            s.insert_knot(needs_direction()?, *knot, *times)?,
        )),
        (ToolSurface::Rational(s), Operation::Insert { knot, times }) => one(
            ToolSurface::Rational(s.insert_knot(needs_direction()?, *knot, *times)?),
        ),
        (ToolSurface::Plain(s), Operation::Refine { knots }) => {
            one(ToolSurface::Plain(s.refine(needs_direction()?, knots)?))
        }
        (ToolSurface::Rational(s), Operation::Refine { knots }) => {
            one(ToolSurface::Rational(s.refine(needs_direction()?, knots)?))
        }
        (
            ToolSurface::Plain(s),
            Operation::Remove {
                knot,
                times,
                tolerance,
            },
        ) => one(ToolSurface::Plain(s.remove_knot(
            needs_direction()?,
            *knot,
            *times,
            *tolerance,
        )?)),
        (
            ToolSurface::Rational(s),
            Operation::Remove {
                knot,
                times,
                tolerance,
            },
        ) => one(ToolSurface::Rational(s.remove_knot(
            needs_direction()?,
            *knot,
            *times,
            *tolerance,
        )?)),
        (ToolSurface::Plain(s), Operation::Elevate { times }) => one(ToolSurface::Plain(
            s.elevate_degree(needs_direction()?, *times)?,
        )),
        (ToolSurface::Rational(s), Operation::Elevate { times }) => one(ToolSurface::Rational(
            s.elevate_degree(needs_direction()?, *times)?,
        )),
        (ToolSurface::Plain(s), Operation::Split { at }) => {
            let (a, b) = s.split(needs_direction()?, *at)?;
            json!([one(ToolSurface::Plain(a)), one(ToolSurface::Plain(b))])
        }
        (ToolSurface::Rational(s), Operation::Split { at }) => {
            let (a, b) = s.split(needs_direction()?, *at)?;
            json!([one(ToolSurface::Rational(a)), one(ToolSurface::Rational(b))])
        }
        (ToolSurface::Plain(s), Operation::Bezier) => json!(
            s.bezier_patches()
                .into_iter()
                .map(|row| row
                    .into_iter()
                    .map(|p| one(ToolSurface::Plain(p)))
                    .collect::<Vec<_>>())
                .collect::<Vec<_>>()
        ),
        (ToolSurface::Rational(s), Operation::Bezier) => json!(
            s.bezier_patches()?
                .into_iter()
                .map(|row| row
                    .into_iter()
                    .map(|p| one(ToolSurface::Rational(p)))
                    .collect::<Vec<_>>())
                .collect::<Vec<_>>()
        ),
        (ToolSurface::Plain(s), Operation::Derivative { order }) => json!({
            "du": one(ToolSurface::Plain(s.derivative_surface(*order, 0)?)),
            "dv": one(ToolSurface::Plain(s.derivative_surface(0, *order)?)),
        }),
        (ToolSurface::Rational(_), Operation::Derivative { .. }) => {
            return Err(invalid(
                "the derivative of a NURBS surface is not a NURBS surface on the same knots; use `spline eval --derivatives K`",
            ));
        }
    };
    io::raw(&value)
}

/// Draws a planar NURBS curve: control polygon, control points, the curve, and optionally
/// its curvature comb.
pub fn plot_nurbs(svg: &mut SvgPlot, nurbs: &NurbsObject, comb: bool) -> Result<()> {
    let (curve, dim) = (&nurbs.curve, nurbs.dim);
    if dim != 2 {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("plot draws planar curves (2 coordinates), got {dim}"),
        ));
    }
    let planar: NurbsCurve<f64, 2> = curve.map_control_points(|p| Vector2::new(p[0], p[1]));
    let polygon = planar.control_points();
    svg.add_polyline(&polygon, "polygon");
    svg.add_markers(&polygon, "control");
    let params = sample_params(planar.homogeneous(), 64);
    svg.add_polyline(&planar.eval_many(&params)?, "curve");
    if comb {
        let (a, b) = planar.domain();
        let samples = 200;
        let teeth: Vec<(Vector2<f64>, Vector2<f64>, f64)> = (0..=samples)
            .filter_map(|j| {
                let u = a + (b - a) * f64::from(j) / f64::from(samples);
                let p = planar.eval(u).ok()?;
                let n = planar.unit_normal(u).ok()?;
                let k = planar.signed_curvature(u).ok()?;
                Some((p, n, k))
            })
            .collect();
        // |n κ| = |κ|: the curvature itself, not a norm that would underflow for tiny κ.
        let max = teeth.iter().fold(0.0f64, |m, (_, _, k)| m.max(k.abs()));
        if max > 0.0 {
            let (lo, hi) = polygon.iter().fold(
                (
                    Vector2::repeat(f64::INFINITY),
                    Vector2::repeat(f64::NEG_INFINITY),
                ),
                |(lo, hi), p| (lo.inf(p), hi.sup(p)),
            );
            // A tooth of length 0.2 · size · |κ| / max|κ|, formed without overflow.
            let size = (hi * 0.5 - lo * 0.5).amax() * 2.0;
            let segments: Vec<_> = teeth
                .iter()
                .map(|(p, n, k)| (*p, p - n * ((k / max) * (0.2 * size))))
                .filter(|(_, q)| q.x.is_finite() && q.y.is_finite())
                .collect();
            let ends: Vec<_> = segments.iter().map(|s| s.1).collect();
            svg.add_segments(&segments, "comb");
            svg.add_polyline(&ends, "comb");
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------
// make

/// Build a classic curve or surface and print it as JSON.
#[derive(Args)]
pub struct MakeArgs {
    #[command(subcommand)]
    shape: Shape,
}

/// The full-circle constructions of the course notes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Construction {
    /// 9 control points on a square, knots [0,0,0,¼,¼,½,½,¾,¾,1,1,1], weights [1,√2/2,1,…].
    Square,
    /// 7 control points on an equilateral triangle, knots [0,0,0,⅓,⅓,⅔,⅔,1,1,1], weights
    /// [1,½,1,½,1,½,1].
    Triangle,
}

#[derive(Subcommand)]
enum Shape {
    /// A full circle as a NURBS curve (degree 2, starting at center + radius · x axis and
    /// turning counter-clockwise about the normal).
    Circle(CircleArgs),
    /// A circular arc of any sweep as a NURBS curve of rational quadratic pieces.
    Arc(ArcArgs),
    /// A conic arc: the rational quadratic Bézier curve P0, P1, P2 with weights [1, w1, 1]
    /// (ellipse for w1 < 1, parabola for w1 = 1, hyperbola for w1 > 1).
    Conic(ConicArgs),
    /// The cylindrical surface (extrusion) of a curve along a vector: degree 1 in v on [0, 1].
    Extrude(ExtrudeArgs),
    /// The ruled surface joining two curves by segments (v = 0 on the first, v = 1 on the
    /// second); the curves are made compatible (degree, domain, knots) first.
    Ruled(RuledArgs),
    /// The conical surface joining a curve (v = 0) to an apex (v = 1).
    Cone(ConeArgs),
    /// The surface of revolution of a profile curve about an axis (u along the profile,
    /// v in [0, 1] around the axis).
    Revolve(RevolveArgs),
    /// A NURBS sphere: a half circle from the north to the south pole revolved about the z
    /// axis (5 × 9 control points, degrees 2 and 2).
    Sphere(SphereArgs),
    /// A NURBS torus: a circle revolved about an axis through the center (9 × 9 control
    /// points, degrees 2 and 2).
    Torus(TorusArgs),
}

#[derive(Args)]
struct CircleArgs {
    /// Center as a JSON array: [x, y] for a planar circle, [x, y, z] for a circle in space.
    #[arg(long)]
    center: String,
    /// Radius (positive).
    #[arg(long, allow_hyphen_values = true)]
    radius: f64,
    /// Normal of the plane of a circle in space, as a JSON array [x, y, z] (default
    /// [0, 0, 1]; only with a 3-D center). The circle starts on the coordinate axis least
    /// aligned with the normal, projected on the plane.
    #[arg(long)]
    normal: Option<String>,
    /// How the circle is built.
    #[arg(long, value_enum, default_value_t = Construction::Square)]
    construction: Construction,
}

#[derive(Args)]
struct ArcArgs {
    /// Center as a JSON array: [x, y] or [x, y, z].
    #[arg(long)]
    center: String,
    /// Radius (positive).
    #[arg(long, allow_hyphen_values = true)]
    radius: f64,
    /// Normal of the plane for an arc in space, as a JSON array (default [0, 0, 1]; only with
    /// a 3-D center).
    #[arg(long)]
    normal: Option<String>,
    /// Start angle in degrees, from the x axis of the plane towards its y axis.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    start: f64,
    /// Sweep angle in degrees: non-zero, at most 360 in magnitude; negative turns clockwise.
    #[arg(long, allow_hyphen_values = true)]
    sweep: f64,
    /// Largest angle of one rational quadratic piece, in degrees, below 180 (the notes use 90
    /// and 120). Each piece of angle Δ has the middle weight cos(Δ/2).
    #[arg(long, default_value_t = 90.0, allow_hyphen_values = true)]
    max_piece: f64,
}

#[derive(Args)]
struct ConicArgs {
    /// Start point P0 as a JSON array (2 to 8 coordinates).
    #[arg(long)]
    p0: String,
    /// Middle control point P1, where the end tangents meet.
    #[arg(long)]
    p1: String,
    /// End point P2.
    #[arg(long)]
    p2: String,
    /// Middle weight w1 > 0 (w0 = w2 = 1).
    #[arg(long, allow_hyphen_values = true)]
    w1: Option<f64>,
    /// Instead of --w1: the shoulder point S, the point of the arc at u = ½, on the segment
    /// from the midpoint M of P0P2 to P1; then w1 = |SM| / |SP1|.
    #[arg(long, conflicts_with = "w1")]
    shoulder: Option<String>,
}

#[derive(Args)]
struct ExtrudeArgs {
    /// Curve file (JSON, B-spline or NURBS curve), or - for standard input.
    curve: String,
    /// Extrusion vector as a JSON array, of the curve's dimension.
    #[arg(long)]
    vector: String,
}

#[derive(Args)]
struct RuledArgs {
    /// First curve file (JSON, B-spline or NURBS): the surface at v = 0.
    first: String,
    /// Second curve file: the surface at v = 1 (its domain is mapped onto the first's).
    second: String,
}

#[derive(Args)]
struct ConeArgs {
    /// Curve file (JSON, B-spline or NURBS), or - for standard input.
    curve: String,
    /// Apex as a JSON array, of the curve's dimension.
    #[arg(long)]
    apex: String,
}

#[derive(Args)]
struct RevolveArgs {
    /// Profile curve file (JSON, B-spline or NURBS, 2 or 3 coordinates; planar profiles lie
    /// in z = 0), or - for standard input.
    profile: String,
    /// A point of the axis as a JSON array (2 or 3 coordinates).
    #[arg(long, default_value = "[0, 0, 0]")]
    axis_point: String,
    /// The direction of the axis as a JSON array (2 or 3 coordinates, non-zero).
    #[arg(long, default_value = "[0, 0, 1]")]
    axis_direction: String,
    /// Angle of revolution in degrees, right-handed about the axis direction: non-zero, at
    /// most 360 in magnitude. A full turn uses the 9-point circle (6.9)–(6.10), otherwise
    /// pieces of at most 90°.
    #[arg(long, default_value_t = 360.0, allow_hyphen_values = true)]
    angle: f64,
}

#[derive(Args)]
struct SphereArgs {
    /// Center as a JSON array [x, y, z].
    #[arg(long)]
    center: String,
    /// Radius (positive).
    #[arg(long, allow_hyphen_values = true)]
    radius: f64,
}

#[derive(Args)]
struct TorusArgs {
    /// Center as a JSON array [x, y, z].
    #[arg(long)]
    center: String,
    /// Major radius: distance from the axis to the center of the revolved circle.
    #[arg(long, allow_hyphen_values = true)]
    major: f64,
    /// Minor radius: radius of the revolved circle (below the major radius).
    #[arg(long, allow_hyphen_values = true)]
    minor: f64,
    /// Direction of the axis through the center, as a JSON array (non-zero).
    #[arg(long, default_value = "[0, 0, 1]")]
    axis: String,
}

/// Parses a JSON point option with a fixed number of coordinates.
fn point<const D: usize>(option: &str, text: &str) -> Result<SVector<f64, D>> {
    let v: Vec<f64> = io::parse_arg(option, text)?;
    if v.len() != D {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("{option} must have {D} coordinates, got {}", v.len()),
        ));
    }
    Ok(SVector::from_column_slice(&v))
}

/// Parses a JSON point option of any dimension up to `MAX_DIM`, padded.
fn padded_point(option: &str, text: &str) -> Result<(Pt, usize)> {
    let v: Vec<f64> = io::parse_arg(option, text)?;
    let p = io::pad(&v).map_err(|e| e.context(option))?;
    Ok((p, v.len()))
}

fn same_dim(option: &str, got: usize, expected: usize) -> Result<()> {
    if got == expected {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("{option} has {got} coordinates, the curve has {expected}"),
        ))
    }
}

fn construction(c: Construction) -> CircleConstruction {
    match c {
        Construction::Square => CircleConstruction::Square,
        Construction::Triangle => CircleConstruction::Triangle,
    }
}

/// The frame of a circle or arc: planar for a 2-D center, the plane through a 3-D center
/// perpendicular to the normal otherwise. Returns the frame padded to `MAX_DIM` and the
/// dimension.
fn circle_frame(center: &str, normal: Option<&str>) -> Result<(Frame<f64, MAX_DIM>, usize)> {
    let c: Vec<f64> = io::parse_arg("--center", center)?;
    let pad3 = |v: Vector3<f64>| io::pad(v.as_slice());
    match c.len() {
        2 => {
            if normal.is_some() {
                return Err(invalid(
                    "--normal applies to circles in space (3-D centers)",
                ));
            }
            let f = Frame::planar(Vector2::new(c[0], c[1]));
            let frame = Frame::new(
                io::pad(f.origin().as_slice())?,
                io::pad(f.x_axis().as_slice())?,
                io::pad(f.y_axis().as_slice())?,
            )?;
            Ok((frame, 2))
        }
        3 => {
            let n = normal.map_or(Ok(Vector3::z()), |t| point::<3>("--normal", t))?;
            let f = Frame::with_normal(Vector3::new(c[0], c[1], c[2]), n)?;
            let frame = Frame::new(pad3(f.origin())?, pad3(f.x_axis())?, pad3(f.y_axis())?)?;
            Ok((frame, 3))
        }
        d => Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("--center must have 2 or 3 coordinates, got {d}"),
        )),
    }
}

/// A curve object of the tool as a NURBS curve (unit weights for B-splines), with its
/// dimension and whether it was rational.
fn read_curve(path: &str) -> Result<(Nurbs, usize, bool)> {
    match io::read_object(path)? {
        Object::Curve(c) => Ok((NurbsCurve::from_bspline(&c.curve), c.dim, false)),
        Object::Nurbs(NurbsObject { curve, dim }) => Ok((curve, dim, true)),
        Object::Surface(_) => Err(invalid(format!("{path}: expected a curve, got a surface"))),
    }
}

/// The polynomial curve behind a unit-weight NURBS curve.
fn polynomial(curve: &Nurbs) -> BSpline<f64, Pt> {
    curve
        .to_bspline()
        .expect("a B-spline read as NURBS has unit weights")
}

/// A surface built from the curve in `path` and the point given by `option`
/// (`(name, JSON)`, of the curve's dimension): NURBS when the curve is, polynomial otherwise.
fn curve_and_point(
    path: &str,
    (option, text): (&str, &str),
    rational: impl FnOnce(&Nurbs, Pt) -> Result<NurbsSurf>,
    plain: impl FnOnce(&BSpline<f64, Pt>, Pt) -> Result<Surf>,
) -> Result<Value> {
    let (curve, dim, is_rational) = read_curve(path)?;
    let (point, d) = padded_point(option, text)?;
    same_dim(option, d, dim)?;
    let surface = if is_rational {
        ToolSurface::Rational(rational(&curve, point)?)
    } else {
        ToolSurface::Plain(plain(&polynomial(&curve), point)?)
    };
    Ok(surface_json(&surface, dim))
}

fn make_json(shape: &Shape) -> Result<Value> {
    Ok(match shape {
        Shape::Circle(a) => {
            let (frame, dim) = circle_frame(&a.center, a.normal.as_deref())?;
            nurbs_json(
                &NurbsCurve::circle(&frame, a.radius, construction(a.construction))?,
                dim,
            )
        }
        Shape::Arc(a) => {
            let (frame, dim) = circle_frame(&a.center, a.normal.as_deref())?;
            let pieces = (a.sweep.abs() / a.max_piece).ceil();
            #[allow(clippy::cast_precision_loss)]
            if a.max_piece > 0.0 && pieces > spline_geom::MAX_ARC_PIECES as f64 {
                return Err(invalid(format!(
                    "--max-piece {}: an arc of {}° needs {} pieces of at most {}°, more than the supported maximum {}",
                    spline_core::Short(a.max_piece),
                    spline_core::Short(a.sweep.abs()),
                    spline_core::Short(pieces),
                    spline_core::Short(a.max_piece),
                    spline_geom::MAX_ARC_PIECES
                )));
            }
            let arc = NurbsCurve::arc_with_max_piece(
                &frame,
                a.radius,
                a.start.to_radians(),
                a.sweep.to_radians(),
                a.max_piece.to_radians(),
            )?;
            nurbs_json(&arc, dim)
        }
        Shape::Conic(a) => {
            let (p0, d0) = padded_point("--p0", &a.p0)?;
            let (p1, d1) = padded_point("--p1", &a.p1)?;
            let (p2, d2) = padded_point("--p2", &a.p2)?;
            same_dim("--p1", d1, d0)?;
            same_dim("--p2", d2, d0)?;
            let arc = match (&a.w1, &a.shoulder) {
                (Some(w1), None) => NurbsCurve::conic_arc(p0, p1, p2, *w1)?,
                (None, Some(s)) => {
                    let (s, ds) = padded_point("--shoulder", s)?;
                    same_dim("--shoulder", ds, d0)?;
                    NurbsCurve::conic_arc_through(p0, p1, p2, s)?
                }
                _ => {
                    return Err(invalid(
                        "give the middle weight with --w1 W or the shoulder point with --shoulder JSON",
                    ));
                }
            };
            nurbs_json(&arc, d0)
        }
        Shape::Extrude(a) => curve_and_point(
            &a.curve,
            ("--vector", &a.vector),
            NurbsSurface::extrusion,
            Surface::extrusion,
        )?,
        Shape::Ruled(a) => {
            let (c1, d1, r1) = read_curve(&a.first)?;
            let (c2, d2, r2) = read_curve(&a.second)?;
            if d1 != d2 {
                return Err(Error::new(
                    ErrorKind::DimensionMismatch,
                    format!("the curves have {d1} and {d2} coordinates"),
                ));
            }
            if r1 || r2 {
                surface_json(&ToolSurface::Rational(NurbsSurface::ruled(&c1, &c2)?), d1)
            } else {
                surface_json(
                    &ToolSurface::Plain(Surface::ruled(&polynomial(&c1), &polynomial(&c2))?),
                    d1,
                )
            }
        }
        Shape::Cone(a) => curve_and_point(
            &a.curve,
            ("--apex", &a.apex),
            NurbsSurface::cone,
            Surface::cone,
        )?,
        Shape::Revolve(a) => {
            let (curve, dim, _) = read_curve(&a.profile)?;
            if !(2..=3).contains(&dim) {
                return Err(Error::new(
                    ErrorKind::DimensionMismatch,
                    format!("a profile must have 2 or 3 coordinates, got {dim}"),
                ));
            }
            let to3 = |option: &str, text: &str| -> Result<Vector3<f64>> {
                let (p, d) = padded_point(option, text)?;
                if !(2..=3).contains(&d) {
                    return Err(Error::new(
                        ErrorKind::DimensionMismatch,
                        format!("{option} must have 2 or 3 coordinates, got {d}"),
                    ));
                }
                Ok(Vector3::new(p[0], p[1], p[2]))
            };
            let axis = Axis::new(
                to3("--axis-point", &a.axis_point)?,
                to3("--axis-direction", &a.axis_direction)?,
            )?;
            let profile: NurbsCurve<f64, 3> =
                curve.map_control_points(|p| Vector3::new(p[0], p[1], p[2]));
            let surface = NurbsSurface::revolution(&profile, &axis, a.angle.to_radians())?;
            json!(SurfaceRecord::from_nurbs_surface(&surface))
        }
        Shape::Sphere(a) => {
            let c = point::<3>("--center", &a.center)?;
            json!(SurfaceRecord::from_nurbs_surface(&NurbsSurface::sphere(
                c, a.radius
            )?))
        }
        Shape::Torus(a) => {
            let c = point::<3>("--center", &a.center)?;
            let axis = point::<3>("--axis", &a.axis)?;
            json!(SurfaceRecord::from_nurbs_surface(&NurbsSurface::torus(
                c, axis, a.major, a.minor
            )?))
        }
    })
}

/// `spline make ...`: prints the constructed object as JSON.
pub fn make(args: &MakeArgs) -> Result<()> {
    io::print_json(&make_json(&args.shape)?)
}

// ---------------------------------------------------------------------------------------
// mesh

/// Triangulate a surface and write the mesh.
#[derive(Args)]
pub struct MeshArgs {
    /// Surface file (JSON: a B-spline or NURBS surface with 1 to 3 coordinates), or - for
    /// standard input.
    surface: String,
    /// Output file; the extension picks the format: FILE.obj (Wavefront, with vertex
    /// normals), FILE.off (geomview OFF) or FILE.svg (a shaded picture).
    #[arg(short, long)]
    output: String,
    /// Number of equal parameter steps in u (every interior knot is added as well).
    #[arg(long, default_value_t = 32)]
    segments_u: usize,
    /// Number of equal parameter steps in v (every interior knot is added as well).
    #[arg(long, default_value_t = 32)]
    segments_v: usize,
}

#[derive(Clone, Copy)]
enum MeshFormat {
    Obj,
    Off,
    Svg,
}

fn mesh_format(path: &str) -> Result<MeshFormat> {
    let ext = std::path::Path::new(path)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("obj") => Ok(MeshFormat::Obj),
        Some("off") => Ok(MeshFormat::Off),
        Some("svg") => Ok(MeshFormat::Svg),
        _ => Err(invalid(format!(
            "{path}: the output must end in .obj, .off or .svg"
        ))),
    }
}

/// `spline mesh SURFACE -o FILE`: writes the mesh and prints
/// `{"output", "vertices", "triangles"}`.
pub fn mesh(args: &MeshArgs) -> Result<()> {
    let format = mesh_format(&args.output)?;
    let SurfaceObject { surface, dim } = match io::read_object(&args.surface)? {
        Object::Surface(s) => s,
        _ => {
            return Err(invalid(format!(
                "{}: mesh needs a surface (degree [p, q])",
                args.surface
            )));
        }
    };
    if dim > 3 {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("meshes are built from surfaces with 1 to 3 coordinates, got {dim}"),
        ));
    }
    // Open the output before the work, so that a bad path fails at once.
    let file = io::create_file(&args.output)?;
    let to3 = |p: &Pt| Vector3::new(p[0], p[1], p[2]);
    let mesh: TriangleMesh = match &surface {
        ToolSurface::Plain(s) => s
            .map_control_points(to3)
            .tessellate(args.segments_u, args.segments_v)?,
        ToolSurface::Rational(s) => s
            .map_control_points(to3)
            .tessellate(args.segments_u, args.segments_v)?,
    };
    let text = match format {
        MeshFormat::Obj => mesh.to_obj(),
        MeshFormat::Off => mesh.to_off(),
        MeshFormat::Svg => mesh.to_svg(&MeshView::default()),
    };
    io::write_file(file, &args.output, text.as_bytes())?;
    io::print_json(&json!({
        "output": args.output,
        "vertices": mesh.vertices.len(),
        "triangles": mesh.triangles.len(),
    }))
}
