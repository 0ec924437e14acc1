//! The cusps of the offsets of planar B-spline curves: where the signed curvature times the
//! offset distance is one, found exactly as the zeros of a polynomial spline built from the
//! curvature invariants.

use crate::curves::{Form, Invariant, PlanarInvariants};
use crate::product::{linear_combination, product, square};
use crate::roots::zeros;
use nalgebra::Vector2;
use spline_core::{Error, Result, Scalar, cast, from_count, to_f64};
use spline_geom::{BSpline, ParamCurve};

/// Grid steps per piece for the sign changes of φ.
const GRID: usize = 1024;

/// Grid steps around a zero of F.
const FINE_GRID: usize = 256;

/// How far from one κ d may be at a zero of F (rounding) for it to be a cusp.
const CUSP_CHECK: f64 = 1e-6;

/// A cusp of the offset $O(u) = C(u) + d\,N(u)$ of a planar curve ($N$ the unit normal to the
/// left of the tangent): a parameter where $\kappa(u)\, d = 1$, so that
/// $O'(u) = \lVert C'(u) \rVert (1 - \kappa(u) d)\, T(u)$ vanishes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OffsetCusp<T> {
    /// The parameter on the curve (and on the offset).
    pub u: T,
    /// The point of the offset there.
    pub point: Vector2<T>,
    /// Whether $\kappa d - 1$ changes sign there (a true cusp, where the offset reverses
    /// direction); otherwise the offset only stops there (a double root).
    pub sign_change: bool,
}

/// The cusps of the offset at signed distance `distance` (positive to the left of the
/// direction of travel) of a polynomial planar B-spline curve: the parameters where
/// $\kappa d = 1$, in increasing order. Candidates are the zeros of the polynomial spline
/// $F = d^2 h_4^2 - h_1^3$ (with $h_1 = C' \cdot C'$, $h_4 = C' \wedge C''$, so that
/// $\kappa = h_4 / h_1^{3/2}$; the root isolation of this crate) and the sign changes of
/// $\varphi = d\,h_4 - h_1^{3/2}$ on a grid of 1024 steps per piece and of 256 steps around
/// every zero of `F` (where the curve is slow, `F` is tiny beside its coefficients and
/// rounding merges or moves its zeros); each is polished by Newton's method on `φ` and kept
/// where $\lvert \kappa d - 1 \rvert \le 10^{-6}$ with $d\,h_4 > 0$. `accuracy` is the
/// parameter accuracy of the isolation (the polish then goes to rounding). Curves of degree
/// 1 have none. Scale-invariant: the curve and the distance are first divided by a power of
/// four near their size, so a curve scaled by any factor from 1e-300 to 1e300 (with its
/// distance) has the same cusps.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::BSpline;
/// // The parabola y = x² on [−1, 1]: κ = 2 / (1 + 4x²)^{3/2}; offset by d = 1 toward the
/// // concave side, cusps where κ = 1: x = ±√((2^{2/3} − 1) / 4).
/// let parabola = BSpline::from_knots(2, vec![-1.0, -1.0, -1.0, 1.0, 1.0, 1.0], vec![
///     Vector2::new(-1.0, 1.0), Vector2::new(0.0, -1.0), Vector2::new(1.0, 1.0)])?;
/// let cusps = spline_algebra::offset_cusps(&parabola, 1.0, 1e-13)?;
/// let x = ((2f64.powf(2.0 / 3.0) - 1.0) / 4.0).sqrt();
/// assert_eq!(cusps.len(), 2);
/// assert!((cusps[0].u + x).abs() < 1e-12 && (cusps[1].u - x).abs() < 1e-12);
/// assert!(cusps.iter().all(|c| c.sign_change));
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`spline_core::ErrorKind::NonFinite`] for a non-finite distance;
/// [`spline_core::ErrorKind::InvalidTolerance`] unless `accuracy` is positive and finite;
/// [`spline_core::ErrorKind::DegreeTooHigh`] when $h_1^3$ exceeds the supported degree (degree
/// above 5); the evaluation errors of the curve.
pub fn offset_cusps<T: Scalar>(
    curve: &BSpline<T, Vector2<T>>,
    distance: T,
    accuracy: T,
) -> Result<Vec<OffsetCusp<T>>> {
    if !distance.is_finite() {
        return Err(Error::non_finite("the offset distance"));
    }
    if !(accuracy > T::zero() && accuracy.is_finite()) {
        return Err(Error::invalid_tolerance(
            "cusp accuracy",
            "positive and finite",
            to_f64(accuracy),
        ));
    }
    if curve.degree() < 2 || distance == T::zero() {
        return Ok(Vec::new());
    }
    // F grows as the sixth power of the coordinates (under- or overflow beyond about
    // 1e±50): the curve and the distance are divided by a power of four near their size
    // (exact), so the cusps are those of the unscaled problem, their points scaled back.
    let largest = curve
        .control_points()
        .iter()
        .fold(distance.abs(), |m, p| m.max(p.amax()));
    let scale: T = cast(spline_core::power_of_two_scale(to_f64(largest)));
    if scale != T::one() {
        let mut scaled = curve.clone();
        for p in scaled.control_points_mut() {
            *p /= scale;
        }
        let mut cusps = offset_cusps(&scaled, distance / scale, accuracy)?;
        for cusp in &mut cusps {
            cusp.point *= scale;
        }
        return Ok(cusps);
    }
    let invariants = PlanarInvariants::new(curve.knots())?;
    let points = curve.control_points();
    let h1 = invariants.invariant_value(Invariant::H1, points, Form::BSpline)?;
    let h4 = invariants.invariant_value(Invariant::H4, points, Form::BSpline)?;
    let h1_cubed = product(&h1, &square(&h1)?.value)?;
    let f = linear_combination(
        distance * distance,
        &square(&h4)?.value,
        -T::one(),
        &h1_cubed,
    )?;
    let (a, b) = curve.domain();
    // F has a wide range of magnitudes (h1³ beside d² h4²), so rounding can move, merge or
    // invent its zeros: each is polished on the well-conditioned φ(u) = d h4 − h1^{3/2} by
    // Newton's method, and the sign changes of φ on a grid of every piece are added.
    let mut found = Vec::new();
    let mut windows: Vec<(T, T, usize)> = Vec::new();
    for zero in zeros(&f, accuracy)? {
        if let Some(u) = polish(curve, distance, zero.at(), (a, b))? {
            found.push(u);
        }
        // Where rounding blurs F, its zero is an interval or a point between close roots:
        // the sign changes of φ nearby are searched on a fine grid.
        let margin = (b - a) * cast(1e-3);
        windows.push((
            (zero.start - margin).max(a),
            (zero.end + margin).min(b),
            FINE_GRID,
        ));
    }
    let breaks = curve.breaks();
    windows.extend(breaks.windows(2).map(|w| (w[0], w[1], GRID)));
    for (lo, hi, cells) in windows {
        let grid: Vec<T> = (0..=cells)
            // The last point is `hi` itself: `lo + (hi − lo)` can round one step past it.
            .map(|k| {
                if k == cells {
                    hi
                } else {
                    lo + (hi - lo) * from_count::<T>(k) / from_count::<T>(cells)
                }
            })
            .collect();
        let values = grid
            .iter()
            .map(|&u| phi(curve, distance, u))
            .collect::<Result<Vec<T>>>()?;
        for k in 0..cells {
            if values[k] * values[k + 1] < T::zero() {
                let u = bisect(curve, distance, (grid[k], grid[k + 1]), values[k], accuracy)?;
                if let Some(u) = polish(curve, distance, u, (a, b))? {
                    found.push(u);
                }
            }
        }
    }
    found.sort_by(|x, y| x.partial_cmp(y).unwrap_or(std::cmp::Ordering::Equal));
    found.dedup_by(|y, x| (*y - *x).abs() <= (b - a) * cast(1e-9));
    let mut out = Vec::with_capacity(found.len());
    for u in found {
        let d = curve.derivatives(u, 1)?;
        let normal = Vector2::new(-d[1].y, d[1].x) / d[1].norm();
        // Whether κ d − 1 changes sign, from φ beside the cusp.
        let delta = (b - a) * cast(1e-7);
        let sign_change = u - delta > a
            && u + delta < b
            && phi(curve, distance, u - delta)? * phi(curve, distance, u + delta)? < T::zero();
        out.push(OffsetCusp {
            u,
            point: d[0] + normal * distance,
            sign_change,
        });
    }
    Ok(out)
}

