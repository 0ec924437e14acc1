//! Offset surfaces $O(u, v) = S(u, v) + d\,n(u, v)$: exact for planes and spheres (an affine
//! map of the control net), otherwise a B-spline within a tolerance
//! (`spline_fit::AdaptiveSurfaceApproximation`), refused where the offset folds.

use super::options::OffsetOptions;
use super::revolution::Revolution;
use nalgebra::{Matrix4, Vector3, Vector4};
use spline_core::{Error, ErrorKind, Result, Scalar, cast, from_count, to_f64};
use spline_fit::AdaptiveSurfaceApproximation;
use spline_geom::{NurbsSurface, ParamSurface, SpatialSurface, Surface};

/// Relative accuracy of the plane and sphere checks (as for circular arcs).
const SHAPE_CHECK: f64 = 1e-12;

/// The offset surface: an approximating B-spline surface, or the exact surface where there is
/// one (a plane translated, a sphere scaled about its centre), of the same kind as the input.
#[derive(Clone, Debug)]
pub enum SurfaceOffsetShape<T: Scalar> {
    /// A B-spline surface (within the tolerance, or exact for a polynomial plane or sphere).
    Polynomial(Surface<T, Vector3<T>>),
    /// A NURBS surface: the offset of a rational plane or sphere (exact), or of a surface of
    /// revolution (its meridian's offset revolved: exact for a line or a circular arc,
    /// otherwise within the tolerance).
    Rational(NurbsSurface<T, 3>),
}

/// The kind of exact offset found, if any.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExactOffset {
    /// Not exact: an approximation within the tolerance.
    Approximate,
    /// A plane, translated by $d\,n$.
    Plane,
    /// A piece of a sphere, scaled about its centre to radius $r + d$ (outward normal).
    Sphere,
    /// A surface of revolution whose meridian is a line or a circular arc (a cylinder, a
    /// cone, a torus): the revolution of the meridian's offset in its plane.
    Revolution,
}

/// The offset of a surface and how close it is.
#[derive(Clone, Debug)]
pub struct SurfaceOffset<T: Scalar> {
    /// The offset surface (on the domain of the original; the same parameters).
    pub surface: SurfaceOffsetShape<T>,
    /// Whether the offset is exact, and of which shape.
    pub exact: ExactOffset,
    /// The largest distance between `surface` and the exact offset at the check points (zero
    /// for an exact offset).
    pub max_error: T,
}

/// Surfaces in space whose offsets [`offset_surface`] computes (B-spline and NURBS).
pub trait SurfaceOffsetSource<T: Scalar>: ParamSurface<T, Point = Vector3<T>> {
    /// The degrees `(p, q)`.
    fn offset_degrees(&self) -> (usize, usize);

    /// The Cartesian control points.
    fn cartesian_net(&self) -> Vec<Vector3<T>>;

    /// The knot vectors in `u` and in `v` (clamped or not; only the interior ones are used).
    fn offset_knots(&self) -> (Vec<T>, Vec<T>);

    /// The surface under an affine map of space (exact for both kinds).
    fn affine_image(&self, map: impl Fn(&Vector3<T>) -> Vector3<T>) -> SurfaceOffsetShape<T>;

    /// The surface as a NURBS surface, if it is one (surfaces of revolution are).
    fn as_nurbs(&self) -> Option<&NurbsSurface<T, 3>>;
}

impl<T: Scalar> SurfaceOffsetSource<T> for Surface<T, Vector3<T>> {
    fn offset_degrees(&self) -> (usize, usize) {
        (self.knots_u().degree(), self.knots_v().degree())
    }

    fn cartesian_net(&self) -> Vec<Vector3<T>> {
        self.control_points().to_vec()
    }

    fn offset_knots(&self) -> (Vec<T>, Vec<T>) {
        (
            self.knots_u().knots().to_vec(),
            self.knots_v().knots().to_vec(),
        )
    }

    fn affine_image(&self, map: impl Fn(&Vector3<T>) -> Vector3<T>) -> SurfaceOffsetShape<T> {
        SurfaceOffsetShape::Polynomial(self.map_control_points(map))
    }

    fn as_nurbs(&self) -> Option<&NurbsSurface<T, 3>> {
        None
    }
}

