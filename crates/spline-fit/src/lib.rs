//! Fitting B-splines to data: interpolation, least squares, parameter correction.
//!
//! - Parametrisation ([`Parametrization`]: uniform, chordal, centripetal, given) and knot
//!   placement ([`KnotChoice`]: averaging, uniform, The NURBS Book (9.68), given).
//! - Interpolation of curves ([`interpolate`], optionally with end derivatives), closed
//!   curves ([`interpolate_closed`]), functions ([`interpolate_function`]), natural splines
//!   of any even order ([`natural_spline`], [`natural_cubic`]), surfaces through grids
//!   ([`interpolate_surface`], by the two passes of seed 004 §7) and Bézier curves
//!   ([`bezier_interpolate`], seed 003 TD2).
//! - Surfaces through curves: skinning through sections ([`skin`]), sweeps along a path
//!   with rotation-minimising frames ([`sweep`]), Gordon surfaces through a curve network
//!   ([`gordon`]); grid interpolation with boundary derivatives
//!   ([`interpolate_surface_with_derivatives`]).
//! - Approximation of any map within a tolerance by adaptive knot refinement
//!   ([`AdaptiveApproximation`]) and reparametrisation by arc length
//!   ([`reparametrize_by_arc_length`]); offsets of planar curves within a tolerance
//!   ([`offset_curve`], with the cusps from `spline_algebra::offset_cusps` as corners);
//!   degree reduction within a tolerance ([`reduce_degree`]).
//! - Periodic splines ([`spline_geom::PeriodicBSpline`]): interpolation with scipy's periodic
//!   conditions ([`interpolate_periodic`]) and periodic least squares with an optional
//!   smoothing term ([`least_squares_periodic`]).
//! - Least squares ([`LeastSquares`], [`approximate`]) with weights, pinned ends, fixed
//!   control-point coordinates (seed 000 §3.3), a smoothing term, normal equations or QR;
//!   Bézier least squares ([`bezier_least_squares`], seed 003 TD3); surfaces from grids and
//!   from scattered points ([`approximate_surface_grid`], [`approximate_surface_scattered`]);
//!   unorganised points and meshes with parameters by projection, parameter correction and
//!   deviations both ways ([`fit_scattered`]).
//! - Parameter correction ([`correct_parameters`], seed 003) and robust closest points on
//!   curves ([`closest_point`]) and surfaces ([`SurfaceProjector`], many queries on one
//!   hierarchy of bounding boxes).
//! - Intersections: curve–surface points, tangential ones flagged
//!   ([`intersect_curve_surface`]), and surface–surface curves traced to a tolerance with
//!   their parameters on both surfaces ([`intersect_surfaces`]), also as B-spline curves in
//!   space and in both parameter planes ([`intersect_surfaces_as_splines`]).
//! - Smoothing splines: the penalised spline with its weight chosen by generalised
//!   cross-validation ([`smoothing_spline`], scipy's `make_smoothing_spline`), and the
//!   spline that meets a residual target with knots placed automatically
//!   ([`smoothing_to_residual`], FITPACK's `curfit`, scipy's `make_splrep`), for functions
//!   and parametric curves ([`smoothing_curve`], [`smoothing_curve_to_residual`]).
//! - Parameter correction ([`correct_parameters`], seed 003) and robust closest points
//!   ([`closest_point`]).
//! - Deviation reports ([`Deviation`]): maximum and RMS distance and which points.
//!
//! Every linear system is banded and solved in `O(n p²)` (collocation without pivoting,
//! banded LU with partial pivoting for end conditions and periodic systems, banded Cholesky
//! or Givens QR for least squares). Everything is generic over the scalar (`f64`, `f32`,
//! dual numbers) and the point type.
//!
//! Surface fits return a [`spline_geom::Surface`] with the parameters of the data and the
//! deviation ([`SurfaceFit`]), as curve fits return a [`spline_geom::BSpline`] ([`CurveFit`]).
//!
//! ```
//! use nalgebra::Vector2;
//! use spline_fit::{InterpolationOptions, interpolate};
//! let points = [Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(2.0, 0.0)];
//! let fit = interpolate(&points, 2, &InterpolationOptions::default())?;
//! assert!(fit.deviation.max < 1e-14);
//! # Ok::<(), spline_core::Error>(())
//! ```
//!
//! # Feature flags
//! None.

