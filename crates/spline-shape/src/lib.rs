//! spline-shape: see the crate description. Work in progress.
