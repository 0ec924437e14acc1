//! What an intersection search answers: isolated intersections and overlaps, and the two
//! in one list along the first curve.

use nalgebra::Vector2;
use spline_core::{Scalar, to_f64};

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

/// An arc along which two curves coincide within the tolerance (or a curve with itself:
/// then `u` lies before `v`): `[u.0, u.1]` on the first curve (`u.0 < u.1`) and its image
/// on the second, from `v.0` (where `A(u.0)` lies) to `v.1` (where `A(u.1)` lies), so
/// `v.0 > v.1` when the curves run in opposite directions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveOverlap<T> {
    /// The interval on the first curve.
    pub u: (T, T),
    /// Its image on the second curve (decreasing when `reversed`).
    pub v: (T, T),
    /// Whether the second curve runs the other way along the overlap.
    pub reversed: bool,
    /// The ends of the overlap, `A(u.0)` and `A(u.1)`.
    pub points: (Vector2<T>, Vector2<T>),
}

/// The intersections of two curves (or the self-intersections of one): isolated points
/// and overlaps.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CurveIntersections<T> {
    /// The isolated intersections, in increasing `u`.
    pub points: Vec<CurveIntersection<T>>,
    /// The arcs along which the curves coincide, in increasing `u.0`.
    pub overlaps: Vec<CurveOverlap<T>>,
}

/// One answer of [`CurveIntersections::events`]: an isolated point or an overlap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CurveEvent<'a, T> {
    /// An isolated intersection.
    Point(&'a CurveIntersection<T>),
    /// An arc along which the curves coincide.
    Overlap(&'a CurveOverlap<T>),
}

impl<T: Scalar> CurveIntersections<T> {
    /// The points and the overlaps in one list, in increasing `u` along the first curve (an
    /// overlap at the start of its interval; a point before an overlap that starts where it
    /// lies): the order in which a front end reports them.
    #[must_use]
    pub fn events(&self) -> Vec<CurveEvent<'_, T>> {
        let mut events: Vec<(T, CurveEvent<'_, T>)> = self
            .points
            .iter()
            .map(|p| (p.u, CurveEvent::Point(p)))
            .chain(
                self.overlaps
                    .iter()
                    .map(|o| (o.u.0, CurveEvent::Overlap(o))),
            )
            .collect();
        events.sort_by(|x, y| to_f64(x.0).total_cmp(&to_f64(y.0)));
        events.into_iter().map(|(_, event)| event).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::{CurveEvent, CurveIntersection, CurveIntersections, CurveOverlap};
    use nalgebra::Vector2;

    #[test]
    fn events_are_in_order_along_the_first_curve() {
        let point = |u: f64| CurveIntersection {
            u,
            v: 0.0,
            point: Vector2::new(u, 0.0),
            tangential: false,
            gap: 0.0,
        };
        let overlap = |u: (f64, f64)| CurveOverlap {
            u,
            v: u,
            reversed: false,
            points: (Vector2::new(u.0, 0.0), Vector2::new(u.1, 0.0)),
        };
        let hits = CurveIntersections {
            points: vec![point(0.1), point(0.5), point(0.9)],
            overlaps: vec![overlap((0.2, 0.4)), overlap((0.5, 0.7))],
        };
        let order: Vec<(f64, bool)> = hits
            .events()
            .iter()
            .map(|e| match e {
                CurveEvent::Point(p) => (p.u, false),
                CurveEvent::Overlap(o) => (o.u.0, true),
            })
            .collect();
        assert_eq!(
            order,
            [
                (0.1, false),
                (0.2, true),
                (0.5, false),
                (0.5, true),
                (0.9, false)
            ]
        );
    }
}
