//! Offsets of surfaces of revolution through their meridian: the offset of a surface of
//! revolution is the revolution of the offset of its meridian in the meridian plane (the
//! normal of the surface lies in that plane), so a cylinder, a cone or a torus has an exact
//! offset (a line or a circular arc moved along its normal), and any other meridian's offset
//! is a planar curve offset within the tolerance, revolved exactly.

use super::curve_offset::{OffsetShape, offset_planar_curve};
use super::options::OffsetOptions;
use nalgebra::{Vector2, Vector3};
use spline_core::{KnotVector, Result, Scalar, cast};
use spline_geom::{NurbsCurve, NurbsSurface};

/// Relative accuracy of the structure checks (as for planes and spheres).
const STRUCTURE_CHECK: f64 = 1e-11;

/// A NURBS surface whose control net is its first column revolved: row `i`, column `j` is
/// the point `(ρ_i, h_i)` of the meridian at angle `θ_j`, its distance from the axis scaled
/// by `f_j`, its weight by `c_j` (the circle construction along `v`).
pub(super) struct Revolution<T: Scalar> {
    centre: Vector3<T>,
    /// Unit direction of the axis.
    axis: Vector3<T>,
    /// Unit radial direction of the first column, and `axis × radial`.
    radial: Vector3<T>,
    across: Vector3<T>,
    /// `(cos θ_j, sin θ_j)`, `f_j` and `c_j` per column.
    angles: Vec<(T, T)>,
    factors: Vec<T>,
    weight_ratios: Vec<T>,
    /// The meridian `(ρ, h)` in the plane of `radial` and `axis`.
    meridian: NurbsCurve<T, 2>,
    knots_v: KnotVector<T>,
}

/// The offset of a surface of revolution, and whether it is exact.
pub(super) struct RevolvedOffset<T: Scalar> {
    pub(super) surface: NurbsSurface<T, 3>,
    pub(super) max_error: T,
}

