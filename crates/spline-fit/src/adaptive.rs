//! Approximation of any parametric map within a tolerance by adaptive knot refinement: the
//! one implementation behind reparametrisation by arc length, offsets and degree reduction.

use crate::lsq::LeastSquares;
use crate::params::check_degree;
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, from_count,
    power_of_two_scale, to_f64,
};
use spline_geom::BSpline;
use std::cell::Cell;

/// The power of two near the size of the first values a map returns (one until then): the
/// adaptive fits divide every value by it (exact), so that their least squares and
/// deviations are those of the unscaled map at any scale from 1e-300 to 1e300.
pub(crate) struct FirstScale<T>(Cell<Option<T>>);

impl<T: Scalar> FirstScale<T> {
    pub(crate) fn new() -> Self {
        Self(Cell::new(None))
    }

    /// The scale, one before the first values.
    pub(crate) fn get(&self) -> T {
        self.0.get().unwrap_or_else(T::one)
    }

    /// Divides `points` by the scale, fixed from them if they are the first values.
    pub(crate) fn divide<P: ControlPoint<T>>(&self, points: &mut [P]) {
        let s = self.0.get().unwrap_or_else(|| {
            let largest = points.iter().fold(T::zero(), |m, q| m.max(q.max_abs()));
            let s = cast(power_of_two_scale(to_f64(largest)));
            self.0.set(Some(s));
            s
        });
        let inverse = T::one() / s;
        for q in points {
            *q = *q * inverse;
        }
    }
}

/// A tolerance below this many units in the last place of the values (their power-of-four
/// scale) is refused by [`AdaptiveApproximation`] when the first fit does not meet it.
const ROUNDING_FLOOR: f64 = 4.0;

/// The most pieces [`AdaptiveApproximation`] allows by default.
pub const MAX_ADAPTIVE_PIECES: usize = 100_000;

/// Approximation of a map $f : [a, b] \to \mathbb{R}^D$ by a clamped B-spline of degree `p`
/// within a tolerance: least squares on `2 (p + 1)` samples per knot span, ends pinned
/// ($C(a) = f(a)$, $C(b) = f(b)$), the deviation measured at `4 (p + 1)` other points per
/// span, and every span whose deviation exceeds **half** the tolerance split in two; until
/// every span meets it. The tolerance is absolute (in the units of the map's values); the
/// computation is scale-invariant: the values are divided by a power of four near their
/// size before the least squares and the deviations, so a map scaled by any factor from
/// 1e-300 to 1e300, with its tolerance, gives the same fit scaled. The fit is $C^{p-1}$ except at `corners` (multiplicity `p`, `C⁰`),
/// where `f` may have a kink (the cusps of an offset).
///
/// ```
/// use spline_fit::AdaptiveApproximation;
/// let fit = AdaptiveApproximation::new(3, 1e-8)
///     .fit((0.0, 3.0), |t: f64| Ok(t.sin()))?;
/// assert!(fit.max_error <= 1e-8);
/// assert!((fit.curve.eval(1.0)? - 1.0f64.sin()).abs() < 1e-8);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct AdaptiveApproximation<T> {
    degree: usize,
    tolerance: T,
    breaks: Vec<T>,
    corners: Vec<T>,
    max_pieces: usize,
}

/// The result of [`AdaptiveApproximation::fit`].
#[derive(Clone, Debug)]
pub struct AdaptiveFit<T, P> {
    /// The approximating curve on `[a, b]`.
    pub curve: BSpline<T, P>,
    /// The largest deviation $\lVert C(u) - f(u) \rVert$ at the check points.
    pub max_error: T,
    /// How many refinement passes were needed.
    pub passes: usize,
}

impl<T: Scalar> AdaptiveApproximation<T> {
    /// Degree `p` and the tolerance on $\lVert C(u) - f(u) \rVert$.
    #[must_use]
    pub fn new(degree: usize, tolerance: T) -> Self {
        Self {
            degree,
            tolerance,
            breaks: Vec::new(),
            corners: Vec::new(),
            max_pieces: MAX_ADAPTIVE_PIECES,
        }
    }

