//! Bézier curves: Bernstein form on a parameter interval.

use crate::bspline::BSpline;
use crate::structural::BernsteinElevation;
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, MAX_ORDER, Result, Scalar, VectorSpace,
    bernstein_all, from_count, to_f64,
};

/// A Bézier curve of degree `n` on `[a, b]`:
/// $P(t) = \sum_{i=0}^{n} B_i^n\\!\left(\frac{t-a}{b-a}\right) P_i$.
///
/// Any degree is accepted (interpolating Bézier curves of seed 003 have one control point per
/// data point); degrees above [`spline_core::MAX_DEGREE`] fall back to heap memory in
/// de Casteljau's algorithm and cannot become a [`BSpline`].
///
/// ```
/// use spline_geom::Bezier;
/// let b = Bezier::new(vec![0.0, 1.0, 0.0])?;
/// assert_eq!(b.eval(0.5)?, 0.5);
/// let (left, right) = b.subdivide(0.5)?;
/// assert_eq!(left.control_points(), &[0.0, 0.5, 0.5]);
/// assert_eq!(right.control_points(), &[0.5, 0.5, 0.0]);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Bezier<T, P> {
    control_points: Vec<P>,
    start: T,
    end: T,
}

/// Accessors, for any point type.
impl<T: Scalar, P> Bezier<T, P> {
    pub(crate) fn new_unchecked(control_points: Vec<P>, start: T, end: T) -> Self {
        Self {
            control_points,
            start,
            end,
        }
    }

    /// The degree `n` (number of control points − 1).
    #[must_use]
    pub fn degree(&self) -> usize {
        self.control_points.len() - 1
    }

    /// The control points.
    #[must_use]
    pub fn control_points(&self) -> &[P] {
        &self.control_points
    }

    /// Mutable access to the control points (their number, the degree plus one, is fixed).
    #[inline]
    pub fn control_points_mut(&mut self) -> &mut [P] {
        &mut self.control_points
    }

    /// The parameter interval `[a, b]`.
    #[must_use]
    pub fn interval(&self) -> (T, T) {
        (self.start, self.end)
    }
}

impl<T: Scalar, P: ControlPoint<T>> Bezier<T, P> {
    /// A Bézier curve on `[0, 1]`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] without control points; [`ErrorKind::NonFinite`].
    pub fn new(control_points: Vec<P>) -> Result<Self> {
        Self::with_interval(control_points, T::zero(), T::one())
    }

