//! The settings of an offset, of curves and of surfaces alike.

use spline_core::{Scalar, cast};

/// The settings of an offset: degree of the approximation and the largest distance allowed
/// between it and the exact offset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OffsetOptions<T> {
    /// Degree of the approximating B-spline (3 is a good choice).
    pub degree: usize,
    /// The largest distance between the result and the exact offset at the same parameter.
    pub tolerance: T,
}

impl<T: Scalar> Default for OffsetOptions<T> {
    fn default() -> Self {
        Self {
            degree: 3,
            tolerance: cast(1e-6),
        }
    }
}
