//! The endpoints, one per lab of seed 003 (and the curvature tools): each parses its
//! request, calls the library and answers what the page draws. No geometry is computed
//! here: de Casteljau, subdivision and elevation are spline-geom's, the fits spline-fit's,
//! the features spline-algebra's and the eraser spline-shape's.

use crate::values::{
    MAX_DEGREE, MAX_POINTS, MAX_SAMPLES, Point, count, planar, points, record, samples, xy, xys,
};
use serde::Deserialize;
use serde_json::{Value, json};
use spline_algebra::{CurveFeatures, default_feature_accuracy};
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_fit::{
    BezierLeastSquaresRequest, CorrectionOptions, InterpolationOptions, KnotChoice,
    LeastSquaresRequest, LsqKnots, Parametrization, bezier_interpolate, fit_bezier_least_squares,
    fit_least_squares,
};
use spline_geom::{BSpline, Bezier, ParamCurve, curvature_comb};
use spline_io::exchange::CurveRecord;
use spline_shape::{MAX_CURVATURE_EXTREMA, SmoothingOptions, WarmStart, smooth, smooth_from};

/// Samples per knot span of the drawn B-spline curves, unless the request says otherwise.
const PER_SPAN: usize = 24;
/// Samples of a drawn Bézier curve, unless the request says otherwise.
const BEZIER_SAMPLES: usize = 201;

fn per_span() -> usize {
    PER_SPAN
}
fn bezier_samples() -> usize {
    BEZIER_SAMPLES
}
fn chordal() -> String {
    "chordal".into()
}
fn all_parametrizations() -> Vec<String> {
    Parametrization::<f64>::NAMES.map(String::from).to_vec()
}

fn parametrization(name: &str) -> Result<Parametrization<f64>> {
    Parametrization::from_name(name)
}

fn degree(value: usize) -> Result<usize> {
    count(value, MAX_DEGREE, "degree")
}

/// `POST /api/bezier`: a Bézier curve, its de Casteljau construction at `t`, the
/// subdivision there and the curve raised by `elevate` degrees.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BezierRequest {
    control_points: Vec<[f64; 2]>,
    t: f64,
    #[serde(default)]
    elevate: usize,
    #[serde(default = "bezier_samples")]
    samples: usize,
}

pub(crate) fn bezier(request: &BezierRequest) -> Result<Value> {
    let control = points(&request.control_points, 2, "control_points")?;
    degree(control.len() - 1)?;
    let samples = count(request.samples, MAX_SAMPLES, "samples")?.max(2);
    let elevate = if request.elevate > MAX_DEGREE {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "elevate must be at most {MAX_DEGREE}, got {}",
                request.elevate
            ),
        )
        .with_value(request.elevate as f64)
        .with_interval(0.0, MAX_DEGREE as f64));
    } else {
        request.elevate
    };
    let curve = Bezier::new(control)?;
    let t = request.t;
    // The de Casteljau triangle at t (level j, point i: the curve of P_i … P_{i+j} at t);
    // it refuses a t outside [0, 1].
    let triangle = curve.de_casteljau(t)?;
    let point = curve.eval(t)?;
    // Halves only strictly inside the interval: at its ends the library refuses to split.
    let (left, right) = match curve.subdivide(t) {
        Ok((l, r)) => (
            json!(xys(l.control_points())),
            json!(xys(r.control_points())),
        ),
        Err(e) if e.kind() == ErrorKind::OutOfDomain => (Value::Null, Value::Null),
        Err(e) => return Err(e),
    };
    // `samples` equal steps over the one piece of the curve, ends included.
    let drawn = curve.eval_many(&curve.sample_params(samples - 1))?;
    let elevated = curve.elevate_degree(elevate);
    Ok(json!({
        "curve": record(&curve.to_bspline()?),
        "samples": xys(&drawn),
        "point": xy(&point),
        "casteljau": triangle.iter().map(|level| xys(level)).collect::<Vec<_>>(),
        "left": left,
        "right": right,
        "elevated": xys(elevated.control_points()),
    }))
}

/// `POST /api/bspline`: a B-spline curve of the given degree on the control points, with
/// the given knots (or clamped uniform ones), optionally with one knot inserted.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BSplineRequest {
    degree: usize,
    control_points: Vec<[f64; 2]>,
    #[serde(default)]
    knots: Option<Vec<f64>>,
    #[serde(default)]
    insert: Option<f64>,
    #[serde(default = "per_span")]
    per_span: usize,
}

