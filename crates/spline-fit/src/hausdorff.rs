//! How far a curve is from data, both ways: data → curve by closest points, and curve →
//! data polyline by dense sampling (together, the two-sided Hausdorff distance between the
//! curve and the polyline through the data).

use crate::project::closest_point;
use crate::report::Deviation;
use spline_core::{
    ControlPoint, Error, ErrorKind, Result, Scalar, cast, from_count, golden_section_max, to_f64,
};
use spline_geom::BSpline;

/// Samples per non-empty knot span for the curve → data direction, before refining the
/// largest one.
const SAMPLES_PER_SPAN: usize = 48;

/// Polyline segments per bounding box of the pruning index.
const CHUNK: usize = 16;

/// The distance of a curve from data points, both ways.
#[derive(Clone, Debug, PartialEq)]
pub struct TwoSidedDeviation<T> {
    /// Data → curve: the closest-point distance of each data point
    /// ([`crate::closest_point`]), with the largest, its index and the RMS.
    pub to_curve: Deviation<T>,
    /// The parameter of each data point's closest point.
    pub params: Vec<T>,
    /// Curve → data: the largest distance from a point of the curve to the polyline through
    /// the data (sampled densely on every knot span, the largest sample refined by golden
    /// section).
    pub to_data: T,
    /// The parameter where the curve is farthest from the polyline.
    pub to_data_param: T,
    /// The largest excess of the curve → data distance over what the polyline's own chords
    /// explain: over the samples, the distance to the nearest polyline segment minus half its
    /// length (a round curve through two data points stays within half their distance of
    /// their chord; a curve that loops or strays between data points does not).
    pub to_data_excess: T,
}

impl<T: Scalar> TwoSidedDeviation<T> {
    /// The two-sided Hausdorff distance: the larger of both directions.
    #[must_use]
    pub fn hausdorff(&self) -> T {
        self.to_curve.max.max(self.to_data)
    }
}

/// Bounding boxes of consecutive chunks of polyline segments, to skip most segments when
/// looking for the nearest one.
struct PolylineIndex<'a, T, P> {
    points: &'a [P],
    boxes: Vec<(P, P)>,
    _scalar: std::marker::PhantomData<T>,
}

impl<'a, T: Scalar, P: ControlPoint<T>> PolylineIndex<'a, T, P> {
    fn new(points: &'a [P]) -> Self {
        let segments = points.len().saturating_sub(1).max(1);
        let boxes = (0..segments.div_ceil(CHUNK))
            .map(|c| {
                let lo = c * CHUNK;
                let hi = ((c + 1) * CHUNK).min(points.len() - 1);
                let mut min = points[lo];
                let mut max = points[lo];
                for q in &points[lo..=hi] {
                    for d in 0..P::DIM {
                        min.set_coord(d, min.coord(d).min(q.coord(d)));
                        max.set_coord(d, max.coord(d).max(q.coord(d)));
                    }
                }
                (min, max)
            })
            .collect();
        Self {
            points,
            boxes,
            _scalar: std::marker::PhantomData,
        }
    }

    /// The distance from `x` to the polyline.
    fn distance(&self, x: &P) -> T {
        self.nearest(x).0
    }

    /// The distance from `x` to the polyline and the length of the nearest segment.
    fn nearest(&self, x: &P) -> (T, T) {
        let pts = self.points;
        if pts.len() == 1 {
            return ((*x - pts[0]).length(), T::zero());
        }
        let mut length = T::zero();
        let mut best = T::max_value().unwrap_or_else(|| cast(f64::MAX));
        let mut order: Vec<(T, usize)> = self
            .boxes
            .iter()
            .enumerate()
            .map(|(c, (min, max))| {
                let mut s = T::zero();
                for d in 0..P::DIM {
                    let v = x.coord(d);
                    let e = (min.coord(d) - v).max(v - max.coord(d)).max(T::zero());
                    s += e * e;
                }
                (s.sqrt(), c)
            })
            .collect();
        order.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
        for (bound, c) in order {
            if bound >= best {
                break;
            }
            let lo = c * CHUNK;
            let hi = ((c + 1) * CHUNK).min(pts.len() - 1);
            for k in lo..hi {
                let d = segment_distance(x, &pts[k], &pts[k + 1]);
                if d < best {
                    best = d;
                    length = (pts[k + 1] - pts[k]).length();
                }
            }
        }
        (best, length)
    }
}

/// The distance from `x` to the segment `[a, b]`.
fn segment_distance<T: Scalar, P: ControlPoint<T>>(x: &P, a: &P, b: &P) -> T {
    let ab = *b - *a;
    let len2 = ab.length_squared();
    let t = if len2 > T::zero() {
        ((*x - *a).dot(&ab) / len2).max(T::zero()).min(T::one())
    } else {
        T::zero()
    };
    (*x - (*a + ab * t)).length()
}

