//! Surfaces fitted to scattered points or to the vertices of a triangle mesh: parameters by
//! projection on a base surface, least squares with a smoothing term, parameter correction
//! by closest points, deviations both ways.

use crate::MAX_CORRECTION_ITERATIONS;
use crate::report::Deviation;
use crate::surface::approximate_surface_scattered;
use crate::surface_project::{SurfaceProjector, closest_local};
use nalgebra::{Matrix3, Vector3};
use spline_core::{Error, ErrorKind, KnotVector, Result, Scalar, cast, from_count, to_f64};
use spline_geom::{ParamSurface, Surface};

/// The largest least-squares system of a scattered fit: unknowns × half-bandwidth of the
/// banded normal equations (about this many numbers are stored).
pub const MAX_SCATTERED_SYSTEM: usize = 50_000_000;

/// Samples per knot span and direction of the surface → data deviation.
const SAMPLES_PER_SPAN: usize = 6;

/// Options of [`fit_scattered`].
#[derive(Clone, Debug, PartialEq)]
pub struct ScatteredOptions<T> {
    /// Degrees `(p, q)` (default bicubic).
    pub degrees: (usize, usize),
    /// Control points `(n_u, n_v)`, on clamped uniform knots.
    pub control_points: (usize, usize),
    /// The weight λ of the thin-plate term $\lambda \iint \lVert S_{uu} \rVert^2 +
    /// 2 \lVert S_{uv} \rVert^2 + \lVert S_{vv} \rVert^2$ (default 0; needed where the data
    /// leave control points undetermined).
    pub smoothing: T,
    /// Parameter-correction sweeps: each moves every point's parameters to its closest
    /// point on the current surface and fits again (default 5).
    pub corrections: usize,
}

impl<T: Scalar> Default for ScatteredOptions<T> {
    fn default() -> Self {
        Self {
            degrees: (3, 3),
            control_points: (8, 8),
            smoothing: T::zero(),
            corrections: 5,
        }
    }
}

/// A surface fitted to scattered data, with its deviations both ways.
#[derive(Clone, Debug, PartialEq)]
pub struct ScatteredFit<T> {
    /// The surface.
    pub surface: Surface<T, Vector3<T>>,
    /// The parameters of the data points after correction.
    pub params: Vec<(T, T)>,
    /// Data → surface: each point's distance to its closest point on the surface (a global
    /// search, [`SurfaceProjector`]).
    pub to_surface: Deviation<T>,
    /// Surface → data: the largest distance from a dense sampling of the surface to the
    /// data — the nearest triangle for a mesh, the nearest point for a point cloud (then it
    /// includes half the spacing of the data).
    pub to_data: T,
    /// The correction sweeps done (they stop early when the RMS no longer falls).
    pub corrections: usize,
}

fn bounds_of<T: Scalar>(coords: &[(T, T)]) -> ((T, T), (T, T)) {
    let (mut lo, mut hi) = (coords[0], coords[0]);
    for &(x, y) in coords {
        lo = (lo.0.min(x), lo.1.min(y));
        hi = (hi.0.max(x), hi.1.max(y));
    }
    (lo, hi)
}

/// Parameters of the points by orthogonal projection on their least-squares plane (the
/// eigenvector of the smallest eigenvalue of the covariance is its normal), in the axes of
/// their smallest bounding rectangle, mapped onto `[0, 1]²` by that rectangle.
fn plane_params<T: Scalar>(points: &[Vector3<T>]) -> Result<Vec<(T, T)>> {
    let n: T = from_count(points.len());
    let mean = points.iter().fold(Vector3::zeros(), |a, p| a + p) / n;
    let mut cov = Matrix3::zeros();
    for p in points {
        let d = p - mean;
        cov += d * d.transpose();
    }
    let eig = cov.symmetric_eigen();
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| to_f64(eig.eigenvalues[b]).total_cmp(&to_f64(eig.eigenvalues[a])));
    let (e1, e2) = (
        eig.eigenvectors.column(order[0]).into_owned(),
        eig.eigenvectors.column(order[1]).into_owned(),
    );
    let coords: Vec<(T, T)> = points
        .iter()
        .map(|p| ((p - mean).dot(&e1), (p - mean).dot(&e2)))
        .collect();
    // In the plane, the axes of the smallest bounding rectangle (tried every half degree):
    // the domain [0, 1]² then covers the data with the least empty area.
    let rotated = |angle: f64| -> Vec<(T, T)> {
        let (c, s) = (cast::<T>(angle.cos()), cast::<T>(angle.sin()));
        coords
            .iter()
            .map(|&(x, y)| (c * x + s * y, c * y - s * x))
            .collect()
    };
    let area = |angle: f64| {
        let (lo, hi) = bounds_of(&rotated(angle));
        to_f64((hi.0 - lo.0) * (hi.1 - lo.1))
    };
    let best = (0..180)
        .map(|k| f64::from(k) * std::f64::consts::PI / 360.0)
        .min_by(|&a, &b| area(a).total_cmp(&area(b)))
        .unwrap_or(0.0);
    let coords = rotated(best);
    let (lo, hi) = bounds_of(&coords);
    if !(hi.0 > lo.0 && hi.1 > lo.1) {
        return Err(Error::new(
            ErrorKind::DegenerateGeometry,
            "the points lie on a line: no surface parametrisation",
        ));
    }
    Ok(coords
        .into_iter()
        .map(|(x, y)| ((x - lo.0) / (hi.0 - lo.0), (y - lo.1) / (hi.1 - lo.1)))
        .collect())
}

