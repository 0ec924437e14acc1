//! The analytic entities of a STEP file converted exactly to NURBS: `LINE`, `CIRCLE` and
//! `ELLIPSE` (bounded by the vertices of the edges that use them), `PLANE`,
//! `CYLINDRICAL_SURFACE`, `CONICAL_SURFACE` (bounded by the edges of their faces),
//! `SPHERICAL_SURFACE`, `TOROIDAL_SURFACE` (whole), `SURFACE_OF_REVOLUTION` (a full turn)
//! and `SURFACE_OF_LINEAR_EXTRUSION` (along its vector, or over its face's edges).
//!
//! Parametrisations: a line segment is a degree-1 curve whose parameter is the distance
//! along the line's unit direction (Open CASCADE's `Geom_Line`); circles and ellipses are
//! rational quadratic arcs on `[0, 1]` (pieces of at most 90°) from the start vertex
//! counter-clockwise about the placement's axis; planes are bilinear patches over the box of
//! their face's edges in the placement's `(x, y)`; cylinders and cones are surfaces of
//! revolution (`u` along the generatrix over the heights their face's edges reach, `v` a
//! full turn); spheres and tori are the 9-point constructions of spline-geom. Outside a
//! B-rep (an analytic entity no edge or face bounds), a line spans its vector's magnitude,
//! a plane the square `[−1, 1]²` of its placement, a cylinder or cone the heights `[0, 1]`.

use super::instance::{Instance, Param, error_at, number, text, underlying};
use super::reader::Reader;
use super::splines::{curve_parts, read_curve};
use crate::{Geometry, Item};
use nalgebra::{Vector2, Vector3};
use spline_core::{KnotVector, Result};
use spline_geom::{Axis, BSpline, Frame, NurbsCurve, NurbsSurface};
use std::collections::{BTreeMap, HashMap};
use std::f64::consts::TAU;

/// A right-handed frame: origin, x, y, z (unit, orthogonal).
#[derive(Clone, Copy)]
struct Placement {
    origin: Vector3<f64>,
    x: Vector3<f64>,
    y: Vector3<f64>,
    z: Vector3<f64>,
}

impl Placement {
    fn local(&self, p: &Vector3<f64>) -> Vector3<f64> {
        let d = p - self.origin;
        Vector3::new(d.dot(&self.x), d.dot(&self.y), d.dot(&self.z))
    }

    fn global(&self, x: f64, y: f64, z: f64) -> Vector3<f64> {
        self.origin + self.x * x + self.y * y + self.z * z
    }
}

fn reference(p: Option<&Param>) -> Option<u64> {
    match p {
        Some(Param::Reference(r)) => Some(*r),
        _ => None,
    }
}

fn three(v: &[f64], line: usize) -> Result<Vector3<f64>> {
    match v {
        [x, y, z] => Ok(Vector3::new(*x, *y, *z)),
        [x, y] => Ok(Vector3::new(*x, *y, 0.0)),
        _ => Err(error_at(line, "expected 2 or 3 coordinates")),
    }
}