/// The distinct knots of the domain (its ends included) with their multiplicities and
/// points.
fn knot_marks(curve: &BSpline<f64, Point>) -> Result<Vec<Value>> {
    let knots = curve.knots();
    let breaks = knots.domain_breaks();
    let points = curve.eval_many(&breaks)?;
    Ok(breaks
        .iter()
        .zip(&points)
        .map(|(&u, p)| json!({"u": u, "multiplicity": knots.multiplicity(u), "point": xy(p)}))
        .collect())
}

fn bspline_answer(curve: &BSpline<f64, Point>, per_span: usize) -> Result<Value> {
    Ok(json!({
        "curve": record(curve),
        "samples": samples(curve, per_span)?,
        "knots": knot_marks(curve)?,
        "domain": [curve.domain().0, curve.domain().1],
    }))
}

pub(crate) fn bspline(request: &BSplineRequest) -> Result<Value> {
    let control = points(&request.control_points, 2, "control_points")?;
    let p = degree(request.degree)?;
    // Too few control points for the degree: the knot vector or the curve refuses them.
    let knots = match &request.knots {
        Some(k) if k.len() > MAX_POINTS + MAX_DEGREE => {
            return Err(Error::new(ErrorKind::InvalidLength, "too many knots"));
        }
        Some(k) => KnotVector::new(p, k.clone())?,
        None => KnotVector::clamped_uniform(p, control.len(), 0.0, 1.0)?,
    };
    let mut curve = BSpline::new(knots, control)?;
    if let Some(u) = request.insert {
        curve = curve.insert_knot(u, 1)?;
    }
    bspline_answer(&curve, count(request.per_span, MAX_SAMPLES, "per_span")?)
}

/// `POST /api/interpolate`: the curves through the points for each parametrisation
/// (seed 003 TD2: a Bézier curve of degree `n`, or a B-spline of the given degree with
/// averaged knots).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct InterpolateRequest {
    points: Vec<[f64; 2]>,
    #[serde(default)]
    degree: Option<usize>,
    #[serde(default = "all_parametrizations")]
    parametrizations: Vec<String>,
    #[serde(default = "per_span")]
    per_span: usize,
}

pub(crate) fn interpolate(request: &InterpolateRequest) -> Result<Value> {
    let data = points(&request.points, 2, "points")?;
    let per_span = count(request.per_span, MAX_SAMPLES, "per_span")?;
    if request.parametrizations.len() > 3 {
        return Err(
            Error::new(ErrorKind::InvalidLength, "at most three parametrizations")
                .with_counts(3, request.parametrizations.len()),
        );
    }
    let mut fits = Vec::new();
    for name in &request.parametrizations {
        let param = parametrization(name)?;
        let (curve, params, max) = match request.degree {
            None => {
                degree(data.len() - 1)?;
                let fit = bezier_interpolate(&data, &param, (0.0, 1.0))?;
                (fit.curve.to_bspline()?, fit.params, fit.deviation.max)
            }
            Some(p) => {
                let options = InterpolationOptions {
                    parametrization: param,
                    knots: KnotChoice::Averaging,
                    ..InterpolationOptions::default()
                };
                let fit = spline_fit::interpolate(&data, degree(p)?, &options)?;
                (fit.curve, fit.params, fit.deviation.max)
            }
        };
        let per = if request.degree.is_none() {
            per_span * 8
        } else {
            per_span
        };
        fits.push(json!({
            "parametrization": name,
            "curve": record(&curve),
            "params": params,
            "max_deviation": max,
            "samples": samples(&curve, per.min(MAX_SAMPLES))?,
        }));
    }
    Ok(json!({ "fits": fits }))
}

/// `POST /api/approximate`: least squares with `control_points` control points (or a Bézier
/// curve of degree `degree` with `"bezier": true`), from the named parametrisation or from
/// `params` (those of the previous answer), then `correct` sweeps of parameter correction.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ApproximateRequest {
    points: Vec<[f64; 2]>,
    degree: usize,
    #[serde(default)]
    control_points: Option<usize>,
    #[serde(default)]
    bezier: bool,
    #[serde(default = "chordal")]
    parametrization: String,
    #[serde(default)]
    params: Option<Vec<f64>>,
    #[serde(default)]
    knots: Option<Vec<f64>>,
    #[serde(default)]
    correct: usize,
    #[serde(default)]
    angle_tolerance: Option<f64>,
    #[serde(default = "per_span")]
    per_span: usize,
}

