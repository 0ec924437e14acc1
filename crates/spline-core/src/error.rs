//! The error type shared by every layer of the library.

use std::fmt;
use std::sync::Arc;

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
    /// Any other invalid argument (unknown option, inconsistent settings…).
    InvalidArgument,
    /// Reading or writing a file or stream failed; [`std::error::Error::source`] holds the
    /// I/O error.
    Io,
    /// The operation does not exist for this kind of object (the derivative of a NURBS
    /// curve as a NURBS curve on the same knots, a mesh of a curve…).
    Unsupported,
    /// A derivative order above the degree, or above
    /// [`crate::MAX_DERIVATIVE_ORDER`].
    OrderTooHigh,
    /// A tolerance or accuracy that is negative, zero where it must be positive, or NaN.
    InvalidTolerance,
    /// Two operands, or an operand and an operator, live on different spaces (different
    /// domains, degrees or knot vectors where equal ones are needed).
    SpaceMismatch,
    /// An index (of a control point, a coordinate, a knot) is out of range.
    IndexOutOfRange,
}

/// The error of every fallible operation: an [`ErrorKind`], a one-line message that says
/// what was wrong with which input, the structured facts behind it ([`Error::index`],
/// [`Error::value`], [`Error::interval`], [`Error::counts`], and for a file's content
/// [`Error::line`] and [`Error::file`]) and, for I/O failures, the underlying error as
/// [`std::error::Error::source`].
///
/// Messages are for people: [`Error::new`] and [`Error::context`] keep them on one line
/// (line breaks become spaces) and write numbers short: a number that `{}` would print with
/// hundreds of digits (`5e-324`, `1e300`) is written in exponent form, with the same
/// shortest round-trip digits. Programs match on [`Error::kind`] and read the fields.
///
/// ```
/// use spline_core::{Error, ErrorKind};
/// let e = Error::new(ErrorKind::OutOfDomain, format!("parameter {} is outside", -5e-324));
/// assert_eq!(e.message(), "parameter -5e-324 is outside");
/// let e = Error::out_of_domain(2.5, (0.0, 1.0)).context("parameter 3");
/// assert_eq!(e.kind(), ErrorKind::OutOfDomain);
/// assert_eq!((e.value(), e.interval()), (Some(2.5), Some((0.0, 1.0))));
/// assert_eq!(e.to_string(), "parameter 3: parameter 2.5 is outside the domain [0, 1]");
/// ```
#[derive(Clone, Debug)]
pub struct Error {
    /// Boxed so that `Result<T>` stays one pointer larger than `T` on the hot paths.
    inner: Box<Inner>,
}

/// What an [`Error`] holds.
#[derive(Clone, Debug)]
struct Inner {
    kind: ErrorKind,
    message: String,
    fields: Fields,
    source: Option<Arc<dyn std::error::Error + Send + Sync + 'static>>,
    /// The file the error is about, when it came from one.
    file: Option<Arc<str>>,
}

/// The structured facts of an [`Error`], each present when it applies.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Fields {
    index: Option<usize>,
    value: Option<f64>,
    interval: Option<(f64, f64)>,
    counts: Option<(usize, usize)>,
    line: Option<usize>,
}

/// Errors are equal when their kinds, messages and fields are (sources are not compared).
impl PartialEq for Error {
    fn eq(&self, other: &Self) -> bool {
        let (a, b) = (&self.inner, &other.inner);
        a.kind == b.kind && a.message == b.message && a.fields == b.fields && a.file == b.file
    }
}

