//! Curves and surfaces: the generic containers of the `spline` library and every classic
//! algorithm on them.
//!
//! - [`BSpline`]: degree + knot vector + control points of any [`ControlPoint`] type
//!   (functions, curves in `R^D`, homogeneous points), with evaluation (de Boor and basis
//!   form), derivatives of any order, the derivative curve, knot insertion, refinement and
//!   removal, degree elevation, splitting, clamping, Bézier decomposition, reversal.
//! - [`Bezier`]: de Casteljau, Bernstein evaluation, subdivision, elevation, hodograph.
//! - Planar differential geometry, adaptive arc length, the variation-diminishing count.
//! - [`Surface`]: tensor-product surfaces with evaluation (tensor fast path on grids), all
//!   partial derivatives, derivative surfaces, iso-curves, Bézier patches, every structural
//!   algorithm in either [`Direction`], normals, fundamental forms and curvatures
//!   ([`LocalProperties`]).
//! - [`NurbsCurve`] and [`NurbsSurface`]: rational views over containers of [`Homogeneous`]
//!   points, with rational derivatives of any order and the classic constructions (conics,
//!   circles both ways of the notes, arcs, extrusion, ruled and conical surfaces, surfaces of
//!   revolution, sphere, torus); tessellation into a [`TriangleMesh`].
//!
//! File formats (the JSON exchange format, OBJ, OFF, SVG, STEP, IGES…) live in `spline-io`.
//!
//! ```
//! use nalgebra::Vector2;
//! use spline_geom::BSpline;
//! let curve = BSpline::from_knots(
//!     2,
//!     vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
//!     vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 2.0), Vector2::new(2.0, 0.0)],
//! )?;
//! let split = curve.split(0.5)?;
//! assert_eq!(split.0.eval(0.5)?, curve.eval(0.5)?);
//! # Ok::<(), spline_core::Error>(())
//! ```

mod arclength;
mod bezier;
mod bspline;
mod columns;
mod comb;
mod construct;
mod curve_tools;
mod evaluator;
mod homogeneous;
mod lanes;
mod mesh;
mod nd;
mod nurbs;
mod operations;
#[cfg(feature = "parallel")]
mod parallel;
mod param;
mod param_impls;
mod periodic;
mod pieces;
mod planar;
mod structural;
mod surface;
mod surface_geometry;
mod transfer;
mod variation;

pub use arclength::DEFAULT_ACCURACY;
pub use bezier::Bezier;
pub use bspline::BSpline;
pub use columns::{ColumnSpline, Extrapolate, PowerBasisKnots};
pub use comb::{CombTooth, comb_segments, curvature_comb, evenly_spaced_params};
pub use construct::{
    Axis, CircleConstruction, ConicKind, Frame, MAX_ARC_PIECES, MovingFrame, boolean_sum,
    compatible_curves, compatible_surfaces, rotation_minimizing_frames,
};
pub use curve_tools::{
    ArcLengthTable, BoundingBox, MAX_TESSELLATION_SEGMENTS, hull_box, param_at_length, pieces_box,
    tessellate,
};
pub use evaluator::{CurveEvaluator, NurbsEvaluator};
pub use homogeneous::Homogeneous;
pub use mesh::{MAX_MESH_SEGMENTS, TriangleMesh};
pub use nd::{NdSpline, knot_vectors};
pub use nurbs::{
    HomogeneousContainer, NurbsCurve, NurbsCurve2, NurbsCurve3, NurbsSurface, NurbsSurface3,
    NurbsSurfaceEvaluator, Rational,
};
pub use operations::{Operation, Outcome, StructuralCurve, StructuralSurface};
pub use param::{ParamCurve, ParamSurface, PlanarCurve, SpatialSurface};
pub use periodic::PeriodicBSpline;
pub use planar::wedge;
pub use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar};
pub use structural::DEFAULT_REMOVAL_TOLERANCE;
pub use surface::{Direction, Surface, SurfaceEvaluator};
pub use surface_geometry::{FundamentalForm, LocalProperties};
pub use variation::sign_changes;

/// A B-spline function (scalar control points).
pub type BSplineFunction<T = f64> = BSpline<T, T>;
/// A planar B-spline curve.
pub type Curve2<T = f64> = BSpline<T, nalgebra::Vector2<T>>;
/// A spatial B-spline curve.
pub type Curve3<T = f64> = BSpline<T, nalgebra::Vector3<T>>;
/// A B-spline surface in space.
pub type Surface3<T = f64> = Surface<T, nalgebra::Vector3<T>>;
