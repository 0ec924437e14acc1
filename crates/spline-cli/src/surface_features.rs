//! `spline surface-features`: the parabolic lines of a surface of either kind
//! ([`spline_algebra::parabolic_lines`]), as polylines in `(u, v)` and in space, its
//! umbilics ([`spline_algebra::umbilics`], those at poles flagged) and its red and blue
//! ridges ([`spline_algebra::surface_ridges`]); for functions `s(u, v)` the parabolic lines
//! and the red and blue ridges of the graph (thesis §5.7, [`spline_algebra::ridges`]).

use crate::io;
use crate::objects::{Object, read_object, surface3};
use clap::Args;
use serde_json::{Value, json};
use spline_algebra::ZeroSet;
use spline_core::Result;
use spline_geom::{NurbsSurface, Surface};

/// Curves of curvature features of a surface.
#[derive(Args)]
pub struct SurfaceFeaturesArgs {
    /// Surface file (JSON: a B-spline or NURBS surface with 3 coordinates, or a B-spline
    /// function s(u, v) with 1, taken as its graph), or - for standard input.
    surface: String,
    /// Points per patch width on each polyline (drawing resolution only: the topology is
    /// decided by the Bernstein coefficients, every vertex is on the curve to rounding).
    #[arg(long, default_value_t = 8)]
    samples: usize,
}

/// The polylines of a zero set in `(u, v)` and on the surface.
pub fn polylines(surface: &NurbsSurface<f64, 3>, set: &ZeroSet) -> Result<Vec<Value>> {
    set.curves
        .iter()
        .map(|uv| {
            let points = uv
                .iter()
                .map(|p| surface.eval(p[0], p[1]).map(|x| [x.x, x.y, x.z]))
                .collect::<Result<Vec<_>>>()?;
            Ok(json!({"uv": uv, "points": points}))
        })
        .collect()
}

/// `spline surface-features SURFACE [--samples N]`: prints `{"parabolic_lines": [{"uv",
/// "points"}], "parabolic_regions": [[[u0, v0], [u1, v1]]], "singular_points": [[u, v]],
/// "umbilics": [{"uv", "point", "singular_line"}], "umbilics_isolated": bool, "ridges":
/// [{"colour", "uv", "points"}], "ridge_singular_points": [[u, v]],
/// "ridge_constant_regions": [{"colour", "uv": [[u0, v0], [u1, v1]]}]}`.
pub fn surface_features(args: &SurfaceFeaturesArgs) -> Result<()> {
    let object = read_object(&args.surface)?;
    if let Object::Surface(f) = &object {
        if f.dim == 1 {
            return function_features(&f.value.map_control_points(|p| p[0]), args);
        }
    }
    let surface = surface3(&object, &args.surface, "surface-features")?;
    let spline_algebra::SurfaceFeatures {
        parabolic_lines: set,
        umbilics,
        ridges,
    } = spline_algebra::surface_features(&surface, args.samples)
        .map_err(|e| e.context(&args.surface))?;
    let pole = |p: &[f64; 2], on_line: bool| -> Result<Value> {
        let x = surface.eval(p[0], p[1])?;
        Ok(json!({"uv": p, "point": [x.x, x.y, x.z], "singular_line": on_line}))
    };
    let mut points = Vec::new();
    for p in &umbilics.points {
        points.push(pole(p, false)?);
    }
    for p in &umbilics.poles {
        points.push(pole(p, true)?);
    }
    let mut coloured = Vec::new();
    let mut constant = Vec::new();
    for (colour, lines, regions) in [
        ("red", &ridges.red, &ridges.red_constant),
        ("blue", &ridges.blue, &ridges.blue_constant),
    ] {
        let set = ZeroSet {
            curves: lines.clone(),
            ..ZeroSet::default()
        };
        for mut line in polylines(&surface, &set)? {
            line["colour"] = json!(colour);
            coloured.push(line);
        }
        for r in regions {
            constant.push(json!({"colour": colour, "uv": r}));
        }
    }
    io::print_json(&json!({
        "parabolic_lines": polylines(&surface, &set)?,
        "parabolic_regions": set.regions,
        "singular_points": set.singular,
        "umbilics": points,
        "umbilics_isolated": !umbilics.not_isolated,
        "ridges": coloured,
        "ridge_singular_points": ridges.singular,
        "ridge_constant_regions": constant,
    }))
}

/// A function `s(u, v)` (a surface with one coordinate), as the graph `(u, v, s)`: its
/// parabolic lines are the zeros of the Hessian determinant `s_uu s_vv − s_uv²` (whose sign
/// is the sign of K), its ridges those of thesis §5.7 ([`spline_algebra::ridges`]).
fn function_features(s: &Surface<f64, f64>, args: &SurfaceFeaturesArgs) -> Result<()> {
    let context = |e: spline_core::Error| e.context(&args.surface);
    let graph = |uv: &[[f64; 2]]| -> Result<Value> {
        let points = uv
            .iter()
            .map(|p| s.eval(p[0], p[1]).map(|z| [p[0], p[1], z]))
            .collect::<Result<Vec<_>>>()?;
        Ok(json!({"uv": uv, "points": points}))
    };
    let det = spline_algebra::hessian_determinant(s).map_err(context)?;
    let set = spline_algebra::zero_set(&det.value, args.samples).map_err(context)?;
    let ridges = spline_algebra::ridges(s, args.samples).map_err(context)?;
    let mut coloured = Vec::new();
    for (colour, lines) in [("red", &ridges.red), ("blue", &ridges.blue)] {
        for line in lines {
            let mut value = graph(line)?;
            value["colour"] = json!(colour);
            coloured.push(value);
        }
    }
    io::print_json(&json!({
        "parabolic_lines": set.curves.iter().map(|c| graph(c)).collect::<Result<Vec<_>>>()?,
        "parabolic_regions": set.regions,
        "singular_points": set.singular,
        "ridges": coloured,
        "ridge_singular_points": ridges.singular,
    }))
}
