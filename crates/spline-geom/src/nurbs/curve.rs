//! NURBS curves: the rational view over a B-spline of homogeneous points.

use super::derivatives::rational_curve_derivatives;
use super::rational::Rational;
use super::removal::check_rational_removal;
use super::weighted::{cartesian_scale, check_result_weights, mapped, weighted_points};
use crate::bezier::bezier_as_bspline;
use crate::bspline::BSpline;
use crate::homogeneous::Homogeneous;
use crate::operations::StructuralCurve;
use crate::structural::check_tolerance;
use nalgebra::SVector;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, MAX_ORDER, Result, Scalar};

/// A NURBS curve in $\mathbb{R}^D$ (seed 004 Definition 6.1):
///
/// $$ R(u) = \frac{\sum_i N_{i,p}(u)\\, w_i P_i}{\sum_i N_{i,p}(u)\\, w_i}, \qquad w_i > 0. $$
///
/// Stored as a [`BSpline`] of [`Homogeneous`] points `(w_i P_i, w_i)`; the Cartesian control
/// points and the weights are views. Weights are validated (positive and finite) on
/// construction, so evaluation never divides by zero.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::NurbsCurve;
/// // The quarter circle (6.1) of seed 004: U = [0,0,0,1,1,1], W = [1, 1, 2].
/// let quarter = NurbsCurve::from_knots(
///     2,
///     vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(1.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(0.0, 1.0)],
///     vec![1.0, 1.0, 2.0],
/// )?;
/// let t: f64 = 0.5; // C(t) = ((1 − t²)/(1 + t²), 2t/(1 + t²))
/// let p = quarter.eval(t)?;
/// assert!((p - Vector2::new((1.0 - t * t) / (1.0 + t * t), 2.0 * t / (1.0 + t * t))).norm() < 1e-15);
/// # Ok::<(), spline_core::Error>(())
/// ```
pub type NurbsCurve<T, const D: usize> = Rational<BSpline<T, Homogeneous<T, D>>, T, D>;

/// A planar NURBS curve.
pub type NurbsCurve2<T = f64> = NurbsCurve<T, 2>;
/// A spatial NURBS curve.
pub type NurbsCurve3<T = f64> = NurbsCurve<T, 3>;

impl<T: Scalar, const D: usize> NurbsCurve<T, D> {
    /// A NURBS curve from a knot vector, Cartesian control points and their weights.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] if the numbers of points, weights and basis functions
    /// differ; [`ErrorKind::InvalidWeight`] for a zero, negative or non-finite weight;
    /// [`ErrorKind::NonFinite`] for a non-finite coordinate.
    pub fn new(
        knots: KnotVector<T>,
        control_points: Vec<SVector<T, D>>,
        weights: Vec<T>,
    ) -> Result<Self> {
        let points = weighted_points(control_points, weights, |i| i.to_string())?;
        Ok(Self::wrap(BSpline::new(knots, points)?))
    }

    /// A NURBS curve from a degree, raw knots, Cartesian control points and weights.
    ///
    /// # Errors
    /// The errors of [`KnotVector::new`] and [`NurbsCurve::new`].
    pub fn from_knots(
        degree: usize,
        knots: Vec<T>,
        control_points: Vec<SVector<T, D>>,
        weights: Vec<T>,
    ) -> Result<Self> {
        Self::new(KnotVector::new(degree, knots)?, control_points, weights)
    }

    /// A non-rational B-spline curve as a NURBS curve with unit weights.
    #[must_use]
    pub fn from_bspline(curve: &BSpline<T, SVector<T, D>>) -> Self {
        Self::wrap(curve.map_control_points(|p| Homogeneous::new(*p, T::one())))
    }

    /// The degree `p`.
    #[inline]
    #[must_use]
    pub fn degree(&self) -> usize {
        self.container.degree()
    }

    /// The knot vector.
    #[inline]
    #[must_use]
    pub fn knots(&self) -> &KnotVector<T> {
        self.container.knots()
    }

    /// The parametric domain $[u_p, u_n]$.
    #[inline]
    #[must_use]
    pub fn domain(&self) -> (T, T) {
        self.container.domain()
    }

