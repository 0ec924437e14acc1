//! Intersections of planar curves of any kind (B-spline, Bézier, NURBS, periodic): all
//! intersections of two curves and the self-intersections of one, by subdivision of their
//! Bézier pieces (convex hulls of the control points bound every piece, also rational ones
//! with positive weights), each candidate refined by Newton's method to the precision of
//! floating point, tangential intersections refined on a system that stays regular at a
//! tangency and flagged, and arcs along which the curves coincide reported as overlaps
//! (parameter intervals on both).
//!
//! Stages: `piece` (Bézier pieces, boxes, fat lines), `search` (the subdivision), `refine`
//! (Newton's method), `overlap` (pieces of overlaps chained into maximal intervals).

mod frame;
mod overlap;
mod piece;
mod refine;
mod results;
mod search;

pub use results::{
    CurveEvent, CurveIntersection, CurveIntersections, CurveOverlap, TANGENTIAL_SINE,
};
pub use search::MAX_INTERSECTION_PAIRS;

use frame::Frame;
use overlap::{Setting, within};
use piece::pieces_of;
use refine::{deduplicate, refine};
use search::{Found, Reach, subdivide};
#[cfg(doc)]
use spline_core::ErrorKind;
use spline_core::{Error, Result, Scalar, cast, to_f64};
use spline_geom::PlanarCurve;

/// The contact tolerance the front ends use when none is given, relative to the curves'
/// size ([`intersect_curves_relative`], [`self_intersections_relative`]): the same answer
/// at every scale.
pub const DEFAULT_RELATIVE_CONTACT: f64 = 1e-9;

/// [`ErrorKind::InvalidTolerance`] unless the tolerance is positive and finite.
fn check_tolerance<T: Scalar>(tolerance: T) -> Result<()> {
    if tolerance > T::zero() && tolerance.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid_tolerance(
            "intersection tolerance",
            "positive and finite",
            to_f64(tolerance),
        ))
    }
}

