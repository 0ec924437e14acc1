//! NURBS curves and surfaces: rational views over B-spline containers of homogeneous points.
//!
//! A NURBS curve is the central projection of a B-spline curve in $\mathbb{R}^{D+1}$ whose
//! control points are $(w_i P_i, w_i)$ (seed 004 (6.4)–(6.5)). Evaluation is evaluation in
//! homogeneous space followed by the projection; rational derivatives follow from Leibniz's
//! rule (The NURBS Book A4.2 and A4.4); every structural algorithm (insertion, refinement,
//! removal, elevation, splitting) runs unchanged on the homogeneous container.

use crate::bezier::bezier_as_bspline;
use crate::bspline::BSpline;
use crate::homogeneous::{Homogeneous, check_weight, check_weights};
use crate::structural::relative_scale;
use crate::surface::{Direction, Surface, flatten_net};
use nalgebra::{RealField, SVector};
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, MAX_ORDER, Result, Scalar, cast, from_count, to_f64,
};

/// A NURBS curve in $\mathbb{R}^D$ (seed 004 Definition 6.1):
///
/// $$ R(u) = \frac{\sum_i N_{i,p}(u)\, w_i P_i}{\sum_i N_{i,p}(u)\, w_i}, \qquad w_i > 0. $$
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
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsCurve<T, const D: usize> {
    curve: BSpline<T, Homogeneous<T, D>>,
    /// The Cartesian control points $P_i$ (a view of `curve`, kept so that
    /// [`NurbsCurve::control_points`] is a slice as for every other container).
    points: Vec<SVector<T, D>>,
    /// The weights $w_i$ (likewise).
    weights: Vec<T>,
}

/// A planar NURBS curve.
pub type NurbsCurve2<T = f64> = NurbsCurve<T, 2>;
/// A spatial NURBS curve.
pub type NurbsCurve3<T = f64> = NurbsCurve<T, 3>;

