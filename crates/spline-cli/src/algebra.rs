//! Spline-algebra subcommands: product, curvature, features.

use crate::curves::ObjectArgs;
use clap::Args;
use spline_core::{Error, ErrorKind, Result};

fn not_yet(what: &str) -> Error {
    Error::new(
        ErrorKind::InvalidArgument,
        format!("{what} is not supported yet"),
    )
}

#[derive(Args)]
pub struct ProductArgs {
    /// First factor: a B-spline function (1-D control points).
    a: String,
    /// Second factor, on the same domain.
    b: String,
    /// Also print the Jacobians of the product's coefficients.
    #[arg(long)]
    jacobian: bool,
}

#[derive(Args)]
pub struct CurvatureArgs {
    /// A planar curve (JSON).
    object: String,
    /// Parameters as a JSON array.
    #[arg(long)]
    at: String,
}

/// Parameters of the inflections and curvature extrema of a planar curve.
pub struct PlanarFeatures {
    /// Parameters of the inflections.
    pub inflections: Vec<f64>,
    /// Parameters of the curvature extrema.
    pub curvature_extrema: Vec<f64>,
}

/// Finds inflections and curvature extrema.
pub fn planar_features(_curve: &spline_geom::Curve2) -> Result<PlanarFeatures> {
    Err(not_yet("curve features"))
}

pub fn product(args: &ProductArgs) -> Result<()> {
    Err(not_yet(&format!("product of {} and {}", args.a, args.b)))
}

pub fn curvature(args: &CurvatureArgs) -> Result<()> {
    Err(not_yet(&format!("curvature of {}", args.object)))
}

pub fn features(args: &ObjectArgs) -> Result<()> {
    Err(not_yet(&format!("features of {}", args.object)))
}