pub(crate) fn approximate(request: &ApproximateRequest) -> Result<Value> {
    let data = points(&request.points, 2, "points")?;
    let p = degree(request.degree)?;
    let per_span = count(request.per_span, MAX_SAMPLES, "per_span")?;
    let param = match &request.params {
        Some(given) if given.len() == data.len() => Parametrization::Given(given.clone()),
        Some(given) => {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!("{} params for {} points", given.len(), data.len()),
            ));
        }
        None => parametrization(&request.parametrization)?,
    };
    let mut options = CorrectionOptions {
        max_iterations: request.correct,
        ..CorrectionOptions::default()
    };
    if let Some(eps) = request.angle_tolerance {
        options.angle_tolerance = eps;
    }
    let correction = (request.correct > 0).then_some(options);
    let (curve, params, fit, report) = if request.bezier {
        let answer = fit_bezier_least_squares(
            &data,
            &BezierLeastSquaresRequest {
                parametrization: param,
                correction,
                ..BezierLeastSquaresRequest::new(p)
            },
        )?;
        let fit = answer.fit;
        (
            fit.curve.to_bspline()?,
            fit.params,
            fit.deviation,
            answer.correction,
        )
    } else {
        let knots = match (&request.knots, request.control_points) {
            (Some(k), _) if k.len() > MAX_POINTS + MAX_DEGREE => {
                return Err(Error::new(ErrorKind::InvalidLength, "too many knots"));
            }
            (Some(k), _) => LsqKnots::Given(KnotVector::new(p, k.clone())?),
            (None, Some(n)) => LsqKnots::ControlPoints(n),
            (None, None) => {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    "give control_points (or knots) for a B-spline approximation, or \"bezier\": true",
                ));
            }
        };
        let answer = fit_least_squares(
            &data,
            &LeastSquaresRequest {
                parametrization: param,
                correction,
                ..LeastSquaresRequest::new(p, knots)
            },
        )?;
        let fit = answer.fit;
        (fit.curve, fit.params, fit.deviation, answer.correction)
    };
    // The feet of the data on the curve: the points at the data's parameters.
    let feet = curve.eval_many(&params)?;
    let per = if request.bezier {
        (per_span * 8).min(MAX_SAMPLES)
    } else {
        per_span
    };
    let mut answer = json!({
        "curve": record(&curve),
        "params": params,
        "samples": samples(&curve, per)?,
        "projections": xys(&feet),
        "max_deviation": fit.max,
        "rms": fit.rms,
    });
    if let Some(report) = report {
        answer["correction"] = json!({
            "iterations": report.iterations,
            "converged": report.converged,
            "angle_error": report.angle_error(),
            "angles": report.angles,
            "errors": report.errors,
        });
    }
    Ok(answer)
}

/// `POST /api/features`: the curvature comb, the curvature plot, the inflections and the
/// curvature extrema of a planar B-spline curve.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct FeaturesRequest {
    curve: CurveRecord,
    #[serde(default = "per_span")]
    per_span: usize,
}

fn marks(curve: &BSpline<f64, Point>, params: &[f64]) -> Result<Vec<Value>> {
    params
        .iter()
        .map(|&u| {
            Ok(json!({
                "u": u,
                "point": xy(&curve.eval(u)?),
                "curvature": curve.signed_curvature(u)?,
            }))
        })
        .collect()
}

pub(crate) fn features(request: &FeaturesRequest) -> Result<Value> {
    let curve = planar(&request.curve)?;
    let per_span = count(request.per_span, MAX_SAMPLES, "per_span")?;
    let found = curve.features(default_feature_accuracy(curve.domain()))?;
    let params = curve.sample_params(per_span);
    if params.len() > MAX_POINTS {
        return Err(Error::new(ErrorKind::InvalidLength, "too many samples"));
    }
    // The comb: at each sample, the point, the signed curvature and the unit normal (where
    // the curve is regular; a cusp of the control polygon leaves a gap).
    let comb: Vec<[f64; 6]> = curvature_comb(&curve, &params)
        .iter()
        .map(|t| {
            [
                t.u,
                t.point.x,
                t.point.y,
                t.curvature,
                t.normal.x,
                t.normal.y,
            ]
        })
        .collect();
    Ok(json!({
        "curve": record(&curve),
        "samples": samples(&curve, per_span)?,
        "comb": comb,
        "inflections": marks(&curve, &found.inflections)?,
        "curvature_extrema": marks(&curve, &found.curvature_extrema)?,
        "constant_curvature": found.constant_curvature,
    }))
}

