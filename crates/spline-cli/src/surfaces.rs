//! Surfaces as people use them: `closest`, the surface cases of `intersect`, `make skin |
//! sweep | coons | gordon` and `approximate-surface`. Parse → library → print.

use crate::io::{self, Json, Pt};
use crate::objects::{AnyCurve, Curve, Object, Sized, read_curve, read_object};
use clap::Args;
use nalgebra::Vector3;
use serde_json::json;
use spline_core::{Error, ErrorKind, Result};
use spline_fit::{
    CurveSurfaceEvent, ScatteredOptions, SurfaceProjector, Tolerances, closest_point,
    fit_scattered, gordon, intersect_curve_surface_with_overlaps, intersect_surfaces_as_splines,
    skin, skin_rational, sweep,
};
use spline_geom::{NurbsCurve, NurbsSurface, ParamCurve, ParamSurface, Surface};

fn invalid(message: impl Into<String>) -> Error {
    Error::new(ErrorKind::InvalidArgument, message)
}

/// `spline closest OBJECT --points JSON`.
#[derive(Args)]
pub struct ClosestArgs {
    /// The curve or surface (JSON file, `-` for stdin).
    object: String,
    /// The points to project, as JSON: `[[x, y, z], ...]`.
    #[arg(long)]
    points: String,
}

/// The points of `--points`, padded, checked against the object's dimension.
fn query_points(text: &str, dim: usize) -> Result<Vec<Pt>> {
    let rows: Vec<Vec<f64>> = io::parse_arg("--points", text)?;
    rows.iter()
        .enumerate()
        .map(|(k, r)| {
            if r.len() != dim {
                return Err(Error::new(
                    ErrorKind::DimensionMismatch,
                    format!(
                        "--points entry {k}: {} coordinates for an object with {dim}",
                        r.len()
                    ),
                ));
            }
            io::pad(r).map_err(|e| e.context(format_args!("--points entry {k}")))
        })
        .collect()
}

/// Prints `[{"u"[, "v"], "point", "distance"}]` for each point.
///
/// # Errors
/// Unreadable objects, bad points, non-finite coordinates.
pub fn closest(args: &ClosestArgs) -> Result<()> {
    let object = read_object(&args.object)?;
    let out: Vec<serde_json::Value> = match &object {
        Object::Curve(c) => curve_hits(&c.value, c.dim, &args.points)?,
        Object::Nurbs(c) => curve_hits(&c.value, c.dim, &args.points)?,
        Object::Surface(s) => surface_hits(&s.value, s.dim, &args.points)?,
        Object::NurbsSurface(s) => surface_hits(&s.value, s.dim, &args.points)?,
    };
    io::print_json(&out)
}

fn curve_hits<C: ParamCurve<f64, Point = Pt>>(
    c: &C,
    dim: usize,
    text: &str,
) -> Result<Vec<serde_json::Value>> {
    query_points(text, dim)?
        .into_iter()
        .enumerate()
        .map(|(k, q)| {
            let hit = closest_point(c, q).map_err(|e| e.context(format_args!("point {k}")))?;
            Ok(json!({"u": hit.param, "point": io::unpad(&hit.point, dim), "distance": hit.distance}))
        })
        .collect()
}

fn surface_hits<S: ParamSurface<f64, Point = Pt>>(
    s: &S,
    dim: usize,
    text: &str,
) -> Result<Vec<serde_json::Value>> {
    let points = query_points(text, dim)?;
    let projector = SurfaceProjector::new(s)?;
    projector
        .closest_many(&points)?
        .into_iter()
        .map(|h| Ok(json!({"u": h.u, "v": h.v, "point": io::unpad(&h.point, dim), "distance": h.distance})))
        .collect()
}

