//! The integration tests of the facade `spline` (cross-crate tests), one module per former test file, linked into one
//! test binary (one link instead of one per file: the cold CI build is dominated by links).

#![allow(unreachable_pub)]

mod features;
mod limits;
mod reference;
mod scale;
