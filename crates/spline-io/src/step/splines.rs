//! B-spline curves and surfaces of every form (`_WITH_KNOTS`, `UNIFORM_`, `QUASI_UNIFORM_`,
//! `BEZIER_`), simple or complex instances, rational or not, turned into containers.

use super::instance::{Instance, Param, error_at, integer, list, number, text};
use super::reader::Reader;
use crate::Geometry;
use nalgebra::{SVector, Vector3};
use spline_core::{Error, KnotVector, Result};
use spline_geom::{BSpline, NurbsCurve, NurbsSurface, Surface};

/// The knots of a spline from the `_WITH_KNOTS` multiplicities and values, or implied by the
/// form (`UNIFORM_`, `QUASI_UNIFORM_`, `BEZIER_`) for `count` control points.
fn knots_of(form: KnotForm<'_>, degree: usize, count: usize, line: usize) -> Result<Vec<f64>> {
    #[allow(clippy::cast_precision_loss)]
    let f = |i: usize| i as f64;
    match form {
        KnotForm::Explicit(multiplicities, values) => {
            if multiplicities.len() != values.len() {
                return Err(error_at(
                    line,
                    format!(
                        "{} knot multiplicities for {} knots",
                        multiplicities.len(),
                        values.len()
                    ),
                ));
            }
            let mut knots = Vec::new();
            for (m, k) in multiplicities.iter().zip(values) {
                let m = integer(m)
                    .and_then(|m| usize::try_from(m).ok())
                    .filter(|&m| m >= 1 && m <= degree + 1)
                    .ok_or_else(|| {
                        error_at(
                            line,
                            format!("a knot multiplicity must be 1 to {}", degree + 1),
                        )
                    })?;
                let k = number(k).ok_or_else(|| error_at(line, "a knot is not a number"))?;
                if knots.len() + m > count + degree + 1 {
                    return Err(error_at(
                        line,
                        format!(
                            "the multiplicities add up to more than the {} knots of {count} control points of degree {degree}",
                            count + degree + 1
                        ),
                    ));
                }
                knots.extend(std::iter::repeat_n(k, m));
            }
            Ok(knots)
        }
        // ISO 10303-42: uniform knots are -p, -p + 1, …; quasi-uniform ones 0, …, with the
        // ends repeated p + 1 times; Bézier ones 0, 1, … with every break repeated p times.
        KnotForm::Uniform => Ok((0..count + degree + 1).map(|i| f(i) - f(degree)).collect()),
        KnotForm::QuasiUniform => {
            let interior = count.saturating_sub(degree + 1);
            let mut k = vec![0.0; degree + 1];
            k.extend((1..=interior).map(f));
            k.extend(std::iter::repeat_n(f(interior + 1), degree + 1));
            Ok(k)
        }
        KnotForm::Bezier => {
            if degree == 0 || (count - 1) % degree != 0 {
                return Err(error_at(
                    line,
                    format!(
                        "a Bézier curve of degree {degree} needs a multiple of {degree} plus one control points, got {count}"
                    ),
                ));
            }
            let segments = (count - 1) / degree;
            let mut knots = vec![0.0; degree + 1];
            for s in 1..segments {
                knots.extend(std::iter::repeat_n(f(s), degree));
            }
            knots.extend(std::iter::repeat_n(f(segments), degree + 1));
            Ok(knots)
        }
    }
}

#[derive(Clone, Copy)]
enum KnotForm<'a> {
    Explicit(&'a [Param], &'a [Param]),
    Uniform,
    QuasiUniform,
    Bezier,
}

