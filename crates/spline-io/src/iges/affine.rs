//! The affine maps of transformation matrices (entity 124): read by the directory (chains of
//! matrices) and applied by the entities.

use nalgebra::{Matrix3, Vector3};

/// An affine map $x \mapsto M x + t$ (entity 124).
#[derive(Clone, Copy, Debug)]
pub(super) struct Affine {
    pub(super) m: Matrix3<f64>,
    pub(super) t: Vector3<f64>,
}

impl Affine {
    pub(super) fn apply(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.m * p + self.t
    }

    /// `self ∘ inner`.
    pub(super) fn after(&self, inner: &Self) -> Self {
        Self {
            m: self.m * inner.m,
            t: self.m * inner.t + self.t,
        }
    }
}