impl<T: Scalar> Revolution<T> {
    /// The structure of `surface` if it is a surface of revolution with its circles along
    /// `v` (degree 2 in `v`, every row a circle about one axis, the net its first column
    /// revolved), within `1e-11` of its size.
    pub(super) fn of(surface: &NurbsSurface<T, 3>) -> Option<Self> {
        let (_, q) = surface.degrees();
        let (nu, nv) = surface.net_size();
        if q != 2 || nv < 3 {
            return None;
        }
        let point = |i: usize, j: usize| surface.control_point(i, j);
        let size = (0..nu)
            .flat_map(|i| (0..nv).map(move |j| (i, j)))
            .fold(T::zero(), |m, (i, j)| m.max(point(i, j).amax()));
        let check = cast::<T>(STRUCTURE_CHECK) * size;
        // The row farthest from being a point sets the axis: its curve is a circular arc.
        let spread =
            |i: usize| (0..nv).fold(T::zero(), |m, j| m.max((point(i, j) - point(i, 0)).norm()));
        let row = (0..nu).max_by(|&a, &b| {
            spread(a)
                .partial_cmp(&spread(b))
                .unwrap_or(std::cmp::Ordering::Equal)
        })?;
        if !(spread(row) > check) {
            return None;
        }
        let knots_v = surface.knots_v().clone();
        let row_curve = NurbsCurve::<T, 3>::new(
            knots_v.clone(),
            (0..nv).map(|j| point(row, j)).collect(),
            (0..nv).map(|j| surface.weight(row, j)).collect(),
        )
        .ok()?;
        let (a, b) = row_curve.domain();
        let third = (b - a) / cast::<T>(3.0);
        let samples = [a, a + third, a + third * cast::<T>(2.0)].map(|v| row_curve.eval(v));
        let [p0, p1, p2] = [
            samples[0].as_ref().ok()?,
            samples[1].as_ref().ok()?,
            samples[2].as_ref().ok()?,
        ];
        let (centre, axis) = circumcircle(p0, p1, p2)?;
        let radial_of = |p: &Vector3<T>| {
            let d = p - centre;
            d - axis * d.dot(&axis)
        };
        let first = radial_of(&point(row, 0));
        let length = first.norm();
        if !(length > check) {
            return None;
        }
        let radial = first / length;
        let across = axis.cross(&radial);
        let mut angles = Vec::with_capacity(nv);
        let mut factors = Vec::with_capacity(nv);
        let mut weight_ratios = Vec::with_capacity(nv);
        for j in 0..nv {
            let r = radial_of(&point(row, j));
            let norm = r.norm();
            if !(norm > check) {
                return None;
            }
            angles.push((r.dot(&radial) / norm, r.dot(&across) / norm));
            factors.push(norm / length);
            weight_ratios.push(surface.weight(row, j) / surface.weight(row, 0));
        }
        // Every row is its first point revolved with the same angles, factors and weights.
        let mut meridian_points = Vec::with_capacity(nu);
        let mut meridian_weights = Vec::with_capacity(nu);
        for i in 0..nu {
            let d = point(i, 0) - centre;
            let (rho, h) = (d.dot(&radial), d.dot(&axis));
            if !(d.dot(&across).abs() <= check) {
                return None;
            }
            let w0 = surface.weight(i, 0);
            for j in 0..nv {
                let (cos, sin) = angles[j];
                let expected =
                    centre + axis * h + (radial * cos + across * sin) * (rho * factors[j]);
                let weight = w0 * weight_ratios[j];
                if !((point(i, j) - expected).norm() <= check)
                    || !((surface.weight(i, j) - weight).abs()
                        <= cast::<T>(STRUCTURE_CHECK) * weight)
                {
                    return None;
                }
            }
            meridian_points.push(Vector2::new(rho, h));
            meridian_weights.push(w0);
        }
        let meridian =
            NurbsCurve::new(surface.knots_u().clone(), meridian_points, meridian_weights).ok()?;
        Some(Self {
            centre,
            axis,
            radial,
            across,
            angles,
            factors,
            weight_ratios,
            meridian,
            knots_v,
        })
    }

    /// The offset at `distance` along the surface's normal: the meridian's offset (exact for
    /// a line, a translation of its control points, and for a circular arc; otherwise within
    /// the tolerance) revolved with this structure. `None` where the meridian's offset has
    /// cusps (the offset folds) or the surface's normal is nowhere defined on the meridian.
    pub(super) fn offset(
        &self,
        surface: &NurbsSurface<T, 3>,
        distance: T,
        options: &OffsetOptions<T>,
    ) -> Result<Option<RevolvedOffset<T>>> {
        let Some(side) = self.normal_side(surface)? else {
            return Ok(None);
        };
        let moved = side * distance;
        let (meridian, max_error) = if let Some(normal) = self.line_normal() {
            // A straight meridian (cylinder, cone, plane ring): its control points move
            // along its one normal, the parametrisation kept.
            let shift = normal * moved;
            (
                NurbsCurve::new(
                    self.meridian.knots().clone(),
                    self.meridian
                        .control_points()
                        .iter()
                        .map(|p| p + shift)
                        .collect(),
                    self.meridian.weights().to_vec(),
                )?,
                T::zero(),
            )
        } else {
            let found = offset_planar_curve(&self.meridian, moved, options)?;
            if !found.cusps.is_empty() {
                return Ok(None);
            }
            let curve = match found.curve {
                OffsetShape::Rational(c) => c,
                OffsetShape::Polynomial(c) => NurbsCurve::from_bspline(&c),
            };
            (curve, found.max_error)
        };
        let nv = self.angles.len();
        let mut points = Vec::with_capacity(meridian.len() * nv);
        let mut weights = Vec::with_capacity(meridian.len() * nv);
        for (p, &w) in meridian.control_points().iter().zip(meridian.weights()) {
            for j in 0..nv {
                let (cos, sin) = self.angles[j];
                points.push(
                    self.centre
                        + self.axis * p.y
                        + (self.radial * cos + self.across * sin) * (p.x * self.factors[j]),
                );
                weights.push(w * self.weight_ratios[j]);
            }
        }
        let surface = NurbsSurface::new(
            meridian.knots().clone(),
            self.knots_v.clone(),
            points,
            weights,
        )?;
        Ok(Some(RevolvedOffset { surface, max_error }))
    }

