//! The integration tests of spline-io, one module per format family, linked into one test
//! binary.

#![allow(unreachable_pub)]

mod error_fields;
mod exchange;
mod iges;
mod meshes;
mod pictures;
mod points;
mod step;
