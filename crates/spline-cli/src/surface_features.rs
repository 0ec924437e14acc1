//! `spline surface-features`: the parabolic lines of a surface of either kind
//! ([`spline_algebra::parabolic_lines`]), as polylines in `(u, v)` and in space, and its
//! umbilics ([`spline_algebra::umbilics`]).

use crate::io::{self, Pt};
use crate::objects::{Object, read_object};
use clap::Args;
use nalgebra::Vector3;
use serde_json::{Value, json};
use spline_algebra::ZeroSet;
use spline_core::{Error, ErrorKind, Result};
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

/// Reads a 3-D surface of either kind as a NURBS surface.
pub fn read_surface3(path: &str, what: &str) -> Result<NurbsSurface<f64, 3>> {
    let to3 = |p: &Pt| Vector3::new(p[0], p[1], p[2]);
    let (dim, surface) = match read_object(path)? {
        Object::Surface(s) => (
            s.dim,
            NurbsSurface::from_surface(&s.value.map_control_points(to3)),
        ),
        Object::NurbsSurface(s) => (s.dim, s.value.map_control_points(to3)),
        Object::Curve(_) | Object::Nurbs(_) => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "{path}: {what} needs a surface (degree [p, q]); use `spline features` for curves"
                ),
            ));
        }
    };
    if dim != 3 {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("{path}: {what} needs a surface in 3-D space, got {dim} coordinates"),
        ));
    }
    Ok(surface)
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
    let surface = read_surface3(&args.surface, "surface-features")?;
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