    /// Initial interior knots (simple), e.g. the breaks of the map.
    #[must_use]
    pub fn breaks(mut self, breaks: &[T]) -> Self {
        self.breaks = breaks.to_vec();
        self
    }

    /// Interior parameters where the fit is only `C⁰` (knots of multiplicity `p`).
    #[must_use]
    pub fn corners(mut self, corners: &[T]) -> Self {
        self.corners = corners.to_vec();
        self
    }

    /// The most knot spans allowed (default [`MAX_ADAPTIVE_PIECES`]); with the number of
    /// initial spans, no refinement happens and the fit fails unless it meets the tolerance.
    #[must_use]
    pub fn max_pieces(mut self, pieces: usize) -> Self {
        self.max_pieces = pieces;
        self
    }

    /// Fits `f` on `[a, b]`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidTolerance`] unless the tolerance is positive and finite, or when
    /// it is below the rounding of the values (4 units in their last place) and the first
    /// fit does not meet it;
    /// [`ErrorKind::DegreeTooHigh`]; [`ErrorKind::EmptyDomain`] unless `a < b` (finite);
    /// [`ErrorKind::OutOfDomain`] for breaks or corners outside `(a, b)`;
    /// [`ErrorKind::ToleranceExceeded`] when more than the allowed pieces would be needed
    /// (the message gives the best deviation reached); the errors of `f`.
    pub fn fit<P: ControlPoint<T>>(
        &self,
        domain: (T, T),
        f: impl Fn(T) -> Result<P>,
    ) -> Result<AdaptiveFit<T, P>> {
        self.fit_many(domain, |us| us.iter().map(|&u| f(u)).collect())
    }

    /// [`Self::fit`] for a map evaluated on many parameters at once (always increasing),
    /// for maps that are cheaper in batches (arc length).
    ///
    /// # Errors
    /// As [`Self::fit`].
    pub fn fit_many<P: ControlPoint<T>>(
        &self,
        (a, b): (T, T),
        f: impl Fn(&[T]) -> Result<Vec<P>>,
    ) -> Result<AdaptiveFit<T, P>> {
        check_degree(self.degree)?;
        if !(self.tolerance > T::zero() && self.tolerance.is_finite()) {
            return Err(Error::invalid_tolerance(
                "approximation tolerance",
                "positive and finite",
                to_f64(self.tolerance),
            ));
        }
        if !(a.is_finite() && b.is_finite() && a < b) {
            return Err(Error::new(
                ErrorKind::EmptyDomain,
                format!("cannot approximate on [{}, {}]", to_f64(a), to_f64(b)),
            ));
        }
        for &u in self.breaks.iter().chain(&self.corners) {
            if !(u > a && u < b) {
                return Err(Error::out_of_domain(to_f64(u), (to_f64(a), to_f64(b)))
                    .context("interior break"));
            }
        }
        let p = self.degree.max(1);
        let mut breaks: Vec<T> = self.breaks.iter().chain(&self.corners).copied().collect();
        breaks.push(a);
        breaks.push(b);
        breaks.sort_by(|x, y| x.partial_cmp(y).unwrap_or(std::cmp::Ordering::Equal));
        breaks.dedup();
        // The values are divided by a power of four near the size of the first samples
        // (exact), so that the fit and its deviations are those of the unscaled map: no
        // underflow of the least squares at 1e-300, no overflow at 1e300.
        let scale = FirstScale::new();
        let scaled = |us: &[T]| -> Result<Vec<P>> {
            let mut points = f(us)?;
            scale.divide(&mut points);
            Ok(points)
        };
        let mut passes = 0;
        loop {
            let (mut curve, errors) = self.fit_on(p, &breaks, &scaled)?;
            let s = scale.get();
            let target = self.tolerance * cast(0.5) / s;
            let worst = errors.iter().fold(T::zero(), |m, &e| m.max(e)) * s;
            let bad: Vec<usize> = (0..errors.len()).filter(|&k| errors[k] > target).collect();
            // A tolerance below the rounding of the values can never be met: refining would
            // only run to the limit of pieces (tens of seconds).
            let floor = cast::<T>(ROUNDING_FLOOR * f64::EPSILON) * s;
            if !bad.is_empty() && self.tolerance < floor {
                return Err(Error::invalid_tolerance(
                    "approximation tolerance",
                    &format!(
                        "at least {:.1e} ({ROUNDING_FLOOR} units in the last place of the values, of size about {:.1e})",
                        to_f64(floor),
                        to_f64(s)
                    ),
                    to_f64(self.tolerance),
                ));
            }
            if bad.is_empty() {
                for q in curve.control_points_mut() {
                    *q = *q * s;
                }
                return Ok(AdaptiveFit {
                    curve,
                    max_error: worst,
                    passes,
                });
            }
            if breaks.len() - 1 + bad.len() > self.max_pieces {
                return Err(Error::new(
                    ErrorKind::ToleranceExceeded,
                    format!(
                        "the approximation needs more than {} pieces: the best deviation reached is {:.3e} (tolerance {:.3e})",
                        self.max_pieces,
                        to_f64(worst),
                        to_f64(self.tolerance)
                    ),
                ));
            }
            let mut refined = Vec::with_capacity(breaks.len() + bad.len());
            for k in 0..breaks.len() - 1 {
                refined.push(breaks[k]);
                if bad.binary_search(&k).is_ok() {
                    let mid = (breaks[k] + breaks[k + 1]) * cast(0.5);
                    if mid > breaks[k] && mid < breaks[k + 1] {
                        refined.push(mid);
                    }
                }
            }
            refined.push(b);
            if refined.len() == breaks.len() {
                return Err(Error::new(
                    ErrorKind::ToleranceExceeded,
                    format!(
                        "the approximation cannot be refined further (pieces at rounding size): best deviation {:.3e}",
                        to_f64(worst)
                    ),
                ));
            }
            breaks = refined;
            passes += 1;
        }
    }

