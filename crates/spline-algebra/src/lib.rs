//! spline-algebra: see the crate description. Work in progress.