    /// A Bézier curve on `[a, b]`.
    ///
    /// # Errors
    /// As [`Bezier::new`]; [`ErrorKind::EmptyDomain`] unless `a < b`.
    pub fn with_interval(control_points: Vec<P>, a: T, b: T) -> Result<Self> {
        if control_points.is_empty() {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                "a Bézier curve needs at least one control point",
            ));
        }
        if let Some(i) = control_points.iter().position(|p| !p.all_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("control point {i} is not finite"),
            ));
        }
        if !(a.is_finite() && b.is_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                "interval ends must be finite",
            ));
        }
        if !(a < b) {
            return Err(Error::new(
                ErrorKind::EmptyDomain,
                format!("interval [{}, {}] is empty", to_f64(a), to_f64(b)),
            ));
        }
        Ok(Self::new_unchecked(control_points, a, b))
    }

    fn local(&self, t: T) -> Result<T> {
        if !t.is_finite() {
            return Err(Error::new(ErrorKind::NonFinite, "parameter is not finite"));
        }
        if t < self.start || t > self.end {
            return Err(Error::new(
                ErrorKind::OutOfDomain,
                format!(
                    "parameter {} is outside the interval [{}, {}]",
                    to_f64(t),
                    to_f64(self.start),
                    to_f64(self.end)
                ),
            ));
        }
        Ok((t - self.start) / (self.end - self.start))
    }

    /// The point at `t` by de Casteljau's algorithm (seed 003 TD1): repeated linear
    /// interpolation, numerically the most stable evaluation.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn eval(&self, t: T) -> Result<P> {
        let s = self.local(t)?;
        let n = self.degree();
        let mut stack = [P::origin(); MAX_ORDER];
        let mut heap;
        let work: &mut [P] = if n < MAX_ORDER {
            stack[..=n].copy_from_slice(&self.control_points);
            &mut stack[..=n]
        } else {
            heap = self.control_points.clone();
            &mut heap
        };
        let r = T::one() - s;
        for level in 1..=n {
            for i in 0..=n - level {
                work[i] = work[i] * r + work[i + 1] * s;
            }
        }
        Ok(work[0])
    }

    /// The point at `t` as $\sum B_i^n P_i$ with all Bernstein polynomials computed by their
    /// recurrence (the original evaluation of seed 003 TD1).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn eval_bernstein(&self, t: T) -> Result<P> {
        let s = self.local(t)?;
        let n = self.degree();
        let mut b = vec![T::zero(); n + 1];
        bernstein_all(n, s, &mut b);
        Ok(self
            .control_points
            .iter()
            .zip(&b)
            .fold(P::origin(), |acc, (p, w)| acc + *p * *w))
    }

    /// De Casteljau's triangle at `t` (seed 003 TD1): level 0 is the control points and
    /// level `j` the $n + 1 - j$ points
    /// $P_i^j = (1 - s)\,P_i^{j-1} + s\,P_{i+1}^{j-1}$, $s = \frac{t-a}{b-a}$, so that
    /// $P_i^j$ is the point at `t` of the Bézier curve of $P_i, \dots, P_{i+j}$; the last
    /// level is the single point $P_0^n = P(t)$, equal to [`Bezier::eval`] bit for bit.
    /// The first points of the levels are the control points of the left half of
    /// [`Bezier::subdivide`] at `t`, the last points (from the last level up) those of the
    /// right half.
    ///
    /// Like [`Bezier::eval`], it accepts the whole closed interval `[a, b]` (at the ends
    /// the triangle degenerates: every level repeats the first, or the last, points of the
    /// one above) and refuses parameters outside it: no extrapolation.
    ///
    /// ```
    /// use spline_geom::Bezier;
    /// let b = Bezier::new(vec![0.0, 4.0, 8.0])?;
    /// let levels = b.de_casteljau(0.25)?;
    /// assert_eq!(levels, vec![vec![0.0, 4.0, 8.0], vec![1.0, 5.0], vec![2.0]]);
    /// assert_eq!(levels[2][0], b.eval(0.25)?);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] for a non-finite `t`; [`ErrorKind::OutOfDomain`] for `t`
    /// outside `[a, b]`.
    pub fn de_casteljau(&self, t: T) -> Result<Vec<Vec<P>>> {
        let s = self.local(t)?;
        let mut work = self.control_points.clone();
        let mut levels = Vec::with_capacity(work.len());
        casteljau_levels(&mut work, s, |level| levels.push(level.to_vec()));
        Ok(levels)
    }

    /// Splits at `t` (seed 004 §8.4): the left and right Bézier curves on `[a, t]` and
    /// `[t, b]`, whose control points are the two sides of the de Casteljau triangle
    /// ([`Bezier::de_casteljau`]).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::OutOfDomain`] unless `a < t < b`.
    pub fn subdivide(&self, t: T) -> Result<(Self, Self)> {
        let s = self.local(t)?;
        if !(t > self.start && t < self.end) {
            return Err(Error::new(
                ErrorKind::OutOfDomain,
                "subdivision parameter must lie strictly inside the interval",
            ));
        }
        let mut work = self.control_points.clone();
        let mut left = Vec::with_capacity(work.len());
        let mut right = Vec::with_capacity(work.len());
        casteljau_levels(&mut work, s, |level| {
            left.push(level[0]);
            right.push(level[level.len() - 1]);
        });
        right.reverse();
        Ok((
            Self::new_unchecked(left, self.start, t),
            Self::new_unchecked(right, t, self.end),
        ))
    }

    /// Raises the degree by `times`:
    /// $Q_i = \sum_j \binom{n}{j}\binom{r}{i-j} / \binom{n+r}{i}\ P_j$ (the Bernstein elevation
    /// that [`BSpline::elevate_degree`] applies to every segment).
    ///
    /// # Panics
    /// If `n + times` overflows `usize` (a programmer error: no such curve fits in memory).
    #[must_use]
    pub fn elevate_degree(&self, times: usize) -> Self {
        let nh = self
            .degree()
            .checked_add(times)
            .expect("the elevated degree of a Bézier curve overflows usize");
        let mut points = vec![P::origin(); nh + 1];
        BernsteinElevation::new(self.degree(), times).apply(&self.control_points, &mut points);
        Self::new_unchecked(points, self.start, self.end)
    }

    /// The derivative (hodograph) $\frac{n}{b-a}(P_{i+1} - P_i)$, degree `n − 1`; the
    /// derivative of a constant is the zero curve of degree 0.
    #[must_use]
    pub fn derivative(&self) -> Self {
        let mut hodograph = Self::new_unchecked(
            vec![P::origin(); self.degree().max(1)],
            self.start,
            self.end,
        );
        self.derivative_into(&mut hodograph);
        hodograph
    }

    /// [`Bezier::derivative`] written into `hodograph`, a curve on the same interval with
    /// `max(n, 1)` control points (no allocation).
    ///
    /// ```
    /// use spline_geom::Bezier;
    /// let f = Bezier::new(vec![0.0, 1.0, 3.0])?;
    /// let mut d = f.derivative();
    /// Bezier::new(vec![0.0, 2.0, 2.0])?.derivative_into(&mut d);
    /// assert_eq!(d.control_points(), &[4.0, 0.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Panics
    /// If `hodograph` has another number of control points or another interval.
    pub fn derivative_into(&self, hodograph: &mut Self) {
        let n = self.degree();
        assert!(
            hodograph.control_points.len() == n.max(1)
                && hodograph.start == self.start
                && hodograph.end == self.end,
            "the hodograph of a degree-{n} Bézier curve has {} control points on the same interval",
            n.max(1)
        );
        if n == 0 {
            hodograph.control_points[0] = P::origin();
            return;
        }
        let scale = from_count::<T>(n) / (self.end - self.start);
        for (slot, w) in hodograph
            .control_points
            .iter_mut()
            .zip(self.control_points.windows(2))
        {
            *slot = (w[1] - w[0]) * scale;
        }
    }

    /// The same curve as a clamped B-spline on `[a, b]`.
    ///
    /// # Errors
    /// [`ErrorKind::DegreeTooHigh`] above [`spline_core::MAX_DEGREE`].
    pub fn to_bspline(&self) -> Result<BSpline<T, P>> {
        BSpline::new(
            KnotVector::bezier(self.degree(), self.start, self.end)?,
            self.control_points.clone(),
        )
    }
}

