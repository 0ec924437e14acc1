//! The instances of the exchange structure as parsed (their line, their records and
//! parameters), the accessors of parameters, and the parse errors that name a line.

use spline_core::{Error, ErrorKind};
use std::collections::HashMap;

/// Lists nest at most this deep (a B-spline surface's points are two levels down).
pub(super) const MAX_NESTING: usize = 32;

/// A parameter of an entity instance.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Param {
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
pub(super) struct Instance {
    pub(super) line: usize,
    pub(super) records: Vec<(String, Vec<Param>)>,
}

impl Instance {
    pub(super) fn record(&self, name: &str) -> Option<&[Param]> {
        self.records
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, p)| p.as_slice())
    }
}

pub(super) fn error_at(line: usize, message: impl std::fmt::Display) -> Error {
    Error::new(ErrorKind::Parse, format!("STEP line {line}: {message}")).with_line(line)
}

pub(super) fn number(p: &Param) -> Option<f64> {
    match p {
        Param::Real(x) => Some(*x),
        #[allow(clippy::cast_precision_loss)]
        Param::Integer(i) => Some(*i as f64),
        Param::Typed(_, inner) => number(inner),
        _ => None,
    }
}

pub(super) fn integer(p: &Param) -> Option<i64> {
    match p {
        Param::Integer(i) => Some(*i),
        Param::Typed(_, inner) => integer(inner),
        _ => None,
    }
}

pub(super) fn list(p: &Param) -> Option<&[Param]> {
    match p {
        Param::List(l) => Some(l),
        _ => None,
    }
}

pub(super) fn text(p: &Param) -> String {
    match p {
        Param::Text(s) => s.clone(),
        _ => String::new(),
    }
}

/// Follows the wrappers between topology and geometry (`TRIMMED_CURVE`'s basis curve,
/// `SURFACE_CURVE`/`SEAM_CURVE`'s 3-D curve, `RECTANGULAR_TRIMMED_SURFACE`'s basis surface)
/// to the instance that holds the geometry.
pub(super) fn underlying(instances: &HashMap<u64, Instance>, mut id: u64) -> Option<u64> {
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
