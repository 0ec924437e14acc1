//! `spline._core.Curve`: a B-spline with scalar or vector coefficients of dimension 1 to 4,
//! the library's `BSpline<f64, P>` behind one Python class.

use crate::{Csr, Features, IntoPy, array, bad_input, csr, flatten, knot_vector, points, slice};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use spline::algebra::{
    SplineMap, default_feature_accuracy, planar_features, product_with_jacobians,
};
use spline::io::exchange::CurveRecord;
use spline::nalgebra::SVector;
use spline::{BSpline, ControlPoint, KnotVector};

/// The largest dimension of vector coefficients (each dimension is its own monomorphised
/// evaluation loop, as fast as the Rust batch).
pub(crate) const MAX_DIM: usize = 4;

/// Parameters evaluated per chunk: the points of a chunk stay in cache between the library's
/// batch evaluation and the copy into the flat output.
const CHUNK: usize = 16_384;

type B<P> = BSpline<f64, P>;

/// A B-spline whose coefficient type is chosen at run time.
#[derive(Clone, Debug)]
pub(crate) enum Dyn {
    /// Scalar coefficients (numpy shape `(n,)`).
    S(B<f64>),
    /// Vector coefficients of dimension 1 (shape `(n, 1)`).
    V1(B<SVector<f64, 1>>),
    /// Dimension 2.
    V2(B<SVector<f64, 2>>),
    /// Dimension 3.
    V3(B<SVector<f64, 3>>),
    /// Dimension 4.
    V4(B<SVector<f64, 4>>),
}

/// `Dyn::from`: a B-spline in its variant.
macro_rules! variants {
    ($($P:ty => $V:ident),+) => {
        $(impl From<B<$P>> for Dyn {
            fn from(curve: B<$P>) -> Self {
                Dyn::$V(curve)
            }
        })+
    };
}

variants!(
    f64 => S,
    SVector<f64, 1> => V1,
    SVector<f64, 2> => V2,
    SVector<f64, 3> => V3,
    SVector<f64, 4> => V4
);

/// Runs `$e` with `$P` the coefficient type of dimension `$dim` (`0`: scalar) and wraps the
/// resulting B-spline in the matching [`Dyn`] variant; another dimension `$d` gives `$other`.
macro_rules! dyn_by_dim {
    ($dim:expr, $P:ident => $e:expr, $d:pat => $other:expr) => {
        by_dim!($dim, $P => $e.map(Dyn::from), [1, 2, 3, 4], $d => $other)
    };
}
pub(crate) use dyn_by_dim;

/// Runs `$e` on the curve inside whichever variant.
macro_rules! with {
    ($d:expr, $c:ident => $e:expr) => {
        match $d {
            Dyn::S($c) => $e,
            Dyn::V1($c) => $e,
            Dyn::V2($c) => $e,
            Dyn::V3($c) => $e,
            Dyn::V4($c) => $e,
        }
    };
}

/// Maps the curve to a curve of the same variant.
macro_rules! map {
    ($d:expr, $c:ident => $e:expr) => {
        match $d {
            Dyn::S($c) => Dyn::S($e),
            Dyn::V1($c) => Dyn::V1($e),
            Dyn::V2($c) => Dyn::V2($e),
            Dyn::V3($c) => Dyn::V3($e),
            Dyn::V4($c) => Dyn::V4($e),
        }
    };
}

/// Batch evaluation (the library's `eval_many_into`) into a flat vector, chunk by chunk.
fn eval_flat<P: ControlPoint<f64>>(curve: &B<P>, x: &[f64]) -> spline::Result<Vec<f64>> {
    let mut out = Vec::with_capacity(x.len() * P::DIM);
    let mut buffer = vec![P::origin(); CHUNK.min(x.len())];
    for chunk in x.chunks(CHUNK) {
        let buffer = &mut buffer[..chunk.len()];
        curve.eval_many_into(chunk, buffer)?;
        for p in buffer.iter() {
            out.extend((0..P::DIM).map(|i| p.coord(i)));
        }
    }
    Ok(out)
}

impl Dyn {
    /// A curve from knots and a flat coefficient array of `dim` columns (`0`: scalar).
    pub(crate) fn new(knots: KnotVector<f64>, flat: &[f64], dim: usize) -> spline::Result<Self> {
        if dim > 0 && flat.len() % dim != 0 {
            return Err(spline::Error::new(
                spline::ErrorKind::DimensionMismatch,
                format!("{} coefficients do not make rows of {dim}", flat.len()),
            ));
        }
        dyn_by_dim!(dim, P => B::<P>::new(knots, points(flat)), _ => Err(spline::Error::new(
            spline::ErrorKind::DimensionMismatch,
            format!("coefficients of dimension {dim}: 1 to {MAX_DIM} are supported"),
        )))
    }

