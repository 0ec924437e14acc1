//! `spline surface-features`: the parabolic lines of a surface of either kind
//! ([`spline_algebra::parabolic_lines`]), as polylines in `(u, v)` and in space, its
//! umbilics ([`spline_algebra::umbilics`], those at poles flagged) and its red and blue
//! ridges ([`spline_algebra::surface_ridges`]); for functions `s(u, v)` the parabolic lines
//! and the red and blue ridges of the graph (thesis §5.7, [`spline_algebra::ridges`]).

use crate::io;
use crate::objects::{Object, read_object, surface3};
use clap::Args;
use serde_json::{Value, json};
use spline_algebra::{FunctionFeatures, LiftedPolyline, on_graph, on_surface};
use spline_core::Result;
use spline_geom::Surface;

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

/// Lifted polylines as `{"uv", "points"}` (and the colour of a ridge).
fn polylines(lines: &[LiftedPolyline], colour: Option<&str>) -> Vec<Value> {
    lines
        .iter()
        .map(|line| {
            let points: Vec<[f64; 3]> = line.points.iter().map(|p| [p.x, p.y, p.z]).collect();
            match colour {
                Some(colour) => json!({"colour": colour, "uv": line.uv, "points": points}),
                None => json!({"uv": line.uv, "points": points}),
            }
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
    let mut points = Vec::new();
    for (uvs, on_line) in [(&umbilics.points, false), (&umbilics.poles, true)] {
        for line in on_surface(&surface, std::slice::from_ref(uvs))? {
            for (p, x) in line.uv.iter().zip(&line.points) {
                points.push(json!({"uv": p, "point": [x.x, x.y, x.z], "singular_line": on_line}));
            }
        }
    }
    let mut coloured = polylines(&on_surface(&surface, &ridges.red)?, Some("red"));
    coloured.extend(polylines(
        &on_surface(&surface, &ridges.blue)?,
        Some("blue"),
    ));
    let constant: Vec<Value> = [
        ("red", &ridges.red_constant),
        ("blue", &ridges.blue_constant),
    ]
    .into_iter()
    .flat_map(|(colour, regions)| {
        regions
            .iter()
            .map(move |r| json!({"colour": colour, "uv": r}))
    })
    .collect();
    io::print_json(&json!({
        "parabolic_lines": polylines(&on_surface(&surface, &set.curves)?, None),
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
    let FunctionFeatures {
        parabolic_lines: set,
        ridges,
    } = spline_algebra::function_features(s, args.samples).map_err(|e| e.context(&args.surface))?;
    let mut coloured = polylines(&on_graph(s, &ridges.red)?, Some("red"));
    coloured.extend(polylines(&on_graph(s, &ridges.blue)?, Some("blue")));
    io::print_json(&json!({
        "parabolic_lines": polylines(&on_graph(s, &set.curves)?, None),
        "parabolic_regions": set.regions,
        "singular_points": set.singular,
        "ridges": coloured,
        "ridge_singular_points": ridges.singular,
    }))
}
