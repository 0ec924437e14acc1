//! scipy's FITPACK replicas (`make_splrep`, `make_splprep`, `generate_knots`) as the library
//! implements them (`spline_fit::make_splrep`, `generate_knots`; `periodic` is scipy's
//! `bc_type="periodic"`). `spline._splrep` validates the arguments with scipy's words and
//! builds the `BSpline`.

use crate::{IntoPy, array, bad_input, flatten, optional_slice, points, slice};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use spline::fit::{SplrepOptions, chord_length_parameters, generate_knots, make_splrep};

/// The largest number of coordinates of `make_splprep`'s points.
const MAX_SPLPREP_DIM: usize = 6;

/// Knots, row-major coefficients and whether the residual target was met.
type SplrepFit<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>, bool);

/// Runs `$e` with `$P` the point type of `$dim` coordinates (`0`: scalar), up to
/// [`MAX_SPLPREP_DIM`].
macro_rules! splprep_dim {
    ($dim:expr, $P:ident => $e:expr) => {
        by_dim!($dim, $P => $e, [1, 2, 3, 4, 5, 6], d => Err(bad_input(format!(
            "values of {d} coordinates: 1 to {MAX_SPLPREP_DIM} are supported"
        ))))
    };
}

/// The fit of `make_splrep` (`dim = 0`: scalar values) or `make_splprep` (`dim`
/// coordinates, `x` the parameters): `(t, c, converged)` with `c` row-major; `converged`
/// is false when the residual target was not met (FITPACK's `ier` 2 or 3).
#[pyfunction]
#[pyo3(signature = (x, y, dim, w, xb, xe, k, s, t, nest, periodic=false))]
#[allow(clippy::too_many_arguments)]
fn splrep_fit<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    y: PyReadonlyArray1<'py, f64>,
    dim: usize,
    w: Option<PyReadonlyArray1<'py, f64>>,
    xb: Option<f64>,
    xe: Option<f64>,
    k: usize,
    s: f64,
    t: Option<PyReadonlyArray1<'py, f64>>,
    nest: Option<usize>,
    periodic: bool,
) -> PyResult<SplrepFit<'py>> {
    let (x, y) = (slice(&x, "x")?, slice(&y, "y")?);
    let (w, t) = (optional_slice(&w, "w")?, optional_slice(&t, "t")?);
    let options = SplrepOptions {
        weights: w,
        xb,
        xe,
        k,
        s,
        t,
        nest,
        periodic,
    };
    let (knots, coefficients, converged) = splprep_dim!(dim, P => {
        let values: Vec<P> = points(y);
        py.detach(|| make_splrep(x, &values, &options)).py().map(|fit| {
            let flat = flatten(fit.spline.control_points());
            (fit.spline.knots().knots().to_vec(), flat, fit.converged)
        })
    })?;
    Ok((array(py, knots), array(py, coefficients), converged))
}

/// Every knot vector of FITPACK's first stage (`generate_knots`; for `s = 0` the one
/// vector of interpolation, `y` unused).
#[pyfunction]
#[pyo3(signature = (x, y, dim, w, xb, xe, k, s, nest, periodic=false))]
#[allow(clippy::too_many_arguments)]
fn splrep_knots(
    py: Python<'_>,
    x: PyReadonlyArray1<'_, f64>,
    y: PyReadonlyArray1<'_, f64>,
    dim: usize,
    w: Option<PyReadonlyArray1<'_, f64>>,
    xb: Option<f64>,
    xe: Option<f64>,
    k: usize,
    s: f64,
    nest: Option<usize>,
    periodic: bool,
) -> PyResult<Vec<Vec<f64>>> {
    let (x, y) = (slice(&x, "x")?, slice(&y, "y")?);
    let w = optional_slice(&w, "w")?;
    let options = SplrepOptions {
        weights: w,
        xb,
        xe,
        k,
        s,
        t: None,
        nest,
        periodic,
    };
    splprep_dim!(dim, P => {
        let values: Vec<P> = points(y);
        py.detach(|| generate_knots(x, &values, &options)).py()
    })
}

/// scipy's default parameters of `make_splprep`: cumulative chord lengths on `[0, 1]` of
/// the points (flat, row-major, `dim` coordinates).
#[pyfunction]
fn chord_lengths<'py>(
    py: Python<'py>,
    points: PyReadonlyArray1<'py, f64>,
    dim: usize,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let flat = slice(&points, "x")?;
    let u = splprep_dim!(dim, P => {
        let values: Vec<P> = crate::points(flat);
        chord_length_parameters(&values).py()
    })?;
    Ok(array(py, u))
}

/// Registers the functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(splrep_fit, m)?)?;
    m.add_function(wrap_pyfunction!(splrep_knots, m)?)?;
    m.add_function(wrap_pyfunction!(chord_lengths, m)?)?;
    Ok(())
}
