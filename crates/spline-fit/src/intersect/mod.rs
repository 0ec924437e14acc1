//! Intersections with surfaces: curve–surface points and surface–surface curves (issue 12's
//! curve–curve intersection lives with the curves).

mod curve_surface;
mod curve_surface_overlap;
mod lm;
mod march;
mod splines;
mod tolerances;

pub use curve_surface::{CurveSurfaceHit, intersect_curve_surface};
pub use curve_surface_overlap::{
    CurveSurfaceEvent, CurveSurfaceIntersections, CurveSurfaceOverlap,
    intersect_curve_surface_with_overlaps,
};
use lm::lm_solve;
pub use march::{IntersectionCurve, MAX_TRACE_POINTS, intersect_surfaces};
pub use splines::{
    IntersectionSpline, SurfaceIntersection, intersect_surfaces_as_splines, intersection_splines,
};
pub use tolerances::Tolerances;
use tolerances::{check_tolerance, scale_of_boxes};
