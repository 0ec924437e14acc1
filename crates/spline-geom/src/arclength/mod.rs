//! Adaptive arc length (the quadrature behind [`crate::ParamCurve::arc_length`]).

mod stops;

use crate::Bezier;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, cast, gauss_legendre, to_f64};
pub(crate) use stops::stop_cuts;

/// The default relative accuracy of [`crate::ParamCurve::arc_length`] (and of
/// [`crate::ArcLengthTable`]): lengths to about nine digits at every scale.
pub const DEFAULT_ACCURACY: f64 = 1e-9;

struct Quadrature<T> {
    nodes: Vec<T>,
    weights: Vec<T>,
}

/// The rule's estimate of an integral and the range of the integrand at its nodes.
#[derive(Clone, Copy)]
struct Estimate<T> {
    value: T,
    low: T,
    high: T,
}

impl<T: Scalar> Quadrature<T> {
    fn new(n: usize) -> Self {
        let (nodes, weights) = gauss_legendre::<T>(n).into_iter().unzip();
        Self { nodes, weights }
    }

    fn integrate(&self, a: T, b: T, f: &impl Fn(T) -> T) -> Estimate<T> {
        let half = (b - a) * cast(0.5);
        let mid = (a + b) * cast(0.5);
        let mut sum = T::zero();
        let mut range: Option<(T, T)> = None;
        for (&x, &w) in self.nodes.iter().zip(&self.weights) {
            let y = f(mid + half * x);
            sum += w * y;
            range = Some(range.map_or((y, y), |(low, high)| (low.min(y), high.max(y))));
        }
        let (low, high) = range.unwrap_or((T::zero(), T::zero()));
        Estimate {
            value: sum * half,
            low,
            high,
        }
    }
}

/// $\int \lVert C'(u) \rVert\\,du$ over the pieces between consecutive `breaks` (the speed
/// is smooth inside each), by adaptive Gauss–Legendre quadrature to the **relative**
/// `accuracy`: every piece (and every half a piece is bisected into) is accepted when two
/// estimates agree to `accuracy` times its own length, so the sum is accurate to `accuracy`
/// times the total at any scale of the coordinates and whatever the number of pieces (an
/// absolute accuracy shared among 10⁵ pieces asked each for 1e-15 and took minutes).
/// Below what rounding allows, no interval is asked for more (see [`Piece::adaptive`]): the
/// length is then as accurate as the speed can be evaluated.
///
/// # Errors
/// [`ErrorKind::NoConvergence`] if a piece cannot reach the accuracy.
pub(crate) fn adaptive_length<T: Scalar>(
    breaks: &[T],
    accuracy: T,
    speed: impl Fn(T) -> T,
) -> Result<T> {
    let rule = Quadrature::<T>::new(8);
    let mut total = T::zero();
    for w in breaks.windows(2) {
        let whole = rule.integrate(w[0], w[1], &speed).value;
        // The piece's share: `accuracy` times its length, split between halves on bisection.
        let budget = whole.abs() * accuracy;
        let mut piece = Piece {
            rule: &rule,
            f: &speed,
            ends: (w[0], w[1]),
            noise: None,
            intervals: 0,
        };
        total += piece.adaptive((w[0], w[1]), whole, budget, 0)?;
    }
    Ok(total)
}

/// Bisections below this depth do not measure the speed's rounding (most pieces converge
/// before).
const PROBE_DEPTH: usize = 6;

/// The most intervals one piece may be bisected into (a bound on the work where the speed's
/// rounding is not caught by its measure).
const MAX_INTERVALS: usize = 1 << 16;

/// One piece's quadrature: the rule, the speed, and the rounding of the speed measured on
/// the piece when first needed.
struct Piece<'a, T, F> {
    rule: &'a Quadrature<T>,
    f: &'a F,
    ends: (T, T),
    /// The largest second difference of the speed at neighbouring floating-point parameters
    /// (its rounding), once measured.
    noise: Option<T>,
    intervals: usize,
}