/// De Casteljau's triangle at the local parameter `s`, in place: `work` holds the control
/// points on entry; `level` sees level 0 (the control points), then each level `j` as the
/// first `n + 1 - j` points of `work` after $P_i \leftarrow (1 - s) P_i + s P_{i+1}$.
/// The one kernel of [`Bezier::de_casteljau`] and [`Bezier::subdivide`].
fn casteljau_levels<T: Scalar, P: ControlPoint<T>>(
    work: &mut [P],
    s: T,
    mut level: impl FnMut(&[P]),
) {
    let n = work.len() - 1;
    let r = T::one() - s;
    level(work);
    for j in 1..=n {
        for i in 0..=n - j {
            work[i] = work[i] * r + work[i + 1] * s;
        }
        level(&work[..=n - j]);
    }
}

impl<T: Scalar, V: VectorSpace<T>> BSpline<T, V> {
    /// The Bézier segments of the curve, one per non-empty knot span of the domain, each on
    /// its own parameter interval ([`BSpline::to_bernstein`], cut into segments).
    #[must_use]
    pub fn bezier_segments(&self) -> Vec<Bezier<T, V>> {
        let p = self.degree();
        let pieces = self.to_bernstein();
        let breaks = self.knots().domain_breaks();
        pieces
            .control_points()
            .chunks_exact(p + 1)
            .zip(breaks.windows(2))
            .map(|(segment, ends)| Bezier::new_unchecked(segment.to_vec(), ends[0], ends[1]))
            .collect()
    }
}

