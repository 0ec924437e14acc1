//! NURBS surfaces: the rational view over a tensor-product surface of homogeneous points.

use super::curve::NurbsCurve;
use super::derivatives::{homogeneous_square, rational_surface_derivatives};
use super::rational::Rational;
use super::removal::{check_rational_removal, unbounded};
use super::weighted::{cartesian_scale, mapped, weighted_points};
use crate::homogeneous::Homogeneous;
use crate::operations::StructuralSurface;
use crate::structural::check_tolerance;
use crate::surface::{Direction, Surface, flatten_net};
use nalgebra::SVector;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar};

/// A NURBS surface in $\mathbb{R}^D$ (seed 004 (6.11), (6.14)):
///
/// $$ S(u, v) = \frac{\sum_{i,j} N_{i,p}(u) N_{j,q}(v)\\, w_{ij} P_{ij}}
///                   {\sum_{i,j} N_{i,p}(u) N_{j,q}(v)\\, w_{ij}}, \qquad w_{ij} > 0. $$
///
/// Stored as a [`Surface`] of [`Homogeneous`] points; the net is row-major, `i` along `u`.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsSurface;
/// let sphere = NurbsSurface::sphere(Vector3::new(1.0f64, 2.0, 3.0), 2.0)?;
/// let p = sphere.eval(0.3, 0.8)?;
/// assert!(((p - Vector3::new(1.0, 2.0, 3.0)).norm() - 2.0).abs() < 1e-14);
/// # Ok::<(), spline_core::Error>(())
/// ```
pub type NurbsSurface<T, const D: usize> = Rational<Surface<T, Homogeneous<T, D>>, T, D>;

/// A NURBS surface in space.
pub type NurbsSurface3<T = f64> = NurbsSurface<T, 3>;

impl<T: Scalar, const D: usize> NurbsSurface<T, D> {
    /// A NURBS surface from two knot vectors, the row-major Cartesian control net
    /// (`[i * n_v + j]` is $P_{ij}$) and the weights in the same layout.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] if the sizes do not match; [`ErrorKind::InvalidWeight`];
    /// [`ErrorKind::NonFinite`].
    pub fn new(
        knots_u: KnotVector<T>,
        knots_v: KnotVector<T>,
        control_points: Vec<SVector<T, D>>,
        weights: Vec<T>,
    ) -> Result<Self> {
        let nv = knots_v.num_basis();
        let points = weighted_points(control_points, weights, |k| {
            format!("({}, {})", k / nv, k % nv)
        })?;
        Ok(Self::wrap(Surface::new(knots_u, knots_v, points)?))
    }

    /// A NURBS surface from a net of rows `net[i][j]` and weights `weights[i][j]`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] if the net or the weights do not have `n_u` rows of `n_v`
    /// entries; the errors of [`NurbsSurface::new`].
    pub fn from_net(
        knots_u: KnotVector<T>,
        knots_v: KnotVector<T>,
        net: Vec<Vec<SVector<T, D>>>,
        weights: Vec<Vec<T>>,
    ) -> Result<Self> {
        let points = flatten_net(&knots_u, &knots_v, net, "control points")?;
        let weights = flatten_net(&knots_u, &knots_v, weights, "weights")?;
        Self::new(knots_u, knots_v, points, weights)
    }

    /// A non-rational surface as a NURBS surface with unit weights.
    #[must_use]
    pub fn from_surface(surface: &Surface<T, SVector<T, D>>) -> Self {
        Self::wrap(surface.map_control_points(|p| Homogeneous::new(*p, T::one())))
    }

    /// The degrees `(p, q)`.
    #[inline]
    #[must_use]
    pub fn degrees(&self) -> (usize, usize) {
        self.container.degrees()
    }

    /// The degree in one direction.
    #[inline]
    #[must_use]
    pub fn degree(&self, direction: Direction) -> usize {
        self.container.degree(direction)
    }

    /// The knot vector in `u`.
    #[inline]
    #[must_use]
    pub fn knots_u(&self) -> &KnotVector<T> {
        self.container.knots_u()
    }

    /// The knot vector in `v`.
    #[inline]
    #[must_use]
    pub fn knots_v(&self) -> &KnotVector<T> {
        self.container.knots_v()
    }

    /// The knot vector in one direction.
    #[inline]
    #[must_use]
    pub fn knots(&self, direction: Direction) -> &KnotVector<T> {
        self.container.knots(direction)
    }

    /// The size `(n_u, n_v)` of the control net.
    #[inline]
    #[must_use]
    pub fn net_size(&self) -> (usize, usize) {
        self.container.net_size()
    }

