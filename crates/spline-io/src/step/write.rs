//! STEP files written: an AP214 product with its geometry in geometric sets, B-splines as
//! `_WITH_KNOTS` entities (rational ones as complex instances), numbers that read back to the
//! same `f64`.

use crate::real::real;
use crate::{Geometry, Item};
use nalgebra::{Vector2, Vector3};
use spline_core::{Error, KnotVector, Result};
use std::fmt::Write as _;

/// A STEP string: quotes doubled, backslashes doubled, characters outside printable ASCII
/// as `\X2\…\X0\`.
fn string(s: &str) -> String {
    let mut out = String::from("'");
    for c in s.chars() {
        match c {
            '\'' => out.push_str("''"),
            '\\' => out.push_str("\\\\"),
            ' '..='~' => out.push(c),
            _ => {
                out.push_str("\\X2\\");
                let mut units = [0u16; 2];
                for u in c.encode_utf16(&mut units) {
                    let _ = write!(out, "{u:04X}");
                }
                out.push_str("\\X0\\");
            }
        }
    }
    out.push('\'');
    out
}

/// Writes instances, numbering them.
struct Writer {
    text: String,
    next: u64,
}

impl Writer {
    fn add(&mut self, body: &str) -> u64 {
        let id = self.next;
        self.next += 1;
        let _ = writeln!(self.text, "#{id} = {body};");
        id
    }

    fn point(&mut self, coords: &[f64]) -> u64 {
        let c: Vec<String> = coords.iter().map(|&x| real(x)).collect();
        self.add(&format!("CARTESIAN_POINT('',({}))", c.join(",")))
    }

    fn refs(ids: &[u64]) -> String {
        let r: Vec<String> = ids.iter().map(|i| format!("#{i}")).collect();
        format!("({})", r.join(","))
    }
}

/// Distinct knots and their multiplicities.
fn compress(knots: &KnotVector<f64>) -> (String, String) {
    let mut values: Vec<f64> = Vec::new();
    let mut counts: Vec<usize> = Vec::new();
    for &k in knots.knots() {
        if values.last() == Some(&k) {
            *counts.last_mut().expect("a count per value") += 1;
        } else {
            values.push(k);
            counts.push(1);
        }
    }
    let c: Vec<String> = counts.iter().map(ToString::to_string).collect();
    let v: Vec<String> = values.iter().map(|&x| real(x)).collect();
    (format!("({})", c.join(",")), format!("({})", v.join(",")))
}

fn write_curve(
    w: &mut Writer,
    name: &str,
    knots: &KnotVector<f64>,
    points: &[Vec<f64>],
    weights: Option<&[f64]>,
) -> u64 {
    let ids: Vec<u64> = points.iter().map(|p| w.point(p)).collect();
    let (mults, values) = compress(knots);
    let p = knots.degree();
    let (a, b) = knots.domain();
    let closed = points.first() == points.last() && points.len() > 1 && a < b;
    let flag = if closed { ".T." } else { ".F." };
    match weights {
        None => w.add(&format!(
            "B_SPLINE_CURVE_WITH_KNOTS({},{p},{},.UNSPECIFIED.,{flag},.U.,{mults},{values},.UNSPECIFIED.)",
            string(name),
            Writer::refs(&ids)
        )),
        Some(weights) => {
            let ws: Vec<String> = weights.iter().map(|&x| real(x)).collect();
            w.add(&format!(
                "( BOUNDED_CURVE() B_SPLINE_CURVE({p},{},.UNSPECIFIED.,{flag},.U.) B_SPLINE_CURVE_WITH_KNOTS({mults},{values},.UNSPECIFIED.) CURVE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE(({})) REPRESENTATION_ITEM({}) )",
                Writer::refs(&ids),
                ws.join(","),
                string(name)
            ))
        }
    }
}

fn write_surface(
    w: &mut Writer,
    name: &str,
    (ku, kv): (&KnotVector<f64>, &KnotVector<f64>),
    points: &[Vector3<f64>],
    weights: Option<&[f64]>,
) -> u64 {
    let (nu, nv) = (ku.num_basis(), kv.num_basis());
    let mut rows = Vec::with_capacity(nu);
    for i in 0..nu {
        let ids: Vec<u64> = (0..nv)
            .map(|j| w.point(points[i * nv + j].as_slice()))
            .collect();
        rows.push(Writer::refs(&ids));
    }
    let net = format!("({})", rows.join(","));
    let (mu, vu) = compress(ku);
    let (mv, vv) = compress(kv);
    let (pu, pv) = (ku.degree(), kv.degree());
    match weights {
        None => w.add(&format!(
            "B_SPLINE_SURFACE_WITH_KNOTS({},{pu},{pv},{net},.UNSPECIFIED.,.F.,.F.,.U.,{mu},{mv},{vu},{vv},.UNSPECIFIED.)",
            string(name)
        )),
        Some(weights) => {
            let wr: Vec<String> = (0..nu)
                .map(|i| {
                    let r: Vec<String> = (0..nv).map(|j| real(weights[i * nv + j])).collect();
                    format!("({})", r.join(","))
                })
                .collect();
            w.add(&format!(
                "( BOUNDED_SURFACE() B_SPLINE_SURFACE({pu},{pv},{net},.UNSPECIFIED.,.F.,.F.,.U.) B_SPLINE_SURFACE_WITH_KNOTS({mu},{mv},{vu},{vv},.UNSPECIFIED.) GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE(({})) REPRESENTATION_ITEM({}) SURFACE() )",
                wr.join(","),
                string(name)
            ))
        }
    }
}