/// `spline intersect A [B] [--tolerance T]`.
#[derive(Args)]
pub struct IntersectArgs {
    /// The first object (curve or surface).
    a: String,
    /// The second object (curve or surface); curves alone ask for self-intersections.
    b: Option<String>,
    /// Surface–surface: how far the traced polylines may stray from the true curves
    /// (default 1e-4 of the objects' size); curve–curve: the distance under which the
    /// curves touch (default 1e-9).
    #[arg(long)]
    tolerance: Option<f64>,
}

/// A surface in space for the intersection algorithms.
enum Spatial {
    Plain(Surface<f64, Vector3<f64>>),
    Rational(NurbsSurface<f64, 3>),
}

fn spatial_surface(object: &Object, path: &str) -> Result<Option<Spatial>> {
    let to3 = |p: &Pt| Vector3::new(p[0], p[1], p[2]);
    Ok(match object {
        Object::Surface(s) => {
            crate::objects::check_dim(s.dim, 3, "a surface in space")
                .map_err(|e| e.context(path))?;
            Some(Spatial::Plain(s.value.map_control_points(to3)))
        }
        Object::NurbsSurface(s) => {
            crate::objects::check_dim(s.dim, 3, "a surface in space")
                .map_err(|e| e.context(path))?;
            Some(Spatial::Rational(
                s.value.map_control_points::<3>(|p| to3(p)),
            ))
        }
        _ => None,
    })
}

/// Dispatches on the kinds of the objects: curve–surface (either order) and
/// surface–surface here; curve–curve and self-intersections (no surface) go to
/// [`crate::curves::intersect_curve_objects`].
///
/// # Errors
/// Unreadable objects, objects not in space, bad tolerances.
pub fn intersect(args: &IntersectArgs) -> Result<()> {
    let a = read_object(&args.a)?;
    let Some(path_b) = &args.b else {
        // One curve: its self-intersections.
        return crate::curves::intersect_curve_objects((a, &args.a), None, args.tolerance);
    };
    let b = read_object(path_b)?;
    if let Some(t) = args.tolerance {
        if !(t > 0.0 && t.is_finite()) {
            return Err(Error::invalid_tolerance(
                "--tolerance",
                "positive and finite",
                t,
            ));
        }
    }
    let tolerances = Tolerances {
        trace: args.tolerance,
        ..Tolerances::default()
    };
    let sa = spatial_surface(&a, &args.a)?;
    let sb = spatial_surface(&b, path_b)?;
    let out = match (sa, sb) {
        (Some(x), Some(y)) => surface_surface(&x, &y, &tolerances)?,
        (Some(s), None) => curve_surface(&b, path_b, &s, &tolerances)?,
        (None, Some(s)) => curve_surface(&a, &args.a, &s, &tolerances)?,
        (None, None) => {
            return crate::curves::intersect_curve_objects(
                (a, &args.a),
                Some((b, path_b)),
                args.tolerance,
            );
        }
    };
    io::print_json(&out)
}

fn curve_surface(
    curve: &Object,
    path: &str,
    s: &Spatial,
    t: &Tolerances<f64>,
) -> Result<serde_json::Value> {
    let c = match curve {
        Object::Curve(c) => c.with(NurbsCurve::from_bspline(&c.value)),
        Object::Nurbs(c) => c.clone(),
        _ => unreachable!("surfaces are handled by the caller"),
    };
    crate::objects::check_dim(c.dim, 3, "a curve in space").map_err(|e| e.context(path))?;
    let c3: NurbsCurve<f64, 3> = c
        .value
        .map_control_points::<3>(|p| Vector3::new(p[0], p[1], p[2]));
    let found = match s {
        Spatial::Plain(s) => intersect_curve_surface_with_overlaps(&c3, s, t)?,
        Spatial::Rational(s) => intersect_curve_surface_with_overlaps(&c3, s, t)?,
    };
    // Points and arcs of the curve in the surface, in the library's order.
    let events = found.events().into_iter().map(|event| match event {
        CurveSurfaceEvent::Point(h) => json!({"t": h.t, "u": h.u, "v": h.v,
            "point": [h.point.x, h.point.y, h.point.z], "tangential": h.tangential}),
        CurveSurfaceEvent::Overlap(o) => {
            let (p, q) = o.points;
            let ((u0, v0), (u1, v1)) = o.uv;
            json!({"overlap": true, "t": [o.t.0, o.t.1], "uv": [[u0, v0], [u1, v1]],
                   "points": [[p.x, p.y, p.z], [q.x, q.y, q.z]]})
        }
    });
    Ok(events.collect())
}

