//! `spline._core.NurbsCurve` (planar or spatial) and `spline._core.NurbsSurface` (spatial),
//! with the constructions: circles and arcs, spheres and tori.

use crate::curve::curve_record;
use crate::{Features, IntoPy, array, bad_input, flatten, knot_vector, slice};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use spline::algebra::{default_feature_accuracy, planar_features};
use spline::geom::{CircleConstruction, Frame};
use spline::io::exchange::{CurveRecord, SurfaceRecord};
use spline::nalgebra::{SVector, Vector2, Vector3};
use spline::{NurbsCurve, NurbsSurface};

/// A NURBS curve of dimension 2 or 3.
#[derive(Clone, Debug)]
enum Rational {
    /// Planar.
    N2(NurbsCurve<f64, 2>),
    /// Spatial.
    N3(NurbsCurve<f64, 3>),
}

/// Runs `$e` on the curve inside whichever variant.
macro_rules! with {
    ($d:expr, $c:ident => $e:expr) => {
        match $d {
            Rational::N2($c) => $e,
            Rational::N3($c) => $e,
        }
    };
}

/// Points of dimension `D` from a flat array.
fn points<const D: usize>(flat: &[f64]) -> PyResult<Vec<SVector<f64, D>>> {
    if flat.len() % D != 0 {
        return Err(bad_input(format!(
            "{} coordinates do not make points of dimension {D}",
            flat.len()
        )));
    }
    Ok(crate::points(flat))
}

/// A NURBS curve (`spline.NurbsCurve` wraps it).
#[pyclass(frozen, module = "spline._core")]
pub(crate) struct NurbsCurveCore(Rational);

#[pymethods]
impl NurbsCurveCore {
    /// A NURBS curve from its degree, knots, Cartesian control points (flat, `dim` = 2 or 3
    /// columns) and weights.
    #[new]
    fn new(
        degree: usize,
        knots: PyReadonlyArray1<'_, f64>,
        points: PyReadonlyArray1<'_, f64>,
        weights: PyReadonlyArray1<'_, f64>,
        dim: usize,
    ) -> PyResult<Self> {
        let knots = knot_vector(degree, &knots, "t")?;
        let flat = slice(&points, "c")?;
        let weights = slice(&weights, "w")?.to_vec();
        Ok(Self(match dim {
            2 => Rational::N2(NurbsCurve::new(knots, self::points(flat)?, weights).py()?),
            3 => Rational::N3(NurbsCurve::new(knots, self::points(flat)?, weights).py()?),
            d => {
                return Err(bad_input(format!(
                    "NURBS curves of dimension {d}: 2 or 3 are supported"
                )));
            }
        }))
    }

    /// The full circle of radius `radius` about `center` (2 or 3 coordinates; in space, in
    /// the plane normal to `normal`), nine control points on a square or seven on a triangle.
    #[staticmethod]
    #[pyo3(signature = (center, radius, normal=None, triangle=false))]
    fn circle(
        center: Vec<f64>,
        radius: f64,
        normal: Option<Vec<f64>>,
        triangle: bool,
    ) -> PyResult<Self> {
        let how = if triangle {
            CircleConstruction::Triangle
        } else {
            CircleConstruction::Square
        };
        Self::conic(center, normal, |f2, f3| match (f2, f3) {
            (Some(f), _) => NurbsCurve::circle(f, radius, how).map(Rational::N2),
            (_, Some(f)) => NurbsCurve::circle(f, radius, how).map(Rational::N3),
            _ => unreachable!("one frame is given"),
        })
    }

    /// The arc of radius `radius` about `center` from angle `start` sweeping `sweep`
    /// (radians; negative: clockwise), of rational quadratic pieces of at most 90°.
    #[staticmethod]
    #[pyo3(signature = (center, radius, start, sweep, normal=None))]
    fn arc(
        center: Vec<f64>,
        radius: f64,
        start: f64,
        sweep: f64,
        normal: Option<Vec<f64>>,
    ) -> PyResult<Self> {
        Self::conic(center, normal, |f2, f3| match (f2, f3) {
            (Some(f), _) => NurbsCurve::arc(f, radius, start, sweep).map(Rational::N2),
            (_, Some(f)) => NurbsCurve::arc(f, radius, start, sweep).map(Rational::N3),
            _ => unreachable!("one frame is given"),
        })
    }

