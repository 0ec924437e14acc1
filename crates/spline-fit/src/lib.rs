//! spline-fit: see the crate description. Work in progress.
