//! IGES files written: the five sections in fixed columns, one 126 per curve and one 128
//! per surface, names as labels and name properties, numbers that read back to the same
//! `f64`.

use super::layout::{GLOBAL_WIDTH, PARAM_WIDTH};
use crate::real::real;
use crate::{Geometry, Item};
use nalgebra::{Vector2, Vector3};
use spline_core::{Error, ErrorKind, KnotVector, Result};
use std::fmt::Write as _;

/// A Hollerith string constant.
pub(super) fn hollerith(s: &str) -> String {
    format!("{}H{s}", s.len())
}

/// The parameters of one entity as text pieces (each written with its delimiter after).
pub(super) struct Entity {
    pub(super) kind: u32,
    pub(super) form: u32,
    pub(super) label: String,
    pub(super) params: Vec<String>,
}

/// Packs parameters into records of `width` columns: each parameter followed by its
/// delimiter, never split except a string longer than a record.
pub(super) fn pack(params: &[String], width: usize) -> Vec<String> {
    let mut records = Vec::new();
    let mut current = String::new();
    for (k, p) in params.iter().enumerate() {
        let piece = format!("{p}{}", if k + 1 == params.len() { ';' } else { ',' });
        if current.len() + piece.len() <= width {
            current.push_str(&piece);
            continue;
        }
        if piece.len() <= width {
            records.push(std::mem::take(&mut current));
            current = piece;
            continue;
        }
        // A long string: fill the records to their last column (the reader concatenates them).
        for c in piece.chars() {
            if current.len() == width {
                records.push(std::mem::take(&mut current));
            }
            current.push(c);
        }
    }
    if !current.is_empty() {
        records.push(current);
    }
    records
}

/// The parameters of a 126 from knots, control points (3-D), weights and flags.
pub(super) fn curve_params(
    knots: &KnotVector<f64>,
    points: &[Vector3<f64>],
    weights: Option<&[f64]>,
    planar: bool,
    closed: bool,
) -> Vec<String> {
    let n = points.len();
    let mut p = vec![
        "126".to_string(),
        (n - 1).to_string(),
        knots.degree().to_string(),
        u8::from(planar).to_string(),
        u8::from(closed).to_string(),
        u8::from(weights.is_none()).to_string(),
        "0".to_string(),
    ];
    p.extend(knots.knots().iter().map(|&u| real(u)));
    match weights {
        Some(w) => p.extend(w.iter().map(|&w| real(w))),
        None => p.extend(std::iter::repeat_n("1.0".to_string(), n)),
    }
    for q in points {
        p.extend(q.iter().map(|&x| real(x)));
    }
    let (a, b) = knots.domain();
    p.push(real(a));
    p.push(real(b));
    let normal = if planar { [0.0, 0.0, 1.0] } else { [0.0; 3] };
    p.extend(normal.iter().map(|&x| real(x)));
    p
}

/// The parameters of a 128 from a row-major net (written with the u index fastest).
pub(super) fn surface_params(
    knots_u: &KnotVector<f64>,
    knots_v: &KnotVector<f64>,
    points: &[Vector3<f64>],
    weights: Option<&[f64]>,
) -> Vec<String> {
    let (nu, nv) = (knots_u.num_basis(), knots_v.num_basis());
    let mut p = vec![
        "128".to_string(),
        (nu - 1).to_string(),
        (nv - 1).to_string(),
        knots_u.degree().to_string(),
        knots_v.degree().to_string(),
        "0".to_string(),
        "0".to_string(),
        u8::from(weights.is_none()).to_string(),
        "0".to_string(),
        "0".to_string(),
    ];
    p.extend(knots_u.knots().iter().map(|&u| real(u)));
    p.extend(knots_v.knots().iter().map(|&u| real(u)));
    for j in 0..nv {
        for i in 0..nu {
            p.push(weights.map_or_else(|| "1.0".to_string(), |w| real(w[i * nv + j])));
        }
    }
    for j in 0..nv {
        for i in 0..nu {
            p.extend(points[i * nv + j].iter().map(|&x| real(x)));
        }
    }
    for (a, b) in [knots_u.domain(), knots_v.domain()] {
        p.push(real(a));
        p.push(real(b));
    }
    p
}