impl<T: Scalar, F: Fn(T) -> T> Piece<'_, T, F> {
    /// The rounding of the speed on the piece: at the rule's nodes $x$, the second
    /// difference $f(x + δ) - 2 f(x) + f(x - δ)$ with $δ$ a few units in the last place of
    /// $x$ (the smooth part, $f'' δ^2$, is far below it): what is left is the speed's
    /// rounding, e.g. of control points far from the origin around a small curve.
    fn noise(&mut self) -> T {
        if let Some(noise) = self.noise {
            return noise;
        }
        let (a, b) = self.ends;
        let half = (b - a) * cast(0.5);
        let mid = (a + b) * cast(0.5);
        let eps = T::default_epsilon();
        let mut noise = T::zero();
        for &x in &self.rule.nodes {
            let u = mid + half * x;
            let delta = eps * cast::<T>(4.0) * (u.abs() + half.abs());
            let second = (self.f)(u + delta) - (self.f)(u) * cast(2.0) + (self.f)(u - delta);
            noise = noise.max(second.abs());
        }
        self.noise = Some(noise);
        noise
    }

    /// The integral over `[a, b]` given the rule's estimate `whole` there (the halves'
    /// estimates are passed down on bisection, not computed again), to the absolute `budget`
    /// (each half gets half of it: the errors of the accepted intervals add up to at most
    /// the piece's budget).
    ///
    /// No interval is asked for less than rounding allows:
    /// - `8 ε` times its value (the rounding of the speeds and of their sum);
    /// - `8 ε max(|a|, |b|)` times the spread of the speed over its nodes: the nodes are
    ///   parameters rounded to `ε |u|`, which moves the speed by its slope times that, and
    ///   over the interval the slope adds up to the spread. Where the speed is steep (a
    ///   rational curve whose weights pile the length up near one end, issue 26) the two
    ///   estimates differ by this however short the interval, and the budget, halved on
    ///   every bisection, fell below it (an accuracy of 2e-27 asked near u = −1.897);
    /// - from depth [`PROBE_DEPTH`] on, twice the speed's measured rounding
    ///   ([`Self::noise`]) times the interval's width: each estimate is off by up to the
    ///   rounding of the speeds it adds up, which no bisection reduces.
    ///
    /// # Errors
    /// [`ErrorKind::NoConvergence`] past 48 bisections or [`MAX_INTERVALS`] intervals.
    fn adaptive(&mut self, (a, b): (T, T), whole: T, budget: T, depth: usize) -> Result<T> {
        self.intervals += 1;
        let mid = (a + b) * cast(0.5);
        let left = self.rule.integrate(a, mid, self.f);
        let right = self.rule.integrate(mid, b, self.f);
        let halves = left.value + right.value;
        let spread = left.high.max(right.high) - left.low.min(right.low);
        let rounding = cast::<T>(8.0) * T::default_epsilon();
        let mut floor = rounding * (halves.abs() + a.abs().max(b.abs()) * spread);
        // The halves estimate is far more accurate than `whole`; their difference bounds its
        // error.
        let difference = (halves - whole).abs();
        if difference > budget.max(floor) && depth >= PROBE_DEPTH {
            floor += self.noise() * cast(2.0) * (b - a);
        }
        let tol = budget.max(floor);
        if difference <= tol {
            return Ok(halves);
        }
        if depth >= 48 || self.intervals >= MAX_INTERVALS {
            return Err(Error::new(
                ErrorKind::NoConvergence,
                format!(
                    "arc length did not reach the accuracy {:.1e} near u = {}",
                    to_f64(tol),
                    to_f64(mid)
                ),
            ));
        }
        let half = budget * cast(0.5);
        Ok(self.adaptive((a, mid), left.value, half, depth + 1)?
            + self.adaptive((mid, b), right.value, half, depth + 1)?)
    }
}

/// A rational Bézier piece whose largest weight exceeds its smallest by more than this is
/// measured by [`rational_piece_length`].
const WEIGHT_RATIO: f64 = 16.0;

/// The weight of a homogeneous coefficient (its last coordinate, the one beyond the
/// point's `point_dim`); `None` for a polynomial coefficient.
fn weight_of<T: Scalar, Q: ControlPoint<T>>(q: &Q, point_dim: usize) -> Option<T> {
    (Q::DIM == point_dim + 1).then(|| q.coord(point_dim))
}

/// Whether the coefficients of a rational piece have weights (all positive and finite)
/// more than [`WEIGHT_RATIO`] apart: the curve then rushes through parts of the piece in
/// parameter intervals as narrow as their ratio (weights `[1, 1e300, 1]` run from `P0` to
/// `P1` in the first 1e-300 of the domain, and from `P1` to `P2` in an interval no
/// parameter near 1 resolves), which quadrature nodes spread over the piece miss.
pub(crate) fn far_apart<T: Scalar, Q: ControlPoint<T>>(
    coefficients: &[Q],
    point_dim: usize,
) -> bool {
    let mut range: Option<(T, T)> = None;
    for q in coefficients {
        let Some(w) = weight_of(q, point_dim) else {
            return false;
        };
        if !(w > T::zero() && w.is_finite()) {
            return false;
        }
        range = Some(range.map_or((w, w), |(lo, hi)| (lo.min(w), hi.max(w))));
    }
    range.is_some_and(|(lo, hi)| hi > lo * cast(WEIGHT_RATIO))
}

