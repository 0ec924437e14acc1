//! The entities read as geometry: 126 and 128 (the B-spline curve and surface, restricted to
//! their parameter ranges), 110 (line), 100 (circular arc), 120 (surface of revolution) and
//! 122 (tabulated cylinder) converted exactly; transformations applied.

use super::affine::Affine;
use super::directory::{Entry, File, Params};
use super::layout::{Section, at, parse_error};
use crate::Geometry;
use nalgebra::{Rotation3, Unit, Vector2, Vector3};
use spline_core::{ControlPoint, KnotVector, Result};
use spline_geom::{Axis, BSpline, Direction, Frame, NurbsCurve3, NurbsSurface3, Surface};

/// A converted curve, polynomial or rational.
#[derive(Clone, Debug)]
pub(super) enum Curve {
    Poly(BSpline<f64, Vector3<f64>>),
    Rational(NurbsCurve3<f64>),
}

impl Curve {
    pub(super) fn transformed(self, affine: Option<Affine>) -> Self {
        let Some(a) = affine else { return self };
        match self {
            Self::Poly(c) => Self::Poly(c.map_control_points(|p| a.apply(p))),
            Self::Rational(c) => Self::Rational(c.map_control_points(|p| a.apply(p))),
        }
    }

    pub(super) fn rational(&self) -> NurbsCurve3<f64> {
        match self {
            Self::Poly(c) => NurbsCurve3::from_bspline(c),
            Self::Rational(c) => c.clone(),
        }
    }

    pub(super) fn geometry(self) -> Geometry {
        match self {
            Self::Poly(c) => Geometry::Curve3(c),
            Self::Rational(c) => Geometry::NurbsCurve3(c),
        }
    }
}

/// A converted surface, polynomial or rational.
pub(super) enum Patch {
    Poly(Surface<f64, Vector3<f64>>),
    Rational(NurbsSurface3<f64>),
}

impl Patch {
    pub(super) fn transformed(self, affine: Option<Affine>) -> Self {
        let Some(a) = affine else { return self };
        match self {
            Self::Poly(s) => Self::Poly(s.map_control_points(|p| a.apply(p))),
            Self::Rational(s) => Self::Rational(s.map_control_points(|p| a.apply(p))),
        }
    }

    pub(super) fn geometry(self) -> Geometry {
        match self {
            Self::Poly(s) => Geometry::Surface(s),
            Self::Rational(s) => Geometry::NurbsSurface(s),
        }
    }
}

/// The domain `[lo, hi]` restricted to the parameter range `[a, b]` read from the file:
/// `None` when the range covers the domain, the intersection otherwise.
pub(super) fn range_within(
    (lo, hi): (f64, f64),
    (a, b): (f64, f64),
    line: usize,
    what: &str,
) -> Result<Option<(f64, f64)>> {
    let (a, b) = (a.max(lo), b.min(hi));
    if !(a < b) {
        return Err(parse_error(
            Section::Parameter,
            line,
            format!(
                "the parameter range {what} [{a}, {b}] is empty or outside the knot domain [{lo}, {hi}]"
            ),
        ));
    }
    Ok((a > lo || b < hi).then_some((a, b)))
}

/// Restricts a surface to `[a, b]` in `direction` (within its domain).
pub(super) fn restrict_surface<P: ControlPoint<f64>>(
    mut s: Surface<f64, P>,
    direction: Direction,
    (a, b): (f64, f64),
) -> Result<Surface<f64, P>> {
    let (lo, hi) = match direction {
        Direction::U => s.domain().0,
        Direction::V => s.domain().1,
    };
    if a > lo {
        s = s.split(direction, a)?.1;
    }
    if b < hi {
        s = s.split(direction, b)?.0;
    }
    Ok(s)
}

/// Whether the weights are all equal (the curve or surface is then polynomial).
pub(super) fn equal_weights(weights: &[f64]) -> bool {
    weights.iter().all(|&w| w == weights[0])
}

