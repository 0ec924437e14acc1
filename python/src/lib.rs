//! `spline._core`: the compiled half of the Python package `spline` (`python/python/spline/`
//! is the other half: scipy-style wrappers, `scipy.sparse` Jacobians and the type stubs).
//!
//! Everything here binds the library (`spline`), it computes nothing of its own: arrays come
//! in as contiguous `float64` numpy arrays (the Python layer converts), go out as flat numpy
//! arrays that the Python layer reshapes without copying, long work runs with the GIL
//! released, and every library error becomes a `spline.SplineError` (a `ValueError`)
//! carrying the library's one-line message, its kind in `.kind`.

// PyO3 extracts arguments by value (numpy borrows, vectors): the lint's advice to take a
// reference does not apply to `#[pyfunction]`s and `#[pymethods]`.
#![allow(clippy::needless_pass_by_value)]

#[macro_use]
mod convert;
mod cad;
mod columns;
mod curve;
mod fitting;
mod nd;
mod nurbs;
mod scipy_fit;
mod splrep;

use convert::SplineError;
pub(crate) use convert::{
    Csr, Features, IntoPy, array, bad_input, csr, features, flatten, knot_vector, optional_slice,
    points, slice,
};
use pyo3::prelude::*;

/// The module `spline._core`.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SplineError", m.py().get_type::<SplineError>())?;
    cad::register(m)?;
    columns::register(m)?;
    curve::register(m)?;
    nd::register(m)?;
    fitting::register(m)?;
    nurbs::register(m)?;
    scipy_fit::register(m)?;
    splrep::register(m)?;
    Ok(())
}