    /// The least-squares fit on the knots with these breaks and the deviation per span.
    fn fit_on<P: ControlPoint<T>>(
        &self,
        p: usize,
        breaks: &[T],
        f: &impl Fn(&[T]) -> Result<Vec<P>>,
    ) -> Result<(BSpline<T, P>, Vec<T>)> {
        let (a, b) = (breaks[0], breaks[breaks.len() - 1]);
        let mut interior = Vec::new();
        for &u in &breaks[1..breaks.len() - 1] {
            let times = if self.corners.contains(&u) { p } else { 1 };
            interior.extend(std::iter::repeat_n(u, times));
        }
        let knots = KnotVector::clamped(p, a, b, &interior)?;
        let per_fit = 2 * (p + 1);
        let per_check = 4 * (p + 1);
        let mut params = Vec::with_capacity((breaks.len() - 1) * per_fit + 1);
        for w in breaks.windows(2) {
            for j in 0..per_fit {
                params.push(w[0] + (w[1] - w[0]) * from_count::<T>(j) / from_count::<T>(per_fit));
            }
        }
        params.push(b);
        let points = f(&params)?;
        let control = LeastSquares::new(&points, &params, knots.clone())
            .pin_ends()
            .control_points()?;
        let curve = BSpline::new(knots, control)?;
        let mut checks = Vec::with_capacity((breaks.len() - 1) * per_check);
        for w in breaks.windows(2) {
            for j in 0..per_check {
                // Offsets by half a step from the fitting samples.
                let t = from_count::<T>(2 * j + 1) / from_count::<T>(2 * per_check);
                checks.push(w[0] + (w[1] - w[0]) * t);
            }
        }
        let values = f(&checks)?;
        let mut errors = vec![T::zero(); breaks.len() - 1];
        for (i, (&u, v)) in checks.iter().zip(&values).enumerate() {
            let e = &mut errors[i / per_check];
            *e = (*e).max((curve.eval(u)? - *v).length());
        }
        Ok((curve, errors))
    }
}
