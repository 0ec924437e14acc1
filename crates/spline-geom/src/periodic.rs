//! Periodic B-splines: closed curves and periodic functions as a kind of their own.
//!
//! A [`PeriodicBSpline`] holds `n` control points on [`PeriodicKnots`] and evaluates at any
//! parameter (modulo the period). Its structural operations are the open ones run on the
//! same spline written over three periods ([`PeriodicKnots::extended`]), where the middle
//! period is exact: knot insertion and refinement, the derivative, degree elevation and
//! opening into a clamped curve reuse the one implementation of each in
//! [`crate::BSpline`].

use crate::bspline::BSpline;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, PeriodicKnots, Result, Scalar};

/// A periodic B-spline $C(u + T) = C(u)$ of degree `p` with `n` control points:
///
/// $$ C(u) = \sum_{i=0}^{n-1} P_i \sum_{m \in \mathbb{Z}} N_{i + mn, p}(u) $$
///
/// on the bi-infinite knots of [`PeriodicKnots`]. Evaluation takes any finite parameter;
/// the domain of one turn is $[t_0, t_0 + T]$, and the curve is $C^{p - m}$ at a knot of
/// multiplicity `m`, across $t_0$ as everywhere else. [`PeriodicBSpline::to_bspline`] gives
/// the wrapped open form (the last `p` control points repeating the first `p`), which is
/// what scipy's periodic `BSpline` holds.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_core::PeriodicKnots;
/// use spline_geom::PeriodicBSpline;
/// let square = vec![
///     Vector2::new(1.0, 0.0), Vector2::new(0.0, 1.0),
///     Vector2::new(-1.0, 0.0), Vector2::new(0.0, -1.0),
/// ];
/// let knots = PeriodicKnots::uniform(2, 4, 0.0, 4.0)?;
/// let c = PeriodicBSpline::new(knots, square)?;
/// assert_eq!(c.eval(0.5)?, c.eval(4.5)?);           // any parameter, modulo the period
/// let d = c.derivatives(0.0, 1)?[1];
/// assert!((d - c.derivatives(4.0, 1)?[1]).norm() < 1e-15); // smooth across the seam
/// let open = c.to_open(1.0)?;                          // clamped on [1, 5]
/// assert!((open.eval(1.0)? - c.eval(1.0)?).norm() < 1e-15);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct PeriodicBSpline<T, P> {
    knots: PeriodicKnots<T>,
    /// The wrapped form: `n + p` control points, the last `p` repeating the first `p`.
    wrapped: BSpline<T, P>,
}

impl<T: Scalar, P: ControlPoint<T>> PeriodicBSpline<T, P> {
    /// A periodic spline from its knots and its `n` control points.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there is one control point per knot of the
    /// period; [`ErrorKind::NonFinite`] for a control point that is not finite.
    pub fn new(knots: PeriodicKnots<T>, control_points: Vec<P>) -> Result<Self> {
        let n = knots.num_basis();
        if control_points.len() != n {
            return Err(Error::invalid_length(
                format_args!(
                    "a periodic spline with {n} knots per period needs {n} control points"
                ),
                n,
                control_points.len(),
            ));
        }
        let p = knots.degree();
        let wrapped_points: Vec<P> = (0..n + p).map(|i| control_points[i % n]).collect();
        let wrapped = BSpline::new(knots.wrapped(), wrapped_points)?;
        Ok(Self { knots, wrapped })
    }

    /// The periodic spline behind a wrapped open B-spline: knots with
    /// $u_{i+n} - u_i$ equal to the length of the domain and the last `p` control points
    /// equal to the first `p`, each within `tolerance` relative to the period and to the
    /// size of the control polygon (the form [`PeriodicBSpline::to_bspline`] and
    /// `spline_fit::interpolate_closed` return).
    ///
    /// # Errors
    /// [`ErrorKind::SpaceMismatch`] when the knots are not periodic;
    /// [`ErrorKind::ToleranceExceeded`] when the control points do not wrap.
    pub fn from_wrapped(curve: &BSpline<T, P>, tolerance: T) -> Result<Self> {
        let knots = PeriodicKnots::from_wrapped(curve.knots(), tolerance)?;
        let n = knots.num_basis();
        let points = curve.control_points();
        let size = points.iter().fold(T::one(), |m, q| m.max(q.max_abs()));
        if let Some(i) = (0..knots.degree()).find(|&i| (points[i + n] - points[i]).max_abs() > tolerance * size) {
            return Err(Error::new(
                ErrorKind::ToleranceExceeded,
                format!(
                    "the curve is not closed: control point {} does not repeat control point {i}",
                    i + n
                ),
            ));
        }
        Self::new(knots, points[..n].to_vec())
    }