/// The curve entities whose knots their form implies, with the form.
const CURVE_FORMS: [(&str, KnotForm<'static>); 3] = [
    ("BEZIER_CURVE", KnotForm::Bezier),
    ("UNIFORM_CURVE", KnotForm::Uniform),
    ("QUASI_UNIFORM_CURVE", KnotForm::QuasiUniform),
];

/// The surface entities whose knots their form implies, with the form.
const SURFACE_FORMS: [(&str, KnotForm<'static>); 3] = [
    ("BEZIER_SURFACE", KnotForm::Bezier),
    ("UNIFORM_SURFACE", KnotForm::Uniform),
    ("QUASI_UNIFORM_SURFACE", KnotForm::QuasiUniform),
];

/// The first of `forms` whose record the complex instance has: its form and entity.
fn implied_form(
    instance: &Instance,
    forms: &[(&'static str, KnotForm<'static>)],
) -> Option<(KnotForm<'static>, &'static str)> {
    forms
        .iter()
        .find(|(entity, _)| instance.record(entity).is_some())
        .map(|&(entity, form)| (form, entity))
}

fn degree_of(p: &Param, line: usize) -> Result<usize> {
    integer(p)
        .and_then(|d| usize::try_from(d).ok())
        .filter(|d| (1..=spline_core::MAX_DEGREE).contains(d))
        .ok_or_else(|| {
            error_at(
                line,
                format!("a degree must be 1 to {}", spline_core::MAX_DEGREE),
            )
        })
}

/// The error of a record `what` whose parameters are not those of its entity.
fn wrong_parameters(line: usize, what: &str) -> Error {
    error_at(line, format!("{what} has the wrong parameters"))
}

/// The weights of the `RATIONAL_B_SPLINE_CURVE` or `_SURFACE` record (`entity`) of a complex
/// instance, `None` without one.
fn rational_weights<'a>(instance: &'a Instance, entity: &str) -> Result<Option<&'a [Param]>> {
    match instance.record(entity) {
        Some([Param::List(w)] | [_, Param::List(w)]) => Ok(Some(w.as_slice())),
        Some(_) => Err(wrong_parameters(instance.line, entity)),
        None => Ok(None),
    }
}

/// The name of a complex instance: its `REPRESENTATION_ITEM` record's (empty without one).
fn item_name(instance: &Instance) -> String {
    instance
        .record("REPRESENTATION_ITEM")
        .and_then(|p| p.first())
        .map(text)
        .unwrap_or_default()
}

/// What a B-spline instance holds before it becomes a container.
pub(super) struct CurveParts<'a> {
    pub(super) name: String,
    degree: usize,
    points: &'a [Param],
    knots: KnotForm<'a>,
    weights: Option<&'a [Param]>,
    pub(super) entity: &'static str,
}

pub(super) fn curve_parts(instance: &Instance) -> Result<Option<CurveParts<'_>>> {
    let line = instance.line;
    let bad = |what: &str| wrong_parameters(line, what);
    let weights = rational_weights(instance, "RATIONAL_B_SPLINE_CURVE")?;
    // The simple instance: every attribute in one record.
    if let Some(p) = instance
        .record("B_SPLINE_CURVE_WITH_KNOTS")
        .filter(|p| p.len() == 9)
    {
        let (Some(points), Some(m), Some(k)) = (list(&p[2]), list(&p[6]), list(&p[7])) else {
            return Err(bad("B_SPLINE_CURVE_WITH_KNOTS"));
        };
        return Ok(Some(CurveParts {
            name: text(&p[0]),
            degree: degree_of(&p[1], line)?,
            points,
            knots: KnotForm::Explicit(m, k),
            weights,
            entity: "B_SPLINE_CURVE_WITH_KNOTS",
        }));
    }
    for (simple, form) in CURVE_FORMS {
        if let Some(p) = instance.record(simple).filter(|p| p.len() == 6) {
            let Some(points) = list(&p[2]) else {
                return Err(bad(simple));
            };
            return Ok(Some(CurveParts {
                name: text(&p[0]),
                degree: degree_of(&p[1], line)?,
                points,
                knots: form,
                weights,
                entity: simple,
            }));
        }
    }
    // The complex instance: B_SPLINE_CURVE holds degree and points, the subtype the knots.
    let Some(base) = instance.record("B_SPLINE_CURVE") else {
        return Ok(None);
    };
    let (degree, points) = match base {
        [d, Param::List(points), ..] if base.len() == 5 => (d, points.as_slice()),
        [_, d, Param::List(points), ..] if base.len() == 6 => (d, points.as_slice()),
        _ => return Err(bad("B_SPLINE_CURVE")),
    };
    let (knots, entity) = if let Some(k) = instance.record("B_SPLINE_CURVE_WITH_KNOTS") {
        match k {
            [Param::List(m), Param::List(v), _] => {
                (KnotForm::Explicit(m, v), "B_SPLINE_CURVE_WITH_KNOTS")
            }
            _ => return Err(bad("B_SPLINE_CURVE_WITH_KNOTS")),
        }
    } else if let Some(implied) = implied_form(instance, &CURVE_FORMS) {
        implied
    } else {
        return Err(error_at(
            line,
            "a B_SPLINE_CURVE without knots (no _WITH_KNOTS, UNIFORM_, QUASI_UNIFORM_ or BEZIER_ form)",
        ));
    };
    let name = item_name(instance);
    Ok(Some(CurveParts {
        name,
        degree: degree_of(degree, line)?,
        points,
        knots,
        weights,
        entity,
    }))
}

