//! Closest point on a curve: subdivision with bounds, then a safeguarded Newton iteration.

use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, cast};
use spline_geom::{Bezier, ParamCurve};

/// The point of a curve closest to a given point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection<T, P> {
    /// The parameter `u*` of the closest point.
    pub param: T,
    /// The closest point `C(u*)`.
    pub point: P,
    /// Its distance to the given point.
    pub distance: T,
}

/// The extent `(min, max)` of coordinate `c` over the points (not empty).
fn coordinate_range<T: Scalar, P: ControlPoint<T>>(points: &[P], c: usize) -> (T, T) {
    let (mut lo, mut hi) = (points[0].coord(c), points[0].coord(c));
    for p in &points[1..] {
        lo = lo.min(p.coord(c));
        hi = hi.max(p.coord(c));
    }
    (lo, hi)
}

/// Distance from `q` to the axis-aligned box of the control points (a lower bound of the
/// distance to the piece by the convex hull property).
fn box_distance<T: Scalar, P: ControlPoint<T>>(points: &[P], q: &P) -> T {
    // The length of the gap vector, without overflow or underflow of its squares.
    P::from_coords(|c| {
        let (lo, hi) = coordinate_range(points, c);
        let x = q.coord(c);
        (lo - x).max(x - hi).max(T::zero())
    })
    .length()
}

fn box_diagonal<T: Scalar, P: ControlPoint<T>>(points: &[P]) -> T {
    P::from_coords(|c| {
        let (lo, hi) = coordinate_range(points, c);
        hi - lo
    })
    .length()
}

/// Halvings of a Bézier piece at most in the closest-point search (pieces `2⁻⁶⁰` of it).
const MAX_DEPTH: usize = 60;