impl Reader<'_> {
    fn point3(&self, p: Option<&Param>, line: usize) -> Result<Vector3<f64>> {
        let p = p.ok_or_else(|| error_at(line, "a point is missing"))?;
        three(&self.point(p, line)?, line)
    }

    fn direction(&self, id: u64, line: usize) -> Result<Vector3<f64>> {
        let d = self.get(id, line)?;
        let Some([_, Param::List(c)]) = d.record("DIRECTION") else {
            return Err(error_at(d.line, format!("#{id} is not a DIRECTION")));
        };
        let c: Vec<f64> = c
            .iter()
            .map(|x| number(x).ok_or_else(|| error_at(d.line, "a direction ratio is not a number")))
            .collect::<Result<_>>()?;
        let v = three(&c, d.line)?;
        let n = v.norm();
        if !(n > 0.0 && n.is_finite()) {
            return Err(error_at(
                d.line,
                format!("#{id}: a direction must not be zero"),
            ));
        }
        Ok(v / n)
    }

    /// `AXIS2_PLACEMENT_3D(name, location, axis, ref_direction)` (or `_2D`).
    fn placement(&self, id: u64, line: usize) -> Result<Placement> {
        let a = self.get(id, line)?;
        let (p, three_d) = match (
            a.record("AXIS2_PLACEMENT_3D"),
            a.record("AXIS2_PLACEMENT_2D"),
        ) {
            (Some(p), _) => (p, true),
            (None, Some(p)) => (p, false),
            _ => {
                return Err(error_at(
                    a.line,
                    format!("#{id} is not an AXIS2_PLACEMENT_3D"),
                ));
            }
        };
        let origin = self.point3(p.get(1), a.line)?;
        let z = match (three_d, reference(p.get(2))) {
            (true, Some(d)) => self.direction(d, a.line)?,
            _ => Vector3::z(),
        };
        let reference_x = match reference(p.get(if three_d { 3 } else { 2 })) {
            Some(d) => self.direction(d, a.line)?,
            None if z.x.abs() < 0.9 => Vector3::x(),
            None => Vector3::y(),
        };
        let x = reference_x - z * z.dot(&reference_x);
        let n = x.norm();
        if !(n > 1e-12) {
            return Err(error_at(
                a.line,
                format!("#{id}: the reference direction is parallel to the axis"),
            ));
        }
        let x = x / n;
        Ok(Placement {
            origin,
            x,
            y: z.cross(&x),
            z,
        })
    }

    /// `VECTOR(name, orientation, magnitude)`: the unit direction and the magnitude (1 when
    /// it is not a number).
    fn vector(&self, id: u64, line: usize) -> Result<(Vector3<f64>, f64)> {
        let v = self.get(id, line)?;
        let Some(p) = v.record("VECTOR") else {
            return Err(error_at(v.line, format!("#{id} is not a VECTOR")));
        };
        let direction = self.direction(
            reference(p.get(1)).ok_or_else(|| error_at(v.line, "VECTOR needs a DIRECTION"))?,
            v.line,
        )?;
        Ok((direction, p.get(2).and_then(number).unwrap_or(1.0)))
    }

    fn vertex(&self, id: Option<u64>, line: usize) -> Result<Option<Vector3<f64>>> {
        let Some(id) = id else { return Ok(None) };
        let v = self.get(id, line)?;
        match v.record("VERTEX_POINT") {
            Some(p) => self.point3(p.get(1), v.line).map(Some),
            None => Ok(None),
        }
    }
}

/// A circular or elliptic arc from angle `start` sweeping `sweep` (`a`, `b`: semi-axes).
fn arc(place: &Placement, a: f64, b: f64, start: f64, sweep: f64) -> Result<NurbsCurve<f64, 3>> {
    let unit = Frame::new(Vector3::zeros(), Vector3::x(), Vector3::y())?;
    let circle = NurbsCurve::arc(&unit, 1.0, start, sweep)?;
    Ok(circle.map_control_points::<3>(|p| place.global(a * p.x, b * p.y, 0.0)))
}

/// The angle of a point on an ellipse with semi-axes `a`, `b` in the placement's plane.
fn angle(place: &Placement, a: f64, b: f64, p: &Vector3<f64>) -> f64 {
    let l = place.local(p);
    (l.y / b).atan2(l.x / a).rem_euclid(TAU)
}