mod adaptive;
mod adaptive_surface;
mod arclength;
mod banded;
mod bezier;
mod bezier_request;
mod columns;
mod correction;
mod feature_knots;
mod hausdorff;
mod interpolate;
mod intersect;
mod lsq;
mod natural;
mod nd_interp;
mod noise;
mod offset;
mod params;
mod periodic;
mod project;
mod reduce;
mod report;
mod requests;
mod scattered;
mod skin;
mod skin_rational;
mod slab;
mod smoothing;
mod surface;
mod surface_ends;
mod surface_project;
mod sweep;

pub use adaptive::{AdaptiveApproximation, AdaptiveFit, MAX_ADAPTIVE_PIECES};
pub use adaptive_surface::{
    AdaptiveSurfaceApproximation, AdaptiveSurfaceFit, MAX_ADAPTIVE_PATCHES,
};
pub use arclength::reparametrize_by_arc_length;
pub use bezier::{BezierFit, bezier_interpolate, bezier_least_squares};
pub use bezier_request::{
    BezierLeastSquaresFit, BezierLeastSquaresRequest, fit_bezier_least_squares,
};
pub use columns::{InterpBc, make_interp_spline, make_lsq_spline};
pub use correction::{
    CorrectionOptions, CorrectionReport, MAX_CORRECTION_ITERATIONS, correct_parameters,
    correct_parameters_bezier,
};
pub use feature_knots::{curvature_knots, curvature_knots_with};
pub use hausdorff::{TwoSidedDeviation, two_sided_deviation};
pub use interpolate::{
    InterpolationOptions, interpolate, interpolate_closed, interpolate_function,
    interpolate_with_knots,
};
pub use intersect::{
    CurveSurfaceEvent, CurveSurfaceHit, CurveSurfaceIntersections, CurveSurfaceOverlap,
    IntersectionCurve, IntersectionSpline, MAX_TRACE_POINTS, SurfaceIntersection, Tolerances,
    intersect_curve_surface, intersect_curve_surface_with_overlaps, intersect_surfaces,
    intersect_surfaces_as_splines, intersection_splines,
};
#[cfg(feature = "parallel")]
pub use lsq::PARALLEL_MIN_POINTS;
pub use lsq::{
    GridLeastSquares, GridNormalEquations, LeastSquares, LsqMethod, NormalEquations, approximate,
};
pub use natural::{natural_cubic, natural_spline};
pub use nd_interp::make_ndbspl;
pub use noise::{noise_stride, parametrize_above_noise};
pub use offset::{offset_curve, offset_point};
pub use params::{
    KnotChoice, Parametrization, nurbs_book_knots, parametrize, parametrize_closed, parametrize_in,
};
pub use periodic::{interpolate_periodic, least_squares_periodic};
pub use project::{Projection, closest_point, project_ordered};
pub use reduce::reduce_degree;
pub use report::{CurveFit, Deviation, deviation};
pub use requests::{
    InterpolationRequest, LeastSquaresFit, LeastSquaresRequest, LsqKnots, fit_interpolation,
    fit_least_squares,
};
pub use scattered::{MAX_SCATTERED_SYSTEM, ScatteredFit, ScatteredOptions, fit_scattered};
pub use skin::{Gordon, Skinned, gordon, skin};
pub use skin_rational::{SkinnedNurbs, skin_rational};
pub use smoothing::{
    MAX_RESIDUAL_ITERATIONS, ResidualFit, SmoothingFit, SmoothingParameter, make_smoothing_spline,
    smoothing_curve, smoothing_curve_to_residual, smoothing_spline, smoothing_to_residual,
};
pub use smoothing::{
    SplrepOptions, chord_length_parameters, generate_knots, make_splprep, make_splrep,
};
pub use surface::{
    SurfaceFit, approximate_surface_grid, approximate_surface_scattered, interpolate_surface,
    surface_grid_params,
};
pub use surface_ends::{SurfaceEnds, interpolate_surface_with_derivatives};
pub use surface_project::{
    SurfaceProjection, SurfaceProjector, closest_local, closest_point_on_surface,
};
pub use sweep::{MAX_SWEEP_SECTIONS, sweep};
