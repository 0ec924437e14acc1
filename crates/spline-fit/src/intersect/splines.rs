//! Surface–surface intersection curves as B-spline curves: the curve in space and its images
//! in the parameter planes of both surfaces, on one parameter (OCCT's `GeomAPI_IntSS` with
//! its 2-D curves).

use super::march::{IntersectionCurve, Tracer, intersect_surfaces};
use super::{Tolerances, scale_of_boxes};
use crate::adaptive::AdaptiveApproximation;
use crate::surface_project::BoxTree;
use nalgebra::{SVector, Vector2, Vector3, Vector4};
use spline_core::{Error, ErrorKind, Result, Scalar, cast, to_f64};
use spline_geom::{BSpline, ParamSurface};

/// One smooth piece of a surface–surface intersection curve as B-spline curves on one
/// parameter `t ∈ [0, 1]` (proportional to arc length along the traced points).
#[derive(Clone, Debug)]
pub struct IntersectionSpline<T> {
    /// The curve in space, $C(t)$.
    pub curve: BSpline<T, Vector3<T>>,
    /// Its image in the parameters of the first surface, $(u_A, v_A)(t)$.
    pub pcurve_a: BSpline<T, Vector2<T>>,
    /// Its image in the parameters of the second surface, $(u_B, v_B)(t)$.
    pub pcurve_b: BSpline<T, Vector2<T>>,
    /// The largest of $\lVert C(t) - X(t) \rVert$, $\lVert S_A(p_A(t)) - X(t) \rVert$ and
    /// $\lVert S_B(p_B(t)) - X(t) \rVert$ at the check points, $X(t)$ the intersection
    /// point there.
    pub max_error: T,
}