/// The point of `curve` (any kind: B-spline, Bézier or NURBS, [`ParamCurve`]) closest to
/// `target`, with its parameter and distance.
///
/// Robust for points far away, near cusps and equidistant from several arcs: the curve is
/// cut into its Bézier pieces, pieces are subdivided (de Casteljau, in homogeneous space for
/// rational curves) while the distance to the bounding box of their control points — a
/// lower bound by the convex hull property —
/// can still beat the best distance found, down to pieces a thousandth of the curve's size
/// and a quarter of the best distance (so that a piece holds one local minimum of the
/// distance near the best: the global one, not a neighbour as on a swallowtail of an
/// offset); then on every surviving piece a Newton iteration on
/// $g(u) = \langle C(u) - Q, C'(u) \rangle$ is run, safeguarded to stay in the piece and to
/// decrease the distance (falling back to halved steps where $C'$ vanishes, as at cusps),
/// to machine precision. Ties go to the smallest parameter.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::closest_point;
/// use spline_geom::BSpline;
/// let parabola = BSpline::from_knots(
///     2,
///     vec![-1.0f64, -1.0, -1.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(-1.0, 1.0), Vector2::new(0.0, -1.0), Vector2::new(1.0, 1.0)],
/// )?; // y = x²
/// let hit = closest_point(&parabola, Vector2::new(0.0, -2.0))?;
/// assert!(hit.param.abs() < 1e-12 && (hit.distance - 2.0).abs() < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::NonFinite`] if `target` is not finite.
pub fn closest_point<T: Scalar, C: ParamCurve<T>>(
    curve: &C,
    target: C::Point,
) -> Result<Projection<T, C::Point>> {
    if !target.all_finite() {
        return Err(Error::new(
            ErrorKind::NonFinite,
            "the point to project is not finite",
        ));
    }
    let project = |cp: &[C::Coefficient]| cp.iter().map(C::project).collect::<Vec<_>>();
    let segments: Vec<Bezier<T, C::Coefficient>> = curve
        .bezier_pieces()
        .into_iter()
        .map(|(lo, hi, cp)| Bezier::with_interval(cp, lo, hi))
        .collect::<Result<_>>()?;
    let size = box_diagonal(&curve.control_polygon());
    let min_size = size * cast::<T>(1e-3);
    let (a, _) = curve.domain();
    let start = curve.eval(a)?;
    let mut best = Projection {
        param: a,
        point: start,
        distance: (start - target).length(),
    };
    let consider = |best: &mut Projection<T, C::Point>, param: T, point: C::Point| {
        let d = (point - target).length();
        if d < best.distance || (d == best.distance && param < best.param) {
            *best = Projection {
                param,
                point,
                distance: d,
            };
        }
    };
    for s in &segments {
        let (lo, hi) = s.interval();
        let cp = s.control_points();
        consider(&mut best, lo, C::project(&cp[0]));
        consider(&mut best, hi, C::project(&cp[cp.len() - 1]));
    }
    // Branch and bound over the pieces.
    let mut stack: Vec<(Bezier<T, C::Coefficient>, usize)> =
        segments.into_iter().map(|s| (s, 0)).collect();
    let mut leaves: Vec<(T, T, T)> = Vec::new();
    let half: T = cast(0.5);
    let quarter: T = cast(0.25);
    while let Some((piece, depth)) = stack.pop() {
        let cp = project(piece.control_points());
        let bound = box_distance(&cp, &target);
        if bound > best.distance {
            continue;
        }
        let (lo, hi) = piece.interval();
        // A leaf is small against the curve and against the best distance so far: a piece
        // as large as the distance can hold several local minima (two arcs of a
        // swallowtail), of which Newton's method would find one.
        let diagonal = box_diagonal(&cp);
        // (Below 1e-9 of the curve's size Newton's method converges from anywhere in the
        // piece: points on the curve need not be chased to the depth limit.)
        let small = diagonal <= min_size
            && (diagonal <= best.distance * quarter || diagonal <= size * cast::<T>(1e-9));
        if small || depth >= MAX_DEPTH || !(lo < hi) {
            leaves.push((bound, lo, hi));
            continue;
        }
        let mid = (lo + hi) * half;
        if !(mid > lo && mid < hi) {
            leaves.push((bound, lo, hi));
            continue;
        }
        let (left, right) = piece.subdivide(mid)?;
        let lcp = left.control_points();
        consider(&mut best, mid, C::project(&lcp[lcp.len() - 1]));
        stack.push((right, depth + 1));
        stack.push((left, depth + 1));
    }
    leaves.retain(|&(bound, _, _)| bound <= best.distance);
    for (_, lo, hi) in leaves {
        let found = newton(curve, &target, lo, hi)?;
        consider(&mut best, found.0, found.1);
    }
    Ok(best)
}

/// Foot points of ordered data on a curve, from given parameters: for each point in turn, a
/// safeguarded Newton iteration on $\langle C(u) - Q_k, C'(u) \rangle$ started at its
/// parameter and kept between the new parameter of the previous point and the old one of
/// the next, so that the parameters stay in order and each distance never grows. The step of
/// parameter correction that moves each data point's parameter to its (local) closest point;
/// [`closest_point`] is the global search.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::project_ordered;
/// use spline_geom::BSpline;
/// let line = BSpline::from_knots(
///     1, vec![0.0f64, 0.0, 1.0, 1.0], vec![Vector2::new(0.0, 0.0), Vector2::new(2.0, 0.0)])?;
/// let points = [Vector2::new(0.2, 1.0), Vector2::new(1.0, -1.0), Vector2::new(1.9, 0.5)];
/// let params: Vec<f64> = project_ordered(&line, &points, &[0.0, 0.5, 1.0])?;
/// assert!((params[0] - 0.1).abs() < 1e-12 && (params[2] - 0.95).abs() < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidLength`] unless there is one parameter per point;
/// [`ErrorKind::UnsortedKnots`] for decreasing parameters; [`ErrorKind::OutOfDomain`] for
/// parameters outside the curve's domain; [`ErrorKind::NonFinite`] for points that are not
/// finite.
pub fn project_ordered<T: Scalar, C: ParamCurve<T>>(
    curve: &C,
    points: &[C::Point],
    params: &[T],
) -> Result<Vec<T>> {
    if points.len() != params.len() {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("{} parameters for {} points", params.len(), points.len()),
        ));
    }
    spline_core::check_params(params)?;
    let (a, b) = curve.domain();
    if let Some(k) = params.iter().position(|&u| !(u >= a && u <= b)) {
        return Err(Error::out_of_domain(
            spline_core::to_f64(params[k]),
            (spline_core::to_f64(a), spline_core::to_f64(b)),
        )
        .with_index(k)
        .context(format_args!("data point {k}")));
    }
    if let Some(k) = points.iter().position(|q| !q.all_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("data point {k} is not finite"),
        ));
    }
    let mut out = params.to_vec();
    for k in 0..points.len() {
        let lo = if k == 0 { a } else { out[k - 1] };
        let hi = if k + 1 == points.len() {
            b
        } else {
            params[k + 1]
        };
        let start = out[k].max(lo).min(hi);
        out[k] = newton_from(curve, &points[k], start, lo, hi)?.0;
    }
    Ok(out)
}