    /// The number of control points.
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        self.container.control_points().len()
    }

    /// Always `false`: a curve has at least `p + 1` control points.
    #[inline]
    #[must_use]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Whether all weights are equal: the curve is then a polynomial B-spline curve.
    #[must_use]
    pub fn is_polynomial(&self) -> bool {
        let w = self.container.control_points()[0].weight;
        self.container
            .control_points()
            .iter()
            .all(|h| h.weight == w)
    }

    /// The non-rational B-spline curve with the same control points, if all weights are
    /// equal ([`NurbsCurve::is_polynomial`]).
    #[must_use]
    pub fn to_bspline(&self) -> Option<BSpline<T, SVector<T, D>>> {
        self.is_polynomial()
            .then(|| self.container.map_control_points(Homogeneous::project))
    }

    /// Applies an affine map to the Cartesian control points, keeping the weights: by the
    /// affine invariance of NURBS this maps the curve. (A non-affine `f` gives a curve
    /// that is not the image of this one.)
    #[must_use]
    pub fn map_control_points<const E: usize>(
        &self,
        mut f: impl FnMut(&SVector<T, D>) -> SVector<T, E>,
    ) -> NurbsCurve<T, E> {
        NurbsCurve::new_unchecked(self.container.map_control_points(|h| mapped(h, &mut f)))
    }

    /// The point $R(u)$: the point of the homogeneous B-spline ([`BSpline::eval`], with its
    /// cached piecewise polynomial form after as many calls as spans), then the projection
    /// (6.5).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    #[inline]
    pub fn eval(&self, u: T) -> Result<SVector<T, D>> {
        Ok(self.container.eval(u)?.project())
    }

    /// Evaluates at many parameters.
    ///
    /// # Errors
    /// As [`NurbsCurve::eval_many_into`].
    pub fn eval_many(&self, params: &[T]) -> Result<Vec<SVector<T, D>>> {
        let mut out = vec![SVector::zeros(); params.len()];
        self.eval_many_into(params, &mut out)?;
        Ok(out)
    }

    /// Evaluates at many parameters into `out` (same length), in any order and without
    /// allocating: the batch kernel of [`BSpline::eval_many_into`] in homogeneous space
    /// (the cached piecewise polynomial form), then the projection.
    /// All parameters are checked before anything is written.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use spline_geom::NurbsCurve;
    /// let quarter = NurbsCurve::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    ///     vec![Vector2::new(1.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(0.0, 1.0)],
    ///     vec![1.0, 1.0, 2.0])?;
    /// let params = [0.9, 0.1, 0.5];
    /// let mut out = [Vector2::<f64>::zeros(); 3];
    /// quarter.eval_many_into(&params, &mut out)?;
    /// for (p, &u) in out.iter().zip(&params) {
    ///     assert!((p - quarter.eval(u)?).norm() < 1e-15);
    ///     assert!((p.norm() - 1.0).abs() < 1e-15);
    /// }
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] if the lengths differ; [`ErrorKind::NonFinite`] or
    /// [`ErrorKind::OutOfDomain`] for the first bad parameter.
    pub fn eval_many_into(&self, params: &[T], out: &mut [SVector<T, D>]) -> Result<()> {
        self.container.eval_many_map(params, out, |h| h.project())
    }

    /// $R(u), R'(u), …, R^{(k)}(u)$ with `k = out.len() − 1` (The NURBS Book A4.2), written
    /// into `out`. Unlike polynomial curves, rational derivatives above the degree are not
    /// zero; order `k` costs `O(p)` operations (the homogeneous derivatives above the degree
    /// vanish). No heap allocation.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for the parameter;
    /// [`ErrorKind::NonFinite`] when a derivative is too large for the scalar type (rational
    /// derivatives of order `k` grow like `k!`; `f64` overflows near order 170).
    pub fn derivatives_into(&self, u: T, out: &mut [SVector<T, D>]) -> Result<()> {
        let span = self.container.span_of(u)?;
        if out.is_empty() {
            return Ok(());
        }
        let mut stack = [Homogeneous::<T, D>::origin(); MAX_ORDER];
        let hom = &mut stack[..out.len().min(self.degree() + 1)];
        self.container.derivatives_in_span(span, u, hom);
        rational_curve_derivatives(hom, out)
    }

    /// The derivatives $R^{(j)}(u)$ for `j = 0 … order`.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use spline_geom::NurbsCurve;
    /// let quarter = NurbsCurve::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    ///     vec![Vector2::new(1.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(0.0, 1.0)],
    ///     vec![1.0, 1.0, 2.0])?;
    /// // C'(0) = (0, 2) for C(t) = ((1 − t²)/(1 + t²), 2t/(1 + t²)).
    /// assert!((quarter.derivatives(0.0, 1)?[1] - Vector2::new(0.0, 2.0)).norm() < 1e-15);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] above [`spline_core::MAX_DERIVATIVE_ORDER`]; the errors
    /// of [`NurbsCurve::derivatives_into`].
    pub fn derivatives(&self, u: T, order: usize) -> Result<Vec<SVector<T, D>>> {
        spline_core::check_derivative_order(order)?;
        let mut out = vec![SVector::zeros(); order + 1];
        self.derivatives_into(u, &mut out)?;
        Ok(out)
    }

    /// Inserts the knot `u` `times` times, in homogeneous space; the curve is unchanged.
    ///
    /// # Errors
    /// As [`BSpline::insert_knot`].
    pub fn insert_knot(&self, u: T, times: usize) -> Result<Self> {
        Self::checked(self.container.insert_knot(u, times)?)
    }

    /// Inserts many knots at once (knot refinement), in homogeneous space.
    ///
    /// # Errors
    /// As [`BSpline::refine`].
    pub fn refine(&self, knots: &[T]) -> Result<Self> {
        Self::checked(self.container.refine(knots)?)
    }

    /// [`NurbsCurve::insert_knot`] in place ([`BSpline::insert_knot_mut`] on the homogeneous
    /// points). The new weights are convex combinations of positive ones: always valid.
    ///
    /// # Errors
    /// As [`BSpline::insert_knot`]; the curve is unchanged on error.
    pub fn insert_knot_mut(&mut self, u: T, times: usize) -> Result<()> {
        self.container.insert_knot_mut(u, times)?;
        debug_assert!(check_result_weights(self.container.control_points()).is_ok());
        self.resync();
        Ok(())
    }

    /// [`NurbsCurve::refine`] in place ([`BSpline::refine_mut`] on the homogeneous points).
    ///
    /// # Errors
    /// As [`BSpline::refine`]; the curve is unchanged on error.
    pub fn refine_mut(&mut self, knots: &[T]) -> Result<()> {
        self.container.refine_mut(knots)?;
        debug_assert!(check_result_weights(self.container.control_points()).is_ok());
        self.resync();
        Ok(())
    }

    /// Removes the interior knot `u` `times` times if the curve moves by at most `tolerance`
    /// (absolute, in Cartesian space). The removal runs in homogeneous space; the change of
    /// the rational curve is then bounded exactly (see [`BSpline::remove_knot_within`]) by
    /// re-inserting the knots: homogeneous control points within $\delta$ of the original
    /// ones move the curve by at most $\delta (1 + |P|_{max}) / w_{min}$ (The NURBS Book
    /// (5.30)). That bound grows with the curve's distance from the origin; where it exceeds
    /// the tolerance, the two rational curves are compared directly over the spans the
    /// removal changes (64 samples per span, the largest refined by golden-section search),
    /// and that deviation decides (and is the one an error reports).
    ///
    /// # Errors
    /// As [`BSpline::remove_knot_within`]; [`ErrorKind::ToleranceExceeded`] also when the
    /// removal would make a weight non-positive.
    pub fn remove_knot_within(&self, u: T, times: usize, tolerance: T) -> Result<Self> {
        check_tolerance(tolerance)?;
        let removed = self.container.reduced(&self.knots().removed(u, times)?)?;
        let back = removed.insert_knot(u, times)?;
        let bounded = check_rational_removal(
            self.container.control_points(),
            removed.control_points(),
            back.control_points(),
            (u, times),
            tolerance,
        );
        match bounded {
            Ok(()) => Self::checked(removed),
            // The bound of (5.30) grows with the distance of the curve from the origin and
            // with 1/w_min; when it refuses, the rational curves themselves are compared.
            Err(_)
                if removed
                    .control_points()
                    .iter()
                    .all(|h| h.weight > T::zero()) =>
            {
                let candidate = Self::checked(removed)?;
                let deviation = self.sampled_deviation(&candidate, u)?;
                if deviation <= tolerance {
                    Ok(candidate)
                } else {
                    Err(crate::structural::tolerance_exceeded(
                        u,
                        times,
                        Some(deviation),
                        tolerance,
                    ))
                }
            }
            Err(e) => Err(e),
        }
    }

    /// The largest distance between this curve and `other` (the same curve with the knot
    /// `u` removed) over the spans the removal changes (`p + 1` spans on each side of `u`):
    /// 64 samples per span, then the largest refined by golden-section search between its
    /// neighbours. The distance is smooth inside a span, so the refined maximum is the true
    /// one to the search's precision.
    fn sampled_deviation(&self, other: &Self, u: T) -> Result<T> {
        let knots = self.knots().knots();
        let p = self.degree();
        let first = knots.partition_point(|&k| k < u);
        let last = knots.partition_point(|&k| k <= u);
        let lo = knots[first.saturating_sub(p + 1).max(p)];
        let hi = knots[(last + p).min(knots.len() - p - 1)];
        let distance = |t: T| -> Result<T> { Ok((self.eval(t)? - other.eval(t)?).norm()) };
        let mut best = (T::zero(), lo);
        let spans: Vec<T> = knots
            .iter()
            .copied()
            .filter(|&k| k >= lo && k <= hi)
            .collect();
        let samples = 64;
        let step_of = |a: T, b: T| (b - a) / spline_core::from_count::<T>(samples);
        for pair in spans.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            if b <= a {
                continue;
            }
            let step = step_of(a, b);
            for i in 0..=samples {
                let t = (a + step * spline_core::from_count::<T>(i)).min(b);
                let d = distance(t)?;
                if d > best.0 {
                    best = (d, t);
                }
            }
        }
        // Golden-section refinement of the largest sample within one step on each side.
        let (mut a, mut b) = (best.1, best.1);
        for pair in spans.windows(2) {
            if best.1 >= pair[0] && best.1 <= pair[1] && pair[1] > pair[0] {
                let step = step_of(pair[0], pair[1]);
                a = (best.1 - step).max(pair[0]);
                b = (best.1 + step).min(pair[1]);
            }
        }
        let [(fc, _), (fd, _)] = spline_core::golden_section_max(distance, (a, b), T::zero())?;
        Ok(best.0.max(fc).max(fd))
    }

    /// [`NurbsCurve::remove_knot_within`] with a tolerance relative to the size of the
    /// control polygon (its largest Cartesian coordinate magnitude, or 1 if that is smaller).
    ///
    /// # Errors
    /// As [`NurbsCurve::remove_knot_within`].
    pub fn remove_knot(&self, u: T, times: usize, relative_tolerance: T) -> Result<Self> {
        let scale = cartesian_scale(self.container.control_points());
        self.remove_knot_within(u, times, relative_tolerance * scale)
    }

    /// Raises the degree by `times`, in homogeneous space.
    ///
    /// # Errors
    /// As [`BSpline::elevate_degree`].
    pub fn elevate_degree(&self, times: usize) -> Result<Self> {
        Self::checked(self.container.elevate_degree(times)?)
    }

    /// Splits at `u` into two curves clamped at `u`.
    ///
    /// # Errors
    /// As [`BSpline::split`].
    pub fn split(&self, u: T) -> Result<(Self, Self)> {
        let (a, b) = self.container.split(u)?;
        Ok((Self::checked(a)?, Self::checked(b)?))
    }

    /// The same curve with clamped knots.
    #[must_use]
    pub fn clamped(&self) -> Self {
        Self::new_unchecked(self.container.clamped())
    }

    /// The same curve traversed backwards on the same domain.
    #[must_use]
    pub fn reversed(&self) -> Self {
        Self::new_unchecked(self.container.reversed())
    }

    /// The same curve on the domain `[a, b]`.
    ///
    /// # Errors
    /// As [`BSpline::reparametrized`].
    pub fn reparametrized(&self, a: T, b: T) -> Result<Self> {
        Ok(Self::new_unchecked(self.container.reparametrized(a, b)?))
    }

    /// The rational Bézier segments, one per non-empty knot span, each a clamped NURBS curve
    /// on its span.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidWeight`] when a weight underflows to zero (weights spanning
    /// hundreds of orders of magnitude).
    pub fn bezier_segments(&self) -> Result<Vec<Self>> {
        self.container
            .bezier_segments()
            .into_iter()
            .map(|b| Self::checked(bezier_as_bspline(&b)))
            .collect()
    }
}

impl<T: Scalar, const D: usize> StructuralCurve<T> for NurbsCurve<T, D> {
    fn insert_knot(&self, u: T, times: usize) -> Result<Self> {
        NurbsCurve::insert_knot(self, u, times)
    }

    fn refine(&self, knots: &[T]) -> Result<Self> {
        NurbsCurve::refine(self, knots)
    }

    fn remove_knot(&self, u: T, times: usize, relative_tolerance: T) -> Result<Self> {
        NurbsCurve::remove_knot(self, u, times, relative_tolerance)
    }

    fn elevate_degree(&self, times: usize) -> Result<Self> {
        NurbsCurve::elevate_degree(self, times)
    }

    fn split(&self, u: T) -> Result<(Self, Self)> {
        NurbsCurve::split(self, u)
    }

    fn bezier_curves(&self) -> Result<Vec<Self>> {
        self.bezier_segments()
    }

    fn derivative_curve(&self, _order: usize) -> Result<Self> {
        Err(Error::new(
            ErrorKind::Unsupported,
            "the derivative of a NURBS curve is not a NURBS curve on the same knots (its values are NurbsCurve::derivatives; `spline eval --derivatives K`)",
        ))
    }
}