/// An analytic curve bounded by the vertices of an edge (`None`: its default extent).
fn curve(
    reader: &Reader<'_>,
    instance: &Instance,
    id: u64,
    ends: Option<(Vector3<f64>, Vector3<f64>)>,
) -> Result<Option<(NurbsCurve<f64, 3>, &'static str)>> {
    let line = instance.line;
    if let Some(p) = instance.record("LINE") {
        let origin = reader.point3(p.get(1), line)?;
        let vector = reference(p.get(2)).ok_or_else(|| error_at(line, "LINE needs a VECTOR"))?;
        let (direction, magnitude) = reader.vector(vector, line)?;
        let (t0, t1) = match ends {
            Some((a, b)) => {
                let (s, t) = ((a - origin).dot(&direction), (b - origin).dot(&direction));
                (s.min(t), s.max(t))
            }
            None => (0.0, magnitude),
        };
        if !(t1 > t0) {
            return Err(error_at(
                line,
                format!("#{id}: the edge on this LINE has no length"),
            ));
        }
        let segment = segment((t0, t1), |t| origin + direction * t)?;
        return Ok(Some((segment, "LINE")));
    }
    let (place, a, b, entity) = if let Some(p) = instance.record("CIRCLE") {
        let place = reader.placement(
            reference(p.get(1)).ok_or_else(|| error_at(line, "CIRCLE needs a placement"))?,
            line,
        )?;
        let r = p
            .get(2)
            .and_then(number)
            .ok_or_else(|| error_at(line, "CIRCLE needs a radius"))?;
        (place, r, r, "CIRCLE")
    } else if let Some(p) = instance.record("ELLIPSE") {
        let place = reader.placement(
            reference(p.get(1)).ok_or_else(|| error_at(line, "ELLIPSE needs a placement"))?,
            line,
        )?;
        let a = p
            .get(2)
            .and_then(number)
            .ok_or_else(|| error_at(line, "ELLIPSE needs two semi-axes"))?;
        let b = p
            .get(3)
            .and_then(number)
            .ok_or_else(|| error_at(line, "ELLIPSE needs two semi-axes"))?;
        (place, a, b, "ELLIPSE")
    } else {
        return Ok(None);
    };
    if !(a > 0.0 && b > 0.0) {
        return Err(error_at(line, format!("#{id}: radii must be positive")));
    }
    let (start, sweep) = match ends {
        Some((p, q)) => {
            let (s, e) = (angle(&place, a, b, &p), angle(&place, a, b, &q));
            let sweep = (e - s).rem_euclid(TAU);
            (s, if sweep < 1e-12 { TAU } else { sweep })
        }
        None => (0.0, TAU),
    };
    Ok(Some((arc(&place, a, b, start, sweep)?, entity)))
}

/// Points along the edges that bound a face (sampled curves, vertices).
fn face_points(
    reader: &Reader<'_>,
    face: &Instance,
    edges: &HashMap<u64, Vec<Vector3<f64>>>,
) -> Vec<Vector3<f64>> {
    let mut out = Vec::new();
    let Some(bounds) = face
        .record("ADVANCED_FACE")
        .or_else(|| face.record("FACE_SURFACE"))
        .and_then(|p| match p.get(1) {
            Some(Param::List(b)) => Some(b.clone()),
            _ => None,
        })
    else {
        return out;
    };
    for bound in bounds.iter().filter_map(|b| reference(Some(b))) {
        let Some(b) = reader.instances.get(&bound) else {
            continue;
        };
        let Some(loop_id) = b
            .record("FACE_OUTER_BOUND")
            .or_else(|| b.record("FACE_BOUND"))
            .and_then(|p| reference(p.get(1)))
        else {
            continue;
        };
        let Some(Some(Param::List(oriented))) = reader
            .instances
            .get(&loop_id)
            .and_then(|l| l.record("EDGE_LOOP"))
            .map(|p| p.get(1))
        else {
            continue;
        };
        for o in oriented.iter().filter_map(|o| reference(Some(o))) {
            let edge = reader
                .instances
                .get(&o)
                .and_then(|oe| oe.record("ORIENTED_EDGE"))
                .and_then(|p| reference(p.get(3)));
            if let Some(points) = edge.and_then(|e| edges.get(&e)) {
                out.extend(points);
            }
        }
    }
    out
}

/// The profile line of a cylinder or cone between heights `h0 < h1`, at radius
/// `r(h) = radius + h·slope`, in the placement's `x z` half-plane.
fn profile(
    place: &Placement,
    radius: f64,
    slope: f64,
    (h0, h1): (f64, f64),
) -> Result<NurbsCurve<f64, 3>> {
    segment((h0, h1), |h| place.global(radius + h * slope, 0.0, h))
}

/// The straight segment from `at(t0)` to `at(t1)`, of degree 1 on the parameters
/// `[t0, t1]`.
fn segment((t0, t1): (f64, f64), at: impl Fn(f64) -> Vector3<f64>) -> Result<NurbsCurve<f64, 3>> {
    let line = BSpline::new(
        KnotVector::new(1, vec![t0, t0, t1, t1])?,
        vec![at(t0), at(t1)],
    )?;
    Ok(NurbsCurve::from_bspline(&line))
}