/// A Bézier segment of a valid B-spline as a clamped B-spline on its interval (its degree
/// is at most [`spline_core::MAX_DEGREE`], so no check is needed).
pub(crate) fn bezier_as_bspline<T: Scalar, P: VectorSpace<T>>(
    segment: &Bezier<T, P>,
) -> BSpline<T, P> {
    let (a, b) = segment.interval();
    let p = segment.degree();
    let mut knots = vec![a; p + 1];
    knots.extend(std::iter::repeat_n(b, p + 1));
    BSpline::new_unchecked(
        KnotVector::new_unchecked(p, knots),
        segment.control_points().to_vec(),
    )
}

#[cfg(test)]
mod tests {
    use super::Bezier;
    use nalgebra::Vector2;
    use spline_core::ErrorKind;

    fn quartic_on(a: f64, b: f64) -> Bezier<f64, Vector2<f64>> {
        Bezier::with_interval(
            vec![
                Vector2::new(0.0, 0.0),
                Vector2::new(1.0, 2.5),
                Vector2::new(3.0, -1.0),
                Vector2::new(4.0, 0.7),
                Vector2::new(5.5, 2.0),
            ],
            a,
            b,
        )
        .unwrap()
    }

    /// The triangle's last point is `eval` bit for bit; its first points are the left half
    /// of `subdivide`, its last points (from the bottom up) the right half; every point of
    /// level `j` is the sub-polygon's curve at `t`.
    #[test]
    fn the_triangle_is_eval_and_subdivide() {
        for (a, b) in [(0.0, 1.0), (-2.0, 3.0)] {
            let curve = quartic_on(a, b);
            let n = curve.degree();
            for k in 1..10 {
                let t = a + (b - a) * f64::from(k) / 10.0;
                let levels = curve.de_casteljau(t).unwrap();
                assert_eq!(levels.len(), n + 1);
                assert_eq!(levels[0], curve.control_points());
                for (j, level) in levels.iter().enumerate() {
                    assert_eq!(level.len(), n + 1 - j);
                    for (i, point) in level.iter().enumerate() {
                        let sub = curve.control_points()[i..=i + j].to_vec();
                        let sub = Bezier::with_interval(sub, a, b).unwrap();
                        assert_eq!(*point, sub.eval(t).unwrap());
                    }
                }
                assert_eq!(levels[n], vec![curve.eval(t).unwrap()]);
                let (left, right) = curve.subdivide(t).unwrap();
                let firsts: Vec<_> = levels.iter().map(|l| l[0]).collect();
                let lasts: Vec<_> = levels.iter().rev().map(|l| l[l.len() - 1]).collect();
                assert_eq!(left.control_points(), firsts);
                assert_eq!(right.control_points(), lasts);
                assert!((curve.eval_bernstein(t).unwrap() - levels[n][0]).norm() < 1e-13);
            }
        }
    }

    /// At the ends of the interval the triangle degenerates (each level repeats the first
    /// or the last points); outside it and for non-finite parameters it is refused, as
    /// `eval` refuses them.
    #[test]
    fn the_triangle_takes_the_closed_interval_only() {
        let curve = quartic_on(-2.0, 3.0);
        let points = curve.control_points();
        let n = curve.degree();
        let at_start = curve.de_casteljau(-2.0).unwrap();
        let at_end = curve.de_casteljau(3.0).unwrap();
        for j in 0..=n {
            assert_eq!(at_start[j], points[..=n - j]);
            assert_eq!(at_end[j], points[j..]);
        }
        for t in [-2.5, 3.0 + 1e-12] {
            assert_eq!(
                curve.de_casteljau(t).unwrap_err().kind(),
                ErrorKind::OutOfDomain
            );
        }
        assert_eq!(
            curve.de_casteljau(f64::NAN).unwrap_err().kind(),
            ErrorKind::NonFinite
        );
        let point = Bezier::new(vec![Vector2::new(1.0, 2.0)]).unwrap();
        assert_eq!(
            point.de_casteljau(0.3).unwrap(),
            vec![vec![Vector2::new(1.0, 2.0)]]
        );
    }
}
