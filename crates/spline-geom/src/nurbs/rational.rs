//! The rational view over a container of homogeneous points, and the containers it views.

use super::weighted::{cartesian, check_result_weights, weights_of};
use crate::bspline::BSpline;
use crate::homogeneous::{Homogeneous, check_weights};
use crate::surface::Surface;
use nalgebra::SVector;
#[cfg(doc)]
use spline_core::ErrorKind;
use spline_core::{Result, Scalar};

/// A container of homogeneous points: the B-spline curve behind a [`NurbsCurve`], the
/// surface behind a [`NurbsSurface`].
///
/// [`NurbsCurve`]: crate::NurbsCurve
/// [`NurbsSurface`]: crate::NurbsSurface
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
///
/// [`NurbsCurve`]: crate::NurbsCurve
/// [`NurbsSurface`]: crate::NurbsSurface
#[derive(Clone, Debug, PartialEq)]
pub struct Rational<C, T, const D: usize> {
    pub(super) container: C,
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
    pub(super) fn wrap(container: C) -> Self {
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