pub(super) fn lift(p: &Vector2<f64>) -> Vector3<f64> {
    Vector3::new(p.x, p.y, 0.0)
}

/// The largest coordinate magnitude of an item's control points.
pub(super) fn max_coordinate(geometry: &Geometry) -> f64 {
    geometry.coordinates().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// The entity parameters of an item (the containers hold finite numbers only). Unclamped
/// geometry is clamped first (knots inserted at the ends of the domain: the same curve or
/// surface on the same parameters), since readers such as Open CASCADE's take the end knots
/// of a 126 or 128 as the ends of its domain.
pub(super) fn entity_params(item: &Item) -> Vec<String> {
    let clamped = match &item.geometry {
        Geometry::Curve2(c) => Geometry::Curve2(c.clamped()),
        Geometry::Curve3(c) => Geometry::Curve3(c.clamped()),
        Geometry::NurbsCurve2(c) => Geometry::NurbsCurve2(c.clamped()),
        Geometry::NurbsCurve3(c) => Geometry::NurbsCurve3(c.clamped()),
        Geometry::Surface(s) => Geometry::Surface(s.clamped()),
        Geometry::NurbsSurface(s) => Geometry::NurbsSurface(s.clamped()),
    };
    match &clamped {
        Geometry::Curve2(c) => {
            let points: Vec<_> = c.control_points().iter().map(lift).collect();
            let (a, b) = c.domain();
            let closed = matches!((c.eval(a), c.eval(b)), (Ok(x), Ok(y)) if x == y);
            curve_params(c.knots(), &points, None, true, closed)
        }
        Geometry::Curve3(c) => {
            let (a, b) = c.domain();
            let closed = matches!((c.eval(a), c.eval(b)), (Ok(x), Ok(y)) if x == y);
            curve_params(c.knots(), c.control_points(), None, false, closed)
        }
        Geometry::NurbsCurve2(c) => {
            let points: Vec<_> = c.control_points().iter().map(lift).collect();
            let (a, b) = c.domain();
            let closed = matches!((c.eval(a), c.eval(b)), (Ok(x), Ok(y)) if x == y);
            curve_params(c.knots(), &points, Some(c.weights()), true, closed)
        }
        Geometry::NurbsCurve3(c) => {
            let (a, b) = c.domain();
            let closed = matches!((c.eval(a), c.eval(b)), (Ok(x), Ok(y)) if x == y);
            curve_params(
                c.knots(),
                c.control_points(),
                Some(c.weights()),
                false,
                closed,
            )
        }
        Geometry::Surface(s) => surface_params(s.knots_u(), s.knots_v(), s.control_points(), None),
        Geometry::NurbsSurface(s) => surface_params(
            s.knots_u(),
            s.knots_v(),
            s.control_points(),
            Some(s.weights()),
        ),
    }
}

/// The date and time now (UTC) as `YYYYMMDD.HHNNSS`.
pub(super) fn timestamp() -> String {
    let seconds = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let days = i64::try_from(seconds / 86_400).unwrap_or(0);
    let rem = seconds % 86_400;
    // Civil date from days since 1970-01-01 (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}{month:02}{day:02}.{:02}{:02}{:02}",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// Writes items as an IGES 5.3 fixed-format ASCII file (see the [module
/// documentation](super)): one 126 per curve, one 128 per surface, a 406 form 15 name
/// property after each entity whose name is longer than the 8-column label.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for a name that is not printable ASCII (IGES files are
/// ASCII).
pub fn write_iges(items: &[Item]) -> Result<String> {
    let mut entities: Vec<Entity> = Vec::new();
    let mut max_coordinate = 0.0f64;
    for (index, item) in items.iter().enumerate() {
        if !item.name.bytes().all(|b| b.is_ascii_graphic() || b == b' ') {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "IGES writer: the name of item {index} ({:?}) is not printable ASCII",
                    item.name
                ),
            )
            .with_index(index));
        }
        let mut params = entity_params(item);
        max_coordinate = max_coordinate.max(self::max_coordinate(&item.geometry));
        let kind = if params[0] == "126" { 126 } else { 128 };
        let name = item.name.trim();
        let label: String = name.chars().take(8).collect();
        if name.len() > 8 {
            // The name property is the entity after this one.
            let pointer = 2 * (entities.len() + 1) + 1;
            params.extend(["0".to_string(), "1".to_string(), pointer.to_string()]);
        }
        params.remove(0);
        entities.push(Entity {
            kind,
            form: 0,
            label,
            params,
        });
        if name.len() > 8 {
            entities.push(Entity {
                kind: 406,
                form: 15,
                label: String::new(),
                params: vec!["1".to_string(), hollerith(name)],
            });
        }
    }
    let mut out = String::new();
    let record = |out: &mut String, data: &str, letter: char, seq: usize| {
        let _ = writeln!(out, "{data:<72}{letter}{seq:7}");
    };
    let start = "B-spline and NURBS geometry written by spline-io (IGES 5.3).";
    record(&mut out, start, 'S', 1);
    let date = timestamp();
    let global = [
        hollerith(","),
        hollerith(";"),
        hollerith("spline"),
        hollerith("spline.igs"),
        hollerith("spline-io"),
        hollerith("spline-io IGES 5.3"),
        "32".to_string(),
        "38".to_string(),
        "6".to_string(),
        "308".to_string(),
        "15".to_string(),
        hollerith("spline"),
        "1.0".to_string(),
        "2".to_string(),
        hollerith("MM"),
        "1".to_string(),
        "1.0".to_string(),
        hollerith(&date),
        "1.0E-7".to_string(),
        real(max_coordinate),
        hollerith("spline-io"),
        hollerith("spline-io"),
        "11".to_string(),
        "0".to_string(),
        hollerith(&date),
    ];
    let global_records = pack(&global, GLOBAL_WIDTH);
    for (k, r) in global_records.iter().enumerate() {
        record(&mut out, r, 'G', k + 1);
    }
    // Parameter Data first (the directory entries need its record numbers).
    let mut parameter = String::new();
    let mut directory = String::new();
    let mut p_count = 0;
    for (k, e) in entities.iter().enumerate() {
        let de = 2 * k + 1;
        let mut params = vec![e.kind.to_string()];
        params.extend(e.params.iter().cloned());
        let records = pack(&params, PARAM_WIDTH);
        let first = p_count + 1;
        for r in &records {
            p_count += 1;
            record(&mut parameter, &format!("{r:<64}{de:8}"), 'P', p_count);
        }
        let status = if e.kind == 406 {
            "00010000"
        } else {
            "00000000"
        };
        let line1 = format!(
            "{:8}{first:8}{:8}{:8}{:8}{:8}{:8}{:8}{status}",
            e.kind, 0, 0, 0, 0, 0, 0
        );
        let line2 = format!(
            "{:8}{:8}{:8}{:8}{:8}{:8}{:8}{:>8}{:8}",
            e.kind,
            0,
            0,
            records.len(),
            e.form,
            "",
            "",
            e.label,
            0
        );
        record(&mut directory, &line1, 'D', de);
        record(&mut directory, &line2, 'D', de + 1);
    }
    out.push_str(&directory);
    out.push_str(&parameter);
    let terminate = format!(
        "S{:7}G{:7}D{:7}P{:7}",
        1,
        global_records.len(),
        2 * entities.len(),
        p_count
    );
    record(&mut out, &terminate, 'T', 1);
    Ok(out)
}
