//! Point files: a JSON array of arrays (feature `serde`), or text with one point per line
//! whose coordinates are separated by whitespace or commas. The tokens of a line are shared
//! with the airfoil reader ([`crate::airfoil`]).

use spline_core::{Error, ErrorKind, Result};

/// Parses a point file: a JSON array of arrays, or text with one point per line whose
/// coordinates are separated by whitespace or commas. Lines starting with `#` and lines
/// that are not all numbers (headers, notes, placeholders such as `......` in some UIUC
/// airfoil files) are skipped; a number in parentheses, `(0.0022)`, is read as the number.
///
/// ```
/// let points = spline_io::points::parse_points("NACA 0012\n1.0 0.0\n0.5, 0.06\n# note\n0 0")?;
/// assert_eq!(points, vec![vec![1.0, 0.0], vec![0.5, 0.06], vec![0.0, 0.0]]);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::Parse`] for malformed JSON (and, without the feature `serde`, for any JSON);
/// [`ErrorKind::DimensionMismatch`] if points differ in dimension (the message names the
/// line); [`ErrorKind::NonFinite`]; [`ErrorKind::TooFewPoints`] if no point was found.
pub fn parse_points(text: &str) -> Result<Vec<Vec<f64>>> {
    let points: Vec<(usize, Vec<f64>)> = if text.trim_start().starts_with('[') {
        json_rows(text)?
            .into_iter()
            .enumerate()
            .map(|(i, r)| (i + 1, r))
            .collect()
    } else {
        text.lines()
            .enumerate()
            .filter_map(|(i, line)| {
                let line = line.trim();
                if line.is_empty() || line.starts_with('#') {
                    return None;
                }
                numbers(&tokens(line)).map(|v| (i + 1, v))
            })
            .collect()
    };
    let Some((_, first)) = points.first() else {
        return Err(Error::new(ErrorKind::TooFewPoints, "no points found"));
    };
    let d = first.len();
    for (line, p) in &points {
        if p.len() != d || d == 0 {
            return Err(Error::new(
                ErrorKind::DimensionMismatch,
                format!(
                    "point on line {line} has {} coordinates, the first point has {d}",
                    p.len()
                ),
            ));
        }
        if p.iter().any(|x| !x.is_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("point on line {line} is not finite"),
            ));
        }
    }
    Ok(points.into_iter().map(|(_, p)| p).collect())
}

/// The rows of a JSON array of number arrays.
#[cfg(feature = "serde")]
fn json_rows(text: &str) -> Result<Vec<Vec<f64>>> {
    serde_json::from_str(text).map_err(|e| {
        Error::new(
            ErrorKind::Parse,
            format!("points are not a JSON array of number arrays: {e}"),
        )
    })
}

/// Without serde, JSON point files are refused.
#[cfg(not(feature = "serde"))]
fn json_rows(_text: &str) -> Result<Vec<Vec<f64>>> {
    Err(Error::new(
        ErrorKind::Parse,
        "JSON point files need the feature serde of spline-io",
    ))
}

/// The non-empty tokens of a line, split at whitespace and commas.
pub(crate) fn tokens(line: &str) -> Vec<&str> {
    line.split(|c: char| c.is_whitespace() || c == ',')
        .filter(|t| !t.is_empty())
        .collect()
}

/// The numbers of the tokens (`(1.5` and `2)` read as 1.5 and 2 only when both
/// parentheses are there: `(1.5)`), or `None` if one is not a number.
pub(crate) fn numbers(tokens: &[&str]) -> Option<Vec<f64>> {
    tokens
        .iter()
        .map(|t| {
            let t = t
                .strip_prefix('(')
                .and_then(|t| t.strip_suffix(')'))
                .unwrap_or(t);
            t.parse::<f64>().ok()
        })
        .collect()
}
