//! The picture and curve-geometry subcommands: `plot`, `curvature`, `features`, for planar
//! curves of every kind ([`PlanarCurve`], [`CurveFeatures`]) and, for `features`, 3-D
//! curves ([`SpaceCurveFeatures`]).

use crate::io;
use crate::objects::{Object, check_dim, read_object};
use crate::structural::ObjectArgs;
use clap::Args;
use nalgebra::{Vector2, Vector3};
use serde_json::json;
use spline_algebra::{
    CurveFeatures, PlanarFeatures, SpaceCurveFeatures, SpaceFeatures, default_feature_accuracy,
};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::{BSpline, NurbsCurve, ParamCurve, PlanarCurve};
use spline_io::svg::SvgPlot;

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

#[derive(Args)]
pub struct CurvatureArgs {
    /// A planar curve (JSON; B-spline or NURBS), or - for standard input.
    object: String,
    /// Parameters as a JSON array.
    #[arg(long)]
    at: String,
}

/// A planar curve of either kind.
pub enum Planar {
    /// A B-spline curve.
    Polynomial(BSpline<f64, Vector2<f64>>),
    /// A NURBS curve.
    Rational(NurbsCurve<f64, 2>),
}

/// Reads a planar curve; `what` says what needs it, for messages.
pub fn read_planar(path: &str, what: &str) -> Result<Planar> {
    planar_of(read_object(path)?, path, what)
}

/// The planar curve in an object read from `path`.
pub fn planar_of(object: Object, path: &str, what: &str) -> Result<Planar> {
    let planar = |p: &crate::io::Pt| Vector2::new(p[0], p[1]);
    let dimension = |dim| check_dim(dim, 2, "a planar curve").map_err(|e| e.context(path));
    match object {
        Object::Curve(c) => {
            dimension(c.dim)?;
            Ok(Planar::Polynomial(c.value.map_control_points(planar)))
        }
        Object::Nurbs(c) => {
            dimension(c.dim)?;
            Ok(Planar::Rational(c.value.map_control_points(planar)))
        }
        Object::Surface(_) | Object::NurbsSurface(_) => Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{path}: {what} needs a planar curve, got a surface; use `spline mesh` for surfaces"
            ),
        )
        .with_file(path)),
    }
}

/// Inflections and curvature extrema, located to the library's default accuracy.
fn features_of<C: PlanarCurve<f64> + CurveFeatures<f64>>(curve: &C) -> Result<PlanarFeatures<f64>> {
    curve.features(default_feature_accuracy(curve.domain()))
}

fn draw<C: PlanarCurve<f64> + CurveFeatures<f64>>(
    svg: &mut SvgPlot,
    curve: &C,
    args: &PlotArgs,
) -> Result<()> {
    svg.add_curve(curve);
    if args.comb {
        svg.add_curvature_comb(curve, 200);
    }
    if args.features {
        let features = features_of(curve)?;
        svg.add_markers(&curve.eval_many(&features.inflections)?, "inflection");
        svg.add_markers(&curve.eval_many(&features.curvature_extrema)?, "extremum");
    }
    Ok(())
}

pub fn plot(args: &PlotArgs) -> Result<()> {
    let file = io::create_file(&args.output)?;
    let mut svg = SvgPlot::new();
    for path in &args.objects {
        match read_planar(path, "plot")? {
            Planar::Polynomial(c) => draw(&mut svg, &c, args),
            Planar::Rational(c) => draw(&mut svg, &c, args),
        }
        .map_err(|e| e.context(path))?;
    }
    io::write_file(file, &args.output, svg.render().as_bytes())
}

fn curvatures<C: PlanarCurve<f64>>(curve: &C, params: &[f64]) -> Result<Vec<f64>> {
    params
        .iter()
        .enumerate()
        .map(|(i, &u)| {
            curve
                .signed_curvature(u)
                .map_err(|e| e.context(format_args!("--at entry {i}")))
        })
        .collect()
}

pub fn curvature(args: &CurvatureArgs) -> Result<()> {
    let params: Vec<f64> = io::parse_arg("--at", &args.at)?;
    let values = match read_planar(&args.object, "curvature")? {
        Planar::Polynomial(c) => curvatures(&c, &params)?,
        Planar::Rational(c) => curvatures(&c, &params)?,
    };
    io::print_json(&values)
}

pub fn features(args: &ObjectArgs) -> Result<()> {
    let path = &args.object;
    let object = read_object(path)?;
    let dim = match &object {
        Object::Curve(c) => c.dim,
        Object::Nurbs(c) => c.dim,
        Object::Surface(_) | Object::NurbsSurface(_) => {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "{path}: features needs a planar or 3-D curve, got a surface; use `spline surface-features` for surfaces"
                ),
            )
            .with_file(path));
        }
    };
    if dim == 3 {
        let spatial = |p: &crate::io::Pt| Vector3::new(p[0], p[1], p[2]);
        let features = match object {
            Object::Curve(c) => space_features_of(&c.value.map_control_points(spatial)),
            Object::Nurbs(c) => space_features_of(&c.value.map_control_points(spatial)),
            _ => unreachable!("surfaces are refused above"),
        }
        .map_err(|e| e.context(path))?;
        let mut out = json!({
            "curvature_extrema": features.curvature_extrema,
            "torsion_zeros": features.torsion_zeros,
        });
        if let Some(k) = features.constant_curvature {
            out["constant_curvature"] = json!(k);
        }
        if let Some(t) = features.constant_torsion {
            out["constant_torsion"] = json!(t);
        }
        return io::print_json(&out);
    }
    let features = match planar_of(object, path, "features")? {
        Planar::Polynomial(c) => features_of(&c),
        Planar::Rational(c) => features_of(&c),
    }
    .map_err(|e| e.context(path))?;
    let mut out = json!({
        "inflections": features.inflections,
        "curvature_extrema": features.curvature_extrema,
    });
    if let Some(k) = features.constant_curvature {
        out["constant_curvature"] = json!(k);
    }
    io::print_json(&out)
}

/// Curvature extrema and torsion zeros of a 3-D curve, located to the library's default
/// accuracy.
fn space_features_of<C: ParamCurve<f64> + SpaceCurveFeatures<f64>>(
    curve: &C,
) -> Result<SpaceFeatures<f64>> {
    curve.space_features(default_feature_accuracy(curve.domain()))
}