    /// `0` for scalar coefficients, otherwise the dimension of the points.
    pub(crate) fn dim(&self) -> usize {
        match self {
            Dyn::S(_) => 0,
            Dyn::V1(_) => 1,
            Dyn::V2(_) => 2,
            Dyn::V3(_) => 3,
            Dyn::V4(_) => 4,
        }
    }

    pub(crate) fn knots(&self) -> &KnotVector<f64> {
        with!(self, c => c.knots())
    }

    fn flat(&self) -> Vec<f64> {
        with!(self, c => flatten(c.control_points()))
    }

    /// The `nu`-th derivative at every parameter, flat: the library's batch on the curve or,
    /// for `nu > 0`, on its derivative curve (one value per point, through that curve's
    /// cached piecewise form; `derivatives_many_into` would compute every order up to `nu`).
    fn eval(&self, x: &[f64], nu: usize) -> spline::Result<Vec<f64>> {
        if nu == 0 {
            with!(self, c => eval_flat(c, x))
        } else {
            with!(self, c => eval_flat(&c.derivative(nu)?, x))
        }
    }

    fn record(&self) -> CurveRecord {
        with!(self, c => CurveRecord::from_bspline(c))
    }
}

/// A curve record from exchange-format JSON text (a bad-input error naming what it is not).
pub(crate) fn curve_record(text: &str) -> PyResult<CurveRecord> {
    CurveRecord::from_json(text)
        .map_err(|e| bad_input(format!("not an exchange-format curve: {e}")))
}

/// A B-spline curve or function (`spline.BSpline` wraps it; see there).
#[pyclass(frozen, module = "spline._core")]
pub(crate) struct Curve(pub(crate) Dyn);

#[pymethods]
impl Curve {
    /// A B-spline of degree `degree` on `knots` with coefficients `coefficients` (flat, row
    /// after row, `dim` columns; `dim = 0` for scalar coefficients).
    #[new]
    fn new(
        degree: usize,
        knots: PyReadonlyArray1<'_, f64>,
        coefficients: PyReadonlyArray1<'_, f64>,
        dim: usize,
    ) -> PyResult<Self> {
        let knots = knot_vector(degree, &knots, "t")?;
        Dyn::new(knots, slice(&coefficients, "c")?, dim)
            .py()
            .map(Self)
    }

    /// The degree.
    #[getter]
    fn degree(&self) -> usize {
        self.0.knots().degree()
    }

    /// `0` for scalar coefficients, otherwise the dimension of the control points.
    #[getter]
    fn dim(&self) -> usize {
        self.0.dim()
    }

