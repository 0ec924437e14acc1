//! The integration tests of spline-core, one module per former test file, linked into one
//! test binary (one link instead of one per file: the cold CI build is dominated by links).

#![allow(unreachable_pub)]

mod basis;
mod knots;
mod span_table;