/// An AP214 file holding the items; see the [module](super) documentation.
///
/// # Errors
/// [`spline_core::ErrorKind::NonFinite`] if a coordinate, weight or knot is not finite (the containers
/// hold finite numbers only, so this does not happen for items built by this library).
pub fn write_step(items: &[Item]) -> Result<String> {
    let mut w = Writer {
        text: String::new(),
        next: 1,
    };
    let header = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('spline: B-spline and NURBS geometry'),'2;1');\nFILE_NAME('','',(''),(''),'spline','spline','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n";
    let app = w.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')");
    w.add(&format!(
        "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"
    ));
    let product_context = w.add(&format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
    let product = w.add(&format!(
        "PRODUCT('spline','spline','',(#{product_context}))"
    ));
    w.add(&format!(
        "PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{product}))"
    ));
    let formation = w.add(&format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"));
    let definition_context = w.add(&format!(
        "PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"
    ));
    let definition = w.add(&format!(
        "PRODUCT_DEFINITION('design','',#{formation},#{definition_context})"
    ));
    let shape = w.add(&format!("PRODUCT_DEFINITION_SHAPE('','',#{definition})"));
    let length = w.add("( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )");
    let angle = w.add("( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) )");
    let solid = w.add("( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() )");
    let uncertainty = w.add(&format!(
        "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#{length},'distance_accuracy_value','confusion accuracy')"
    ));
    let context = w.add(&format!(
        "( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{uncertainty})) GLOBAL_UNIT_ASSIGNED_CONTEXT((#{length},#{angle},#{solid})) REPRESENTATION_CONTEXT('spline','3D') )"
    ));
    let mut curves = Vec::new();
    let mut surfaces = Vec::new();
    for item in items {
        let name = item.name.as_str();
        // A 2-D curve is written in the plane z = 0 of the 3-D context (CAD systems read
        // 3-D geometry only; Open CASCADE skips 2-D points there).
        let v2 = |p: &Vector2<f64>| vec![p.x, p.y, 0.0];
        let v3 = |p: &Vector3<f64>| vec![p.x, p.y, p.z];
        check_finite(&item.geometry)?;
        let (knots, points, weights): (_, Vec<_>, _) = match &item.geometry {
            Geometry::Curve2(c) => (c.knots(), c.control_points().iter().map(v2).collect(), None),
            Geometry::Curve3(c) => (c.knots(), c.control_points().iter().map(v3).collect(), None),
            Geometry::NurbsCurve2(c) => {
                let points = c.control_points().iter().map(v2).collect();
                (c.knots(), points, Some(c.weights()))
            }
            Geometry::NurbsCurve3(c) => {
                let points = c.control_points().iter().map(v3).collect();
                (c.knots(), points, Some(c.weights()))
            }
            Geometry::Surface(s) => {
                let knots = (s.knots_u(), s.knots_v());
                surfaces.push(write_surface(&mut w, name, knots, s.control_points(), None));
                continue;
            }
            Geometry::NurbsSurface(s) => {
                let (knots, weights) = ((s.knots_u(), s.knots_v()), Some(s.weights()));
                surfaces.push(write_surface(
                    &mut w,
                    name,
                    knots,
                    s.control_points(),
                    weights,
                ));
                continue;
            }
        };
        curves.push(write_curve(&mut w, name, knots, &points, weights));
    }
    let mut representations = Vec::new();
    if !curves.is_empty() {
        let set = w.add(&format!(
            "GEOMETRIC_CURVE_SET('',{})",
            Writer::refs(&curves)
        ));
        representations.push(w.add(&format!(
            "GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION('',(#{set}),#{context})"
        )));
    }
    if !surfaces.is_empty() {
        let set = w.add(&format!("GEOMETRIC_SET('',{})", Writer::refs(&surfaces)));
        representations.push(w.add(&format!(
            "GEOMETRICALLY_BOUNDED_SURFACE_SHAPE_REPRESENTATION('',(#{set}),#{context})"
        )));
    }
    for r in representations {
        w.add(&format!("SHAPE_DEFINITION_REPRESENTATION(#{shape},#{r})"));
    }
    Ok(format!("{header}{}ENDSEC;\nEND-ISO-10303-21;\n", w.text))
}

fn check_finite(geometry: &Geometry) -> Result<()> {
    let ok = geometry.coordinates().all(f64::is_finite);
    if ok {
        Ok(())
    } else {
        Err(Error::non_finite("a control point written to STEP"))
    }
}
