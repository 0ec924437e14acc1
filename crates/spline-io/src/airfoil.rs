//! Airfoil coordinate files: the UIUC Selig format, with its variants in the database, and the
//! Lednicer format.
//!
//! - **Selig**: a name line, then `x y` per line from the trailing edge over the upper
//!   surface to the leading edge and back along the lower surface.
//! - Variants found in the UIUC database are accepted: several text lines before the
//!   coordinates (a name and a description), placeholder lines without a coordinate
//!   (`0.0000     ......`), a line
//!   of metadata numbers that are not a point (the `tasopt-*` files: four numbers), blank
//!   lines, `#` comments, numbers in parentheses (`(0.0022)`), commas as separators, no
//!   name line at all, and a footer of text lines after the coordinates (credits, a source
//!   address).
//! - **Lednicer**: a name line, a line with the numbers of upper and lower points
//!   (`17. 17.`), then the upper surface from the leading edge to the trailing edge and the
//!   lower surface likewise, separated by blank lines; the points are returned in Selig order
//!   (the leading-edge point once when both surfaces share it).
//!
//! Anything else is refused with the offending line named.

use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result};

/// The layout an airfoil file was read in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AirfoilFormat {
    /// Selig order, one point per line after an optional header.
    Selig,
    /// Lednicer: counts, then the upper and the lower surface from the leading edge.
    Lednicer,
}

/// An airfoil read from a coordinate file.
#[derive(Clone, Debug, PartialEq)]
pub struct Airfoil {
    /// The name line, if the file has one.
    pub name: Option<String>,
    /// The points in Selig order.
    pub points: Vec<Vector2<f64>>,
    /// The layout of the file.
    pub format: AirfoilFormat,
}

#[derive(Clone, Debug, PartialEq)]
enum Line {
    Blank,
    Numbers(Vec<f64>),
    Text(String),
}

fn classify(line: &str) -> Line {
    let line = line.split('#').next().unwrap_or("").trim();
    if line.is_empty() {
        return Line::Blank;
    }
    let tokens = crate::points::tokens(line);
    match crate::points::numbers(&tokens) {
        Some(v) => Line::Numbers(v),
        // A placeholder such as `0.0000     ......` holds no point.
        None if tokens.len() >= 2
            && tokens[0].parse::<f64>().is_ok()
            && tokens[1..]
                .iter()
                .all(|t| t.len() >= 3 && t.chars().all(|c| c == '.')) =>
        {
            Line::Blank
        }
        None => Line::Text(line.to_owned()),
    }
}

/// A short quote of a line for messages.
fn quote(text: &str) -> String {
    let mut out: String = text.chars().take(40).collect();
    if text.chars().count() > 40 {
        out.push('…');
    }
    format!("{out:?}")
}

/// Reads an airfoil coordinate file (Selig or Lednicer; see the module documentation).
///
/// ```
/// use spline_io::airfoil::{AirfoilFormat, parse_airfoil};
/// let selig = "NACA 0012\n1.0 0.0013\n0.5 0.0529\n0.0 0.0\n0.5 -0.0529\n1.0 -0.0013\n";
/// let a = parse_airfoil(selig)?;
/// assert_eq!(a.name.as_deref(), Some("NACA 0012"));
/// assert_eq!((a.points.len(), a.format), (5, AirfoilFormat::Selig));
/// let lednicer = "NACA 0012\n3. 3.\n\n0.0 0.0\n0.5 0.0529\n1.0 0.0013\n\n0.0 0.0\n0.5 -0.0529\n1.0 -0.0013\n";
/// let b = parse_airfoil(lednicer)?;
/// assert_eq!(b.format, AirfoilFormat::Lednicer);
/// assert_eq!(b.points, a.points);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::Parse`] for a line that is neither a point, a header line before the
/// points, nor blank (the line is named), or Lednicer counts that do not match the lines;
/// [`ErrorKind::NonFinite`] for infinite or NaN coordinates; [`ErrorKind::TooFewPoints`] with
/// fewer than three points.
pub fn parse_airfoil(text: &str) -> Result<Airfoil> {
    let lines: Vec<(usize, Line)> = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, classify(l)))
        .collect();
    // The header: text lines and numeric lines that are not points, before the first point.
    let mut name = None;
    let mut body = 0;
    // The first numeric header line: a file whose every line has three numbers is points
    // in space, not a header followed by nothing.
    let mut numeric_header: Option<(usize, usize)> = None;
    while body < lines.len() {
        match &lines[body].1 {
            Line::Blank => {}
            Line::Text(t) => {
                if name.is_none() {
                    name = Some(t.clone());
                }
            }
            Line::Numbers(v) if v.len() == 2 => break,
            Line::Numbers(v) => {
                numeric_header.get_or_insert((lines[body].0, v.len()));
            }
        }
        body += 1;
    }
    // Lednicer: the first numeric line holds two integral counts ≥ 2 that match the data.
    if let Some((_, Line::Numbers(counts))) = lines.get(body) {
        let (nu, nl) = (counts[0], counts[1]);
        let points: Vec<(usize, &Vec<f64>)> = lines[body + 1..]
            .iter()
            .filter_map(|(i, l)| match l {
                Line::Numbers(v) => Some((*i, v)),
                _ => None,
            })
            .collect();
        let integral = |v: f64| v >= 2.0 && v.fract() == 0.0 && v < 1e6;
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        if integral(nu) && integral(nl) && (nu + nl) as usize == points.len() {
            let upper = nu as usize;
            let surface = |rows: &[(usize, &Vec<f64>)]| -> Result<Vec<Vector2<f64>>> {
                rows.iter().map(|(i, v)| point(*i, v)).collect()
            };
            let up = surface(&points[..upper])?;
            let low = surface(&points[upper..])?;
            let mut selig: Vec<Vector2<f64>> = up.into_iter().rev().collect();
            let skip = usize::from(selig.last() == low.first());
            selig.extend(low.into_iter().skip(skip));
            return finish(name, selig, AirfoilFormat::Lednicer);
        }
    }
    let mut selig = Vec::new();
    for (k, (i, line)) in lines[body..].iter().enumerate() {
        match line {
            Line::Blank => {}
            Line::Numbers(v) => selig.push(point(*i, v)?),
            Line::Text(t) => {
                // A footer (credits, a source address) may follow the coordinates; text
                // between points may not.
                let more = lines[body + k + 1..]
                    .iter()
                    .any(|(_, l)| matches!(l, Line::Numbers(_)));
                if more {
                    return Err(Error::new(
                        ErrorKind::Parse,
                        format!(
                            "line {i}: expected the two coordinates of a point, got {}",
                            quote(t)
                        ),
                    )
                    .with_line(*i));
                }
                break;
            }
        }
    }
    if let (true, Some((line, count))) = (selig.is_empty(), numeric_header) {
        return Err(Error::new(
            ErrorKind::Parse,
            format!(
                "line {line}: expected the two coordinates of a point, got {count} numbers (planar points need two columns)"
            ),
        )
        .with_line(line));
    }
    finish(name, selig, AirfoilFormat::Selig)
}

