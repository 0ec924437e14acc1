//! The picture and curve-geometry subcommands: `plot`, `curvature`, `features`, for planar
//! curves of every kind ([`PlanarCurve`], [`CurveFeatures`]).

use crate::io;
use crate::objects::{Object, check_dim, read_object};
use crate::structural::ObjectArgs;
use clap::Args;
use nalgebra::Vector2;
use serde_json::json;
use spline_algebra::{CurveFeatures, PlanarFeatures};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::export::SvgPlot;
use spline_geom::{BSpline, NurbsCurve, PlanarCurve};

/// Root accuracy of `features`, relative to the length of the domain.
const RELATIVE_ACCURACY: f64 = 1e-12;

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
enum Planar {
    Polynomial(BSpline<f64, Vector2<f64>>),
    Rational(NurbsCurve<f64, 2>),
}

/// Reads a planar curve; `what` says what needs it, for messages.
fn read_planar(path: &str, what: &str) -> Result<Planar> {
    let planar = |p: &crate::io::Pt| Vector2::new(p[0], p[1]);
    let dimension = |dim| check_dim(dim, 2, "a planar curve").map_err(|e| e.context(path));
    match read_object(path)? {
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
        )),
    }
}

/// Inflections and curvature extrema, located to `1e-12` times the domain length.
fn features_of<C: PlanarCurve<f64> + CurveFeatures<f64>>(curve: &C) -> Result<PlanarFeatures<f64>> {
    let (a, b) = curve.domain();
    curve.features(RELATIVE_ACCURACY * (b - a))
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
    let features = match read_planar(&args.object, "features")? {
        Planar::Polynomial(c) => features_of(&c),
        Planar::Rational(c) => features_of(&c),
    }
    .map_err(|e| e.context(&args.object))?;
    io::print_json(&json!({
        "inflections": features.inflections,
        "curvature_extrema": features.curvature_extrema,
    }))
}