fn surface_surface(a: &Spatial, b: &Spatial, t: &Tolerances<f64>) -> Result<serde_json::Value> {
    let found = match (a, b) {
        (Spatial::Plain(x), Spatial::Plain(y)) => intersect_surfaces_as_splines(x, y, t)?,
        (Spatial::Plain(x), Spatial::Rational(y)) => intersect_surfaces_as_splines(x, y, t)?,
        (Spatial::Rational(x), Spatial::Plain(y)) => intersect_surfaces_as_splines(x, y, t)?,
        (Spatial::Rational(x), Spatial::Rational(y)) => intersect_surfaces_as_splines(x, y, t)?,
    };
    let pairs = |v: &[(f64, f64)]| v.iter().map(|&(u, w)| [u, w]).collect::<Vec<_>>();
    let pad3 = |q: &Vector3<f64>| io::pad(q.as_slice()).expect("3 coordinates");
    let pad2 = |q: &nalgebra::Vector2<f64>| io::pad(q.as_slice()).expect("2 coordinates");
    found
        .iter()
        .map(|found| {
            let c = &found.traced;
            let pieces = found
                .pieces
                .iter()
                .map(|piece| {
                    Ok(json!({
                        "curve": Sized { value: piece.curve.map_control_points(pad3), dim: 3 }.json()?,
                        "pcurve_a": Sized { value: piece.pcurve_a.map_control_points(pad2), dim: 2 }.json()?,
                        "pcurve_b": Sized { value: piece.pcurve_b.map_control_points(pad2), dim: 2 }.json()?,
                        "max_error": piece.max_error,
                    }))
                })
                .collect::<Result<Vec<_>>>()?;
            Ok(json!({
                "points": c.points.iter().map(|p| [p.x, p.y, p.z]).collect::<Vec<_>>(),
                "uv_a": pairs(&c.uv_a),
                "uv_b": pairs(&c.uv_b),
                "closed": c.closed,
                "pieces": pieces,
            }))
        })
        .collect::<Result<Vec<_>>>()
        .map(serde_json::Value::Array)
}

/// The curves of these files, all of the first one's dimension (and polynomial when
/// `require_polynomial`: for the constructions that combine control points linearly).
fn curves_of_one_dimension(
    paths: &[String],
    what: &str,
    require_polynomial: bool,
) -> Result<(Vec<AnyCurve>, usize)> {
    let curves: Vec<AnyCurve> = paths.iter().map(|p| read_curve(p)).collect::<Result<_>>()?;
    let dim = curves.first().map_or(0, |c| c.curve.dim);
    for (c, path) in curves.iter().zip(paths) {
        if c.curve.dim != dim {
            return Err(Error::new(
                ErrorKind::DimensionMismatch,
                format!(
                    "{path}: {} coordinates, the first {what} has {dim}",
                    c.curve.dim
                ),
            ));
        }
        if require_polynomial && c.rational {
            return Err(Error::new(
                ErrorKind::Unsupported,
                format!("{path}: a rational curve; {what}s must be B-spline curves"),
            ));
        }
    }
    Ok((curves, dim))
}

/// Curves of the same dimension, all polynomial (for the constructions that combine
/// control points linearly).
fn polynomial_curves(paths: &[String], what: &str) -> Result<(Vec<Curve>, usize)> {
    let (curves, dim) = curves_of_one_dimension(paths, what, true)?;
    Ok((curves.iter().map(AnyCurve::polynomial).collect(), dim))
}

