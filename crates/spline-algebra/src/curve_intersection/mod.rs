//! Intersections of planar curves of any kind (B-spline, Bézier, NURBS, periodic): all
//! intersections of two curves and the self-intersections of one, by subdivision of their
//! Bézier pieces (convex hulls of the control points bound every piece, also rational ones
//! with positive weights), each candidate refined by Newton's method to the precision of
//! floating point, tangential intersections refined on a system that stays regular at a
//! tangency and flagged.

use nalgebra::Vector2;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, cast, to_f64};
use spline_geom::{Bezier, ParamCurve, PlanarCurve, wedge};

/// The largest number of piece pairs examined before the search gives up (curves that
/// overlap along an arc have infinitely many intersections).
pub const MAX_INTERSECTION_PAIRS: usize = 1_000_000;

/// An intersection of two curves, or a self-intersection of one (`u < v`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveIntersection<T> {
    /// The parameter on the first curve.
    pub u: T,
    /// The parameter on the second curve (on the same curve for a self-intersection).
    pub v: T,
    /// The point, the middle of $A(u)$ and $B(v)$.
    pub point: Vector2<T>,
    /// Whether the curves touch there with parallel tangents (the sine of the angle between
    /// them below [`TANGENTIAL_SINE`]).
    pub tangential: bool,
    /// $|A(u) − B(v)|$: the rounding of floating point at a crossing; at a tangential
    /// contact, the gap between the curves (up to the tolerance: two curves that come within
    /// the tolerance of each other touch).
    pub gap: T,
}

/// Intersections where the sine of the angle between the tangents is below this are
/// tangential.
pub const TANGENTIAL_SINE: f64 = 1e-6;

/// Below this sine of the angle between the tangents, a tangency is tried as well.
const NEAR_TANGENT_SINE: f64 = 1e-3;

/// A Bézier piece of a curve: its interval, its coefficients and the box of their
/// projections (which contains the piece).
#[derive(Clone, Debug)]
struct Piece<T: Scalar, Q: ControlPoint<T>> {
    bezier: Bezier<T, Q>,
    lo: Vector2<T>,
    hi: Vector2<T>,
    /// Largest distance of a projected control point from the chord.
    flatness: T,
    first: Vector2<T>,
    last: Vector2<T>,
    /// The projected control points.
    points: Vec<Vector2<T>>,
}

impl<T: Scalar, Q: ControlPoint<T>> Piece<T, Q> {
    fn new(bezier: Bezier<T, Q>, project: impl Fn(&Q) -> Vector2<T>) -> Self {
        let points: Vec<Vector2<T>> = bezier.control_points().iter().map(&project).collect();
        let (mut lo, mut hi) = (points[0], points[0]);
        for q in &points[1..] {
            lo = lo.inf(q);
            hi = hi.sup(q);
        }
        let (first, last) = (points[0], points[points.len() - 1]);
        let chord = last - first;
        let length = chord.norm();
        let flatness = points.iter().fold(T::zero(), |m, q| {
            let d = if length > T::zero() {
                wedge(&chord, &(q - first)).abs() / length
            } else {
                (q - first).norm()
            };
            m.max(d)
        });
        Self {
            bezier,
            lo,
            hi,
            flatness,
            first,
            last,
            points,
        }
    }

    fn size(&self) -> T {
        (self.hi - self.lo).norm()
    }

    fn split(&self, project: &impl Fn(&Q) -> Vector2<T>) -> Option<(Self, Self)> {
        let (a, b) = self.bezier.interval();
        let mid = (a + b) * cast(0.5);
        if !(mid > a && mid < b) {
            return None;
        }
        let (l, r) = self.bezier.subdivide(mid).ok()?;
        Some((Piece::new(l, project), Piece::new(r, project)))
    }

    /// Whether the boxes of the two pieces come within `slack` of each other and neither
    /// piece's fat line (the strip along its chord holding its control points) is
    /// separated by more than `slack` from the other's control points.
    fn overlaps<R: ControlPoint<T>>(&self, other: &Piece<T, R>, slack: T) -> bool {
        (0..2).all(|c| self.lo[c] <= other.hi[c] + slack && other.lo[c] <= self.hi[c] + slack)
            && self.fat_line_meets(&other.points, slack)
            && other.fat_line_meets(&self.points, slack)
    }

