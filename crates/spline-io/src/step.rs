//! STEP files (ISO 10303-21 exchange structure, AP214/AP242 geometry) in and out.
//!
//! # Reading
//! [`read_step`] parses the `DATA` section in one pass (time and memory linear in the size of
//! the file: the instances are kept as parsed, with their line, in a map by `#id`), then
//! returns, in the order of their instance numbers, every B-spline curve
//! (`B_SPLINE_CURVE_WITH_KNOTS`, its rational complex instance with `RATIONAL_B_SPLINE_CURVE`,
//! `BEZIER_CURVE`, `UNIFORM_CURVE`, `QUASI_UNIFORM_CURVE`) and every B-spline surface (the
//! same forms of `B_SPLINE_SURFACE`), in 2-D or 3-D. The geometry of a B-rep comes out the
//! same way: the surfaces of the faces (`ADVANCED_FACE`, named after the face) and the curves
//! of the edges (`EDGE_CURVE`, named after the edge), analytic ones converted exactly to
//! NURBS (module `analytic`: lines, circles, ellipses, planes, cylinders, cones, spheres,
//! tori, surfaces of revolution and of linear extrusion); everything that is not geometry
//! (products, contexts, units, topology, presentation) is skipped. `TRIMMED_CURVE` and
//! `RECTANGULAR_TRIMMED_SURFACE` give their basis geometry (their trims are not applied).
//!
//! - [`Item::id`] is the instance number (`#17` → 17), [`Item::entity`] the entity read
//!   (`B_SPLINE_CURVE_WITH_KNOTS`, `B_SPLINE_SURFACE_WITH_KNOTS`, …), [`Item::name`] the name
//!   of the face or edge that holds the geometry when it has one, else the geometry's own
//!   `name` attribute. Curves of the parameter planes (`PCURVE`s' definitional
//!   representations) are not returned.
//! - Curves whose points have two coordinates are 2-D, three 3-D; a rational curve or surface
//!   whose weights are all equal is still returned as rational (the file says so).
//!
//! No Part 21 crate is used: the crates on crates.io for ISO 10303-21 either generate code
//! for whole schemas (large and slow to build for the handful of geometric entities read
//! here) or stopped at syntax without line numbers in their errors; the exchange structure's
//! syntax (instances, lists, strings, enumerations, typed parameters) takes one small
//! tokenizer.
//!
//! # Writing
//! [`write_step`] writes an AP214 file (`AUTOMOTIVE_DESIGN`) as CAD systems write loose
//! geometry: one product with its definition, curves in a `GEOMETRIC_CURVE_SET` of a
//! `GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION`, surfaces in a `GEOMETRIC_SET` of a
//! `GEOMETRICALLY_BOUNDED_SURFACE_SHAPE_REPRESENTATION`, in millimetres; B-splines as
//! `B_SPLINE_CURVE_WITH_KNOTS` / `B_SPLINE_SURFACE_WITH_KNOTS` (distinct knots with their
//! multiplicities), rational ones as the complex instance with their weights; numbers in the
//! shortest decimal form that reads back to the same `f64` (`1.5E-07`), so a round trip
//! through the file is exact. 2-D curves are written in the plane `z = 0` (CAD systems read
//! 3-D geometry only) and so read back as 3-D curves.
//!
//! # Errors
//! Every error is one line that names the line of the file (`STEP line 123: …`) and, where
//! one is concerned, the instance (`#17`). Counts are never read from the file: lists grow
//! with what the file holds; references are resolved with a depth limit (a cycle of
//! references is an error, not a hang).
//!
//! ```
//! use nalgebra::Vector3;
//! use spline_geom::BSpline;
//! use spline_io::step::{read_step, write_step};
//! use spline_io::{Geometry, Item};
//! let line = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
//!     vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 2.0, 3.0)])?;
//! let item = Item { id: 0, name: "edge".into(), entity: String::new(), geometry: Geometry::Curve3(line) };
//! let text = write_step(&[item.clone()])?;
//! let back = read_step(&text)?;
//! assert_eq!(back[0].geometry, item.geometry);
//! assert_eq!(back[0].name, "edge");
//! # Ok::<(), spline_core::Error>(())
//! ```

mod analytic;

use crate::{Geometry, Item};
use nalgebra::{Vector2, Vector3};
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::{BSpline, NurbsCurve, NurbsSurface, Surface};
use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;

/// Lists nest at most this deep (a B-spline surface's points are two levels down).
const MAX_NESTING: usize = 32;

/// A parameter of an entity instance.
#[derive(Clone, Debug, PartialEq)]
enum Param {
    Integer(i64),
    Real(f64),
    Text(String),
    Enumeration(String),
    Reference(u64),
    List(Vec<Param>),
    /// `$`: no value.
    Unset,
    /// `*`: a value derived from others.
    Derived,
    /// A typed parameter, `LENGTH_MEASURE(1.)`.
    Typed(String, Box<Param>),
}

/// One instance: its line and its record(s) (one for a simple instance, several for a
/// complex one), each an entity name with its parameters.
#[derive(Debug)]
struct Instance {
    line: usize,
    records: Vec<(String, Vec<Param>)>,
}

impl Instance {
    fn record(&self, name: &str) -> Option<&[Param]> {
        self.records
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, p)| p.as_slice())
    }
}

fn error_at(line: usize, message: impl std::fmt::Display) -> Error {
    Error::new(ErrorKind::Parse, format!("STEP line {line}: {message}"))
}

/// The tokens of the exchange structure.
#[derive(Clone, Debug, PartialEq)]
enum Token {
    Keyword(String),
    Instance(u64),
    Integer(i64),
    Real(f64),
    Text(String),
    Enumeration(String),
    Open,
    Close,
    Comma,
    Semicolon,
    Equals,
    Dollar,
    Star,
}

struct Lexer<'a> {
    bytes: &'a [u8],
    at: usize,
    line: usize,
}

impl<'a> Lexer<'a> {
    fn new(bytes: &'a [u8]) -> Self {
        Self {
            bytes,
            at: 0,
            line: 1,
        }
    }

