//! The integration tests of spline-shape, one module per former test file, linked into one
//! test binary (one link instead of one per file: the cold CI build is dominated by links).

#![allow(unreachable_pub)]

mod adaptive;
mod airfoils;
mod barrier;
mod clarabel;
mod eraser;
mod eraser_closed;
mod eraser_many_points;
mod eraser_request;
mod eraser_warnings;
mod flecnodal;
mod functions;
mod offset_surfaces;
mod parametric_convexity;
mod revolution;
mod spatial_convexity;
mod surfaces;
