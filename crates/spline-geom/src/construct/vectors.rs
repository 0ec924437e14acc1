//! Vector helpers of the constructions: a perpendicular unit vector, and a norm that neither
//! overflows nor underflows.

use nalgebra::Vector3;
use spline_core::Scalar;

/// A unit vector perpendicular to the unit vector `n`: the coordinate axis least aligned
/// with `n` (the first on ties), projected on the plane `n⊥`.
pub(super) fn perpendicular<T: Scalar>(n: &Vector3<T>) -> Vector3<T> {
    let mut best = 0;
    for i in 1..3 {
        if n[i].abs() < n[best].abs() {
            best = i;
        }
    }
    let e = Vector3::<T>::ith(best, T::one());
    let x = e - n * n.dot(&e);
    x / safe_norm(&x)
}

/// The Euclidean length computed on the vector divided by its largest coordinate, so that it
/// neither overflows (coordinates above 1e154) nor underflows (below 1e-154).
pub(super) fn safe_norm<T: Scalar, const D: usize>(v: &nalgebra::SVector<T, D>) -> T {
    let m = v.amax();
    if m > T::zero() && m.is_finite() {
        (v / m).norm() * m
    } else {
        v.norm()
    }
}