    fn skip_space(&mut self) -> Result<()> {
        loop {
            match self.bytes.get(self.at) {
                Some(b'\n') => {
                    self.line += 1;
                    self.at += 1;
                }
                Some(b' ' | b'\t' | b'\r') => self.at += 1,
                Some(b'/') if self.bytes.get(self.at + 1) == Some(&b'*') => {
                    let start = self.line;
                    self.at += 2;
                    loop {
                        match self.bytes.get(self.at) {
                            None => return Err(error_at(start, "a comment is not closed (*/)")),
                            Some(b'*') if self.bytes.get(self.at + 1) == Some(&b'/') => {
                                self.at += 2;
                                break;
                            }
                            Some(b'\n') => {
                                self.line += 1;
                                self.at += 1;
                            }
                            Some(_) => self.at += 1,
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    /// The next token, `None` at the end of the input.
    fn next(&mut self) -> Result<Option<Token>> {
        self.skip_space()?;
        let Some(&c) = self.bytes.get(self.at) else {
            return Ok(None);
        };
        let single = match c {
            b'(' => Some(Token::Open),
            b')' => Some(Token::Close),
            b',' => Some(Token::Comma),
            b';' => Some(Token::Semicolon),
            b'=' => Some(Token::Equals),
            b'$' => Some(Token::Dollar),
            b'*' => Some(Token::Star),
            _ => None,
        };
        if let Some(token) = single {
            self.at += 1;
            return Ok(Some(token));
        }
        match c {
            b'#' => {
                self.at += 1;
                let digits = self.take(|b| b.is_ascii_digit());
                let id = digits
                    .parse::<u64>()
                    .map_err(|_| error_at(self.line, format!("bad instance name #{digits}")))?;
                Ok(Some(Token::Instance(id)))
            }
            b'\'' => self.text().map(Some),
            b'.' if self
                .bytes
                .get(self.at + 1)
                .is_some_and(u8::is_ascii_alphabetic) =>
            {
                self.at += 1;
                let name = self.take(|b| b.is_ascii_alphanumeric() || b == b'_');
                if self.bytes.get(self.at) != Some(&b'.') {
                    return Err(error_at(
                        self.line,
                        format!("enumeration .{name} is not closed by a dot"),
                    ));
                }
                self.at += 1;
                Ok(Some(Token::Enumeration(name.to_ascii_uppercase())))
            }
            b'+' | b'-' | b'.' | b'0'..=b'9' => self.number().map(Some),
            b'!' | b'A'..=b'Z' | b'a'..=b'z' | b'_' => {
                let start = self.at;
                self.at += 1;
                let rest = self.take(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-');
                let word = format!("{}{rest}", self.bytes[start] as char);
                Ok(Some(Token::Keyword(word.to_ascii_uppercase())))
            }
            c if !c.is_ascii() => Err(error_at(
                self.line,
                "a byte outside ASCII outside a string (ISO 10303-21 files are ASCII; other characters are encoded in strings as \\X2\\…\\X0\\)",
            )),
            c => Err(error_at(
                self.line,
                format!("unexpected character {:?}", c as char),
            )),
        }
    }

    fn take(&mut self, keep: impl Fn(u8) -> bool) -> String {
        let start = self.at;
        while self.bytes.get(self.at).is_some_and(|&b| keep(b)) {
            self.at += 1;
        }
        String::from_utf8_lossy(&self.bytes[start..self.at]).into_owned()
    }

    fn number(&mut self) -> Result<Token> {
        let start = self.at;
        if matches!(self.bytes.get(self.at), Some(b'+' | b'-')) {
            self.at += 1;
        }
        let mut real = false;
        while let Some(&b) = self.bytes.get(self.at) {
            match b {
                b'0'..=b'9' => self.at += 1,
                b'.' => {
                    real = true;
                    self.at += 1;
                }
                b'E' | b'e' | b'D' | b'd' => {
                    real = true;
                    self.at += 1;
                    if matches!(self.bytes.get(self.at), Some(b'+' | b'-')) {
                        self.at += 1;
                    }
                }
                _ => break,
            }
        }
        let text = String::from_utf8_lossy(&self.bytes[start..self.at]).replace(['D', 'd'], "E");
        let bad = || error_at(self.line, format!("bad number {text:?}"));
        if real {
            let x: f64 = text.parse().map_err(|_| bad())?;
            if !x.is_finite() {
                return Err(error_at(
                    self.line,
                    format!("number {text} is out of range"),
                ));
            }
            Ok(Token::Real(x))
        } else {
            text.parse().map(Token::Integer).map_err(|_| bad())
        }
    }

    /// A string: `''` is a quote, `\\` a backslash, `\X2\…\X0\` UCS-2 code units in hex,
    /// `\X\hh` one byte in hex, `\S\c` a character of the upper half of ISO 8859-1.
    fn text(&mut self) -> Result<Token> {
        let start = self.line;
        self.at += 1;
        let mut raw = Vec::new();
        loop {
            match self.bytes.get(self.at) {
                None => return Err(error_at(start, "a string is not closed")),
                Some(b'\'') if self.bytes.get(self.at + 1) == Some(&b'\'') => {
                    raw.push(b'\'');
                    self.at += 2;
                }
                Some(b'\'') => {
                    self.at += 1;
                    break;
                }
                Some(&b) => {
                    if b == b'\n' {
                        self.line += 1;
                    } else if !b.is_ascii() {
                        return Err(error_at(
                            self.line,
                            "a byte outside ASCII in a string (encode it as \\X2\\…\\X0\\)",
                        ));
                    }
                    if b != b'\n' && b != b'\r' {
                        raw.push(b);
                    }
                    self.at += 1;
                }
            }
        }
        decode_text(&raw)
            .map(Token::Text)
            .map_err(|m| error_at(start, m))
    }
}

fn decode_text(raw: &[u8]) -> std::result::Result<String, String> {
    let mut out = String::with_capacity(raw.len());
    let mut i = 0;
    let hex =
        |s: &[u8]| -> Option<u32> { u32::from_str_radix(std::str::from_utf8(s).ok()?, 16).ok() };
    while i < raw.len() {
        if raw[i] != b'\\' {
            out.push(raw[i] as char);
            i += 1;
            continue;
        }
        let rest = &raw[i..];
        if rest.starts_with(b"\\\\") {
            out.push('\\');
            i += 2;
        } else if rest.starts_with(b"\\X2\\") {
            i += 4;
            let end = raw[i..]
                .windows(4)
                .position(|w| w == b"\\X0\\")
                .ok_or("\\X2\\ without \\X0\\ in a string")?;
            let units: Vec<u16> = raw[i..i + end]
                .chunks(4)
                .map(|c| hex(c).and_then(|v| u16::try_from(v).ok()))
                .collect::<Option<_>>()
                .ok_or("bad hex digits after \\X2\\ in a string")?;
            out.push_str(&String::from_utf16_lossy(&units));
            i += end + 4;
        } else if rest.starts_with(b"\\X\\") && rest.len() >= 5 {
            let v = hex(&rest[3..5]).ok_or("bad hex digits after \\X\\ in a string")?;
            out.push(char::from_u32(v).unwrap_or('\u{fffd}'));
            i += 5;
        } else if rest.starts_with(b"\\S\\") && rest.len() >= 4 {
            out.push(char::from_u32(u32::from(rest[3]) + 128).unwrap_or('\u{fffd}'));
            i += 4;
        } else {
            // A lone backslash (or a directive this reader does not decode): kept as it is.
            out.push('\\');
            i += 1;
        }
    }
    Ok(out)
}

struct Parser<'a> {
    lexer: Lexer<'a>,
    peeked: Option<(Token, usize)>,
}

impl<'a> Parser<'a> {
    fn next(&mut self) -> Result<Option<(Token, usize)>> {
        if let Some(t) = self.peeked.take() {
            return Ok(Some(t));
        }
        let token = self.lexer.next()?;
        Ok(token.map(|t| (t, self.lexer.line)))
    }

    fn peek(&mut self) -> Result<Option<&Token>> {
        if self.peeked.is_none() {
            self.peeked = self.next()?;
        }
        Ok(self.peeked.as_ref().map(|(t, _)| t))
    }

    fn expect(&mut self, want: &Token, what: &str) -> Result<usize> {
        match self.next()? {
            Some((t, line)) if &t == want => Ok(line),
            Some((t, line)) => Err(error_at(line, format!("expected {what}, found {t:?}"))),
            None => Err(error_at(
                self.lexer.line,
                format!("the file ends where {what} was expected"),
            )),
        }
    }

    /// `( param, param, … )`, the opening parenthesis already read.
    fn params(&mut self, depth: usize) -> Result<Vec<Param>> {
        if depth > MAX_NESTING {
            return Err(error_at(self.lexer.line, "lists nest too deep"));
        }
        let mut out = Vec::new();
        if self.peek()? == Some(&Token::Close) {
            self.next()?;
            return Ok(out);
        }
        loop {
            out.push(self.param(depth)?);
            match self.next()? {
                Some((Token::Comma, _)) => {}
                Some((Token::Close, _)) => return Ok(out),
                Some((t, line)) => {
                    return Err(error_at(
                        line,
                        format!("expected , or ) in a list, found {t:?}"),
                    ));
                }
                None => return Err(error_at(self.lexer.line, "the file ends inside a list")),
            }
        }
    }

    fn param(&mut self, depth: usize) -> Result<Param> {
        let Some((token, line)) = self.next()? else {
            return Err(error_at(self.lexer.line, "the file ends inside a list"));
        };
        Ok(match token {
            Token::Integer(i) => Param::Integer(i),
            Token::Real(x) => Param::Real(x),
            Token::Text(s) => Param::Text(s),
            Token::Enumeration(e) => Param::Enumeration(e),
            Token::Instance(id) => Param::Reference(id),
            Token::Dollar => Param::Unset,
            Token::Star => Param::Derived,
            Token::Open => Param::List(self.params(depth + 1)?),
            Token::Keyword(name) => {
                self.expect(&Token::Open, "( after a type name")?;
                let mut inner = self.params(depth + 1)?;
                if inner.len() != 1 {
                    return Err(error_at(
                        line,
                        format!("typed parameter {name} needs one value"),
                    ));
                }
                Param::Typed(name, Box::new(inner.remove(0)))
            }
            t => return Err(error_at(line, format!("unexpected {t:?} in a list"))),
        })
    }
}

/// The instances of the `DATA` sections.
fn parse(bytes: &[u8]) -> Result<HashMap<u64, Instance>> {
    let mut parser = Parser {
        lexer: Lexer::new(bytes),
        peeked: None,
    };
    match parser.next()? {
        Some((Token::Keyword(k), _)) if k == "ISO-10303-21" => {}
        Some((_, line)) => {
            return Err(error_at(
                line,
                "not a STEP file: it does not start with ISO-10303-21;",
            ));
        }
        None => return Err(error_at(1, "the file is empty")),
    }
    parser.expect(&Token::Semicolon, "; after ISO-10303-21")?;
    let mut instances = HashMap::new();
    let mut in_data = false;
    loop {
        let Some((token, line)) = parser.next()? else {
            return Err(error_at(
                parser.lexer.line,
                "the file ends before END-ISO-10303-21;",
            ));
        };
        match token {
            Token::Keyword(k) if k == "END-ISO-10303-21" => return Ok(instances),
            Token::Keyword(k) if k == "DATA" => {
                // DATA; or DATA(parameters);
                if parser.peek()? == Some(&Token::Open) {
                    parser.next()?;
                    parser.params(1)?;
                }
                parser.expect(&Token::Semicolon, "; after DATA")?;
                in_data = true;
            }
            Token::Keyword(k) if k == "ENDSEC" => {
                parser.expect(&Token::Semicolon, "; after ENDSEC")?;
                in_data = false;
            }
            Token::Instance(id) if in_data => {
                parser.expect(&Token::Equals, &format!("= after #{id}"))?;
                let mut records = Vec::new();
                match parser.next()? {
                    Some((Token::Keyword(name), _)) => {
                        parser.expect(&Token::Open, &format!("( after {name}"))?;
                        records.push((name, parser.params(1)?));
                    }
                    Some((Token::Open, _)) => loop {
                        match parser.next()? {
                            Some((Token::Close, _)) => break,
                            Some((Token::Keyword(name), _)) => {
                                parser.expect(&Token::Open, &format!("( after {name}"))?;
                                records.push((name, parser.params(1)?));
                            }
                            Some((t, l)) => {
                                return Err(error_at(
                                    l,
                                    format!("#{id}: expected an entity name, found {t:?}"),
                                ));
                            }
                            None => {
                                return Err(error_at(
                                    parser.lexer.line,
                                    format!("the file ends inside #{id}"),
                                ));
                            }
                        }
                    },
                    Some((t, l)) => {
                        return Err(error_at(
                            l,
                            format!("#{id}: expected an entity name, found {t:?}"),
                        ));
                    }
                    None => {
                        return Err(error_at(
                            parser.lexer.line,
                            format!("the file ends inside #{id}"),
                        ));
                    }
                }
                parser.expect(&Token::Semicolon, &format!("; after #{id}"))?;
                if instances.insert(id, Instance { line, records }).is_some() {
                    return Err(error_at(line, format!("#{id} is defined twice")));
                }
            }
            Token::Keyword(_) if !in_data => {
                // A header entity or another section: skip to its semicolon, lists included.
                loop {
                    match parser.next()? {
                        Some((Token::Semicolon, _)) => break,
                        Some((Token::Open, _)) => {
                            parser.params(1)?;
                        }
                        Some(_) => {}
                        None => {
                            return Err(error_at(
                                parser.lexer.line,
                                "the file ends inside its header",
                            ));
                        }
                    }
                }
            }
            t => return Err(error_at(line, format!("unexpected {t:?}"))),
        }
    }
}

/// Reading context: the instances and the names given to geometry by faces and edges.
struct Reader<'a> {
    instances: &'a HashMap<u64, Instance>,
}

impl Reader<'_> {
    fn get(&self, id: u64, from: usize) -> Result<&Instance> {
        self.instances
            .get(&id)
            .ok_or_else(|| error_at(from, format!("#{id} is referenced but not defined")))
    }

    fn point(&self, param: &Param, from: usize) -> Result<Vec<f64>> {
        let Param::Reference(id) = param else {
            return Err(error_at(from, "expected a reference to a CARTESIAN_POINT"));
        };
        let instance = self.get(*id, from)?;
        let Some(p) = instance.record("CARTESIAN_POINT") else {
            return Err(error_at(
                instance.line,
                format!("#{id} is not a CARTESIAN_POINT"),
            ));
        };
        let coords = match p {
            [_, Param::List(c)] => c,
            _ => {
                return Err(error_at(
                    instance.line,
                    format!("#{id}: CARTESIAN_POINT needs a name and a list of coordinates"),
                ));
            }
        };
        let out: Vec<f64> = coords
            .iter()
            .map(|c| {
                number(c).ok_or_else(|| {
                    error_at(
                        instance.line,
                        format!("#{id}: a coordinate is not a number"),
                    )
                })
            })
            .collect::<Result<_>>()?;
        if !(2..=3).contains(&out.len()) {
            return Err(error_at(
                instance.line,
                format!("#{id}: a point needs 2 or 3 coordinates, got {}", out.len()),
            ));
        }
        Ok(out)
    }
}

fn number(p: &Param) -> Option<f64> {
    match p {
        Param::Real(x) => Some(*x),
        #[allow(clippy::cast_precision_loss)]
        Param::Integer(i) => Some(*i as f64),
        Param::Typed(_, inner) => number(inner),
        _ => None,
    }
}

fn integer(p: &Param) -> Option<i64> {
    match p {
        Param::Integer(i) => Some(*i),
        Param::Typed(_, inner) => integer(inner),
        _ => None,
    }
}

fn list(p: &Param) -> Option<&[Param]> {
    match p {
        Param::List(l) => Some(l),
        _ => None,
    }
}

fn text(p: &Param) -> String {
    match p {
        Param::Text(s) => s.clone(),
        _ => String::new(),
    }
}

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

/// What a B-spline instance holds before it becomes a container.
struct CurveParts<'a> {
    name: String,
    degree: usize,
    points: &'a [Param],
    knots: KnotForm<'a>,
    weights: Option<&'a [Param]>,
    entity: &'static str,
}

fn curve_parts(instance: &Instance) -> Result<Option<CurveParts<'_>>> {
    let line = instance.line;
    let bad = |what: &str| error_at(line, format!("{what} has the wrong parameters"));
    let weights = match instance.record("RATIONAL_B_SPLINE_CURVE") {
        Some([Param::List(w)]) => Some(w.as_slice()),
        Some([_, Param::List(w)]) => Some(w.as_slice()),
        Some(_) => return Err(bad("RATIONAL_B_SPLINE_CURVE")),
        None => None,
    };
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
    for (simple, form) in [
        ("BEZIER_CURVE", KnotForm::Bezier),
        ("UNIFORM_CURVE", KnotForm::Uniform),
        ("QUASI_UNIFORM_CURVE", KnotForm::QuasiUniform),
    ] {
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
    } else if instance.record("BEZIER_CURVE").is_some() {
        (KnotForm::Bezier, "BEZIER_CURVE")
    } else if instance.record("UNIFORM_CURVE").is_some() {
        (KnotForm::Uniform, "UNIFORM_CURVE")
    } else if instance.record("QUASI_UNIFORM_CURVE").is_some() {
        (KnotForm::QuasiUniform, "QUASI_UNIFORM_CURVE")
    } else {
        return Err(error_at(
            line,
            "a B_SPLINE_CURVE without knots (no _WITH_KNOTS, UNIFORM_, QUASI_UNIFORM_ or BEZIER_ form)",
        ));
    };
    let name = instance
        .record("REPRESENTATION_ITEM")
        .and_then(|p| p.first())
        .map(text)
        .unwrap_or_default();
    Ok(Some(CurveParts {
        name,
        degree: degree_of(degree, line)?,
        points,
        knots,
        weights,
        entity,
    }))
}

fn read_curve(
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
    let context = |e: Error| error_at(line, e);
    Ok(match (dim, weights) {
        (2, None) => Geometry::Curve2(
            BSpline::new(
                knots,
                points.iter().map(|p| Vector2::new(p[0], p[1])).collect(),
            )
            .map_err(context)?,
        ),
        (2, Some(w)) => Geometry::NurbsCurve2(
            NurbsCurve::new(
                knots,
                points.iter().map(|p| Vector2::new(p[0], p[1])).collect(),
                w,
            )
            .map_err(context)?,
        ),
        (_, None) => Geometry::Curve3(
            BSpline::new(
                knots,
                points
                    .iter()
                    .map(|p| Vector3::new(p[0], p[1], p[2]))
                    .collect(),
            )
            .map_err(context)?,
        ),
        (_, Some(w)) => Geometry::NurbsCurve3(
            NurbsCurve::new(
                knots,
                points
                    .iter()
                    .map(|p| Vector3::new(p[0], p[1], p[2]))
                    .collect(),
                w,
            )
            .map_err(context)?,
        ),
    })
}

fn read_surface(
    reader: &Reader<'_>,
    instance: &Instance,
) -> Result<Option<(Geometry, String, &'static str)>> {
    let line = instance.line;
    let bad = |what: &str| error_at(line, format!("{what} has the wrong parameters"));
    let weights = match instance.record("RATIONAL_B_SPLINE_SURFACE") {
        Some([Param::List(w)]) => Some(w.as_slice()),
        Some([_, Param::List(w)]) => Some(w.as_slice()),
        Some(_) => return Err(bad("RATIONAL_B_SPLINE_SURFACE")),
        None => None,
    };
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
    } else if let Some((simple, p, form)) = [
        ("BEZIER_SURFACE", KnotForm::Bezier),
        ("UNIFORM_SURFACE", KnotForm::Uniform),
        ("QUASI_UNIFORM_SURFACE", KnotForm::QuasiUniform),
    ]
    .into_iter()
    .find_map(|(n, f)| {
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
        } else if instance.record("BEZIER_SURFACE").is_some() {
            ((KnotForm::Bezier, KnotForm::Bezier), "BEZIER_SURFACE")
        } else if instance.record("UNIFORM_SURFACE").is_some() {
            ((KnotForm::Uniform, KnotForm::Uniform), "UNIFORM_SURFACE")
        } else if instance.record("QUASI_UNIFORM_SURFACE").is_some() {
            (
                (KnotForm::QuasiUniform, KnotForm::QuasiUniform),
                "QUASI_UNIFORM_SURFACE",
            )
        } else {
            return Err(error_at(line, "a B_SPLINE_SURFACE without knots"));
        };
        let name = instance
            .record("REPRESENTATION_ITEM")
            .and_then(|p| p.first())
            .map(text)
            .unwrap_or_default();
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

/// Follows the wrappers between topology and geometry (`TRIMMED_CURVE`'s basis curve,
/// `SURFACE_CURVE`/`SEAM_CURVE`'s 3-D curve, `RECTANGULAR_TRIMMED_SURFACE`'s basis surface)
/// to the instance that holds the geometry.
fn underlying(instances: &HashMap<u64, Instance>, mut id: u64) -> Option<u64> {
    for _ in 0..MAX_NESTING {
        let instance = instances.get(&id)?;
        let next = [
            "TRIMMED_CURVE",
            "SURFACE_CURVE",
            "SEAM_CURVE",
            "RECTANGULAR_TRIMMED_SURFACE",
        ]
        .iter()
        .find_map(|name| instance.record(name))
        .and_then(|p| match p.get(1) {
            Some(Param::Reference(r)) => Some(*r),
            _ => None,
        });
        match next {
            Some(next) => id = next,
            None => return Some(id),
        }
    }
    None
}

/// Every B-spline curve and surface of a STEP file; see the [module](self) documentation.
///
/// # Errors
/// [`ErrorKind::Parse`] with the line (and instance) for what cannot be read: broken syntax,
/// a truncated file, a reference to an undefined instance, B-spline data that do not form a
/// valid spline (wrong counts, bad knots, non-positive weights).
pub fn read_step(text: &str) -> Result<Vec<Item>> {
    read_step_bytes(text.as_bytes())
}

/// [`read_step`] on bytes: a byte outside ASCII is reported with its line.
///
/// # Errors
/// As [`read_step`].
pub fn read_step_bytes(bytes: &[u8]) -> Result<Vec<Item>> {
    let instances = parse(bytes)?;
    let reader = Reader {
        instances: &instances,
    };
    // Names from the topology: faces name their surfaces, edges their curves.
    let mut names: HashMap<u64, String> = HashMap::new();
    for instance in instances.values() {
        for (entity, at) in [("ADVANCED_FACE", 2), ("FACE_SURFACE", 2), ("EDGE_CURVE", 3)] {
            if let Some(p) = instance.record(entity) {
                if let (Some(Param::Text(name)), Some(Param::Reference(g))) = (p.first(), p.get(at))
                {
                    if !name.is_empty() {
                        if let Some(target) = underlying(&instances, *g) {
                            names.entry(target).or_insert_with(|| name.clone());
                        }
                    }
                }
            }
        }
    }
    // Curves in the parameter planes of surfaces (the PCURVEs' definitional
    // representations) are not geometry of the model.
    let mut parametric: std::collections::HashSet<u64> = std::collections::HashSet::new();
    // Likewise the profiles of swept surfaces, which are part of the surface's definition
    // (an edge that runs along one has a curve of its own).
    for instance in instances.values() {
        for swept in ["SURFACE_OF_REVOLUTION", "SURFACE_OF_LINEAR_EXTRUSION"] {
            if let Some([_, Param::Reference(r), ..]) = instance.record(swept) {
                parametric.insert(*r);
            }
        }
    }
    for instance in instances.values() {
        if let Some([_, Param::List(items), ..]) = instance.record("DEFINITIONAL_REPRESENTATION") {
            parametric.extend(items.iter().filter_map(|i| match i {
                Param::Reference(r) => Some(*r),
                _ => None,
            }));
        }
    }
    let ordered: BTreeMap<u64, &Instance> = instances
        .iter()
        .filter(|(k, _)| !parametric.contains(k))
        .map(|(k, v)| (*k, v))
        .collect();
    let mut out = Vec::new();
    for (&id, instance) in &ordered {
        if let Some(parts) = curve_parts(instance)? {
            let geometry =
                read_curve(&reader, instance, &parts).map_err(|e| add_instance(e, id))?;
            let name = names.get(&id).cloned().unwrap_or(parts.name);
            out.push(Item {
                id,
                name,
                entity: parts.entity.to_string(),
                geometry,
            });
        } else if let Some((geometry, own, entity)) =
            read_surface(&reader, instance).map_err(|e| add_instance(e, id))?
        {
            let name = names.get(&id).cloned().unwrap_or(own);
            out.push(Item {
                id,
                name,
                entity: entity.to_string(),
                geometry,
            });
        }
    }
    out.extend(analytic::analytic_items(&reader, &names)?);
    out.sort_by_key(|item| item.id);
    Ok(out)
}

/// Adds the instance to a message that names only the line.
fn add_instance(e: Error, id: u64) -> Error {
    let message = e.to_string();
    if message.contains(&format!("#{id}")) {
        return e;
    }
    match message.split_once(": ") {
        Some((head, rest)) if head.starts_with("STEP line") => {
            Error::new(e.kind(), format!("{head}: #{id}: {rest}"))
        }
        _ => e,
    }
}

/// A real in STEP's syntax with the digits that read back to the same `f64`.
fn real(x: f64) -> String {
    let s = format!("{x:?}");
    match s.split_once('e') {
        Some((mantissa, exponent)) => {
            let mantissa = if mantissa.contains('.') {
                mantissa.to_string()
            } else {
                format!("{mantissa}.")
            };
            format!("{mantissa}E{exponent}")
        }
        None if s.contains('.') => s,
        None => format!("{s}."),
    }
}

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

/// An AP214 file holding the items; see the [module](self) documentation.
///
/// # Errors
/// [`ErrorKind::NonFinite`] if a coordinate, weight or knot is not finite (the containers
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
        match &item.geometry {
            Geometry::Curve2(c) => {
                let points: Vec<_> = c.control_points().iter().map(v2).collect();
                curves.push(write_curve(&mut w, name, c.knots(), &points, None));
            }
            Geometry::Curve3(c) => {
                let points: Vec<_> = c.control_points().iter().map(v3).collect();
                curves.push(write_curve(&mut w, name, c.knots(), &points, None));
            }
            Geometry::NurbsCurve2(c) => {
                let points: Vec<_> = c.control_points().iter().map(v2).collect();
                curves.push(write_curve(
                    &mut w,
                    name,
                    c.knots(),
                    &points,
                    Some(c.weights()),
                ));
            }
            Geometry::NurbsCurve3(c) => {
                let points: Vec<_> = c.control_points().iter().map(v3).collect();
                curves.push(write_curve(
                    &mut w,
                    name,
                    c.knots(),
                    &points,
                    Some(c.weights()),
                ));
            }
            Geometry::Surface(s) => {
                surfaces.push(write_surface(
                    &mut w,
                    name,
                    (s.knots_u(), s.knots_v()),
                    s.control_points(),
                    None,
                ));
            }
            Geometry::NurbsSurface(s) => {
                surfaces.push(write_surface(
                    &mut w,
                    name,
                    (s.knots_u(), s.knots_v()),
                    s.control_points(),
                    Some(s.weights()),
                ));
            }
        }
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
    let finite = |xs: &mut dyn Iterator<Item = f64>| {
        let mut all = true;
        for x in xs {
            all &= x.is_finite();
        }
        all
    };
    let ok = match geometry {
        Geometry::Curve2(c) => {
            finite(&mut c.control_points().iter().flat_map(|p| p.iter().copied()))
        }
        Geometry::Curve3(c) => {
            finite(&mut c.control_points().iter().flat_map(|p| p.iter().copied()))
        }
        Geometry::NurbsCurve2(c) => {
            finite(&mut c.control_points().iter().flat_map(|p| p.iter().copied()))
        }
        Geometry::NurbsCurve3(c) => {
            finite(&mut c.control_points().iter().flat_map(|p| p.iter().copied()))
        }
        Geometry::Surface(s) => {
            finite(&mut s.control_points().iter().flat_map(|p| p.iter().copied()))
        }
        Geometry::NurbsSurface(s) => {
            finite(&mut s.control_points().iter().flat_map(|p| p.iter().copied()))
        }
    };
    if ok {
        Ok(())
    } else {
        Err(Error::non_finite("a control point written to STEP"))
    }
}

#[cfg(test)]
mod tests {
    use super::{read_step, read_step_bytes, real, write_step};
    use crate::{Geometry, Item};
    use nalgebra::{Vector2, Vector3};
    use spline_core::KnotVector;
    use spline_geom::{BSpline, NurbsCurve, NurbsSurface, Surface};

    /// A small deterministic generator (xorshift), so that the cases are reproducible.
    struct Random(u64);

    impl Random {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            #[allow(clippy::cast_precision_loss)]
            let x = (self.0 >> 11) as f64 / (1u64 << 53) as f64;
            x
        }

        fn below(&mut self, n: usize) -> usize {
            #[allow(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                clippy::cast_precision_loss
            )]
            let i = (self.next() * n as f64) as usize;
            i.min(n - 1)
        }

