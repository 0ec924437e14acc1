//! The integration tests of the `spline` tool, one module per former test file, linked into one
//! test binary (one link instead of one per file: the cold CI build is dominated by links).

#![allow(unreachable_pub)]

mod algebra;
mod common;
mod curve_tools;
mod curves;
mod fitting;
mod functions;
mod offset_surfaces;
mod overlap_tools;
mod readme;
mod reliability;
mod reliability_answers;
mod reproducers;
mod scale;
mod shape;
mod studio;
mod surface_features;
mod surface_tools;
mod surfaces;
mod surfaces_make;
mod surfaces_operations;
