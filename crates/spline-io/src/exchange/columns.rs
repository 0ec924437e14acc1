//! scipy's spline objects in the exchange format: a [`ColumnSpline`] as a curve record (its
//! columns the coordinates), an [`NdSpline`] as `{"degree": [k…], "knots": [[…]…],
//! "coefficients": …}` with the coefficients nested one array level per dimension, the
//! leaves numbers or points.

use super::decode::{deserialize, json_kind};
use serde_json::{Value, json};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::{ColumnSpline, NdSpline};

/// The record of a spline of columns, `{"control_points", "degree", "knots"}` (the keys
/// sorted: a JSON value), with the rows its knots need (FITPACK's padding dropped).
#[must_use]
pub fn columns_to_value(s: &ColumnSpline) -> Value {
    let m = s.columns();
    let rows: Vec<&[f64]> = s.coefficients()[..s.num_basis() * m]
        .chunks_exact(m)
        .collect();
    json!({"degree": s.degree(), "knots": s.knots(), "control_points": rows})
}

/// The record of an N-dimensional spline, `{"coefficients", "degree", "knots"}` (the keys
/// sorted: a JSON value), the coefficients nested by [`nest`].
#[must_use]
pub fn nd_to_value(s: &NdSpline) -> Value {
    let knots: Vec<&[f64]> = s
        .knot_vectors()
        .iter()
        .map(spline_core::KnotVector::knots)
        .collect();
    let coefficients = nest(s.coefficients(), s.shape(), s.columns());
    json!({"degree": s.degrees(), "knots": knots, "coefficients": coefficients})
}

/// An N-dimensional spline from its record; the coefficients may also be called
/// `"control_points"`, so a surface record without weights reads too.
///
/// # Errors
/// [`ErrorKind::Parse`] for a degree or knots that are not arrays of the right kind
/// (`malformed degree: …`), without coefficients or for coefficients that are not a regular
/// nested array ([`nested_array`]); the errors of [`NdSpline::new`].
pub fn nd_from_value(value: &Value) -> Result<NdSpline> {
    let degree: Vec<usize> = deserialize(
        "degree",
        value.get("degree").cloned().unwrap_or(Value::Null),
    )?;
    let knots: Vec<Vec<f64>> =
        deserialize("knots", value.get("knots").cloned().unwrap_or(Value::Null))?;
    let coefficients = value
        .get("coefficients")
        .or_else(|| value.get("control_points"))
        .ok_or_else(|| {
            Error::new(
                ErrorKind::Parse,
                "an N-dimensional spline needs \"degree\", \"knots\" and \"coefficients\"",
            )
        })?;
    let (_, m, c) = nested_array(coefficients, degree.len(), "coefficients")?;
    NdSpline::new(knots, c, &degree, m, true)
}

/// Reads arrays nested `depth` levels deep whose leaves are numbers or arrays of numbers
/// (points of `m` numbers, `m` taken from the first): the shape, `m` (1 for numbers) and
/// the values row-major.
///
/// ```
/// use serde_json::json;
/// let (shape, m, values) =
///     spline_io::exchange::nested_array(&json!([[[1, 2], [3, 4]]]), 2, "values")?;
/// assert_eq!((shape, m, values), (vec![1, 2], 2, vec![1.0, 2.0, 3.0, 4.0]));
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::Parse`] (the message starts with `what`) for a level that is not an array
/// or is empty (with the level as [`Error::index`]), or an array that is not regular (rows
/// of different lengths, points of different sizes, leaves that are not numbers).
pub fn nested_array(
    value: &Value,
    depth: usize,
    what: &str,
) -> Result<(Vec<usize>, usize, Vec<f64>)> {
    let bad = |detail: String| Error::new(ErrorKind::Parse, format!("{what}: {detail}"));
    let mut shape = Vec::with_capacity(depth);
    let mut level = value;
    for d in 0..depth {
        let items = level.as_array().ok_or_else(|| {
            bad(format!("level {d} is {}, not an array", json_kind(level))).with_index(d)
        })?;
        let first = items
            .first()
            .ok_or_else(|| bad(format!("level {d} is empty")).with_index(d))?;
        shape.push(items.len());
        level = first;
    }
    let columns = match level {
        Value::Array(point) => point.len(),
        _ => 1,
    };
    let mut out = Vec::new();
    if !walk(value, 0, &shape, columns, &mut out) {
        return Err(bad(format!(
            "not a regular array of shape {shape:?} of {}",
            if columns == 1 {
                "numbers".to_string()
            } else {
                format!("points of {columns} numbers")
            }
        )));
    }
    Ok((shape, columns, out))
}

/// Appends the leaves of `v` (at level `d` of `shape`, points of `m` numbers) to `out`;
/// `false` when the array is not regular.
fn walk(v: &Value, d: usize, shape: &[usize], m: usize, out: &mut Vec<f64>) -> bool {
    if d == shape.len() {
        return match v {
            Value::Number(x) => {
                m == 1
                    && x.as_f64().is_some_and(|x| {
                        out.push(x);
                        true
                    })
            }
            Value::Array(p) if p.len() == m => p.iter().all(|x| {
                x.as_f64().is_some_and(|x| {
                    out.push(x);
                    true
                })
            }),
            _ => false,
        };
    }
    v.as_array()
        .is_some_and(|a| a.len() == shape[d] && a.iter().all(|x| walk(x, d + 1, shape, m, out)))
}

/// Nests row-major values into arrays of the given shape with points of `m` numbers (bare
/// numbers for `m = 1`); the inverse of [`nested_array`].
///
/// # Panics
/// If `values` holds fewer than `m` times the product of `shape` numbers.
#[must_use]
pub fn nest(values: &[f64], shape: &[usize], m: usize) -> Value {
    match shape.split_first() {
        None if m == 1 => json!(values[0]),
        None => json!(values[..m]),
        Some((&n, rest)) => {
            let size = rest.iter().product::<usize>() * m;
            Value::Array(
                (0..n)
                    .map(|i| nest(&values[i * size..(i + 1) * size], rest, m))
                    .collect(),
            )
        }
    }
}