/// `make skin`: the surface through sections (B-spline or NURBS; all of one kind).
///
/// # Errors
/// As [`spline_fit::skin`]; mixed kinds or dimensions.
pub fn make_skin(paths: &[String], degree: usize) -> Result<Json> {
    if paths.len() < 2 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "--curves: skinning needs at least two sections, got {}",
                paths.len()
            ),
        ));
    }
    let (curves, dim) = curves_of_one_dimension(paths, "section", false)?;
    let (surface, params) = if curves.iter().any(|c| c.rational) {
        let sections: Vec<_> = curves.iter().map(|c| c.curve.value.clone()).collect();
        let skinned = skin_rational(&sections, degree, None)?;
        let record = Sized {
            value: skinned.surface,
            dim,
        }
        .json()?;
        (record, skinned.params)
    } else {
        let sections: Vec<Curve> = curves.iter().map(AnyCurve::polynomial).collect();
        let skinned = skin(&sections, degree, None)?;
        let record = Sized {
            value: skinned.surface,
            dim,
        }
        .json()?;
        (record, skinned.params)
    };
    io::raw(&json!({"surface": surface, "params": params}))
}

/// `make coons`: the Coons patch of four curves (bottom, top, left, right): a B-spline
/// surface of B-spline curves, a NURBS surface when any curve is rational.
///
/// # Errors
/// As [`Surface::coons`] and [`NurbsSurface::coons`]; not four curves, or curves of
/// different dimensions.
pub fn make_coons(paths: &[String]) -> Result<Json> {
    if paths.len() != 4 {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "--curves: a Coons patch needs four curves (bottom, top, left, right), got {}",
                paths.len()
            ),
        )
        .with_counts(4, paths.len()));
    }
    let (curves, dim) = curves_of_one_dimension(paths, "boundary curve", false)?;
    if !curves.iter().any(|c| c.rational) {
        let c: Vec<Curve> = curves.iter().map(AnyCurve::polynomial).collect();
        return Sized {
            value: Surface::coons(&c[0], &c[1], &c[2], &c[3])?,
            dim,
        }
        .json();
    }
    let c: Vec<_> = curves.iter().map(|c| &c.curve.value).collect();
    Sized {
        value: NurbsSurface::coons(c[0], c[1], c[2], c[3])?,
        dim,
    }
    .json()
}

/// `make gordon`: the Gordon surface of a curve network.
///
/// # Errors
/// As [`spline_fit::gordon`].
pub fn make_gordon(
    u_paths: &[String],
    v_paths: &[String],
    degree: usize,
    tolerance: f64,
) -> Result<Json> {
    let (us, dim) = polynomial_curves(u_paths, "u-curve")?;
    let (vs, dv) = polynomial_curves(v_paths, "v-curve")?;
    if dim != dv {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("the u-curves have {dim} coordinates, the v-curves {dv}"),
        ));
    }
    let network = gordon(&us, &vs, (degree, degree), tolerance)?;
    let surface = Sized {
        value: network.surface,
        dim,
    }
    .json()?;
    io::raw(&json!({
        "surface": surface,
        "params_u": network.params_u,
        "params_v": network.params_v,
        "crossing_gap": network.crossing_gap,
    }))
}

/// `make sweep`: a B-spline profile swept along a path (B-spline or NURBS) in space.
///
/// # Errors
/// As [`spline_fit::sweep`]; curves not in space.
pub fn make_sweep(profile: &str, path: &str, sections: usize) -> Result<Json> {
    let (p, dim) = polynomial_curves(&[profile.to_string()], "profile")?;
    crate::objects::check_dim(dim, 3, "a profile in space").map_err(|e| e.context(profile))?;
    let along = read_curve(path)?;
    crate::objects::check_dim(along.curve.dim, 3, "a path in space")
        .map_err(|e| e.context(path))?;
    let to3 = |q: &Pt| Vector3::new(q[0], q[1], q[2]);
    let prof = p[0].map_control_points(to3);
    let path3: NurbsCurve<f64, 3> = along.curve.value.map_control_points::<3>(|q| to3(q));
    let s = sweep(&prof, &path3, sections, None)?;
    let surface = Sized {
        value: s
            .surface
            .map_control_points(|q| io::pad(q.as_slice()).expect("3 coordinates")),
        dim: 3,
    }
    .json()?;
    io::raw(&json!({"surface": surface, "params": s.params}))
}