impl Error {
    /// Creates an error of the given kind with a human-readable message.
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Self {
            inner: Box::new(Inner {
                kind,
                message: for_people(message.into()),
                fields: Fields::default(),
                source: None,
                file: None,
            }),
        }
    }

    /// [`ErrorKind::OutOfDomain`]: `parameter {u} is outside the domain [{a}, {b}]`, with
    /// the parameter as [`Error::value`] and the domain as [`Error::interval`].
    #[must_use]
    pub fn out_of_domain(u: f64, (a, b): (f64, f64)) -> Self {
        Self::new(
            ErrorKind::OutOfDomain,
            format!(
                "parameter {} is outside the domain [{}, {}]",
                Short(u),
                Short(a),
                Short(b)
            ),
        )
        .with_value(u)
        .with_interval(a, b)
    }

    /// [`ErrorKind::NonFinite`]: `{what} is not finite`.
    #[must_use]
    pub fn non_finite(what: impl fmt::Display) -> Self {
        Self::new(ErrorKind::NonFinite, format!("{what} is not finite"))
    }

    /// [`ErrorKind::InvalidLength`]: `{what}: expected {expected}, got {found}`, with the two
    /// counts as [`Error::counts`].
    #[must_use]
    pub fn invalid_length(what: impl fmt::Display, expected: usize, found: usize) -> Self {
        Self::new(
            ErrorKind::InvalidLength,
            format!("{what}: expected {expected}, got {found}"),
        )
        .with_counts(expected, found)
    }

    /// [`ErrorKind::InvalidTolerance`]: `{what} must be {requirement}, got {value}`.
    #[must_use]
    pub fn invalid_tolerance(what: &str, requirement: &str, value: f64) -> Self {
        Self::new(
            ErrorKind::InvalidTolerance,
            format!("{what} must be {requirement}, got {}", Short(value)),
        )
        .with_value(value)
    }

    /// [`ErrorKind::OrderTooHigh`]: a derivative order above `limit` (the degree, or
    /// [`crate::MAX_DERIVATIVE_ORDER`]), with `(limit, order)` as [`Error::counts`].
    #[must_use]
    pub fn order_too_high(order: usize, limit: usize, what: &str) -> Self {
        Self::new(
            ErrorKind::OrderTooHigh,
            format!("derivative order {order} exceeds {what} {limit}"),
        )
        .with_counts(limit, order)
    }

    /// [`ErrorKind::Io`]: `cannot {action}: {error}`, with the I/O error as
    /// [`std::error::Error::source`].
    #[must_use]
    pub fn io(action: impl fmt::Display, error: std::io::Error) -> Self {
        let mut e = Self::new(ErrorKind::Io, format!("cannot {action}: {error}"));
        e.inner.source = Some(Arc::new(error));
        e
    }

    /// Attaches an underlying error, returned by [`std::error::Error::source`].
    #[must_use]
    pub fn with_source(mut self, source: impl std::error::Error + Send + Sync + 'static) -> Self {
        self.inner.source = Some(Arc::new(source));
        self
    }

    /// Records the index of the offending entry (a control point, a parameter, a knot).
    #[must_use]
    pub fn with_index(mut self, index: usize) -> Self {
        self.inner.fields.index = Some(index);
        self
    }

    /// Records the offending value (a parameter, a knot, a weight, a tolerance).
    #[must_use]
    pub fn with_value(mut self, value: f64) -> Self {
        self.inner.fields.value = Some(value);
        self
    }

    /// Records the interval involved: a domain, or the allowed range of an argument (an
    /// open end as `±∞`: `(0, ∞)` for "positive").
    #[must_use]
    pub fn with_interval(mut self, a: f64, b: f64) -> Self {
        self.inner.fields.interval = Some((a, b));
        self
    }

    /// Records an expected and a found count (lengths, orders, multiplicities).
    #[must_use]
    pub fn with_counts(mut self, expected: usize, found: usize) -> Self {
        self.inner.fields.counts = Some((expected, found));
        self
    }

    /// Records the 1-based line of the input text the error is about (a file's line, a
    /// record of a fixed-column file).
    #[must_use]
    pub fn with_line(mut self, line: usize) -> Self {
        self.inner.fields.line = Some(line);
        self
    }

    /// Records the file the error is about (its path as the caller named it). The message
    /// is not changed: [`Error::context`] says it for people.
    #[must_use]
    pub fn with_file(mut self, file: impl fmt::Display) -> Self {
        self.inner.file = Some(file.to_string().into());
        self
    }

    /// The kind of the error.
    #[must_use]
    pub fn kind(&self) -> ErrorKind {
        self.inner.kind
    }

    /// The message, one line, without a trailing period.
    #[must_use]
    pub fn message(&self) -> &str {
        &self.inner.message
    }

    /// The index of the offending entry, when the error is about one.
    #[must_use]
    pub fn index(&self) -> Option<usize> {
        self.inner.fields.index
    }

    /// The offending value, when the error is about one.
    #[must_use]
    pub fn value(&self) -> Option<f64> {
        self.inner.fields.value
    }

    /// The interval involved: the domain of an out-of-domain parameter, or the allowed
    /// range of an argument outside it (with [`Error::value`]).
    #[must_use]
    pub fn interval(&self) -> Option<(f64, f64)> {
        self.inner.fields.interval
    }

    /// The 1-based line of the input text, for errors about a file's content.
    #[must_use]
    pub fn line(&self) -> Option<usize> {
        self.inner.fields.line
    }

    /// The file the error is about, when it came from one.
    #[must_use]
    pub fn file(&self) -> Option<&str> {
        self.inner.file.as_deref()
    }

    /// `(expected, found)` counts, for errors about lengths, orders and multiplicities.
    #[must_use]
    pub fn counts(&self) -> Option<(usize, usize)> {
        self.inner.fields.counts
    }

    /// Prefixes the message with context (`"control point 3: " + message`).
    #[must_use]
    pub fn context(mut self, context: impl fmt::Display) -> Self {
        self.inner.message = for_people(format!("{context}: {}", self.inner.message));
        self
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.inner.message)
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.inner
            .source
            .as_deref()
            .map(|e| e as &(dyn std::error::Error + 'static))
    }
}

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
