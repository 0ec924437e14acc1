//! Periodic B-splines: closed curves (and periodic functions) as a first-class kind.

use crate::bspline::BSpline;
use crate::param::ParamCurve;
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, MAX_DEGREE, Result, Scalar, VectorSpace, cast,
    from_count, to_f64,
};

/// A periodic B-spline of degree `p`: knots $t_0 \le … \le t_{N-1}$ in one period
/// $[a, a + T)$, extended by $t_{j+N} = t_j + T$, and `N` control points $c_0 … c_{N-1}$,
/// extended by $c_{i+N} = c_i$:
///
/// $$ C(u) = \sum_{i} c_{i \bmod N} N_{i,p}(u), \qquad C(u + T) = C(u). $$
///
/// The curve is closed and $C^{p-m}$ at a knot of multiplicity `m ≤ p`, also across the
/// closing point. It is stored as the *wrapped* container of the period $[a, a + T]$ (the
/// form of scipy's periodic `BSpline` and of `spline_fit::interpolate_closed`): `N + 2p + 1`
/// knots $t_{-p} … t_{N+p}$ and `N + p` control points whose last `p` repeat the first `p`
/// ([`PeriodicBSpline::wrapped`]); basis function `i` has the support $[t_{i-p}, t_{i+1}]$.
/// Evaluation accepts every finite parameter and reduces it to the period.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::PeriodicBSpline;
/// // A closed uniform cubic on the control polygon of a square.
/// let square = vec![
///     Vector2::new(1.0, 0.0), Vector2::new(0.0, 1.0),
///     Vector2::new(-1.0, 0.0), Vector2::new(0.0, -1.0),
/// ];
/// let curve = PeriodicBSpline::new(3, vec![0.0, 1.0, 2.0, 3.0], 4.0, square)?;
/// let (a, b) = curve.domain();
/// assert_eq!((a, b), (0.0, 4.0));
/// assert!((curve.eval(0.3)? - curve.eval(4.3)?).norm() < 1e-14); // periodic
/// let d0 = curve.derivatives(a, 2)?;
/// let d1 = curve.derivatives(b - 1e-12, 2)?;
/// assert!((d0[1] - d1[1]).norm() < 1e-9); // C² across the closing point
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct PeriodicBSpline<T, P> {
    wrapped: BSpline<T, P>,
    count: usize,
}

impl<T: Scalar, P: ControlPoint<T>> PeriodicBSpline<T, P> {
    /// The periodic B-spline of degree `p` with the knots `knots` of one period
    /// ($t_0 \le … \le t_{N-1} < t_0 + T$), the period `T` and `N` control points.
    ///
    /// # Errors
    /// [`ErrorKind::DegreeTooHigh`] above [`MAX_DEGREE`]; [`ErrorKind::InvalidLength`] unless
    /// there are as many knots as control points; [`ErrorKind::TooFewPoints`] unless
    /// `N ≥ p + 1`; [`ErrorKind::NonFinite`]; [`ErrorKind::UnsortedKnots`] for decreasing
    /// knots; [`ErrorKind::EmptyDomain`] unless $t_{N-1} < t_0 + T$;
    /// [`ErrorKind::KnotMultiplicity`] for a knot repeated more than `p` times (the curve
    /// would not be continuous).
    pub fn new(degree: usize, knots: Vec<T>, period: T, control_points: Vec<P>) -> Result<Self> {
        check_periodic_shape(degree, knots.len(), control_points.len())?;
        if let Some(j) = knots.iter().position(|k| !k.is_finite()) {
            return Err(Error::non_finite(format_args!("knot {j}")).with_index(j));
        }
        if !period.is_finite() {
            return Err(Error::non_finite("the period"));
        }
        if let Some(j) = (1..knots.len()).find(|&j| knots[j] < knots[j - 1]) {
            return Err(Error::new(
                ErrorKind::UnsortedKnots,
                format!("periodic knots decrease at index {j}"),
            ));
        }
        let n = knots.len();
        if !(knots[n - 1] < knots[0] + period) {
            return Err(Error::new(
                ErrorKind::EmptyDomain,
                format!(
                    "the period {} must exceed the span of one period's knots ({} to {})",
                    to_f64(period),
                    to_f64(knots[0]),
                    to_f64(knots[n - 1])
                ),
            ));
        }
        let extended = extend_knots(&knots, period, degree, 1);
        drop(knots);
        let knot_vector = KnotVector::new(degree, extended)?;
        check_multiplicities(&knot_vector, degree, n)?;
        if let Some(i) = control_points.iter().position(|c| !c.all_finite()) {
            return Err(Error::non_finite(format_args!("control point {i}")).with_index(i));
        }
        let mut wrapped = control_points;
        wrapped.extend_from_within(..degree);
        Ok(Self {
            wrapped: BSpline::new_unchecked(knot_vector, wrapped),
            count: n,
        })
    }