/// All intersections of two planar curves of any kind: the points where they come within
/// `tolerance` (absolute, in the units of the points) of each other, each refined by
/// Newton's method to the precision of floating point, tangential ones (sine of the angle
/// between the tangents below [`TANGENTIAL_SINE`]) refined on a system that stays regular
/// at a tangency and flagged; and the arcs along which they coincide within the tolerance,
/// as parameter intervals on both ([`CurveOverlap`]).
///
/// The Bézier pieces of both curves are subdivided (de Casteljau) while the boxes of their
/// control points come within the tolerance of each other and either piece is not flat
/// to a quarter of the tolerance; pairs of flat pieces whose chords come within the
/// tolerance are the candidates (their parameters where the pieces reach the chords' closest
/// points, not the chords' fractions, which are no parameters on a rational piece). The
/// convex hull property makes the search complete: an intersection lies in every box
/// containing it, so none is missed. A pair of pieces one of which lies on the other curve
/// (samples projected onto it, all within the tolerance, their feet in order) is a piece of
/// an overlap; the other piece is examined further only outside the image (where it may
/// still cross). Flat pieces that run along each other further than a tangency can (two
/// collinear segments overlapping in part) are split until a part lies on the other curve.
/// The pieces of overlaps are chained, their ends found by bisection on the distance (so
/// the intervals are maximal; where the overlap ends because the other curve does, at the
/// foot of its end), each interval sampled again (the foot followed along, also past a
/// sharp corner of both curves), and overlaps that meet merged into one. A run shorter than
/// `8 √(tolerance · size)` (`size` the larger [`planar_extent`]) is a tangency, not an
/// overlap: two curves that touch stay within the tolerance over about
/// `√(8 tolerance / Δκ)`; it is refined as a point. Intersections inside an overlap (on both
/// of its intervals) are not listed again. Parameters computed by affine maps are clamped
/// to their intervals, so none is a rounding step outside the domain. The search runs on
/// the curves divided by a power of four near their size (exact in binary floating
/// point), so coordinates from 1e-300 to 1e300 give the parameters of their unscaled
/// counterparts.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::BSpline;
/// // The parabola y = x² − 1/2 and the line y = 0 on [−1, 1]: x = ±1/√2.
/// let parabola = BSpline::from_knots(2, vec![-1.0, -1.0, -1.0, 1.0, 1.0, 1.0], vec![
///     Vector2::new(-1.0, 0.5), Vector2::new(0.0, -1.5), Vector2::new(1.0, 0.5)])?;
/// let line = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
///     vec![Vector2::new(-1.0, 0.0), Vector2::new(1.0, 0.0)])?;
/// let hits = spline_algebra::intersect_curves(&parabola, &line, 1e-9)?;
/// assert_eq!(hits.points.len(), 2);
/// assert!((hits.points[1].point.x - 0.5f64.sqrt()).abs() < 1e-14);
/// assert!(!hits.points[1].tangential && hits.overlaps.is_empty());
/// // The parabola against itself: one overlap, the whole curve.
/// let same = spline_algebra::intersect_curves(&parabola, &parabola, 1e-9)?;
/// assert!(same.points.is_empty() && same.overlaps.len() == 1);
/// assert_eq!((same.overlaps[0].u, same.overlaps[0].v), ((-1.0, 1.0), (-1.0, 1.0)));
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidTolerance`] unless the tolerance is positive and finite;
/// [`ErrorKind::NoConvergence`] if more than [`MAX_INTERSECTION_PAIRS`] pairs of pieces
/// were examined (a safety net: not reached by the geometry); the evaluation errors of
/// the curves.
pub fn intersect_curves<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    tolerance: T,
) -> Result<CurveIntersections<T>> {
    pair_in_frame(a, b, Given::Absolute(tolerance))
}

/// A tolerance as the caller gave it: in the curves' units, or relative to their size.
#[derive(Clone, Copy)]
enum Given<T> {
    Absolute(T),
    Relative(T),
}

impl<T: Scalar> Given<T> {
    /// The tolerance in `frame`, for curves of `size` (the caller's units).
    fn in_frame(self, frame: &Frame, size: T) -> T {
        match self {
            Self::Absolute(tolerance) => framed(frame, tolerance),
            Self::Relative(relative) => scaled(relative, frame.to_frame(size)),
        }
    }
}

/// The intersections of two curves, searched in the frame of their size.
fn pair_in_frame<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    given: Given<T>,
) -> Result<CurveIntersections<T>> {
    let (Given::Absolute(t) | Given::Relative(t)) = given;
    check_tolerance(t)?;
    let size = planar_extent(a)?.max(planar_extent(b)?);
    let frame = Frame::of_pair::<T, A, B>(size);
    let tolerance = given.in_frame(&frame, size);
    let found = search_pair(&frame.view(a), &frame.view(b), tolerance)?;
    Ok(back(&frame, found))
}

/// The self-intersections of a curve, searched in the frame of its size.
fn self_in_frame<T: Scalar, C: PlanarCurve<T>>(
    curve: &C,
    given: Given<T>,
) -> Result<CurveIntersections<T>> {
    let (Given::Absolute(t) | Given::Relative(t)) = given;
    check_tolerance(t)?;
    let size = planar_extent(curve)?;
    let frame = Frame::of::<T, C>(size);
    let tolerance = given.in_frame(&frame, size);
    Ok(back(&frame, self_search(&frame.view(curve), tolerance)?))
}

/// A tolerance of the caller's units in `frame` (the smallest normal `f64` where it
/// underflows: far below the rounding of the coordinates there).
fn framed<T: Scalar>(frame: &Frame, tolerance: T) -> T {
    frame.to_frame(tolerance).max(cast(f64::MIN_POSITIVE))
}

/// The intersections found in `frame`, in the caller's units.
fn back<T: Scalar>(frame: &Frame, mut found: CurveIntersections<T>) -> CurveIntersections<T> {
    for p in &mut found.points {
        p.point = p.point.map(|x| frame.to_caller(x));
        p.gap = frame.to_caller(p.gap);
    }
    for o in &mut found.overlaps {
        o.points = (
            o.points.0.map(|x| frame.to_caller(x)),
            o.points.1.map(|x| frame.to_caller(x)),
        );
    }
    found
}

/// [`intersect_curves`] on curves in a frame where their size is near 1.
fn search_pair<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    tolerance: T,
) -> Result<CurveIntersections<T>> {
    let pa = pieces_of(a)?;
    let pb = pieces_of(b)?;
    let mut pairs = 0;
    let mut found = Found {
        starts: Vec::new(),
        overlaps: Vec::new(),
    };
    let setting = Setting {
        tolerance,
        size: planar_extent(a)?.max(planar_extent(b)?),
        same: false,
    };
    let limits = (tolerance, setting.shortest());
    let reach = Reach::Neighbours;
    subdivide(a, b, &pa, &pb, limits, reach, &mut found, &mut pairs)?;
    let (overlaps, more) = overlap::overlaps(a, b, found.overlaps, &setting)?;
    let (ua, ub) = a.domain();
    let (va, vb) = b.domain();
    let (merge_u, merge_v) = ((ub - ua) * cast(1e-9), (vb - va) * cast(1e-9));
    // On a closed curve the two ends are one point: report it at the start.
    let closed_a = (a.eval(ua)? - a.eval(ub)?).norm() <= tolerance;
    let closed_b = (b.eval(va)? - b.eval(vb)?).norm() <= tolerance;
    let mut points = Vec::new();
    for s in found.starts.into_iter().chain(more) {
        if let Some(mut hit) = refine(a, b, s, tolerance)? {
            if within(&overlaps, hit.u, hit.v) {
                continue;
            }
            if closed_a && ub - hit.u <= merge_u {
                hit.u = ua;
            }
            if closed_b && vb - hit.v <= merge_v {
                hit.v = va;
            }
            points.push(hit);
        }
    }
    Ok(CurveIntersections {
        points: deduplicate(points, (merge_u, merge_v), setting.radius(), tolerance),
        overlaps,
    })
}

/// The size of a planar curve for relative tolerances: the largest side of the box of its
/// (projected) Bézier control points, which contains the curve. Computed without squaring,
/// so it is finite for coordinates up to the largest float.
///
/// # Errors
/// The curve's conversion to Bézier pieces (never for a valid curve).
pub fn planar_extent<T: Scalar, C: PlanarCurve<T>>(curve: &C) -> Result<T> {
    let pieces = pieces_of(curve)?;
    let Some(first) = pieces.first() else {
        return Ok(T::zero());
    };
    let (lo, hi) = pieces.iter().fold((first.lo, first.hi), |(lo, hi), p| {
        (lo.inf(&p.lo), hi.sup(&p.hi))
    });
    Ok((hi.x - lo.x).max(hi.y - lo.y))
}

/// `relative` times `size`, or `relative` itself when that is zero (a point).
fn scaled<T: Scalar>(relative: T, size: T) -> T {
    if size > T::zero() && (relative * size) > T::zero() {
        relative * size
    } else {
        relative
    }
}

/// [`intersect_curves`] with a tolerance relative to the curves' size: `relative` times the
/// larger [`planar_extent`] of the two (the absolute tolerance when both are points). The
/// answer to a scaled pair is then the scaled answer of the unscaled pair, at every scale
/// from 1e-300 to 1e300 (tested): the search runs on the curves divided by a power of four
/// near their size, exactly.
///
/// # Errors
/// As [`intersect_curves`].
pub fn intersect_curves_relative<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    relative: T,
) -> Result<CurveIntersections<T>> {
    pair_in_frame(a, b, Given::Relative(relative))
}

/// [`self_intersections`] with a tolerance relative to the curve's [`planar_extent`].
///
/// # Errors
/// As [`self_intersections`].
pub fn self_intersections_relative<T: Scalar, C: PlanarCurve<T>>(
    curve: &C,
    relative: T,
) -> Result<CurveIntersections<T>> {
    self_in_frame(curve, Given::Relative(relative))
}

/// The self-intersections of a planar curve of any kind: pairs `u < v` with
/// $C(u) = C(v)$ within `tolerance`, refined and flagged as in [`intersect_curves`], and
/// the arcs the curve runs over twice (a curve that goes back over itself) as overlaps,
/// `u` before `v`.
///
/// The Bézier pieces are first split until each is *monotone* (the legs of its control
/// polygon in an open half-plane, so that the piece cannot cross itself; pieces smaller
/// than a quarter of the tolerance count as points, so a cusp is not split without end);
/// then every pair of pieces is intersected. Adjacent pieces meet at their common end,
/// which is not a self-intersection, nor are the ends of a closed curve (`C(a) = C(b)`).
/// Near a cusp the two branches stay within the tolerance over a short arc: the cusp is
/// reported once, as a tangential self-intersection with `u` and `v` on either side.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::BSpline;
/// // A cubic Bézier loop: P0 = (0, 0), P1 = (2, 2), P2 = (−1, 2), P3 = (1, 0).
/// let curve = BSpline::from_knots(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0], vec![
///     Vector2::new(0.0, 0.0), Vector2::new(2.0, 2.0),
///     Vector2::new(-1.0, 2.0), Vector2::new(1.0, 0.0)])?;
/// let loops = spline_algebra::self_intersections(&curve, 1e-9)?.points;
/// assert_eq!(loops.len(), 1);
/// let (p, q) = (curve.eval(loops[0].u)?, curve.eval(loops[0].v)?);
/// assert!((p - q).norm() < 1e-13);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`intersect_curves`]; [`ErrorKind::DegenerateGeometry`] for a curve that is a single
/// point (all control points equal).
pub fn self_intersections<T: Scalar, C: PlanarCurve<T>>(
    curve: &C,
    tolerance: T,
) -> Result<CurveIntersections<T>> {
    self_in_frame(curve, Given::Absolute(tolerance))
}

/// [`self_intersections`] of a curve in a frame where its size is near 1.
fn self_search<T: Scalar, C: PlanarCurve<T>>(
    curve: &C,
    tolerance: T,
) -> Result<CurveIntersections<T>> {
    let size = planar_extent(curve)?;
    if !(size > T::zero()) {
        return Err(Error::new(
            spline_core::ErrorKind::DegenerateGeometry,
            "degenerate curve: all its control points coincide, it is a single point",
        ));
    }
    let mut monotone = Vec::new();
    let mut todo = pieces_of(curve)?;
    todo.reverse();
    // Pieces smaller than the tolerance are points for this purpose: near a cusp or a turn
    // back, the legs of ever smaller pieces are rounding noise of either sign, and
    // splitting them until floating point stops would make ~1e8 pieces (the work is bounded
    // by the geometry: the curve's extent over the tolerance).
    let point_like = tolerance * cast(0.25);
    while let Some(p) = todo.pop() {
        if p.size() <= point_like || p.is_monotone() {
            monotone.push(p);
            continue;
        }
        match p.split(&C::project) {
            Some((l, r)) => {
                todo.push(r);
                todo.push(l);
            }
            // A piece too short to split is a point for this purpose.
            None => monotone.push(p),
        }
    }
    let (a, b) = curve.domain();
    let closed = (curve.eval(a)? - curve.eval(b)?).norm() <= tolerance;
    let merge = (b - a) * cast(1e-9);
    let mut pairs = 0;
    let mut found = Found {
        starts: Vec::new(),
        overlaps: Vec::new(),
    };
    let setting = Setting {
        tolerance,
        size,
        same: true,
    };
    let limits = (tolerance, setting.shortest());
    for i in 0..monotone.len() {
        let later = &monotone[i + 1..];
        let single = std::slice::from_ref(&monotone[i]);
        let reach = Reach::Piece;
        subdivide(
            curve, curve, single, later, limits, reach, &mut found, &mut pairs,
        )?;
    }
    let (overlaps, more) = overlap::overlaps(curve, curve, found.overlaps, &setting)?;
    let mut points = Vec::new();
    for s in found.starts.into_iter().chain(more) {
        if let Some(hit) = refine(curve, curve, s, tolerance)? {
            let (u, v) = if hit.u <= hit.v {
                (hit.u, hit.v)
            } else {
                (hit.v, hit.u)
            };
            // The common ends of neighbouring pieces, and the seam of a closed curve.
            let same = v - u <= merge;
            let seam = closed && u - a <= merge && b - v <= merge;
            if !same && !seam && !within(&overlaps, u, v) {
                points.push(CurveIntersection { u, v, ..hit });
            }
        }
    }
    Ok(CurveIntersections {
        points: deduplicate(points, (merge, merge), setting.radius(), tolerance),
        overlaps,
    })
}