    /// The parametric domain `((u_min, u_max), (v_min, v_max))`.
    #[inline]
    #[must_use]
    pub fn domain(&self) -> ((T, T), (T, T)) {
        self.container.domain()
    }

    /// The Cartesian control point $P_{ij}$.
    ///
    /// # Panics
    /// If `i ≥ n_u` or `j ≥ n_v`.
    #[must_use]
    pub fn control_point(&self, i: usize, j: usize) -> SVector<T, D> {
        self.container.control_point(i, j).project()
    }

    /// The weight $w_{ij}$.
    ///
    /// # Panics
    /// If `i ≥ n_u` or `j ≥ n_v`.
    #[must_use]
    pub fn weight(&self, i: usize, j: usize) -> T {
        self.container.control_point(i, j).weight
    }

    /// Applies an affine map to the Cartesian control points, keeping the weights (this maps
    /// the surface by affine invariance).
    #[must_use]
    pub fn map_control_points<const E: usize>(
        &self,
        mut f: impl FnMut(&SVector<T, D>) -> SVector<T, E>,
    ) -> NurbsSurface<T, E> {
        NurbsSurface::new_unchecked(self.container.map_control_points(|h| mapped(h, &mut f)))
    }

    /// The point $S(u, v)$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    #[inline]
    pub fn eval(&self, u: T, v: T) -> Result<SVector<T, D>> {
        Ok(self.container.eval(u, v)?.project())
    }

    /// All rational partial derivatives $\partial^{k+l} S / \partial u^k \partial v^l$,
    /// `0 ≤ k, l ≤ order`, into `out[k * (order + 1) + l]` (The NURBS Book A4.4 on the full
    /// square of orders). The homogeneous derivatives vanish above the degrees, so order
    /// `(k, l)` costs `O(p q)` operations; the working memory is bounded by the degrees.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless `out.len() = (order + 1)²`;
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for the parameters;
    /// [`ErrorKind::NonFinite`] when a derivative is too large for the scalar type.
    pub fn derivatives_into(
        &self,
        u: T,
        v: T,
        order: usize,
        out: &mut [SVector<T, D>],
    ) -> Result<()> {
        let (top, len) = homogeneous_square(order, self.container.degrees(), out.len())?;
        let (su, sv) = self.container.find_spans(u, v)?;
        // On the stack up to order 5 (the usual case), on the heap above.
        let mut stack = [Homogeneous::<T, D>::origin(); 36];
        let mut heap = Vec::new();
        let hom = if len <= stack.len() {
            &mut stack[..len]
        } else {
            heap.resize(len, Homogeneous::<T, D>::origin());
            &mut heap[..]
        };
        self.container.derivatives_in_spans(su, sv, u, v, top, hom);
        rational_surface_derivatives(hom, top, order, out)
    }

    /// The rational partial derivatives `[k][l]` for `0 ≤ k, l ≤ order`.
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] above [`spline_core::MAX_DERIVATIVE_ORDER`]; the errors
    /// of [`NurbsSurface::derivatives_into`].
    pub fn derivatives(&self, u: T, v: T, order: usize) -> Result<Vec<Vec<SVector<T, D>>>> {
        spline_core::check_derivative_order(order)?;
        let mut flat = vec![SVector::zeros(); (order + 1) * (order + 1)];
        self.derivatives_into(u, v, order, &mut flat)?;
        Ok(flat.chunks_exact(order + 1).map(<[_]>::to_vec).collect())
    }

    /// Evaluates on the grid `us × vs` with the tensor fast path of
    /// [`Surface::eval_grid_into`] in homogeneous space; `[a * vs.len() + b]` $= S(u_a, v_b)$.
    ///
    /// # Errors
    /// As [`Surface::eval_grid_into`].
    pub fn eval_grid(&self, us: &[T], vs: &[T]) -> Result<Vec<SVector<T, D>>> {
        Ok(self
            .container
            .eval_grid(us, vs)?
            .iter()
            .map(Homogeneous::project)
            .collect())
    }

    /// The iso-parametric curve `v ↦ S(u, v)` at fixed `u`, a NURBS curve.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn curve_at_u(&self, u: T) -> Result<NurbsCurve<T, D>> {
        Ok(NurbsCurve::new_unchecked(self.container.curve_at_u(u)?))
    }

    /// The iso-parametric curve `u ↦ S(u, v)` at fixed `v`, a NURBS curve.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn curve_at_v(&self, v: T) -> Result<NurbsCurve<T, D>> {
        Ok(NurbsCurve::new_unchecked(self.container.curve_at_v(v)?))
    }

    /// The same surface with clamped knots in both directions.
    #[must_use]
    pub fn clamped(&self) -> Self {
        Self::new_unchecked(self.container.clamped())
    }

    /// The same surface traversed backwards in `direction`.
    #[must_use]
    pub fn reversed(&self, direction: Direction) -> Self {
        Self::new_unchecked(self.container.reversed(direction))
    }

    /// The same surface with the domain of `direction` mapped onto `[a, b]`.
    ///
    /// # Errors
    /// As [`Surface::reparametrized`].
    pub fn reparametrized(&self, direction: Direction, a: T, b: T) -> Result<Self> {
        Ok(Self::new_unchecked(
            self.container.reparametrized(direction, a, b)?,
        ))
    }

    /// The surface with `u` and `v` exchanged.
    #[must_use]
    pub fn transposed(&self) -> Self {
        Self::new_unchecked(self.container.transposed())
    }
}