/// Newton's method on $\varphi(u) = d\,h_4 - h_1^{3/2}$ from `u` (inside the domain): the
/// parameter where $\kappa d = 1$ to rounding, or `None` if there is none nearby (a zero of
/// `F` made by rounding, or one with $\kappa d = -1$).
fn polish<T: Scalar>(
    curve: &BSpline<T, Vector2<T>>,
    distance: T,
    mut u: T,
    (a, b): (T, T),
) -> Result<Option<T>> {
    let start = u;
    for _ in 0..50 {
        let d = curve.derivatives(u, 3)?;
        let h1 = d[1].norm_squared();
        let root = h1.sqrt();
        let phi = distance * spline_geom::wedge(&d[1], &d[2]) - h1 * root;
        let dphi =
            distance * spline_geom::wedge(&d[1], &d[3]) - cast::<T>(3.0) * root * d[1].dot(&d[2]);
        if !(dphi.abs() > T::zero()) {
            break;
        }
        let step = phi / dphi;
        u = (u - step).max(a).min(b);
        if step.abs() <= T::default_epsilon() * (T::one() + u.abs()) {
            break;
        }
    }
    let d = curve.derivatives(u, 2)?;
    let speed = d[1].norm();
    let kappa_d = distance * spline_geom::wedge(&d[1], &d[2]) / (speed * speed * speed);
    let near = (u - start).abs() <= (b - a) * cast(1e-3);
    Ok(((kappa_d - T::one()).abs() <= cast(CUSP_CHECK) && near).then_some(u))
}

/// $\varphi(u) = d\,h_4 - h_1^{3/2}$, of the sign of $\kappa d - 1$.
fn phi<T: Scalar>(curve: &BSpline<T, Vector2<T>>, distance: T, u: T) -> Result<T> {
    let d = curve.derivatives(u, 2)?;
    let h1 = d[1].norm_squared();
    Ok(distance * spline_geom::wedge(&d[1], &d[2]) - h1 * h1.sqrt())
}

/// Bisection of φ on `(lo, hi)` (φ(lo) of sign `at_lo`, opposite at `hi`) to `accuracy`.
fn bisect<T: Scalar>(
    curve: &BSpline<T, Vector2<T>>,
    distance: T,
    (mut lo, mut hi): (T, T),
    at_lo: T,
    accuracy: T,
) -> Result<T> {
    for _ in 0..200 {
        let mid = (lo + hi) * cast(0.5);
        if hi - lo <= accuracy || !(mid > lo && mid < hi) {
            break;
        }
        if phi(curve, distance, mid)? * at_lo > T::zero() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok((lo + hi) * cast(0.5))
}