/// Safeguarded Newton iteration for the closest point on `[lo, hi]`, from the best of the
/// two ends and the middle.
fn newton<T: Scalar, C: ParamCurve<T>>(
    curve: &C,
    target: &C::Point,
    lo: T,
    hi: T,
) -> Result<(T, C::Point)> {
    let mut best = (lo, T::max_value().unwrap_or_else(|| cast(f64::MAX)));
    for u in [lo, (lo + hi) * cast::<T>(0.5), hi] {
        let f = (curve.eval(u)? - *target).length();
        if f < best.1 {
            best = (u, f);
        }
    }
    newton_from(curve, target, best.0, lo, hi)
}

/// Safeguarded Newton iteration for the closest point on `[lo, hi]` from `t`.
fn newton_from<T: Scalar, C: ParamCurve<T>>(
    curve: &C,
    target: &C::Point,
    start: T,
    lo: T,
    hi: T,
) -> Result<(T, C::Point)> {
    let half: T = cast(0.5);
    let mut ders = [C::Point::origin(); 3];
    let mut t = start;
    curve.derivatives_into(t, &mut ders)?;
    // The iteration runs on points divided by a power of four near their size (exact): no
    // squares underflowing at 1e-300 or overflowing at 1e300, the steps of the unscaled
    // problem.
    let size = ders
        .iter()
        .fold(target.max_abs(), |m, p| m.max(p.max_abs()));
    let scale: T = cast(spline_core::power_of_two_scale(spline_core::to_f64(size)));
    let inverse = T::one() / scale;
    let target = &(*target * inverse);
    let scaled = |d: &mut [C::Point; 3]| {
        for p in d.iter_mut() {
            *p = *p * inverse;
        }
    };
    scaled(&mut ders);
    let dist2 = |ders: &[C::Point; 3]| (ders[0] - *target).length_squared();
    let mut f = dist2(&ders);
    let width = hi - lo;
    let eps = T::default_epsilon();
    let slack = T::one() + eps * cast::<T>(8.0);
    for _ in 0..100 {
        let r = ders[0] - *target;
        let g = r.dot(&ders[1]);
        let gp = ders[1].length_squared() + r.dot(&ders[2]);
        let newton = gp > T::zero();
        let mut step = if newton {
            -g / gp
        } else if g > T::zero() {
            -width * cast::<T>(0.25)
        } else if g < T::zero() {
            width * cast::<T>(0.25)
        } else {
            break;
        };
        let mut moved = false;
        for halving in 0..60 {
            let cand = (t + step).max(lo).min(hi);
            if cand == t {
                break;
            }
            let mut d = [C::Point::origin(); 3];
            curve.derivatives_into(cand, &mut d)?;
            scaled(&mut d);
            let fc = dist2(&d);
            // A full Newton step is taken unless it clearly increases the distance (near
            // the minimum, rounding makes the distance flat while g still converges).
            if fc < f || (newton && halving == 0 && fc <= f * slack) {
                moved = (cand - t).abs() > eps * (t.abs() + width);
                t = cand;
                f = fc.min(f);
                ders = d;
                break;
            }
            step *= half;
        }
        if !moved {
            break;
        }
    }
    Ok((t, ders[0] * scale))
}