pub(super) fn read_curve(
    reader: &Reader<'_>,
    instance: &Instance,
    parts: &CurveParts<'_>,
) -> Result<Geometry> {
    let line = instance.line;
    let points: Vec<Vec<f64>> = parts
        .points
        .iter()
        .map(|p| reader.point(p, line))
        .collect::<Result<_>>()?;
    let dim = points.first().map_or(3, Vec::len);
    if points.iter().any(|p| p.len() != dim) {
        return Err(error_at(
            line,
            "the control points have different dimensions",
        ));
    }
    let knots = knots_of(parts.knots, parts.degree, points.len(), line)?;
    let knots = KnotVector::new(parts.degree, knots).map_err(|e| error_at(line, e))?;
    let weights = parts
        .weights
        .map(|w| {
            w.iter()
                .map(|x| number(x).ok_or_else(|| error_at(line, "a weight is not a number")))
                .collect::<Result<Vec<f64>>>()
        })
        .transpose()?;
    let geometry = if dim == 2 {
        curve(
            knots,
            &points,
            weights,
            Geometry::Curve2,
            Geometry::NurbsCurve2,
        )
    } else {
        curve(
            knots,
            &points,
            weights,
            Geometry::Curve3,
            Geometry::NurbsCurve3,
        )
    };
    geometry.map_err(|e| error_at(line, e))
}

/// The curve on `knots` through the first `D` coordinates of every point, as
/// `polynomial` or, with weights, `rational`.
fn curve<const D: usize>(
    knots: KnotVector<f64>,
    points: &[Vec<f64>],
    weights: Option<Vec<f64>>,
    polynomial: fn(BSpline<f64, SVector<f64, D>>) -> Geometry,
    rational: fn(NurbsCurve<f64, D>) -> Geometry,
) -> Result<Geometry> {
    let points = points
        .iter()
        .map(|p| SVector::from_column_slice(&p[..D]))
        .collect();
    Ok(match weights {
        None => polynomial(BSpline::new(knots, points)?),
        Some(w) => rational(NurbsCurve::new(knots, points, w)?),
    })
}

