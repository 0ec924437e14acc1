//! `spline surface-features`: the parabolic lines of a surface of either kind
//! ([`spline_algebra::parabolic_lines`]), as polylines in `(u, v)` and in space, and its
//! umbilics ([`spline_algebra::umbilics`]).

use crate::io;
use crate::objects::{read_object, surface3};
use clap::Args;
use serde_json::{Value, json};
use spline_algebra::ZeroSet;
use spline_core::Result;
use spline_geom::NurbsSurface;

/// Curves of curvature features of a surface.
#[derive(Args)]
pub struct SurfaceFeaturesArgs {
    /// Surface file (JSON: a B-spline or NURBS surface with 3 coordinates), or - for
    /// standard input.
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
/// "umbilics": [{"uv", "point"}], "umbilics_isolated": bool}`.
pub fn surface_features(args: &SurfaceFeaturesArgs) -> Result<()> {
    let surface = surface3(
        &read_object(&args.surface)?,
        &args.surface,
        "surface-features",
    )?;
    let set = spline_algebra::parabolic_lines(&surface, args.samples)
        .map_err(|e| e.context(&args.surface))?;
    let umbilics = spline_algebra::umbilics(&surface).map_err(|e| e.context(&args.surface))?;
    let points = umbilics
        .points
        .iter()
        .map(|p| {
            let x = surface.eval(p[0], p[1])?;
            Ok(json!({"uv": p, "point": [x.x, x.y, x.z]}))
        })
        .collect::<Result<Vec<_>>>()?;
    io::print_json(&json!({
        "parabolic_lines": polylines(&surface, &set)?,
        "parabolic_regions": set.regions,
        "singular_points": set.singular,
        "umbilics": points,
        "umbilics_isolated": !umbilics.not_isolated,
    }))
}