    /// The periodic B-spline whose wrapped container is `curve` (scipy's periodic form, the
    /// result of `spline_fit::interpolate_closed`): `N + 2p + 1` knots whose first and last
    /// `2p + 1` differ by the period $T = u_{N+p} - u_p$, and `N + p` control points whose last
    /// `p` repeat the first `p`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] if the knots or control points do not repeat with the
    /// period (knots to 8 ulps of the largest knot, control points exactly); the errors of
    /// [`PeriodicBSpline::new`].
    pub fn from_wrapped(curve: &BSpline<T, P>) -> Result<Self> {
        let p = curve.degree();
        let m = curve.len();
        if m < 2 * p + 1 {
            return Err(Error::new(
                ErrorKind::TooFewPoints,
                format!(
                    "a wrapped periodic curve of degree {p} needs at least {} control points, got {m}",
                    2 * p + 1
                ),
            ));
        }
        let n = m - p;
        let u = curve.knots().knots();
        let period = u[n + p] - u[p];
        let scale = u.iter().fold(period.abs(), |s, k| s.max(k.abs()));
        let slack = scale * cast::<T>(8.0 * f64::EPSILON);
        for k in 0..=2 * p {
            if (u[k + n] - u[k] - period).abs() > slack {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!(
                        "knots {k} and {} do not differ by the period {}",
                        k + n,
                        to_f64(period)
                    ),
                )
                .with_index(k + n));
            }
        }
        let points = curve.control_points();
        if let Some(i) = (0..p).find(|&i| points[i] != points[i + n]) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "control point {} does not repeat control point {i}: the curve is not wrapped",
                    i + n
                ),
            )
            .with_index(i + n));
        }
        Self::new(p, u[p..p + n].to_vec(), period, points[..n].to_vec())
    }

    /// The degree `p`.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.wrapped.degree()
    }

    /// The period `T`.
    #[must_use]
    pub fn period(&self) -> T {
        let (a, b) = self.wrapped.domain();
        b - a
    }

    /// The period's parameter interval $[a, a + T]$ (`a` is the first knot).
    #[must_use]
    pub fn domain(&self) -> (T, T) {
        self.wrapped.domain()
    }

    /// The knots of one period, $t_0 … t_{N-1}$.
    #[must_use]
    pub fn period_knots(&self) -> &[T] {
        let p = self.degree();
        &self.wrapped.knots().knots()[p..p + self.count]
    }

    /// The `N` distinct control points.
    #[must_use]
    pub fn control_points(&self) -> &[P] {
        &self.wrapped.control_points()[..self.count]
    }

    /// The number `N` of distinct control points (of knots in one period).
    #[must_use]
    pub fn len(&self) -> usize {
        self.count
    }

    /// Never: a periodic B-spline has at least `p + 1` control points.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The wrapped container on the period (`N + p` control points, the last `p` repeating
    /// the first): the same curve on $[a, a + T]$ as an ordinary unclamped B-spline.
    #[must_use]
    pub fn wrapped(&self) -> &BSpline<T, P> {
        &self.wrapped
    }

    /// `u` reduced to the period: $a + ((u - a) \bmod T)$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] for a parameter that is not finite.
    pub fn reduce(&self, u: T) -> Result<T> {
        if !u.is_finite() {
            return Err(
                Error::non_finite(format_args!("parameter {}", to_f64(u))).with_value(to_f64(u))
            );
        }
        let (a, b) = self.domain();
        if u >= a && u <= b {
            return Ok(u);
        }
        let period = b - a;
        let v = u - ((u - a) / period).floor() * period;
        // Rounding can land a hair outside the period.
        Ok(if v < a || v >= b { a } else { v })
    }

    /// The point $C(u)$ for any finite `u` (reduced to the period).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`].
    pub fn eval(&self, u: T) -> Result<P> {
        self.wrapped.eval(self.reduce(u)?)
    }

    /// $C(u), C'(u), …, C^{(k)}(u)$ for any finite `u`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::OrderTooHigh`] as [`BSpline::derivatives`].
    pub fn derivatives(&self, u: T, order: usize) -> Result<Vec<P>> {
        self.wrapped.derivatives(self.reduce(u)?, order)
    }

    /// The wrapped container repeated over `periods` periods (`N·periods + p` control points
    /// on $[a, a + \text{periods}\cdot T]$).
    fn extended(&self, periods: usize) -> BSpline<T, P> {
        let p = self.degree();
        let knots = extend_knots(self.period_knots(), self.period(), p, periods);
        let points = self.control_points();
        let control = (0..self.count * periods + p)
            .map(|i| points[i % self.count])
            .collect();
        BSpline::new_unchecked(KnotVector::new_unchecked(p, knots), control)
    }
}