    /// Whether the strip along the chord that holds this piece's control points comes
    /// within `slack` of the convex hull of `points` (always true for a piece whose ends
    /// coincide).
    fn fat_line_meets(&self, points: &[Vector2<T>], slack: T) -> bool {
        let chord = self.last - self.first;
        let length = chord.norm();
        if !(length > T::zero()) {
            return true;
        }
        let distance = |q: &Vector2<T>| wedge(&chord, &(q - self.first)) / length;
        let band = |ps: &[Vector2<T>]| {
            let d0 = distance(&ps[0]);
            ps[1..].iter().fold((d0, d0), |(lo, hi), q| {
                let d = distance(q);
                (lo.min(d), hi.max(d))
            })
        };
        let (lo, hi) = band(&self.points);
        let (qlo, qhi) = band(points);
        qhi >= lo - slack && qlo <= hi + slack
    }

    /// Whether the directions of the projected control polygon's legs lie in an open
    /// half-plane: the piece then has no self-intersection (its tangents stay in the cone
    /// of the legs, also for rational pieces with positive weights).
    fn is_monotone(&self, project: &impl Fn(&Q) -> Vector2<T>) -> bool {
        let points: Vec<Vector2<T>> = self.bezier.control_points().iter().map(project).collect();
        let chord = self.last - self.first;
        let legs: Vec<Vector2<T>> = points.windows(2).map(|w| w[1] - w[0]).collect();
        legs.iter().all(|l| l.dot(&chord) > T::zero())
    }
}

/// The Bézier pieces of a curve.
fn pieces_of<T: Scalar, C: ParamCurve<T, Point = Vector2<T>>>(
    curve: &C,
) -> Result<Vec<Piece<T, C::Coefficient>>> {
    curve
        .bezier_pieces()
        .into_iter()
        .map(|(a, b, coefficients)| {
            Bezier::with_interval(coefficients, a, b).map(|z| Piece::new(z, C::project))
        })
        .collect()
}

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

/// A candidate pair of parameter intervals with a starting point.
#[derive(Clone, Copy, Debug)]
struct Candidate<T> {
    u: T,
    v: T,
}

/// Subdivides pairs of pieces whose boxes overlap until both pieces are flat (within a
/// quarter of the tolerance) or cannot be split, and collects a start for Newton's method
/// where their chords come within the tolerance.
fn candidates<T: Scalar, QA: ControlPoint<T>, QB: ControlPoint<T>>(
    a: &[Piece<T, QA>],
    b: &[Piece<T, QB>],
    project_a: &impl Fn(&QA) -> Vector2<T>,
    project_b: &impl Fn(&QB) -> Vector2<T>,
    tolerance: T,
    pairs: &mut usize,
) -> Result<Vec<Candidate<T>>> {
    let flat = tolerance * cast(0.25);
    let mut out = Vec::new();
    let mut stack: Vec<(Piece<T, QA>, Piece<T, QB>)> = Vec::new();
    for pa in a {
        for pb in b {
            stack.push((pa.clone(), pb.clone()));
        }
    }
    while let Some((pa, pb)) = stack.pop() {
        if !pa.overlaps(&pb, tolerance) {
            continue;
        }
        *pairs += 1;
        if *pairs > MAX_INTERSECTION_PAIRS {
            return Err(Error::new(
                ErrorKind::NoConvergence,
                format!(
                    "more than {MAX_INTERSECTION_PAIRS} pairs of pieces stay within the tolerance: the curves seem to overlap along an arc (infinitely many intersections)"
                ),
            ));
        }
        let flat_a = pa.flatness <= flat;
        let flat_b = pb.flatness <= flat;
        if flat_a && flat_b {
            if let Some(c) = chord_candidate(&pa, &pb, tolerance) {
                out.push(c);
            }
            continue;
        }
        // Split the larger piece that is not flat.
        let split_a = !flat_a && (flat_b || pa.size() >= pb.size());
        let split = if split_a {
            pa.split(project_a)
                .map(|(l, r)| [(l, pb.clone()), (r, pb.clone())])
        } else {
            pb.split(project_b)
                .map(|(l, r)| [(pa.clone(), l), (pa.clone(), r)])
        };
        match split {
            Some(halves) => stack.extend(halves),
            None => {
                // At the resolution of floating point: keep the pair as a candidate.
                out.push(Candidate {
                    u: mid(pa.bezier.interval()),
                    v: mid(pb.bezier.interval()),
                });
            }
        }
    }
    Ok(out)
}

