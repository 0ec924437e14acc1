//! The error type shared by every layer of the library.

use std::fmt;

/// What went wrong, in a form a program can match on.
///
/// The list grows as the library grows, so matches need a wildcard arm.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    /// A knot, parameter, coordinate or weight is NaN or infinite.
    NonFinite,
    /// The knots are not in non-decreasing order.
    UnsortedKnots,
    /// A knot is repeated more than `degree + 1` times.
    KnotMultiplicity,
    /// Sizes do not agree: number of knots, control points, weights, parameters.
    InvalidLength,
    /// The degree is too high for the data or above [`crate::MAX_DEGREE`].
    DegreeTooHigh,
    /// The parametric domain `[u_p, u_n]` is empty.
    EmptyDomain,
    /// A parameter lies outside the parametric domain.
    OutOfDomain,
    /// Points or objects of different dimensions were combined.
    DimensionMismatch,
    /// A weight is zero, negative or not finite.
    InvalidWeight,
    /// An operation would change the shape by more than the allowed tolerance.
    ToleranceExceeded,
    /// A linear system is singular or numerically too ill-conditioned to solve.
    SingularSystem,
    /// The data leave a knot span empty (the Schoenberg–Whitney conditions fail).
    SchoenbergWhitney,
    /// Too few data points for what was asked.
    TooFewPoints,
    /// Geometry that the construction cannot handle (zero-length axis, coincident points…).
    DegenerateGeometry,
    /// An iterative method did not converge.
    NoConvergence,
    /// Malformed input text (JSON, point files).
    Parse,
    /// Any other invalid argument (negative tolerance, unknown option…).
    InvalidArgument,
}

/// The error of every fallible operation: a [`ErrorKind`] plus a one-line message that says
/// what was wrong with which input.
///
/// Messages are for people: [`Error::new`] and [`Error::context`] keep them on one line
/// (line breaks become spaces) and write numbers short: a number that `{}` would print with
/// hundreds of digits (`5e-324`, `1e300`) is written in exponent form, with the same
/// shortest round-trip digits.
///
/// ```
/// use spline_core::{Error, ErrorKind};
/// let e = Error::new(ErrorKind::OutOfDomain, format!("parameter {} is outside", -5e-324));
/// assert_eq!(e.message(), "parameter -5e-324 is outside");
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error {
    kind: ErrorKind,
    message: String,
}

impl Error {
    /// Creates an error of the given kind with a human-readable message.
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Self {
            kind,
            message: for_people(message.into()),
        }
    }

    /// The kind of the error.
    #[must_use]
    pub fn kind(&self) -> ErrorKind {
        self.kind
    }

    /// The message, one line, without a trailing period.
    #[must_use]
    pub fn message(&self) -> &str {
        &self.message
    }

    /// Prefixes the message with context (`"control point 3: " + message`).
    #[must_use]
    pub fn context(mut self, context: impl fmt::Display) -> Self {
        self.message = for_people(format!("{context}: {}", self.message));
        self
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Error {}

/// `Result` with the library's [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

/// One line, short numbers (see [`Error`]).
fn for_people(message: String) -> String {
    let one_line = if message.contains(['\n', '\r']) {
        message
            .split(['\n', '\r'])
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join(" ")
    } else {
        message
    };
    shorten_numbers(&one_line)
}

/// Rewrites the decimal numbers of a message that are longer than their exponent form: `{}`
/// of an `f64` never uses an exponent, so `5e-324` would print with 324 digits.
fn shorten_numbers(text: &str) -> String {
    let bytes = text.as_bytes();
    let is_digit = |i: usize| bytes.get(i).is_some_and(u8::is_ascii_digit);
    let mut out = String::with_capacity(text.len());
    let mut copied = 0;
    let mut i = 0;
    while i < bytes.len() {
        let starts_number = is_digit(i) && (i == 0 || !bytes[i - 1].is_ascii_alphanumeric());
        if !starts_number {
            i += 1;
            continue;
        }
        let start = i;
        while is_digit(i) {
            i += 1;
        }
        let mut has_point = false;
        if bytes.get(i) == Some(&b'.') && is_digit(i + 1) {
            has_point = true;
            i += 1;
            while is_digit(i) {
                i += 1;
            }
        }
        let token = &text[start..i];
        // Integers up to 20 digits are counts and indices (u64), printed as they are.
        let long = if has_point {
            token.len() > 21
        } else {
            token.len() > 20
        };
        if long {
            if let Ok(x) = token.parse::<f64>() {
                out.push_str(&text[copied..start]);
                out.push_str(&format!("{x:e}"));
                copied = i;
            }
        }
    }
    out.push_str(&text[copied..]);
    out
}

/// A number written for people: `{}` (shortest round-trip digits) when that is short, the
/// exponent form `{:e}` for very small and very large magnitudes.
///
/// ```
/// use spline_core::Short;
/// assert_eq!(Short(0.25).to_string(), "0.25");
/// assert_eq!(Short(-5e-324).to_string(), "-5e-324");
/// assert_eq!(Short(1e300).to_string(), "1e300");
/// assert_eq!(Short(1000000000000.0941).to_string(), "1000000000000.0941");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Short(pub f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        let magnitude = x.abs();
        if x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&magnitude) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// The error for a result that does not fit in the floating-point range although the input
/// is finite (for example a derivative of a curve with huge coordinates on a tiny domain).
#[must_use]
pub fn overflow(what: impl fmt::Display) -> Error {
    Error::new(
        ErrorKind::NonFinite,
        format!("{what} is too large for floating point"),
    )
}