    /// The periodic knots.
    #[must_use]
    pub fn knots(&self) -> &PeriodicKnots<T> {
        &self.knots
    }

    /// The degree `p`.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// The period `T`.
    #[must_use]
    pub fn period(&self) -> T {
        self.knots.period()
    }

    /// The `n` control points.
    #[must_use]
    pub fn control_points(&self) -> &[P] {
        &self.wrapped.control_points()[..self.knots.num_basis()]
    }

    /// The domain of one turn, $[t_0, t_0 + T]$.
    #[must_use]
    pub fn domain(&self) -> (T, T) {
        self.knots.domain()
    }

    /// The wrapped open form: the B-spline on [`PeriodicKnots::wrapped`] with `n + p`
    /// control points, equal to this spline on one period.
    #[must_use]
    pub fn to_bspline(&self) -> BSpline<T, P> {
        self.wrapped.clone()
    }

    /// The wrapped open form, borrowed.
    #[must_use]
    pub fn as_bspline(&self) -> &BSpline<T, P> {
        &self.wrapped
    }

    /// The parameter at which the wrapped form is evaluated: `u` itself on the closed
    /// domain (so that the end of the domain is a left limit, as for open curves), else
    /// `u` moved into it by whole periods.
    fn local(&self, u: T) -> Result<T> {
        if !u.is_finite() {
            return Err(
                Error::non_finite(format_args!("parameter {}", spline_core::to_f64(u)))
                    .with_value(spline_core::to_f64(u)),
            );
        }
        let (a, b) = self.domain();
        Ok(if u >= a && u <= b { u } else { self.knots.wrap(u) })
    }

    /// The point $C(u)$ for any finite `u`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] for NaN or infinite `u`.
    pub fn eval(&self, u: T) -> Result<P> {
        self.wrapped.eval(self.local(u)?)
    }

    /// $C(u), …, C^{(k)}(u)$ into `out` (`k = out.len() − 1`), for any finite `u`.
    ///
    /// # Errors
    /// As [`BSpline::derivatives_into`].
    pub fn derivatives_into(&self, u: T, out: &mut [P]) -> Result<()> {
        self.wrapped.derivatives_into(self.local(u)?, out)
    }

    /// The derivatives $C^{(j)}(u)$ for `j = 0 … order`.
    ///
    /// # Errors
    /// As [`BSpline::derivatives`].
    pub fn derivatives(&self, u: T, order: usize) -> Result<Vec<P>> {
        self.wrapped.derivatives(self.local(u)?, order)
    }

    /// The same spline as an open B-spline over one period before and one after this one:
    /// domain $[t_0 - T, t_0 + 2T]$.
    fn three_periods(&self) -> BSpline<T, P> {
        let n = self.knots.num_basis();
        let points = (0..3 * n + self.degree())
            .map(|i| self.control_points()[i % n])
            .collect();
        BSpline::new_unchecked(self.knots.extended(1, 1), points)
    }

    /// Reads the periodic spline on `knots` off an open spline that equals it on
    /// $[t_0 - T, t_0 + 2T]$ and whose knots there are those of `knots`.
    fn from_three_periods(knots: PeriodicKnots<T>, open: &BSpline<T, P>) -> Self {
        let (a, _) = knots.domain();
        let first = open.knots().knots().partition_point(|&k| k < a);
        let p = knots.degree();
        let n = knots.num_basis();
        let points = open.control_points()[first - p..first - p + n].to_vec();
        Self::new(knots, points).expect("the points of a valid spline are finite")
    }

    /// Inserts the knot `u` (modulo the period) `times` times without changing the curve.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::KnotMultiplicity`] above `p + 1`.
    pub fn insert_knot(&self, u: T, times: usize) -> Result<Self> {
        self.refine(&vec![u; times])
    }

