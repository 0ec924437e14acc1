//! Adaptive arc length (the quadrature behind [`crate::ParamCurve::arc_length`]).

use crate::Bezier;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, cast, gauss_legendre, to_f64};

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

/// A part of a piece is free of near-stops when its velocity's Bézier coefficients all lie
/// on one side of the origin by at least this fraction of the largest of them (the speed
/// then varies by at most this factor over the part).
const STOP_MARGIN: f64 = 0.25;

/// The most cuts of one piece ([`stop_cuts`]): four stops at the deepest halving.
const MAX_STOP_CUTS: usize = 4 * MAX_STOP_DEPTH;

/// The deepest halving of a piece around a stop (a true cusp, `C' = 0`, is never free):
/// what is left unseparated is `2⁻⁴⁰` of the piece, around a speed that vanishes there.
const MAX_STOP_DEPTH: usize = 40;

/// Appends to `out` the parameters inside the piece `[lo, hi]` (Bézier `coefficients`,
/// homogeneous with the weight beyond `point_dim` when rational) at which to cut it so that
/// no part has a near-stop inside: a place where the speed dips far below its size on
/// either side (a zigzag that almost turns back). Gauss nodes spread over a piece step over
/// such a narrow dip, and two estimates agree while both miss it (10⁵ pieces of a steep
/// zigzag lost `8·10⁻⁷` of their length at an accuracy of `10⁻⁹`). The velocity's
/// numerator — the hodograph `A'` of a polynomial piece, `w A' − w' A` of a rational one,
/// in Bernstein form — is halved by de Casteljau until its coefficients lie on one side of
/// the origin by [`STOP_MARGIN`] of their size.
pub(crate) fn stop_cuts<T: Scalar, Q: ControlPoint<T>>(
    coefficients: &[Q],
    point_dim: usize,
    (lo, hi): (T, T),
    out: &mut Vec<T>,
) {
    let Some(velocity) = velocity_numerator(coefficients, point_dim) else {
        return;
    };
    let mut todo = vec![(velocity, T::zero(), T::one(), 0usize)];
    let mut cuts = Vec::new();
    while let Some((part, s0, s1, depth)) = todo.pop() {
        // Near-stops are isolated: a few halvings each. The bound keeps the work finite
        // whatever the piece (a part that is never free would otherwise fill a whole
        // binary tree).
        if depth >= MAX_STOP_DEPTH || cuts.len() >= MAX_STOP_CUTS || free_of_stops(&part) {
            continue;
        }
        let (left, right) = halve(&part);
        let mid = (s0 + s1) * cast(0.5);
        cuts.push(mid);
        todo.push((left, s0, mid, depth + 1));
        todo.push((right, mid, s1, depth + 1));
    }
    cuts.sort_by(|a, b| a.partial_cmp(b).unwrap_or(core::cmp::Ordering::Equal));
    out.extend(
        cuts.into_iter()
            .map(|s| lo + (hi - lo) * s)
            .filter(|&u| u > lo && u < hi),
    );
}