fn mid<T: Scalar>((a, b): (T, T)) -> T {
    (a + b) * cast(0.5)
}

/// The start of Newton's method for two flat pieces: the closest points of their chords,
/// if those come within the tolerance (plus the flatness of the pieces).
fn chord_candidate<T: Scalar, QA: ControlPoint<T>, QB: ControlPoint<T>>(
    pa: &Piece<T, QA>,
    pb: &Piece<T, QB>,
    tolerance: T,
) -> Option<Candidate<T>> {
    let (s, t, distance) = segment_closest(pa.first, pa.last, pb.first, pb.last);
    if distance > tolerance + pa.flatness + pb.flatness {
        return None;
    }
    let (a0, a1) = pa.bezier.interval();
    let (b0, b1) = pb.bezier.interval();
    Some(Candidate {
        u: a0 + (a1 - a0) * s,
        v: b0 + (b1 - b0) * t,
    })
}

/// The closest points `p0 + s (p1 − p0)` and `q0 + t (q1 − q0)` of two segments and their
/// distance.
fn segment_closest<T: Scalar>(
    p0: Vector2<T>,
    p1: Vector2<T>,
    q0: Vector2<T>,
    q1: Vector2<T>,
) -> (T, T, T) {
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.norm_squared(), d2.norm_squared(), d2.dot(&r));
    let clamp = |x: T| x.max(T::zero()).min(T::one());
    let (s, t) = if a == T::zero() && e == T::zero() {
        (T::zero(), T::zero())
    } else if a == T::zero() {
        (T::zero(), clamp(f / e))
    } else {
        let c = d1.dot(&r);
        if e == T::zero() {
            (clamp(-c / a), T::zero())
        } else {
            let b = d1.dot(&d2);
            let denom = a * e - b * b;
            let mut s = if denom > T::zero() {
                clamp((b * f - c * e) / denom)
            } else {
                T::zero()
            };
            let mut t = (b * s + f) / e;
            if t < T::zero() {
                t = T::zero();
                s = clamp(-c / a);
            } else if t > T::one() {
                t = T::one();
                s = clamp((b - c) / a);
            }
            (s, t)
        }
    };
    let distance = ((p0 + d1 * s) - (q0 + d2 * t)).norm();
    (s, t, distance)
}

/// Value, first and second derivatives at `u` (clamped into the domain).
fn jet<T: Scalar, C: PlanarCurve<T>>(curve: &C, u: T) -> Result<(T, [Vector2<T>; 3])> {
    let (a, b) = curve.domain();
    let u = u.max(a).min(b);
    let mut d = [Vector2::zeros(); 3];
    curve.derivatives_into(u, &mut d)?;
    Ok((u, d))
}