    /// The knots (a copy).
    fn knots<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.0.knots().knots().to_vec())
    }

    /// The coefficients, flat (a copy).
    fn coefficients<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.0.flat())
    }

    /// The base interval `(t[k], t[n])`.
    fn domain(&self) -> (f64, f64) {
        self.0.knots().domain()
    }

    /// The `nu`-th derivative at every parameter of `x`, flat (GIL released).
    fn eval<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        nu: usize,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let x = slice(&x, "x")?;
        let out = py.detach(|| self.0.eval(x, nu)).py()?;
        Ok(array(py, out))
    }

    /// The derivative of order `nu` as a B-spline of degree `k − nu`.
    fn derivative(&self, nu: usize) -> PyResult<Self> {
        Ok(Self(map!(&self.0, c => c.derivative(nu).py()?)))
    }

    /// The same curve with the knot `u` inserted `m` times.
    fn insert_knot(&self, u: f64, m: usize) -> PyResult<Self> {
        Ok(Self(map!(&self.0, c => c.insert_knot(u, m).py()?)))
    }

    /// The same curve with every knot of `new_knots` inserted.
    fn refine(&self, new_knots: PyReadonlyArray1<'_, f64>) -> PyResult<Self> {
        let new_knots = slice(&new_knots, "knots")?;
        Ok(Self(map!(&self.0, c => c.refine(new_knots).py()?)))
    }

    /// The same curve with its degree raised by `times`.
    fn elevate_degree(&self, py: Python<'_>, times: usize) -> PyResult<Self> {
        py.detach(|| Ok(map!(&self.0, c => c.elevate_degree(times)?)))
            .py()
            .map(Self)
    }

    /// The coefficient map of knot insertion (CSR parts): new coefficients = M · old.
    fn insertion_map<'py>(&self, py: Python<'py>, u: f64, m: usize) -> PyResult<Csr<'py>> {
        let map = SplineMap::insertion(self.0.knots(), u, m).py()?;
        Ok(csr(py, map.matrix()))
    }

    /// The coefficient map of refinement by `new_knots`.
    fn refinement_map<'py>(
        &self,
        py: Python<'py>,
        new_knots: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Csr<'py>> {
        let map = SplineMap::refinement(self.0.knots(), slice(&new_knots, "knots")?).py()?;
        Ok(csr(py, map.matrix()))
    }

    /// The coefficient map of degree elevation by `times`.
    fn elevation_map<'py>(&self, py: Python<'py>, times: usize) -> PyResult<Csr<'py>> {
        let map = py
            .detach(|| SplineMap::elevation(self.0.knots(), times))
            .py()?;
        Ok(csr(py, map.matrix()))
    }

    /// The coefficient map of the derivative of order `nu`.
    fn derivative_map<'py>(&self, py: Python<'py>, nu: usize) -> PyResult<Csr<'py>> {
        let map = SplineMap::derivative(self.0.knots(), nu).py()?;
        Ok(csr(py, map.matrix()))
    }

    /// The curve in the exchange format (JSON text).
    fn to_json(&self) -> String {
        self.0.record().to_json()
    }

    /// A curve from exchange-format JSON text (`weights` are refused: use `NurbsCurve`).
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        let record = curve_record(text)?;
        if record.weights.is_some() {
            return Err(bad_input(
                "the curve has weights: read it with NurbsCurve.from_json",
            ));
        }
        // A scalar function is a curve of dimension 1 in the exchange format.
        let dim = match record.dimension().py()? {
            1 => 0,
            d => d,
        };
        let flat: Vec<f64> = record.control_points.concat();
        Dyn::new(record.knot_vector().py()?, &flat, dim)
            .py()
            .map(Self)
    }

    /// Inflections and curvature extrema of a planar curve, located to `accuracy` (absolute,
    /// in the parameter; by default the library's, relative to the domain):
    /// `(inflections, curvature_extrema, constant_curvature)`.
    #[pyo3(signature = (accuracy=None))]
    fn features<'py>(&self, py: Python<'py>, accuracy: Option<f64>) -> PyResult<Features<'py>> {
        let Dyn::V2(c) = &self.0 else {
            return Err(bad_input(
                "features need a planar curve (coefficients of shape (n, 2))",
            ));
        };
        let accuracy = accuracy.unwrap_or_else(|| default_feature_accuracy(c.domain()));
        let f = py.detach(|| planar_features(c, accuracy)).py()?;
        Ok(crate::features(py, f))
    }

    /// The signed curvature of a planar curve at every parameter of `x`.
    fn curvature<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let Dyn::V2(c) = &self.0 else {
            return Err(bad_input(
                "curvature needs a planar curve (coefficients of shape (n, 2))",
            ));
        };
        let x = slice(&x, "x")?;
        // The library has no batch of curvatures: one call per point.
        let out = py
            .detach(|| {
                x.iter()
                    .map(|&u| c.signed_curvature(u))
                    .collect::<spline::Result<Vec<f64>>>()
            })
            .py()?;
        Ok(array(py, out))
    }
}

/// The product of two B-spline functions with the Jacobians of its coefficients with
/// respect to those of each factor: `(product, J_a, J_b)` (CSR parts).
#[pyfunction]
fn product<'py>(py: Python<'py>, a: &Curve, b: &Curve) -> PyResult<(Curve, Csr<'py>, Csr<'py>)> {
    let (Dyn::S(a), Dyn::S(b)) = (&a.0, &b.0) else {
        return Err(bad_input(
            "product: both factors must be B-spline functions (coefficients of shape (n,))",
        ));
    };
    let p = py.detach(|| product_with_jacobians(a, b)).py()?;
    Ok((
        Curve(Dyn::S(p.product)),
        csr(py, &p.jacobian_a),
        csr(py, &p.jacobian_b),
    ))
}

/// Registers the class and functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Curve>()?;
    m.add_function(wrap_pyfunction!(product, m)?)?;
    Ok(())
}
