//! Near-stops of a piece: where its speed dips far below its size on either side, and the
//! cuts that keep Gauss nodes from stepping over such a dip.

use spline_core::{ControlPoint, Scalar, cast};

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
