//! The JSON endpoints of the studio, independent of HTTP: [`handle`] takes the name of an
//! endpoint and the request body and answers the JSON value the page draws, or an
//! [`ApiError`]. Every request carries the whole state it needs (the page keeps its points,
//! knots and parameters), so the server holds none and each browser tab is independent.
//!
//! Curves in requests and answers are exchange-format records (`docs/exchange-format.md`);
//! points are `[x, y]` arrays. The endpoints and their fields are listed in
//! `docs/exchange-format.md`, section "spline studio".

use crate::labs;
use nalgebra::Vector2;
use serde::de::DeserializeOwned;
use serde_json::Value;
use spline_core::{Error, ErrorKind, Result};
use spline_geom::{BSpline, ParamCurve};
use spline_io::exchange::CurveRecord;

/// A planar point of the studio.
pub type Point = Vector2<f64>;

/// The largest number of points (data or control points) a request may carry.
pub const MAX_POINTS: usize = 100_000;
/// The largest number of samples a drawn curve may ask for (per span, or in all for Bézier
/// curves).
pub const MAX_SAMPLES: usize = 10_000;
/// The largest degree the studio accepts (Bézier curves of many points included).
pub const MAX_DEGREE: usize = 60;

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

/// Checks a list of `[x, y]` points: at most [`MAX_POINTS`], at least `min`, all finite.
///
/// # Errors
/// [`ErrorKind::TooFewPoints`], [`ErrorKind::InvalidLength`] or [`ErrorKind::NonFinite`].
pub fn points(raw: &[[f64; 2]], min: usize, what: &str) -> Result<Vec<Point>> {
    if raw.len() > MAX_POINTS {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("{what}: {} points, at most {MAX_POINTS}", raw.len()),
        ));
    }
    if raw.len() < min {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!("{what}: {} point(s), at least {min} needed", raw.len()),
        ));
    }
    if let Some(k) = raw.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("{what}: point {k} is not finite"),
        ));
    }
    Ok(raw.iter().map(|p| Vector2::new(p[0], p[1])).collect())
}

/// Checks a count given by the user against `1..=max`.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`].
pub fn count(value: usize, max: usize, what: &str) -> Result<usize> {
    if value == 0 || value > max {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("{what} must be between 1 and {max}, got {value}"),
        ));
    }
    Ok(value)
}

/// `[x, y]` for JSON.
#[must_use]
pub fn xy(p: &Point) -> [f64; 2] {
    [p.x, p.y]
}

/// `[x, y]` of each point.
#[must_use]
pub fn xys(points: &[Point]) -> Vec<[f64; 2]> {
    points.iter().map(xy).collect()
}

/// The exchange-format record of a planar B-spline curve.
#[must_use]
pub fn record(curve: &BSpline<f64, Point>) -> CurveRecord {
    CurveRecord::from_bspline(curve)
}

/// A planar B-spline curve from its exchange-format record.
///
/// # Errors
/// [`ErrorKind::DimensionMismatch`] unless the points are 2-D; [`ErrorKind::InvalidLength`]
/// beyond [`MAX_POINTS`]; the errors of [`CurveRecord::to_bspline`].
pub fn planar(record: &CurveRecord) -> Result<BSpline<f64, Point>> {
    if record.control_points.len() > MAX_POINTS || record.knots.len() > MAX_POINTS + MAX_DEGREE {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("curve: more than {MAX_POINTS} control points"),
        ));
    }
    if record.weights.is_some() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "curve: the studio draws B-spline curves (no weights)",
        ));
    }
    let d = record.dimension()?;
    if d != 2 {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!("curve: the studio draws planar curves, this one has dimension {d}"),
        ));
    }
    record.to_bspline()
}

/// The points of the drawn polyline of a B-spline curve: `per_span` equal parameter steps
/// in every knot span ([`ParamCurve::sample_params`]), as `[x, y]`.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for `per_span` outside `1..=MAX_SAMPLES`; evaluation
/// errors.
pub fn samples(curve: &BSpline<f64, Point>, per_span: usize) -> Result<Vec<[f64; 2]>> {
    count(per_span, MAX_SAMPLES, "samples per span")?;
    let params = curve.sample_params(per_span);
    if params.len() > MAX_POINTS {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "{} samples asked for, at most {MAX_POINTS}: fewer per span",
                params.len()
            ),
        ));
    }
    Ok(xys(&curve.eval_many(&params)?))
}