/// The length of a rational Bézier piece given by its homogeneous `coefficients` (weights
/// positive, in the last coordinate beyond the point's `point_dim`), whatever its weights:
/// halved by de Casteljau in its own parameter (not the curve's, whose floating-point
/// numbers cannot resolve a part 1e-300 wide near 1) until the weights of every part come
/// within [`WEIGHT_RATIO`], each part scaled to largest weight 1 and measured by the
/// adaptive quadrature of its own speed $\lVert (A' − C w') / w \rVert$ on `[0, 1]`.
///
/// # Errors
/// As [`adaptive_length`].
pub(crate) fn rational_piece_length<T: Scalar, Q: ControlPoint<T>>(
    coefficients: &[Q],
    point_dim: usize,
    accuracy: T,
) -> Result<T> {
    let mut total = T::zero();
    let mut todo = vec![(Bezier::new(coefficients.to_vec())?, 0usize)];
    while let Some((part, depth)) = todo.pop() {
        // 2100 halvings take a weight ratio of 1e600 to 1 (each halves it at least at an
        // end); a part that does not come within the ratio is measured as it is. Each half
        // is taken on [0, 1] again: its own parameter, resolved however narrow it is.
        if far_apart(part.control_points(), point_dim) && depth < 2100 {
            let (left, right) = part.subdivide(cast(0.5))?;
            todo.push((Bezier::new(right.control_points().to_vec())?, depth + 1));
            todo.push((Bezier::new(left.control_points().to_vec())?, depth + 1));
            continue;
        }
        let largest = part
            .control_points()
            .iter()
            .filter_map(|q| weight_of(q, point_dim))
            .fold(T::zero(), nalgebra::RealField::max);
        let part = Bezier::new(
            part.control_points()
                .iter()
                .map(|q| *q * (T::one() / largest))
                .collect(),
        )?;
        let hodograph = part.derivative();
        // The speed ‖(A′ − C w′) / w‖ of the projection C = A / w.
        let speed = |t: T| {
            let (Ok(value), Ok(derivative)) = (part.eval(t), hodograph.eval(t)) else {
                return T::zero();
            };
            let (w, dw) = (value.coord(point_dim), derivative.coord(point_dim));
            (0..point_dim)
                .map(|i| {
                    let d = (derivative.coord(i) - value.coord(i) / w * dw) / w;
                    d * d
                })
                .fold(T::zero(), |sum, d| sum + d)
                .sqrt()
        };
        total += adaptive_length(&[T::zero(), T::one()], accuracy, speed)?;
    }
    Ok(total)
}

/// The length between `a` and `b` of a curve with the Bézier `pieces`, those with weights
/// far apart ([`far_apart`]) clipped to `[a, b]` and measured by [`rational_piece_length`],
/// the others by [`adaptive_length`] of the curve's `speed`.
///
/// # Errors
/// As [`adaptive_length`]; the subdivision's errors for non-finite coefficients.
pub(crate) fn length_by_pieces<T: Scalar, Q: ControlPoint<T>>(
    pieces: &[(T, T, Vec<Q>)],
    point_dim: usize,
    (a, b): (T, T),
    accuracy: T,
    speed: impl Fn(T) -> T,
) -> Result<T> {
    let mut total = T::zero();
    for (lo, hi, coefficients) in pieces {
        let (x, y) = (lo.max(a), hi.min(b));
        if !(x < y) {
            continue;
        }
        if !far_apart(coefficients, point_dim) {
            let mut breaks = vec![x];
            stop_cuts(coefficients, point_dim, (*lo, *hi), &mut breaks);
            breaks.retain(|&u| u >= x && u < y);
            breaks.push(y);
            total += adaptive_length(&breaks, accuracy, &speed)?;
            continue;
        }
        let mut part = Bezier::with_interval(coefficients.clone(), *lo, *hi)?;
        if x > *lo {
            part = part.subdivide(x)?.1;
        }
        if y < *hi {
            part = part.subdivide(y)?.0;
        }
        total += rational_piece_length(part.control_points(), point_dim, accuracy)?;
    }
    Ok(total)
}