/// Entity 126, the rational B-spline curve.
pub(super) fn read_126(params: &mut Params) -> Result<Curve> {
    let (k, line) = params.count("K (upper index of the control points)", 0)?;
    let (m, _) = params.count("M (degree)", 0)?;
    let _planar = params.int("PROP1")?;
    let _closed = params.int("PROP2")?;
    let polynomial = params.int("PROP3")? == 1;
    let _periodic = params.int("PROP4")?;
    let n = k.checked_add(1);
    let knots = k.checked_add(m).and_then(|s| s.checked_add(2));
    let needed = knots
        .zip(n)
        .and_then(|(nk, n)| n.checked_mul(4).and_then(|x| x.checked_add(nk)))
        .and_then(|x| x.checked_add(2));
    params.require(
        needed,
        line,
        format_args!("K = {k} and M = {m} (knots, weights, control points, V(0), V(1))"),
    )?;
    let (n, knots_len) = (k + 1, k + m + 2);
    let knots_line = params.line();
    let mut knots = Vec::with_capacity(knots_len);
    for _ in 0..knots_len {
        knots.push(params.real("knot")?);
    }
    let knots = KnotVector::new(m, knots).map_err(at(Section::Parameter, knots_line))?;
    let weights_line = params.line();
    let mut weights = Vec::with_capacity(n);
    for _ in 0..n {
        weights.push(params.real("weight")?);
    }
    let points_line = params.line();
    let mut points = Vec::with_capacity(n);
    for _ in 0..n {
        points.push(params.point("control point")?);
    }
    let range_line = params.line();
    let range = (params.real("V(0)")?, params.real("V(1)")?);
    if params.remaining() >= 3 {
        params.point("unit normal")?;
    }
    let curve = if polynomial && equal_weights(&weights) {
        Curve::Poly(BSpline::new(knots, points).map_err(at(Section::Parameter, points_line))?)
    } else {
        let line = if weights.iter().all(|&w| w > 0.0) {
            points_line
        } else {
            weights_line
        };
        Curve::Rational(
            NurbsCurve3::new(knots, points, weights).map_err(at(Section::Parameter, line))?,
        )
    };
    let domain = match &curve {
        Curve::Poly(c) => c.domain(),
        Curve::Rational(c) => c.domain(),
    };
    let Some((a, b)) = range_within(domain, range, range_line, "V(0), V(1)")? else {
        return Ok(curve);
    };
    let restrict = at(Section::Parameter, range_line);
    Ok(match curve {
        Curve::Poly(c) => Curve::Poly(c.restricted(a, b).map_err(restrict)?),
        Curve::Rational(c) => Curve::Rational(
            NurbsCurve3::from_homogeneous(c.homogeneous().restricted(a, b).map_err(restrict)?)
                .map_err(at(Section::Parameter, range_line))?,
        ),
    })
}

/// Entity 128, the rational B-spline surface: weights and control points with the first
/// (u) index running fastest, transposed into the row-major net.
pub(super) fn read_128(params: &mut Params) -> Result<Patch> {
    let (k1, line) = params.count("K1 (upper index in u)", 0)?;
    let (k2, _) = params.count("K2 (upper index in v)", 0)?;
    let (m1, _) = params.count("M1 (degree in u)", 0)?;
    let (m2, _) = params.count("M2 (degree in v)", 0)?;
    for prop in ["PROP1", "PROP2"] {
        params.int(prop)?;
    }
    let polynomial = params.int("PROP3")? == 1;
    for prop in ["PROP4", "PROP5"] {
        params.int(prop)?;
    }
    let nu = k1.checked_add(1);
    let nv = k2.checked_add(1);
    let ku = k1.checked_add(m1).and_then(|s| s.checked_add(2));
    let kv = k2.checked_add(m2).and_then(|s| s.checked_add(2));
    let count = nu.zip(nv).and_then(|(a, b)| a.checked_mul(b));
    let needed = (|| {
        ku?.checked_add(kv?)?
            .checked_add(count?.checked_mul(4)?)?
            .checked_add(4)
    })();
    params.require(
        needed,
        line,
        format_args!("K1 = {k1}, K2 = {k2}, M1 = {m1}, M2 = {m2} (knots, weights, control points, U(0), U(1), V(0), V(1))"),
    )?;
    let (nu, nv, ku, kv, count) = (
        k1 + 1,
        k2 + 1,
        k1 + m1 + 2,
        k2 + m2 + 2,
        (k1 + 1) * (k2 + 1),
    );
    let mut read_knots = |len: usize, degree: usize, what: &str| -> Result<KnotVector<f64>> {
        let line = params.line();
        let mut knots = Vec::with_capacity(len);
        for _ in 0..len {
            knots.push(params.real(what)?);
        }
        KnotVector::new(degree, knots).map_err(|e| {
            e.context(what)
                .context(format_args!("IGES line {line} (P)"))
        })
    };
    let knots_u = read_knots(ku, m1, "knots in u")?;
    let knots_v = read_knots(kv, m2, "knots in v")?;
    let weights_line = params.line();
    let mut weights = vec![0.0; count];
    for j in 0..nv {
        for i in 0..nu {
            weights[i * nv + j] = params.real("weight")?;
        }
    }
    let points_line = params.line();
    let mut points = vec![Vector3::zeros(); count];
    for j in 0..nv {
        for i in 0..nu {
            points[i * nv + j] = params.point("control point")?;
        }
    }
    let range_line = params.line();
    let u_range = (params.real("U(0)")?, params.real("U(1)")?);
    let v_range = (params.real("V(0)")?, params.real("V(1)")?);
    let mut patch = if polynomial && equal_weights(&weights) {
        Patch::Poly(
            Surface::new(knots_u, knots_v, points).map_err(at(Section::Parameter, points_line))?,
        )
    } else {
        let line = if weights.iter().all(|&w| w > 0.0) {
            points_line
        } else {
            weights_line
        };
        Patch::Rational(
            NurbsSurface3::new(knots_u, knots_v, points, weights)
                .map_err(at(Section::Parameter, line))?,
        )
    };
    for (direction, range, what) in [
        (Direction::U, u_range, "U(0), U(1)"),
        (Direction::V, v_range, "V(0), V(1)"),
    ] {
        let domain = match &patch {
            Patch::Poly(s) => s.domain(),
            Patch::Rational(s) => s.domain(),
        };
        let domain = if direction == Direction::U {
            domain.0
        } else {
            domain.1
        };
        if let Some(r) = range_within(domain, range, range_line, what)? {
            let restrict = at(Section::Parameter, range_line);
            patch = match patch {
                Patch::Poly(s) => Patch::Poly(restrict_surface(s, direction, r).map_err(restrict)?),
                Patch::Rational(s) => Patch::Rational(
                    NurbsSurface3::from_homogeneous(
                        restrict_surface(s.homogeneous().clone(), direction, r)
                            .map_err(restrict)?,
                    )
                    .map_err(at(Section::Parameter, range_line))?,
                ),
            };
        }
    }
    Ok(patch)
}

