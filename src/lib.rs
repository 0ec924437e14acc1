//! `spline`: B-spline and NURBS curves and surfaces in Rust — evaluation, every classic
//! structural algorithm, fitting, and spline algebra with Jacobians.
//!
//! ```
//! use spline::prelude::*;
//!
//! // A planar cubic (seed 000 §2.3.3) and a quarter circle as a NURBS curve.
//! let curve = BSpline::from_knots(
//!     3,
//!     vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0],
//!     vec![
//!         Vector2::new(0.41705, 0.10673), Vector2::new(0.28802, 0.60088),
//!         Vector2::new(0.90553, 0.46053), Vector2::new(1.3203, 0.79678),
//!         Vector2::new(1.8041, 0.63012), Vector2::new(1.477, 0.13012),
//!     ],
//! )?;
//! let quarter = NurbsCurve::from_knots(
//!     2,
//!     vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
//!     vec![Vector2::new(1.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(0.0, 1.0)],
//!     vec![1.0, 1.0, 2.0],
//! )?;
//! // Every kind of curve answers the same questions (ParamCurve, PlanarCurve).
//! fn turning<C: PlanarCurve<f64>>(c: &C, u: f64) -> f64 {
//!     c.signed_curvature(u).unwrap()
//! }
//! assert!((turning(&quarter, 0.5) - 1.0).abs() < 1e-14);
//! let elevated = curve.elevate_degree(1)?; // exact: the same curve, degree 4
//! assert!((elevated.eval(1.5)? - curve.eval(1.5)?).norm() < 1e-14);
//! # Ok::<(), spline::Error>(())
//! ```
//!
//! # Layers
//! Each layer is a crate of its own, re-exported here; no dependency runs upward
//! (`ARCHITECTURE.md`).
//!
//! - [`core`] (`spline-core`): the [`Scalar`] and [`ControlPoint`] traits,
//!   validated [`KnotVector`]s with every knot-vector rule of the structural operations,
//!   basis functions, the structured [`Error`].
//! - [`geom`] (`spline-geom`): the containers — [`BSpline`], [`Bezier`],
//!   [`Surface`], [`NurbsCurve`], [`NurbsSurface`] — with each structural algorithm written
//!   once, generic over the point type; the capability traits [`ParamCurve`] and
//!   [`ParamSurface`]; constructions, meshes.
//! - [`fit`] (`spline-fit`): interpolation, the one least-squares path,
//!   parameter correction, closest points, deviations both ways.
//! - [`algebra`] (`spline-algebra`): structural operations as sparse maps
//!   (the same algorithms run on symbolic points), products with Jacobians and Hessians,
//!   curvature invariants, root isolation, inflections and curvature extrema.
//! - [`shape`] (`spline-shape`): interior-point solver, constrained
//!   approximation, the selective eraser of curvature extrema, shape optimisation.
//! - [`io`] (`spline-io`): every file format (exchange format, points, airfoils, OBJ, OFF,
//!   SVG, gnuplot, STEP, IGES).
//!
//! The [`prelude`] brings the containers, the traits and the nalgebra vectors into scope;
//! [`nalgebra`] is re-exported, so a project does not need to match its version.
//!
//! # Feature flags
//! - `serde` (default): the JSON exchange format — [`io::exchange`]: every curve and surface
//!   to and from JSON, the records, CAD items in it (`io::Geometry::to_exchange`) — and JSON
//!   point files.
//!
//! Every file format — the exchange format, point files, airfoils, OBJ and OFF meshes, SVG
//! and gnuplot pictures, STEP and IGES — is read and written by [`io`] (`spline-io`).

/// The guide: doc-tested chapters from scipy, CAD and the thesis to this library.
pub mod guide;

pub use spline_algebra as algebra;
pub use spline_core as core;
pub use spline_fit as fit;
pub use spline_geom as geom;
pub use spline_io as io;
pub use spline_shape as shape;

/// The linear algebra the containers are built on (`nalgebra`), re-exported so that the
/// point types of a downstream crate are the library's.
pub use nalgebra;

pub use spline_algebra::{ProductMap, SplineMap, TensorMap};
pub use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, SymbolicPoint, VectorSpace,
};
pub use spline_geom::{
    BSpline, BSplineFunction, Bezier, Curve2, Curve3, CurveEvaluator, Direction, Homogeneous,
    NurbsCurve, NurbsCurve2, NurbsCurve3, NurbsEvaluator, NurbsSurface, NurbsSurface3,
    NurbsSurfaceEvaluator, Operation, Outcome, ParamCurve, ParamSurface, PlanarCurve,
    SpatialSurface, StructuralCurve, StructuralSurface, Surface, Surface3, SurfaceEvaluator,
    TriangleMesh,
};

/// The containers, the traits and the nalgebra vectors: `use spline::prelude::*;`.
pub mod prelude {
    pub use crate::algebra::{CurveFeatures, SplineMap};
    pub use crate::core::{
        ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, VectorSpace,
    };
    pub use crate::geom::{
        BSpline, Bezier, Direction, Homogeneous, NurbsCurve, NurbsSurface, ParamCurve,
        ParamSurface, PlanarCurve, SpatialSurface, StructuralCurve, StructuralSurface, Surface,
    };
    pub use nalgebra::{SVector, Vector2, Vector3};
}

/// The examples of the README, compiled and run as doc tests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