    /// Inserts all of `new_knots` (any order, modulo the period): knot refinement on the
    /// spline written over three periods, each knot inserted in all three.
    ///
    /// # Errors
    /// As [`PeriodicBSpline::insert_knot`].
    pub fn refine(&self, new_knots: &[T]) -> Result<Self> {
        let target = self.knots.refined(new_knots)?;
        if new_knots.is_empty() {
            return Ok(self.clone());
        }
        let t = self.period();
        let mut all = Vec::with_capacity(3 * new_knots.len());
        for &u in new_knots {
            let w = self.knots.wrap(u);
            all.extend([w - t, w, w + t]);
        }
        let refined = self.three_periods().refine(&all)?;
        Ok(Self::from_three_periods(target, &refined))
    }

    /// The clamped open curve that starts at `u` (modulo the period) and runs once around,
    /// on $[u, u + T]$: the periodic spline split into an open one.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`].
    pub fn to_open(&self, u: T) -> Result<BSpline<T, P>> {
        let start = self.knots.wrap(self.local(u)?);
        self.three_periods().restricted(start, start + self.period())
    }

    /// The derivative of order `order`, a periodic spline of degree `p − order` (a knot
    /// copy dropped where it is discontinuous, as for open splines).
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] above the degree; [`ErrorKind::TooFewPoints`] when the
    /// derivative would have fewer knots per period than its degree needs.
    pub fn derivative(&self, order: usize) -> Result<Self> {
        let target = self.knots.derivative_knots(order)?;
        let open = self.three_periods().derivative(order)?;
        Ok(Self::from_three_periods(target, &open))
    }

    /// Raises the degree by `times` (every knot's multiplicity rises by `times`).
    ///
    /// # Errors
    /// [`ErrorKind::DegreeTooHigh`] above [`spline_core::MAX_DEGREE`].
    pub fn elevate_degree(&self, times: usize) -> Result<Self> {
        if times == 0 {
            return Ok(self.clone());
        }
        let q = spline_core::check_elevated_degree(self.degree(), times)?;
        let knots: Vec<T> = self
            .knots
            .knots()
            .iter()
            .flat_map(|&k| std::iter::repeat_n(k, 1))
            .collect();
        let mut elevated_knots = Vec::with_capacity(knots.len() * (times + 1));
        let breaks = breakpoints(&knots);
        for (k, m) in breaks {
            elevated_knots.extend(std::iter::repeat_n(k, m + times));
        }
        let target = PeriodicKnots::new(q, elevated_knots, self.period())?;
        let open = self.three_periods().elevate_degree(times)?;
        Ok(Self::from_three_periods(target, &open))
    }

    /// The same curve traversed backwards: $\tilde C(u) = C(a + b - u)$ on the same domain.
    #[must_use]
    pub fn reversed(&self) -> Self {
        let open = self.wrapped.reversed();
        Self::from_wrapped_exact(&open)
    }

    /// The same curve on a domain starting at `a` with period `period` (an affine change
    /// of parameter).
    ///
    /// # Errors
    /// [`ErrorKind::EmptyDomain`] unless the period is positive; [`ErrorKind::NonFinite`].
    pub fn reparametrized(&self, a: T, period: T) -> Result<Self> {
        let open = self.wrapped.reparametrized(a, a + period)?;
        PeriodicBSpline::from_wrapped(&open, spline_core::cast(1e-12))
    }

    /// The wrapped form of a curve known to be periodic (the result of an exact
    /// operation on a wrapped form).
    fn from_wrapped_exact(open: &BSpline<T, P>) -> Self {
        Self::from_wrapped(open, spline_core::cast(1e-12))
            .expect("operations on a wrapped form keep it periodic")
    }
}

/// The distinct values of sorted knots with their multiplicities.
fn breakpoints<T: Scalar>(knots: &[T]) -> Vec<(T, usize)> {
    let mut out: Vec<(T, usize)> = Vec::new();
    for &k in knots {
        match out.last_mut() {
            Some((last, m)) if *last == k => *m += 1,
            _ => out.push((k, 1)),
        }
    }
    out
}

impl<T: Scalar, P: ControlPoint<T>> From<PeriodicBSpline<T, P>> for BSpline<T, P> {
    fn from(curve: PeriodicBSpline<T, P>) -> Self {
        curve.wrapped
    }
}

/// The wrapped knot vector of a periodic spline space (re-exported for symmetry with
/// [`BSpline::knots`]).
#[must_use]
pub fn wrapped_knots<T: Scalar>(knots: &PeriodicKnots<T>) -> KnotVector<T> {
    knots.wrapped()
}