impl<T: Scalar> SurfaceOffsetSource<T> for NurbsSurface<T, 3> {
    fn offset_degrees(&self) -> (usize, usize) {
        self.degrees()
    }

    fn cartesian_net(&self) -> Vec<Vector3<T>> {
        let (nu, nv) = self.net_size();
        (0..nu)
            .flat_map(|i| (0..nv).map(move |j| (i, j)))
            .map(|(i, j)| self.control_point(i, j))
            .collect()
    }

    fn offset_knots(&self) -> (Vec<T>, Vec<T>) {
        (
            self.knots_u().knots().to_vec(),
            self.knots_v().knots().to_vec(),
        )
    }

    fn affine_image(&self, map: impl Fn(&Vector3<T>) -> Vector3<T>) -> SurfaceOffsetShape<T> {
        SurfaceOffsetShape::Rational(self.map_control_points(map))
    }

    fn as_nurbs(&self) -> Option<&NurbsSurface<T, 3>> {
        Some(self)
    }
}

/// The offset $O(u, v) = S(u, v) + d\,n(u, v)$ of a surface in space at signed distance
/// `distance` along the unit normal $n = S_u \times S_v / \lVert S_u \times S_v \rVert$
/// (Open CASCADE's `Geom_OffsetSurface`), on the same parameters.
///
/// - A plane (control points in one plane, one normal) is translated by $d\,n$: exact.
/// - A piece of a sphere is scaled about its centre by $1 - d H$ (radius $r + d$ for the
///   outward normal): exact. It is recognised on the `(4 p + 5) × (4 q + 5)` grid points of
///   every patch: the sphere fitted to them (least squares) passes through every one to
///   $16 \cdot 10^{-12}$ of the piece's size (the diagonal of their bounding box, or the
///   radius if smaller) plus the rounding of their position ($64 ε$ times the largest
///   coordinate of the net), and the normal is $\pm (S - c) / r$ with one sign at every
///   regular one. On a patch, $w^2 (\lVert S - c \rVert^2 - r^2)$ is a polynomial of
///   degrees `(2 p, 2 q)`: zero on the grid, it is zero everywhere. Nothing in the check is
///   absolute: the same sphere is recognised at every size and wherever it is.
/// - A NURBS surface of revolution (degree 2 around the axis, its control net a meridian
///   revolved, like the output of `NurbsSurface::revolution` or `NurbsSurface::torus`) has as
///   offset the revolution of its meridian's planar offset, on the same parameters: exact
///   for a straight meridian (cylinders, cones: its control points moved along its normal)
///   and for a circular one (tori: [`crate::offset_planar_curve`]'s concentric arc),
///   otherwise the meridian's offset within the tolerance, revolved exactly.
/// - Otherwise the offset folds where $1 - d\,\kappa_i \le 0$ for a principal curvature
///   $\kappa_i$ (a principal radius of curvature on the normal's side shorter than $|d|$):
///   refused, with the place; else it is approximated within `options.tolerance` by a
///   B-spline surface of degrees `(options.degree, options.degree)`, starting from the
///   surface's breaks. At singular points ($S_u \times S_v = 0$, e.g. a collapsed edge), the
///   normal is its limit from inside the domain, and no curvature is taken there. Singular
///   means $\lVert S_u \times S_v \rVert \le 64 ε (1 + M / E) (\lVert S_u \rVert^2 +
///   \lVert S_v \rVert^2)$, $M$ the largest coordinate of the control net and $E$ the
///   diagonal of its bounding box: the derivatives carry the rounding of the position (about
///   $ε M$ per extent $E$), so below this $S_u \times S_v$ is rounding, as at the pole of a
///   sphere away from the origin, which has no normal there rather than a radius of
///   curvature of $10^{-15}$.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsSurface;
/// use spline_shape::{ExactOffset, OffsetOptions, SurfaceOffsetShape, offset_surface};
/// let sphere = NurbsSurface::sphere(Vector3::new(1.0f64, 2.0, 3.0), 2.0)?;
/// let offset = offset_surface(&sphere, 0.5, &OffsetOptions::default())?;
/// assert_eq!(offset.exact, ExactOffset::Sphere);
/// let SurfaceOffsetShape::Rational(larger) = offset.surface else { unreachable!() };
/// let p = larger.eval(0.3, 0.8)?;
/// assert!(((p - Vector3::new(1.0, 2.0, 3.0)).norm() - 2.5).abs() < 1e-13);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::NonFinite`] for a non-finite distance; [`ErrorKind::DegenerateGeometry`]
/// where the offset folds, where a sphere's offset collapses to its centre, or where the
/// surface has no normal even as a limit; [`ErrorKind::InvalidTolerance`],
/// [`ErrorKind::ToleranceExceeded`] and the other errors of
/// `spline_fit::AdaptiveSurfaceApproximation`.
pub fn offset_surface<T: Scalar, S: SurfaceOffsetSource<T>>(
    surface: &S,
    distance: T,
    options: &OffsetOptions<T>,
) -> Result<SurfaceOffset<T>> {
    if !distance.is_finite() {
        return Err(Error::non_finite("the offset distance"));
    }
    // Checked whether the offset turns out exact or not: a bad setting is an error either way.
    if !(options.tolerance > T::zero() && options.tolerance.is_finite()) {
        return Err(Error::invalid_tolerance(
            "offset tolerance",
            "positive and finite",
            to_f64(options.tolerance),
        ));
    }
    let exact = |shape, kind| SurfaceOffset {
        surface: shape,
        exact: kind,
        max_error: T::zero(),
    };
    if distance == T::zero() {
        return Ok(exact(surface.affine_image(|p| *p), ExactOffset::Plane));
    }
    let samples = Samples::of(surface)?;
    if let Some(normal) = samples.plane() {
        let shift = normal * distance;
        return Ok(exact(
            surface.affine_image(|p| p + shift),
            ExactOffset::Plane,
        ));
    }
    if let Some((centre, mean)) = samples.sphere() {
        let factor = T::one() - distance * mean;
        if factor.abs() <= cast::<T>(SHAPE_CHECK) {
            return Err(Error::new(
                ErrorKind::DegenerateGeometry,
                format!(
                    "the offset at distance {} of a sphere of radius {} collapses to its centre",
                    to_f64(distance),
                    to_f64(T::one() / mean.abs())
                ),
            )
            .with_value(to_f64(distance)));
        }
        return Ok(exact(
            surface.affine_image(|p| centre + (p - centre) * factor),
            ExactOffset::Sphere,
        ));
    }
    samples.check_no_fold(distance)?;
    if let Some(nurbs) = surface.as_nurbs() {
        if let Some(revolution) = Revolution::of(nurbs) {
            if let Some(found) = revolution.offset(nurbs, distance, options)? {
                let kind = if found.max_error == T::zero() {
                    ExactOffset::Revolution
                } else {
                    ExactOffset::Approximate
                };
                return Ok(SurfaceOffset {
                    surface: SurfaceOffsetShape::Rational(found.surface),
                    exact: kind,
                    max_error: found.max_error,
                });
            }
        }
    }
    let (p, q) = surface.offset_degrees();
    let degree = options.degree.max(1);
    let (knots_u, knots_v) = surface.offset_knots();
    // At a knot of multiplicity m the surface is C^{p−m}, its normal C^{p−m−1}: the fit's
    // knot there has the multiplicity that allows as little continuity.
    let interior = |knots: &[T], p: usize| {
        let mut out = Vec::new();
        let mut k = p + 1;
        while k + p + 1 < knots.len() {
            let m = knots[k..knots.len() - p - 1]
                .iter()
                .take_while(|&&x| x == knots[k])
                .count();
            let times = (degree + m + 1).saturating_sub(p).clamp(1, degree);
            if knots[k] > knots[p] && knots[k] < knots[knots.len() - p - 1] {
                out.extend(std::iter::repeat_n(knots[k], times));
            }
            k += m;
        }
        out
    };
    let fit = AdaptiveSurfaceApproximation::new((degree, degree), options.tolerance)
        .breaks(&interior(&knots_u, p), &interior(&knots_v, q))
        .fit(surface.domain(), |us, vs| {
            let mut out = Vec::with_capacity(us.len() * vs.len());
            for &u in us {
                for &v in vs {
                    out.push(offset_point(surface, &samples.rounding, u, v, distance)?);
                }
            }
            Ok(out)
        })
        .map_err(|e| {
            e.context(format_args!(
                "offset of a surface of degrees ({p}, {q}) at distance {}",
                to_f64(distance)
            ))
        })?;
    Ok(SurfaceOffset {
        surface: SurfaceOffsetShape::Polynomial(fit.surface),
        exact: ExactOffset::Approximate,
        max_error: fit.max_error,
    })
}

