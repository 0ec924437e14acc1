//! The selective eraser of curvature extrema (thesis ch. 6): the planar B-spline curve
//! closest to data points whose curvature has only the allowed extrema.
//!
//! With `g = h1 h2 − 3 h3 h4` (`κ′ = g / h1^{5/2}`, thesis (6.10)), the curvature is monotone
//! on a parameter interval where `g` keeps one sign. The allowed extrema are knots of the
//! curve (of multiplicity `p − 2`, so that `c‴` and hence `g` may jump there while the
//! curvature stays continuous); they cut the domain into pieces on which the curvature must
//! increase and decrease alternately. Every Bernstein coefficient of `g` on every piece is
//! constrained to the piece's sign (6.21): by the variation-diminishing property, `g` then
//! keeps that sign and the only extrema are the allowed ones.
//!
//! The method is built on spline-fit:
//! 1. centripetal parameters, a least-squares fit and parameter correction locate the shape;
//! 2. knots follow its curvature ([`spline_fit::curvature_knots_with`]), the allowed extrema
//!    are placed on it (the strongest maximum or minimum of the oriented curvature, or where
//!    the caller says) and become knots; a least-squares fit with parameter correction on
//!    these knots is the start;
//! 3. phase I of the interior-point method finds a strictly feasible curve near it;
//! 4. rounds of: the constrained least-squares problem (spline-fit's normal equations under
//!    the sign conditions) solved by the interior-point method from the current curve;
//!    parameter correction (each data point moves to its closest point, so that what is
//!    minimised is the true point-to-curve distance); with [`Objective::MaxDeviation`],
//!    Lawson's reweighting of the data towards the smallest maximum deviation; refinement of
//!    the pieces whose conditions are active (subdivision keeps the curve feasible and makes
//!    the sufficient conditions closer to `g ≥ 0` itself). The best curve is kept.

mod closed;
mod closed_topology;
mod distances;
mod driver;
mod fewest_extrema;
mod input;
mod open_topology;
mod pieces;
mod placement;
mod problem;
mod request;
mod screening;
mod smooth;
mod smooth_request;
mod tolerance;
mod topology;
mod types;
mod verify;

pub use fewest_extrema::{AUTO_EXTREMA_TOLERANCE, smooth_fewest_extrema};
pub use request::{ExtremaCount, OptionSpelling, SmoothWords};
pub use smooth::{smooth, smooth_from};
pub use smooth_request::{AllowedExtrema, ControlPoints, SmoothRequest};
pub use tolerance::smooth_to_tolerance;
pub use types::{
    CurvatureExtremum, DEVIATION_WARNING_FACTOR, DEVIATION_WARNING_FLOOR, Extremum, ExtremumKind,
    MAX_CURVATURE_EXTREMA, Objective, SmoothSummary, SmoothedCurve, SmoothingOptions, WarmStart,
};
pub use verify::{SampledExtremum, sampled_curvature_extrema};