/// The Bernstein coefficients (rows of `point_dim` numbers) of a polynomial whose direction
/// and zeros are those of the piece's velocity: differences of the control points, or of
/// `w A' − w' A` (degree `2p − 1` as a product; the common factor `p` dropped). `None` for
/// a piece of degree 0 or with non-finite coefficients.
fn velocity_numerator<T: Scalar, Q: ControlPoint<T>>(
    coefficients: &[Q],
    point_dim: usize,
) -> Option<Vec<Vec<T>>> {
    let p = coefficients.len().checked_sub(1).filter(|&p| p > 0)?;
    // A rational piece divided by its largest weight (the same curve): products of
    // weights and coordinates then stay finite for points up to the largest float.
    let largest_weight = if Q::DIM == point_dim {
        T::one()
    } else {
        coefficients
            .iter()
            .map(|q| q.coord(point_dim).abs())
            .fold(T::zero(), nalgebra::RealField::max)
    };
    if !(largest_weight > T::zero() && largest_weight.is_finite()) {
        return None;
    }
    let coordinate = |q: &Q, i: usize| q.coord(i) / largest_weight;
    let rows: Vec<Vec<T>> = if Q::DIM == point_dim {
        coefficients
            .windows(2)
            .map(|w| {
                (0..point_dim)
                    .map(|i| coordinate(&w[1], i) - coordinate(&w[0], i))
                    .collect()
            })
            .collect()
    } else {
        // (f g)_k = Σ_{i+j=k} C(p, i) C(p−1, j) / C(2p−1, k) f_i g_j with f = w, g = ΔA
        // (and f = A, g = Δw).
        let weight = |q: &Q| coordinate(q, point_dim);
        let binomial = |n: usize, k: usize| -> T {
            (0..k).fold(T::one(), |c, m| {
                c * cast::<T>((n - m) as f64) / cast::<T>((m + 1) as f64)
            })
        };
        (0..2 * p)
            .map(|k| {
                let mut row = vec![T::zero(); point_dim];
                for i in k.saturating_sub(p - 1)..=k.min(p) {
                    let j = k - i;
                    let factor = binomial(p, i) * binomial(p - 1, j) / binomial(2 * p - 1, k);
                    let a = &coefficients[i];
                    let (c, d) = (&coefficients[j], &coefficients[j + 1]);
                    let dw = weight(d) - weight(c);
                    for (r, value) in row.iter_mut().enumerate() {
                        let da = coordinate(d, r) - coordinate(c, r);
                        *value += factor * (weight(a) * da - coordinate(a, r) * dw);
                    }
                }
                row
            })
            .collect()
    };
    // Divided by their largest coordinate: lengths and products of the rows neither
    // overflow nor underflow at any scale of the points (only their directions matter).
    if rows.iter().flatten().any(|v: &T| !v.is_finite()) {
        return None;
    }
    let largest = rows
        .iter()
        .flatten()
        .fold(T::zero(), |m, v| if v.abs() > m { v.abs() } else { m });
    if largest == T::zero() {
        return Some(rows);
    }
    Some(
        rows.into_iter()
            .map(|row| row.into_iter().map(|v| v / largest).collect())
            .collect(),
    )
}

/// Whether the rows lie on one side of the origin by [`STOP_MARGIN`] of the largest: along
/// the direction of their sum, every row reaches that far (all zero: a point, no stop to
/// resolve).
fn free_of_stops<T: Scalar>(rows: &[Vec<T>]) -> bool {
    let norm = |v: &[T]| v.iter().fold(T::zero(), |s, &x| s + x * x).sqrt();
    let largest = rows
        .iter()
        .map(|r| norm(r))
        .fold(T::zero(), nalgebra::RealField::max);
    if largest == T::zero() {
        return true;
    }
    let dim = rows[0].len();
    let sum: Vec<T> = (0..dim)
        .map(|i| rows.iter().fold(T::zero(), |s, r| s + r[i]))
        .collect();
    let length = norm(&sum);
    if !(length > T::zero()) {
        return false;
    }
    rows.iter().all(|r| {
        let along = r.iter().zip(&sum).fold(T::zero(), |s, (&a, &b)| s + a * b) / length;
        along >= largest * cast(STOP_MARGIN)
    })
}

/// De Casteljau at ½ on rows of coefficients.
fn halve<T: Scalar>(rows: &[Vec<T>]) -> (Vec<Vec<T>>, Vec<Vec<T>>) {
    let n = rows.len();
    let mut work = rows.to_vec();
    let mut left = Vec::with_capacity(n);
    let mut right = Vec::with_capacity(n);
    left.push(work[0].clone());
    right.push(work[n - 1].clone());
    for level in 1..n {
        for k in 0..n - level {
            let next = work[k + 1].clone();
            for (a, b) in work[k].iter_mut().zip(next) {
                *a = (*a + b) * cast(0.5);
            }
        }
        left.push(work[0].clone());
        right.push(work[n - 1 - level].clone());
    }
    right.reverse();
    (left, right)
}

#[cfg(test)]
mod tests {
    use super::{stop_cuts, velocity_numerator};
    use nalgebra::{Vector2, Vector3};

    /// The value at `t` of Bernstein rows.
    fn bernstein(rows: &[Vec<f64>], t: f64) -> Vec<f64> {
        let mut work = rows.to_vec();
        for level in 1..rows.len() {
            for k in 0..rows.len() - level {
                let next = work[k + 1].clone();
                for (a, b) in work[k].iter_mut().zip(next) {
                    *a = (1.0 - t) * *a + t * b;
                }
            }
        }
        work[0].clone()
    }

