//! The integration tests of spline-fit, one module per former test file, linked into one
//! test binary (one link instead of one per file: the cold CI build is dominated by links).

#![allow(unreachable_pub)]

mod adaptive_surface;
mod arclength;
mod closest_global;
mod curve_surface_overlaps;
mod errors;
mod geometry;
mod offsets;
mod parallel;
mod periodic;
mod properties;
mod reference;
mod seeds;
mod smoothing;
mod splrep_periodic;
mod surface_closest;
mod surface_construct;
mod surface_intersect;
mod surface_intersect_splines;
mod surface_scattered;