/// `POST /api/erase`: the selective eraser (thesis ch. 6): the closest cubic with
/// `control_points` control points whose curvature has only `extrema` extrema
/// (alternately maximum, minimum, … as `spline smooth --curvature-extrema`). With the
/// previous answer's `warm` record (while a data point is dragged) the eraser starts from
/// that answer ([`smooth_from`]): the update follows the drag.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct EraseRequest {
    points: Vec<[f64; 2]>,
    control_points: usize,
    extrema: usize,
    #[serde(default = "per_span")]
    per_span: usize,
    /// The `warm` record of the previous answer (while a point is dragged).
    #[serde(default)]
    warm: Option<WarmRecord>,
}

/// Where the previous answer ended, as the page sends it back.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct WarmRecord {
    curve: CurveRecord,
    allowed_extrema: Vec<f64>,
    first_sign: f64,
    knot_exponent: f64,
}

pub(crate) fn erase(request: &EraseRequest) -> Result<Value> {
    let data = points(&request.points, 4, "points")?;
    let per_span = count(request.per_span, MAX_SAMPLES, "per_span")?;
    let k = count(request.extrema, MAX_CURVATURE_EXTREMA, "extrema")?;
    let n = count(request.control_points, MAX_POINTS, "control_points")?;
    let mut options = SmoothingOptions::new(n);
    // Alternately maximum, minimum, … as the tool's --curvature-extrema: the library's rule.
    options.request_extrema(Some(k), Vec::new())?;
    let result = match &request.warm {
        Some(warm) => {
            let start = WarmStart {
                curve: planar(&warm.curve)?,
                allowed_extrema: warm.allowed_extrema.clone(),
                first_sign: warm.first_sign,
                knot_exponent: warm.knot_exponent,
                closed: false,
            };
            smooth_from(&data, &options, &start)?
        }
        None => smooth(&data, &options)?,
    };
    let curve = &result.curve;
    Ok(json!({
        "warm": {
            "curve": record(curve),
            "allowed_extrema": result.allowed_extrema,
            "first_sign": result.first_sign,
            "knot_exponent": result.knot_exponent,
        },
        "newton_steps": result.newton_steps,
        "curve": record(curve),
        "samples": samples(curve, per_span)?,
        "max_deviation": result.deviation.to_curve.max,
        "max_deviation_to_data": result.deviation.to_data,
        "extrema": result.extrema.iter().map(|e| json!({
            "u": e.param, "point": xy(&e.point), "kind": e.kind.to_string(),
        })).collect::<Vec<_>>(),
        "inflections": marks(curve, &result.inflections)?,
    }))
}

/// `POST /api/load`: the points of an uploaded file — an airfoil `.dat` (Selig or
/// Lednicer), a point file, or a JSON curve (its control points, and the curve).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LoadRequest {
    text: String,
}

pub(crate) fn load(request: &LoadRequest) -> Result<Value> {
    let text = request.text.trim_start();
    if text.starts_with('{') {
        let record = CurveRecord::from_json(text).map_err(|e| e.context("JSON curve"))?;
        let curve = planar(&record)?;
        return Ok(json!({
            "points": xys(curve.control_points()),
            "curve": record,
            "degree": curve.degree(),
        }));
    }
    let loaded = if text.starts_with('[') {
        let rows = spline_io::points::parse_points(text)?;
        let pts = rows
            .iter()
            .map(|r| match r.as_slice() {
                [x, y] => Ok([*x, *y]),
                _ => Err(Error::new(
                    ErrorKind::DimensionMismatch,
                    format!("points have {} coordinates, the studio draws 2", r.len()),
                )),
            })
            .collect::<Result<Vec<_>>>()?;
        json!({ "points": pts })
    } else {
        let airfoil = spline_io::airfoil::parse_airfoil(text)?;
        json!({ "points": xys(&airfoil.points), "name": airfoil.name })
    };
    let n = loaded["points"].as_array().map_or(0, Vec::len);
    if n > MAX_POINTS {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("{n} points, at most {MAX_POINTS}"),
        ));
    }
    Ok(loaded)
}
