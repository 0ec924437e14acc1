//! The fixed-format layout of IGES records (the widths of their columns), the section a
//! record belongs to, and the errors that name the record.

use spline_core::{Error, ErrorKind};
use std::fmt;

/// Columns of a record (without the line break).
pub(super) const RECORD: usize = 80;
/// Columns of data in the Start and Global sections.
pub(super) const GLOBAL_WIDTH: usize = 72;
/// Columns of parameters in a Parameter Data record.
pub(super) const PARAM_WIDTH: usize = 64;

/// The section of a record, for messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Section {
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
pub(super) fn parse_error(section: Section, line: usize, message: impl fmt::Display) -> Error {
    Error::new(
        ErrorKind::Parse,
        format!("IGES line {line} ({section}): {message}"),
    )
    .with_line(line)
}

/// Prefixes an error of the geometry layer with the record it comes from.
pub(super) fn at(section: Section, line: usize) -> impl FnOnce(Error) -> Error {
    move |e| e.context(format_args!("IGES line {line} ({section})"))
}
