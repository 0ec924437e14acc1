//! Shape control and optimisation with B-splines.
//!
//! - [`adaptive`]: shape optimisation with adaptive parametrisation (seed 000 §3: minimise
//!   perimeter² / area by Nelder–Mead, re-fitting the parametrisation between steps).
//! - [`barrier`]: a log-barrier interior-point solver on sparse matrices, with a phase-I
//!   search for a strictly feasible start and a shifted Newton matrix for non-convex
//!   problems.
//! - [`constrained`]: least-squares approximation of functions of one variable under sign
//!   constraints on their derivatives, on sub-intervals, with sign changes (thesis §5.1–5.4).
//! - [`constrained_surface`]: the same for functions of two variables on grids: sign
//!   constraints on partial derivatives and convexity (thesis §5.5–5.6).
//! - [`eraser`]: the selective eraser of curvature extrema of planar curves (thesis ch. 6),
//!   e.g. airfoil smoothing.
//! - [`offset`]: offsets of curves (planar and space, B-spline and NURBS) with their cusps,
//!   and of surfaces; exact for arcs, planes and spheres, otherwise within a tolerance (the
//!   tool calls it once).

#[macro_use]
mod settings;

pub mod adaptive;
pub mod barrier;
pub mod constrained;
pub mod constrained_parametric;
pub mod constrained_spatial;
pub mod constrained_surface;
pub mod eraser;
pub mod flecnodal;
pub mod offset;
mod problem;
pub mod revolution;

pub use adaptive::{
    AdaptiveIteration, AdaptiveOptions, MAX_ADAPTIVE_CONTROL_POINTS, MAX_ADAPTIVE_ITERATIONS,
    MAX_ADAPTIVE_SAMPLES, MAX_SIMPLEX_ITERATIONS, default_initial_shape,
    optimise_perimeter_over_area, perimeter_squared_over_area,
};
pub use barrier::{
    BarrierOptions, BarrierProblem, BarrierReport, STALL_STEPS, find_feasible, find_feasible_near,
    minimize,
};
pub use constrained::{
    ConstraintCheck, FunctionApproximation, FunctionConstraint, FunctionFit, MAX_SIGN_PATTERNS,
};
pub use constrained_parametric::{ParametricConvexFit, ParametricConvexity};
pub use constrained_spatial::{
    MAX_SPATIAL_CONTROL_POINTS, SpatialConvexFit, SpatialConvexProblem, SpatialConvexity,
};
pub use constrained_surface::{
    ConstrainedSurfaceFit, Region, SurfaceApproximation, SurfaceConstraint,
};
pub use eraser::{
    AUTO_EXTREMA_TOLERANCE, AllowedExtrema, ControlPoints, CurvatureExtremum,
    DEVIATION_WARNING_FACTOR, DEVIATION_WARNING_FLOOR, ExtremaCount, Extremum, ExtremumKind,
    MAX_CURVATURE_EXTREMA, Objective, OptionSpelling, SampledExtremum, SmoothRequest,
    SmoothSummary, SmoothWords, SmoothedCurve, SmoothingOptions, WarmStart,
    sampled_curvature_extrema, smooth, smooth_fewest_extrema, smooth_from, smooth_to_tolerance,
};
pub use flecnodal::{FlecnodalCircles, control_flecnodal_circles};
pub use offset::{
    CUSP_ACCURACY, CurveOffset, Cusp, ExactOffset, OffsetOptions, OffsetShape, OffsetSource,
    SurfaceOffset, SurfaceOffsetShape, SurfaceOffsetSource, offset_planar_curve,
    offset_space_curve, offset_surface,
};
pub use problem::{ApproximationProblem, Sign};
pub use revolution::{
    MeridianControl, ParabolicCircles, RidgeControl, TranslationControl, control_parabolic_circles,
    control_ridge_circles, control_translation_parabolic_lines, revolution_surface,
    translation_surface,
};
