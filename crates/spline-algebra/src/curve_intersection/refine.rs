//! Newton's method on a candidate: on `A(u) = B(v)`, on the regular system of a tangency,
//! and the local foot point of a point on a curve; duplicates merged.

use super::results::{CurveIntersection, TANGENTIAL_SINE};
use nalgebra::Vector2;
use spline_core::{Result, Scalar, cast};
use spline_geom::{PlanarCurve, wedge};

/// Below this sine of the angle between the tangents, a tangency is tried as well.
pub(super) const NEAR_TANGENT_SINE: f64 = 1e-3;

/// A start for Newton's method.
#[derive(Clone, Copy, Debug)]
pub(super) struct Candidate<T> {
    pub(super) u: T,
    pub(super) v: T,
}

/// Value, first and second derivatives at `u` (clamped into the domain).
pub(super) fn jet<T: Scalar, C: PlanarCurve<T>>(curve: &C, u: T) -> Result<(T, [Vector2<T>; 3])> {
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
pub(super) fn refine<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
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
/// `merge_u`, `merge_v` are the same intersection; so are results with parameters within
/// `10⁵` times those whose points lie within `tolerance` of each other (the branches on
/// either side of a cusp meet like that), or within `radius` when either is a tangency (two
/// curves that touch stay within the tolerance along an arc of half-width about
/// `√(8 tolerance R)` on a curve of radius `R`, and Newton's method may stop anywhere on
/// it). Two transversal crossings farther apart than the tolerance are two intersections
/// however close. The first in `u` is kept, tangential if any of its group is.
pub(super) fn deduplicate<T: Scalar>(
    mut found: Vec<CurveIntersection<T>>,
    (merge_u, merge_v): (T, T),
    radius: T,
    tolerance: T,
) -> Vec<CurveIntersection<T>> {
    found.sort_by(|x, y| x.u.partial_cmp(&y.u).unwrap_or(std::cmp::Ordering::Equal));
    let wide: T = cast(1e5);
    let mut out: Vec<CurveIntersection<T>> = Vec::with_capacity(found.len());
    for f in found {
        if let Some(same) = out.iter_mut().find(|g| {
            let (du, dv) = ((g.u - f.u).abs(), (g.v - f.v).abs());
            let distance = (g.point - f.point).norm();
            let reach = if g.tangential || f.tangential {
                radius
            } else {
                tolerance
            };
            (du <= merge_u && dv <= merge_v)
                || (distance <= reach && du <= merge_u * wide && dv <= merge_v * wide)
        }) {
            same.tangential |= f.tangential;
            continue;
        }
        out.push(f);
    }
    out
}