/// Entity 110 form 0, the line segment `P1 + t (P2 − P1)`, `t ∈ [0, 1]`.
pub(super) fn read_110(params: &mut Params) -> Result<Curve> {
    let line = params.line();
    let (p1, p2) = (params.point("start point")?, params.point("end point")?);
    let knots =
        KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0]).map_err(at(Section::Parameter, line))?;
    Ok(Curve::Poly(
        BSpline::new(knots, vec![p1, p2]).map_err(at(Section::Parameter, line))?,
    ))
}

/// Entity 100, the circular arc in the plane `z = ZT`, counterclockwise from the start
/// point to the end point (a full circle when they coincide), as exact rational quadratic
/// pieces on `[0, 1]`.
pub(super) fn read_100(params: &mut Params) -> Result<Curve> {
    let line = params.line();
    let zt = params.real("ZT")?;
    let center = Vector2::new(params.real("center")?, params.real("center")?);
    let start = Vector2::new(params.real("start point")?, params.real("start point")?);
    let end = Vector2::new(params.real("end point")?, params.real("end point")?);
    let (s, e) = (start - center, end - center);
    let radius = s.norm();
    if !(radius > 0.0) || !radius.is_finite() {
        return Err(parse_error(
            Section::Parameter,
            line,
            "circular arc (100) with a zero radius (start point at the center)",
        ));
    }
    let tolerance = 1e-7 * radius.max(1.0);
    if (e.norm() - radius).abs() > tolerance.max(1e-9 * radius)
        && (e.norm() - radius).abs() > 1e-6 * radius
    {
        return Err(parse_error(
            Section::Parameter,
            line,
            format!(
                "circular arc (100): the start and end points are at distances {} and {} from the center",
                radius,
                e.norm()
            ),
        ));
    }
    let a0 = s.y.atan2(s.x);
    let mut sweep = e.y.atan2(e.x) - a0;
    while sweep <= 0.0 {
        sweep += std::f64::consts::TAU;
    }
    if start == end {
        sweep = std::f64::consts::TAU;
    }
    let frame = Frame::new(
        Vector3::new(center.x, center.y, zt),
        Vector3::x(),
        Vector3::y(),
    )
    .map_err(at(Section::Parameter, line))?;
    Ok(Curve::Rational(
        NurbsCurve3::arc(&frame, radius, a0, sweep).map_err(at(Section::Parameter, line))?,
    ))
}

/// What reading one entity gives.
pub(super) enum Read {
    Curve(Curve),
    Patch(Patch),
    /// Not geometry this reader converts.
    Skipped,
}