/// The range of the points' heights along the placement's axis (`[0, 1]` without points).
fn heights(place: &Placement, points: &[Vector3<f64>]) -> (f64, f64) {
    if points.is_empty() {
        return (0.0, 1.0);
    }
    let (lo, hi) = points
        .iter()
        .map(|p| place.local(p).z)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), z| {
            (l.min(z), h.max(z))
        });
    if hi > lo { (lo, hi) } else { (lo, lo + 1.0) }
}

fn surface(
    reader: &Reader<'_>,
    instance: &Instance,
    id: u64,
    points: &[Vector3<f64>],
) -> Result<Option<(NurbsSurface<f64, 3>, &'static str)>> {
    let line = instance.line;
    let placement = |p: &[Param]| {
        reader.placement(
            reference(p.get(1))
                .ok_or_else(|| error_at(line, format!("#{id} needs a placement")))?,
            line,
        )
    };
    let positive = |p: Option<&Param>, what: &str| -> Result<f64> {
        p.and_then(number)
            .filter(|x| *x > 0.0 && x.is_finite())
            .ok_or_else(|| error_at(line, format!("#{id}: {what} must be positive")))
    };
    if let Some(p) = instance.record("PLANE") {
        let place = placement(p)?;
        let (mut lo, mut hi) = (Vector2::new(-1.0, -1.0), Vector2::new(1.0, 1.0));
        if !points.is_empty() {
            lo = Vector2::repeat(f64::INFINITY);
            hi = Vector2::repeat(f64::NEG_INFINITY);
            for q in points {
                let l = place.local(q).xy();
                lo = lo.inf(&l);
                hi = hi.sup(&l);
            }
            for k in 0..2 {
                if !(hi[k] > lo[k]) {
                    hi[k] = lo[k] + 1.0;
                }
            }
        }
        let net = vec![
            vec![place.global(lo.x, lo.y, 0.0), place.global(lo.x, hi.y, 0.0)],
            vec![place.global(hi.x, lo.y, 0.0), place.global(hi.x, hi.y, 0.0)],
        ];
        let knots = |a: f64, b: f64| KnotVector::new(1, vec![a, a, b, b]);
        let plane = spline_geom::Surface::from_net(knots(lo.x, hi.x)?, knots(lo.y, hi.y)?, net)?;
        return Ok(Some((NurbsSurface::from_surface(&plane), "PLANE")));
    }
    let revolve =
        |place: &Placement, profile: NurbsCurve<f64, 3>| -> Result<NurbsSurface<f64, 3>> {
            NurbsSurface::revolution(&profile, &Axis::new(place.origin, place.z)?, TAU)
        };
    if let Some(p) = instance.record("CYLINDRICAL_SURFACE") {
        let place = placement(p)?;
        let r = positive(p.get(2), "the radius")?;
        let s = revolve(&place, profile(&place, r, 0.0, heights(&place, points))?)?;
        return Ok(Some((s, "CYLINDRICAL_SURFACE")));
    }
    if let Some(p) = instance.record("CONICAL_SURFACE") {
        let place = placement(p)?;
        let r = p
            .get(2)
            .and_then(number)
            .filter(|x| *x >= 0.0)
            .ok_or_else(|| error_at(line, format!("#{id}: the radius must not be negative")))?;
        let angle = p
            .get(3)
            .and_then(number)
            .ok_or_else(|| error_at(line, format!("#{id}: the semi-angle is missing")))?;
        let s = revolve(
            &place,
            profile(&place, r, angle.tan(), heights(&place, points))?,
        )?;
        return Ok(Some((s, "CONICAL_SURFACE")));
    }
    if let Some(p) = instance.record("SPHERICAL_SURFACE") {
        let place = placement(p)?;
        let r = positive(p.get(2), "the radius")?;
        return Ok(Some((
            NurbsSurface::sphere(place.origin, r)?,
            "SPHERICAL_SURFACE",
        )));
    }
    if let Some(p) = instance.record("TOROIDAL_SURFACE") {
        let place = placement(p)?;
        let major = positive(p.get(2), "the major radius")?;
        let minor = positive(p.get(3), "the minor radius")?;
        return Ok(Some((
            NurbsSurface::torus(place.origin, place.z, major, minor)?,
            "TOROIDAL_SURFACE",
        )));
    }
    let swept = |p: &[Param]| -> Result<NurbsCurve<f64, 3>> {
        let c = reference(p.get(1))
            .ok_or_else(|| error_at(line, format!("#{id} needs a swept curve")))?;
        let c = underlying(reader.instances, c).ok_or_else(|| {
            error_at(
                line,
                format!("#{id}: the swept curve's references form a cycle"),
            )
        })?;
        let ci = reader.get(c, line)?;
        if let Some(parts) = curve_parts(ci)? {
            return Ok(match read_curve(reader, ci, &parts)? {
                Geometry::Curve3(b) => NurbsCurve::from_bspline(&b),
                Geometry::NurbsCurve3(n) => n,
                Geometry::Curve2(b) => {
                    NurbsCurve::from_bspline(&b.map_control_points(|q| Vector3::new(q.x, q.y, 0.0)))
                }
                Geometry::NurbsCurve2(n) => {
                    n.map_control_points::<3>(|q| Vector3::new(q.x, q.y, 0.0))
                }
                _ => return Err(error_at(line, "not a curve")),
            });
        }
        curve(reader, ci, c, None)?.map(|(c, _)| c).ok_or_else(|| {
            error_at(
                ci.line,
                format!("#{c}: this swept curve cannot be converted"),
            )
        })
    };
    if let Some(p) = instance.record("SURFACE_OF_REVOLUTION") {
        let profile = swept(p)?;
        let axis_id =
            reference(p.get(2)).ok_or_else(|| error_at(line, format!("#{id} needs an axis")))?;
        let a = reader.get(axis_id, line)?;
        let Some(ap) = a.record("AXIS1_PLACEMENT") else {
            return Err(error_at(
                a.line,
                format!("#{axis_id} is not an AXIS1_PLACEMENT"),
            ));
        };
        let origin = reader.point3(ap.get(1), a.line)?;
        let direction = match reference(ap.get(2)) {
            Some(d) => reader.direction(d, a.line)?,
            None => Vector3::z(),
        };
        let s = NurbsSurface::revolution(&profile, &Axis::new(origin, direction)?, TAU)?;
        return Ok(Some((s, "SURFACE_OF_REVOLUTION")));
    }
    if let Some(p) = instance.record("SURFACE_OF_LINEAR_EXTRUSION") {
        let profile = swept(p)?;
        let vector =
            reference(p.get(2)).ok_or_else(|| error_at(line, format!("#{id} needs a VECTOR")))?;
        let (direction, magnitude) = reader.vector(vector, line)?;
        // Over the face: the range of the edges' offsets from the profile's start along the
        // direction; else the vector itself.
        let base = profile.eval(profile.domain().0)?;
        let (lo, hi) = if points.is_empty() {
            (0.0, magnitude)
        } else {
            let offsets = points.iter().map(|q| (q - base).dot(&direction));
            let (lo, hi) = offsets.fold((0.0f64, 0.0f64), |(l, h), t| (l.min(t), h.max(t)));
            if hi > lo { (lo, hi) } else { (0.0, magnitude) }
        };
        let start = profile.map_control_points::<3>(|q| q + direction * lo);
        let s = NurbsSurface::extrusion(&start, direction * (hi - lo))?;
        return Ok(Some((s, "SURFACE_OF_LINEAR_EXTRUSION")));
    }
    Ok(None)
}