impl<T: Scalar, V: VectorSpace<T> + ControlPoint<T>> PeriodicBSpline<T, V> {
    /// Inserts the knot `u` (any finite parameter, reduced to the period) `times` times:
    /// the same curve with `N + times` control points, still periodic. Boehm's insertion on
    /// two periods, at `u` and `u + T` (spline-geom's one refinement), read back on the
    /// second one.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::KnotMultiplicity`] if the knot would occur
    /// more than `p` times.
    pub fn insert_knot(&self, u: T, times: usize) -> Result<Self> {
        let u = self.reduce(u)?;
        let p = self.degree();
        let period = self.period();
        let existing = self.period_knots().iter().filter(|&&k| k == u).count();
        if existing + times > p {
            return Err(Error::new(
                ErrorKind::KnotMultiplicity,
                format!(
                    "inserting u = {} {times} times gives multiplicity {} > degree {p} (a periodic curve must stay continuous)",
                    to_f64(u),
                    existing + times
                ),
            ));
        }
        if times == 0 {
            return Ok(self.clone());
        }
        let two = self.extended(2);
        let mut new_knots = vec![u; times];
        new_knots.extend(std::iter::repeat_n(u + period, times));
        let refined = two.refine(&new_knots)?;
        let n = self.count + times;
        let knots = refined.knots().knots()[p..p + n].to_vec();
        // The second period: its coefficients are blossoms at knots inside [a, a + 2T),
        // all of the new periodic sequence (the first period's left ones are not).
        let control = refined.control_points()[n..2 * n].to_vec();
        Self::new(p, knots, period, control)
    }

    /// Inserts many knots at once (any finite parameters, reduced to the period, in any
    /// order, repeats allowed): the same curve with `N + r` control points, still periodic.
    /// One refinement of the two-period container at every `u` and `u + T` (The NURBS Book
    /// A5.4), read back on the second period; no copy of the curve per knot.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use spline_geom::PeriodicBSpline;
    /// let square = vec![
    ///     Vector2::new(1.0, 0.0), Vector2::new(0.0, 1.0),
    ///     Vector2::new(-1.0, 0.0), Vector2::new(0.0, -1.0),
    /// ];
    /// let curve = PeriodicBSpline::new(3, vec![0.0, 1.0, 2.0, 3.0], 4.0, square)?;
    /// let finer = curve.refine(&[0.5, 2.5, 5.5, 0.5])?; // 5.5 is 1.5 of the period
    /// assert_eq!(finer.len(), 8);
    /// assert!((finer.eval(1.7)? - curve.eval(1.7)?).norm() < 1e-14);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::KnotMultiplicity`] if a knot would occur more
    /// than `p` times. The curve is not changed on error.
    pub fn refine(&self, knots: &[T]) -> Result<Self> {
        let p = self.degree();
        let period = self.period();
        let (a, b) = self.domain();
        // The end of the period is its start.
        let mut reduced = knots
            .iter()
            .map(|&u| self.reduce(u).map(|v| if v == b { a } else { v }))
            .collect::<Result<Vec<T>>>()?;
        // Finite after the reduction: no NaN to order.
        reduced.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        for run in reduced.chunk_by(|a, b| a == b) {
            let u = run[0];
            let existing = self.period_knots().iter().filter(|&&k| k == u).count();
            if existing + run.len() > p {
                return Err(Error::new(
                    ErrorKind::KnotMultiplicity,
                    format!(
                        "inserting u = {} {} times gives multiplicity {} > degree {p} (a periodic curve must stay continuous)",
                        to_f64(u),
                        run.len(),
                        existing + run.len()
                    ),
                ));
            }
        }
        if reduced.is_empty() {
            return Ok(self.clone());
        }
        let mut both = reduced.clone();
        both.extend(reduced.iter().map(|&u| u + period));
        let refined = self.extended(2).refine(&both)?;
        let n = self.count + reduced.len();
        let knots = refined.knots().knots()[p..p + n].to_vec();
        // The second period (see `insert_knot`).
        let control = refined.control_points()[n..2 * n].to_vec();
        Self::new(p, knots, period, control)
    }

