//! `spline make`: the classic constructions of the library (circles, arcs, conics,
//! extrusions, ruled, conical and revolved surfaces, spheres, tori) from the command line.

use crate::io::{self, Json, MAX_DIM, Pt};
use crate::objects::{Curve, Nurbs, NurbsSurf, Sized, Surf, read_curve};
use clap::{Args, Subcommand, ValueEnum};
use nalgebra::{SVector, Vector2, Vector3};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::{Axis, CircleConstruction, Frame, NurbsCurve, NurbsSurface, Surface};
use spline_io::exchange::SurfaceRecord;

fn invalid(message: impl Into<String>) -> Error {
    Error::new(ErrorKind::InvalidArgument, message)
}

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
    /// A NURBS sphere: a half circle from the north to the south pole revolved about the
    /// axis through the poles (--axis, default z; 5 × 9 control points, degrees 2 and 2).
    Sphere(SphereArgs),
    /// A NURBS torus: a circle revolved about an axis through the center (9 × 9 control
    /// points, degrees 2 and 2).
    Torus(TorusArgs),
    /// The surface through section curves (skinning, lofting): u along the sections;
    /// prints {surface, params} (the v of each section).
    Skin(SkinArgs),
    /// A B-spline profile swept along a path with rotation-minimising frames; prints
    /// {surface, params} (the v of each copy of the profile).
    Sweep(SweepArgs),
    /// The Coons patch of four boundary curves: bottom (v = 0), top, left (u = 0), right
    /// (B-spline or NURBS; a NURBS patch when any curve has weights).
    Coons(CoonsArgs),
    /// The Gordon surface through a network of u-curves and v-curves (the first curve of
    /// each family is the boundary where the other family starts); prints {surface,
    /// params_u, params_v, crossing_gap}.
    Gordon(GordonArgs),
}

/// `make skin`.
#[derive(Args)]
struct SkinArgs {
    /// The section curves (JSON files), in order.
    #[arg(long, num_args = 1.., required = true)]
    curves: Vec<String>,
    /// The degree across the sections (lowered to the number of sections − 1).
    #[arg(long, default_value_t = 3)]
    degree: usize,
}

/// `make sweep`.
#[derive(Args)]
struct SweepArgs {
    /// The profile curve in space, placed at the start of the path.
    #[arg(long)]
    profile: String,
    /// The path curve in space.
    #[arg(long)]
    path: String,
    /// Copies of the profile along the path that the surface interpolates.
    #[arg(long, default_value_t = 16)]
    sections: usize,
}

/// `make coons`.
#[derive(Args)]
struct CoonsArgs {
    /// The four boundary curves: bottom, top, left, right.
    #[arg(long, num_args = 4, required = true)]
    curves: Vec<String>,
}

/// `make gordon`.
#[derive(Args)]
struct GordonArgs {
    /// The curves along u, in order across v.
    #[arg(long, num_args = 2.., required = true)]
    u_curves: Vec<String>,
    /// The curves along v, in order across u.
    #[arg(long, num_args = 2.., required = true)]
    v_curves: Vec<String>,
    /// The degree across each family (lowered to the number of curves − 1).
    #[arg(long, default_value_t = 3)]
    degree: usize,
    /// How far apart crossing curves may be.
    #[arg(long, default_value_t = 1e-6)]
    tolerance: f64,
}

/// Where a circle or an arc lies: its center, radius and plane.
#[derive(Args)]
struct PlaneCircle {
    /// Center as a JSON array: [x, y] in the plane, [x, y, z] in space.
    #[arg(long)]
    center: String,
    /// Radius (positive).
    #[arg(long, allow_hyphen_values = true)]
    radius: f64,
    /// Normal of the plane in space, as a JSON array [x, y, z] (default [0, 0, 1]; only with
    /// a 3-D center). The circle starts on the coordinate axis least aligned with the
    /// normal, projected on the plane.
    #[arg(long)]
    normal: Option<String>,
}

#[derive(Args)]
struct CircleArgs {
    #[command(flatten)]
    on: PlaneCircle,
    /// How the circle is built.
    #[arg(long, value_enum, default_value_t = Construction::Square)]
    construction: Construction,
}