/// `spline approximate-surface POINTS --control-points '[m, n]' ...`.
#[derive(Args)]
pub struct ApproximateSurfaceArgs {
    /// Points in space (JSON array or text, one point per line) or a triangle mesh (`.obj`:
    /// `v x y z` and `f i j k` lines, read by `spline_io::obj::read_obj`).
    points: String,
    /// Control points in u and v, as JSON: `[m, n]`.
    #[arg(long)]
    control_points: String,
    /// Degrees in u and v, as JSON (default `[3, 3]`).
    #[arg(long)]
    degree: Option<String>,
    /// Parameter-correction sweeps (default 5).
    #[arg(long, default_value_t = 5)]
    correct_parameters: usize,
    /// The weight of the thin-plate smoothing term (default 0).
    #[arg(long, default_value_t = 0.0)]
    smoothing: f64,
}

/// Prints `{"surface", "max_deviation", "rms", "max_deviation_to_data", "corrections"}`.
///
/// # Errors
/// As [`spline_fit::fit_scattered`]; unreadable or malformed inputs.
pub fn approximate_surface(args: &ApproximateSurfaceArgs) -> Result<()> {
    let [nu, nv]: [usize; 2] = io::parse_arg("--control-points", &args.control_points)?;
    let [p, q]: [usize; 2] = match &args.degree {
        Some(text) => io::parse_arg("--degree", text)?,
        None => [3, 3],
    };
    let (points, triangles) = if args.points.to_ascii_lowercase().ends_with(".obj") {
        let mesh = spline_io::obj::read_obj(&io::read_text(&args.points)?)
            .map_err(|e| e.context(&args.points))?;
        (mesh.vertices, Some(mesh.triangles))
    } else {
        let rows = io::read_points(&args.points)?;
        let points = rows
            .iter()
            .enumerate()
            .map(|(k, r)| {
                if r.len() == 3 {
                    Ok(Vector3::new(r[0], r[1], r[2]))
                } else {
                    Err(Error::new(
                        ErrorKind::DimensionMismatch,
                        format!(
                            "{}: point {k} has {} coordinates, expected 3",
                            args.points,
                            r.len()
                        ),
                    ))
                }
            })
            .collect::<Result<Vec<_>>>()?;
        (points, None)
    };
    let options = ScatteredOptions {
        degrees: (p, q),
        control_points: (nu, nv),
        smoothing: args.smoothing,
        corrections: args.correct_parameters,
    };
    if !(args.smoothing >= 0.0 && args.smoothing.is_finite()) {
        return Err(invalid(format!(
            "--smoothing must be finite and non-negative, got {}",
            args.smoothing
        ))
        .with_value(args.smoothing)
        .with_interval(0.0, f64::INFINITY));
    }
    let none: Option<&Surface<f64, Vector3<f64>>> = None;
    let fit = fit_scattered(&points, triangles.as_deref(), none, &options)?;
    let surface = Sized {
        value: fit
            .surface
            .map_control_points(|q| io::pad(q.as_slice()).expect("3 coordinates")),
        dim: 3,
    }
    .json()?;
    io::print_json(&json!({
        "surface": surface,
        "max_deviation": fit.to_surface.max,
        "rms": fit.to_surface.rms,
        "max_deviation_to_data": fit.to_data,
        "corrections": fit.corrections,
    }))
}
