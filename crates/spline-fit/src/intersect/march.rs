//! Surface–surface intersection by marching: seeds from overlapping leaves of the two box
//! hierarchies, then tracing along $n_A \times n_B$ with a predictor, a corrector on the
//! plane normal to the step, and step control by the deviation of each chord.

use super::curve_surface::overlapping;
use super::{Tolerances, check_tolerance, lm_solve, scale_of_boxes};
use crate::surface_project::BoxTree;
use nalgebra::{Matrix2, SMatrix, Vector2, Vector3, Vector4};
use spline_core::{
    ControlPoint, Error, ErrorKind, Result, Scalar, cast, power_of_two_scale, to_f64,
};
use spline_geom::ParamSurface;

mod seams;

/// The most points of all traced curves together.
pub const MAX_TRACE_POINTS: usize = 1_000_000;

/// A curve where two surfaces meet, traced as a polyline.
#[derive(Clone, Debug, PartialEq)]
pub struct IntersectionCurve<T> {
    /// The points of the polyline (on the first surface).
    pub points: Vec<Vector3<T>>,
    /// Their parameters on the first surface.
    pub uv_a: Vec<(T, T)>,
    /// Their parameters on the second surface.
    pub uv_b: Vec<(T, T)>,
    /// Whether the curve is a closed loop (its last point repeats the first in space; its
    /// parameters may be those of the other side of a seam).
    pub closed: bool,
}

/// Values and first partials of both surfaces at `x = (u_a, v_a, u_b, v_b)`.
pub(super) struct Pair<T> {
    pub(super) a: [Vector3<T>; 3],
    pub(super) b: [Vector3<T>; 3],
}

fn partials<T: Scalar, S: ParamSurface<T, Point = Vector3<T>>>(
    s: &S,
    u: T,
    v: T,
) -> Result<[Vector3<T>; 3]> {
    let mut d = [Vector3::zeros(); 4];
    s.derivatives_into(u, v, 1, &mut d)?;
    Ok([d[0], d[2], d[1]])
}

pub(super) struct Tracer<'s, T: Scalar, A, B> {
    pub(super) a: &'s A,
    pub(super) b: &'s B,
    pub(super) lower: Vector4<T>,
    pub(super) upper: Vector4<T>,
    distance: T,
    trace: T,
    angle: T,
    max_step: T,
    /// The power of four near the size of the surfaces: every point and partial is divided
    /// by it (exactly), so that marching sees objects of size about one at any scale.
    unit: T,
}

