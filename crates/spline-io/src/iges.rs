//! IGES 5.3 (Initial Graphics Exchange Specification) files in and out: fixed-format ASCII
//! files of 80-column records, B-spline curves (entity 126) and surfaces (entity 128).
//!
//! A file is five sections, each record marked by its letter in column 73 and its sequence
//! number in columns 74–80: Start (`S`, free text), Global (`G`: the delimiters, units,
//! precision…), Directory Entry (`D`: two records of ten 8-column fields per entity),
//! Parameter Data (`P`: each entity's parameters in columns 1–64, its directory-entry
//! pointer in columns 65–72) and Terminate (`T`: the record counts).
//!
//! # Reading
//! [`read_iges`] returns, in directory order, every rational B-spline curve (126) and
//! surface (128) of the file, and converts exactly to NURBS the entities whose conversion
//! is exact and simple: the line segment (110, form 0), the circular arc (100), the surface
//! of revolution (120) and the tabulated cylinder (122) when their curves convert. Every
//! other entity (the B-rep of Open CASCADE: 186, 514, 510, 508, 504, 502; trimmed surfaces
//! 144 and 142, composite curves 102, conics 104, planes 108, the analytic surfaces
//! 190–198, properties, annotations…) is skipped without error. Curves referenced by a
//! 120 or 122 are returned on their own as well.
//!
//! - [`Item::id`] is the sequence number of the entity's first directory-entry record (an odd
//!   number), [`Item::entity`] the entity type number as text (`"126"`, `"110"`…),
//!   [`Item::name`] the name of a name property (406 form 15) the entity points to, else
//!   its directory-entry label (8 columns, blanks trimmed).
//! - Curves are read as 3-D curves, planar ones too (a 126 with `PROP1 = 1` and all `z = 0`
//!   is a 3-D curve in the plane `z = 0`); a curve is polynomial ([`Geometry::Curve3`]) when
//!   `PROP3 = 1` and its weights are equal, rational otherwise; likewise for surfaces.
//! - A transformation matrix (entity 124) referenced from a directory entry, and the chain
//!   of matrices the 124 itself references, is applied to the control points (affine maps
//!   commute with B-spline and NURBS evaluation, so this is exact up to rounding).
//! - A parameter range `V(0), V(1)` (surfaces: `U(0), U(1), V(0), V(1)`) narrower than the
//!   knot domain restricts the geometry to it exactly, by knot insertion; a range reaching
//!   outside the domain is intersected with the domain (writers round it).
//! - Coordinates are returned in the file's model units; the units of the Global section are
//!   checked for syntax but not applied.
//!
//! # Writing
//! [`write_iges`] writes each item as a 126 or a 128 (polynomial: `PROP3 = 1` and unit
//! weights; rational: the weights; 2-D curves as planar curves in `z = 0` with the normal
//! `(0, 0, 1)`), on its full knot domain, numbers in the shortest decimal form that reads
//! back to the same `f64` (`1.5E-7`), strings as Hollerith constants, model units
//! millimetres. The item's name goes into the 8-column label (truncated) and, when longer,
//! into a name property (406 form 15) the entity points to.
//!
//! # Errors
//! Every error is one line naming the section and the sequence number of the record:
//! `IGES line 57 (P): …` (`IGES file line 12: …` when the record's section is unknown).
//! Counts read from the file are checked against the number of parameters present before
//! anything is allocated.
//!
//! ```
//! use nalgebra::Vector3;
//! use spline_geom::BSpline;
//! use spline_io::iges::{read_iges, write_iges};
//! use spline_io::{Geometry, Item};
//! let line = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
//!     vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 2.0, 3.0)])?;
//! let item = Item { id: 0, name: "edge".into(), entity: String::new(), geometry: Geometry::Curve3(line) };
//! let text = write_iges(&[item.clone()])?;
//! let back = read_iges(&text)?;
//! assert_eq!(back[0].geometry, item.geometry);
//! assert_eq!((back[0].id, back[0].name.as_str(), back[0].entity.as_str()), (1, "edge", "126"));
//! # Ok::<(), spline_core::Error>(())
//! ```

use crate::{Geometry, Item};
use nalgebra::{Matrix3, Rotation3, Unit, Vector2, Vector3};
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result};
use spline_geom::{Axis, BSpline, Direction, Frame, NurbsCurve3, NurbsSurface3, Surface};
use std::fmt::{self, Write as _};

/// Columns of a record (without the line break).
const RECORD: usize = 80;
/// Columns of data in the Start and Global sections.
const GLOBAL_WIDTH: usize = 72;
/// Columns of parameters in a Parameter Data record.
const PARAM_WIDTH: usize = 64;

// ---------------------------------------------------------------------------------------
// Errors
// ---------------------------------------------------------------------------------------

/// The section of a record, for messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Section {
    Start,
    Global,
    Directory,
    Parameter,
    Terminate,
}

impl Section {
    fn letter(self) -> char {
        match self {
            Self::Start => 'S',
            Self::Global => 'G',
            Self::Directory => 'D',
            Self::Parameter => 'P',
            Self::Terminate => 'T',
        }
    }
}

impl fmt::Display for Section {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.letter())
    }
}

/// `IGES line {line} ({section}): {message}`, a parse error.
fn parse_error(section: Section, line: usize, message: impl fmt::Display) -> Error {
    Error::new(
        ErrorKind::Parse,
        format!("IGES line {line} ({section}): {message}"),
    )
}

/// Prefixes an error of the geometry layer with the record it comes from.
fn at(section: Section, line: usize) -> impl FnOnce(Error) -> Error {
    move |e| e.context(format_args!("IGES line {line} ({section})"))
}

// ---------------------------------------------------------------------------------------
// Reading: records and sections
// ---------------------------------------------------------------------------------------

/// Reads an IGES 5.3 file from bytes: as [`read_iges`], after checking that every byte is
/// ASCII.
///
/// # Errors
/// [`ErrorKind::Parse`] naming the line and column of the first byte that is not ASCII;
/// the errors of [`read_iges`].
pub fn read_iges_bytes(bytes: &[u8]) -> Result<Vec<Item>> {
    check_ascii(bytes)?;
    let text = std::str::from_utf8(bytes)
        .map_err(|_| Error::new(ErrorKind::Parse, "IGES file line 1: the file is not text"))?;
    read_iges(text)
}

/// The first byte that is not ASCII (or is a control character other than line breaks,
/// tabs and form feeds), as an error naming its line and column.
fn check_ascii(bytes: &[u8]) -> Result<()> {
    let bad = |b: u8| !(b.is_ascii_graphic() || matches!(b, b' ' | b'\n' | b'\r' | b'\t' | 0x0c));
    if let Some(i) = bytes.iter().position(|&b| bad(b)) {
        let line = 1 + bytes[..i].iter().filter(|&&b| b == b'\n').count();
        let start = bytes[..i]
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |k| k + 1);
        let what = if bytes[i].is_ascii() {
            "control character"
        } else {
            "non-ASCII byte"
        };
        return Err(Error::new(
            ErrorKind::Parse,
            format!(
                "IGES file line {line}: {what} 0x{:02X} in column {}; IGES files are ASCII",
                bytes[i],
                i - start + 1
            ),
        ));
    }
    Ok(())
}

/// The records of the five sections, each the text of columns 1–72.
struct Sections<'a> {
    global: Vec<&'a str>,
    directory: Vec<&'a str>,
    parameter: Vec<&'a str>,
    terminate: Option<&'a str>,
}

/// The physical lines of the file: line breaks, or 80-column records without breaks.
fn physical_lines(text: &str) -> Vec<&str> {
    let trimmed = text.trim_end_matches(['\n', '\r', '\u{1a}']);
    if !trimmed.contains('\n') && trimmed.len() > RECORD && trimmed.len() % RECORD == 0 {
        return (0..trimmed.len() / RECORD)
            .map(|k| &trimmed[k * RECORD..(k + 1) * RECORD])
            .collect();
    }
    trimmed
        .split('\n')
        .map(|l| l.strip_suffix('\r').unwrap_or(l))
        .collect()
}

fn split_sections(text: &str) -> Result<Sections<'_>> {
    let order = |c: char| match c {
        'S' => Some((0, Section::Start)),
        'G' => Some((1, Section::Global)),
        'D' => Some((2, Section::Directory)),
        'P' => Some((3, Section::Parameter)),
        'T' => Some((4, Section::Terminate)),
        _ => None,
    };
    let mut sections = Sections {
        global: Vec::new(),
        directory: Vec::new(),
        parameter: Vec::new(),
        terminate: None,
    };
    let mut counts = [0usize; 5];
    let mut current = 0;
    for (k, line) in physical_lines(text).into_iter().enumerate() {
        let file_line = k + 1;
        let file_error = |message: String| {
            Error::new(
                ErrorKind::Parse,
                format!("IGES file line {file_line}: {message}"),
            )
        };
        if line.trim().is_empty() {
            continue;
        }
        if line.len() > RECORD {
            return Err(file_error(format!(
                "the record has {} columns; IGES records have {RECORD}",
                line.len()
            )));
        }
        if line.len() < 73 {
            return Err(file_error(format!(
                "the record has {} columns, too few for the section letter in column 73 \
                 (a fixed-format IGES file has 80-column records)",
                line.len()
            )));
        }
        let letter = char::from(line.as_bytes()[72]);
        let Some((rank, section)) = order(letter) else {
            return Err(file_error(match letter {
                'C' => "compressed ASCII IGES files are not supported".to_string(),
                'B' => "binary IGES files are not supported".to_string(),
                _ => format!("unknown section letter '{letter}' in column 73"),
            }));
        };
        if rank < current {
            return Err(file_error(format!(
                "a record of section {section} after a later section"
            )));
        }
        if rank == 4 && counts[4] > 0 {
            return Err(file_error("a second Terminate record".to_string()));
        }
        current = rank;
        counts[rank] += 1;
        let expected = counts[rank];
        let number = line[73..].trim();
        if number.parse::<usize>().ok() != Some(expected) {
            return Err(parse_error(
                section,
                expected,
                format!(
                    "sequence number '{number}' in columns 74–80, expected {expected} (a record is missing or out of order)"
                ),
            ));
        }
        let data = &line[..72];
        match section {
            Section::Start => {}
            Section::Global => sections.global.push(data),
            Section::Directory => sections.directory.push(data),
            Section::Parameter => sections.parameter.push(data),
            Section::Terminate => sections.terminate = Some(data),
        }
    }
    let Some(terminate) = sections.terminate else {
        return Err(Error::new(
            ErrorKind::Parse,
            format!(
                "IGES line {} ({}): the file ends without a Terminate (T) record (truncated?)",
                counts[current].max(1),
                ["S", "G", "D", "P", "T"][current]
            ),
        ));
    };
    check_terminate(terminate, &counts)?;
    if sections.global.is_empty() {
        return Err(parse_error(
            Section::Global,
            1,
            "the file has no Global section",
        ));
    }
    if sections.directory.len() % 2 != 0 {
        return Err(parse_error(
            Section::Directory,
            sections.directory.len(),
            format!(
                "{} Directory Entry records; each entity has two",
                sections.directory.len()
            ),
        ));
    }
    Ok(sections)
}