    /// The degree.
    #[getter]
    fn degree(&self) -> usize {
        with!(&self.0, c => c.degree())
    }

    /// The dimension of the control points.
    #[getter]
    fn dim(&self) -> usize {
        match self.0 {
            Rational::N2(_) => 2,
            Rational::N3(_) => 3,
        }
    }

    /// The knots.
    fn knots<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, with!(&self.0, c => c.knots().knots().to_vec()))
    }

    /// The Cartesian control points, flat.
    fn control_points<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, with!(&self.0, c => flatten(c.control_points())))
    }

    /// The weights.
    fn weights<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, with!(&self.0, c => c.weights().to_vec()))
    }

    /// The `nu`-th derivative at every parameter of `x`, flat (GIL released): points by the
    /// library's batch, derivatives by its evaluator (the curve's cached piecewise form).
    fn eval<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        nu: usize,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let x = slice(&x, "x")?;
        let out = py
            .detach(|| -> spline::Result<Vec<f64>> {
                with!(&self.0, c => {
                    if nu == 0 {
                        Ok(flatten(&c.eval_many(x)?))
                    } else {
                        // The library has no batch of rational derivatives: one evaluator
                        // call per point, into one buffer (order ν needs the lower orders
                        // anyway, The NURBS Book A4.2).
                        spline::core::check_derivative_order(nu)?;
                        let evaluator = c.evaluator();
                        let mut d = vec![SVector::zeros(); nu + 1];
                        let mut out = Vec::with_capacity(x.len() * self.dim());
                        for &u in x {
                            evaluator.derivatives_into(u, &mut d)?;
                            out.extend(d[nu].iter());
                        }
                        Ok(out)
                    }
                })
            })
            .py()?;
        Ok(array(py, out))
    }

    /// The same curve with the knot `u` inserted `m` times.
    fn insert_knot(&self, u: f64, m: usize) -> PyResult<Self> {
        Ok(Self(match &self.0 {
            Rational::N2(c) => Rational::N2(c.insert_knot(u, m).py()?),
            Rational::N3(c) => Rational::N3(c.insert_knot(u, m).py()?),
        }))
    }

    /// The same curve with its degree raised by `times`.
    fn elevate_degree(&self, times: usize) -> PyResult<Self> {
        Ok(Self(match &self.0 {
            Rational::N2(c) => Rational::N2(c.elevate_degree(times).py()?),
            Rational::N3(c) => Rational::N3(c.elevate_degree(times).py()?),
        }))
    }

    /// Inflections and curvature extrema of a planar curve (as `Curve.features`).
    #[pyo3(signature = (accuracy=None))]
    fn features<'py>(&self, py: Python<'py>, accuracy: Option<f64>) -> PyResult<Features<'py>> {
        let Rational::N2(c) = &self.0 else {
            return Err(bad_input("features need a planar curve"));
        };
        let accuracy = accuracy.unwrap_or_else(|| default_feature_accuracy(c.domain()));
        let f = py.detach(|| planar_features(c, accuracy)).py()?;
        Ok(crate::features(py, f))
    }

    /// The curve in the exchange format (JSON text).
    fn to_json(&self) -> String {
        let record = with!(&self.0, c => CurveRecord::from_nurbs(c));
        record.to_json()
    }

    /// A NURBS curve from exchange-format JSON (unit weights when it has none).
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        let record = curve_record(text)?;
        Ok(Self(match record.dimension().py()? {
            2 => Rational::N2(record.to_nurbs().py()?),
            3 => Rational::N3(record.to_nurbs().py()?),
            d => {
                return Err(bad_input(format!(
                    "NURBS curves of dimension {d}: 2 or 3 are supported"
                )));
            }
        }))
    }
}

/// A frame for a construction.
type Frames = (Option<Frame<f64, 2>>, Option<Frame<f64, 3>>);

impl NurbsCurveCore {
    /// Builds a conic in the frame at `center` (planar, or normal to `normal` in space).
    fn conic(
        center: Vec<f64>,
        normal: Option<Vec<f64>>,
        build: impl FnOnce(Option<&Frame<f64, 2>>, Option<&Frame<f64, 3>>) -> spline::Result<Rational>,
    ) -> PyResult<Self> {
        let frames: Frames = match (center.as_slice(), normal.as_deref()) {
            ([x, y], None) => (Some(Frame::planar(Vector2::new(*x, *y))), None),
            ([x, y, z], normal) => {
                let n = match normal {
                    None => Vector3::z(),
                    Some([a, b, c]) => Vector3::new(*a, *b, *c),
                    Some(_) => return Err(bad_input("normal: expected 3 coordinates")),
                };
                let frame = Frame::with_normal(Vector3::new(*x, *y, *z), n).py()?;
                (None, Some(frame))
            }
            _ => {
                return Err(bad_input(
                    "center: expected 2 coordinates (planar) or 3 (in space, with a normal)",
                ));
            }
        };
        build(frames.0.as_ref(), frames.1.as_ref()).py().map(Self)
    }
}

