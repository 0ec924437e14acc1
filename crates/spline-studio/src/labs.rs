//! The endpoints, one per lab of seed 003 (and the curvature tools): each parses its
//! request, calls the library and answers what the page draws. No geometry is computed
//! here: de Casteljau, subdivision and elevation are spline-geom's, the fits spline-fit's,
//! the features spline-algebra's and the eraser spline-shape's.

use crate::values::{
    MAX_DEGREE, MAX_POINTS, MAX_SAMPLES, Point, count, planar, points, record, samples, xy, xys,
};
use serde::Deserialize;
use serde_json::{Value, json};
use spline_algebra::CurveFeatures;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_fit::{
    CorrectionOptions, InterpolationOptions, KnotChoice, LeastSquaresRequest, LsqKnots,
    Parametrization, bezier_interpolate, bezier_least_squares, correct_parameters_bezier,
    deviation, fit_least_squares,
};
use spline_geom::{BSpline, Bezier, ParamCurve};
use spline_io::exchange::CurveRecord;
use spline_shape::{MAX_CURVATURE_EXTREMA, SmoothingOptions, WarmStart, smooth, smooth_from};

/// Samples per knot span of the drawn B-spline curves, unless the request says otherwise.
const PER_SPAN: usize = 24;
/// Samples of a drawn Bézier curve, unless the request says otherwise.
const BEZIER_SAMPLES: usize = 201;
/// Relative accuracy of the located features (as `spline features`).
const FEATURE_ACCURACY: f64 = 1e-12;

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
    let curve = Bezier::new(control.clone())?;
    let t = request.t;
    let point = curve.eval(t)?;
    // The de Casteljau triangle: level j, point i is the Bézier curve of P_i … P_{i+j} at t
    // (the library's de Casteljau evaluation of each sub-polygon).
    let n = control.len() - 1;
    let mut triangle = Vec::with_capacity(n + 1);
    for level in 0..=n {
        let row = (0..=n - level)
            .map(|i| Ok(xy(&Bezier::new(control[i..=i + level].to_vec())?.eval(t)?)))
            .collect::<Result<Vec<_>>>()?;
        triangle.push(row);
    }
    let (left, right) = if t > 0.0 && t < 1.0 {
        let (l, r) = curve.subdivide(t)?;
        (
            json!(xys(l.control_points())),
            json!(xys(r.control_points())),
        )
    } else {
        (Value::Null, Value::Null)
    };
    #[allow(clippy::cast_precision_loss)]
    let params: Vec<f64> = (0..samples)
        .map(|k| k as f64 / (samples - 1) as f64)
        .collect();
    let drawn = params
        .iter()
        .map(|&s| curve.eval(s).map(|p| xy(&p)))
        .collect::<Result<Vec<_>>>()?;
    let elevated = curve.elevate_degree(elevate);
    Ok(json!({
        "curve": record(&curve.to_bspline()?),
        "samples": drawn,
        "point": xy(&point),
        "casteljau": triangle,
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

fn knot_marks(curve: &BSpline<f64, Point>) -> Result<Vec<Value>> {
    let (a, b) = curve.domain();
    curve
        .knots()
        .breakpoints()
        .into_iter()
        .filter(|&(u, _)| u >= a && u <= b)
        .map(|(u, mult)| Ok(json!({"u": u, "multiplicity": mult, "point": xy(&curve.eval(u)?)})))
        .collect()
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
    if p >= control.len() {
        return Err(Error::new(
            ErrorKind::DegreeTooHigh,
            format!(
                "degree {p} needs at least {} control points, got {}",
                p + 1,
                control.len()
            ),
        ));
    }
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
    let (curve, params, report) = if request.bezier {
        let start = bezier_least_squares(&data, p, &param, (0.0, 1.0), None)?;
        if request.correct == 0 {
            (start.curve.to_bspline()?, start.params, None)
        } else {
            let (fit, report) =
                correct_parameters_bezier(&data, &start.params, p, (0.0, 1.0), &options)?;
            (fit.curve.to_bspline()?, fit.params, Some(report))
        }
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
                correction: (request.correct > 0).then_some(options),
                ..LeastSquaresRequest::new(p, knots)
            },
        )?;
        (answer.fit.curve, answer.fit.params, answer.correction)
    };
    let feet = curve.eval_many(&params)?;
    let fit = deviation(&curve, &params, &data)?;
    let (max, rms) = (fit.max, fit.rms);
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
        "max_deviation": max,
        "rms": rms,
    });
    if let Some(report) = report {
        answer["correction"] = json!({
            "iterations": report.iterations,
            "converged": report.converged,
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
    let (a, b) = curve.domain();
    let found = curve.features(FEATURE_ACCURACY * (b - a))?;
    let params = curve.sample_params(per_span);
    if params.len() > MAX_POINTS {
        return Err(Error::new(ErrorKind::InvalidLength, "too many samples"));
    }
    // The comb: at each sample, the point, the signed curvature and the unit normal (where
    // the curve is regular; a cusp of the control polygon leaves a gap).
    let mut comb = Vec::with_capacity(params.len());
    for &u in &params {
        if let (Ok(p), Ok(k), Ok(n)) = (
            curve.eval(u),
            curve.signed_curvature(u),
            curve.unit_normal(u),
        ) {
            comb.push([u, p.x, p.y, k, n.x, n.y]);
        }
    }
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