    /// A rational quadratic (weights 1, 0.3, 2): `p N(t) / w(t)²` is the velocity of the
    /// projected curve (up to the rows' normalisation, one factor), against central
    /// differences.
    #[test]
    fn the_rational_numerator_is_the_velocity_times_the_squared_weight() {
        let (points, weights) = (
            [
                Vector2::new(1.0, 0.0),
                Vector2::new(1.5, 2.0),
                Vector2::new(-1.0, 0.5),
            ],
            [1.0, 0.3, 2.0],
        );
        let homogeneous: Vec<Vector3<f64>> = points
            .iter()
            .zip(weights)
            .map(|(p, w)| Vector3::new(p.x * w, p.y * w, w))
            .collect();
        let rows = velocity_numerator(&homogeneous, 2).unwrap();
        assert_eq!(rows.len(), 4);
        let curve = |t: f64| {
            let b = [(1.0 - t) * (1.0 - t), 2.0 * t * (1.0 - t), t * t];
            let h: Vector3<f64> = (0..3).map(|i| homogeneous[i] * b[i]).sum();
            (Vector2::new(h.x / h.z, h.y / h.z), h.z)
        };
        // The rows are normalised: `p N / w²` is the velocity times one constant factor.
        let mut factors = Vec::new();
        for t in [0.0f64, 0.17, 0.5, 0.83, 1.0] {
            let h = 1e-6f64;
            let (lo, hi) = ((t - h).max(0.0), (t + h).min(1.0));
            let velocity = (curve(hi).0 - curve(lo).0) / (hi - lo);
            let n = bernstein(&rows, t);
            let w = curve(t).1;
            let predicted = Vector2::new(n[0], n[1]) * (2.0 / (w * w));
            let factor = predicted.norm() / velocity.norm();
            assert!(
                (predicted / factor - velocity).norm() < 1e-5 * velocity.norm(),
                "t = {t}: {predicted} vs {velocity}"
            );
            factors.push(factor);
        }
        assert!(
            factors.iter().all(|f| (f / factors[0] - 1.0).abs() < 1e-5),
            "{factors:?}"
        );
    }

    /// A cubic that nearly turns back twice (y' vanishes at t ≈ 0.26 and 0.74 while x moves
    /// at 1e-5 of the speed's size) is cut on both sides of its slowest point, close to it;
    /// a straight piece and a gentle arc are not cut.
    #[test]
    fn pieces_are_cut_around_near_stops_only() {
        let dip = [
            Vector2::new(0.0, 0.0),
            Vector2::new(1e-5, 1.0),
            Vector2::new(2e-5, -0.6),
            Vector2::new(3e-5, 0.4),
        ];
        let mut cuts = Vec::new();
        stop_cuts(&dip, 2, (2.0, 3.0), &mut cuts);
        assert!(!cuts.is_empty());
        // The same cuts at every scale of the points (the rows are normalised: at 1e300 their
        // squares overflowed, every part failed the test and the halvings filled a tree).
        for scale in [1e300, 1e-300] {
            let scaled: Vec<Vector2<f64>> = dip.iter().map(|p| p * scale).collect();
            let mut at_scale = Vec::new();
            stop_cuts(&scaled, 2, (2.0, 3.0), &mut at_scale);
            assert_eq!(at_scale, cuts, "at {scale:e}");
        }
        assert!(cuts.windows(2).all(|w| w[0] < w[1]));
        assert!(cuts.iter().all(|&u| u > 2.0 && u < 3.0));
        // The speed's minimum is between two cuts that are close together.
        let speed = |u: f64| {
            let t = u - 2.0;
            let d: Vector2<f64> = (0..3)
                .map(|i| {
                    let b = [(1.0 - t) * (1.0 - t), 2.0 * t * (1.0 - t), t * t][i];
                    (dip[i + 1] - dip[i]) * (3.0 * b)
                })
                .sum();
            d.norm()
        };
        let slowest = (0..=100_000)
            .map(|k| 2.0 + f64::from(k) / 100_000.0)
            .min_by(|a, b| speed(*a).total_cmp(&speed(*b)))
            .unwrap();
        let after = cuts.partition_point(|&u| u < slowest);
        assert!(after > 0 && after < cuts.len(), "{slowest} {cuts:?}");
        assert!(cuts[after] - cuts[after - 1] < 1e-3, "{slowest} {cuts:?}");
        for gentle in [
            [
                Vector2::new(0.0, 0.0),
                Vector2::new(1.0, 0.0),
                Vector2::new(2.0, 0.0),
                Vector2::new(3.0, 0.0),
            ],
            [
                Vector2::new(0.0, 0.0),
                Vector2::new(1.0, 0.5),
                Vector2::new(2.0, 0.5),
                Vector2::new(3.0, 0.0),
            ],
        ] {
            let mut none = Vec::new();
            stop_cuts(&gentle, 2, (0.0, 1.0), &mut none);
            assert!(none.is_empty(), "{none:?}");
        }
    }
}