/// Refines a candidate: Newton's method on `A(u) = B(v)`; where the tangents are nearly
/// parallel, Newton's method on the regular system of a tangency
/// `A'(u) ∧ B'(v) = 0`, `(A(u) − B(v)) · B'(v) = 0`. Returns the refined parameters when
/// the curves meet there within the tolerance.
fn refine<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    start: Candidate<T>,
    tolerance: T,
) -> Result<Option<CurveIntersection<T>>> {
    let (mut u, mut v) = (start.u, start.v);
    let eps = T::default_epsilon();
    let mut best: Option<(T, T, T)> = None;
    for _ in 0..60 {
        let (uu, da) = jet(a, u)?;
        let (vv, db) = jet(b, v)?;
        (u, v) = (uu, vv);
        let f = da[0] - db[0];
        let distance = f.norm();
        if best.is_none_or(|(_, _, d)| distance < d) {
            best = Some((u, v, distance));
        }
        // Solve [A' −B'] (du, dv) = −f.
        let det = wedge(&da[1], &(-db[1]));
        let scale = da[1].norm() * db[1].norm();
        if !(det.abs() > scale * cast(1e-10)) {
            break;
        }
        let du = wedge(&(-f), &(-db[1])) / det;
        let dv = wedge(&da[1], &(-f)) / det;
        u += du;
        v += dv;
        if du.abs() <= eps * (T::one() + u.abs()) && dv.abs() <= eps * (T::one() + v.abs()) {
            let (uu, da) = jet(a, u)?;
            let (vv, db) = jet(b, v)?;
            let distance = (da[0] - db[0]).norm();
            if best.is_none_or(|(_, _, d)| distance <= d) {
                best = Some((uu, vv, distance));
            }
            break;
        }
    }
    let (mut u, mut v, mut distance) = best.expect("one iteration at least");
    let sine = |p: &Vector2<T>, q: &Vector2<T>| wedge(p, q).abs() / (p.norm() * q.norm());
    let (_, da) = jet(a, u)?;
    let (_, db) = jet(b, v)?;
    // Near a tangency Newton's method on A(u) = B(v) converges slowly (a double root) and
    // stops on a singular matrix: unless it has reached the rounding of the points, the
    // regular system of a tangency may do better (nearby: it may also converge to another
    // contact).
    let rounding = eps
        * cast(16.0)
        * (T::one() + da[0].norm() + u.abs() * da[1].norm() + v.abs() * db[1].norm());
    if sine(&da[1], &db[1]) < cast(NEAR_TANGENT_SINE) {
        if let Some((tu, tv, td)) = refine_tangency(a, b, u, v)? {
            let (ua, ub) = a.domain();
            let (va, vb) = b.domain();
            let near = (tu - u).abs() <= (ub - ua) * cast(1e-3)
                && (tv - v).abs() <= (vb - va) * cast(1e-3);
            if td <= distance.max(rounding) && near {
                (u, v, distance) = (tu, tv, td);
            }
        }
    }
    if distance > tolerance {
        return Ok(None);
    }
    let (_, da) = jet(a, u)?;
    let (_, db) = jet(b, v)?;
    let tangential = sine(&da[1], &db[1]) < cast(TANGENTIAL_SINE);
    Ok(Some(CurveIntersection {
        u,
        v,
        point: (da[0] + db[0]) * cast::<T>(0.5),
        tangential,
        gap: distance,
    }))
}

/// Newton's method on `g(u, v) = (A'(u) ∧ B'(v), (A(u) − B(v)) · B'(v)) = 0`: parallel
/// tangents with `A(u)` on the normal of `B` at `v`. At a tangency of curves with different
/// curvatures the Jacobian is regular (unlike that of `A(u) − B(v)`), so the point of
/// contact is found to full precision. Returns `(u, v, |A(u) − B(v)|)`.
fn refine_tangency<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    mut u: T,
    mut v: T,
) -> Result<Option<(T, T, T)>> {
    let eps = T::default_epsilon();
    for _ in 0..60 {
        let (uu, da) = jet(a, u)?;
        let (vv, db) = jet(b, v)?;
        (u, v) = (uu, vv);
        let f = da[0] - db[0];
        let g1 = wedge(&da[1], &db[1]);
        let g2 = f.dot(&db[1]);
        let j11 = wedge(&da[2], &db[1]);
        let j12 = wedge(&da[1], &db[2]);
        let j21 = da[1].dot(&db[1]);
        let j22 = f.dot(&db[2]) - db[1].norm_squared();
        let det = j11 * j22 - j12 * j21;
        if !(det.abs() > T::zero()) || !det.is_finite() {
            return Ok(None);
        }
        let du = (-g1 * j22 + g2 * j12) / det;
        let dv = (-g2 * j11 + g1 * j21) / det;
        u += du;
        v += dv;
        if du.abs() <= eps * (T::one() + u.abs()) && dv.abs() <= eps * (T::one() + v.abs()) {
            break;
        }
    }
    let (u, da) = jet(a, u)?;
    let (v, db) = jet(b, v)?;
    Ok(Some((u, v, (da[0] - db[0]).norm())))
}

