//! The integration tests of spline-studio, one module per former test file, linked into one
//! test binary (one link instead of one per file: the cold CI build is dominated by links).

#![allow(unreachable_pub)]

mod browser;
mod browser_driver;
mod http;