impl<'s, T: Scalar, A, B> Tracer<'s, T, A, B>
where
    A: ParamSurface<T, Point = Vector3<T>>,
    B: ParamSurface<T, Point = Vector3<T>>,
{
    /// The tracer of `a` and `b` with the tolerances for objects of size `scale`; its
    /// points, partials and lengths are in units of [`Tracer::unit`] (a power of four near
    /// `scale`).
    pub(super) fn new(a: &'s A, b: &'s B, tolerances: &Tolerances<T>, scale: T) -> Self {
        let ((ua0, ua1), (va0, va1)) = a.domain();
        let ((ub0, ub1), (vb0, vb1)) = b.domain();
        let unit: T = cast(power_of_two_scale(to_f64(scale)));
        Self {
            a,
            b,
            lower: Vector4::new(ua0, va0, ub0, vb0),
            upper: Vector4::new(ua1, va1, ub1, vb1),
            distance: tolerances.distance_for(scale) / unit,
            trace: tolerances.trace_for(scale) / unit,
            angle: tolerances.angle,
            max_step: scale * cast::<T>(0.02) / unit,
            unit,
        }
    }

    /// The unit of the tracer's points and lengths.
    pub(super) fn unit(&self) -> T {
        self.unit
    }

    /// The points and first partials of both surfaces at `x`, in units of [`Tracer::unit`].
    pub(super) fn eval(&self, x: &Vector4<T>) -> Result<Pair<T>> {
        let inverse = T::one() / self.unit;
        let scaled = |d: [Vector3<T>; 3]| d.map(|v| v * inverse);
        Ok(Pair {
            a: scaled(partials(self.a, x[0], x[1])?),
            b: scaled(partials(self.b, x[2], x[3])?),
        })
    }

    /// A point on both surfaces near `x`: residual norm and the point.
    fn settle(&self, x: Vector4<T>) -> Result<(Vector4<T>, T)> {
        lm_solve(
            |x: &Vector4<T>| {
                let p = self.eval(x)?;
                let j = SMatrix::<T, 3, 4>::from_columns(&[p.a[1], p.a[2], -p.b[1], -p.b[2]]);
                Ok((p.a[0] - p.b[0], j))
            },
            x,
            (self.lower, self.upper),
        )
    }

    /// A point on both surfaces and on the plane through `origin` normal to `normal`.
    pub(super) fn on_plane(
        &self,
        x: Vector4<T>,
        origin: Vector3<T>,
        normal: Vector3<T>,
    ) -> Result<(Vector4<T>, T)> {
        self.constrained(x, |p: &Pair<T>, _| {
            (
                (p.a[0] - origin).dot(&normal),
                Vector4::new(
                    normal.dot(&p.a[1]),
                    normal.dot(&p.a[2]),
                    T::zero(),
                    T::zero(),
                ),
            )
        })
    }

    /// A point on both surfaces with parameter `index` at `value` (a domain boundary).
    pub(super) fn on_bound(
        &self,
        x: Vector4<T>,
        index: usize,
        value: T,
    ) -> Result<(Vector4<T>, T)> {
        self.constrained(x, |_, x: &Vector4<T>| {
            let mut row = Vector4::zeros();
            row[index] = T::one();
            (x[index] - value, row)
        })
    }

    fn constrained(
        &self,
        x: Vector4<T>,
        extra: impl Fn(&Pair<T>, &Vector4<T>) -> (T, Vector4<T>),
    ) -> Result<(Vector4<T>, T)> {
        lm_solve(
            |x: &Vector4<T>| {
                let p = self.eval(x)?;
                let d = p.a[0] - p.b[0];
                let (e, row) = extra(&p, x);
                let mut j = SMatrix::<T, 4, 4>::zeros();
                for (c, col) in [p.a[1], p.a[2], -p.b[1], -p.b[2]].iter().enumerate() {
                    for r in 0..3 {
                        j[(r, c)] = col[r];
                    }
                    j[(3, c)] = row[c];
                }
                Ok((Vector4::new(d[0], d[1], d[2], e), j))
            },
            x,
            (self.lower, self.upper),
        )
    }

    /// The unit tangent of the intersection at `x`, or `None` where the surfaces are
    /// tangent to each other.
    fn tangent(&self, p: &Pair<T>) -> Option<Vector3<T>> {
        // Partials divided by their lengths first: their cross products would overflow (or
        // underflow) for surfaces of size 1e±150 and beyond.
        let unit = |d: &Vector3<T>| {
            let length = ControlPoint::length(d);
            (length > T::zero()).then(|| d / length)
        };
        let (a1, a2, b1, b2) = (
            unit(&p.a[1])?,
            unit(&p.a[2])?,
            unit(&p.b[1])?,
            unit(&p.b[2])?,
        );
        let na = a1.cross(&a2);
        let nb = b1.cross(&b2);
        let t = na.cross(&nb);
        let scale = na.norm() * nb.norm();
        (t.norm() > self.angle * scale && scale > T::zero()).then(|| t / t.norm())
    }

    /// The change of the parameters of both surfaces that moves their point by `step`
    /// (first order).
    fn parameter_step(p: &Pair<T>, step: &Vector3<T>) -> Vector4<T> {
        let solve = |d: &[Vector3<T>; 3]| -> Vector2<T> {
            let m = Matrix2::new(
                d[1].dot(&d[1]),
                d[1].dot(&d[2]),
                d[1].dot(&d[2]),
                d[2].dot(&d[2]),
            );
            let r = Vector2::new(d[1].dot(step), d[2].dot(step));
            m.try_inverse().map_or_else(Vector2::zeros, |inv| inv * r)
        };
        let (da, db) = (solve(&p.a), solve(&p.b));
        Vector4::new(da[0], da[1], db[0], db[1])
    }

    /// Parameters that move the point of both surfaces by `step` (first order).
    fn predict(&self, x: &Vector4<T>, p: &Pair<T>, step: Vector3<T>) -> Vector4<T> {
        (x + Self::parameter_step(p, &step))
            .sup(&self.lower)
            .inf(&self.upper)
    }

    /// How far the midpoint of the chord between two points of the curve is from the curve,
    /// measured on the plane normal to the chord (infinite if no curve point is there).
    fn chord_deviation(&self, x: &Vector4<T>, y: &Vector4<T>) -> Result<T> {
        let half: T = cast(0.5);
        let (p, q) = (self.eval(x)?.a[0], self.eval(y)?.a[0]);
        let chord = q - p;
        let length = chord.norm();
        if !(length > T::zero()) {
            return Ok(T::zero());
        }
        let mid = (p + q) * half;
        let (xm, rm) = self.on_plane((x + y) * half, mid, chord / length)?;
        Ok(if rm <= self.distance {
            (self.eval(&xm)?.a[0] - mid).norm()
        } else {
            T::max_value().unwrap_or_else(|| cast(f64::MAX))
        })
    }

    /// Which parameter of `y` sits on a boundary of its domain that `x`, the point before
    /// it, is not on, if any: a step from `x` to `y` reaches that boundary. (A step along a
    /// boundary that `x` is on, after crossing a seam, reaches no boundary; one from there
    /// to another boundary does, at a corner of the domain.)
    fn reaches_boundary(&self, x: &Vector4<T>, y: &Vector4<T>) -> Option<usize> {
        (0..4).find(|&k| {
            (y[k] <= self.lower[k] && x[k] > self.lower[k])
                || (y[k] >= self.upper[k] && x[k] < self.upper[k])
        })
    }

    /// Traces from `start` along `direction` until a boundary, a closed loop (back at
    /// `home`, the seed of the curve, after `travelled` and the length of this trace) or a
    /// tangency: the points after the start, whether the loop closed and the direction of
    /// the last step.
    fn trace(
        &self,
        start: Vector4<T>,
        direction: Vector3<T>,
        home: &Vector4<T>,
        travelled: &mut T,
        budget: &mut usize,
    ) -> Result<Segment<T>> {
        let origin = self.eval(home)?.a[0];
        let mut out = Vec::new();
        let (mut x, mut dir) = (start, direction);
        let mut h = self.max_step;
        let min_step = self.max_step * cast::<T>(1e-9);
        let half: T = cast(0.5);
        let open = |points, direction| Segment {
            points,
            closed: false,
            direction,
        };
        loop {
            if *budget == 0 {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!(
                        "the intersection curves need more than {MAX_TRACE_POINTS} points at this tolerance"
                    ),
                ));
            }
            let p = self.eval(&x)?;
            let here = p.a[0];
            // A step that leaves a domain ends at its boundary.
            let predicted = self.predict(&x, &p, dir * h);
            let (next, residual) = self.on_plane(predicted, here + dir * h, dir)?;
            let advance = (self.eval(&next)?.a[0] - here).dot(&dir);
            if !(residual <= self.distance) || !(advance > T::zero()) {
                if let Some(k) = self.reaches_boundary(&x, &predicted) {
                    let value = if predicted[k] <= self.lower[k] {
                        self.lower[k]
                    } else {
                        self.upper[k]
                    };
                    let (end, r) = self.on_bound(x, k, value)?;
                    if r <= self.distance
                        && (self.eval(&end)?.a[0] - here).dot(&dir) > T::zero()
                        && self.chord_deviation(&x, &end)? <= self.trace
                    {
                        out.push(end);
                        return Ok(open(out, dir));
                    }
                }
                h *= half;
                if h < min_step {
                    return Ok(open(out, dir));
                }
                continue;
            }
            // The chord must stay within the tracing tolerance of the curve.
            let there = self.eval(&next)?.a[0];
            let chord = there - here;
            let deviation = self.chord_deviation(&x, &next)?;
            if deviation > self.trace {
                h *= half;
                if h < min_step {
                    return Ok(open(out, dir));
                }
                continue;
            }
            *travelled += chord.norm();
            *budget -= 1;
            // Back at the seed: the loop is closed.
            if *travelled > self.max_step * cast::<T>(2.0)
                && (origin - here).norm() <= chord.norm() * cast::<T>(1.01)
                && (origin - here).dot(&dir) > T::zero()
            {
                out.push(*home);
                return Ok(Segment {
                    points: out,
                    closed: true,
                    direction: dir,
                });
            }
            out.push(next);
            if self.reaches_boundary(&x, &next).is_some() {
                return Ok(open(out, dir));
            }
            let Some(t) = self.tangent(&self.eval(&next)?) else {
                return Ok(open(out, dir));
            };
            dir = if t.dot(&dir) >= T::zero() { t } else { -t };
            x = next;
            if deviation < self.trace * cast::<T>(0.25) {
                h = (h * cast::<T>(1.5)).min(self.max_step);
            }
        }
    }
}