/// The traced intersection `curve` of `a` and `b` (from [`super::intersect_surfaces`]) as
/// cubic B-spline curves within `tolerance` (absolute, in the units of the surfaces): one
/// [`IntersectionSpline`] per smooth piece. A piece ends where the parameters of a surface
/// jump (a curve crossing the seam of a closed surface, or passing through a pole): a closed
/// curve is started at its seam, so that it stays one piece when it crosses one seam.
///
/// The map fitted is $t \mapsto (X, \sigma_A p_A, \sigma_B p_B)$: at each `t`, a point on
/// both surfaces (Levenberg–Marquardt from the traced points, on the plane through the
/// polyline's point normal to its chord), the parameters weighted by the largest speed
/// $\sigma$ of their surface, so that one tolerance bounds the error in space of all three
/// curves ([`AdaptiveApproximation`], common knots).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::{Tolerances, intersect_surfaces, intersection_splines};
/// use spline_geom::{NurbsSurface, Surface};
/// let sphere = NurbsSurface::sphere(Vector3::new(0.0f64, 0.0, 0.0), 1.0)?;
/// let plane = Surface::bezier(vec![
///     vec![Vector3::new(-2.0, -2.0, 0.5), Vector3::new(-2.0, 2.0, 0.5)],
///     vec![Vector3::new(2.0, -2.0, 0.5), Vector3::new(2.0, 2.0, 0.5)],
/// ])?;
/// let traced = intersect_surfaces(&sphere, &plane, &Tolerances::default())?;
/// let pieces = intersection_splines(&sphere, &plane, &traced[0], 1e-7)?;
/// assert_eq!(pieces.len(), 1);
/// for k in 0..=100 {
///     let p = pieces[0].curve.eval(f64::from(k) / 100.0)?;
///     assert!((p.xy().norm() - 0.75f64.sqrt()).abs() < 1e-7 && (p.z - 0.5).abs() < 1e-7);
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidTolerance`] unless `tolerance` is positive and finite;
/// [`ErrorKind::InvalidLength`] for a curve with mismatched parameter lists;
/// [`ErrorKind::ToleranceExceeded`] when a piece needs more knot spans than
/// [`crate::MAX_ADAPTIVE_PIECES`]; the errors of evaluation.
pub fn intersection_splines<T, A, B>(
    a: &A,
    b: &B,
    curve: &IntersectionCurve<T>,
    tolerance: T,
) -> Result<Vec<IntersectionSpline<T>>>
where
    T: Scalar,
    A: ParamSurface<T, Point = Vector3<T>>,
    B: ParamSurface<T, Point = Vector3<T>>,
{
    if !(tolerance > T::zero() && tolerance.is_finite()) {
        return Err(Error::invalid_tolerance(
            "intersection curve tolerance",
            "positive and finite",
            to_f64(tolerance),
        ));
    }
    let n = curve.points.len();
    if curve.uv_a.len() != n || curve.uv_b.len() != n {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "an intersection curve with {n} points has {} and {} parameter pairs",
                curve.uv_a.len(),
                curve.uv_b.len()
            ),
        ));
    }
    let tolerances = Tolerances {
        distance: Some(tolerance * cast::<T>(1e-3)),
        trace: Some(tolerance),
        ..Tolerances::default()
    };
    // The work is done in the tracer's unit (a power of four near the size of the curve):
    // no squares overflow or underflow at sizes from 1e-300 to 1e300.
    let size = curve
        .points
        .iter()
        .fold(T::zero(), |m, p| m.max(p.amax()))
        .max(tolerance);
    let tracer = Tracer::new(a, b, &tolerances, size);
    let unit = tracer.unit();
    let normalised = IntersectionCurve {
        points: curve.points.iter().map(|p| p / unit).collect(),
        uv_a: curve.uv_a.clone(),
        uv_b: curve.uv_b.clone(),
        closed: curve.closed,
    };
    let tolerance = tolerance / unit;
    let mut pieces = Vec::new();
    for piece in smooth_pieces(&tracer, &normalised, tolerance)? {
        if piece.len() >= 2 {
            let mut spline = fit_piece(&tracer, &piece, tolerance)?;
            for q in spline.curve.control_points_mut() {
                *q *= unit;
            }
            spline.max_error *= unit;
            pieces.push(spline);
        }
    }
    Ok(pieces)
}

/// A surface–surface intersection curve, traced and as B-splines.
#[derive(Clone, Debug)]
pub struct SurfaceIntersection<T> {
    /// The traced polyline with its parameters on both surfaces.
    pub traced: IntersectionCurve<T>,
    /// Its smooth pieces as B-spline curves within the tracing tolerance.
    pub pieces: Vec<IntersectionSpline<T>>,
}

/// [`intersect_surfaces`] with each curve also as B-spline curves in space and in both
/// parameter planes ([`intersection_splines`]), within the tracing tolerance
/// ([`Tolerances::trace`]; by default `1e-4` of the size of the surfaces).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::{Tolerances, intersect_surfaces_as_splines};
/// use spline_geom::{NurbsSurface, Surface};
/// let sphere = NurbsSurface::sphere(Vector3::new(0.0f64, 0.0, 0.0), 1.0)?;
/// let plane = Surface::bezier(vec![
///     vec![Vector3::new(-2.0, -2.0, 0.0), Vector3::new(-2.0, 2.0, 0.0)],
///     vec![Vector3::new(2.0, -2.0, 0.0), Vector3::new(2.0, 2.0, 0.0)],
/// ])?;
/// let found = intersect_surfaces_as_splines(&sphere, &plane, &Tolerances::default())?;
/// let piece = &found[0].pieces[0]; // the equator
/// assert!((piece.curve.eval(0.3)?.norm() - 1.0).abs() < 1e-4);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`intersect_surfaces`] and [`intersection_splines`].
pub fn intersect_surfaces_as_splines<T, A, B>(
    a: &A,
    b: &B,
    tolerances: &Tolerances<T>,
) -> Result<Vec<SurfaceIntersection<T>>>
where
    T: Scalar,
    A: ParamSurface<T, Point = Vector3<T>>,
    B: ParamSurface<T, Point = Vector3<T>>,
{
    let traced = intersect_surfaces(a, b, tolerances)?;
    if traced.is_empty() {
        return Ok(Vec::new());
    }
    let tree_b = BoxTree::new(b)?;
    let root = &tree_b.nodes[tree_b.root];
    let scale = scale_of_boxes(&BoxTree::new(a)?, std::iter::once((root.lo, root.hi)));
    let tolerance = tolerances.trace_for(scale);
    traced
        .into_iter()
        .map(|curve| {
            let pieces = intersection_splines(a, b, &curve, tolerance)?;
            Ok(SurfaceIntersection {
                traced: curve,
                pieces,
            })
        })
        .collect()
}

/// A traced point: in space, and its parameters `(u_A, v_A, u_B, v_B)`.
type Traced<T> = (Vector3<T>, Vector4<T>);

/// The ends of the pieces on either side of a jump (see [`crossing`]).
type Crossing<T> = (Option<Traced<T>>, Option<Traced<T>>);

/// The traced points split where the parameters of a surface jump by more than half its
/// domain (a seam or a pole between two traced points); a closed curve with such jumps
/// starts after its first. Where the jump is a seam, the piece before it ends and the one
/// after it starts at the crossing of the seam (the same point in space, on either side of
/// the domain); at a pole, the next piece starts at the last point of the previous one.
fn smooth_pieces<T, A, B>(
    tracer: &Tracer<'_, T, A, B>,
    curve: &IntersectionCurve<T>,
    tolerance: T,
) -> Result<Vec<Vec<Traced<T>>>>
where
    T: Scalar,
    A: ParamSurface<T, Point = Vector3<T>>,
    B: ParamSurface<T, Point = Vector3<T>>,
{
    let half = (tracer.upper - tracer.lower) * cast::<T>(0.5);
    let mut points: Vec<Traced<T>> = (0..curve.points.len())
        .map(|k| {
            let (ua, va) = curve.uv_a[k];
            let (ub, vb) = curve.uv_b[k];
            (curve.points[k], Vector4::new(ua, va, ub, vb))
        })
        .collect();
    let jump = |x: &Vector4<T>, y: &Vector4<T>| (0..4).any(|i| (y[i] - x[i]).abs() > half[i]);
    let mut pieces = vec![Vec::new()];
    if curve.closed && points.len() > 2 {
        if let Some(k) = (0..points.len() - 1).find(|&k| jump(&points[k].1, &points[k + 1].1)) {
            // The last point repeats the first in space: drop it, start after the jump,
            // and end at the crossing before the new first point.
            points.pop();
            points.rotate_left(k + 1);
            let (end, start) = crossing(tracer, &points[points.len() - 1], &points[0], tolerance)?;
            if let Some(start) = start {
                points.insert(0, start);
            }
            if let Some(end) = end {
                points.push(end);
            }
        }
    }
    for (k, point) in points.iter().enumerate() {
        if k > 0 && jump(&points[k - 1].1, &point.1) {
            let (end, start) = crossing(tracer, &points[k - 1], point, tolerance)?;
            if let Some(end) = end {
                pieces.last_mut().expect("a piece").push(end);
            }
            pieces.push(start.into_iter().collect());
        }
        pieces.last_mut().expect("a piece").push(*point);
    }
    Ok(pieces)
}

/// Where the curve between the traced points `before` and `after`, whose parameters jump,
/// crosses the boundary of the domain: the point on the side of `before` and the one on the
/// side of `after` (`None` where no point on both surfaces is found there); at a pole, where
/// the jump is not across a boundary, `before`'s point with `after`'s parameters.
fn crossing<T, A, B>(
    tracer: &Tracer<'_, T, A, B>,
    before: &Traced<T>,
    after: &Traced<T>,
    tolerance: T,
) -> Result<Crossing<T>>
where
    T: Scalar,
    A: ParamSurface<T, Point = Vector3<T>>,
    B: ParamSurface<T, Point = Vector3<T>>,
{
    let accept = tolerance * cast::<T>(1e-3);
    let reach = (after.0 - before.0).norm() + tolerance;
    let (lower, upper) = (tracer.lower, tracer.upper);
    let width = upper - lower;
    // The coordinate that jumps most, relative to its domain.
    let i = (0..4)
        .max_by(|&p, &q| {
            let r = |k: usize| (after.1[k] - before.1[k]).abs() / width[k];
            r(p).partial_cmp(&r(q)).unwrap_or(std::cmp::Ordering::Equal)
        })
        .expect("four coordinates");
    let near_bound = |x: T| {
        if x - lower[i] < upper[i] - x {
            lower[i]
        } else {
            upper[i]
        }
    };
    let (from, to) = (near_bound(before.1[i]), near_bound(after.1[i]));
    let settle = |x: &Vector4<T>, value: T| -> Result<Option<Traced<T>>> {
        let (y, residual) = tracer.on_bound(*x, i, value)?;
        let point = tracer.eval(&y)?.a[0];
        Ok((residual <= accept && (point - before.0).norm() <= reach).then_some((point, y)))
    };
    if from != to {
        let end = settle(&before.1, from)?;
        let start = settle(&after.1, to)?;
        if end.is_some() && start.is_some() {
            return Ok((end, start));
        }
    }
    // A pole: the next piece starts where this one ends, with the next parameters.
    let chord = after.0 - before.0;
    if chord.norm() > T::zero() {
        let (y, residual) = tracer.on_plane(after.1, before.0, chord / chord.norm())?;
        if residual <= accept {
            return Ok((None, Some((tracer.eval(&y)?.a[0], y))));
        }
    }
    Ok((None, None))
}

/// The cubic B-splines of one smooth piece of traced points.
fn fit_piece<T, A, B>(
    tracer: &Tracer<'_, T, A, B>,
    piece: &[Traced<T>],
    tolerance: T,
) -> Result<IntersectionSpline<T>>
where
    T: Scalar,
    A: ParamSurface<T, Point = Vector3<T>>,
    B: ParamSurface<T, Point = Vector3<T>>,
{
    // Chord-length parameters on [0, 1].
    let mut params = vec![T::zero()];
    for w in piece.windows(2) {
        let last = params[params.len() - 1];
        params.push(last + (w[1].0 - w[0].0).norm());
    }
    let total = params[params.len() - 1];
    if total > T::zero() {
        for t in &mut params {
            *t /= total;
        }
    } else {
        // A piece of coincident points: a constant curve.
        let m = params.len() - 1;
        for (k, t) in params.iter_mut().enumerate() {
            *t = cast::<T>(k as f64) / cast::<T>(m as f64);
        }
    }
    // The largest speed of each surface along the piece.
    let mut sigma_a = T::zero();
    let mut sigma_b = T::zero();
    for (_, x) in piece {
        let p = tracer.eval(x)?;
        sigma_a = sigma_a.max(p.a[1].norm()).max(p.a[2].norm());
        sigma_b = sigma_b.max(p.b[1].norm()).max(p.b[2].norm());
    }
    let weight = |s: T| if s > T::zero() { s } else { T::one() };
    let (sigma_a, sigma_b) = (weight(sigma_a), weight(sigma_b));
    let last = piece.len() - 1;
    let point_at = |t: T| -> Result<SVector<T, 7>> {
        let k = params.partition_point(|&s| s <= t).clamp(1, last) - 1;
        let span = params[k + 1] - params[k];
        let lambda = if span > T::zero() {
            ((t - params[k]) / span).max(T::zero()).min(T::one())
        } else {
            T::zero()
        };
        let (p0, x0) = piece[k];
        let (p1, x1) = piece[k + 1];
        let guess = x0 + (x1 - x0) * lambda;
        let origin = p0 + (p1 - p0) * lambda;
        let chord = p1 - p0;
        let settled = if lambda == T::zero() {
            Some(x0)
        } else if lambda == T::one() {
            Some(x1)
        } else if chord.norm() > T::zero() {
            let (x, residual) = tracer.on_plane(guess, origin, chord / chord.norm())?;
            (residual <= tolerance * cast::<T>(1e-3)).then_some(x)
        } else {
            None
        };
        let (point, x) = match settled {
            Some(x) => (tracer.eval(&x)?.a[0], x),
            // Where no point on both surfaces is found (a tangency at the end of the
            // trace), the polyline's own point, within the tracing tolerance of the curve.
            None => (origin, guess),
        };
        Ok(SVector::<T, 7>::from_column_slice(&[
            point.x,
            point.y,
            point.z,
            x[0] * sigma_a,
            x[1] * sigma_a,
            x[2] * sigma_b,
            x[3] * sigma_b,
        ]))
    };
    let fit = AdaptiveApproximation::new(3, tolerance).fit((T::zero(), T::one()), point_at)?;
    let curve = fit
        .curve
        .map_control_points(|q| Vector3::new(q[0], q[1], q[2]));
    let pcurve_a = fit
        .curve
        .map_control_points(|q| Vector2::new(q[3] / sigma_a, q[4] / sigma_a));
    let pcurve_b = fit
        .curve
        .map_control_points(|q| Vector2::new(q[5] / sigma_b, q[6] / sigma_b));
    // The errors in space of the three curves at the points between the traced ones.
    let mut max_error = fit.max_error;
    let ((ua0, ua1), (va0, va1)) = tracer.a.domain();
    let ((ub0, ub1), (vb0, vb1)) = tracer.b.domain();
    let inside = |q: Vector2<T>, (u0, u1): (T, T), (v0, v1): (T, T)| {
        (q.x.max(u0).min(u1), q.y.max(v0).min(v1))
    };
    for k in 0..last {
        for j in 0..4 {
            let t = params[k] + (params[k + 1] - params[k]) * cast::<T>(f64::from(j) / 4.0);
            let exact = point_at(t)?;
            let x = Vector3::new(exact[0], exact[1], exact[2]);
            let c = curve.eval(t)?;
            let (ua, va) = inside(pcurve_a.eval(t)?, (ua0, ua1), (va0, va1));
            let (ub, vb) = inside(pcurve_b.eval(t)?, (ub0, ub1), (vb0, vb1));
            let on_a = tracer.a.eval(ua, va)? / tracer.unit();
            let on_b = tracer.b.eval(ub, vb)? / tracer.unit();
            max_error = max_error
                .max((c - x).norm())
                .max((on_a - x).norm())
                .max((on_b - x).norm());
        }
    }
    Ok(IntersectionSpline {
        curve,
        pcurve_a,
        pcurve_b,
        max_error,
    })
}
