//! `spline._core.NdColumns`: the library's `NdSpline` (scipy's `NdBSpline`: a tensor product
//! in any number of dimensions with any number of value columns). `spline.NdBSpline`
//! (`python/spline/_nd.py`) validates the arguments with scipy's words and reshapes.

use crate::{Csr, IntoPy, array, csr, slice};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use spline::geom::{NdSpline, knot_vectors};

/// A tensor-product spline with `columns` value columns (see `spline.NdBSpline`).
#[pyclass(frozen, module = "spline._core")]
pub(crate) struct NdColumns(pub(crate) NdSpline);

#[pymethods]
impl NdColumns {
    /// A spline from one knot vector and degree per dimension and the coefficients flat,
    /// row-major of shape `n_1 × … × n_d × columns`.
    #[new]
    fn new(
        t: Vec<Vec<f64>>,
        c: PyReadonlyArray1<'_, f64>,
        k: Vec<usize>,
        columns: usize,
        extrapolate: bool,
    ) -> PyResult<Self> {
        NdSpline::new(t, slice(&c, "c")?.to_vec(), &k, columns, extrapolate)
            .py()
            .map(Self)
    }

    /// The partial derivative of orders `nu` (one per dimension, empty for values) of every
    /// column at the points `xi` (flat, `N × d`): flat `N × columns`, NaN rows outside the
    /// domain without `extrapolate`. The GIL is released.
    fn eval<'py>(
        &self,
        py: Python<'py>,
        xi: PyReadonlyArray1<'py, f64>,
        nu: Vec<usize>,
        extrapolate: bool,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let xi = slice(&xi, "xi")?;
        let d = self.0.ndim();
        let npts = xi.len() / d.max(1);
        let mut out = vec![0.0; npts * self.0.columns()];
        py.detach(|| self.0.eval_into(xi, &nu, extrapolate, &mut out))
            .py()?;
        Ok(array(py, out))
    }

    /// The partial derivative of orders `nu` as a spline.
    fn derivative(&self, nu: Vec<usize>) -> PyResult<Self> {
        self.0.derivative(&nu).py().map(Self)
    }

    /// The knot vectors (copies).
    fn knots(&self) -> Vec<Vec<f64>> {
        self.0
            .knot_vectors()
            .iter()
            .map(|k| k.knots().to_vec())
            .collect()
    }

    /// The degrees.
    fn degrees(&self) -> Vec<usize> {
        self.0.degrees()
    }

    /// The coefficients, flat (a copy).
    fn coefficients<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.0.coefficients().to_vec())
    }
}

/// The tensor-product design matrix at the points `xi` (flat, `N × d`) as CSR parts.
#[pyfunction]
fn nd_design_matrix<'py>(
    py: Python<'py>,
    xi: PyReadonlyArray1<'py, f64>,
    t: Vec<Vec<f64>>,
    k: Vec<usize>,
    extrapolate: bool,
) -> PyResult<Csr<'py>> {
    let xi = slice(&xi, "xi")?;
    let knots = knot_vectors(t, &k).py()?;
    let m = py
        .detach(|| NdSpline::design_matrix(xi, &knots, extrapolate))
        .py()?;
    Ok(csr(py, &m))
}

/// Registers the class and functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NdColumns>()?;
    m.add_function(wrap_pyfunction!(nd_design_matrix, m)?)?;
    Ok(())
}
