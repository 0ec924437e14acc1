//! Shape control and optimisation with B-splines.
//!
//! - [`barrier`]: a log-barrier interior-point solver on sparse matrices, with a phase-I
//!   search for a strictly feasible start and a shifted Newton matrix for non-convex
//!   problems.

pub mod barrier;

pub use barrier::{BarrierOptions, BarrierProblem, BarrierReport, find_feasible, minimize};