/// Fits a B-spline surface to scattered points $Q_k$ (or the vertices of a triangle mesh):
///
/// 1. parameters by projection: on `base` (any surface, its closest points,
///    [`SurfaceProjector`]; the fit lives on the base's domain) or, by default, on the
///    points' least-squares plane (on `[0, 1]²`);
/// 2. least squares on clamped uniform knots with the thin-plate smoothing term
///    ([`crate::approximate_surface_scattered`]);
/// 3. parameter correction: each point's parameters move to its closest point on the
///    fitted surface (a Newton iteration from the current ones, [`closest_local`]), and the
///    surface is fitted again, `options.corrections` times or until the RMS stops falling;
/// 4. deviations both ways ([`ScatteredFit`]): every data point's global closest point,
///    and the surface sampled densely against the data (the nearest triangle of `triangles`
///    when given, else the nearest point).
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] with fewer points than control points and no smoothing;
/// [`ErrorKind::InvalidArgument`] for too many correction sweeps
/// ([`MAX_CORRECTION_ITERATIONS`]), control points below the order, or a system above
/// [`MAX_SCATTERED_SYSTEM`]; [`ErrorKind::IndexOutOfRange`] for a triangle naming a missing
/// vertex; [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] for points on a
/// line; the errors of [`crate::approximate_surface_scattered`] (a control point the data do
/// not determine: add smoothing).
pub fn fit_scattered<T: Scalar, S: ParamSurface<T, Point = Vector3<T>>>(
    points: &[Vector3<T>],
    triangles: Option<&[[usize; 3]]>,
    base: Option<&S>,
    options: &ScatteredOptions<T>,
) -> Result<ScatteredFit<T>> {
    let (p, q) = options.degrees;
    let (nu, nv) = options.control_points;
    crate::params::check_degree(p)?;
    crate::params::check_degree(q)?;
    if nu <= p || nv <= q {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{nu} × {nv} control points: degrees ({p}, {q}) need at least {} × {}",
                p + 1,
                q + 1
            ),
        )
        .with_counts(
            if nu <= p { p + 1 } else { q + 1 },
            if nu <= p { nu } else { nv },
        ));
    }
    let system = nu
        .checked_mul(nv)
        .and_then(|n| n.checked_mul(p * nv + q + 1))
        .filter(|&s| s <= MAX_SCATTERED_SYSTEM);
    if system.is_none() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{nu} × {nv} control points make a least-squares system above {MAX_SCATTERED_SYSTEM} numbers"
            ),
        ));
    }
    if options.corrections > MAX_CORRECTION_ITERATIONS {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{} correction sweeps: at most {MAX_CORRECTION_ITERATIONS}",
                options.corrections
            ),
        )
        .with_counts(MAX_CORRECTION_ITERATIONS, options.corrections));
    }
    if points.len() < nu * nv && !(options.smoothing > T::zero()) {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "{} points for {nu} × {nv} control points: give more points or a smoothing weight",
                points.len()
            ),
        ));
    }
    if let Some(k) = points
        .iter()
        .position(|x| !x.iter().all(|c| nalgebra::ComplexField::is_finite(c)))
    {
        return Err(Error::non_finite(format_args!("data point {k}")));
    }
    if let Some(tris) = triangles {
        if let Some(t) = tris
            .iter()
            .position(|t| t.iter().any(|&i| i >= points.len()))
        {
            return Err(Error::new(
                ErrorKind::IndexOutOfRange,
                format!(
                    "triangle {t} names vertex {:?} of {} vertices",
                    tris[t],
                    points.len()
                ),
            ));
        }
    }
    let (mut params, ((a, b), (c, d))) = match base {
        Some(s) => {
            let projector = SurfaceProjector::new(s)?;
            let params = projector
                .closest_many(points)?
                .into_iter()
                .map(|h| (h.u, h.v))
                .collect();
            (params, s.domain())
        }
        None => (
            plane_params(points)?,
            ((T::zero(), T::one()), (T::zero(), T::one())),
        ),
    };
    let ku = KnotVector::clamped_uniform(p, nu, a, b)?;
    let kv = KnotVector::clamped_uniform(q, nv, c, d)?;
    let mut fit = approximate_surface_scattered(&params, points, &ku, &kv, options.smoothing)?;
    let mut done = 0;
    for _ in 0..options.corrections {
        let moved: Vec<(T, T)> = points
            .iter()
            .zip(&params)
            .map(|(x, &uv)| closest_local(&fit.surface, *x, uv).map(|h| (h.u, h.v)))
            .collect::<Result<_>>()?;
        let next = approximate_surface_scattered(&moved, points, &ku, &kv, options.smoothing)?;
        done += 1;
        let better = next.deviation.rms < fit.deviation.rms;
        if better {
            (fit, params) = (next, moved);
        }
        if !better || next_converged(&fit.deviation) {
            break;
        }
    }
    let surface = fit.surface;
    let projector = SurfaceProjector::new(&surface)?;
    let to_surface = Deviation::from_distances(
        projector
            .closest_many(points)?
            .into_iter()
            .map(|h| h.distance)
            .collect(),
    );
    let to_data = surface_to_data(&surface, points, triangles)?;
    Ok(ScatteredFit {
        surface,
        params,
        to_surface,
        to_data,
        corrections: done,
    })
}