fn check_point<T: Scalar, const D: usize>(
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
fn weighted_points<T: Scalar, const D: usize>(
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
fn cartesian<T: Scalar, const D: usize>(points: &[Homogeneous<T, D>]) -> Vec<SVector<T, D>> {
    points.iter().map(Homogeneous::project).collect()
}

/// The weights $w_k$ of homogeneous points.
fn weights_of<T: Scalar, const D: usize>(points: &[Homogeneous<T, D>]) -> Vec<T> {
    points.iter().map(|h| h.weight).collect()
}

/// The homogeneous point of `f(P)` with the weight of `h = (w P, w)`.
fn mapped<T: Scalar, const D: usize, const E: usize>(
    h: &Homogeneous<T, D>,
    f: &mut impl FnMut(&SVector<T, D>) -> SVector<T, E>,
) -> Homogeneous<T, E> {
    Homogeneous::new(f(&h.project()) * h.weight, h.weight)
}

/// The scale of a relative removal tolerance: the largest Cartesian coordinate magnitude,
/// or 1 if that is smaller.
fn cartesian_scale<T: Scalar, const D: usize>(points: &[Homogeneous<T, D>]) -> T {
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
fn rational_curve_derivatives<T: Scalar, const D: usize>(
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
fn check_result_weights<T: Scalar, const D: usize>(points: &[Homogeneous<T, D>]) -> Result<()> {
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

fn derivative_overflow(order: usize) -> Error {
    Error::new(
        ErrorKind::NonFinite,
        format!(
            "the rational derivative of order {order} is too large for floating point (rational derivatives grow like order!)"
        ),
    )
}

/// Rational partial derivatives of a surface on the square `0 ≤ k, l ≤ order` from the
/// homogeneous ones (The NURBS Book A4.4). `hom` holds the homogeneous derivatives on the
/// square `0 ≤ i, j ≤ top` (row-major, rows of `top + 1`; those above are zero); `out` is
/// row-major with rows of `order + 1`.
///
/// # Errors
/// [`ErrorKind::NonFinite`] when a derivative leaves the range of the scalar type.
fn rational_surface_derivatives<T: Scalar, const D: usize>(
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
fn rational_deviation_bound<T: Scalar, const D: usize>(
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

fn check_tolerance<T: Scalar>(tolerance: T) -> Result<()> {
    if tolerance >= T::zero() {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("tolerance must be non-negative, got {}", to_f64(tolerance)),
        ))
    }
}

/// Accepts a knot removal done in homogeneous space if the rational shape moves by at most
/// `tolerance` and every weight stays positive: `back` is `removed` with the knots
/// re-inserted, compared with `original` by [`rational_deviation_bound`].
fn check_rational_removal<T: Scalar, const D: usize>(
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
        _ => Err(exceeded(t, times, bound.filter(|_| weights_ok), tolerance)),
    }
}

fn exceeded<T: Scalar>(t: T, times: usize, bound: Option<T>, tolerance: T) -> Error {
    let what = match bound {
        Some(b) => format!("by up to {:.3e}", to_f64(b)),
        None => "and make a weight non-positive".to_owned(),
    };
    Error::new(
        ErrorKind::ToleranceExceeded,
        format!(
            "removing knot {} {times} time(s) would move the shape {what}, more than the tolerance {:.3e}",
            to_f64(t),
            to_f64(tolerance)
        ),
    )
}

/// A tolerance so large that the homogeneous removal never refuses: the rational check is
/// done afterwards.
fn unbounded<T: Scalar>() -> T {
    T::max_value().unwrap_or_else(|| cast(f64::MAX))
}

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

    /// A NURBS curve from its homogeneous container.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidWeight`] unless every weight is positive and finite.
    pub fn from_homogeneous(curve: BSpline<T, Homogeneous<T, D>>) -> Result<Self> {
        check_weights(curve.control_points().iter().map(|h| h.weight))?;
        Ok(Self::wrap(curve))
    }

    /// The curve of a homogeneous container with positive weights, with its views.
    fn wrap(curve: BSpline<T, Homogeneous<T, D>>) -> Self {
        Self {
            points: cartesian(curve.control_points()),
            weights: weights_of(curve.control_points()),
            curve,
        }
    }

    /// A non-rational B-spline curve as a NURBS curve with unit weights.
    #[must_use]
    pub fn from_bspline(curve: &BSpline<T, SVector<T, D>>) -> Self {
        Self::wrap(curve.map_control_points(|p| Homogeneous::new(*p, T::one())))
    }

    pub(crate) fn new_unchecked(curve: BSpline<T, Homogeneous<T, D>>) -> Self {
        debug_assert!(curve.control_points().iter().all(|h| h.weight > T::zero()));
        Self::wrap(curve)
    }

    /// The result of a structural operation in homogeneous space: positive weights in theory
    /// (positive combinations of positive weights), but weights spanning hundreds of orders of
    /// magnitude can underflow to zero.
    fn checked(curve: BSpline<T, Homogeneous<T, D>>) -> Result<Self> {
        check_result_weights(curve.control_points())?;
        Ok(Self::wrap(curve))
    }

    /// The homogeneous B-spline curve (6.4) whose projection this curve is.
    #[inline]
    #[must_use]
    pub fn homogeneous(&self) -> &BSpline<T, Homogeneous<T, D>> {
        &self.curve
    }

    /// Consumes the curve, returning its homogeneous container.
    #[must_use]
    pub fn into_homogeneous(self) -> BSpline<T, Homogeneous<T, D>> {
        self.curve
    }

    /// The degree `p`.
    #[inline]
    #[must_use]
    pub fn degree(&self) -> usize {
        self.curve.degree()
    }

    /// The knot vector.
    #[inline]
    #[must_use]
    pub fn knots(&self) -> &KnotVector<T> {
        self.curve.knots()
    }

    /// The parametric domain $[u_p, u_n]$.
    #[inline]
    #[must_use]
    pub fn domain(&self) -> (T, T) {
        self.curve.domain()
    }

    /// The number of control points.
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        self.curve.control_points().len()
    }

    /// Always `false`: a curve has at least `p + 1` control points.
    #[inline]
    #[must_use]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The Cartesian control points $P_i$.
    #[must_use]
    pub fn control_points(&self) -> &[SVector<T, D>] {
        &self.points
    }

    /// The weights $w_i$.
    #[must_use]
    pub fn weights(&self) -> &[T] {
        &self.weights
    }

    /// Whether all weights are equal: the curve is then a polynomial B-spline curve.
    #[must_use]
    pub fn is_polynomial(&self) -> bool {
        let w = self.curve.control_points()[0].weight;
        self.curve.control_points().iter().all(|h| h.weight == w)
    }

    /// The non-rational B-spline curve with the same control points, if all weights are
    /// equal ([`NurbsCurve::is_polynomial`]).
    #[must_use]
    pub fn to_bspline(&self) -> Option<BSpline<T, SVector<T, D>>> {
        self.is_polynomial()
            .then(|| self.curve.map_control_points(Homogeneous::project))
    }

    /// Applies an affine map to the Cartesian control points, keeping the weights: by the
    /// affine invariance of NURBS this maps the curve. (A non-affine `f` gives a curve
    /// that is not the image of this one.)
    #[must_use]
    pub fn map_control_points<const E: usize>(
        &self,
        mut f: impl FnMut(&SVector<T, D>) -> SVector<T, E>,
    ) -> NurbsCurve<T, E> {
        NurbsCurve::new_unchecked(self.curve.map_control_points(|h| mapped(h, &mut f)))
    }

    /// The point $R(u)$: de Boor in homogeneous space, then the projection (6.5).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    #[inline]
    pub fn eval(&self, u: T) -> Result<SVector<T, D>> {
        let span = self.curve.knots().find_span(u)?;
        Ok(self.curve.eval_in_span(span, u).project())
    }

    /// Evaluates at many parameters (increasing order takes a constant-time span search).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for the first bad parameter.
    pub fn eval_many(&self, params: &[T]) -> Result<Vec<SVector<T, D>>> {
        let knots = self.curve.knots();
        for (i, &u) in params.iter().enumerate() {
            knots
                .check_param(u)
                .map_err(|e| e.context(format_args!("parameter {i}")))?;
        }
        let mut span = self.degree();
        Ok(params
            .iter()
            .map(|&u| {
                span = knots.span_in_domain_from(u, span);
                self.curve.eval_in_span(span, u).project()
            })
            .collect())
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
        let span = self.curve.knots().find_span(u)?;
        if out.is_empty() {
            return Ok(());
        }
        let mut stack = [Homogeneous::<T, D>::origin(); MAX_ORDER];
        let hom = &mut stack[..out.len().min(self.degree() + 1)];
        self.curve.derivatives_in_span(span, u, hom);
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
    /// [`ErrorKind::InvalidArgument`] above [`spline_core::MAX_DERIVATIVE_ORDER`]; the errors
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
        Self::checked(self.curve.insert_knot(u, times)?)
    }

    /// Inserts many knots at once (knot refinement), in homogeneous space.
    ///
    /// # Errors
    /// As [`BSpline::refine`].
    pub fn refine(&self, knots: &[T]) -> Result<Self> {
        Self::checked(self.curve.refine(knots)?)
    }

    /// Removes the interior knot `u` `times` times if the curve moves by at most `tolerance`
    /// (absolute, in Cartesian space). The removal runs in homogeneous space; the change of
    /// the rational curve is then bounded exactly (see [`BSpline::remove_knot_within`]) by
    /// re-inserting the knots: homogeneous control points within $\delta$ of the original
    /// ones move the curve by at most $\delta (1 + |P|_{max}) / w_{min}$ (The NURBS Book
    /// (5.30)).
    ///
    /// # Errors
    /// As [`BSpline::remove_knot_within`]; [`ErrorKind::ToleranceExceeded`] also when the
    /// removal would make a weight non-positive.
    pub fn remove_knot_within(&self, u: T, times: usize, tolerance: T) -> Result<Self> {
        check_tolerance(tolerance)?;
        let removed = self.curve.remove_knot_within(u, times, unbounded())?;
        let back = removed.insert_knot(u, times)?;
        check_rational_removal(
            self.curve.control_points(),
            removed.control_points(),
            back.control_points(),
            (u, times),
            tolerance,
        )?;
        Self::checked(removed)
    }

    /// [`NurbsCurve::remove_knot_within`] with a tolerance relative to the size of the
    /// control polygon (its largest Cartesian coordinate magnitude, or 1 if that is smaller).
    ///
    /// # Errors
    /// As [`NurbsCurve::remove_knot_within`].
    pub fn remove_knot(&self, u: T, times: usize, relative_tolerance: T) -> Result<Self> {
        let scale = cartesian_scale(self.curve.control_points());
        self.remove_knot_within(u, times, relative_tolerance * scale)
    }

    /// Raises the degree by `times`, in homogeneous space.
    ///
    /// # Errors
    /// As [`BSpline::elevate_degree`].
    pub fn elevate_degree(&self, times: usize) -> Result<Self> {
        Self::checked(self.curve.elevate_degree(times)?)
    }

    /// Splits at `u` into two curves clamped at `u`.
    ///
    /// # Errors
    /// As [`BSpline::split`].
    pub fn split(&self, u: T) -> Result<(Self, Self)> {
        let (a, b) = self.curve.split(u)?;
        Ok((Self::checked(a)?, Self::checked(b)?))
    }

    /// The same curve with clamped knots.
    #[must_use]
    pub fn clamped(&self) -> Self {
        Self::new_unchecked(self.curve.clamped())
    }

    /// The same curve traversed backwards on the same domain.
    #[must_use]
    pub fn reversed(&self) -> Self {
        Self::new_unchecked(self.curve.reversed())
    }

    /// The same curve on the domain `[a, b]`.
    ///
    /// # Errors
    /// As [`BSpline::reparametrized`].
    pub fn reparametrized(&self, a: T, b: T) -> Result<Self> {
        Ok(Self::new_unchecked(self.curve.reparametrized(a, b)?))
    }

    /// The rational Bézier segments, one per non-empty knot span, each a clamped NURBS curve
    /// on its span.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidWeight`] when a weight underflows to zero (weights spanning
    /// hundreds of orders of magnitude).
    pub fn bezier_segments(&self) -> Result<Vec<Self>> {
        self.curve
            .bezier_segments()
            .into_iter()
            .map(|b| Self::checked(bezier_as_bspline(&b)))
            .collect()
    }
}

/// A NURBS surface in $\mathbb{R}^D$ (seed 004 (6.11), (6.14)):
///
/// $$ S(u, v) = \frac{\sum_{i,j} N_{i,p}(u) N_{j,q}(v)\, w_{ij} P_{ij}}
///                   {\sum_{i,j} N_{i,p}(u) N_{j,q}(v)\, w_{ij}}, \qquad w_{ij} > 0. $$
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
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface<T, const D: usize> {
    surface: Surface<T, Homogeneous<T, D>>,
    /// The Cartesian control net, row-major (a view of `surface`).
    points: Vec<SVector<T, D>>,
    /// The weights, row-major (likewise).
    weights: Vec<T>,
}

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

    /// A NURBS surface from its homogeneous container.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidWeight`] unless every weight is positive and finite.
    pub fn from_homogeneous(surface: Surface<T, Homogeneous<T, D>>) -> Result<Self> {
        check_weights(surface.control_points().iter().map(|h| h.weight))?;
        Ok(Self::wrap(surface))
    }

    /// The surface of a homogeneous container with positive weights, with its views.
    fn wrap(surface: Surface<T, Homogeneous<T, D>>) -> Self {
        Self {
            points: cartesian(surface.control_points()),
            weights: weights_of(surface.control_points()),
            surface,
        }
    }

    /// A non-rational surface as a NURBS surface with unit weights.
    #[must_use]
    pub fn from_surface(surface: &Surface<T, SVector<T, D>>) -> Self {
        Self::wrap(surface.map_control_points(|p| Homogeneous::new(*p, T::one())))
    }

    pub(crate) fn new_unchecked(surface: Surface<T, Homogeneous<T, D>>) -> Self {
        debug_assert!(
            surface
                .control_points()
                .iter()
                .all(|h| h.weight > T::zero())
        );
        Self::wrap(surface)
    }

    /// See [`NurbsCurve::checked`].
    fn checked(surface: Surface<T, Homogeneous<T, D>>) -> Result<Self> {
        check_result_weights(surface.control_points())?;
        Ok(Self::wrap(surface))
    }

    /// The homogeneous surface whose projection this surface is.
    #[inline]
    #[must_use]
    pub fn homogeneous(&self) -> &Surface<T, Homogeneous<T, D>> {
        &self.surface
    }

    /// Consumes the surface, returning its homogeneous container.
    #[must_use]
    pub fn into_homogeneous(self) -> Surface<T, Homogeneous<T, D>> {
        self.surface
    }

    /// The degrees `(p, q)`.
    #[inline]
    #[must_use]
    pub fn degrees(&self) -> (usize, usize) {
        self.surface.degrees()
    }

    /// The degree in one direction.
    #[inline]
    #[must_use]
    pub fn degree(&self, direction: Direction) -> usize {
        self.surface.degree(direction)
    }

    /// The knot vector in `u`.
    #[inline]
    #[must_use]
    pub fn knots_u(&self) -> &KnotVector<T> {
        self.surface.knots_u()
    }

    /// The knot vector in `v`.
    #[inline]
    #[must_use]
    pub fn knots_v(&self) -> &KnotVector<T> {
        self.surface.knots_v()
    }

    /// The knot vector in one direction.
    #[inline]
    #[must_use]
    pub fn knots(&self, direction: Direction) -> &KnotVector<T> {
        self.surface.knots(direction)
    }

    /// The size `(n_u, n_v)` of the control net.
    #[inline]
    #[must_use]
    pub fn net_size(&self) -> (usize, usize) {
        self.surface.net_size()
    }

    /// The parametric domain `((u_min, u_max), (v_min, v_max))`.
    #[inline]
    #[must_use]
    pub fn domain(&self) -> ((T, T), (T, T)) {
        self.surface.domain()
    }

    /// The Cartesian control points, row-major.
    #[must_use]
    pub fn control_points(&self) -> &[SVector<T, D>] {
        &self.points
    }

    /// The weights, row-major.
    #[must_use]
    pub fn weights(&self) -> &[T] {
        &self.weights
    }

    /// The Cartesian control point $P_{ij}$.
    ///
    /// # Panics
    /// If `i ≥ n_u` or `j ≥ n_v`.
    #[must_use]
    pub fn control_point(&self, i: usize, j: usize) -> SVector<T, D> {
        self.surface.control_point(i, j).project()
    }

    /// The weight $w_{ij}$.
    ///
    /// # Panics
    /// If `i ≥ n_u` or `j ≥ n_v`.
    #[must_use]
    pub fn weight(&self, i: usize, j: usize) -> T {
        self.surface.control_point(i, j).weight
    }

    /// Applies an affine map to the Cartesian control points, keeping the weights (this maps
    /// the surface by affine invariance).
    #[must_use]
    pub fn map_control_points<const E: usize>(
        &self,
        mut f: impl FnMut(&SVector<T, D>) -> SVector<T, E>,
    ) -> NurbsSurface<T, E> {
        NurbsSurface::new_unchecked(self.surface.map_control_points(|h| mapped(h, &mut f)))
    }

    /// The point $S(u, v)$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    #[inline]
    pub fn eval(&self, u: T, v: T) -> Result<SVector<T, D>> {
        Ok(self.surface.eval(u, v)?.project())
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
        let len = crate::bspline::square_len(order)?;
        crate::bspline::check_same_len(len, out.len())?;
        let (su, sv) = self.surface.find_spans(u, v)?;
        let (p, q) = self.surface.degrees();
        let top = order.min(p.max(q));
        let mut hom = vec![Homogeneous::<T, D>::origin(); (top + 1) * (top + 1)];
        self.surface
            .derivatives_in_spans(su, sv, u, v, top, &mut hom);
        rational_surface_derivatives(&hom, top, order, out)
    }

    /// The rational partial derivatives `[k][l]` for `0 ≤ k, l ≤ order`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] above [`spline_core::MAX_DERIVATIVE_ORDER`]; the errors
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
            .surface
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
        Ok(NurbsCurve::new_unchecked(self.surface.curve_at_u(u)?))
    }

    /// The iso-parametric curve `u ↦ S(u, v)` at fixed `v`, a NURBS curve.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn curve_at_v(&self, v: T) -> Result<NurbsCurve<T, D>> {
        Ok(NurbsCurve::new_unchecked(self.surface.curve_at_v(v)?))
    }

    /// Inserts the knot `t` `times` times in `direction`, in homogeneous space.
    ///
    /// # Errors
    /// As [`Surface::insert_knot`].
    pub fn insert_knot(&self, direction: Direction, t: T, times: usize) -> Result<Self> {
        Self::checked(self.surface.insert_knot(direction, t, times)?)
    }

    /// Inserts many knots in `direction`, in homogeneous space.
    ///
    /// # Errors
    /// As [`Surface::refine`].
    pub fn refine(&self, direction: Direction, knots: &[T]) -> Result<Self> {
        Self::checked(self.surface.refine(direction, knots)?)
    }

    /// Removes the interior knot `t` of `direction` `times` times if the surface moves by at
    /// most `tolerance` (absolute, Cartesian), bounded as in
    /// [`NurbsCurve::remove_knot_within`].
    ///
    /// # Errors
    /// As [`NurbsCurve::remove_knot_within`].
    pub fn remove_knot_within(
        &self,
        direction: Direction,
        t: T,
        times: usize,
        tolerance: T,
    ) -> Result<Self> {
        check_tolerance(tolerance)?;
        let removed = self
            .surface
            .remove_knot_within(direction, t, times, unbounded())?;
        let back = removed.insert_knot(direction, t, times)?;
        check_rational_removal(
            self.surface.control_points(),
            removed.control_points(),
            back.control_points(),
            (t, times),
            tolerance,
        )
        .map_err(|e| e.context(format_args!("direction {direction}")))?;
        Self::checked(removed)
    }

    /// [`NurbsSurface::remove_knot_within`] with a tolerance relative to the size of the
    /// control net.
    ///
    /// # Errors
    /// As [`NurbsCurve::remove_knot_within`].
    pub fn remove_knot(
        &self,
        direction: Direction,
        t: T,
        times: usize,
        relative_tolerance: T,
    ) -> Result<Self> {
        let scale = cartesian_scale(self.surface.control_points());
        self.remove_knot_within(direction, t, times, relative_tolerance * scale)
    }

    /// Raises the degree in `direction` by `times`, in homogeneous space.
    ///
    /// # Errors
    /// As [`Surface::elevate_degree`].
    pub fn elevate_degree(&self, direction: Direction, times: usize) -> Result<Self> {
        Self::checked(self.surface.elevate_degree(direction, times)?)
    }

    /// Splits at `t` in `direction` into two surfaces clamped at `t`.
    ///
    /// # Errors
    /// As [`Surface::split`].
    pub fn split(&self, direction: Direction, t: T) -> Result<(Self, Self)> {
        let (a, b) = self.surface.split(direction, t)?;
        Ok((Self::checked(a)?, Self::checked(b)?))
    }

    /// The same surface with clamped knots in both directions.
    #[must_use]
    pub fn clamped(&self) -> Self {
        Self::new_unchecked(self.surface.clamped())
    }

    /// The same surface traversed backwards in `direction`.
    #[must_use]
    pub fn reversed(&self, direction: Direction) -> Self {
        Self::new_unchecked(self.surface.reversed(direction))
    }

    /// The same surface with the domain of `direction` mapped onto `[a, b]`.
    ///
    /// # Errors
    /// As [`Surface::reparametrized`].
    pub fn reparametrized(&self, direction: Direction, a: T, b: T) -> Result<Self> {
        Ok(Self::new_unchecked(
            self.surface.reparametrized(direction, a, b)?,
        ))
    }

    /// The surface with `u` and `v` exchanged.
    #[must_use]
    pub fn transposed(&self) -> Self {
        Self::new_unchecked(self.surface.transposed())
    }

    /// The rational Bézier patches, `[a][b]` over the `a`-th non-empty span in `u` and the
    /// `b`-th in `v`.
    ///
    /// # Errors
    /// As [`NurbsCurve::bezier_segments`].
    pub fn bezier_patches(&self) -> Result<Vec<Vec<Self>>> {
        self.surface
            .bezier_patches()
            .into_iter()
            .map(|row| row.into_iter().map(Self::checked).collect())
            .collect()
    }
}