/// The points of one run of [`Tracer::trace`].
struct Segment<T> {
    /// The points after the start.
    points: Vec<Vector4<T>>,
    /// Whether the curve came back to its seed.
    closed: bool,
    /// The direction of the last step.
    direction: Vector3<T>,
}

/// The curves where two surfaces in space meet (any kinds), traced as polylines to a
/// tolerance, with their parameters on both surfaces.
///
/// Seeds: every pair of overlapping leaves of the two box hierarchies (as in
/// [`crate::SurfaceProjector`]) starts a Levenberg–Marquardt iteration for
/// $S_A(u_A, v_A) = S_B(u_B, v_B)$; a seed on a curve already traced is skipped. Tracing,
/// from each new seed both ways: the step goes along the tangent $n_A \times n_B$; the
/// corrector puts the point on both surfaces and on the plane normal to the step; the step
/// is halved until the chord's midpoint lies within [`Tolerances::trace`] of the curve
/// (measured on the plane normal to the chord), and grows again when it is far below. A
/// curve that meets the seam of a closed surface (a boundary of its domain where the
/// opposite side is the same points) goes on from the other side, its parameters jumping
/// there (both seams at once at the corner where they meet); it ends where it meets any
/// other boundary of a domain (the end point is on it) or where the surfaces become
/// tangent; it is closed when it comes back to its seed. Points and partials
/// are divided by a power of four near the size of the surfaces while marching (exactly), so
/// the curves of surfaces scaled by any factor from 1e-300 to 1e300 are the scaled curves.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::{Tolerances, intersect_surfaces};
/// use spline_geom::{NurbsSurface, Surface};
/// let sphere = NurbsSurface::sphere(Vector3::new(0.0f64, 0.0, 0.0), 1.0)?;
/// let plane = Surface::bezier(vec![
///     vec![Vector3::new(-2.0, -2.0, 0.5), Vector3::new(-2.0, 2.0, 0.5)],
///     vec![Vector3::new(2.0, -2.0, 0.5), Vector3::new(2.0, 2.0, 0.5)],
/// ])?;
/// let curves = intersect_surfaces(&sphere, &plane, &Tolerances::default())?;
/// assert_eq!(curves.len(), 1);
/// assert!(curves[0].closed);
/// for p in &curves[0].points {  // the circle of radius √3/2 at z = 1/2
///     assert!((p.xy().norm() - 0.75f64.sqrt()).abs() < 1e-9 && (p.z - 0.5).abs() < 1e-9);
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidTolerance`]; [`ErrorKind::InvalidArgument`] when the curves would
/// need more than [`MAX_TRACE_POINTS`] points.
pub fn intersect_surfaces<T, A, B>(
    a: &A,
    b: &B,
    tolerances: &Tolerances<T>,
) -> Result<Vec<IntersectionCurve<T>>>
where
    T: Scalar,
    A: ParamSurface<T, Point = Vector3<T>>,
    B: ParamSurface<T, Point = Vector3<T>>,
{
    check_tolerance(tolerances)?;
    let ta = BoxTree::new(a)?;
    let tb = BoxTree::new(b)?;
    let root_b = &tb.nodes[tb.root];
    let scale = scale_of_boxes(&ta, std::iter::once((root_b.lo, root_b.hi)));
    let tracer = Tracer::new(a, b, tolerances, scale);
    let half: T = cast(0.5);
    let mut curves: Vec<IntersectionCurve<T>> = Vec::new();
    let mut budget = MAX_TRACE_POINTS;
    let mut found = Vec::new();
    let leaves_a: Vec<usize> = (0..ta.nodes.len())
        .filter(|&k| ta.nodes[k].children.is_none())
        .collect();
    for &la in &leaves_a {
        let na = &ta.nodes[la];
        found.clear();
        overlapping(
            &tb,
            &na.lo,
            &na.hi,
            tracer.distance * tracer.unit,
            &mut found,
        );
        for &lb in &found {
            let nb = &tb.nodes[lb];
            let start = Vector4::new(
                (na.rect.0.0 + na.rect.0.1) * half,
                (na.rect.1.0 + na.rect.1.1) * half,
                (nb.rect.0.0 + nb.rect.0.1) * half,
                (nb.rect.1.0 + nb.rect.1.1) * half,
            );
            let (seed, residual) = tracer.settle(start)?;
            if !(residual <= tracer.distance) {
                continue;
            }
            let p = tracer.eval(&seed)?;
            let near = cast::<T>(4.0) * tracer.trace + cast::<T>(4.0) * tracer.distance;
            if curves
                .iter()
                .any(|c| near_polyline(&c.points, &p.a[0], near))
            {
                continue;
            }
            let Some(t) = tracer.tangent(&p) else {
                continue;
            };
            let traced = |q: &Vector3<T>| curves.iter().any(|c| near_polyline(&c.points, q, near));
            let (forward, closed) = tracer.trace_across_seams(seed, t, traced, &mut budget)?;
            let mut xs: Vec<Vector4<T>> = Vec::new();
            if !closed {
                let (backward, _) = tracer.trace_across_seams(seed, -t, traced, &mut budget)?;
                xs.extend(backward.into_iter().rev());
            }
            xs.push(seed);
            xs.extend(forward);
            let mut curve = IntersectionCurve {
                points: Vec::with_capacity(xs.len()),
                uv_a: Vec::with_capacity(xs.len()),
                uv_b: Vec::with_capacity(xs.len()),
                closed,
            };
            for x in &xs {
                curve.points.push(tracer.eval(x)?.a[0]);
                curve.uv_a.push((x[0], x[1]));
                curve.uv_b.push((x[2], x[3]));
            }
            curves.push(curve);
        }
    }
    let mut joined = join_pieces(curves, tracer.distance * cast::<T>(100.0));
    for curve in &mut joined {
        for p in &mut curve.points {
            *p *= tracer.unit;
        }
    }
    Ok(joined)
}

/// Joins curves whose ends meet in space (a curve crossing the seam of a closed surface is
/// traced in pieces, its parameters jumping at the seam), and closes those whose two ends
/// meet.
fn join_pieces<T: Scalar>(
    mut curves: Vec<IntersectionCurve<T>>,
    radius: T,
) -> Vec<IntersectionCurve<T>> {
    let meet = |a: &Vector3<T>, b: &Vector3<T>| (a - b).norm() <= radius;
    let reversed = |c: IntersectionCurve<T>| IntersectionCurve {
        points: c.points.into_iter().rev().collect(),
        uv_a: c.uv_a.into_iter().rev().collect(),
        uv_b: c.uv_b.into_iter().rev().collect(),
        closed: c.closed,
    };
    let mut done: Vec<IntersectionCurve<T>> = Vec::new();
    while let Some(mut c) = curves.pop() {
        loop {
            if c.closed {
                break;
            }
            let (first, last) = (c.points[0], c.points[c.points.len() - 1]);
            if c.points.len() > 2 && meet(&first, &last) {
                c.closed = true;
                break;
            }
            let Some(k) = curves.iter().position(|o| {
                !o.closed
                    && (meet(&last, &o.points[0]) || meet(&last, &o.points[o.points.len() - 1]))
            }) else {
                break;
            };
            let mut other = curves.swap_remove(k);
            if !meet(&last, &other.points[0]) {
                other = reversed(other);
            }
            c.points.extend(other.points.into_iter().skip(1));
            c.uv_a.extend(other.uv_a.into_iter().skip(1));
            c.uv_b.extend(other.uv_b.into_iter().skip(1));
        }
        done.push(c);
    }
    done.reverse();
    done
}

/// Whether `q` lies within `radius` of the polyline.
fn near_polyline<T: Scalar>(points: &[Vector3<T>], q: &Vector3<T>, radius: T) -> bool {
    if points.len() == 1 {
        return (points[0] - q).norm() <= radius;
    }
    points.windows(2).any(|w| {
        let ab = w[1] - w[0];
        let len2 = ab.norm_squared();
        let t = if len2 > T::zero() {
            ((q - w[0]).dot(&ab) / len2).max(T::zero()).min(T::one())
        } else {
            T::zero()
        };
        (q - (w[0] + ab * t)).norm() <= radius
    })
}