/// Keeps one intersection per point: results whose parameters differ by less than
/// `merge_u`, `merge_v` (or whose points coincide within the tolerance with nearby
/// parameters) are the same intersection, the one nearest to exact kept.
fn deduplicate<T: Scalar>(
    mut found: Vec<CurveIntersection<T>>,
    merge_u: T,
    merge_v: T,
) -> Vec<CurveIntersection<T>> {
    found.sort_by(|x, y| x.u.partial_cmp(&y.u).unwrap_or(std::cmp::Ordering::Equal));
    let mut out: Vec<CurveIntersection<T>> = Vec::with_capacity(found.len());
    for f in found {
        if let Some(same) = out
            .iter_mut()
            .find(|g| (g.u - f.u).abs() <= merge_u && (g.v - f.v).abs() <= merge_v)
        {
            same.tangential |= f.tangential;
            continue;
        }
        out.push(f);
    }
    out
}

/// All intersections of two planar curves of any kind, in increasing `u`: the points
/// where they come within `tolerance` (absolute, in the units of the points) of each
/// other, each refined by Newton's method to the precision of floating point, tangential
/// ones (sine of the angle between the tangents below [`TANGENTIAL_SINE`]) refined on a
/// system that stays regular at a tangency and flagged.
///
/// The Bézier pieces of both curves are subdivided (de Casteljau) while the boxes of their
/// control points come within the tolerance of each other and either piece is not flat
/// to a quarter of the tolerance; pairs of flat pieces whose chords come within the
/// tolerance are the candidates. The convex hull property makes the search complete: an
/// intersection lies in every box containing it, so none is missed.
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
/// assert_eq!(hits.len(), 2);
/// assert!((hits[1].point.x - 0.5f64.sqrt()).abs() < 1e-14 && !hits[1].tangential);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidTolerance`] unless the tolerance is positive and finite;
/// [`ErrorKind::NoConvergence`] when more than [`MAX_INTERSECTION_PAIRS`] pairs of pieces
/// stay within the tolerance (curves that overlap along an arc); the evaluation errors of
/// the curves.
pub fn intersect_curves<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    tolerance: T,
) -> Result<Vec<CurveIntersection<T>>> {
    check_tolerance(tolerance)?;
    let pa = pieces_of(a)?;
    let pb = pieces_of(b)?;
    let mut pairs = 0;
    let starts = candidates(&pa, &pb, &A::project, &B::project, tolerance, &mut pairs)?;
    let (ua, ub) = a.domain();
    let (va, vb) = b.domain();
    let (merge_u, merge_v) = ((ub - ua) * cast(1e-9), (vb - va) * cast(1e-9));
    // On a closed curve the two ends are one point: report it at the start.
    let closed_a = (a.eval(ua)? - a.eval(ub)?).norm() <= tolerance;
    let closed_b = (b.eval(va)? - b.eval(vb)?).norm() <= tolerance;
    let mut found = Vec::new();
    for s in starts {
        if let Some(mut hit) = refine(a, b, s, tolerance)? {
            if closed_a && ub - hit.u <= merge_u {
                hit.u = ua;
            }
            if closed_b && vb - hit.v <= merge_v {
                hit.v = va;
            }
            found.push(hit);
        }
    }
    Ok(deduplicate(found, merge_u, merge_v))
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

/// [`intersect_curves`] with a tolerance relative to the curves' size: `relative` times the
/// larger [`planar_extent`] of the two (the absolute tolerance when both are points). The
/// answer to a scaled pair is then the scaled answer: the same crossings at 1e-60 and 1e60
/// as at 1 (tested). Sizes much beyond that range are not covered yet: the search squares
/// and multiplies coordinates, which leave the normal range of `f64` there.
///
/// # Errors
/// As [`intersect_curves`].
pub fn intersect_curves_relative<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    relative: T,
) -> Result<Vec<CurveIntersection<T>>> {
    check_tolerance(relative)?;
    let size = planar_extent(a)?.max(planar_extent(b)?);
    let tolerance = if size > T::zero() && (relative * size) > T::zero() {
        relative * size
    } else {
        relative
    };
    intersect_curves(a, b, tolerance)
}

