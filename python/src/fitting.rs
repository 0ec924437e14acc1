//! Interpolation, least squares, parameter correction, the eraser (`smooth`) and the airfoil
//! reader, as the library (and the CLI's `interpolate`, `approximate`, `smooth`) call them.

use crate::curve::{Curve, Dyn, dyn_by_dim};
use crate::{IntoPy, array, flatten, knot_vector, optional_slice, points, slice};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use spline::KnotVector;
use spline::fit::{
    CorrectionOptions, LeastSquares, LeastSquaresRequest, LsqKnots, Parametrization,
    fit_least_squares, interpolate_with_knots,
};
use spline::io::airfoil::parse_airfoil;
use spline::nalgebra::Vector2;
use spline::shape::{ExtremaCount, OptionSpelling, SmoothRequest, SmoothWords};

/// Runs `$e` with `$P` the point type of dimension `$dim` (`0`: scalar) and wraps the
/// resulting B-spline in the matching [`Dyn`] variant.
macro_rules! by_curve_dim {
    ($dim:expr, $P:ident => $e:expr) => {
        dyn_by_dim!($dim, $P => $e, d => Err(spline::Error::new(
            spline::ErrorKind::DimensionMismatch,
            format!(
                "values of dimension {d}: 1 to {} are supported",
                crate::curve::MAX_DIM
            ),
        )))
    };
}

/// Points of type `P` from a flat array (checked to make whole rows).
fn rows<P: spline::ControlPoint<f64>>(flat: &[f64]) -> spline::Result<Vec<P>> {
    if flat.len() % P::DIM != 0 {
        return Err(spline::Error::new(
            spline::ErrorKind::DimensionMismatch,
            format!("{} values do not make rows of {}", flat.len(), P::DIM),
        ));
    }
    Ok(points(flat))
}

/// Interpolation at abscissae `x` (`make_interp_spline`): on `t`, or on the not-a-knot
/// knots of degree `k` when `t` is `None`.
#[pyfunction]
#[pyo3(signature = (x, y, dim, k, t=None))]
fn interpolate<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    y: PyReadonlyArray1<'py, f64>,
    dim: usize,
    k: usize,
    t: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Curve> {
    let x = slice(&x, "x")?;
    let y = slice(&y, "y")?;
    let knots = match &t {
        Some(t) => knot_vector(k, t, "t")?,
        None => KnotVector::not_a_knot(k, x).py()?,
    };
    py.detach(
        || by_curve_dim!(dim, P => rows::<P>(y).and_then(|q| interpolate_with_knots(&knots, x, &q))),
    )
    .py()
    .map(Curve)
}

/// Weighted least squares on the knots `t` (`make_lsq_spline`): minimises
/// $\sum_j (w_j \lVert y_j - f(x_j) \rVert)^2$.
#[pyfunction]
#[pyo3(signature = (x, y, dim, t, k, w=None))]
fn least_squares<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    y: PyReadonlyArray1<'py, f64>,
    dim: usize,
    t: PyReadonlyArray1<'py, f64>,
    k: usize,
    w: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Curve> {
    let x = slice(&x, "x")?;
    let y = slice(&y, "y")?;
    let w = optional_slice(&w, "w")?;
    let knots = knot_vector(k, &t, "t")?;
    py.detach(|| {
        by_curve_dim!(dim, P => rows::<P>(y).and_then(|q| {
            let mut problem = LeastSquares::new(&q, x, knots.clone());
            if let Some(w) = w {
                problem = problem.weights(w);
            }
            problem.solve().map(|fit| fit.curve)
        }))
    })
    .py()
    .map(Curve)
}

/// The parametrisation named `name` (the library's names).
fn parametrization(name: &str) -> PyResult<Parametrization<f64>> {
    Parametrization::from_name(name).py()
}

/// A fit with parameter correction: the curve, the parameters of the data, the largest and
/// the RMS deviation, the sweeps done and whether the angle criterion stopped them.
type Fitted<'py> = (Curve, Bound<'py, PyArray1<f64>>, f64, f64, usize, bool);

/// Least squares of points with `n` control points and parameter correction (seed 003):
/// `(curve, params, max deviation, rms, sweeps, converged)`.
#[pyfunction]
#[pyo3(signature = (points, dim, n, k, parametrization, iterations, angle_tolerance))]
#[allow(clippy::too_many_arguments)]
fn fit<'py>(
    py: Python<'py>,
    points: PyReadonlyArray1<'py, f64>,
    dim: usize,
    n: usize,
    k: usize,
    parametrization: &str,
    iterations: usize,
    angle_tolerance: f64,
) -> PyResult<Fitted<'py>> {
    let flat = slice(&points, "points")?;
    let how = self::parametrization(parametrization)?;
    let options = CorrectionOptions {
        max_iterations: iterations,
        angle_tolerance,
        ..CorrectionOptions::default()
    };
    let mut extra = (Vec::new(), 0.0, 0.0, 0, false);
    let request = LeastSquaresRequest {
        parametrization: how,
        correction: Some(options),
        ..LeastSquaresRequest::new(k, LsqKnots::ControlPoints(n))
    };
    let curve = py
        .detach(|| {
            by_curve_dim!(dim, P => rows::<P>(flat).and_then(|q| {
                let answer = fit_least_squares(&q, &request)?;
                let fit = answer.fit;
                let (sweeps, converged) = answer
                    .correction
                    .map_or((0, false), |r| (r.iterations, r.converged));
                extra = (
                    fit.params,
                    fit.deviation.max,
                    fit.deviation.rms,
                    sweeps,
                    converged,
                );
                Ok(fit.curve)
            }))
        })
        .py()?;
    let (params, max, rms, sweeps, converged) = extra;
    Ok((Curve(curve), array(py, params), max, rms, sweeps, converged))
}

