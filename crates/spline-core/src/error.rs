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
            message: message.into(),
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
        self.message = format!("{context}: {}", self.message);
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
