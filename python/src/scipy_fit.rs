//! scipy's fitting functions for many columns (`make_interp_spline`, `make_lsq_spline`,
//! `make_smoothing_spline`, `make_ndbspl`) as the library implements them, each one call
//! on the row-major `len(x) × m` data. `spline._make` and `spline._nd` convert the
//! arguments and move the axes.

use crate::columns::Columns;
use crate::{IntoPy, array, bad_input, optional_slice, slice};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use spline::KnotVector;
use spline::fit::{
    InterpBc, LsqMethod, SmoothingParameter, make_interp_spline, make_lsq_spline,
    make_smoothing_spline,
};

/// scipy's `make_smoothing_spline` on every column at once (the library's
/// `spline_fit::make_smoothing_spline`): λ given, or chosen per column by generalised
/// cross-validation.
#[pyfunction]
#[pyo3(signature = (x, y, m, w=None, lam=None))]
fn smoothing_columns(
    py: Python<'_>,
    x: PyReadonlyArray1<'_, f64>,
    y: PyReadonlyArray1<'_, f64>,
    m: usize,
    w: Option<PyReadonlyArray1<'_, f64>>,
    lam: Option<f64>,
) -> PyResult<Columns> {
    let (x, y) = (slice(&x, "x")?, slice(&y, "y")?);
    let w = optional_slice(&w, "w")?;
    let parameter = lam.map_or(SmoothingParameter::Gcv, SmoothingParameter::Lambda);
    py.detach(|| make_smoothing_spline(x, y, m, w, parameter))
        .py()
        .map(Columns)
}

/// The not-a-knot knots of degree `k` for the abscissae `x` (scipy's `_not_a_knot`: the
/// ends `k + 1` times, interior knots the data for odd `k`, midpoints for even `k`, leaving
/// out the first and last `⌈k/2⌉`).
#[pyfunction]
fn not_a_knot<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    k: usize,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let knots = KnotVector::not_a_knot(k, slice(&x, "x")?).py()?;
    Ok(array(py, knots.knots().to_vec()))
}

/// scipy's `make_interp_spline` on every column at once (the library's
/// `spline_fit::make_interp_spline`): `bc` is `"not-a-knot"`, `"periodic"` or `"ends"`,
/// the last with the end conditions `left` and `right`, each a list of `(order, values)`
/// with one value per column.
#[pyfunction]
#[pyo3(signature = (x, y, m, k, t, bc, left, right))]
#[allow(clippy::too_many_arguments)]
fn interp_spline(
    py: Python<'_>,
    x: PyReadonlyArray1<'_, f64>,
    y: PyReadonlyArray1<'_, f64>,
    m: usize,
    k: usize,
    t: Option<PyReadonlyArray1<'_, f64>>,
    bc: &str,
    left: Vec<(usize, Vec<f64>)>,
    right: Vec<(usize, Vec<f64>)>,
) -> PyResult<Columns> {
    let (x, y) = (slice(&x, "x")?, slice(&y, "y")?);
    let t = optional_slice(&t, "t")?;
    let bc = match bc {
        "not-a-knot" => InterpBc::NotAKnot,
        "periodic" => InterpBc::Periodic,
        "ends" => InterpBc::Ends { left, right },
        other => return Err(bad_input(format!("Unknown boundary condition: {other}"))),
    };
    py.detach(|| make_interp_spline(x, y, m, k, t, &bc))
        .py()
        .map(Columns)
}

/// scipy's `make_lsq_spline` on every column at once (the library's
/// `spline_fit::make_lsq_spline`); `method` is `"qr"` or `"norm-eq"`.
#[pyfunction]
#[pyo3(signature = (x, y, m, t, k, w, method))]
#[allow(clippy::too_many_arguments)]
fn lsq_spline(
    py: Python<'_>,
    x: PyReadonlyArray1<'_, f64>,
    y: PyReadonlyArray1<'_, f64>,
    m: usize,
    t: PyReadonlyArray1<'_, f64>,
    k: usize,
    w: Option<PyReadonlyArray1<'_, f64>>,
    method: &str,
) -> PyResult<Columns> {
    let (x, y, t) = (slice(&x, "x")?, slice(&y, "y")?, slice(&t, "t")?);
    let w = optional_slice(&w, "w")?;
    let method = lsq_method(method)?;
    py.detach(|| make_lsq_spline(x, y, m, t, k, w, method))
        .py()
        .map(Columns)
}

/// scipy's `method` of `make_lsq_spline`.
fn lsq_method(name: &str) -> PyResult<LsqMethod> {
    // scipy's words for scipy's test of an unknown method.
    LsqMethod::from_name(name).map_err(|_| bad_input(format!("Unknown method = {name:?}.")))
}

/// scipy's `make_ndbspl` (the library's): the tensor-product interpolant of values on the
/// grid `points` (`values` flat, row-major `m_1 × … × m_d × columns`), not-a-knot in every
/// dimension.
#[pyfunction]
fn make_ndbspl_columns(
    py: Python<'_>,
    points: Vec<Vec<f64>>,
    values: PyReadonlyArray1<'_, f64>,
    k: Vec<usize>,
    columns: usize,
) -> PyResult<crate::nd::NdColumns> {
    let values = slice(&values, "values")?;
    let grid: Vec<&[f64]> = points.iter().map(Vec::as_slice).collect();
    py.detach(|| spline::fit::make_ndbspl(&grid, values, &k, columns))
        .py()
        .map(crate::nd::NdColumns)
}

/// Registers the functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(interp_spline, m)?)?;
    m.add_function(wrap_pyfunction!(lsq_spline, m)?)?;
    m.add_function(wrap_pyfunction!(make_ndbspl_columns, m)?)?;
    m.add_function(wrap_pyfunction!(not_a_knot, m)?)?;
    m.add_function(wrap_pyfunction!(smoothing_columns, m)?)?;
    Ok(())
}