/// What `smooth` returns besides the curve: the CLI's report fields, then the library's record
/// of the line of its `summary.jsonl` ([`SummaryLine`]).
type SmoothReport = (
    (bool, usize, usize, usize),
    f64,
    usize,
    f64,
    f64,
    Vec<(f64, f64, f64, String)>,
    Vec<f64>,
    usize,
    usize,
    usize,
    usize,
    SummaryLine,
);

/// [`spline::shape::SmoothSummary`]'s fields in order: control points, max deviation, max
/// deviation to the data, extrema, error, warnings.
type SummaryLine = (
    Option<usize>,
    Option<f64>,
    Option<f64>,
    Option<usize>,
    Option<String>,
    Vec<String>,
);

/// The selective eraser of curvature extrema (`spline smooth`) on planar points (flat,
/// `x0, y0, x1, …`), the options by the CLI's names (`curvature_extrema`: a count or `auto`,
/// as text): `(curve, ((closed, first_point, control_points, control points of the opened
/// curve), max_deviation, max_deviation_index, max_deviation_to_data, rms, extrema (u, x, y,
/// kind), inflections, refinements, conditions, least_squares_curvature_extrema,
/// newton_steps, summary))`. A closed curve comes as its wrapped container (as the CLI writes
/// it).
#[pyfunction]
#[pyo3(signature = (points, control_points, max_deviation, degree, curvature_extrema, extrema, objective, thorough, knot_search, closed, knot_exponents))]
#[allow(clippy::too_many_arguments)]
fn smooth(
    py: Python<'_>,
    points: PyReadonlyArray1<'_, f64>,
    control_points: Option<usize>,
    max_deviation: Option<f64>,
    degree: usize,
    curvature_extrema: Option<String>,
    extrema: Vec<String>,
    objective: &str,
    thorough: bool,
    knot_search: bool,
    closed: bool,
    knot_exponents: Option<Vec<f64>>,
) -> PyResult<(Curve, SmoothReport)> {
    let words = SmoothWords {
        control_points,
        max_deviation,
        degree,
        curvature_extrema: curvature_extrema.map(|text| {
            text.parse::<ExtremaCount>()
                .map_err(|e| e.context("curvature_extrema"))
        }),
        extrema: &extrema,
        objective,
        thorough,
        knot_search,
        closed,
        knot_exponents: knot_exponents.map(Ok),
    };
    let request = SmoothRequest::from_words(words, OptionSpelling::Keywords).py()?;
    let q: Vec<Vector2<f64>> = rows(slice(&points, "points")?).py()?;
    let r = py.detach(|| request.run(&q)).py()?;
    let summary = r.summary();
    let opened = r.curve.control_points().len();
    let report = (
        (
            r.periodic.is_some(),
            r.first_point,
            r.control_point_count(),
            opened,
        ),
        r.deviation.to_curve.max,
        r.deviation.to_curve.max_index,
        r.deviation.to_data,
        r.deviation.to_curve.rms,
        r.extrema
            .iter()
            .map(|e| (e.param, e.point.x, e.point.y, e.kind.to_string()))
            .collect(),
        r.inflections.clone(),
        r.refinements,
        r.conditions,
        r.start_extrema,
        r.newton_steps,
        (
            summary.control_points,
            summary.max_deviation,
            summary.max_deviation_to_data,
            summary.extrema,
            summary.error,
            summary.warnings,
        ),
    );
    Ok((Curve(Dyn::V2(r.output_curve().clone())), report))
}

/// The points of an airfoil file's text (Selig or Lednicer), flat, in Selig order, and the
/// name line if any.
#[pyfunction]
fn parse_airfoil_text<'py>(
    py: Python<'py>,
    text: &str,
) -> PyResult<(Bound<'py, PyArray1<f64>>, Option<String>)> {
    let airfoil = parse_airfoil(text).py()?;
    Ok((array(py, flatten(&airfoil.points)), airfoil.name))
}

/// Registers the functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(interpolate, m)?)?;
    m.add_function(wrap_pyfunction!(least_squares, m)?)?;
    m.add_function(wrap_pyfunction!(fit, m)?)?;
    m.add_function(wrap_pyfunction!(smooth, m)?)?;
    m.add_function(wrap_pyfunction!(parse_airfoil_text, m)?)?;
    Ok(())
}
