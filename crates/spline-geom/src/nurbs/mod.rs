//! NURBS curves and surfaces: rational views over B-spline containers of homogeneous points.
//!
//! A NURBS curve is the central projection of a B-spline curve in $\mathbb{R}^{D+1}$ whose
//! control points are $(w_i P_i, w_i)$ (seed 004 (6.4)–(6.5)). Evaluation is evaluation in
//! homogeneous space followed by the projection; rational derivatives follow from Leibniz's
//! rule (The NURBS Book A4.2 and A4.4); every structural algorithm (insertion, refinement,
//! removal, elevation, splitting) runs unchanged on the homogeneous container.

use crate::homogeneous::{Homogeneous, check_weight, check_weights};
use crate::structural::{relative_scale, tolerance_exceeded};
use nalgebra::{RealField, SVector};
#[cfg(doc)]
use spline_core::ErrorKind as _;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, cast, from_count};

mod curve;
mod mobius;
mod surface;
mod surface_evaluator;

pub use curve::{NurbsCurve, NurbsCurve2, NurbsCurve3};
pub use surface::{NurbsSurface, NurbsSurface3};
pub use surface_evaluator::NurbsSurfaceEvaluator;

use crate::bspline::BSpline;
use crate::surface::Surface;

/// A container of homogeneous points: the B-spline curve behind a [`NurbsCurve`], the
/// surface behind a [`NurbsSurface`].
pub trait HomogeneousContainer<T, const D: usize> {
    /// The homogeneous control points $(w_i P_i, w_i)$.
    fn homogeneous_points(&self) -> &[Homogeneous<T, D>];
}

impl<T: Scalar, const D: usize> HomogeneousContainer<T, D> for BSpline<T, Homogeneous<T, D>> {
    fn homogeneous_points(&self) -> &[Homogeneous<T, D>] {
        self.control_points()
    }
}

impl<T: Scalar, const D: usize> HomogeneousContainer<T, D> for Surface<T, Homogeneous<T, D>> {
    fn homogeneous_points(&self) -> &[Homogeneous<T, D>] {
        self.control_points()
    }
}

/// The rational view over a container `C` of homogeneous points (seed 000 §2.2: a
/// container holds data, a view interprets it): the central projection of the container,
/// with its Cartesian control points and weights at hand. [`NurbsCurve`] and
/// [`NurbsSurface`] are this view over a B-spline curve and over a surface; weights are
/// positive and finite by construction, so evaluation never divides by zero.
#[derive(Clone, Debug, PartialEq)]
pub struct Rational<C, T, const D: usize> {
    container: C,
    /// The Cartesian control points $P_i$ (kept so that `control_points` is a slice, as for
    /// every other container).
    points: Vec<SVector<T, D>>,
    /// The weights $w_i$.
    weights: Vec<T>,
}

impl<T: Scalar, const D: usize, C: HomogeneousContainer<T, D>> Rational<C, T, D> {
    /// The rational view of a homogeneous container.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidWeight`] unless every weight is positive and finite.
    pub fn from_homogeneous(container: C) -> Result<Self> {
        check_weights(container.homogeneous_points().iter().map(|h| h.weight))?;
        Ok(Self::wrap(container))
    }

    /// The view of a container with positive weights.
    fn wrap(container: C) -> Self {
        Self {
            points: cartesian(container.homogeneous_points()),
            weights: weights_of(container.homogeneous_points()),
            container,
        }
    }

    /// Recomputes the Cartesian points and weights after the container changed in place.
    pub(crate) fn resync(&mut self) {
        let homogeneous = self.container.homogeneous_points();
        self.points.clear();
        self.points
            .extend(homogeneous.iter().map(Homogeneous::project));
        self.weights.clear();
        self.weights.extend(homogeneous.iter().map(|h| h.weight));
    }

    /// A view of a container whose weights are known to be positive.
    pub(crate) fn new_unchecked(container: C) -> Self {
        debug_assert!(
            container
                .homogeneous_points()
                .iter()
                .all(|h| h.weight > T::zero())
        );
        Self::wrap(container)
    }

    /// The result of a structural operation in homogeneous space: positive weights in theory
    /// (positive combinations of positive weights), but weights spanning hundreds of orders of
    /// magnitude can underflow to zero.
    pub(crate) fn checked(container: C) -> Result<Self> {
        check_result_weights(container.homogeneous_points())?;
        Ok(Self::wrap(container))
    }

    /// The homogeneous container (seed 004 (6.4)) whose projection this is.
    #[inline]
    #[must_use]
    pub fn homogeneous(&self) -> &C {
        &self.container
    }

    /// Consumes the view, returning its homogeneous container.
    #[must_use]
    pub fn into_homogeneous(self) -> C {
        self.container
    }

    /// The Cartesian control points $P_i$ (row-major for surfaces).
    #[must_use]
    pub fn control_points(&self) -> &[SVector<T, D>] {
        &self.points
    }

