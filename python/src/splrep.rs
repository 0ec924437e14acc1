//! scipy's FITPACK replicas (`make_splrep`, `make_splprep`, `generate_knots`) as the library
//! implements them (`spline_fit::make_splrep`, `generate_knots`; `periodic` is scipy's
//! `bc_type="periodic"`). `spline._splrep` validates the arguments with scipy's words and
//! builds the `BSpline`.

use crate::{IntoPy, array, bad_input, slice};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use spline::ControlPoint;
use spline::fit::{SplrepOptions, chord_length_parameters, generate_knots, make_splrep};
use spline::nalgebra::SVector;

/// The largest number of coordinates of `make_splprep`'s points.
const MAX_SPLPREP_DIM: usize = 6;

/// Knots, row-major coefficients and whether the residual target was met.
type SplrepFit<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>, bool);

/// Points of type `P` from a flat row-major array.
fn points<P: ControlPoint<f64>>(flat: &[f64]) -> Vec<P> {
    flat.chunks_exact(P::DIM)
        .map(|row| P::from_coords(|i| row[i]))
        .collect()
}

/// Runs `$e` with `$P` the point type of `$dim` coordinates (`0`: scalar).
macro_rules! by_dim {
    ($dim:expr, $P:ident => $e:expr) => {
        match $dim {
            0 => {
                type $P = f64;
                $e
            }
            1 => {
                type $P = SVector<f64, 1>;
                $e
            }
            2 => {
                type $P = SVector<f64, 2>;
                $e
            }
            3 => {
                type $P = SVector<f64, 3>;
                $e
            }
            4 => {
                type $P = SVector<f64, 4>;
                $e
            }
            5 => {
                type $P = SVector<f64, 5>;
                $e
            }
            6 => {
                type $P = SVector<f64, 6>;
                $e
            }
            d => Err(bad_input(format!(
                "values of {d} coordinates: 1 to {MAX_SPLPREP_DIM} are supported"
            ))),
        }
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
    let w = w.as_ref().map(|w| slice(w, "w")).transpose()?;
    let t = t.as_ref().map(|t| slice(t, "t")).transpose()?;
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
    let (knots, coefficients, converged) = by_dim!(dim, P => {
        let values: Vec<P> = points(y);
        py.detach(|| make_splrep(x, &values, &options)).py().map(|fit| {
            let flat: Vec<f64> = fit
                .spline
                .control_points()
                .iter()
                .flat_map(|p| (0..P::DIM).map(move |i| p.coord(i)))
                .collect();
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
    let w = w.as_ref().map(|w| slice(w, "w")).transpose()?;
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
    by_dim!(dim, P => {
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
    let u = by_dim!(dim, P => {
        let values: Vec<P> = self::points(flat);
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