pub(super) fn read_surface(
    reader: &Reader<'_>,
    instance: &Instance,
) -> Result<Option<(Geometry, String, &'static str)>> {
    let line = instance.line;
    let bad = |what: &str| wrong_parameters(line, what);
    let weights = rational_weights(instance, "RATIONAL_B_SPLINE_SURFACE")?;
    type Knots<'b> = (KnotForm<'b>, KnotForm<'b>);
    let (name, du, dv, net, knots, entity): (
        String,
        &Param,
        &Param,
        &[Param],
        Knots<'_>,
        &'static str,
    ) = if let Some(p) = instance
        .record("B_SPLINE_SURFACE_WITH_KNOTS")
        .filter(|p| p.len() == 13)
    {
        let (Some(net), Some(mu), Some(mv), Some(ku), Some(kv)) = (
            list(&p[3]),
            list(&p[8]),
            list(&p[9]),
            list(&p[10]),
            list(&p[11]),
        ) else {
            return Err(bad("B_SPLINE_SURFACE_WITH_KNOTS"));
        };
        (
            text(&p[0]),
            &p[1],
            &p[2],
            net,
            (KnotForm::Explicit(mu, ku), KnotForm::Explicit(mv, kv)),
            "B_SPLINE_SURFACE_WITH_KNOTS",
        )
    } else if let Some((simple, p, form)) = SURFACE_FORMS.into_iter().find_map(|(n, f)| {
        instance
            .record(n)
            .filter(|p| p.len() == 8)
            .map(|p| (n, p, f))
    }) {
        let Some(net) = list(&p[3]) else {
            return Err(bad(simple));
        };
        (text(&p[0]), &p[1], &p[2], net, (form, form), simple)
    } else if let Some(base) = instance.record("B_SPLINE_SURFACE") {
        let (du, dv, net) = match base {
            [du, dv, Param::List(net), ..] if base.len() == 7 => (du, dv, net.as_slice()),
            [_, du, dv, Param::List(net), ..] if base.len() == 8 => (du, dv, net.as_slice()),
            _ => return Err(bad("B_SPLINE_SURFACE")),
        };
        let (knots, entity) = if let Some(k) = instance.record("B_SPLINE_SURFACE_WITH_KNOTS") {
            match k {
                [
                    Param::List(mu),
                    Param::List(mv),
                    Param::List(ku),
                    Param::List(kv),
                    _,
                ] => (
                    (KnotForm::Explicit(mu, ku), KnotForm::Explicit(mv, kv)),
                    "B_SPLINE_SURFACE_WITH_KNOTS",
                ),
                _ => return Err(bad("B_SPLINE_SURFACE_WITH_KNOTS")),
            }
        } else if let Some((form, implied)) = implied_form(instance, &SURFACE_FORMS) {
            ((form, form), implied)
        } else {
            return Err(error_at(line, "a B_SPLINE_SURFACE without knots"));
        };
        let name = item_name(instance);
        (name, du, dv, net, knots, entity)
    } else {
        return Ok(None);
    };
    let (du, dv) = (degree_of(du, line)?, degree_of(dv, line)?);
    let mut rows: Vec<Vec<Vector3<f64>>> = Vec::with_capacity(net.len());
    for row in net {
        let row =
            list(row).ok_or_else(|| error_at(line, "the control net is not a list of lists"))?;
        rows.push(
            row.iter()
                .map(|p| {
                    let c = reader.point(p, line)?;
                    if c.len() == 3 {
                        Ok(Vector3::new(c[0], c[1], c[2]))
                    } else {
                        Err(error_at(
                            line,
                            "a surface's control points need 3 coordinates",
                        ))
                    }
                })
                .collect::<Result<_>>()?,
        );
    }
    let (nu, nv) = (rows.len(), rows.first().map_or(0, Vec::len));
    if nu == 0 || rows.iter().any(|r| r.len() != nv) {
        return Err(error_at(
            line,
            "the rows of the control net differ in length",
        ));
    }
    let ku =
        KnotVector::new(du, knots_of(knots.0, du, nu, line)?).map_err(|e| error_at(line, e))?;
    let kv =
        KnotVector::new(dv, knots_of(knots.1, dv, nv, line)?).map_err(|e| error_at(line, e))?;
    let context = |e: Error| error_at(line, e);
    let geometry = match weights {
        None => Geometry::Surface(Surface::from_net(ku, kv, rows).map_err(context)?),
        Some(w) => {
            if w.len() != nu {
                return Err(error_at(
                    line,
                    format!(
                        "{} rows of weights for {nu} rows of control points",
                        w.len()
                    ),
                ));
            }
            let w: Vec<Vec<f64>> = w
                .iter()
                .map(|r| {
                    list(r)
                        .ok_or_else(|| error_at(line, "the weights are not a list of lists"))?
                        .iter()
                        .map(|x| {
                            number(x).ok_or_else(|| error_at(line, "a weight is not a number"))
                        })
                        .collect()
                })
                .collect::<Result<_>>()?;
            Geometry::NurbsSurface(NurbsSurface::from_net(ku, kv, rows, w).map_err(context)?)
        }
    };
    Ok(Some((geometry, name, entity)))
}