/// Every analytic curve of an edge and analytic surface of a face (or standing alone in a
/// representation), converted; the B-spline ones are read by [`super::read_step_bytes`].
pub(super) fn analytic_items(
    reader: &Reader<'_>,
    names: &HashMap<u64, String>,
) -> Result<Vec<Item>> {
    let ordered: BTreeMap<u64, &Instance> = reader.instances.iter().map(|(k, v)| (*k, v)).collect();
    let mut curves: BTreeMap<u64, (NurbsCurve<f64, 3>, &'static str)> = BTreeMap::new();
    let mut edge_points: HashMap<u64, Vec<Vector3<f64>>> = HashMap::new();
    for (&edge_id, edge) in &ordered {
        let Some(p) = edge.record("EDGE_CURVE") else {
            continue;
        };
        let v1 = reader.vertex(reference(p.get(1)), edge.line)?;
        let v2 = reader.vertex(reference(p.get(2)), edge.line)?;
        let Some(g) = reference(p.get(3)).and_then(|g| underlying(reader.instances, g)) else {
            continue;
        };
        let gi = reader.get(g, edge.line)?;
        let same_sense = !matches!(p.get(4), Some(Param::Enumeration(e)) if e == "F");
        let ends = match (v1, v2) {
            (Some(a), Some(b)) => Some(if same_sense { (a, b) } else { (b, a) }),
            _ => None,
        };
        let mut points: Vec<Vector3<f64>> = [v1, v2].into_iter().flatten().collect();
        if let Some((c, entity)) = curve(reader, gi, g, ends)? {
            let (a, b) = c.domain();
            for k in 0..=16 {
                points.push(c.eval(a + (b - a) * f64::from(k) / 16.0)?);
            }
            curves.entry(g).or_insert((c, entity));
        } else if let Some(parts) = curve_parts(gi)? {
            // A B-spline edge: its control points bound it.
            match read_curve(reader, gi, &parts)? {
                Geometry::Curve3(c) => points.extend(c.control_points()),
                Geometry::NurbsCurve3(c) => points.extend(c.control_points()),
                _ => {}
            }
        }
        edge_points.insert(edge_id, points);
    }
    let mut surfaces: BTreeMap<u64, (NurbsSurface<f64, 3>, &'static str)> = BTreeMap::new();
    for face in ordered.values() {
        let Some(p) = face
            .record("ADVANCED_FACE")
            .or_else(|| face.record("FACE_SURFACE"))
        else {
            continue;
        };
        let Some(g) = reference(p.get(2)).and_then(|g| underlying(reader.instances, g)) else {
            continue;
        };
        if surfaces.contains_key(&g) {
            continue;
        }
        let points = face_points(reader, face, &edge_points);
        if let Some(s) = surface(reader, reader.get(g, face.line)?, g, &points)? {
            surfaces.insert(g, s);
        }
    }
    // Analytic geometry that no edge or face bounds: the entities listed in a representation
    // (a GEOMETRIC_SET, a GEOMETRIC_CURVE_SET, a shape representation's items).
    for set in ordered.values() {
        let items = ["GEOMETRIC_CURVE_SET", "GEOMETRIC_SET"]
            .iter()
            .find_map(|n| set.record(n))
            .and_then(|p| match p.get(1) {
                Some(Param::List(l)) => Some(l.clone()),
                _ => None,
            });
        for g in items.iter().flatten().filter_map(|g| reference(Some(g))) {
            let Some(g) = underlying(reader.instances, g) else {
                continue;
            };
            if curves.contains_key(&g) || surfaces.contains_key(&g) {
                continue;
            }
            let gi = reader.get(g, set.line)?;
            if let Some(c) = curve(reader, gi, g, None)? {
                curves.insert(g, c);
            } else if let Some(s) = surface(reader, gi, g, &[])? {
                surfaces.insert(g, s);
            }
        }
    }
    let name_of = |id: u64| {
        names.get(&id).cloned().unwrap_or_else(|| {
            reader
                .instances
                .get(&id)
                .and_then(|i| i.records.first())
                .and_then(|(_, p)| p.first())
                .map(text)
                .unwrap_or_default()
        })
    };
    let mut out: Vec<Item> = curves
        .into_iter()
        .map(|(id, (c, entity))| Item {
            id,
            name: name_of(id),
            entity: entity.into(),
            geometry: Geometry::NurbsCurve3(c),
        })
        .collect();
    out.extend(surfaces.into_iter().map(|(id, (s, entity))| Item {
        id,
        name: name_of(id),
        entity: entity.into(),
        geometry: Geometry::NurbsSurface(s),
    }));
    Ok(out)
}
