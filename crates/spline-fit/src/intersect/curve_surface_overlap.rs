//! Arcs of a curve that lie in a surface: consecutive intersection points between which the
//! curve stays on the surface within the distance tolerance become one interval, its ends
//! pushed out by bisection on the distance.

use super::curve_surface::{CurveSurfaceHit, intersect_curve_surface};
use super::{Tolerances, check_tolerance, scale_of_boxes};
use crate::surface_project::{BoxTree, SurfaceProjector, bounding_box};
use nalgebra::Vector3;
use spline_core::{Result, Scalar, cast, march_to_boundary, to_f64};
use spline_geom::{ParamCurve, ParamSurface};

/// An arc of a curve that lies in a surface within the distance tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveSurfaceOverlap<T> {
    /// The curve's interval `[t.0, t.1]`, `t.0 < t.1`.
    pub t: (T, T),
    /// The surface parameters `(u, v)` at its two ends.
    pub uv: ((T, T), (T, T)),
    /// The curve's points at its two ends.
    pub points: (Vector3<T>, Vector3<T>),
}

/// The intersections of a curve and a surface: isolated points and arcs in the surface.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CurveSurfaceIntersections<T> {
    /// The isolated points, sorted by the curve's parameter.
    pub points: Vec<CurveSurfaceHit<T>>,
    /// The arcs of the curve in the surface, sorted.
    pub overlaps: Vec<CurveSurfaceOverlap<T>>,
}

/// One answer of [`CurveSurfaceIntersections::events`]: an isolated point or an arc of the
/// curve in the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CurveSurfaceEvent<'a, T> {
    /// An isolated intersection.
    Point(&'a CurveSurfaceHit<T>),
    /// An arc of the curve lying in the surface.
    Overlap(&'a CurveSurfaceOverlap<T>),
}

impl<T: Scalar> CurveSurfaceIntersections<T> {
    /// The points and the arcs in one list, in increasing curve parameter `t` (an arc at the
    /// start of its interval; a point before an arc that starts where it lies): the order in
    /// which a front end reports them.
    #[must_use]
    pub fn events(&self) -> Vec<CurveSurfaceEvent<'_, T>> {
        let mut events: Vec<(T, CurveSurfaceEvent<'_, T>)> = self
            .points
            .iter()
            .map(|p| (p.t, CurveSurfaceEvent::Point(p)))
            .chain(
                self.overlaps
                    .iter()
                    .map(|o| (o.t.0, CurveSurfaceEvent::Overlap(o))),
            )
            .collect();
        events.sort_by(|x, y| to_f64(x.0).total_cmp(&to_f64(y.0)));
        events.into_iter().map(|(_, event)| event).collect()
    }
}

/// A curve parameter with the surface parameters of its point.
type OnBoth<T> = (T, (T, T));

/// Samples checked between two consecutive points.
const SAMPLES: usize = 16;

/// [`intersect_curve_surface`] with the arcs along which the curve lies in the surface
/// reported as intervals ([`CurveSurfaceOverlap`]) instead of points along them: between
/// consecutive intersection points, 15 samples of the curve projected onto the surface (a
/// local Newton iteration from the interpolated parameters) all within the distance
/// tolerance make one arc; arcs that touch are merged and their ends found by bisection on
/// the distance (maximal intervals). Points inside an arc are not listed again.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::{Tolerances, intersect_curve_surface_with_overlaps};
/// use spline_geom::{BSpline, Surface};
/// // The plane z = 0 over [0, 1]², and a line in it from (−1, 0.5, 0) to (2, 0.5, 0).
/// let plane = Surface::bezier(vec![
///     vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 1.0, 0.0)],
///     vec![Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 1.0, 0.0)],
/// ])?;
/// let line = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
///     vec![Vector3::new(-1.0, 0.5, 0.0), Vector3::new(2.0, 0.5, 0.0)])?;
/// let found = intersect_curve_surface_with_overlaps(&line, &plane, &Tolerances::default())?;
/// assert!(found.points.is_empty() && found.overlaps.len() == 1);
/// let (t0, t1): (f64, f64) = found.overlaps[0].t;
/// assert!((t0 - 1.0 / 3.0).abs() < 1e-8 && (t1 - 2.0 / 3.0).abs() < 1e-8);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`intersect_curve_surface`].
pub fn intersect_curve_surface_with_overlaps<T, C, S>(
    curve: &C,
    surface: &S,
    tolerances: &Tolerances<T>,
) -> Result<CurveSurfaceIntersections<T>>
where
    T: Scalar,
    C: ParamCurve<T, Point = Vector3<T>>,
    S: ParamSurface<T, Point = Vector3<T>>,
{
    check_tolerance(tolerances)?;
    let hits = intersect_curve_surface(curve, surface, tolerances)?;
    let tree = BoxTree::new(surface)?;
    let polygon = bounding_box(curve.control_polygon().into_iter());
    let distance = tolerances.distance_for(scale_of_boxes(&tree, std::iter::once(polygon)));
    let projector = SurfaceProjector::new(surface)?;
    let on = |t: T, uv: (T, T)| -> Result<Option<(T, T)>> {
        let p = projector.local(curve.eval(t)?, uv)?;
        Ok((p.distance <= distance).then_some((p.u, p.v)))
    };
    // Arcs between consecutive points.
    let mut arcs: Vec<(OnBoth<T>, OnBoth<T>)> = Vec::new();
    for w in hits.windows(2) {
        let (h0, h1) = (&w[0], &w[1]);
        if !(h1.t > h0.t) {
            continue;
        }
        let mut uv = (h0.u, h0.v);
        let mut all = true;
        for k in 1..SAMPLES {
            let f: T = cast(k as f64 / SAMPLES as f64);
            let t = h0.t + (h1.t - h0.t) * f;
            match on(t, uv)? {
                Some(next) => uv = next,
                None => {
                    all = false;
                    break;
                }
            }
        }
        if all {
            let arc = ((h0.t, (h0.u, h0.v)), (h1.t, (h1.u, h1.v)));
            match arcs.last_mut() {
                Some(last) if last.1.0 == h0.t => last.1 = arc.1,
                _ => arcs.push(arc),
            }
        }
    }
    let (ta, tb) = curve.domain();
    let mut overlaps = Vec::new();
    for (start, end) in arcs {
        let start = push_out(start, ta, &on)?;
        let end = push_out(end, tb, &on)?;
        overlaps.push(CurveSurfaceOverlap {
            t: (start.0, end.0),
            uv: (start.1, end.1),
            points: (curve.eval(start.0)?, curve.eval(end.0)?),
        });
    }
    let margin = (tb - ta) * cast(1e-9);
    let points = hits
        .into_iter()
        .filter(|h| {
            !overlaps
                .iter()
                .any(|o| h.t >= o.t.0 - margin && h.t <= o.t.1 + margin)
        })
        .collect();
    Ok(CurveSurfaceIntersections { points, overlaps })
}

/// From `(t, uv)` on the surface towards `limit`: the last parameter still on it, by
/// doubling steps then bisection.
fn push_out<T: Scalar>(
    (t, uv): OnBoth<T>,
    limit: T,
    on: &impl Fn(T, (T, T)) -> Result<Option<(T, T)>>,
) -> Result<OnBoth<T>> {
    let (good, _) = march_to_boundary((t, uv), limit, |m, good| on(m, good.1))?;
    Ok(good)
}
