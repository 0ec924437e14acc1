//! `spline`: B-spline and NURBS curves and surfaces in Rust.
//!
//! This facade re-exports the layers of the workspace:
//! - [`core`]: scalar and control-point traits, knot vectors, basis functions;
//! - [`geom`]: curves, surfaces, NURBS and their algorithms;
//! - [`fit`]: interpolation and least squares;
//! - [`algebra`]: structural operations as sparse linear maps, products with Jacobians;
//! - [`shape`]: shape control and optimisation.

pub use spline_algebra as algebra;
pub use spline_core as core;
pub use spline_fit as fit;
pub use spline_geom as geom;
pub use spline_shape as shape;

pub use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar};
pub use spline_geom::{BSpline, Bezier};

/// The examples of the README, compiled and run as doc tests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