    /// The closed curve opened at `u` (reduced to the period): the clamped B-spline on
    /// $[u, u + T]$ with the same points, $\tilde C(s) = C(s)$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`].
    pub fn open_at(&self, u: T) -> Result<BSpline<T, V>> {
        let u = self.reduce(u)?;
        self.extended(2).restricted(u, u + self.period())
    }

    /// The derivative $C'$: a periodic B-spline of degree `p − 1` on the same knots.
    ///
    /// # Errors
    /// [`ErrorKind::Unsupported`] for degree 0; [`ErrorKind::NonFinite`] when a
    /// coefficient overflows.
    pub fn derivative(&self) -> Result<Self> {
        if self.degree() == 0 {
            return Err(Error::new(
                ErrorKind::Unsupported,
                "the derivative of a periodic curve of degree 0 is not a periodic B-spline",
            ));
        }
        let d = self.wrapped.derivative(1)?;
        Ok(Self {
            wrapped: d,
            count: self.count,
        })
    }

    /// The same closed curve traversed backwards: $\tilde C(u) = C(a + b - u)$.
    #[must_use]
    pub fn reversed(&self) -> Self {
        Self {
            wrapped: self.wrapped.reversed(),
            count: self.count,
        }
    }
}

impl<T: Scalar, P: ControlPoint<T>> ParamCurve<T> for PeriodicBSpline<T, P> {
    type Point = P;
    type Coefficient = P;

    fn domain(&self) -> (T, T) {
        Self::domain(self)
    }

    fn eval(&self, u: T) -> Result<P> {
        Self::eval(self, u)
    }

    fn derivatives_into(&self, u: T, out: &mut [P]) -> Result<()> {
        self.wrapped.derivatives_into(self.reduce(u)?, out)
    }

    fn breaks(&self) -> Vec<T> {
        self.wrapped.knots().domain_breaks()
    }

    fn bezier_pieces(&self) -> Vec<(T, T, Vec<P>)> {
        ParamCurve::bezier_pieces(&self.wrapped)
    }

    fn project(coefficient: &P) -> P {
        *coefficient
    }

    /// The control polygon, closed: $c_0, …, c_{N-1}, c_0$.
    fn control_polygon(&self) -> Vec<P> {
        let mut points = self.control_points().to_vec();
        points.push(points[0]);
        points
    }
}

/// Checks the degree and the counts of a periodic spline.
fn check_periodic_shape(degree: usize, knots: usize, points: usize) -> Result<()> {
    if degree > MAX_DEGREE {
        return Err(Error::new(
            ErrorKind::DegreeTooHigh,
            format!("degree {degree} exceeds the maximum {MAX_DEGREE}"),
        ));
    }
    if knots != points {
        return Err(Error::invalid_length(
            "knots of one period (one per control point)",
            points,
            knots,
        ));
    }
    if points < degree + 1 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "a periodic B-spline of degree {degree} needs at least {} control points, got {points}",
                degree + 1
            ),
        ));
    }
    Ok(())
}

/// Multiplicities of the periodic sequence (the images of the first knot included).
fn check_multiplicities<T: Scalar>(knots: &KnotVector<T>, degree: usize, n: usize) -> Result<()> {
    let (a, b) = knots.domain();
    for (u, m) in knots.breakpoints() {
        if u >= a && u < b && m > degree {
            return Err(Error::new(
                ErrorKind::KnotMultiplicity,
                format!(
                    "knot {} has multiplicity {m} > degree {degree}: a periodic curve must be continuous ({n} knots per period)",
                    to_f64(u)
                ),
            ));
        }
    }
    Ok(())
}

/// The knots $t_{-p} … t_{N\cdot\text{periods}+p}$ of the periodic sequence.
fn extend_knots<T: Scalar>(one: &[T], period: T, degree: usize, periods: usize) -> Vec<T> {
    let n = one.len();
    let total = n * periods + 2 * degree + 1;
    // j = k − p, written as q·N + r with 0 ≤ r < N (q may be negative): shifted by `offset`
    // periods to stay in unsigned arithmetic.
    let offset = degree.div_ceil(n).max(1);
    (0..total)
        .map(|k| {
            let j = k + n * offset - degree;
            let (q, r) = (j / n, j % n);
            one[r] + period * (from_count::<T>(q) - from_count::<T>(offset))
        })
        .collect()
}
