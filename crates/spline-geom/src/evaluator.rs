//! Evaluators: a curve's cached piecewise polynomial form behind one-point calls.
//!
//! [`BSpline::eval`] keeps the triangular scheme's values bit for bit (algorithms such as curve
//! intersection rely on its rounding matching the derivatives'). A caller who evaluates one
//! point at a time, many times, and only needs the value to the accuracy of the curve asks
//! for an evaluator instead: it builds the curve's Taylor form once (shared with the batches,
//! see [`BSpline::eval_many_into`]) and answers each call with a table lookup and Horner's
//! scheme.

use crate::homogeneous::Homogeneous;
use crate::nurbs::{NurbsCurve, rational_curve_derivatives};
use crate::pieces::Pieces;
use crate::{BSpline, bspline::check_finite_derivatives};
use nalgebra::SVector;
use spline_core::{ControlPoint, MAX_ORDER, Result, Scalar};

/// One-point evaluation of a [`BSpline`] through its cached piecewise polynomial form
/// ([`BSpline::evaluator`]):
///
/// $$ C(u) = \sum_{k=0}^{p} c_k\\,(u - u_s)^k, \qquad u_s \le u < u_{s+1}, $$
///
/// the span `s` from a table in constant time, then `p` multiply-adds. Values agree with
/// [`BSpline::eval`] to the rounding of Horner's scheme (a few units in the last place of the
/// control points' size; the form is refused, and the triangular scheme used, where it would
/// lose more). The domain's end, degrees 0 and above 5 go through the curve's own methods.
///
/// ```
/// use spline_geom::BSpline;
/// let f = BSpline::from_knots(3, vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
///     vec![0.0, 2.0, -1.0, 3.0, 1.0])?;
/// let evaluator = f.evaluator();
/// for u in [0.0, 0.1, 0.5, 0.77, 1.0] {
///     let (fast, exact): (f64, f64) = (evaluator.eval(u)?, f.eval(u)?);
///     assert!((fast - exact).abs() < 1e-14);
/// }
/// assert!(evaluator.eval(1.5).is_err());
/// # Ok::<(), spline_core::Error>(())
/// ```
pub struct CurveEvaluator<'a, T, P> {
    curve: &'a BSpline<T, P>,
    pieces: Option<&'a Pieces<T, P>>,
}

impl<T: Scalar, P: ControlPoint<T>> BSpline<T, P> {
    /// An evaluator for many one-point calls: builds the cached piecewise polynomial form
    /// now (a few evaluations per span, once per curve; clones share it) and borrows the
    /// curve. See [`CurveEvaluator`].
    #[must_use]
    pub fn evaluator(&self) -> CurveEvaluator<'_, T, P> {
        CurveEvaluator {
            curve: self,
            pieces: self.cached_pieces(),
        }
    }
}

impl<T: Scalar, P: ControlPoint<T>> CurveEvaluator<'_, T, P> {
    /// The curve evaluated.
    #[must_use]
    pub fn curve(&self) -> &BSpline<T, P> {
        self.curve
    }

    /// The point $C(u)$.
    ///
    /// # Errors
    /// [`spline_core::ErrorKind::NonFinite`] or [`spline_core::ErrorKind::OutOfDomain`], as
    /// [`BSpline::eval`].
    #[inline]
    pub fn eval(&self, u: T) -> Result<P> {
        if let Some(point) = self
            .pieces
            .and_then(|pieces| pieces.eval_inside(self.curve.knots(), u))
        {
            return Ok(point);
        }
        self.curve.eval(u)
    }

    /// $C(u), C'(u), …, C^{(k)}(u)$ with `k = out.len() − 1`, written into `out` (orders above
    /// the degree are zero). No heap allocation.
    ///
    /// ```
    /// use spline_geom::BSpline;
    /// // f(u) = u³ on [0, 1] as a cubic Bézier function.
    /// let f = BSpline::from_knots(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
    ///     vec![0.0, 0.0, 0.0, 1.0])?;
    /// let mut d = [0.0f64; 5];
    /// f.evaluator().derivatives_into(0.5, &mut d)?;
    /// let expected = [0.125, 0.75, 3.0, 6.0, 0.0];
    /// assert!(d.iter().zip(expected).all(|(a, b): (&f64, f64)| (a - b).abs() < 1e-15));
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSpline::derivatives_into`].
    #[inline]
    pub fn derivatives_into(&self, u: T, out: &mut [P]) -> Result<()> {
        self.derivatives_unchecked(u, out)?;
        check_finite_derivatives(out, u)
    }

    /// The derivatives without the check for overflow.
    #[inline]
    fn derivatives_unchecked(&self, u: T, out: &mut [P]) -> Result<()> {
        let knots = self.curve.knots();
        if self
            .pieces
            .is_some_and(|pieces| pieces.derivatives_inside(knots, u, out))
        {
            return Ok(());
        }
        let span = knots.find_span(u)?;
        self.curve.derivatives_in_span(span, u, out);
        Ok(())
    }
}

/// One-point evaluation of a [`NurbsCurve`] ([`NurbsCurve::evaluator`]): the
/// [`CurveEvaluator`] of its homogeneous B-spline, then the projection.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::NurbsCurve;
/// let quarter = NurbsCurve::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(1.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(0.0, 1.0)],
///     vec![1.0, 1.0, 2.0])?;
/// let evaluator = quarter.evaluator();
/// let mut d = [Vector2::zeros(); 2];
/// evaluator.derivatives_into(0.0, &mut d)?;
/// assert!((d[1] - Vector2::new(0.0, 2.0)).norm() < 1e-14);
/// let on_circle: Vector2<f64> = evaluator.eval(0.5)?;
/// assert!((on_circle.norm() - 1.0).abs() < 1e-15);
/// # Ok::<(), spline_core::Error>(())
/// ```
pub struct NurbsEvaluator<'a, T, const D: usize> {
    homogeneous: CurveEvaluator<'a, T, Homogeneous<T, D>>,
    degree: usize,
}

impl<T: Scalar, const D: usize> NurbsCurve<T, D> {
    /// An evaluator for many one-point calls (see [`NurbsEvaluator`]).
    #[must_use]
    pub fn evaluator(&self) -> NurbsEvaluator<'_, T, D> {
        NurbsEvaluator {
            homogeneous: self.homogeneous().evaluator(),
            degree: self.degree(),
        }
    }
}

impl<T: Scalar, const D: usize> NurbsEvaluator<'_, T, D> {
    /// The point $R(u)$.
    ///
    /// # Errors
    /// As [`NurbsCurve::eval`].
    #[inline]
    pub fn eval(&self, u: T) -> Result<SVector<T, D>> {
        Ok(self.homogeneous.eval(u)?.project())
    }

    /// $R(u), R'(u), …, R^{(k)}(u)$ with `k = out.len() − 1` (The NURBS Book A4.2 on the
    /// homogeneous derivatives). No heap allocation.
    ///
    /// # Errors
    /// As [`NurbsCurve::derivatives_into`].
    pub fn derivatives_into(&self, u: T, out: &mut [SVector<T, D>]) -> Result<()> {
        let mut stack = [Homogeneous::<T, D>::origin(); MAX_ORDER];
        let hom = &mut stack[..out.len().min(self.degree + 1)];
        self.homogeneous.derivatives_unchecked(u, hom)?;
        if out.is_empty() {
            return Ok(());
        }
        rational_curve_derivatives(hom, out)
    }
}
