//! The integration tests of spline-algebra, one module per former test file, linked into one
//! test binary (one link instead of one per file: the cold CI build is dominated by links).

#![allow(unreachable_pub)]

mod bounds;
mod common;
mod curves;
mod curves_features;
mod errors;
mod features;
mod intersections;
mod intersections_examples;
mod intersections_occt;
mod maps;
mod offset_cusps;
mod overlaps;
mod periodic_features;
mod products;
mod revolution;
mod roots;
mod segment_curvature;
mod space;
mod space_random;
mod surface_features;
mod surface_jacobians;
mod surface_ridges;
mod tensor;