/// Structural operations in homogeneous space (the algorithms of [`Surface`] on the
/// homogeneous net), with the change of the rational surface bounded for removals.
impl<T: Scalar, const D: usize> StructuralSurface<T> for NurbsSurface<T, D> {
    /// Inserts the knot `t` `times` times in `direction`, in homogeneous space.
    ///
    /// # Errors
    /// As [`Surface::insert_knot`].
    fn insert_knot(&self, direction: Direction, t: T, times: usize) -> Result<Self> {
        Self::checked(self.container.insert_knot(direction, t, times)?)
    }

    /// Inserts many knots in `direction`, in homogeneous space.
    ///
    /// # Errors
    /// As [`Surface::refine`].
    fn refine(&self, direction: Direction, knots: &[T]) -> Result<Self> {
        Self::checked(self.container.refine(direction, knots)?)
    }

    /// Removes the interior knot `t` of `direction` `times` times if the surface moves by at
    /// most `tolerance` (absolute, Cartesian), bounded as in
    /// [`NurbsCurve::remove_knot_within`].
    ///
    /// # Errors
    /// As [`NurbsCurve::remove_knot_within`].
    fn remove_knot_within(&self, dir: Direction, t: T, times: usize, tol: T) -> Result<Self> {
        check_tolerance(tol)?;
        let removed = self
            .container
            .remove_knot_within(dir, t, times, unbounded())?;
        let back = removed.insert_knot(dir, t, times)?;
        check_rational_removal(
            self.container.control_points(),
            removed.control_points(),
            back.control_points(),
            (t, times),
            tol,
        )
        .map_err(|e| e.context(format_args!("dir {dir}")))?;
        Self::checked(removed)
    }

    /// [`NurbsSurface::remove_knot_within`] with a tolerance relative to the size of the
    /// control net.
    ///
    /// # Errors
    /// As [`NurbsCurve::remove_knot_within`].
    fn remove_knot(&self, dir: Direction, t: T, times: usize, relative: T) -> Result<Self> {
        let scale = cartesian_scale(self.container.control_points());
        self.remove_knot_within(dir, t, times, relative * scale)
    }

    /// Raises the degree in `direction` by `times`, in homogeneous space.
    ///
    /// # Errors
    /// As [`Surface::elevate_degree`].
    fn elevate_degree(&self, direction: Direction, times: usize) -> Result<Self> {
        Self::checked(self.container.elevate_degree(direction, times)?)
    }

    /// Splits at `t` in `direction` into two surfaces clamped at `t`.
    ///
    /// # Errors
    /// As [`Surface::split`].
    fn split(&self, direction: Direction, t: T) -> Result<(Self, Self)> {
        let (a, b) = self.container.split(direction, t)?;
        Ok((Self::checked(a)?, Self::checked(b)?))
    }

    /// The rational Bézier patches, `[a][b]` over the `a`-th non-empty span in `u` and the
    /// `b`-th in `v`.
    ///
    /// # Errors
    /// As [`NurbsCurve::bezier_segments`].
    fn bezier_patches(&self) -> Result<Vec<Vec<Self>>> {
        self.container
            .bezier_patches()
            .into_iter()
            .map(|row| row.into_iter().map(Self::checked).collect())
            .collect()
    }

    fn derivative_surfaces(&self, _order: usize) -> Result<(Self, Self)> {
        Err(Error::new(
            ErrorKind::Unsupported,
            "the derivative of a NURBS surface is not a NURBS surface on the same knots (its values are NurbsSurface::derivatives; `spline eval --derivatives K`)",
        ))
    }
}
