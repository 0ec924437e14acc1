//! The conversions every binding shares: library errors as Python exceptions, numpy arrays
//! in and out, point types chosen at run time (`by_dim!`), features and sparse matrices as
//! tuples.

/// Runs `$e` with `$P` the point type of `$dim` coordinates: `f64` for `0` (scalar values),
/// `SVector<f64, n>` for each `n` listed; another dimension `$d` gives `$other`.
macro_rules! by_dim {
    ($dim:expr, $P:ident => $e:expr, [$($n:literal),+], $d:pat => $other:expr) => {
        match $dim {
            0 => {
                type $P = f64;
                $e
            }
            $($n => {
                type $P = spline::nalgebra::SVector<f64, $n>;
                $e
            })+
            $d => $other,
        }
    };
}

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use spline::algebra::{CsrMatrix, PlanarFeatures};
use spline::{ControlPoint, KnotVector};

create_exception!(
    _core,
    SplineError,
    PyValueError,
    "An error reported by the spline library: bad input (the message says which), or a \
     computation that cannot succeed. `.kind` names the library's error kind."
);

/// A library error as a Python exception: `SplineError(message)` with `.kind` set.
pub(crate) fn py_err(e: &spline::Error) -> PyErr {
    let err = SplineError::new_err(e.to_string());
    Python::attach(|py| {
        // Setting an attribute on a fresh exception instance cannot fail in practice; if it
        // did, the message is still there.
        let _ = err.value(py).setattr("kind", format!("{:?}", e.kind()));
    });
    err
}

/// `Result<T, spline::Error>` → `PyResult<T>`.
pub(crate) trait IntoPy<T> {
    /// Converts the error with [`py_err`].
    fn py(self) -> PyResult<T>;
}

impl<T> IntoPy<T> for spline::Result<T> {
    fn py(self) -> PyResult<T> {
        self.map_err(|e| py_err(&e))
    }
}

/// A bad argument found before the library is called (a shape, a name): `SplineError` too.
pub(crate) fn bad_input(message: impl Into<String>) -> PyErr {
    py_err(&spline::Error::new(
        spline::ErrorKind::InvalidArgument,
        message,
    ))
}

/// The contents of a contiguous 1-D array.
pub(crate) fn slice<'a>(array: &'a PyReadonlyArray1<'_, f64>, what: &str) -> PyResult<&'a [f64]> {
    array
        .as_slice()
        .map_err(|_| bad_input(format!("{what}: expected a contiguous float64 array")))
}

/// The contents of an optional contiguous 1-D array.
pub(crate) fn optional_slice<'a>(
    array: &'a Option<PyReadonlyArray1<'_, f64>>,
    what: &str,
) -> PyResult<Option<&'a [f64]>> {
    array.as_ref().map(|a| slice(a, what)).transpose()
}

/// The knot vector of degree `degree` on the knots of a 1-D array (`what` names it).
pub(crate) fn knot_vector(
    degree: usize,
    knots: &PyReadonlyArray1<'_, f64>,
    what: &str,
) -> PyResult<KnotVector<f64>> {
    KnotVector::new(degree, slice(knots, what)?.to_vec()).py()
}

/// Points of type `P` from a flat row-major array of `P::DIM` columns (an incomplete last
/// row is left out: callers check the length where it matters).
pub(crate) fn points<P: ControlPoint<f64>>(flat: &[f64]) -> Vec<P> {
    flat.chunks_exact(P::DIM)
        .map(|row| P::from_coords(|i| row[i]))
        .collect()
}

/// The coordinates of points, row after row.
pub(crate) fn flatten<P: ControlPoint<f64>>(points: &[P]) -> Vec<f64> {
    let mut out = Vec::with_capacity(points.len() * P::DIM);
    for p in points {
        out.extend((0..P::DIM).map(|i| p.coord(i)));
    }
    out
}

/// A flat vector as a 1-D numpy array (no copy).
pub(crate) fn array(py: Python<'_>, values: Vec<f64>) -> Bound<'_, PyArray1<f64>> {
    PyArray1::from_vec(py, values)
}

/// A sparse matrix in CSR form for `scipy.sparse.csr_array((data, indices, indptr), shape)`.
pub(crate) type Csr<'py> = (
    Bound<'py, PyArray1<f64>>,
    Vec<usize>,
    Vec<usize>,
    (usize, usize),
);

/// Inflections, curvature extrema and the constant curvature of a planar curve.
pub(crate) type Features<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Option<f64>,
);

/// A planar curve's features as `(inflections, curvature_extrema, constant_curvature)`.
pub(crate) fn features(py: Python<'_>, f: PlanarFeatures<f64>) -> Features<'_> {
    (
        array(py, f.inflections),
        array(py, f.curvature_extrema),
        f.constant_curvature,
    )
}

/// A library CSR matrix as the parts of a `scipy.sparse.csr_array`.
pub(crate) fn csr<'py>(py: Python<'py>, m: &CsrMatrix<f64>) -> Csr<'py> {
    let (indptr, indices, data) = m.csr_data();
    (
        array(py, data.to_vec()),
        indices.to_vec(),
        indptr.to_vec(),
        (m.nrows(), m.ncols()),
    )
}
