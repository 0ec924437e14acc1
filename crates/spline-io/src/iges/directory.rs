//! Directory entries and the parameters of each entity, read on demand; transformation
//! matrices (124) with their chains, name properties (406 form 15).

use super::affine::Affine;
use super::layout::{PARAM_WIDTH, Section, parse_error};
use super::tokens::{Token, integer_text, parse_int, parse_real, tokenize};
use nalgebra::{Matrix3, Vector3};
use spline_core::Result;
use std::fmt;

/// One directory entry (the fields used here).
#[derive(Clone, Debug)]
pub(super) struct Entry {
    /// Sequence number of the first record.
    pub(super) seq: usize,
    pub(super) kind: i64,
    pub(super) data: i64,
    pub(super) transform: i64,
    pub(super) lines: i64,
    pub(super) form: i64,
    pub(super) label: String,
}

pub(super) fn parse_entries(records: &[&str]) -> Result<Vec<Entry>> {
    let mut entries = Vec::with_capacity(records.len() / 2);
    for (k, pair) in records.chunks_exact(2).enumerate() {
        let seq = 2 * k + 1;
        let field = |line: usize, index: usize, what: &str| -> Result<i64> {
            let text = pair[line][8 * index..8 * index + 8].trim();
            integer_text(text).ok_or_else(|| {
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
pub(super) struct File<'a> {
    pub(super) entries: Vec<Entry>,
    pub(super) parameter: Vec<&'a str>,
    pub(super) delimiters: (u8, u8),
    /// The map of each transformation matrix (124) read, with the matrices it references.
    pub(super) chains: std::cell::RefCell<std::collections::HashMap<usize, Affine>>,
}

/// The parameters of one entity, read in order.
pub(super) struct Params {
    pub(super) tokens: Vec<Token>,
    pub(super) pos: usize,
    /// The entity type, for messages.
    pub(super) kind: i64,
    /// The record of the entity type, for messages about the whole list.
    pub(super) first_line: usize,
}

impl Params {
    pub(super) fn remaining(&self) -> usize {
        self.tokens.len() - self.pos
    }

    pub(super) fn next(&mut self, what: &str) -> Result<&Token> {
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

    pub(super) fn real(&mut self, what: &str) -> Result<f64> {
        let t = self.next(what)?;
        parse_real(t, Section::Parameter, what)
    }

    pub(super) fn int(&mut self, what: &str) -> Result<i64> {
        let t = self.next(what)?;
        parse_int(t, Section::Parameter, what)
    }

    pub(super) fn string(&mut self, what: &str) -> Result<String> {
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
    pub(super) fn count(&mut self, what: &str, min: i64) -> Result<(usize, usize)> {
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

    pub(super) fn point(&mut self, what: &str) -> Result<Vector3<f64>> {
        Ok(Vector3::new(
            self.real(what)?,
            self.real(what)?,
            self.real(what)?,
        ))
    }

    /// The record of the next parameter.
    pub(super) fn line(&self) -> usize {
        self.tokens
            .get(self.pos)
            .or(self.tokens.last())
            .map_or(self.first_line, |t| t.line)
    }

    /// Checks that `needed` more parameters are present (an error about `what` otherwise).
    pub(super) fn require(
        &self,
        needed: Option<usize>,
        line: usize,
        what: impl fmt::Display,
    ) -> Result<()> {
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
    pub(super) fn entry(&self, pointer: i64, from: &Entry, what: &str) -> Result<&Entry> {
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
    pub(super) fn pointed(&self, params: &mut Params, from: &Entry, what: &str) -> Result<&Entry> {
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
    pub(super) fn params(&self, entry: &Entry) -> Result<Params> {
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
    pub(super) fn transform(&self, entry: &Entry) -> Result<Option<Affine>> {
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
    pub(super) fn property_name(
        &self,
        params: &mut Params,
        entry: &Entry,
    ) -> Result<Option<String>> {
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
