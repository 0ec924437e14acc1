//! Curve–surface intersection: subdivision with bounding boxes on both sides, then a
//! Gauss–Newton iteration on $C(t) - S(u, v) = 0$ from every pair of overlapping leaves.

use super::{Tolerances, check_tolerance, lm_solve, scale_of_boxes};
use crate::surface_project::{BoxTree, Node, bounding_box};
use nalgebra::{Matrix3, Vector3};
#[cfg(doc)]
use spline_core::ErrorKind;
use spline_core::{ControlPoint, Result, Scalar, cast, power_of_two_scale, to_f64};
use spline_geom::{Bezier, ParamCurve, ParamSurface};

/// Splits of one Bézier piece of the curve at most.
const MAX_CURVE_SPLITS: usize = 12;

/// A point where a curve meets a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveSurfaceHit<T> {
    /// The curve's parameter.
    pub t: T,
    /// The surface's parameters.
    pub u: T,
    /// The surface's parameters.
    pub v: T,
    /// The point (on the curve).
    pub point: Vector3<T>,
    /// Whether the curve touches the surface there (its tangent lies in the tangent plane,
    /// within [`Tolerances::angle`]) instead of crossing it.
    pub tangential: bool,
}

/// A leaf of a curve: the box `(lo, hi)` and the parameter interval `[a, b]`.
type CurveLeaf<T> = (Vector3<T>, Vector3<T>, T, T);

/// The leaves of a curve: its Bézier pieces subdivided until each box is small.
fn curve_leaves<T: Scalar, C: ParamCurve<T, Point = Vector3<T>>>(
    curve: &C,
) -> Result<Vec<CurveLeaf<T>>> {
    let pieces: Vec<Bezier<T, C::Coefficient>> = curve
        .bezier_pieces()
        .into_iter()
        .map(|(lo, hi, cp)| Bezier::with_interval(cp, lo, hi))
        .collect::<Result<_>>()?;
    let all = bounding_box(curve.control_polygon().into_iter());
    let min_size = ControlPoint::length(&(all.1 - all.0)) * cast::<T>(1.0 / 24.0);
    let mut leaves = Vec::new();
    let mut stack: Vec<(Bezier<T, C::Coefficient>, usize)> =
        pieces.into_iter().map(|p| (p, 0)).collect();
    while let Some((piece, depth)) = stack.pop() {
        let (lo, hi) = bounding_box(piece.control_points().iter().map(C::project));
        let (a, b) = piece.interval();
        let mid = (a + b) * cast::<T>(0.5);
        if (hi - lo).norm() <= min_size || depth >= MAX_CURVE_SPLITS || !(mid > a && mid < b) {
            leaves.push((lo, hi, a, b));
            continue;
        }
        let (l, r) = piece.subdivide(mid)?;
        stack.push((r, depth + 1));
        stack.push((l, depth + 1));
    }
    Ok(leaves)
}

/// Whether two boxes overlap, each grown by `pad`.
pub(super) fn overlap<T: Scalar>(
    a: (&Vector3<T>, &Vector3<T>),
    b: (&Vector3<T>, &Vector3<T>),
    pad: T,
) -> bool {
    (0..3).all(|k| a.0[k] - pad <= b.1[k] && b.0[k] - pad <= a.1[k])
}

/// The leaves of `tree` whose boxes overlap `[lo, hi]` grown by `pad`.
pub(super) fn overlapping<T: Scalar>(
    tree: &BoxTree<T, Vector3<T>>,
    lo: &Vector3<T>,
    hi: &Vector3<T>,
    pad: T,
    out: &mut Vec<usize>,
) {
    let mut stack = vec![tree.root];
    while let Some(k) = stack.pop() {
        let n: &Node<T, Vector3<T>> = &tree.nodes[k];
        if !overlap((&n.lo, &n.hi), (lo, hi), pad) {
            continue;
        }
        match n.children {
            Some((a, b)) => {
                stack.push(a);
                stack.push(b);
            }
            None => out.push(k),
        }
    }
}