#[derive(Args)]
struct ArcArgs {
    #[command(flatten)]
    on: PlaneCircle,
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
    /// Direction of the axis through the poles, as a JSON array (non-zero).
    #[arg(long, default_value = "[0, 0, 1]")]
    axis: String,
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

/// A surface built from the curve in `path` and the point given by `option`
/// (`(name, JSON)`, of the curve's dimension): NURBS when the curve is, polynomial otherwise.
fn curve_and_point(
    path: &str,
    (option, text): (&str, &str),
    rational: impl FnOnce(&Nurbs, Pt) -> Result<NurbsSurf>,
    plain: impl FnOnce(&Curve, Pt) -> Result<Surf>,
) -> Result<Json> {
    let curve = read_curve(path)?;
    let (point, d) = padded_point(option, text)?;
    same_dim(option, d, curve.curve.dim)?;
    if curve.rational {
        curve
            .curve
            .with(rational(&curve.curve.value, point)?)
            .json()
    } else {
        curve.curve.with(plain(&curve.polynomial(), point)?).json()
    }
}

fn make_json(shape: &Shape) -> Result<Json> {
    Ok(match shape {
        Shape::Skin(a) => crate::surfaces::make_skin(&a.curves, a.degree)?,
        Shape::Sweep(a) => crate::surfaces::make_sweep(&a.profile, &a.path, a.sections)?,
        Shape::Coons(a) => crate::surfaces::make_coons(&a.curves)?,
        Shape::Gordon(a) => {
            crate::surfaces::make_gordon(&a.u_curves, &a.v_curves, a.degree, a.tolerance)?
        }
        Shape::Circle(a) => {
            let (frame, dim) = circle_frame(&a.on.center, a.on.normal.as_deref())?;
            let circle = NurbsCurve::circle(&frame, a.on.radius, construction(a.construction))?;
            Sized { value: circle, dim }.json()?
        }
        Shape::Arc(a) => {
            let (frame, dim) = circle_frame(&a.on.center, a.on.normal.as_deref())?;
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
                ))
                .with_value(a.max_piece));
            }
            let arc = NurbsCurve::arc_with_max_piece(
                &frame,
                a.on.radius,
                a.start.to_radians(),
                a.sweep.to_radians(),
                a.max_piece.to_radians(),
            )?;
            Sized { value: arc, dim }.json()?
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
            Sized {
                value: arc,
                dim: d0,
            }
            .json()?
        }
        Shape::Extrude(a) => curve_and_point(
            &a.curve,
            ("--vector", &a.vector),
            NurbsSurface::extrusion,
            Surface::extrusion,
        )?,
        Shape::Ruled(a) => {
            let c1 = read_curve(&a.first)?;
            let c2 = read_curve(&a.second)?;
            let (d1, d2) = (c1.curve.dim, c2.curve.dim);
            if d1 != d2 {
                return Err(Error::new(
                    ErrorKind::DimensionMismatch,
                    format!("the curves have {d1} and {d2} coordinates"),
                ));
            }
            if c1.rational || c2.rational {
                let s = NurbsSurface::ruled(&c1.curve.value, &c2.curve.value)?;
                c1.curve.with(s).json()?
            } else {
                let s = Surface::ruled(&c1.polynomial(), &c2.polynomial())?;
                c1.curve.with(s).json()?
            }
        }
        Shape::Cone(a) => curve_and_point(
            &a.curve,
            ("--apex", &a.apex),
            NurbsSurface::cone,
            Surface::cone,
        )?,
        Shape::Revolve(a) => {
            let profile = read_curve(&a.profile)?;
            let dim = profile.curve.dim;
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
            let profile: NurbsCurve<f64, 3> = profile
                .curve
                .value
                .map_control_points(|p| Vector3::new(p[0], p[1], p[2]));
            let surface = NurbsSurface::revolution(&profile, &axis, a.angle.to_radians())?;
            io::raw(&SurfaceRecord::from_nurbs_surface(&surface))?
        }
        Shape::Sphere(a) => {
            let c = point::<3>("--center", &a.center)?;
            let axis = point::<3>("--axis", &a.axis)?;
            io::raw(&SurfaceRecord::from_nurbs_surface(
                &NurbsSurface::sphere_about(c, a.radius, axis)?,
            ))?
        }
        Shape::Torus(a) => {
            let c = point::<3>("--center", &a.center)?;
            let axis = point::<3>("--axis", &a.axis)?;
            io::raw(&SurfaceRecord::from_nurbs_surface(&NurbsSurface::torus(
                c, axis, a.major, a.minor,
            )?))?
        }
    })
}

/// `spline make ...`: prints the constructed object as JSON.
pub fn make(args: &MakeArgs) -> Result<()> {
    io::write_stdout(make_json(&args.shape)?.get().as_bytes())
}