impl File<'_> {
    /// Converts the entity `entry` (its own transformation applied); `depth` bounds the
    /// recursion through the curves of 120 and 122.
    pub(super) fn convert(&self, entry: &Entry, depth: usize) -> Result<(Read, Option<Params>)> {
        let read = match (entry.kind, entry.form) {
            (126, _) => {
                let mut p = self.params(entry)?;
                (Read::Curve(read_126(&mut p)?), Some(p))
            }
            (128, _) => {
                let mut p = self.params(entry)?;
                (Read::Patch(read_128(&mut p)?), Some(p))
            }
            (110, 0) => {
                let mut p = self.params(entry)?;
                (Read::Curve(read_110(&mut p)?), Some(p))
            }
            (100, _) => {
                let mut p = self.params(entry)?;
                (Read::Curve(read_100(&mut p)?), Some(p))
            }
            (120, _) if depth == 0 => {
                let mut p = self.params(entry)?;
                (self.read_120(&mut p, entry)?, Some(p))
            }
            (122, _) if depth == 0 => {
                let mut p = self.params(entry)?;
                (self.read_122(&mut p, entry)?, Some(p))
            }
            _ => (Read::Skipped, None),
        };
        let transform = match &read.0 {
            Read::Skipped => None,
            _ => self.transform(entry)?,
        };
        Ok(match read {
            (Read::Curve(c), p) => (Read::Curve(c.transformed(transform)), p),
            (Read::Patch(s), p) => (Read::Patch(s.transformed(transform)), p),
            (Read::Skipped, p) => (Read::Skipped, p),
        })
    }

    /// The curve an entity designates (with its transformation), if it converts.
    pub(super) fn curve_at(
        &self,
        params: &mut Params,
        from: &Entry,
        what: &str,
    ) -> Result<Option<Curve>> {
        let entry = self.pointed(params, from, what)?;
        Ok(match self.convert(entry, 1)?.0 {
            Read::Curve(c) => Some(c),
            _ => None,
        })
    }

    /// Entity 120, the surface of revolution of a generatrix about an axis (a 110) from
    /// angle `SA` to `TA`: `u` along the generatrix, `v ∈ [0, 1]` along the circles.
    pub(super) fn read_120(&self, params: &mut Params, entry: &Entry) -> Result<Read> {
        let axis_entry = self.pointed(params, entry, "axis pointer")?;
        let axis = match (axis_entry.kind, self.convert(axis_entry, 1)?.0) {
            (110, Read::Curve(Curve::Poly(line))) => line,
            _ => return Ok(Read::Skipped),
        };
        let Some(generatrix) = self.curve_at(params, entry, "generatrix pointer")? else {
            return Ok(Read::Skipped);
        };
        let line = params.line();
        let (sa, ta) = (params.real("start angle")?, params.real("terminate angle")?);
        let (p1, p2) = (axis.control_points()[0], axis.control_points()[1]);
        let axis = Axis::new(p1, p2 - p1).map_err(at(Section::Parameter, line))?;
        let mut sweep = ta - sa;
        let tau = std::f64::consts::TAU;
        if sweep > tau && sweep - tau <= 1e-12 * tau {
            sweep = tau;
        }
        let rotation = Rotation3::from_axis_angle(&Unit::new_unchecked(axis.direction()), sa);
        let origin = axis.point();
        let profile = generatrix
            .rational()
            .map_control_points(|p| origin + rotation * (p - origin));
        let surface = NurbsSurface3::revolution(&profile, &axis, sweep)
            .map_err(at(Section::Parameter, line))?;
        Ok(Read::Patch(Patch::Rational(surface)))
    }

    /// Entity 122, the tabulated cylinder: the directrix swept along the segment from its
    /// start point to `(LX, LY, LZ)`; `u` along the directrix, `v ∈ [0, 1]`.
    pub(super) fn read_122(&self, params: &mut Params, entry: &Entry) -> Result<Read> {
        let Some(directrix) = self.curve_at(params, entry, "directrix pointer")? else {
            return Ok(Read::Skipped);
        };
        let line = params.line();
        let end = params.point("terminate point")?;
        let error = at(Section::Parameter, line);
        Ok(Read::Patch(match directrix {
            Curve::Poly(c) => {
                let start = c.eval(c.domain().0).map_err(at(Section::Parameter, line))?;
                Patch::Poly(Surface::extrusion(&c, end - start).map_err(error)?)
            }
            Curve::Rational(c) => {
                let start = c.eval(c.domain().0).map_err(at(Section::Parameter, line))?;
                Patch::Rational(NurbsSurface3::extrusion(&c, end - start).map_err(error)?)
            }
        }))
    }
}