/// All points where `curve` meets `surface` (both in space, any kind), sorted by the
/// curve's parameter, each once.
///
/// Both are cut into pieces whose bounding boxes (of their control points: they contain the
/// pieces) are small — the surface's [`crate::SurfaceProjector`] hierarchy, the curve's
/// Bézier pieces halved — and from every pair of overlapping boxes a Gauss–Newton
/// (Levenberg–Marquardt) iteration solves $C(t) = S(u, v)$ within the domains. Pieces whose
/// boxes do not overlap hold no intersection, so none is missed unless two intersections
/// lie within one pair of leaves (closer than a twentieth of the objects' size), or the
/// iteration from the leaves' centres leaves them for another solution. A solution is kept
/// when $\lVert C(t) - S(u, v) \rVert$ is within the distance tolerance
/// ([`Tolerances::distance`]); it is *tangential* when the sine of the angle between the
/// curve's tangent and the tangent plane is below [`Tolerances::angle`]. Solutions within
/// ten distance tolerances of one another are one (a tangential touch is found from several
/// pairs of leaves). A curve that lies in the surface gives points along the overlap.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::{Tolerances, intersect_curve_surface};
/// use spline_geom::{BSpline, NurbsSurface};
/// let sphere = NurbsSurface::sphere(Vector3::new(0.0f64, 0.0, 0.0), 1.0)?;
/// let line = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
///     vec![Vector3::new(-2.0, 0.0, 0.0), Vector3::new(2.0, 0.0, 0.0)])?;
/// let hits = intersect_curve_surface(&line, &sphere, &Tolerances::default())?;
/// assert_eq!(hits.len(), 2);
/// assert!((hits[0].point - Vector3::new(-1.0, 0.0, 0.0)).norm() < 1e-12);
/// assert!((hits[1].t - 0.75).abs() < 1e-12 && !hits[1].tangential);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidTolerance`] for tolerances that are not positive and finite; errors
/// of evaluation (never for valid objects).
pub fn intersect_curve_surface<T, C, S>(
    curve: &C,
    surface: &S,
    tolerances: &Tolerances<T>,
) -> Result<Vec<CurveSurfaceHit<T>>>
where
    T: Scalar,
    C: ParamCurve<T, Point = Vector3<T>>,
    S: ParamSurface<T, Point = Vector3<T>>,
{
    check_tolerance(tolerances)?;
    let tree = BoxTree::new(surface)?;
    let leaves = curve_leaves(curve)?;
    let scale = scale_of_boxes(&tree, leaves.iter().map(|l| (l.0, l.1)));
    let distance = tolerances.distance_for(scale);
    // The equations are solved on the points divided by a power of four near the objects'
    // size (exact): the normal equations (squares of the derivatives) neither overflow at
    // 1e300 nor underflow at 1e-300.
    let inverse = T::one() / cast::<T>(power_of_two_scale(to_f64(scale)));
    let (ta, tb) = curve.domain();
    let ((ua, ub), (va, vb)) = surface.domain();
    let lower = Vector3::new(ta, ua, va);
    let upper = Vector3::new(tb, ub, vb);
    let half: T = cast(0.5);
    let mut hits: Vec<(CurveSurfaceHit<T>, T)> = Vec::new();
    let mut found = Vec::new();
    for &(lo, hi, a, b) in &leaves {
        found.clear();
        overlapping(&tree, &lo, &hi, distance, &mut found);
        for &k in &found {
            let ((u0, u1), (v0, v1)) = tree.nodes[k].rect;
            let start = Vector3::new((a + b) * half, (u0 + u1) * half, (v0 + v1) * half);
            let residual = |x: &Vector3<T>| -> Result<(Vector3<T>, Matrix3<T>)> {
                let mut cd = [Vector3::zeros(); 2];
                curve.derivatives_into(x[0], &mut cd)?;
                let mut sd = [Vector3::zeros(); 4];
                surface.derivatives_into(x[1], x[2], 1, &mut sd)?;
                // sd[k * 2 + l] = ∂^{k+l} S / ∂u^k ∂v^l.
                Ok((
                    (cd[0] - sd[0]) * inverse,
                    Matrix3::from_columns(&[cd[1], -sd[2], -sd[1]]) * inverse,
                ))
            };
            let (x, f) = lm_solve(residual, start, (lower, upper))?;
            let f = f / inverse;
            if !(f <= distance) {
                continue;
            }
            let mut cd = [Vector3::zeros(); 2];
            curve.derivatives_into(x[0], &mut cd)?;
            let mut sd = [Vector3::zeros(); 4];
            surface.derivatives_into(x[1], x[2], 1, &mut sd)?;
            let (tangent, normal) = (cd[1] * inverse, (sd[2] * inverse).cross(&(sd[1] * inverse)));
            let (tn, nn) = (tangent.norm(), normal.norm());
            let tangential = !(tn > T::zero() && nn > T::zero())
                || (tangent.dot(&normal) / (tn * nn)).abs() < tolerances.angle;
            let hit = CurveSurfaceHit {
                t: x[0],
                u: x[1],
                v: x[2],
                point: cd[0],
                tangential,
            };
            // A tangential touch is only located to about the square root of the distance
            // tolerance (the distance grows quadratically away from it).
            let near = |h: &CurveSurfaceHit<T>| {
                let radius = if h.tangential && hit.tangential {
                    distance.sqrt() * scale.sqrt() * cast::<T>(10.0)
                } else {
                    distance * cast::<T>(10.0)
                };
                ControlPoint::length(&(h.point - hit.point)) <= radius
                    && (h.t - hit.t).abs() <= (tb - ta) * cast::<T>(1e-4)
            };
            match hits.iter_mut().find(|(h, _)| near(h)) {
                Some(old) => {
                    if f < old.1 {
                        *old = (hit, f);
                    }
                }
                None => hits.push((hit, f)),
            }
        }
    }
    let mut hits: Vec<CurveSurfaceHit<T>> = hits.into_iter().map(|(h, _)| h).collect();
    hits.sort_by(|a, b| to_f64(a.t).total_cmp(&to_f64(b.t)));
    Ok(hits)
}