/// The rounding that the derivatives of a surface carry: its position's (see
/// [`offset_surface`]: $S_u \times S_v$ below `64 ε (1 + M / E) (|S_u|² + |S_v|²)` is
/// rounding, and the point is singular).
#[derive(Clone, Copy)]
struct Rounding<T> {
    /// `64 ε (1 + M / E)`, or the largest number for a net of no extent (every point
    /// singular).
    floor: T,
}

impl<T: Scalar> Rounding<T> {
    /// The rounding of a surface with these Cartesian control points.
    fn of(net: &[Vector3<T>]) -> Self {
        let mut lo = net.first().copied().unwrap_or_else(Vector3::zeros);
        let mut hi = lo;
        for p in net {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        let largest = lo.amax().max(hi.amax());
        let extent = (hi - lo).norm();
        let eps = T::default_epsilon() * cast::<T>(64.0);
        let floor = if extent > T::zero() && extent.is_finite() {
            eps * (T::one() + largest / extent)
        } else {
            T::max_value().unwrap_or_else(T::one)
        };
        Self { floor }
    }

    /// Whether $S_u \times S_v$ is no more than rounding (a singular point).
    fn singular(&self, du: &Vector3<T>, dv: &Vector3<T>) -> bool {
        !(du.cross(dv).norm() > self.floor * (du.norm_squared() + dv.norm_squared()))
    }
}

/// The point and the unit normal at `(u, v)`, or `None` for the normal at a singular point.
fn normal_at<T: Scalar, S: ParamSurface<T, Point = Vector3<T>>>(
    surface: &S,
    rounding: &Rounding<T>,
    u: T,
    v: T,
) -> Result<(Vector3<T>, Option<Vector3<T>>)> {
    let mut d = [Vector3::zeros(); 4];
    surface.derivatives_into(u, v, 1, &mut d)?;
    let (du, dv) = (d[2], d[1]);
    let normal = (!rounding.singular(&du, &dv)).then(|| du.cross(&dv).normalize());
    Ok((d[0], normal))
}

/// The point of the offset at `(u, v)`; at a singular point, with the normal's limit from
/// inside the domain, along the segment towards the domain's centre: towards $(a, b)$,
/// $S_u \times S_v$ grows as $t\,[S_u \times (a S_{uv} + b S_{vv}) + (a S_{uu} + b S_{uv})
/// \times S_v]$, whose direction is the limit (at a pole, $S_u \times S_{uv}$), free of the
/// rounding that stepping off the point would divide by; where that vanishes too, the
/// normal a little way towards the centre.
fn offset_point<T: Scalar, S: ParamSurface<T, Point = Vector3<T>>>(
    surface: &S,
    rounding: &Rounding<T>,
    u: T,
    v: T,
    distance: T,
) -> Result<Vector3<T>> {
    let (point, normal) = normal_at(surface, rounding, u, v)?;
    if let Some(n) = normal {
        return Ok(point + n * distance);
    }
    let ((a, b), (c, d)) = surface.domain();
    let half = cast::<T>(0.5);
    let (to_u, to_v) = ((a + b) * half - u, (c + d) * half - v);
    let mut p = [Vector3::zeros(); 9];
    surface.derivatives_into(u, v, 2, &mut p)?;
    let (su, sv, suu, suv, svv) = (p[3], p[1], p[6], p[4], p[2]);
    let growth = su.cross(&(suv * to_u + svv * to_v)) + (suu * to_u + suv * to_v).cross(&sv);
    let size = (su.norm() + sv.norm())
        * (suu.norm() * to_u.abs()
            + suv.norm() * (to_u.abs() + to_v.abs())
            + svv.norm() * to_v.abs());
    if growth.norm() > rounding.floor * size {
        return Ok(point + growth.normalize() * distance);
    }
    for step in [1e-10, 1e-8, 1e-6] {
        let t = cast::<T>(step);
        let (_, nearby) = normal_at(surface, rounding, u + to_u * t, v + to_v * t)?;
        if let Some(n) = nearby {
            return Ok(point + n * distance);
        }
    }
    Err(Error::new(
        ErrorKind::DegenerateGeometry,
        format!(
            "the surface has no normal at ({}, {}), even as a limit from inside the domain",
            to_f64(u),
            to_f64(v)
        ),
    ))
}

/// The point, the normal and the principal curvatures at a regular point `(u, v)`.
#[derive(Clone, Copy)]
struct Sample<T: Scalar> {
    u: T,
    v: T,
    point: Vector3<T>,
    normal: Vector3<T>,
    k1: T,
    k2: T,
}

/// Local properties on a grid of `4 (p + 1) × 4 (q + 1)` points per patch (singular points
/// left out of `regular`, kept in `points`).
struct Samples<T: Scalar> {
    regular: Vec<Sample<T>>,
    /// Every grid point, singular or not (`(4 p + 5) × (4 q + 5)` on every patch).
    points: Vec<Vector3<T>>,
    /// The largest coordinate of the control net (the size for relative checks).
    size: T,
    net: Vec<Vector3<T>>,
    rounding: Rounding<T>,
}

impl<T: Scalar> Samples<T> {
    fn of<S: SurfaceOffsetSource<T>>(surface: &S) -> Result<Self> {
        let (p, q) = surface.offset_degrees();
        let (breaks_u, breaks_v) = surface.breaks();
        let grid = |breaks: &[T], per: usize| {
            let mut params = Vec::with_capacity((breaks.len() - 1) * per + 1);
            for w in breaks.windows(2) {
                for j in 0..per {
                    params.push(w[0] + (w[1] - w[0]) * from_count::<T>(j) / from_count::<T>(per));
                }
            }
            params.push(breaks[breaks.len() - 1]);
            params
        };
        let net = surface.cartesian_net();
        let rounding = Rounding::of(&net);
        let (us, vs) = (grid(&breaks_u, 4 * (p + 1)), grid(&breaks_v, 4 * (q + 1)));
        let mut regular = Vec::new();
        let mut points = Vec::with_capacity(us.len() * vs.len());
        for &u in &us {
            for &v in &vs {
                match surface.local_properties(u, v) {
                    Ok(l) if !rounding.singular(&l.du, &l.dv) => {
                        points.push(l.point);
                        regular.push(Sample {
                            u,
                            v,
                            point: l.point,
                            normal: l.normal,
                            k1: l.max_curvature,
                            k2: l.min_curvature,
                        });
                    }
                    Ok(l) => points.push(l.point),
                    Err(e) if e.kind() == ErrorKind::DegenerateGeometry => {
                        points.push(surface.eval(u, v)?);
                    }
                    Err(e) => return Err(e),
                }
            }
        }
        if regular.is_empty() {
            return Err(Error::new(
                ErrorKind::DegenerateGeometry,
                "the surface has no normal anywhere (S_u × S_v vanishes at every sample): it has no offset",
            ));
        }
        let size = net.iter().fold(T::zero(), |m, p| m.max(p.amax()));
        Ok(Self {
            regular,
            points,
            size,
            net,
            rounding,
        })
    }