fn point(line: usize, v: &[f64]) -> Result<Vector2<f64>> {
    match v {
        [x, y] if x.is_finite() && y.is_finite() => Ok(Vector2::new(*x, *y)),
        [_, _] => Err(Error::new(
            ErrorKind::NonFinite,
            format!("line {line}: the point is not finite"),
        )
        .with_line(line)),
        _ => Err(Error::new(
            ErrorKind::Parse,
            format!(
                "line {line}: expected the two coordinates of a point, got {} numbers",
                v.len()
            ),
        )
        .with_line(line)),
    }
}

fn finish(
    name: Option<String>,
    points: Vec<Vector2<f64>>,
    format: AirfoilFormat,
) -> Result<Airfoil> {
    if points.len() < 3 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "an airfoil needs at least 3 points, the file has {}",
                points.len()
            ),
        ));
    }
    Ok(Airfoil {
        name,
        points,
        format,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uiuc_variants() {
        // tasopt: a line of four metadata numbers after the name.
        let tasopt = "NC120\n -2.0 3.0 -2.5 3.5\n1.0 -0.2492760E-09\n0.99 0.0014\n0.5 0.05\n";
        let a = parse_airfoil(tasopt).unwrap();
        assert_eq!(a.points.len(), 3);
        assert_eq!(a.points[0], Vector2::new(1.0, -0.249_276e-9));
        // A placeholder line and parenthesised numbers (naca23021.dat).
        let naca = "NACA 23021\n1.0000     ......\n1.0000     (0.0022)\n0.9500     0.0153\n0.0 ......\n0.9 0.0276\n";
        let b = parse_airfoil(naca).unwrap();
        assert_eq!(b.points[0], Vector2::new(1.0, 0.0022));
        assert_eq!(b.points.len(), 3);
        // Two text lines, no name line, tabs, blank lines, comments.
        let two = "Ornithopter airfoil.\nS1020\n\n 1.0 0.0\n# comment\n0.5\t0.1\n0.0, 0.0\n";
        let c = parse_airfoil(two).unwrap();
        assert_eq!(c.name.as_deref(), Some("Ornithopter airfoil."));
        assert_eq!(c.points.len(), 3);
        let footer =
            "name\n1 0\n0.5 0.1\n0 0\nProfili-> by Stefano Duranti\nhttp://www.example.org\n";
        assert_eq!(parse_airfoil(footer).unwrap().points.len(), 3);
        let bare = "1\t0.00119\n0.5\t0.02\n0\t0\n";
        assert_eq!(parse_airfoil(bare).unwrap().name, None);
    }

    #[test]
    fn bad_files_name_the_line() {
        let err = parse_airfoil("name\n1 0\n0.5 0.1\nnot a point\n0 0\n").unwrap_err();
        assert_eq!(err.kind(), ErrorKind::Parse);
        assert!(err.to_string().contains("line 4"), "{err}");
        let err = parse_airfoil("name\n1 0\n0.5 0.1 0.3\n0 0\n").unwrap_err();
        assert!(
            err.to_string().contains("line 3") && err.to_string().contains("3 numbers"),
            "{err}"
        );
        let err = parse_airfoil("name\n1 0\n0 0\n").unwrap_err();
        assert_eq!(err.kind(), ErrorKind::TooFewPoints);
        let err = parse_airfoil("name\n1 0\n0.5 inf\n0 0\n").unwrap_err();
        assert_eq!(err.kind(), ErrorKind::NonFinite);
        assert_eq!(
            parse_airfoil("").unwrap_err().kind(),
            ErrorKind::TooFewPoints
        );
        // Every line with three numbers: points in space, said as such (issue 25: "the file
        // has 0 points").
        let err = parse_airfoil("# x y z\n1 0 0\n0.5 0.1 0\n0 0 0\n").unwrap_err();
        assert_eq!(err.kind(), ErrorKind::Parse);
        assert!(
            err.to_string().contains("line 2") && err.to_string().contains("3 numbers"),
            "{err}"
        );
    }
}