/// [`self_intersections`] with a tolerance relative to the curve's [`planar_extent`].
///
/// # Errors
/// As [`self_intersections`].
pub fn self_intersections_relative<T: Scalar, C: PlanarCurve<T>>(
    curve: &C,
    relative: T,
) -> Result<Vec<CurveIntersection<T>>> {
    check_tolerance(relative)?;
    let size = planar_extent(curve)?;
    let tolerance = if size > T::zero() && (relative * size) > T::zero() {
        relative * size
    } else {
        relative
    };
    self_intersections(curve, tolerance)
}

/// The self-intersections of a planar curve of any kind: pairs `u < v` with
/// $C(u) = C(v)$ within `tolerance`, refined and flagged as in [`intersect_curves`].
///
/// The Bézier pieces are first split until each is *monotone* (the legs of its control
/// polygon in an open half-plane, so that the piece cannot cross itself); then every pair
/// of pieces is intersected. Adjacent pieces meet at their common end, which is not a
/// self-intersection, nor are the ends of a closed curve (`C(a) = C(b)`).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::BSpline;
/// // A cubic Bézier loop: P0 = (0, 0), P1 = (2, 2), P2 = (−1, 2), P3 = (1, 0).
/// let curve = BSpline::from_knots(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0], vec![
///     Vector2::new(0.0, 0.0), Vector2::new(2.0, 2.0),
///     Vector2::new(-1.0, 2.0), Vector2::new(1.0, 0.0)])?;
/// let loops = spline_algebra::self_intersections(&curve, 1e-9)?;
/// assert_eq!(loops.len(), 1);
/// let (p, q) = (curve.eval(loops[0].u)?, curve.eval(loops[0].v)?);
/// assert!((p - q).norm() < 1e-13);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`intersect_curves`].
pub fn self_intersections<T: Scalar, C: PlanarCurve<T>>(
    curve: &C,
    tolerance: T,
) -> Result<Vec<CurveIntersection<T>>> {
    check_tolerance(tolerance)?;
    let mut monotone = Vec::new();
    let mut todo = pieces_of(curve)?;
    todo.reverse();
    // Pieces smaller than the tolerance are points for this purpose: near a cusp or a turn
    // back, the legs of ever smaller pieces are rounding noise of either sign, and
    // splitting them until floating point stops would make ~1e8 pieces (the work is bounded
    // by the geometry: the curve's extent over the tolerance).
    let point_like = tolerance * cast(0.25);
    while let Some(p) = todo.pop() {
        if p.size() <= point_like || p.is_monotone(&C::project) {
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
    let mut found = Vec::new();
    for i in 0..monotone.len() {
        let later = &monotone[i + 1..];
        if later.is_empty() {
            break;
        }
        let starts = candidates(
            std::slice::from_ref(&monotone[i]),
            later,
            &C::project,
            &C::project,
            tolerance,
            &mut pairs,
        )?;
        for s in starts {
            if let Some(hit) = refine(curve, curve, s, tolerance)? {
                let (u, v) = if hit.u <= hit.v {
                    (hit.u, hit.v)
                } else {
                    (hit.v, hit.u)
                };
                // The common ends of neighbouring pieces, and the seam of a closed curve.
                let same = v - u <= merge;
                let seam = closed && u - a <= merge && b - v <= merge;
                if !same && !seam {
                    found.push(CurveIntersection { u, v, ..hit });
                }
            }
        }
    }
    Ok(deduplicate(found, merge, merge))
}