    /// The weights $w_i$ (row-major for surfaces).
    #[must_use]
    pub fn weights(&self) -> &[T] {
        &self.weights
    }
}

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

/// Rational derivatives of a curve from the homogeneous ones (The NURBS Book A4.2):
/// $C^{(k)} = \big(A^{(k)} - \sum_{i=1}^{k} \binom{k}{i} w^{(i)} C^{(k-i)}\big) / w$.
///
/// `hom` holds the homogeneous derivatives of orders `0 … hom.len() − 1`; those above are
/// zero (orders above the degree), so the sums stop there and order `k` costs `O(p)`.
///
/// # Errors
/// [`ErrorKind::NonFinite`] when a derivative leaves the range of the scalar type (rational
/// derivatives of order `k` grow like `k!`).
pub(crate) fn rational_curve_derivatives<T: Scalar, const D: usize>(
    hom: &[Homogeneous<T, D>],
    out: &mut [SVector<T, D>],
) -> Result<()> {
    let w0 = hom[0].weight;
    let top = hom.len() - 1;
    for k in 0..out.len() {
        let mut v = if k <= top {
            hom[k].point
        } else {
            SVector::zeros()
        };
        let mut binom = T::one();
        for i in 1..=k.min(top) {
            // C(k, i) from C(k, i − 1).
            binom = binom * from_count::<T>(k - i + 1) / from_count::<T>(i);
            v -= out[k - i] * (binom * hom[i].weight);
        }
        out[k] = v / w0;
        if !out[k].iter().all(nalgebra::ComplexField::is_finite) {
            return Err(derivative_overflow(k));
        }
    }
    Ok(())
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

pub(super) fn derivative_overflow(order: usize) -> Error {
    Error::new(
        ErrorKind::NonFinite,
        format!(
            "the rational derivative of order {order} is too large for floating point (rational derivatives grow like order!)"
        ),
    )
}

/// The homogeneous partial derivatives that the rational ones of a surface of degrees
/// `(p, q)` on the square `0 ≤ k, l ≤ order` need, once `out_len` is checked to be
/// `(order + 1)²`: the orders up to `top = min(order, max(p, q))` (those above vanish) and
/// their number `(top + 1)²`.
///
/// # Errors
/// The errors of [`crate::bspline::square_len`]; [`ErrorKind::InvalidLength`] unless
/// `out_len = (order + 1)²`.
pub(crate) fn homogeneous_square(
    order: usize,
    (p, q): (usize, usize),
    out_len: usize,
) -> Result<(usize, usize)> {
    crate::bspline::check_same_len(crate::bspline::square_len(order)?, out_len)?;
    let top = order.min(p.max(q));
    Ok((top, (top + 1) * (top + 1)))
}

/// Rational partial derivatives of a surface on the square `0 ≤ k, l ≤ order` from the
/// homogeneous ones (The NURBS Book A4.4). `hom` holds the homogeneous derivatives on the
/// square `0 ≤ i, j ≤ top` (row-major, rows of `top + 1`; those above are zero); `out` is
/// row-major with rows of `order + 1`.
///
/// # Errors
/// [`ErrorKind::NonFinite`] when a derivative leaves the range of the scalar type.
pub(crate) fn rational_surface_derivatives<T: Scalar, const D: usize>(
    hom: &[Homogeneous<T, D>],
    top: usize,
    order: usize,
    out: &mut [SVector<T, D>],
) -> Result<()> {
    let w = order + 1;
    let hw = top + 1;
    let weight = |i: usize, j: usize| hom[i * hw + j].weight;
    let w00 = weight(0, 0);
    for k in 0..=order {
        for l in 0..=order {
            let mut v = if k <= top && l <= top {
                hom[k * hw + l].point
            } else {
                SVector::zeros()
            };
            let mut blj = T::one();
            for j in 1..=l.min(top) {
                blj = blj * from_count::<T>(l - j + 1) / from_count::<T>(j);
                v -= out[k * w + l - j] * (blj * weight(0, j));
            }
            let mut bki = T::one();
            for i in 1..=k.min(top) {
                bki = bki * from_count::<T>(k - i + 1) / from_count::<T>(i);
                v -= out[(k - i) * w + l] * (bki * weight(i, 0));
                let mut mixed = SVector::<T, D>::zeros();
                let mut blj = T::one();
                for j in 1..=l.min(top) {
                    blj = blj * from_count::<T>(l - j + 1) / from_count::<T>(j);
                    mixed += out[(k - i) * w + l - j] * (blj * weight(i, j));
                }
                v -= mixed * bki;
            }
            out[k * w + l] = v / w00;
            if !out[k * w + l].iter().all(nalgebra::ComplexField::is_finite) {
                return Err(derivative_overflow(k + l));
            }
        }
    }
    Ok(())
}

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