/// The deviation of `curve` from `points` both ways ([`TwoSidedDeviation`]).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::two_sided_deviation;
/// use spline_geom::BSpline;
/// // A parabolic arch above the chord from (0, 0) to (2, 0): the data are its end points,
/// // so every data point lies on the curve, but the curve leaves the data polyline by 0.5.
/// let arch = BSpline::from_knots(
///     2,
///     vec![0.0f64, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(2.0, 0.0)],
/// )?;
/// let data = [Vector2::new(0.0, 0.0), Vector2::new(2.0, 0.0)];
/// let d = two_sided_deviation(&arch, &data)?;
/// assert!(d.to_curve.max < 1e-15);
/// assert!((d.to_data - 0.5).abs() < 1e-9);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] without points; [`ErrorKind::NonFinite`] for points that are
/// not finite.
pub fn two_sided_deviation<T: Scalar, P: ControlPoint<T>>(
    curve: &BSpline<T, P>,
    points: &[P],
) -> Result<TwoSidedDeviation<T>> {
    if points.is_empty() {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            "a deviation needs at least one data point",
        ));
    }
    // Curve and data divided by a power of four near their size (exact): the distances are
    // those of the unscaled problem times the scale (no squares underflowing at 1e-300 or
    // overflowing at 1e300).
    let largest = points
        .iter()
        .chain(curve.control_points())
        .fold(T::zero(), |m, q| m.max(q.max_abs()));
    let scale: T = cast(spline_core::power_of_two_scale(to_f64(largest)));
    let inverse = T::one() / scale;
    let unit_curve = curve.map_control_points(|c| *c * inverse);
    let unit_points: Vec<P> = points.iter().map(|q| *q * inverse).collect();
    let (distances, params) = feet_of(&unit_curve, &unit_points)?;
    let (to_data, to_data_param, to_data_excess) = curve_to_polyline(&unit_curve, &unit_points)?;
    let mut to_curve = Deviation::from_distances(distances);
    to_curve.max *= scale;
    to_curve.rms *= scale;
    to_curve.sum_squares *= scale * scale;
    for d in &mut to_curve.distances {
        *d *= scale;
    }
    Ok(TwoSidedDeviation {
        to_curve,
        params,
        to_data: to_data * scale,
        to_data_param,
        to_data_excess: to_data_excess * scale,
    })
}

/// The largest distance from the curve to the polyline through `points`, where, and the
/// largest excess over half the nearest segment's length.
fn curve_to_polyline<T: Scalar, P: ControlPoint<T>>(
    curve: &BSpline<T, P>,
    points: &[P],
) -> Result<(T, T, T)> {
    let index = PolylineIndex::new(points);
    let breaks = curve.knots().domain_breaks();
    let distance_at = |u: T| -> Result<T> { Ok(index.distance(&curve.eval(u)?)) };
    let (mut best, mut best_u) = (T::zero(), breaks[0]);
    let mut best_bracket = (breaks[0], breaks[0]);
    let steps: T = from_count(SAMPLES_PER_SPAN);
    let half: T = cast(0.5);
    let mut excess = T::zero();
    for w in breaks.windows(2) {
        let (a, b) = (w[0], w[1]);
        let h = (b - a) / steps;
        for k in 0..=SAMPLES_PER_SPAN {
            let u = if k == SAMPLES_PER_SPAN {
                b
            } else {
                a + h * from_count::<T>(k)
            };
            let (d, length) = index.nearest(&curve.eval(u)?);
            excess = excess.max(d - length * half);
            if d > best {
                best = d;
                best_u = u;
                best_bracket = ((u - h).max(a), (u + h).min(b));
            }
        }
    }
    // Golden-section search for the maximum inside the bracket of the best sample.
    let refined = golden_section_max(distance_at, best_bracket, T::default_epsilon())?;
    for (f, x) in refined {
        if f > best {
            best = f;
            best_u = x;
        }
    }
    Ok((best, best_u, excess))
}

/// The distances of `points` to the curve and the parameters of their closest points, in
/// the order of the points. With the `parallel` feature, for at least
/// [`crate::PARALLEL_MIN_POINTS`] points, on every core: each closest point is independent
/// of the others, so the result is the same bit for bit.
fn feet_of<T: Scalar, P: ControlPoint<T>>(
    curve: &BSpline<T, P>,
    points: &[P],
) -> Result<(Vec<T>, Vec<T>)> {
    let foot = |q: &P| closest_point(curve, *q).map(|hit| (hit.distance, hit.param));
    #[cfg(feature = "parallel")]
    if points.len() >= crate::PARALLEL_MIN_POINTS && rayon::current_num_threads() > 1 {
        use rayon::prelude::*;
        let hits: Vec<Result<(T, T)>> = points.par_iter().map(foot).collect();
        return hits
            .into_iter()
            .collect::<Result<Vec<_>>>()
            .map(|h| h.into_iter().unzip());
    }
    points
        .iter()
        .map(foot)
        .collect::<Result<Vec<_>>>()
        .map(|h| h.into_iter().unzip())
}