/// The Terminate record's counts against the records read.
fn check_terminate(record: &str, counts: &[usize; 5]) -> Result<()> {
    for (k, letter) in ['S', 'G', 'D', 'P'].into_iter().enumerate() {
        let field = &record[8 * k..8 * k + 8];
        let ok = field.starts_with(letter);
        let value = field[1..].trim().parse::<usize>().ok();
        match value {
            Some(n) if ok => {
                if n != counts[k] {
                    return Err(parse_error(
                        Section::Terminate,
                        1,
                        format!(
                            "the Terminate record counts {n} {letter} records, the file has {} (truncated or damaged)",
                            counts[k]
                        ),
                    ));
                }
            }
            _ => {
                return Err(parse_error(
                    Section::Terminate,
                    1,
                    format!(
                        "field {} should be '{letter}' and a count, found '{}'",
                        k + 1,
                        field.trim()
                    ),
                ));
            }
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------
// Reading: free-format parameters
// ---------------------------------------------------------------------------------------

/// One parameter: a Hollerith string or the raw text of a number (empty when defaulted),
/// with the sequence number of the record it starts on.
#[derive(Clone, Debug)]
struct Token {
    text: String,
    string: bool,
    line: usize,
}

/// Splits the free-format text `buffer` (records of `width` columns concatenated, the first
/// being record `first_line` of `section`) into parameters up to the record delimiter.
fn tokenize(
    buffer: &[u8],
    width: usize,
    first_line: usize,
    section: Section,
    delimiters: (u8, u8),
    mut pos: usize,
) -> Result<Vec<Token>> {
    let (pd, rd) = delimiters;
    let line_of = |i: usize| first_line + i.min(buffer.len().saturating_sub(1)) / width;
    let mut tokens = Vec::new();
    loop {
        while pos < buffer.len() && buffer[pos] == b' ' {
            pos += 1;
        }
        if pos >= buffer.len() {
            return Err(parse_error(
                section,
                line_of(buffer.len()),
                format!(
                    "the parameters end without the record delimiter '{}' (truncated?)",
                    char::from(rd)
                ),
            ));
        }
        let start = pos;
        let digits_end = (pos..buffer.len())
            .find(|&i| !buffer[i].is_ascii_digit())
            .unwrap_or(buffer.len());
        let token = if digits_end > pos
            && digits_end < buffer.len()
            && matches!(buffer[digits_end], b'H' | b'h')
        {
            let count: usize = std::str::from_utf8(&buffer[pos..digits_end])
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(usize::MAX);
            let text_start = digits_end + 1;
            if count > buffer.len() - text_start {
                return Err(parse_error(
                    section,
                    line_of(start),
                    format!(
                        "a Hollerith string of {} characters runs past the end of the parameters",
                        &String::from_utf8_lossy(&buffer[pos..digits_end])
                    ),
                ));
            }
            pos = text_start + count;
            while pos < buffer.len() && buffer[pos] == b' ' {
                pos += 1;
            }
            Token {
                text: String::from_utf8_lossy(&buffer[text_start..text_start + count]).into_owned(),
                string: true,
                line: line_of(start),
            }
        } else {
            while pos < buffer.len() && buffer[pos] != pd && buffer[pos] != rd {
                pos += 1;
            }
            Token {
                text: String::from_utf8_lossy(&buffer[start..pos])
                    .trim()
                    .to_string(),
                string: false,
                line: line_of(start),
            }
        };
        if pos >= buffer.len() {
            continue; // reported above
        }
        let delimiter = buffer[pos];
        if delimiter != pd && delimiter != rd {
            return Err(parse_error(
                section,
                line_of(pos),
                format!(
                    "'{}' after a Hollerith string, expected the delimiter '{}' or '{}'",
                    char::from(delimiter),
                    char::from(pd),
                    char::from(rd)
                ),
            ));
        }
        pos += 1;
        tokens.push(token);
        if delimiter == rd {
            return Ok(tokens);
        }
    }
}

/// A real number in IGES form (`1.5`, `-2.`, `.5`, `1.5E-07`, `1.5D-07`; empty is the
/// default 0).
fn parse_real(token: &Token, section: Section, what: &str) -> Result<f64> {
    if token.string {
        return Err(parse_error(
            section,
            token.line,
            format!("{what}: a string where a number is expected"),
        ));
    }
    let text = token.text.as_str();
    if text.is_empty() {
        return Ok(0.0);
    }
    let valid = text
        .bytes()
        .all(|b| b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.' | b'E' | b'e' | b'D' | b'd'))
        && text.bytes().any(|b| b.is_ascii_digit());
    let normal: String = text
        .chars()
        .map(|c| if matches!(c, 'D' | 'd') { 'E' } else { c })
        .collect();
    let value = if valid {
        normal.parse::<f64>().ok()
    } else {
        None
    };
    match value {
        Some(x) if x.is_finite() => Ok(x),
        Some(_) => Err(parse_error(
            section,
            token.line,
            format!("{what}: {text} is out of the range of double precision"),
        )),
        None => Err(parse_error(
            section,
            token.line,
            format!("{what}: '{text}' is not a number"),
        )),
    }
}

/// An integer (empty is the default 0).
fn parse_int(token: &Token, section: Section, what: &str) -> Result<i64> {
    if token.string {
        return Err(parse_error(
            section,
            token.line,
            format!("{what}: a string where an integer is expected"),
        ));
    }
    let text = token.text.as_str();
    if text.is_empty() {
        return Ok(0);
    }
    text.strip_prefix('+')
        .unwrap_or(text)
        .parse::<i64>()
        .map_err(|_| {
            parse_error(
                section,
                token.line,
                format!("{what}: '{text}' is not an integer"),
            )
        })
}

/// The Global section: its delimiters (the rest is checked for syntax only).
fn parse_global(records: &[&str]) -> Result<(u8, u8)> {
    let buffer: Vec<u8> = records.iter().flat_map(|r| r.bytes()).collect();
    let mut pos = 0;
    while pos < buffer.len() && buffer[pos] == b' ' {
        pos += 1;
    }
    let hollerith_char = |pos: usize| -> Option<u8> {
        (buffer.len() > pos + 2 && buffer[pos] == b'1' && matches!(buffer[pos + 1], b'H' | b'h'))
            .then(|| buffer[pos + 2])
    };
    let bad = |message: &str| parse_error(Section::Global, 1, message);
    let pd = if let Some(c) = hollerith_char(pos) {
        pos += 3;
        c
    } else if buffer.get(pos) == Some(&b',') {
        b','
    } else {
        return Err(bad(
            "the Global section must start with the parameter delimiter (1H, or a defaulted ',')",
        ));
    };
    if buffer.get(pos) != Some(&pd) {
        return Err(bad("the parameter delimiter must be followed by itself"));
    }
    pos += 1;
    while pos < buffer.len() && buffer[pos] == b' ' {
        pos += 1;
    }
    let rd = if let Some(c) = hollerith_char(pos) {
        pos += 3;
        c
    } else if buffer.get(pos) == Some(&pd) {
        b';'
    } else {
        return Err(bad(
            "the second Global parameter must be the record delimiter (1H; or defaulted)",
        ));
    };
    if pd == rd || matches!(pd, b' ' | b'0'..=b'9' | b'H' | b'+' | b'-' | b'.') {
        return Err(bad(
            "the parameter and record delimiters are invalid or equal",
        ));
    }
    if buffer.get(pos) == Some(&rd) {
        return Ok((pd, rd));
    }
    if buffer.get(pos) != Some(&pd) {
        return Err(bad(
            "the record delimiter must be followed by the parameter delimiter",
        ));
    }
    let tokens = tokenize(&buffer, GLOBAL_WIDTH, 1, Section::Global, (pd, rd), pos + 1)?;
    // Fields 3 onwards: check the numbers that matter for geometry.
    for (index, what) in [
        (10, "model space scale (field 13)"),
        (16, "minimum resolution (field 19)"),
    ] {
        if let Some(t) = tokens.get(index) {
            parse_real(t, Section::Global, what)?;
        }
    }
    if let Some(t) = tokens.get(11) {
        parse_int(t, Section::Global, "unit flag (field 14)")?;
    }
    Ok((pd, rd))
}

// ---------------------------------------------------------------------------------------
// Reading: directory entries and parameters
// ---------------------------------------------------------------------------------------

/// One directory entry (the fields used here).
#[derive(Clone, Debug)]
struct Entry {
    /// Sequence number of the first record.
    seq: usize,
    kind: i64,
    data: i64,
    transform: i64,
    lines: i64,
    form: i64,
    label: String,
}

fn parse_entries(records: &[&str]) -> Result<Vec<Entry>> {
    let mut entries = Vec::with_capacity(records.len() / 2);
    for (k, pair) in records.chunks_exact(2).enumerate() {
        let seq = 2 * k + 1;
        let field = |line: usize, index: usize, what: &str| -> Result<i64> {
            let text = pair[line][8 * index..8 * index + 8].trim();
            if text.is_empty() {
                return Ok(0);
            }
            text.strip_prefix('+')
                .unwrap_or(text)
                .parse::<i64>()
                .map_err(|_| {
                    parse_error(
                        Section::Directory,
                        seq + line,
                        format!(
                            "field {} ({what}) '{text}' is not an integer",
                            10 * line + index + 1
                        ),
                    )
                })
        };
        let kind = field(0, 0, "entity type")?;
        let kind2 = field(1, 0, "entity type")?;
        if kind != kind2 {
            return Err(parse_error(
                Section::Directory,
                seq + 1,
                format!("entity type {kind2} differs from {kind} on the first record"),
            ));
        }
        entries.push(Entry {
            seq,
            kind,
            data: field(0, 1, "parameter data pointer")?,
            transform: field(0, 6, "transformation matrix pointer")?,
            lines: field(1, 3, "parameter line count")?,
            form: field(1, 4, "form number")?,
            label: pair[1][56..64].trim().to_string(),
        });
    }
    Ok(entries)
}

/// The parsed file: entries and parameter records, with parameters parsed on demand.
struct File<'a> {
    entries: Vec<Entry>,
    parameter: Vec<&'a str>,
    delimiters: (u8, u8),
    /// The map of each transformation matrix (124) read, with the matrices it references.
    chains: std::cell::RefCell<std::collections::HashMap<usize, Affine>>,
}

/// The parameters of one entity, read in order.
struct Params {
    tokens: Vec<Token>,
    pos: usize,
    /// The entity type, for messages.
    kind: i64,
    /// The record of the entity type, for messages about the whole list.
    first_line: usize,
}

impl Params {
    fn remaining(&self) -> usize {
        self.tokens.len() - self.pos
    }

    fn next(&mut self, what: &str) -> Result<&Token> {
        if self.pos >= self.tokens.len() {
            let line = self.tokens.last().map_or(self.first_line, |t| t.line);
            return Err(parse_error(
                Section::Parameter,
                line,
                format!(
                    "entity {} ends after {} parameters, {what} is missing",
                    self.kind,
                    self.tokens.len()
                ),
            ));
        }
        self.pos += 1;
        Ok(&self.tokens[self.pos - 1])
    }

    fn real(&mut self, what: &str) -> Result<f64> {
        let t = self.next(what)?;
        parse_real(t, Section::Parameter, what)
    }

    fn int(&mut self, what: &str) -> Result<i64> {
        let t = self.next(what)?;
        parse_int(t, Section::Parameter, what)
    }

    fn string(&mut self, what: &str) -> Result<String> {
        let t = self.next(what)?;
        if t.string || t.text.is_empty() {
            Ok(t.text.clone())
        } else {
            Err(parse_error(
                Section::Parameter,
                t.line,
                format!("{what}: '{}' is not a Hollerith string", t.text),
            ))
        }
    }

    /// A count in `min..`, checked.
    fn count(&mut self, what: &str, min: i64) -> Result<(usize, usize)> {
        let line = self.line();
        let n = self.int(what)?;
        if n < min {
            return Err(parse_error(
                Section::Parameter,
                line,
                format!("{what} = {n}, at least {min} expected"),
            ));
        }
        Ok((usize::try_from(n).unwrap_or(usize::MAX), line))
    }

    fn point(&mut self, what: &str) -> Result<Vector3<f64>> {
        Ok(Vector3::new(
            self.real(what)?,
            self.real(what)?,
            self.real(what)?,
        ))
    }

    /// The record of the next parameter.
    fn line(&self) -> usize {
        self.tokens
            .get(self.pos)
            .or(self.tokens.last())
            .map_or(self.first_line, |t| t.line)
    }

    /// Checks that `needed` more parameters are present (an error about `what` otherwise).
    fn require(&self, needed: Option<usize>, line: usize, what: impl fmt::Display) -> Result<()> {
        match needed {
            Some(n) if n <= self.remaining() => Ok(()),
            _ => Err(parse_error(
                Section::Parameter,
                line,
                format!(
                    "entity {}: {what} need {} more parameters, the entity has {}",
                    self.kind,
                    needed.map_or_else(|| "too many".to_string(), |n| n.to_string()),
                    self.remaining()
                ),
            )),
        }
    }
}

impl File<'_> {
    /// The entry a directory pointer designates.
    fn entry(&self, pointer: i64, from: &Entry, what: &str) -> Result<&Entry> {
        let index = usize::try_from(pointer)
            .ok()
            .filter(|&p| p % 2 == 1 && p / 2 < self.entries.len())
            .map(|p| p / 2);
        index.map(|i| &self.entries[i]).ok_or_else(|| {
            parse_error(
                Section::Directory,
                from.seq,
                format!(
                    "{what} {pointer} of entity {} is not the sequence number of a directory entry (1, 3, … {})",
                    from.kind,
                    2 * self.entries.len().max(1) - 1
                ),
            )
        })
    }

    /// The pointer of a parameter (`what`) of `params`, as a directory entry.
    fn pointed(&self, params: &mut Params, from: &Entry, what: &str) -> Result<&Entry> {
        let line = params.line();
        let pointer = params.int(what)?;
        self.entry(pointer, from, what).map_err(|_| {
            parse_error(
                Section::Parameter,
                line,
                format!(
                    "{what} {pointer} of entity {} is not the sequence number of a directory entry (1, 3, … {})",
                    from.kind,
                    2 * self.entries.len().max(1) - 1
                ),
            )
        })
    }

    /// The parameters of an entity, after its entity type.
    fn params(&self, entry: &Entry) -> Result<Params> {
        let count = self.parameter.len();
        let first = usize::try_from(entry.data)
            .ok()
            .filter(|&p| p >= 1 && p <= count);
        let lines = usize::try_from(entry.lines).ok().filter(|&n| n >= 1);
        let (Some(first), Some(lines)) = (first, lines) else {
            return Err(parse_error(
                Section::Directory,
                entry.seq,
                format!(
                    "entity {}: parameter data pointer {} and line count {} are outside the {count} Parameter Data records",
                    entry.kind, entry.data, entry.lines
                ),
            ));
        };
        if lines > count - first + 1 {
            return Err(parse_error(
                Section::Directory,
                entry.seq + 1,
                format!(
                    "entity {}: parameter line count {lines} from record {first} runs past the {count} Parameter Data records",
                    entry.kind
                ),
            ));
        }
        let mut buffer = Vec::with_capacity(lines * PARAM_WIDTH);
        for (k, record) in self.parameter[first - 1..first - 1 + lines]
            .iter()
            .enumerate()
        {
            let back = record[64..72].trim();
            if back.parse::<usize>().ok() != Some(entry.seq) {
                return Err(parse_error(
                    Section::Parameter,
                    first + k,
                    format!(
                        "the directory pointer '{back}' in columns 65–72 should be {}, the entity's directory entry",
                        entry.seq
                    ),
                ));
            }
            buffer.extend_from_slice(&record.as_bytes()[..PARAM_WIDTH]);
        }
        let mut tokens = tokenize(
            &buffer,
            PARAM_WIDTH,
            first,
            Section::Parameter,
            self.delimiters,
            0,
        )?;
        let kind_token = tokens.remove(0);
        let kind = parse_int(&kind_token, Section::Parameter, "entity type")?;
        if kind != entry.kind {
            return Err(parse_error(
                Section::Parameter,
                first,
                format!(
                    "the parameters are of entity type {kind}, the directory entry {} says {}",
                    entry.seq, entry.kind
                ),
            ));
        }
        Ok(Params {
            tokens,
            pos: 0,
            kind,
            first_line: first,
        })
    }

    /// The transformation of an entry: its matrix (124), composed with the matrices that
    /// matrix references in turn; `None` when there is none.
    fn transform(&self, entry: &Entry) -> Result<Option<Affine>> {
        // The matrices of the chain not yet known, and the known rest of the chain.
        let mut walk: Vec<(usize, Affine)> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        let mut tail: Option<Affine> = None;
        let mut pointer = entry.transform;
        let mut from = entry;
        while pointer != 0 {
            let matrix = self.entry(pointer, from, "transformation matrix pointer")?;
            if matrix.kind != 124 {
                return Err(parse_error(
                    Section::Directory,
                    from.seq,
                    format!(
                        "the transformation matrix pointer {pointer} designates an entity {}, not a 124",
                        matrix.kind
                    ),
                ));
            }
            if let Some(known) = self.chains.borrow().get(&matrix.seq) {
                tail = Some(*known);
                break;
            }
            if !seen.insert(matrix.seq) {
                return Err(parse_error(
                    Section::Directory,
                    matrix.seq,
                    "the transformation matrices reference each other in a cycle",
                ));
            }
            let mut params = self.params(matrix)?;
            let mut m = Matrix3::zeros();
            let mut t = Vector3::zeros();
            for r in 0..3 {
                for c in 0..3 {
                    m[(r, c)] = params.real("matrix entry")?;
                }
                t[r] = params.real("translation")?;
            }
            walk.push((matrix.seq, Affine { m, t }));
            pointer = matrix.transform;
            from = matrix;
        }
        // Each matrix first, then the ones it references: remember every chain's map, so
        // that long shared chains are composed once.
        let mut total = tail;
        for (seq, this) in walk.into_iter().rev() {
            let full = match total {
                None => this,
                Some(outer) => outer.after(&this),
            };
            self.chains.borrow_mut().insert(seq, full);
            total = Some(full);
        }
        Ok(total)
    }

    /// The name of a name property (406 form 15) among the additional pointers that follow
    /// an entity's own parameters, if any.
    fn property_name(&self, params: &mut Params, entry: &Entry) -> Result<Option<String>> {
        if params.remaining() == 0 {
            return Ok(None);
        }
        let (associations, line) = params.count("number of associativity pointers", 0)?;
        params.require(Some(associations), line, "the associativity pointers")?;
        params.pos += associations;
        if params.remaining() == 0 {
            return Ok(None);
        }
        let (properties, line) = params.count("number of property pointers", 0)?;
        params.require(Some(properties), line, "the property pointers")?;
        let mut name = None;
        for _ in 0..properties {
            let property = self.pointed(params, entry, "property pointer")?;
            if property.kind == 406 && property.form == 15 && name.is_none() {
                let mut p = self.params(property)?;
                let (count, _) = p.count("number of property values", 1)?;
                let _ = count;
                name = Some(p.string("name")?);
            }
        }
        Ok(name)
    }
}

// ---------------------------------------------------------------------------------------
// Geometry
// ---------------------------------------------------------------------------------------

/// An affine map $x \mapsto M x + t$ (entity 124).
#[derive(Clone, Copy, Debug)]
struct Affine {
    m: Matrix3<f64>,
    t: Vector3<f64>,
}

impl Affine {
    fn apply(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.m * p + self.t
    }

    /// `self ∘ inner`.
    fn after(&self, inner: &Self) -> Self {
        Self {
            m: self.m * inner.m,
            t: self.m * inner.t + self.t,
        }
    }
}

/// A converted curve, polynomial or rational.
#[derive(Clone, Debug)]
enum Curve {
    Poly(BSpline<f64, Vector3<f64>>),
    Rational(NurbsCurve3<f64>),
}

impl Curve {
    fn transformed(self, affine: Option<Affine>) -> Self {
        let Some(a) = affine else { return self };
        match self {
            Self::Poly(c) => Self::Poly(c.map_control_points(|p| a.apply(p))),
            Self::Rational(c) => Self::Rational(c.map_control_points(|p| a.apply(p))),
        }
    }

    fn rational(&self) -> NurbsCurve3<f64> {
        match self {
            Self::Poly(c) => NurbsCurve3::from_bspline(c),
            Self::Rational(c) => c.clone(),
        }
    }

    fn geometry(self) -> Geometry {
        match self {
            Self::Poly(c) => Geometry::Curve3(c),
            Self::Rational(c) => Geometry::NurbsCurve3(c),
        }
    }
}

/// A converted surface, polynomial or rational.
enum Patch {
    Poly(Surface<f64, Vector3<f64>>),
    Rational(NurbsSurface3<f64>),
}

impl Patch {
    fn transformed(self, affine: Option<Affine>) -> Self {
        let Some(a) = affine else { return self };
        match self {
            Self::Poly(s) => Self::Poly(s.map_control_points(|p| a.apply(p))),
            Self::Rational(s) => Self::Rational(s.map_control_points(|p| a.apply(p))),
        }
    }

    fn geometry(self) -> Geometry {
        match self {
            Self::Poly(s) => Geometry::Surface(s),
            Self::Rational(s) => Geometry::NurbsSurface(s),
        }
    }
}

/// The domain `[lo, hi]` restricted to the parameter range `[a, b]` read from the file:
/// `None` when the range covers the domain, the intersection otherwise.
fn range_within(
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
fn restrict_surface<P: ControlPoint<f64>>(
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
fn equal_weights(weights: &[f64]) -> bool {
    weights.iter().all(|&w| w == weights[0])
}

/// Entity 126, the rational B-spline curve.
fn read_126(params: &mut Params) -> Result<Curve> {
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
fn read_128(params: &mut Params) -> Result<Patch> {
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
fn read_110(params: &mut Params) -> Result<Curve> {
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
fn read_100(params: &mut Params) -> Result<Curve> {
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
enum Read {
    Curve(Curve),
    Patch(Patch),
    /// Not geometry this reader converts.
    Skipped,
}

impl File<'_> {
    /// Converts the entity `entry` (its own transformation applied); `depth` bounds the
    /// recursion through the curves of 120 and 122.
    fn convert(&self, entry: &Entry, depth: usize) -> Result<(Read, Option<Params>)> {
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
    fn curve_at(&self, params: &mut Params, from: &Entry, what: &str) -> Result<Option<Curve>> {
        let entry = self.pointed(params, from, what)?;
        Ok(match self.convert(entry, 1)?.0 {
            Read::Curve(c) => Some(c),
            _ => None,
        })
    }

    /// Entity 120, the surface of revolution of a generatrix about an axis (a 110) from
    /// angle `SA` to `TA`: `u` along the generatrix, `v ∈ [0, 1]` along the circles.
    fn read_120(&self, params: &mut Params, entry: &Entry) -> Result<Read> {
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
    fn read_122(&self, params: &mut Params, entry: &Entry) -> Result<Read> {
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

/// Reads the B-spline geometry of an IGES 5.3 fixed-format ASCII file (see the
/// [module documentation](self) for what is read and how).
///
/// # Errors
/// [`ErrorKind::Parse`] with a message `IGES line N (X): …` for a malformed file: records
/// that are not 80 columns with a section letter, sections out of order or truncated
/// (the Terminate record's counts), sequence numbers out of order, bad delimiters or
/// numbers, pointers outside the file, transformation matrices referencing each other in a
/// cycle, counts that the parameters present do not match, non-ASCII text; the errors of
/// the geometry constructors (unsorted knots, non-positive weights…) prefixed with the
/// record.
pub fn read_iges(text: &str) -> Result<Vec<Item>> {
    check_ascii(text.as_bytes())?;
    let sections = split_sections(text)?;
    let delimiters = parse_global(&sections.global)?;
    let file = File {
        entries: parse_entries(&sections.directory)?,
        parameter: sections.parameter,
        delimiters,
        chains: std::cell::RefCell::default(),
    };
    let mut items = Vec::new();
    for entry in &file.entries {
        let (read, params) = file.convert(entry, 0)?;
        let geometry = match read {
            Read::Curve(c) => c.geometry(),
            Read::Patch(s) => s.geometry(),
            Read::Skipped => continue,
        };
        let mut name = entry.label.clone();
        if let (Some(mut params), 126 | 128) = (params, entry.kind) {
            if let Some(n) = file.property_name(&mut params, entry)? {
                name = n;
            }
        }
        items.push(Item {
            id: entry.seq as u64,
            name,
            entity: entry.kind.to_string(),
            geometry,
        });
    }
    Ok(items)
}

// ---------------------------------------------------------------------------------------
// Writing
// ---------------------------------------------------------------------------------------

/// A real number in the shortest decimal form that reads back to the same `f64`, with a
/// decimal point, in exponent form (`E`) for small and large magnitudes.
fn real(x: f64) -> String {
    let magnitude = x.abs();
    if x == 0.0 || (1e-5..1e16).contains(&magnitude) {
        let s = format!("{x}");
        if s.contains('.') { s } else { s + ".0" }
    } else {
        let s = format!("{x:e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        if mantissa.contains('.') {
            format!("{mantissa}E{exponent}")
        } else {
            format!("{mantissa}.0E{exponent}")
        }
    }
}

/// A Hollerith string constant.
fn hollerith(s: &str) -> String {
    format!("{}H{s}", s.len())
}

/// The parameters of one entity as text pieces (each written with its delimiter after).
struct Entity {
    kind: u32,
    form: u32,
    label: String,
    params: Vec<String>,
}

/// Packs parameters into records of `width` columns: each parameter followed by its
/// delimiter, never split except a string longer than a record.
fn pack(params: &[String], width: usize) -> Vec<String> {
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
fn curve_params(
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
fn surface_params(
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

fn lift(p: &Vector2<f64>) -> Vector3<f64> {
    Vector3::new(p.x, p.y, 0.0)
}

/// The largest coordinate magnitude of an item's control points.
fn max_coordinate(geometry: &Geometry) -> f64 {
    let max = |it: &mut dyn Iterator<Item = f64>| it.fold(0.0f64, |m, x| m.max(x.abs()));
    match geometry {
        Geometry::Curve2(c) => max(&mut c.control_points().iter().flat_map(|p| p.iter().copied())),
        Geometry::NurbsCurve2(c) => {
            max(&mut c.control_points().iter().flat_map(|p| p.iter().copied()))
        }
        Geometry::Curve3(c) => max(&mut c.control_points().iter().flat_map(|p| p.iter().copied())),
        Geometry::NurbsCurve3(c) => {
            max(&mut c.control_points().iter().flat_map(|p| p.iter().copied()))
        }
        Geometry::Surface(s) => max(&mut s.control_points().iter().flat_map(|p| p.iter().copied())),
        Geometry::NurbsSurface(s) => {
            max(&mut s.control_points().iter().flat_map(|p| p.iter().copied()))
        }
    }
}

/// The entity parameters of an item (the containers hold finite numbers only). Unclamped
/// geometry is clamped first (knots inserted at the ends of the domain: the same curve or
/// surface on the same parameters), since readers such as Open CASCADE's take the end knots
/// of a 126 or 128 as the ends of its domain.
fn entity_params(item: &Item) -> Vec<String> {
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
fn timestamp() -> String {
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
/// documentation](self)): one 126 per curve, one 128 per surface, a 406 form 15 name
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
            ));
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

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;
    use spline_geom::NurbsCurve2;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn item(name: &str, geometry: Geometry) -> Item {
        Item {
            id: 0,
            name: name.to_string(),
            entity: String::new(),
            geometry,
        }
    }

    /// Reproducible awkward numbers (not representable in few decimal digits).
    struct Numbers(u64);

    impl Numbers {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let unit = (self.0 >> 11) as f64 / (1u64 << 53) as f64;
            (unit - 0.5) * 7.0 / 3.0
        }

        fn point3(&mut self) -> Vector3<f64> {
            Vector3::new(self.next(), self.next() * 1e3, self.next() * 1e-6)
        }

        fn weight(&mut self) -> f64 {
            0.3 + (self.next() + 1.2).abs()
        }
    }

    fn bits3(points: &[Vector3<f64>]) -> Vec<[u64; 3]> {
        points
            .iter()
            .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
            .collect()
    }

    fn bits(values: &[f64]) -> Vec<u64> {
        values.iter().map(|x| x.to_bits()).collect()
    }

    /// A knot vector of degree `p` on `[0, 1]` with interior knots of multiplicities 1, p,
    /// 2 (awkward values), clamped or not.
    fn knots(p: usize, clamped: bool) -> KnotVector<f64> {
        let mut k = Vec::new();
        if clamped {
            k.extend(std::iter::repeat_n(0.0, p + 1));
        } else {
            k.extend((0..=p).map(|i| -0.1 * (p - i) as f64));
        }
        k.push(0.1);
        k.extend(std::iter::repeat_n(1.0 / 3.0, p));
        k.extend(std::iter::repeat_n(0.7, 2.min(p)));
        if clamped {
            k.extend(std::iter::repeat_n(1.0, p + 1));
        } else {
            k.extend((0..=p).map(|i| 1.0 + 0.25 * i as f64));
        }
        KnotVector::new(p, k).unwrap()
    }

    fn one(text: &str) -> Item {
        let items = read_iges(text).unwrap();
        assert_eq!(items.len(), 1, "{items:?}");
        items.into_iter().next().unwrap()
    }

    #[test]
    fn polynomial_curves_round_trip_bit_for_bit() {
        let mut rng = Numbers(1);
        for p in 1..=7 {
            for clamped in [true, false] {
                let kv = knots(p, clamped);
                let points: Vec<_> = (0..kv.num_basis()).map(|_| rng.point3()).collect();
                let curve = BSpline::new(kv, points).unwrap();
                let text = write_iges(&[item("c", Geometry::Curve3(curve.clone()))]).unwrap();
                assert!(text.lines().all(|l| l.len() == 80));
                let back = one(&text);
                // Unclamped curves come back clamped: the same curve on the same parameters.
                let curve = curve.clamped();
                assert_eq!(back.entity, "126");
                assert_eq!(back.id, 1);
                assert_eq!(back.name, "c");
                let Geometry::Curve3(c) = back.geometry else {
                    panic!("degree {p}: not a polynomial curve");
                };
                assert_eq!(bits(c.knots().knots()), bits(curve.knots().knots()));
                assert_eq!(bits3(c.control_points()), bits3(curve.control_points()));
                assert_eq!(c.degree(), p);
            }
        }
    }

    #[test]
    fn rational_curves_round_trip_bit_for_bit() {
        let mut rng = Numbers(2);
        for p in 1..=7 {
            let kv = knots(p, p % 2 == 0);
            let n = kv.num_basis();
            let points: Vec<_> = (0..n).map(|_| rng.point3()).collect();
            let weights: Vec<_> = (0..n).map(|_| rng.weight()).collect();
            let curve = NurbsCurve3::new(kv, points, weights).unwrap();
            let text = write_iges(&[item("r", Geometry::NurbsCurve3(curve.clone()))]).unwrap();
            let Geometry::NurbsCurve3(c) = one(&text).geometry else {
                panic!("degree {p}: not rational");
            };
            let curve = curve.clamped();
            assert_eq!(bits(c.knots().knots()), bits(curve.knots().knots()));
            assert_eq!(bits(c.weights()), bits(curve.weights()));
            assert_eq!(bits3(c.control_points()), bits3(curve.control_points()));
            // Written again, the text is the same (the file's numbers are a fixed point).
            let again = write_iges(&[item("r", Geometry::NurbsCurve3(c))]).unwrap();
            let strip = |t: &str| {
                t.lines()
                    .filter(|l| !l.contains('G'))
                    .map(|l| l[..72].to_string())
                    .collect::<Vec<_>>()
            };
            assert_eq!(strip(&again)[1..], strip(&text)[1..]);
        }
    }

    #[test]
    fn planar_curves_are_written_in_z_0_and_read_as_3d() {
        let mut rng = Numbers(3);
        let kv = knots(3, true);
        let n = kv.num_basis();
        let points: Vec<_> = (0..n)
            .map(|_| Vector2::new(rng.next(), rng.next()))
            .collect();
        let weights: Vec<_> = (0..n).map(|_| rng.weight()).collect();
        let poly = BSpline::new(kv.clone(), points.clone()).unwrap();
        let rational = NurbsCurve2::new(kv, points, weights).unwrap();
        let text = write_iges(&[
            item("p", Geometry::Curve2(poly.clone())),
            item("q", Geometry::NurbsCurve2(rational.clone())),
        ])
        .unwrap();
        // PROP1 = 1 (planar), normal (0, 0, 1) before the terminator.
        assert!(text.contains("126,9,3,1,0,1,0,"));
        assert!(text.contains("0.0,0.0,1.0;"));
        let items = read_iges(&text).unwrap();
        assert_eq!((items[0].id, items[1].id), (1, 3));
        let Geometry::Curve3(c) = &items[0].geometry else {
            panic!()
        };
        assert!(c.control_points().iter().all(|p| p.z.to_bits() == 0));
        let xy: Vec<_> = c
            .control_points()
            .iter()
            .map(|p| [p.x.to_bits(), p.y.to_bits()])
            .collect();
        let want: Vec<_> = poly
            .control_points()
            .iter()
            .map(|p| [p.x.to_bits(), p.y.to_bits()])
            .collect();
        assert_eq!(xy, want);
        let Geometry::NurbsCurve3(r) = &items[1].geometry else {
            panic!()
        };
        assert_eq!(bits(r.weights()), bits(rational.weights()));
        let xy: Vec<_> = r
            .control_points()
            .iter()
            .map(|p| [p.x.to_bits(), p.y.to_bits()])
            .collect();
        let want: Vec<_> = rational
            .control_points()
            .iter()
            .map(|p| [p.x.to_bits(), p.y.to_bits()])
            .collect();
        assert_eq!(xy, want);
    }

    #[test]
    fn surfaces_round_trip_bit_for_bit() {
        let mut rng = Numbers(4);
        for (p, q) in [(1, 1), (3, 2), (2, 5), (7, 1)] {
            let (ku, kv) = (knots(p, true), knots(q, false));
            let count = ku.num_basis() * kv.num_basis();
            let points: Vec<_> = (0..count).map(|_| rng.point3()).collect();
            let weights: Vec<_> = (0..count).map(|_| rng.weight()).collect();
            let poly = Surface::new(ku.clone(), kv.clone(), points.clone()).unwrap();
            let rational = NurbsSurface3::new(ku, kv, points, weights).unwrap();
            let text = write_iges(&[
                item("s", Geometry::Surface(poly.clone())),
                item("n", Geometry::NurbsSurface(rational.clone())),
            ])
            .unwrap();
            let items = read_iges(&text).unwrap();
            let (poly, rational) = (poly.clamped(), rational.clamped());
            assert_eq!(items[0].entity, "128");
            let Geometry::Surface(s) = &items[0].geometry else {
                panic!()
            };
            assert_eq!(s.net_size(), poly.net_size());
            assert_eq!(bits(s.knots_u().knots()), bits(poly.knots_u().knots()));
            assert_eq!(bits(s.knots_v().knots()), bits(poly.knots_v().knots()));
            assert_eq!(bits3(s.control_points()), bits3(poly.control_points()));
            let Geometry::NurbsSurface(r) = &items[1].geometry else {
                panic!()
            };
            assert_eq!(bits(r.weights()), bits(rational.weights()));
            assert_eq!(bits3(r.control_points()), bits3(rational.control_points()));
        }
    }

    #[test]
    fn names_go_to_the_label_and_a_name_property() {
        let c = BSpline::from_knots(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![Vector3::zeros(), Vector3::x()],
        )
        .unwrap();
        let text = write_iges(&[
            item("short", Geometry::Curve3(c.clone())),
            item(
                "a name longer than eight characters",
                Geometry::Curve3(c.clone()),
            ),
            item("", Geometry::Curve3(c)),
        ])
        .unwrap();
        assert!(text.contains("35Ha name longer than eight characters;"));
        let items = read_iges(&text).unwrap();
        let names: Vec<_> = items.iter().map(|i| (i.id, i.name.as_str())).collect();
        assert_eq!(
            names,
            [
                (1, "short"),
                (3, "a name longer than eight characters"),
                (7, "")
            ]
        );
        let bad = item("é", items[0].geometry.clone());
        assert_eq!(
            write_iges(&[bad]).unwrap_err().kind(),
            ErrorKind::InvalidArgument
        );
    }

    #[test]
    fn numbers_are_written_short_and_read_back_exactly() {
        let cases = [
            0.1,
            1.0 / 3.0,
            -0.0,
            5e-324,
            f64::MAX,
            f64::MIN_POSITIVE,
            1e16,
            1e-5,
            1e16 - 2.0,
            -123_456.789,
            2.0,
        ];
        for x in cases {
            let s = real(x);
            assert!(s.contains('.'), "{s}");
            assert!(s.len() <= 24, "{s}");
            let t = Token {
                text: s.clone(),
                string: false,
                line: 1,
            };
            assert_eq!(
                parse_real(&t, Section::Parameter, "x").unwrap().to_bits(),
                x.to_bits(),
                "{s}"
            );
        }
        assert_eq!(real(1.5e-7), "1.5E-7");
        assert_eq!(real(2.0), "2.0");
        for (text, value) in [
            ("1.5D-07", 1.5e-7),
            ("1.5d+3", 1500.0),
            ("-2.", -2.0),
            (".5", 0.5),
            ("+3", 3.0),
            ("", 0.0),
            ("1.E2", 100.0),
        ] {
            let t = Token {
                text: text.to_string(),
                string: false,
                line: 1,
            };
            assert_eq!(
                parse_real(&t, Section::Parameter, "x").unwrap(),
                value,
                "{text}"
            );
        }
        for text in ["1.2.3", "inf", "NaN", "1E999", "0x10", "-"] {
            let t = Token {
                text: text.to_string(),
                string: false,
                line: 7,
            };
            let e = parse_real(&t, Section::Parameter, "knot").unwrap_err();
            assert!(e.message().starts_with("IGES line 7 (P): knot"), "{e}");
        }
    }

    // -----------------------------------------------------------------------------------
    // Hand-written files: the records are formatted here, independently of the writer.
    // -----------------------------------------------------------------------------------

    /// One entity of a hand-written file: type, form, transformation pointer, label,
    /// parameters (with their delimiters, as they appear in the file).
    struct Hand<'a>(i64, i64, i64, &'a str, &'a str);

    fn hand_file(entities: &[Hand<'_>]) -> String {
        let mut s = String::new();
        let mut rec = |data: &str, letter: char, seq: usize| {
            s.push_str(&format!("{data:<72}{letter}{seq:07}\n"));
        };
        rec("hand-written IGES test file", 'S', 1);
        rec(
            "1H,,1H;,4Htest,,,,32,38,6,308,15,,1.0,2,2HMM,1,1.0,",
            'G',
            1,
        );
        rec("15H20260101.120000,1.0E-7,10.0,,,11,0;", 'G', 2);
        let mut p_lines: Vec<(String, usize)> = Vec::new();
        let mut d_lines = Vec::new();
        for (k, Hand(kind, form, transform, label, params)) in entities.iter().enumerate() {
            let de = 2 * k + 1;
            let first = p_lines.len() + 1;
            // Split after delimiters into records of at most 64 columns.
            let mut current = String::new();
            for piece in params.split_inclusive([',', ';', '/', '$']) {
                if current.len() + piece.len() > 64 {
                    p_lines.push((std::mem::take(&mut current), de));
                }
                current.push_str(piece);
            }
            p_lines.push((current, de));
            let count = p_lines.len() + 1 - first;
            d_lines.push(format!(
                "{kind:8}{first:8}{:8}{:8}{:8}{:8}{transform:8}{:8}00000000",
                0, 0, 1, 0, 0
            ));
            d_lines.push(format!(
                "{kind:8}{:8}{:8}{count:8}{form:8}{:8}{:8}{label:>8}{:8}",
                0, 0, "", "", 0
            ));
        }
        for (k, d) in d_lines.iter().enumerate() {
            rec(d, 'D', k + 1);
        }
        for (k, (p, de)) in p_lines.iter().enumerate() {
            rec(&format!("{p:<64}{de:8}"), 'P', k + 1);
        }
        rec(
            &format!(
                "S{:07}G{:07}D{:07}P{:07}",
                1,
                2,
                d_lines.len(),
                p_lines.len()
            ),
            'T',
            1,
        );
        s
    }

    /// The quarter circle `((1 − t²)/(1 + t²), 2t/(1 + t²))`, `t ∈ [0, 1]`, with the
    /// parameter range given (entity 126, numbers in the D and bare-point notations).
    const QUARTER: &str = "126,2,2,1,0,0,0,0.,0.,0.,1.,1.,1.,1.0D0,1.,2.,1.,0.,0.,1.,1.,0.,0.,1.,0.,0.25,0.75,0.,0.,1.;";

    #[test]
    fn hand_written_quarter_circle_restricted_to_its_range() {
        let text = hand_file(&[Hand(126, 0, 0, "ARC1", QUARTER)]);
        let item = one(&text);
        assert_eq!(
            (item.id, item.name.as_str(), item.entity.as_str()),
            (1, "ARC1", "126")
        );
        let Geometry::NurbsCurve3(c) = item.geometry else {
            panic!()
        };
        assert_eq!(c.domain(), (0.25, 0.75));
        for t in [0.25, 0.3, 0.5, 0.6, 0.75] {
            let want = Vector3::new((1.0 - t * t) / (1.0 + t * t), 2.0 * t / (1.0 + t * t), 0.0);
            assert!((c.eval(t).unwrap() - want).norm() < 1e-15, "t = {t}");
        }
        // The full range reads the curve as written.
        let full = QUARTER.replace("0.25,0.75", "0.,1.");
        let Geometry::NurbsCurve3(c) = one(&hand_file(&[Hand(126, 0, 0, "", &full)])).geometry
        else {
            panic!()
        };
        assert_eq!(c.weights(), [1.0, 1.0, 2.0]);
        assert_eq!(c.control_points()[1], Vector3::new(1.0, 1.0, 0.0));
    }

    #[test]
    fn hand_written_surface_has_the_u_index_fastest() {
        // K1 = 1, K2 = 2, M1 = 1, M2 = 2: P(i, j) = (i, j, 10 i + j), listed i fastest, so
        // S(u, v) = (u, 2v, 10u + 2v).
        let params = "128,1,2,1,2,0,0,1,0,0,0.,0.,1.,1.,0.,0.,0.,1.,1.,1.,\
                      1.,1.,1.,1.,1.,1.,\
                      0.,0.,0.,1.,0.,10.,0.,1.,1.,1.,1.,11.,0.,2.,2.,1.,2.,12.,\
                      0.,1.,0.,1.;";
        let item = one(&hand_file(&[Hand(128, 0, 0, "PATCH", params)]));
        let Geometry::Surface(s) = item.geometry else {
            panic!()
        };
        assert_eq!(s.net_size(), (2, 3));
        assert_eq!(s.control_point(1, 2), Vector3::new(1.0, 2.0, 12.0));
        let (u, v) = (0.3, 0.6);
        assert!(
            (s.eval(u, v).unwrap() - Vector3::new(u, 2.0 * v, 10.0 * u + 2.0 * v)).norm() < 1e-14
        );
        // A range narrower in v restricts the surface exactly.
        let narrow = params.replace("0.,1.,0.,1.;", "0.,1.,0.5,1.;");
        let Geometry::Surface(s) = one(&hand_file(&[Hand(128, 0, 0, "", &narrow)])).geometry else {
            panic!()
        };
        assert_eq!(s.domain(), ((0.0, 1.0), (0.5, 1.0)));
        assert!((s.eval(u, 0.75).unwrap() - Vector3::new(u, 1.5, 10.0 * u + 1.5)).norm() < 1e-14);
    }

    /// A 124: rotation by 90° about z, then a translation.
    const ROTATE_Z: &str = "124,0.,-1.,0.,0.,1.,0.,0.,0.,0.,0.,1.,0.;";
    const SHIFT_X: &str = "124,1.,0.,0.,1.,0.,1.,0.,0.,0.,0.,1.,0.;";

    #[test]
    fn lines_arcs_and_transformations() {
        let text = hand_file(&[
            Hand(124, 0, 5, "", SHIFT_X), // 1: shift by x, then the matrix at 5
            Hand(110, 0, 1, "L1", "110,0.,0.,0.,1.,2.,3.;"), // 3
            Hand(124, 0, 0, "", ROTATE_Z), // 5
            Hand(100, 0, 0, "A1", "100,5.,1.,1.,2.,1.,1.,2.;"), // 7: quarter arc at z = 5
            Hand(100, 0, 0, "C1", "100,0.,0.,0.,2.,0.,2.,0.;"), // 9: full circle r = 2
            Hand(314, 0, 0, "", "314,50.,50.,50.;"), // 11: a colour, skipped
            Hand(110, 1, 0, "", "110,0.,0.,0.,1.,0.,0.;"), // 13: a ray, skipped
        ]);
        let items = read_iges(&text).unwrap();
        let ids: Vec<_> = items
            .iter()
            .map(|i| (i.id, i.entity.as_str(), i.name.as_str()))
            .collect();
        assert_eq!(ids, [(3, "110", "L1"), (7, "100", "A1"), (9, "100", "C1")]);
        // The line: x ↦ R(x + (1, 0, 0)), R the rotation by 90° about z.
        let Geometry::Curve3(line) = &items[0].geometry else {
            panic!()
        };
        assert_eq!(
            line.control_points(),
            [Vector3::new(0.0, 1.0, 0.0), Vector3::new(-2.0, 2.0, 3.0)]
        );
        let Geometry::NurbsCurve3(arc) = &items[1].geometry else {
            panic!()
        };
        let center = Vector3::new(1.0, 1.0, 5.0);
        for t in [0.0, 0.2, 0.5, 0.9, 1.0] {
            let p = arc.eval(t).unwrap();
            assert!(((p - center).norm() - 1.0).abs() < 1e-15);
        }
        assert!((arc.eval(0.0).unwrap() - Vector3::new(2.0, 1.0, 5.0)).norm() < 1e-15);
        assert!((arc.eval(1.0).unwrap() - Vector3::new(1.0, 2.0, 5.0)).norm() < 1e-15);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((arc.eval(0.5).unwrap() - (center + Vector3::new(h, h, 0.0))).norm() < 1e-15);
        let Geometry::NurbsCurve3(circle) = &items[2].geometry else {
            panic!()
        };
        for t in [0.0, 0.1, 0.37, 0.5, 0.81] {
            assert!((circle.eval(t).unwrap().norm() - 2.0).abs() < 1e-15);
        }
        assert!((circle.eval(0.25).unwrap() - Vector3::new(0.0, 2.0, 0.0)).norm() < 1e-15);
        assert_eq!(circle.eval(1.0).unwrap(), Vector3::new(2.0, 0.0, 0.0));
    }

    #[test]
    fn surfaces_of_revolution_and_tabulated_cylinders() {
        let text = hand_file(&[
            Hand(110, 0, 0, "AXIS", "110,0.,0.,0.,0.,0.,1.;"), // 1
            Hand(110, 0, 0, "GEN", "110,1.,0.,0.,1.,0.,2.;"),  // 3
            Hand(
                120,
                0,
                0,
                "REV",
                &format!("120,1,3,{},{};", real(FRAC_PI_2), real(PI)),
            ), // 5
            Hand(122, 0, 0, "TAB", "122,3,4.,5.,0.;"),         // 7
        ]);
        let items = read_iges(&text).unwrap();
        let ids: Vec<_> = items.iter().map(|i| (i.id, i.entity.as_str())).collect();
        assert_eq!(ids, [(1, "110"), (3, "110"), (5, "120"), (7, "122")]);
        // The half-cylinder x² + y² = 1, 0 ≤ z ≤ 2, from angle π/2 to π.
        let Geometry::NurbsSurface(rev) = &items[2].geometry else {
            panic!()
        };
        for (u, v) in [(0.0, 0.0), (0.5, 0.3), (1.0, 1.0), (0.25, 0.5)] {
            let p = rev.eval(u, v).unwrap();
            assert!((p.x.hypot(p.y) - 1.0).abs() < 1e-15);
            assert!((p.z - 2.0 * u).abs() < 1e-15);
        }
        assert!((rev.eval(0.5, 0.0).unwrap() - Vector3::new(0.0, 1.0, 1.0)).norm() < 1e-15);
        assert!((rev.eval(0.5, 1.0).unwrap() - Vector3::new(-1.0, 0.0, 1.0)).norm() < 1e-15);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((rev.eval(0.5, 0.5).unwrap() - Vector3::new(-h, h, 1.0)).norm() < 1e-15);
        // The generatrix swept to (4, 5, 0): S(u, v) = G(u) + v ((4, 5, 0) − (1, 0, 0)).
        let Geometry::Surface(tab) = &items[3].geometry else {
            panic!()
        };
        let (u, v) = (0.3, 0.7);
        let want = Vector3::new(1.0, 0.0, 2.0 * u) + v * Vector3::new(3.0, 5.0, 0.0);
        assert!((tab.eval(u, v).unwrap() - want).norm() < 1e-15);
    }

    #[test]
    fn transformations_of_rational_curves_and_surfaces() {
        // The quarter circle rotated by 90° about z after a shift by x: R(C(t) + (1, 0, 0)).
        let surface = "128,1,1,1,1,0,0,0,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,2.,1.,4.,\
                       0.,0.,0.,1.,0.,0.,0.,1.,0.,1.,1.,1.,0.,1.,0.,1.;";
        let text = hand_file(&[
            Hand(124, 0, 3, "", SHIFT_X),
            Hand(124, 0, 0, "", ROTATE_Z),
            Hand(126, 0, 1, "Q", &QUARTER.replace("0.25,0.75", "0.,1.")),
            Hand(128, 0, 1, "S", surface),
        ]);
        let items = read_iges(&text).unwrap();
        assert_eq!(items.len(), 2);
        let Geometry::NurbsCurve3(c) = &items[0].geometry else {
            panic!()
        };
        let Geometry::NurbsSurface(s) = &items[1].geometry else {
            panic!()
        };
        let r = |p: Vector3<f64>| Vector3::new(-p.y, p.x + 1.0, p.z);
        for t in [0.0, 0.4, 1.0] {
            let q = Vector3::new((1.0 - t * t) / (1.0 + t * t), 2.0 * t / (1.0 + t * t), 0.0);
            assert!((c.eval(t).unwrap() - r(q)).norm() < 1e-15, "t = {t}");
        }
        // The patch with P(1,1) = (1, 1, 1), the other corners those of the unit square,
        // weights W(0,0) = 1, W(1,0) = 2, W(0,1) = 1, W(1,1) = 4
        // (listed u fastest): w(u, v) = (1 − u)(1 − v) + 2u(1 − v) + (1 − u)v + 4uv.
        let (u, v) = (0.25, 0.5);
        let w = (1.0 - u) * (1.0 - v) + 2.0 * u * (1.0 - v) + (1.0 - u) * v + 4.0 * u * v;
        let q = Vector3::new(
            (2.0 * u * (1.0 - v) + 4.0 * u * v) / w,
            ((1.0 - u) * v + 4.0 * u * v) / w,
            4.0 * u * v / w,
        );
        assert!(
            (s.eval(u, v).unwrap() - r(q)).norm() < 1e-15,
            "{:?} {:?}",
            s.eval(u, v),
            r(q)
        );
    }

    #[test]
    fn a_name_property_names_the_entity() {
        let params = QUARTER.replace("0.,0.,1.;", "0.,0.,1.,1,3,1,5;");
        let text = hand_file(&[
            Hand(126, 0, 0, "LABEL", &params),
            Hand(402, 1, 0, "", "402,1,1;"),
            Hand(406, 15, 0, "", "406,1,18HNamed, with; marks;"),
        ]);
        let item = one(&text);
        assert_eq!(item.name, "Named, with; marks");
    }

    // -----------------------------------------------------------------------------------
    // Malformed files
    // -----------------------------------------------------------------------------------

    fn error(text: &str) -> String {
        let e = read_iges(text).unwrap_err();
        assert_eq!(e.message().lines().count(), 1);
        e.message().to_string()
    }

    fn quarter_file() -> String {
        hand_file(&[Hand(126, 0, 0, "ARC1", QUARTER)])
    }

    #[test]
    fn truncated_files_and_wrong_counts() {
        let text = quarter_file();
        let lines: Vec<_> = text.lines().collect();
        let cut = lines[..lines.len() - 1].join("\n");
        assert_eq!(
            error(&cut),
            "IGES line 2 (P): the file ends without a Terminate (T) record (truncated?)"
        );
        // A Parameter Data record dropped: the Terminate count disagrees.
        let mut dropped: Vec<_> = lines.clone();
        dropped.remove(dropped.len() - 2);
        assert!(
            error(&dropped.join("\n")).starts_with("IGES line"),
            "{}",
            error(&dropped.join("\n"))
        );
        let wrong_t = text.replace(
            "S0000001G0000002D0000002P0000002",
            "S0000001G0000002D0000002P0000009",
        );
        assert_eq!(
            error(&wrong_t),
            "IGES line 1 (T): the Terminate record counts 9 P records, the file has 2 (truncated or damaged)"
        );
        // Every truncation and every single-byte change: an error or a result, no panic.
        for k in 0..text.len() {
            let _ = read_iges(&text[..k]);
        }
        let bytes = text.as_bytes();
        for k in (0..bytes.len()).step_by(3) {
            for b in [b'9', b',', b';', b' ', b'H', b'-', b'0'] {
                let mut m = bytes.to_vec();
                m[k] = b;
                let _ = read_iges_bytes(&m);
            }
        }
    }

    #[test]
    fn counts_inconsistent_with_the_parameters() {
        let short = QUARTER.replace("126,2,2,", "126,3,2,");
        let e = error(&hand_file(&[Hand(126, 0, 0, "", &short)]));
        assert!(
            e.starts_with("IGES line 1 (P): entity 126: K = 3 and M = 2"),
            "{e}"
        );
        let huge = QUARTER.replace("126,2,2,", "126,1000000000000,2,");
        let e = error(&hand_file(&[Hand(126, 0, 0, "", &huge)]));
        assert!(e.contains("K = 1000000000000"), "{e}");
        let huge = QUARTER.replace("126,2,2,", "126,18446744073709551615,2,");
        assert!(error(&hand_file(&[Hand(126, 0, 0, "", &huge)])).contains("IGES line 1 (P)"));
        let negative = QUARTER.replace("126,2,2,", "126,-1,2,");
        assert!(
            error(&hand_file(&[Hand(126, 0, 0, "", &negative)]))
                .contains("K (upper index of the control points) = -1")
        );
        let surface = "128,1000000,1000000,1,1,0,0,1,0,0,0.,0.,1.,1.;";
        let e = error(&hand_file(&[Hand(128, 0, 0, "", surface)]));
        assert!(
            e.starts_with("IGES line 1 (P): entity 128: K1 = 1000000"),
            "{e}"
        );
    }

    #[test]
    fn geometry_errors_name_the_record() {
        let unsorted = QUARTER.replace("0.,0.,0.,1.,1.,1.,", "0.,0.,0.,1.,0.5,1.,");
        let e = error(&hand_file(&[Hand(126, 0, 0, "", &unsorted)]));
        assert!(
            e.starts_with("IGES line 1 (P): knots must be non-decreasing"),
            "{e}"
        );
        let zero_weight = QUARTER.replace("1.0D0,1.,2.", "1.0D0,0.,2.");
        let e = read_iges(&hand_file(&[Hand(126, 0, 0, "", &zero_weight)])).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidWeight);
        assert!(e.message().starts_with("IGES line 1 (P): "), "{e}");
        let outside = QUARTER.replace("0.25,0.75", "2.,3.");
        assert!(
            error(&hand_file(&[Hand(126, 0, 0, "", &outside)])).contains("outside the knot domain")
        );
        let zero_arc = "100,0.,1.,1.,1.,1.,1.,1.;";
        assert!(error(&hand_file(&[Hand(100, 0, 0, "", zero_arc)])).contains("zero radius"));
    }

    #[test]
    fn pointers_out_of_range_and_cycles() {
        // Transformation pointer outside the directory.
        let e = error(&hand_file(&[Hand(126, 0, 9, "", QUARTER)]));
        assert!(
            e.starts_with("IGES line 1 (D): transformation matrix pointer 9"),
            "{e}"
        );
        // An even pointer.
        let e = error(&hand_file(&[Hand(126, 0, 2, "", QUARTER)]));
        assert!(
            e.starts_with("IGES line 1 (D): transformation matrix pointer 2"),
            "{e}"
        );
        // A pointer to something other than a 124.
        let e = error(&hand_file(&[Hand(126, 0, 1, "", QUARTER)]));
        assert!(e.contains("designates an entity 126, not a 124"), "{e}");
        // A 124 referencing itself, and two referencing each other.
        let e = error(&hand_file(&[
            Hand(124, 0, 1, "", ROTATE_Z),
            Hand(126, 0, 1, "", QUARTER),
        ]));
        assert_eq!(
            e,
            "IGES line 1 (D): the transformation matrices reference each other in a cycle"
        );
        let e = error(&hand_file(&[
            Hand(124, 0, 3, "", ROTATE_Z),
            Hand(124, 0, 1, "", SHIFT_X),
            Hand(126, 0, 1, "", QUARTER),
        ]));
        assert!(e.contains("cycle"), "{e}");
        // Parameter data pointer outside the Parameter Data section.
        let text = quarter_file().replace("     126       1       0", "     126      99       0");
        let e = error(&text);
        assert!(
            e.starts_with("IGES line 1 (D): entity 126: parameter data pointer 99"),
            "{e}"
        );
        // A property pointer outside the directory.
        let params = QUARTER.replace("0.,0.,1.;", "0.,0.,1.,0,1,77;");
        let e = error(&hand_file(&[Hand(126, 0, 0, "", &params)]));
        assert!(e.contains("property pointer 77"), "{e}");
        // A 120 whose axis pointer is outside.
        let e = error(&hand_file(&[Hand(120, 0, 0, "", "120,41,1,0.,1.;")]));
        assert!(e.starts_with("IGES line 1 (P): axis pointer 41"), "{e}");
    }

    #[test]
    fn records_and_characters() {
        let text = quarter_file();
        // Non-ASCII text: the line and column of the first bad byte.
        let bad = text.replacen("hand-written", "hand-wrïtten", 1);
        let e = read_iges_bytes(bad.as_bytes()).unwrap_err();
        assert_eq!(
            e.message(),
            "IGES file line 1: non-ASCII byte 0xC3 in column 8; IGES files are ASCII"
        );
        assert_eq!(read_iges(&bad).unwrap_err(), e);
        let mut latin1 = text.as_bytes().to_vec();
        latin1[81 * 2 + 5] = 0xE9;
        let e = read_iges_bytes(&latin1).unwrap_err();
        assert!(
            e.message()
                .starts_with("IGES file line 3: non-ASCII byte 0xE9 in column 6"),
            "{e}"
        );
        // A short record.
        let short = text.replacen("1H,,1H;", "1H,,1H;\n", 1);
        assert!(error(&short).starts_with("IGES file line 2: the record has"));
        // An unterminated Hollerith string.
        let holl = hand_file(&[Hand(406, 15, 0, "", "406,1,99Habc;")]);
        let e = read_iges(&holl);
        assert!(
            e.is_ok(),
            "406 entities are skipped, their parameters not read"
        );
        let params = QUARTER.replace("0.,0.,1.;", "0.,0.,1.,0,1,3;");
        let holl = hand_file(&[
            Hand(126, 0, 0, "", &params),
            Hand(406, 15, 0, "", "406,1,99Habc;"),
        ]);
        assert!(
            error(&holl).contains("Hollerith string of 99 characters"),
            "{}",
            error(&holl)
        );
        // Sequence numbers out of order.
        let swapped = text.replace("D0000002", "D0000003");
        assert!(error(&swapped).starts_with("IGES line 2 (D): sequence number '0000003'"));
        // Compressed files.
        let compressed = text.replacen("S0000001\n", "C0000001\n", 1);
        assert!(error(&compressed).contains("compressed ASCII"));
        // The wrong back-pointer in columns 65–72.
        let lines: Vec<String> = text.lines().map(str::to_string).collect();
        let p = lines.iter().position(|l| l.as_bytes()[72] == b'P').unwrap();
        let mut changed = lines.clone();
        changed[p] = format!("{}{:8}{}", &lines[p][..64], 3, &lines[p][72..]);
        assert!(
            error(&changed.join("\n")).starts_with("IGES line 1 (P): the directory pointer '3'")
        );
        // Records without line breaks read the same.
        let flat: String = text.lines().collect();
        assert_eq!(read_iges(&flat).unwrap(), read_iges(&text).unwrap());
        let crlf = text.replace('\n', "\r\n");
        assert_eq!(read_iges(&crlf).unwrap(), read_iges(&text).unwrap());
    }

    #[test]
    fn delimiters_from_the_global_section() {
        let params = QUARTER.replace(',', "/").replace(';', "$");
        let text = hand_file(&[Hand(126, 0, 0, "", &params)])
            .replace(
                "1H,,1H;,4Htest,,,,32,38,6,308,15,,1.0,2,2HMM,1,1.0,",
                "1H//1H$/4Htest////32/38/6/308/15//1.0/2/2HMM/1/1.0/",
            )
            .replace(
                "15H20260101.120000,1.0E-7,10.0,,,11,0;",
                "15H20260101.120000/1.0E-7/10.0///11/0$",
            );
        let Geometry::NurbsCurve3(c) = one(&text).geometry else {
            panic!()
        };
        assert_eq!(c.domain(), (0.25, 0.75));
    }

    // -----------------------------------------------------------------------------------
    // Open CASCADE
    // -----------------------------------------------------------------------------------

    /// Files written by Open CASCADE 8.0 (`tests/data/iges/occt_write.py`).
    fn occt_file(name: &str) -> Vec<Item> {
        let path = format!("{}/tests/data/iges/{name}", env!("CARGO_MANIFEST_DIR"));
        read_iges_bytes(&std::fs::read(path).unwrap()).unwrap()
    }

    #[test]
    fn occt_bspline_curve_and_surface() {
        let items = occt_file("occt_bspline.igs");
        let kinds: Vec<_> = items.iter().map(|i| (i.id, i.entity.as_str())).collect();
        assert_eq!(
            kinds,
            [
                (5, "128"),
                (11, "126"),
                (15, "126"),
                (17, "126"),
                (19, "126"),
                (21, "110"),
                (23, "110"),
                (25, "110"),
                (27, "110"),
                (29, "126")
            ]
        );
        // The face: P(i, j) = (i, j, i j + i²/10), degrees (2, 1); the point at (0.3, 0.7)
        // printed by the script (Geom_BSplineSurface::Value).
        let Geometry::Surface(s) = &items[0].geometry else {
            panic!()
        };
        assert_eq!((s.degrees(), s.net_size()), ((2, 1), (4, 3)));
        for i in 0..4 {
            for j in 0..3 {
                let (x, y) = (i as f64, j as f64);
                assert!(
                    (s.control_point(i, j) - Vector3::new(x, y, x * y + 0.1 * x * x)).norm()
                        < 1e-15
                );
            }
        }
        assert_eq!(s.knots_u().knots(), [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]);
        let occt = Vector3::new(1.02, 1.4, 1.5659999999999998);
        assert!((s.eval(0.3, 0.7).unwrap() - occt).norm() < 1e-14);
        // The edge: the rational cubic of the script, its point at 0.3 from
        // Geom_BSplineCurve::Value.
        let Geometry::NurbsCurve3(c) = &items[9].geometry else {
            panic!()
        };
        assert_eq!(c.weights(), [1.0, 0.5, 2.0, 1.5, 0.75, 1.0]);
        assert_eq!(
            c.knots().knots(),
            [0.0, 0.0, 0.0, 0.0, 0.4, 0.4, 1.0, 1.0, 1.0, 1.0]
        );
        assert_eq!(c.control_points()[3], Vector3::new(3.0, 0.5, 1.0));
        let occt = Vector3::new(2.089731729879741, -0.641073080481036, 0.37049028677150786);
        assert!((c.eval(0.3).unwrap() - occt).norm() < 1e-14);
    }

    #[test]
    fn occt_box_with_a_fillet_and_a_cylinder() {
        // 186/514/510/508/504/502 B-rep, planes (190), cylinders (192), points and
        // directions (116, 123) skipped; lines and arcs (with 124 matrices) read.
        let items = occt_file("occt_fillet_box.igs");
        let count = |e: &str| items.iter().filter(|i| i.entity == e).count();
        assert_eq!((count("110"), count("100"), items.len()), (22, 4, 26));
        let arcs: Vec<_> = items
            .iter()
            .filter_map(|i| match &i.geometry {
                Geometry::NurbsCurve3(c) if i.entity == "100" => Some(c),
                _ => None,
            })
            .collect();
        // The fillet of radius 2 about the edge x = y = 0 of the box 10 × 20 × 30: quarter
        // arcs about (2, 2, z) from (0, 2, z) to (2, 0, z), z = 0 and 30 (OCCT writes about
        // ten digits); the cylinder: circles of radius 3 about (50, 0, z), z = 0 and 7.
        for (arc, center, radius) in [
            (arcs[0], Vector3::new(2.0, 2.0, 30.0), 2.0),
            (arcs[1], Vector3::new(2.0, 2.0, 0.0), 2.0),
            (arcs[2], Vector3::new(50.0, 0.0, 7.0), 3.0),
            (arcs[3], Vector3::new(50.0, 0.0, 0.0), 3.0),
        ] {
            for t in [0.0, 0.1, 0.5, 0.77, 1.0] {
                let p = arc.eval(t).unwrap();
                assert!(((p - center).norm() - radius).abs() < 1e-9, "{p:?}");
            }
        }
        assert!((arcs[0].eval(0.0).unwrap() - Vector3::new(0.0, 2.0, 30.0)).norm() < 1e-9);
        assert!((arcs[0].eval(1.0).unwrap() - Vector3::new(2.0, 0.0, 30.0)).norm() < 1e-9);
    }

    /// Writes `$IGES_OUT/ours.igs` and `$IGES_OUT/ours.json` (the values) for
    /// `tests/data/iges/occt_check.py`, which reads the file with Open CASCADE and compares.
    #[test]
    #[ignore = "writes files for the Open CASCADE check"]
    fn write_files_for_occt() {
        let dir = std::env::var("IGES_OUT").unwrap();
        let mut rng = Numbers(9);
        let kv = knots(3, true);
        let n = kv.num_basis();
        let points: Vec<_> = (0..n).map(|_| rng.point3()).collect();
        let weights: Vec<_> = (0..n).map(|_| rng.weight()).collect();
        let rational = NurbsCurve3::new(kv.clone(), points.clone(), weights).unwrap();
        let poly = BSpline::new(
            knots(5, true),
            (0..knots(5, true).num_basis())
                .map(|_| rng.point3())
                .collect(),
        )
        .unwrap();
        let planar =
            BSpline::new(kv, points.iter().map(|p| Vector2::new(p.x, p.y)).collect()).unwrap();
        let (ku, kv) = (knots(3, true), knots(2, true));
        let count = ku.num_basis() * kv.num_basis();
        let net: Vec<_> = (0..count).map(|_| rng.point3()).collect();
        let w: Vec<_> = (0..count).map(|_| rng.weight()).collect();
        let surface = Surface::new(ku.clone(), kv.clone(), net.clone()).unwrap();
        let nurbs = NurbsSurface3::new(ku, kv, net, w).unwrap();
        let items = [
            item("rational cubic", Geometry::NurbsCurve3(rational.clone())),
            item("quintic", Geometry::Curve3(poly.clone())),
            item("planar", Geometry::Curve2(planar.clone())),
            item("surface", Geometry::Surface(surface.clone())),
            item("nurbs surface", Geometry::NurbsSurface(nurbs.clone())),
        ];
        std::fs::write(format!("{dir}/ours.igs"), write_iges(&items).unwrap()).unwrap();
        let v3 = |p: &[Vector3<f64>]| p.iter().map(|q| vec![q.x, q.y, q.z]).collect::<Vec<_>>();
        let json = format!(
            "{{\"curves\": [[{:?}, {:?}, {:?}], [{:?}, {:?}, null], [{:?}, {:?}, null]], \"surfaces\": [[{:?}, {:?}, {:?}, {:?}, null], [{:?}, {:?}, {:?}, {:?}, {:?}]]}}",
            rational.knots().knots(), v3(rational.control_points()), rational.weights(),
            poly.knots().knots(), v3(poly.control_points()),
            planar.knots().knots(), v3(&planar.control_points().iter().map(|p| Vector3::new(p.x, p.y, 0.0)).collect::<Vec<_>>()),
            surface.knots_u().knots(), surface.knots_v().knots(), surface.net_size(), v3(surface.control_points()),
            nurbs.knots_u().knots(), nurbs.knots_v().knots(), nurbs.net_size(), v3(nurbs.control_points()), nurbs.weights(),
        )
        .replace('(', "[")
        .replace(')', "]");
        std::fs::write(format!("{dir}/ours.json"), json).unwrap();
    }
}