fn next_converged<T: Scalar>(d: &Deviation<T>) -> bool {
    !(d.max > T::zero())
}

/// The largest distance from samples of the surface to the data.
fn surface_to_data<T: Scalar>(
    surface: &Surface<T, Vector3<T>>,
    points: &[Vector3<T>],
    triangles: Option<&[[usize; 3]]>,
) -> Result<T> {
    let sample = |breaks: Vec<T>| -> Vec<T> {
        let mut out = Vec::new();
        for w in breaks.windows(2) {
            for k in 0..SAMPLES_PER_SPAN {
                out.push(
                    w[0] + (w[1] - w[0]) * from_count::<T>(k) / from_count::<T>(SAMPLES_PER_SPAN),
                );
            }
        }
        out.push(breaks[breaks.len() - 1]);
        out
    };
    let us = sample(surface.knots_u().domain_breaks());
    let vs = sample(surface.knots_v().domain_breaks());
    let grid = surface.eval_grid(&us, &vs)?;
    let mut worst = T::zero();
    for x in &grid {
        let d = match triangles {
            Some(tris) if !tris.is_empty() => tris
                .iter()
                .map(|t| triangle_distance(x, &points[t[0]], &points[t[1]], &points[t[2]]))
                .fold(T::max_value().unwrap_or_else(|| cast(f64::MAX)), |a, b| {
                    a.min(b)
                }),
            _ => points
                .iter()
                .map(|p| (p - x).norm())
                .fold(T::max_value().unwrap_or_else(|| cast(f64::MAX)), |a, b| {
                    a.min(b)
                }),
        };
        worst = worst.max(d);
    }
    Ok(worst)
}

/// The distance from `x` to the triangle `abc` (Ericson, *Real-Time Collision Detection*
/// §5.1.5: the Voronoi regions of the vertices, edges and face).
fn triangle_distance<T: Scalar>(
    x: &Vector3<T>,
    a: &Vector3<T>,
    b: &Vector3<T>,
    c: &Vector3<T>,
) -> T {
    let (ab, ac, ap) = (b - a, c - a, x - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= T::zero() && d2 <= T::zero() {
        return ap.norm();
    }
    let bp = x - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= T::zero() && d4 <= d3 {
        return bp.norm();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= T::zero() && d1 >= T::zero() && d3 <= T::zero() {
        let v = d1 / (d1 - d3);
        return (x - (a + ab * v)).norm();
    }
    let cp = x - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= T::zero() && d5 <= d6 {
        return cp.norm();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= T::zero() && d2 >= T::zero() && d6 <= T::zero() {
        let w = d2 / (d2 - d6);
        return (x - (a + ac * w)).norm();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= T::zero() && (d4 - d3) >= T::zero() && (d5 - d6) >= T::zero() {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (x - (b + (c - b) * w)).norm();
    }
    let denom = va + vb + vc;
    if !(denom > T::zero()) {
        // A degenerate triangle: its edges.
        return [(a, b), (b, c), (a, c)]
            .iter()
            .map(|(p, q)| {
                let e = *q - *p;
                let l = e.norm_squared();
                let t = if l > T::zero() {
                    ((x - *p).dot(&e) / l).max(T::zero()).min(T::one())
                } else {
                    T::zero()
                };
                (x - (*p + e * t)).norm()
            })
            .fold(T::max_value().unwrap_or_else(|| cast(f64::MAX)), |a, b| {
                a.min(b)
            });
    }
    let (v, w) = (vb / denom, vc / denom);
    (x - (a + ab * v + ac * w)).norm()
}
