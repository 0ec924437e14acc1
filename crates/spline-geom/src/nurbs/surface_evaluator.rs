//! One-point evaluation of a NURBS surface: the [`SurfaceEvaluator`] of its homogeneous
//! surface, then the projection (points) or The NURBS Book A4.4 (derivatives).

use super::derivatives::{homogeneous_square, rational_surface_derivatives};
use super::surface::NurbsSurface;
use crate::homogeneous::Homogeneous;
use crate::surface::{SMALL_SQUARE, SurfaceEvaluator};
use nalgebra::SVector;
use spline_core::{ControlPoint, Result, Scalar};

/// One-point evaluation of a [`NurbsSurface`] ([`NurbsSurface::evaluator`]): the
/// [`SurfaceEvaluator`] of its homogeneous surface, then the projection (points) or The
/// NURBS Book A4.4 (derivatives).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsSurface;
/// let sphere = NurbsSurface::sphere(Vector3::new(1.0f64, 2.0, 3.0), 2.0)?;
/// let evaluator = sphere.evaluator();
/// let p = evaluator.eval(0.3, 0.8)?;
/// assert!(((p - Vector3::new(1.0, 2.0, 3.0)).norm() - 2.0).abs() < 1e-14);
/// # Ok::<(), spline_core::Error>(())
/// ```
pub struct NurbsSurfaceEvaluator<'a, T, const D: usize> {
    surface: &'a NurbsSurface<T, D>,
    homogeneous: SurfaceEvaluator<'a, T, Homogeneous<T, D>>,
}

impl<T: Scalar, const D: usize> NurbsSurface<T, D> {
    /// An evaluator for many one-point calls (see [`NurbsSurfaceEvaluator`]).
    #[must_use]
    pub fn evaluator(&self) -> NurbsSurfaceEvaluator<'_, T, D> {
        NurbsSurfaceEvaluator {
            surface: self,
            homogeneous: self.homogeneous().evaluator(),
        }
    }
}

impl<T: Scalar, const D: usize> NurbsSurfaceEvaluator<'_, T, D> {
    /// Whether the homogeneous surface's piecewise polynomial form is in use.
    #[must_use]
    pub fn has_form(&self) -> bool {
        self.homogeneous.has_form()
    }

    /// The point $S(u, v)$.
    ///
    /// # Errors
    /// As [`NurbsSurface::eval`].
    #[inline]
    pub fn eval(&self, u: T, v: T) -> Result<SVector<T, D>> {
        Ok(self.homogeneous.eval(u, v)?.project())
    }

    /// The rational partial derivatives on the square `0 ≤ k, l ≤ order` into
    /// `out[k * (order + 1) + l]`, as [`NurbsSurface::derivatives_into`]. No heap allocation
    /// up to order 5.
    ///
    /// # Errors
    /// As [`NurbsSurface::derivatives_into`].
    pub fn derivatives_into(
        &self,
        u: T,
        v: T,
        order: usize,
        out: &mut [SVector<T, D>],
    ) -> Result<()> {
        let (top, len) =
            homogeneous_square(order, self.homogeneous.surface().degrees(), out.len())?;
        let mut stack = [Homogeneous::<T, D>::origin(); SMALL_SQUARE];
        if len > SMALL_SQUARE
            || !self
                .homogeneous
                .derivatives_unchecked(u, v, top, &mut stack[..len])
        {
            return self.surface.derivatives_into(u, v, order, out);
        }
        rational_surface_derivatives(&stack[..len], top, order, out)
    }
}