    /// The normal of a plane, if the control net lies in one and the normal never turns.
    fn plane(&self) -> Option<Vector3<T>> {
        let normal = self.regular[0].normal;
        let origin = self.regular[0].point;
        let check = cast::<T>(SHAPE_CHECK);
        let flat = self
            .net
            .iter()
            .all(|p| (p - origin).dot(&normal).abs() <= check * self.size);
        let one_side = self
            .regular
            .iter()
            .all(|s| s.normal.dot(&normal) >= T::one() - check.sqrt());
        (flat && one_side).then_some(normal)
    }

    /// The centre and the mean curvature $H = \mp 1 / r$ (outward or inward normal) of a
    /// sphere, if every grid point lies on it and every normal is along its radius with one
    /// orientation (see [`offset_surface`]).
    fn sphere(&self) -> Option<(Vector3<T>, T)> {
        let (centre, radius) = fit_sphere(&self.points)?;
        // Relative to the piece's own size (a nearly flat surface fits a huge sphere, and
        // 10⁻¹² of its radius would be no check), plus the rounding of the position.
        let (mut lo, mut hi) = (self.points[0], self.points[0]);
        for p in &self.points {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        let extent = (hi - lo).norm().min(radius);
        let eps = T::default_epsilon();
        let tolerance = cast::<T>(16.0 * SHAPE_CHECK) * extent + cast::<T>(64.0) * eps * self.size;
        let on = self
            .points
            .iter()
            .all(|p| ((p - centre).norm() - radius).abs() <= tolerance);
        if !on {
            return None;
        }
        // The orientation: +1 for the outward normal, −1 for the inward one.
        let along = |s: &Sample<T>| s.normal.dot(&(s.point - centre)) / radius;
        let sign = along(&self.regular[0]).signum();
        let radial = self
            .regular
            .iter()
            .all(|s| along(s) * sign >= T::one() - cast::<T>(SHAPE_CHECK).sqrt());
        radial.then(|| (centre, -sign / radius))
    }

    /// An error at the first sample where the offset folds: $1 - d\,\kappa_i \le 0$.
    fn check_no_fold(&self, distance: T) -> Result<()> {
        for &Sample { u, v, k1, k2, .. } in &self.regular {
            for k in [k1, k2] {
                if T::one() - distance * k <= T::zero() {
                    return Err(Error::new(
                        ErrorKind::DegenerateGeometry,
                        format!(
                            "the offset at distance {} folds near (u, v) = ({}, {}): a principal radius of curvature there is {:.6e}, shorter than the distance on the normal's side (1 − d κ = {:.3e} ≤ 0)",
                            to_f64(distance),
                            to_f64(u),
                            to_f64(v),
                            1.0 / to_f64(k).abs(),
                            to_f64(T::one() - distance * k)
                        ),
                    )
                    .with_value(to_f64(distance)));
                }
            }
        }
        Ok(())
    }
}

/// The sphere (centre, radius) nearest to `points` in the least-squares sense of
/// $\lVert p - c \rVert^2 - r^2$ (linear in $c$ and $r^2 - \lVert c \rVert^2$), on the
/// points moved to their mean and scaled to unit size (the fit does not depend on where the
/// points are nor on their scale), then one Gauss–Newton step on the distances
/// $\lVert p - c \rVert - r$; `None` for fewer than four points or no sphere (coplanar
/// points, a singular system).
fn fit_sphere<T: Scalar>(points: &[Vector3<T>]) -> Option<(Vector3<T>, T)> {
    if points.len() < 4 {
        return None;
    }
    let count = from_count::<T>(points.len());
    let mean = points.iter().fold(Vector3::zeros(), |s, p| s + p) / count;
    let scale = points
        .iter()
        .fold(T::zero(), |m, p| m.max((p - mean).amax()));
    if !(scale > T::zero() && scale.is_finite()) {
        return None;
    }
    let two = cast::<T>(2.0);
    let mut normal = Matrix4::<T>::zeros();
    let mut rhs = Vector4::<T>::zeros();
    for p in points {
        let q = (p - mean) / scale;
        let row = Vector4::new(q.x * two, q.y * two, q.z * two, T::one());
        normal += row * row.transpose();
        rhs += row * q.norm_squared();
    }
    let x = normal.lu().solve(&rhs)?;
    let mut centre = Vector3::new(x[0], x[1], x[2]);
    let squared = x[3] + centre.norm_squared();
    if !(squared > T::zero() && squared.is_finite()) {
        return None;
    }
    let mut radius = squared.sqrt();
    // One Gauss–Newton step on the distances (the algebraic fit weighs them unevenly).
    let mut normal = Matrix4::<T>::zeros();
    let mut rhs = Vector4::<T>::zeros();
    for p in points {
        let q = (p - mean) / scale - centre;
        let length = q.norm();
        if !(length > T::zero()) {
            return None;
        }
        let row = Vector4::new(q.x / length, q.y / length, q.z / length, T::one());
        normal += row * row.transpose();
        rhs += row * (length - radius);
    }
    let step = normal.lu().solve(&rhs)?;
    centre += Vector3::new(step[0], step[1], step[2]);
    radius += step[3];
    let centre = mean + centre * scale;
    let radius = radius * scale;
    (radius > T::zero() && radius.is_finite()).then_some((centre, radius))
}