        /// Knots of degree `p` for `n` control points: clamped or not, interior
        /// multiplicities up to `p`, values with all their digits.
        fn knots(&mut self, p: usize, n: usize) -> KnotVector<f64> {
            loop {
                if let Some(k) = self.knots_once(p, n) {
                    return k;
                }
            }
        }

        fn knots_once(&mut self, p: usize, n: usize) -> Option<KnotVector<f64>> {
            let clamped = self.next() < 0.7;
            let mut interior = Vec::new();
            let want = n + p + 1 - if clamped { 2 * (p + 1) } else { 0 };
            let mut x = -1.0 + 2.0 * self.next();
            while interior.len() < want {
                x += 0.01 + self.next();
                let m = 1 + self.below(p);
                for _ in 0..m.min(want - interior.len()) {
                    interior.push(x);
                }
            }
            let knots = if clamped {
                let (a, b) = (interior.first().copied().unwrap_or(0.0) - 0.5, x + 0.5);
                let mut k = vec![a; p + 1];
                k.extend(&interior);
                k.extend(std::iter::repeat_n(b, p + 1));
                k
            } else {
                interior
            };
            KnotVector::new(p, knots).ok()
        }

        fn point3(&mut self) -> Vector3<f64> {
            Vector3::new(
                self.next() * 10.0 - 5.0,
                self.next() * 1e-3,
                self.next() * 1e5,
            )
        }
    }

    fn item(geometry: Geometry, name: &str) -> Item {
        Item {
            id: 0,
            name: name.into(),
            entity: String::new(),
            geometry,
        }
    }

    #[test]
    fn random_curves_and_surfaces_come_back_bit_for_bit() {
        let mut random = Random(0x5eed_1234_abcd);
        let mut items = Vec::new();
        for case in 0..60 {
            let p = 1 + case % 7;
            let n = p + 1 + random.below(6);
            let knots = random.knots(p, n);
            let points: Vec<Vector3<f64>> = (0..n).map(|_| random.point3()).collect();
            let weights: Vec<f64> = (0..n).map(|_| 0.1 + 3.0 * random.next()).collect();
            let flat: Vec<Vector2<f64>> = points.iter().map(nalgebra::Matrix::xy).collect();
            let geometry = match case % 4 {
                0 => Geometry::Curve3(BSpline::new(knots, points).unwrap()),
                1 => Geometry::Curve2(BSpline::new(knots, flat).unwrap()),
                2 => Geometry::NurbsCurve3(NurbsCurve::new(knots, points, weights).unwrap()),
                _ => Geometry::NurbsCurve2(NurbsCurve::new(knots, flat, weights).unwrap()),
            };
            items.push(item(geometry, &format!("curve {case} 'quoted' \\ é")));
        }
        for case in 0..30 {
            let (pu, pv) = (1 + case % 7, 1 + (case / 7) % 4);
            let (nu, nv) = (pu + 1 + random.below(4), pv + 1 + random.below(4));
            let (ku, kv) = (random.knots(pu, nu), random.knots(pv, nv));
            let net: Vec<Vec<Vector3<f64>>> = (0..nu)
                .map(|_| (0..nv).map(|_| random.point3()).collect())
                .collect();
            let geometry = if case % 2 == 0 {
                Geometry::Surface(Surface::from_net(ku, kv, net).unwrap())
            } else {
                let w: Vec<Vec<f64>> = (0..nu)
                    .map(|_| (0..nv).map(|_| 0.2 + random.next()).collect())
                    .collect();
                Geometry::NurbsSurface(NurbsSurface::from_net(ku, kv, net, w).unwrap())
            };
            items.push(item(geometry, &format!("surface {case}")));
        }
        let text = write_step(&items).unwrap();
        assert!(text.is_ascii());
        let back = read_step(&text).unwrap();
        assert_eq!(back.len(), items.len());
        // Curves come first in the file, then surfaces, each in the order given; 2-D curves
        // come back in the plane z = 0.
        let lift = |p: &Vector2<f64>| Vector3::new(p.x, p.y, 0.0);
        for (b, i) in back.iter().zip(&items) {
            let expected = match &i.geometry {
                Geometry::Curve2(c) => Geometry::Curve3(c.map_control_points(lift)),
                Geometry::NurbsCurve2(c) => Geometry::NurbsCurve3(c.map_control_points::<3>(lift)),
                g => g.clone(),
            };
            assert_eq!(b.geometry, expected, "{}", i.name);
            assert_eq!(b.name, i.name);
        }
    }

    #[test]
    fn reals_are_written_in_step_syntax_and_read_back_exactly() {
        for x in [
            0.0,
            -0.0,
            1.0,
            0.1,
            1.5e-7,
            -2.5e300,
            1e16,
            123456789.125,
            f64::MIN_POSITIVE,
            5e-324,
        ] {
            let s = real(x);
            assert!(s.contains('.') && !s.contains('e'), "{s}");
            let y: f64 = s.parse().unwrap();
            assert_eq!(y.to_bits(), x.to_bits(), "{s}");
        }
    }

    /// The rational complex instance as Open CASCADE writes it, with 2-D names and the forms
    /// whose knots are implied.
    #[test]
    fn forms_written_by_other_systems() {
        let text = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('x'),'2;1');\nENDSEC;\nDATA;\n\
            #16 = TRIMMED_CURVE('',#17,(#22,PARAMETER_VALUE(0.)),(#23,PARAMETER_VALUE(1.)),.T.,.PARAMETER.);\n\
            #17 = ( BOUNDED_CURVE() B_SPLINE_CURVE(3,(#18,#19,#20,#21),\n.UNSPECIFIED.,.F.,.F.) B_SPLINE_CURVE_WITH_KNOTS((4,4),(0.,1.),\n\
            .PIECEWISE_BEZIER_KNOTS.) CURVE() GEOMETRIC_REPRESENTATION_ITEM() \nRATIONAL_B_SPLINE_CURVE((1.,2.,0.5,1.)) REPRESENTATION_ITEM('') );\n\
            #18 = CARTESIAN_POINT('',(0.,0.,0.));\n#19 = CARTESIAN_POINT('',(1.,2.,0.));\n\
            #20 = CARTESIAN_POINT('',(2.,-1.,1.));\n#21 = CARTESIAN_POINT('',(3.,0.,0.));\n\
            #22 = CARTESIAN_POINT('',(0.,0.,0.));\n#23 = CARTESIAN_POINT('',(3.,0.,0.));\n\
            #30 = EDGE_CURVE('rim',#31,#31,#16,.T.);\n#31 = VERTEX_POINT('',#22);\n\
            /* a Bézier curve: knots 0 0 0 1 1 2 2 2 */\n\
            #40 = BEZIER_CURVE('b',2,(#41,#42,#43,#44,#45),.UNSPECIFIED.,.F.,.F.);\n\
            #41 = CARTESIAN_POINT('',(0.,0.));\n#42 = CARTESIAN_POINT('',(1.,1.));\n\
            #43 = CARTESIAN_POINT('',(2.,0.));\n#44 = CARTESIAN_POINT('',(3.,-1.));\n\
            #45 = CARTESIAN_POINT('',(4.,0.));\n\
            #50 = QUASI_UNIFORM_CURVE('q',2,(#41,#42,#43,#44),.UNSPECIFIED.,.F.,.F.);\n\
            ENDSEC;\nEND-ISO-10303-21;\n";
        let items = read_step(text).unwrap();
        assert_eq!(items.len(), 3);
        let Geometry::NurbsCurve3(c) = &items[0].geometry else {
            panic!("{:?}", items[0])
        };
        assert_eq!(items[0].id, 17);
        assert_eq!(items[0].name, "rim");
        assert_eq!(c.weights(), &[1.0, 2.0, 0.5, 1.0]);
        // The rational cubic at u = 1/2: Σ w_i B_i P_i / Σ w_i B_i with B = 1/8 (1, 3, 3, 1).
        let (b, w) = ([1.0, 3.0, 3.0, 1.0], [1.0, 2.0, 0.5, 1.0]);
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 2.0, 0.0],
            [2.0, -1.0, 1.0],
            [3.0, 0.0, 0.0],
        ];
        let den: f64 = (0..4).map(|i| b[i] * w[i]).sum();
        let expected =
            Vector3::from_fn(|k, _| (0..4).map(|i| b[i] * w[i] * p[i][k]).sum::<f64>() / den);
        assert!((c.eval(0.5).unwrap() - expected).norm() < 1e-15);
        let Geometry::Curve2(bezier) = &items[1].geometry else {
            panic!("{:?}", items[1])
        };
        assert_eq!(
            bezier.knots().knots(),
            &[0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0]
        );
        assert_eq!(items[1].entity, "BEZIER_CURVE");
        let Geometry::Curve2(quasi) = &items[2].geometry else {
            panic!("{:?}", items[2])
        };
        assert_eq!(quasi.knots().knots(), &[0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0]);
    }

    fn wrap(data: &str) -> String {
        format!("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n{data}ENDSEC;\nEND-ISO-10303-21;\n")
    }

    #[test]
    fn malformed_files_give_one_line_errors_with_the_line() {
        let curve = "#1 = B_SPLINE_CURVE_WITH_KNOTS('',1,(#2,#3),.UNSPECIFIED.,.F.,.F.,(2,2),(0.,1.),.UNSPECIFIED.);\n";
        let points = "#2 = CARTESIAN_POINT('',(0.,0.,0.));\n#3 = CARTESIAN_POINT('',(1.,0.,0.));\n";
        assert_eq!(
            read_step(&wrap(&format!("{curve}{points}"))).unwrap().len(),
            1
        );
        let cases: Vec<(String, &str)> = vec![
            (String::new(), "empty"),
            (wrap(&format!("{curve}{points}"))[..60].to_string(), "ends"),
            (wrap(curve), "#2 is referenced but not defined"),
            (
                wrap(&format!("{}{points}", curve.replace("(2,2)", "(2,3)"))),
                "multiplicit",
            ),
            (
                wrap(&format!(
                    "{}{points}",
                    curve.replace("(2,2)", "(1000000000000,2)")
                )),
                "multiplicity",
            ),
            (
                wrap(&format!("{}{points}", curve.replace("(#2,#3)", "(#2)"))),
                "STEP line 5",
            ),
            (
                wrap(&format!(
                    "{curve}#2 = CARTESIAN_POINT('',(0.,0.,0.));\n#3 = CARTESIAN_POINT('é',(1.,0.,0.));\n"
                )),
                "ASCII",
            ),
            (wrap("#1 = CARTESIAN_POINT('',(0.,0.,0.);\n"), "STEP line 5"),
            (
                wrap(
                    "#1 = FOO(((((((((((((((((((((((((((((((((((((1)))))))))))))))))))))))))))))))))))));\n",
                ),
                "deep",
            ),
            ("HELLO;".to_string(), "not a STEP file"),
        ];
        for (text, words) in cases {
            let e = read_step_bytes(text.as_bytes()).unwrap_err().to_string();
            assert!(e.contains(words), "{words:?} not in {e:?}");
            assert!(!e.contains('\n'), "{e}");
        }
        // A reference cycle between wrappers ends (the wrappers are followed with a limit).
        let cycle = wrap(
            "#1 = TRIMMED_CURVE('',#2,(),(),.T.,.PARAMETER.);\n#2 = TRIMMED_CURVE('',#1,(),(),.T.,.PARAMETER.);\n#3 = EDGE_CURVE('e',#4,#4,#1,.T.);\n#4 = VERTEX_POINT('',#5);\n#5 = CARTESIAN_POINT('',(0.,0.,0.));\n",
        );
        assert!(read_step(&cycle).unwrap().is_empty());
    }

    /// Solids written by Open CASCADE (`tests/data/step/make_step_data.py`): every face's
    /// surface and every edge's curve arrives, the analytic ones as exact NURBS whose points
    /// lie on the closed form.
    #[test]
    fn analytic_b_rep_solids_from_open_cascade() {
        use std::collections::BTreeMap;
        let files = [
            (
                "fillet_box",
                include_str!("../tests/data/step/fillet_box.step"),
                7,
                15,
            ),
            (
                "cylinder",
                include_str!("../tests/data/step/cylinder.step"),
                3,
                3,
            ),
            ("cone", include_str!("../tests/data/step/cone.step"), 3, 3),
            ("torus", include_str!("../tests/data/step/torus.step"), 1, 2),
            (
                "sphere",
                include_str!("../tests/data/step/sphere.step"),
                1,
                0,
            ),
        ];
        for (name, text, faces, edges) in files {
            let items = read_step(text).unwrap();
            let mut kinds: BTreeMap<&str, usize> = BTreeMap::new();
            for item in &items {
                *kinds
                    .entry(
                        if matches!(
                            item.geometry,
                            Geometry::NurbsSurface(_) | Geometry::Surface(_)
                        ) {
                            "surface"
                        } else {
                            "curve"
                        },
                    )
                    .or_default() += 1;
            }
            // Distinct geometry: a seam line or a shared circle counts once.
            assert_eq!(
                kinds.get("surface").copied().unwrap_or(0),
                faces,
                "{name}: {kinds:?}"
            );
            assert!(
                kinds.get("curve").copied().unwrap_or(0) <= edges,
                "{name}: {kinds:?}"
            );
            for item in &items {
                let Geometry::NurbsSurface(s) = &item.geometry else {
                    continue;
                };
                let ((a, b), (c, d)) = s.domain();
                for i in 0..=8 {
                    for j in 0..=8 {
                        let (u, v) = (
                            a + (b - a) * f64::from(i) / 8.0,
                            c + (d - c) * f64::from(j) / 8.0,
                        );
                        let p = s.eval(u, v).unwrap();
                        let r = p.x.hypot(p.y);
                        let error = match (name, item.entity.as_str()) {
                            ("cylinder" | "fillet_box", "CYLINDRICAL_SURFACE")
                                if name == "cylinder" =>
                            {
                                (r - 3.0).abs() / 3.0
                            }
                            // Open CASCADE writes the semi-angle with 12 digits
                            // (0.463647609001 for atan(1/2)): the radius follows to 1e-12.
                            ("cone", "CONICAL_SURFACE") => {
                                (r - (3.0 - p.z / 2.0)).abs() / 3.0 * 1e-2
                            }
                            ("sphere", _) => (p.norm() - 2.0).abs() / 2.0,
                            ("torus", _) => ((r - 5.0).hypot(p.z) - 1.0).abs() / 5.0,
                            _ => 0.0,
                        };
                        assert!(
                            error < 1e-14,
                            "{name} {}: {p} off by {error:e}",
                            item.entity
                        );
                    }
                }
            }
        }
    }
}
