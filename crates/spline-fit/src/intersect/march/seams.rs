//! Curves traced on across the seams of closed surfaces: where a traced curve reaches a
//! boundary of a domain whose other side is the same points of the surface (the seam of a
//! torus, a sphere, a closed surface of revolution), the trace goes on from the other side,
//! so that no piece of a curve between two seam crossings depends on a seed of its own
//! (a piece in the corner where the two seams of a torus meet is a few thousandths of the
//! domain, smaller than the leaves that give the seeds).

use super::Tracer;
use nalgebra::{Vector3, Vector4};
use spline_core::{Result, Scalar, cast};
use spline_geom::ParamSurface;

impl<T: Scalar, A, B> Tracer<'_, T, A, B>
where
    A: ParamSurface<T, Point = Vector3<T>>,
    B: ParamSurface<T, Point = Vector3<T>>,
{
    /// Where a curve that ends at `end`, going along `direction`, goes on across the seams
    /// of the closed surfaces: `end` with each parameter that leaves its domain there (its
    /// point within the distance tolerance of the boundary) moved to the other side of the
    /// domain, and the direction there. `None` unless some parameter leaves, and all those
    /// that leave cross seams (the surface the same point on both sides): an end on an edge
    /// of a surface, or at a tangency, is the end of the curve.
    fn across_seams(
        &self,
        end: &Vector4<T>,
        direction: &Vector3<T>,
    ) -> Result<Option<(Vector4<T>, Vector3<T>)>> {
        let p = self.eval(end)?;
        let Some(t) = self.tangent(&p) else {
            return Ok(None);
        };
        let t = if t.dot(direction) >= T::zero() { t } else { -t };
        let velocity = Self::parameter_step(&p, &t);
        let speeds = [p.a[1].norm(), p.a[2].norm(), p.b[1].norm(), p.b[2].norm()];
        let point = |x: &Vector4<T>, k: usize| -> Result<Vector3<T>> {
            let q = self.eval(x)?;
            Ok(if k < 2 { q.a[0] } else { q.b[0] })
        };
        let mut wrapped = *end;
        let mut crossed = false;
        for k in 0..4 {
            let (bound, other) = if velocity[k] < T::zero() {
                (self.lower[k], self.upper[k])
            } else if velocity[k] > T::zero() {
                (self.upper[k], self.lower[k])
            } else {
                continue;
            };
            // A parameter within the distance tolerance of the boundary it heads for is on
            // it (a curve through the corner of a domain crosses both seams at once).
            if !((end[k] - bound).abs() * speeds[k] <= self.distance) {
                continue;
            }
            let mut here = wrapped;
            here[k] = bound;
            let mut there = wrapped;
            there[k] = other;
            if !((point(&here, k)? - point(&there, k)?).norm() <= self.distance) {
                return Ok(None);
            }
            wrapped = there;
            crossed = true;
        }
        if !crossed {
            return Ok(None);
        }
        let Some(s) = self.tangent(&self.eval(&wrapped)?) else {
            return Ok(None);
        };
        Ok(Some((wrapped, if s.dot(&t) >= T::zero() { s } else { -s })))
    }

    /// Traces from the seed `home` along `direction` as [`Tracer::trace`], and on across the
    /// seams of closed surfaces (the parameters jump there; the point on the far side is
    /// not repeated) until the curve ends, closes at `home`, or crosses into a curve already
    /// traced (`traced` is true at a point of one).
    pub(super) fn trace_across_seams(
        &self,
        home: Vector4<T>,
        direction: Vector3<T>,
        traced: impl Fn(&Vector3<T>) -> bool,
        budget: &mut usize,
    ) -> Result<(Vec<Vector4<T>>, bool)> {
        let origin = self.eval(&home)?.a[0];
        // Points this close are one point (the radius of `join_pieces`).
        let same = self.distance * cast::<T>(100.0);
        let mut out = Vec::new();
        let mut travelled = T::zero();
        let mut crossed = false;
        let (mut start, mut dir) = (home, direction);
        loop {
            let segment = self.trace(start, dir, &home, &mut travelled, budget)?;
            // A trace after a seam that makes no step ends the curve (no endless crossing
            // back and forth); the first may end at once, from a seed on a seam.
            let stuck = segment.points.is_empty() && crossed;
            let end = segment.points.last().copied().unwrap_or(start);
            out.extend(segment.points);
            if segment.closed || stuck {
                return Ok((out, segment.closed));
            }
            let Some((wrapped, t)) = self.across_seams(&end, &segment.direction)? else {
                return Ok((out, false));
            };
            let point = self.eval(&wrapped)?.a[0];
            // Across the seam at the seed (a seed on a seam): the loop is closed, its last
            // point the seed in space, on the other side of the seam.
            if travelled > self.max_step * cast::<T>(2.0) && (point - origin).norm() <= same {
                return Ok((out, true));
            }
            if traced(&point) {
                return Ok((out, false));
            }
            crossed = true;
            (start, dir) = (wrapped, t);
        }
    }
}
