//! Cartesian control points with weights and homogeneous points: converted both ways,
//! mapped, and checked.

use crate::homogeneous::{Homogeneous, check_weight};
use crate::structural::relative_scale;
use nalgebra::SVector;
use spline_core::{Error, ErrorKind, Result, Scalar};

pub(super) fn check_point<T: Scalar, const D: usize>(
    p: &SVector<T, D>,
    what: impl FnOnce() -> String,
) -> Result<()> {
    if p.iter().all(nalgebra::ComplexField::is_finite) {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::NonFinite,
            format!("{} is not finite", what()),
        ))
    }
}

/// The homogeneous points $(w_k P_k, w_k)$ of Cartesian control points and their weights,
/// checked; `index(k)` names entry `k` in messages (`3` on a curve, `(0, 3)` on a net).
pub(super) fn weighted_points<T: Scalar, const D: usize>(
    control_points: Vec<SVector<T, D>>,
    weights: Vec<T>,
    index: impl Fn(usize) -> String,
) -> Result<Vec<Homogeneous<T, D>>> {
    if weights.len() != control_points.len() {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "{} control points need {} weights, got {}",
                control_points.len(),
                control_points.len(),
                weights.len()
            ),
        ));
    }
    for (k, &w) in weights.iter().enumerate() {
        check_weight(w).map_err(|e| e.context(format_args!("weight {}", index(k))))?;
    }
    for (k, p) in control_points.iter().enumerate() {
        check_point(p, || format!("control point {}", index(k)))?;
    }
    Ok(control_points
        .into_iter()
        .zip(weights)
        .map(|(p, w)| Homogeneous::new(p * w, w))
        .collect())
}

/// The Cartesian points $P_k$ of homogeneous ones.
pub(super) fn cartesian<T: Scalar, const D: usize>(
    points: &[Homogeneous<T, D>],
) -> Vec<SVector<T, D>> {
    points.iter().map(Homogeneous::project).collect()
}

/// The weights $w_k$ of homogeneous points.
pub(super) fn weights_of<T: Scalar, const D: usize>(points: &[Homogeneous<T, D>]) -> Vec<T> {
    points.iter().map(|h| h.weight).collect()
}

/// The homogeneous point of `f(P)` with the weight of `h = (w P, w)`.
pub(super) fn mapped<T: Scalar, const D: usize, const E: usize>(
    h: &Homogeneous<T, D>,
    f: &mut impl FnMut(&SVector<T, D>) -> SVector<T, E>,
) -> Homogeneous<T, E> {
    Homogeneous::new(f(&h.project()) * h.weight, h.weight)
}

/// The scale of a relative removal tolerance: the largest Cartesian coordinate magnitude,
/// or 1 if that is smaller.
pub(super) fn cartesian_scale<T: Scalar, const D: usize>(points: &[Homogeneous<T, D>]) -> T {
    relative_scale(points.iter().map(|h| h.project().amax()))
}

/// [`ErrorKind::InvalidWeight`] when a weight of a computed NURBS object is not positive and
/// finite, or a point is not finite (weights spanning too many orders of magnitude).
pub(super) fn check_result_weights<T: Scalar, const D: usize>(
    points: &[Homogeneous<T, D>],
) -> Result<()> {
    if points.iter().all(|h| {
        h.weight > T::zero()
            && h.weight.is_finite()
            && h.point.iter().all(nalgebra::ComplexField::is_finite)
    }) {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::InvalidWeight,
            "a weight of the result is zero or too large for floating point: the weights span too many orders of magnitude",
        ))
    }
}
