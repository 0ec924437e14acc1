//! Knot removal of rational shapes: done in homogeneous space, accepted on a bound of the
//! distance the rational shape moves.

use crate::homogeneous::{Homogeneous, check_weight};
use crate::structural::tolerance_exceeded;
use nalgebra::RealField;
use spline_core::{ControlPoint, Result, Scalar, cast};

/// The largest homogeneous distance between two lists of homogeneous points, turned into a
/// bound on the distance between the rational shapes (The NURBS Book (5.30)): if
/// $|P^w_i - Q^w_i| \le \delta$ for all `i`, then $|C(u) - C'(u)| \le \delta (1 + |P|_{max}) /
/// w'_{min}$, since $C' - C = (\Delta A - C \Delta w) / w'$.
pub(super) fn rational_deviation_bound<T: Scalar, const D: usize>(
    original: &[Homogeneous<T, D>],
    changed: &[Homogeneous<T, D>],
) -> Option<T> {
    let delta = original
        .iter()
        .zip(changed)
        .fold(T::zero(), |m, (a, b)| m.max((*a - *b).length()));
    let pmax = original
        .iter()
        .fold(T::zero(), |m, h| m.max(h.project().norm()));
    let wmin = changed.iter().map(|h| h.weight).reduce(RealField::min)?;
    (wmin > T::zero()).then(|| delta * (T::one() + pmax) / wmin)
}

/// Accepts a knot removal done in homogeneous space if the rational shape moves by at most
/// `tolerance` and every weight stays positive: `back` is `removed` with the knots
/// re-inserted, compared with `original` by [`rational_deviation_bound`].
pub(super) fn check_rational_removal<T: Scalar, const D: usize>(
    original: &[Homogeneous<T, D>],
    removed: &[Homogeneous<T, D>],
    back: &[Homogeneous<T, D>],
    (t, times): (T, usize),
    tolerance: T,
) -> Result<()> {
    let bound = rational_deviation_bound(original, back);
    let weights_ok = removed.iter().all(|h| check_weight(h.weight).is_ok());
    match bound {
        Some(b) if b <= tolerance && weights_ok => Ok(()),
        _ => Err(tolerance_exceeded(
            t,
            times,
            bound.filter(|_| weights_ok),
            tolerance,
        )),
    }
}

/// A tolerance so large that the homogeneous removal never refuses: the rational check is
/// done afterwards.
pub(super) fn unbounded<T: Scalar>() -> T {
    T::max_value().unwrap_or_else(|| cast(f64::MAX))
}
