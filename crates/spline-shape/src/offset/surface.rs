//! Offset surfaces $O(u, v) = S(u, v) + d\,n(u, v)$: exact for planes and spheres (an affine
//! map of the control net), otherwise a B-spline within a tolerance
//! (`spline_fit::AdaptiveSurfaceApproximation`), refused where the offset folds.

use super::OffsetOptions;
use super::revolution::Revolution;
use nalgebra::Vector3;
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
/// - A piece of a sphere (every sample umbilic with the same centre $S + n / H$ and radius
///   $1 / |H|$ to $10^{-12}$ of the radius, on `4 (p + 1) × 4 (q + 1)` samples per patch) is
///   scaled about its centre by $1 - d H$ (radius $r + d$ for the outward normal): exact.
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
///   normal is its limit from inside the domain.
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
                    out.push(offset_point(surface, u, v, distance)?);
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

/// The unit normal at `(u, v)`, or `None` where $S_u \times S_v$ vanishes (numerically).
fn normal_at<T: Scalar, S: ParamSurface<T, Point = Vector3<T>>>(
    surface: &S,
    u: T,
    v: T,
) -> Result<(Vector3<T>, Option<Vector3<T>>)> {
    let mut d = [Vector3::zeros(); 4];
    surface.derivatives_into(u, v, 1, &mut d)?;
    let (du, dv) = (d[2], d[1]);
    let cross = du.cross(&dv);
    let len = cross.norm();
    let floor = T::default_epsilon() * cast::<T>(8.0) * (du.norm_squared() + dv.norm_squared());
    Ok((d[0], (len > floor).then(|| cross / len)))
}

/// The point of the offset at `(u, v)`; at a singular point, with the normal's limit from
/// inside the domain (the normal a little way towards the domain's centre).
fn offset_point<T: Scalar, S: ParamSurface<T, Point = Vector3<T>>>(
    surface: &S,
    u: T,
    v: T,
    distance: T,
) -> Result<Vector3<T>> {
    let (point, normal) = normal_at(surface, u, v)?;
    if let Some(n) = normal {
        return Ok(point + n * distance);
    }
    let ((a, b), (c, d)) = surface.domain();
    let half = cast::<T>(0.5);
    let (mid_u, mid_v) = ((a + b) * half, (c + d) * half);
    for step in [1e-10, 1e-8, 1e-6] {
        let t = cast::<T>(step);
        let (_, nearby) = normal_at(surface, u + (mid_u - u) * t, v + (mid_v - v) * t)?;
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
/// left out).
struct Samples<T: Scalar> {
    regular: Vec<Sample<T>>,
    /// The largest coordinate of the control net (the size for relative checks).
    size: T,
    net: Vec<Vector3<T>>,
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
        let mut regular = Vec::new();
        for &u in &grid(&breaks_u, 4 * (p + 1)) {
            for &v in &grid(&breaks_v, 4 * (q + 1)) {
                match surface.local_properties(u, v) {
                    Ok(l) => regular.push(Sample {
                        u,
                        v,
                        point: l.point,
                        normal: l.normal,
                        k1: l.max_curvature,
                        k2: l.min_curvature,
                    }),
                    Err(e) if e.kind() == ErrorKind::DegenerateGeometry => {}
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
        let net = surface.cartesian_net();
        let size = net.iter().fold(T::zero(), |m, p| m.max(p.amax()));
        Ok(Self { regular, size, net })
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

    /// The centre and the mean curvature of a sphere, if every sample is an umbilic of it.
    fn sphere(&self) -> Option<(Vector3<T>, T)> {
        let first = self.regular[0];
        let mean = (first.k1 + first.k2) * cast(0.5);
        if !(mean != T::zero() && mean.is_finite()) {
            return None;
        }
        let radius = T::one() / mean.abs();
        let centre = first.point + first.normal / mean;
        let check = cast::<T>(1e-9) * radius;
        let on = self.regular.iter().all(|s| {
            let h = (s.k1 + s.k2) * cast(0.5);
            ((s.point - centre).norm() - radius).abs()
                <= cast::<T>(SHAPE_CHECK) * radius * cast(16.0)
                && (s.k1 - s.k2).abs() * radius <= cast(1e-6)
                && h * mean > T::zero()
                && (s.point + s.normal / h - centre).norm() <= check
        });
        on.then_some((centre, mean))
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