    /// `+1` where the surface's normal is the meridian's left normal (in the plane of
    /// `radial` and `axis`), `−1` where it is the right one; `None` if no regular point is
    /// found on the first column.
    fn normal_side(&self, surface: &NurbsSurface<T, 3>) -> Result<Option<T>> {
        let ((a, b), (c, _)) = surface.domain();
        for k in 1..8 {
            let u = a + (b - a) * cast::<T>(f64::from(k) / 8.0);
            let mut d = [Vector3::zeros(); 4];
            surface.derivatives_into(u, c, 1, &mut d)?;
            let normal = d[2].cross(&d[1]);
            let tangent = self.meridian.derivatives(u, 1)?[1];
            let left = self.radial * (-tangent.y) + self.axis * tangent.x;
            let scale = normal.norm() * left.norm();
            let dot = normal.dot(&left);
            if scale > T::zero() && dot.abs() > cast::<T>(0.5) * scale {
                return Ok(Some(if dot > T::zero() { T::one() } else { -T::one() }));
            }
        }
        Ok(None)
    }

    /// The unit left normal of a straight meridian (control points on one line), if it is
    /// one.
    fn line_normal(&self) -> Option<Vector2<T>> {
        let points = self.meridian.control_points();
        let (first, last) = (points[0], points[points.len() - 1]);
        let direction = last - first;
        let length = direction.norm();
        let size = points.iter().fold(T::zero(), |m, p| m.max(p.amax()));
        if !(length > cast::<T>(STRUCTURE_CHECK) * size) {
            return None;
        }
        let normal = Vector2::new(-direction.y, direction.x) / length;
        points
            .iter()
            .all(|p| (p - first).dot(&normal).abs() <= cast::<T>(STRUCTURE_CHECK) * size)
            .then_some(normal)
    }
}

/// The centre and the unit normal of the circle through three points, `None` if they are
/// (nearly) on one line.
fn circumcircle<T: Scalar>(
    a: &Vector3<T>,
    b: &Vector3<T>,
    c: &Vector3<T>,
) -> Option<(Vector3<T>, Vector3<T>)> {
    let (ab, ac) = (b - a, c - a);
    let normal = ab.cross(&ac);
    let n2 = normal.norm_squared();
    if !(n2 > T::default_epsilon() * ab.norm_squared() * ac.norm_squared()) {
        return None;
    }
    let to_centre = (normal.cross(&ab) * ac.norm_squared() + ac.cross(&normal) * ab.norm_squared())
        / (cast::<T>(2.0) * n2);
    Some((a + to_centre, normal / n2.sqrt()))
}

#[cfg(test)]
mod tests {
    use super::circumcircle;
    use nalgebra::Vector3;

    #[test]
    fn circumcircle_of_three_points_on_a_circle() {
        let at = |t: f64| Vector3::new(1.0 + 2.0 * t.cos(), -1.0 + 2.0 * t.sin(), 3.0);
        let (centre, normal) = circumcircle(&at(0.1), &at(1.7), &at(4.0)).unwrap();
        assert!((centre - Vector3::new(1.0, -1.0, 3.0)).norm() < 1e-14);
        assert!((normal.z.abs() - 1.0).abs() < 1e-15);
        assert!(circumcircle(&at(0.0), &at(0.0), &at(1.0)).is_none());
    }
}
