//! `spline._core.Columns`: the library's `ColumnSpline` (a spline with any number of
//! coefficient columns on one knot vector, scipy's `BSpline` semantics) behind one Python
//! class. `spline.BSpline` (`python/spline/_bspline.py`) does the array plumbing: axis
//! moves, trailing dimensions flattened to columns, complex values as two real columns.

use crate::{Csr, IntoPy, array, bad_input, csr, slice};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use spline::geom::{ColumnSpline, Extrapolate, PowerBasisKnots};

/// Output values from which an evaluation runs on every core (below, threads cost more than
/// they save).
const PARALLEL_MIN_VALUES: usize = 1 << 16;

/// scipy's `extrapolate` argument by name: `"on"`, `"off"` or `"periodic"`.
fn mode(name: &str) -> PyResult<Extrapolate> {
    Extrapolate::from_name(name).py()
}

/// A spline with `columns` coefficient columns (see `spline.BSpline`).
#[pyclass(frozen, module = "spline._core")]
pub(crate) struct Columns(pub(crate) ColumnSpline);

#[pymethods]
impl Columns {
    /// A spline of degree `k` on the knots `t` with row-major coefficients `c` (flat, `rows ×
    /// columns`, at least `len(t) − k − 1` rows).
    #[new]
    fn new(
        t: PyReadonlyArray1<'_, f64>,
        c: PyReadonlyArray1<'_, f64>,
        k: usize,
        columns: usize,
    ) -> PyResult<Self> {
        ColumnSpline::new(
            slice(&t, "t")?.to_vec(),
            slice(&c, "c")?.to_vec(),
            k,
            columns,
        )
        .py()
        .map(Self)
    }

    /// The number of coefficient columns.
    #[getter]
    fn columns(&self) -> usize {
        self.0.columns()
    }

    /// The `nu`-th derivative of every column at every point of `x`, flat and row-major
    /// (`len(x) × columns`); `mode` is `"on"`, `"off"` (NaN rows outside the base interval)
    /// or `"periodic"`. The GIL is released.
    fn eval<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        nu: usize,
        mode: &str,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let mode = self::mode(mode)?;
        let x = slice(&x, "x")?;
        let columns = self.0.columns();
        let out = py
            .detach(|| {
                let mut out = vec![0.0; x.len().saturating_mul(columns)];
                // Large batches on every core (the same values bit for bit).
                if out.len() >= PARALLEL_MIN_VALUES {
                    self.0.par_eval_into(x, nu, mode, &mut out)?;
                } else {
                    self.0.eval_into(x, nu, mode, &mut out)?;
                }
                Ok::<_, spline::core::Error>(out)
            })
            .py()?;
        Ok(array(py, out))
    }

    /// The degree.
    #[getter]
    fn degree(&self) -> usize {
        self.0.degree()
    }

    /// The knots (a copy).
    fn knots<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.0.knots().to_vec())
    }

    /// The coefficients, flat and row-major (a copy).
    fn coefficients<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.0.coefficients().to_vec())
    }

    /// The derivative of order `nu` (scipy's knots and zero padding).
    fn derivative(&self, nu: usize) -> PyResult<Self> {
        self.0.derivative(nu).py().map(Self)
    }

    /// The antiderivative of order `nu`.
    fn antiderivative(&self, nu: usize) -> PyResult<Self> {
        self.0.antiderivative(nu).py().map(Self)
    }

    /// The integral of every column over `[a, b]` under `mode` (see `eval`).
    fn integrate<'py>(
        &self,
        py: Python<'py>,
        a: f64,
        b: f64,
        mode: &str,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let mode = self::mode(mode)?;
        Ok(array(py, self.0.integrate(a, b, mode).py()?))
    }

    /// The spline with the knot `x` inserted `m` times (`periodic`: FITPACK's periodic rules).
    fn insert_knot(&self, x: f64, m: usize, periodic: bool) -> PyResult<Self> {
        self.0.insert_knot(x, m, periodic).py().map(Self)
    }

    /// The B-spline of a piecewise polynomial (scipy's `from_power_basis`): breakpoints `x`,
    /// power coefficients `c` flat of shape `(k + 1) × (len(x) − 1) × columns`, knots by
    /// `bc_type` (`"not-a-knot"`, `"natural"`, `"clamped"`, `"periodic"`).
    #[staticmethod]
    fn from_power_basis(
        x: PyReadonlyArray1<'_, f64>,
        c: PyReadonlyArray1<'_, f64>,
        order: usize,
        columns: usize,
        bc_type: &str,
    ) -> PyResult<Self> {
        let bc = match bc_type {
            "not-a-knot" => PowerBasisKnots::NotAKnot,
            "natural" | "clamped" => PowerBasisKnots::Augmented,
            "periodic" => PowerBasisKnots::Periodic,
            other => return Err(bad_input(format!("Unknown boundary condition: {other}"))),
        };
        ColumnSpline::from_power_basis(slice(&x, "x")?, slice(&c, "c")?, order, columns, bc)
            .py()
            .map(Self)
    }

    /// The basis element on the knots `t` (degree `len(t) − 2`).
    #[staticmethod]
    fn basis_element(t: PyReadonlyArray1<'_, f64>) -> PyResult<Self> {
        ColumnSpline::basis_element(slice(&t, "t")?).py().map(Self)
    }
}

/// The collocation matrix `B_j(x_i)` of degree `k` on the knots `t` (CSR parts); `mode` as
/// in `Columns.eval` (`"off"`: points outside the base interval are an error).
#[pyfunction]
fn design_matrix<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    t: PyReadonlyArray1<'py, f64>,
    k: usize,
    mode: &str,
) -> PyResult<Csr<'py>> {
    let mode = self::mode(mode)?;
    let (x, t) = (slice(&x, "x")?, slice(&t, "t")?);
    let m = py
        .detach(|| ColumnSpline::design_matrix(x, t, k, mode))
        .py()?;
    Ok(csr(py, &m))
}

/// Registers the class and functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Columns>()?;
    m.add_function(wrap_pyfunction!(design_matrix, m)?)?;
    Ok(())
}
