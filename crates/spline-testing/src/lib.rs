//! Test support for the crates of the `spline` workspace (a dev-dependency only, never
//! published): the reference cases of `tests/data/reference/` ([`reference`](mod@reference)), proptest
//! strategies for knot vectors, spline spaces and splines that shrink to small cases
//! ([`strategies`]), and comparisons of numbers, points and curves ([`compare`]).
//!
//! Its functions panic on failure: a panic is how a test fails.

#![allow(clippy::missing_panics_doc)]

pub mod allocations;
pub mod compare;
pub mod reference;
pub mod strategies;
