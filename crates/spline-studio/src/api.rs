//! The JSON endpoints of the studio, independent of HTTP: [`handle`] takes the name of an
//! endpoint and the request body and answers the JSON value the page draws, or an
//! [`ApiError`]. Every request carries the whole state it needs (the page keeps its points,
//! knots and parameters), so the server holds none and each browser tab is independent.
//!
//! Curves in requests and answers are exchange-format records (`docs/exchange-format.md`);
//! points are `[x, y]` arrays. The endpoints and their fields are listed in
//! `docs/exchange-format.md`, section "spline studio".

use crate::labs;
use serde::de::DeserializeOwned;
use serde_json::Value;
use spline_core::Error;

pub use crate::values::{
    MAX_DEGREE, MAX_POINTS, MAX_SAMPLES, Point, count, planar, points, record, samples, xy, xys,
};

/// The names of the endpoints, `POST /api/<name>`.
pub const ENDPOINTS: &[&str] = &[
    "bezier",
    "bspline",
    "interpolate",
    "approximate",
    "features",
    "erase",
    "load",
];

/// A failed request: the HTTP status and a one-line message, sent as `{"error": message}`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ApiError {
    /// The HTTP status code (400 for bad input, 404 for an unknown endpoint, 413 for a body
    /// too large, 500 for an internal failure).
    pub status: u16,
    /// What went wrong, on one line.
    pub message: String,
}

impl ApiError {
    /// A bad request (status 400).
    #[must_use]
    pub fn bad_request(message: impl Into<String>) -> Self {
        Self {
            status: 400,
            message: one_line(&message.into()),
        }
    }

    /// The JSON body of the error, `{"error": message}`.
    #[must_use]
    pub fn body(&self) -> String {
        serde_json::json!({ "error": self.message }).to_string()
    }
}

impl From<Error> for ApiError {
    fn from(error: Error) -> Self {
        Self::bad_request(error.to_string())
    }
}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Answers one request: `name` is the endpoint (one of [`ENDPOINTS`]), `body` the JSON of
/// the request.
///
/// ```
/// let answer = spline_studio::api::handle(
///     "bezier",
///     br#"{"control_points": [[0, 0], [1, 1], [2, 0]], "t": 0.5}"#,
/// )?;
/// assert_eq!(answer["point"], serde_json::json!([1.0, 0.5]));
/// # Ok::<(), spline_studio::api::ApiError>(())
/// ```
///
/// # Errors
/// Status 404 for an unknown endpoint; 400 for a body that is not the JSON the endpoint
/// expects (the message names the field) or that the library rejects (its message).
pub fn handle(name: &str, body: &[u8]) -> std::result::Result<Value, ApiError> {
    match name {
        "bezier" => Ok(labs::bezier(&parse(body)?)?),
        "bspline" => Ok(labs::bspline(&parse(body)?)?),
        "interpolate" => Ok(labs::interpolate(&parse(body)?)?),
        "approximate" => Ok(labs::approximate(&parse(body)?)?),
        "features" => Ok(labs::features(&parse(body)?)?),
        "erase" => Ok(labs::erase(&parse(body)?)?),
        "load" => Ok(labs::load(&parse(body)?)?),
        other => Err(ApiError {
            status: 404,
            message: format!(
                "unknown endpoint {:?} (POST /api/<name> with name one of {})",
                other.chars().take(40).collect::<String>(),
                ENDPOINTS.join(", ")
            ),
        }),
    }
}

/// Parses a request body, naming the field a problem is about.
///
/// # Errors
/// Status 400 with serde's message.
pub fn parse<R: DeserializeOwned>(body: &[u8]) -> std::result::Result<R, ApiError> {
    let mut de = serde_json::Deserializer::from_slice(body);
    let value = R::deserialize(&mut de)
        .and_then(|v| de.end().map(|()| v))
        .map_err(|e| ApiError::bad_request(format!("malformed request: {e}")))?;
    Ok(value)
}
