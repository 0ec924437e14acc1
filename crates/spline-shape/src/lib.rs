//! Shape control and optimisation with B-splines.
//!
//! - [`barrier`]: a log-barrier interior-point solver on sparse matrices, with a phase-I
//!   search for a strictly feasible start and a shifted Newton matrix for non-convex
//!   problems.
//! - [`eraser`]: the selective eraser of curvature extrema of planar curves (thesis ch. 6),
//!   e.g. airfoil smoothing.

pub mod barrier;
pub mod eraser;

pub use barrier::{
    BarrierOptions, BarrierProblem, BarrierReport, find_feasible, find_feasible_near, minimize,
};
pub use eraser::{EraserOptions, SmoothedCurve, erase_curvature_extrema};