/// A NURBS surface in space (`spline.NurbsSurface` wraps it).
#[pyclass(frozen, module = "spline._core")]
pub(crate) struct NurbsSurfaceCore(NurbsSurface<f64, 3>);

#[pymethods]
impl NurbsSurfaceCore {
    /// A NURBS surface from degrees, knots, the net (flat, row-major `(n_u, n_v, 3)`) and the
    /// weights (flat `(n_u, n_v)`).
    #[new]
    fn new(
        degrees: (usize, usize),
        knots_u: PyReadonlyArray1<'_, f64>,
        knots_v: PyReadonlyArray1<'_, f64>,
        points: PyReadonlyArray1<'_, f64>,
        weights: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Self> {
        let ku = knot_vector(degrees.0, &knots_u, "tu")?;
        let kv = knot_vector(degrees.1, &knots_v, "tv")?;
        let p = self::points::<3>(slice(&points, "points")?)?;
        let w = slice(&weights, "weights")?.to_vec();
        NurbsSurface::new(ku, kv, p, w).py().map(Self)
    }

    /// The sphere of radius `radius` about `center`.
    #[staticmethod]
    fn sphere(center: [f64; 3], radius: f64) -> PyResult<Self> {
        NurbsSurface::sphere(Vector3::from(center), radius)
            .py()
            .map(Self)
    }

    /// The torus about the axis through `center` along `axis`, radii `major > minor > 0`.
    #[staticmethod]
    fn torus(center: [f64; 3], axis: [f64; 3], major: f64, minor: f64) -> PyResult<Self> {
        NurbsSurface::torus(Vector3::from(center), Vector3::from(axis), major, minor)
            .py()
            .map(Self)
    }

    /// The degrees `(p, q)`.
    #[getter]
    fn degrees(&self) -> (usize, usize) {
        self.0.degrees()
    }

    /// The net size `(n_u, n_v)`.
    #[getter]
    fn net_size(&self) -> (usize, usize) {
        self.0.net_size()
    }

    /// The knots in `u` and `v`.
    fn knots<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>) {
        (
            array(py, self.0.knots_u().knots().to_vec()),
            array(py, self.0.knots_v().knots().to_vec()),
        )
    }

    /// The points at the parameter pairs `(u[i], v[i])`, flat (GIL released), by the
    /// library's evaluator (the surface's cached piecewise form).
    fn eval<'py>(
        &self,
        py: Python<'py>,
        u: PyReadonlyArray1<'py, f64>,
        v: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (u, v) = (slice(&u, "u")?, slice(&v, "v")?);
        if u.len() != v.len() {
            return Err(bad_input(format!(
                "u and v differ in length ({} and {})",
                u.len(),
                v.len()
            )));
        }
        let out = py
            .detach(|| -> spline::Result<Vec<f64>> {
                // The library batches surfaces on grids only (`eval_grid`): scattered pairs
                // are one evaluator call each.
                let evaluator = self.0.evaluator();
                let mut out = Vec::with_capacity(3 * u.len());
                for (&a, &b) in u.iter().zip(v) {
                    out.extend(evaluator.eval(a, b)?.iter());
                }
                Ok(out)
            })
            .py()?;
        Ok(array(py, out))
    }

    /// The surface in the exchange format (JSON text).
    fn to_json(&self) -> String {
        SurfaceRecord::from_nurbs_surface(&self.0).to_json()
    }

    /// A NURBS surface from exchange-format JSON (unit weights when it has none).
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        let record = SurfaceRecord::from_json(text)
            .map_err(|e| bad_input(format!("not an exchange-format surface: {e}")))?;
        record.to_nurbs_surface().py().map(Self)
    }
}

/// Registers the classes.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NurbsCurveCore>()?;
    m.add_class::<NurbsSurfaceCore>()?;
    Ok(())
}
