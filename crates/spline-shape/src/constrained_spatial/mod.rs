//! Convexity of a parametric patch whose control points move in all three coordinates
//! (thesis ch. 7, as §5.6 does for functions): the closest patch
//! $S(u, v) = \sum_{ij} P_{ij} B_i(u) B_j(v)$ to points sampled on a grid of parameters
//! whose Gaussian curvature is nowhere negative and whose convex side faces one way.
//!
//! With every coordinate free, $L = S_{uu} \cdot (S_u \times S_v)$ (and `M`, `N`) is cubic
//! in the control points and the numerator $LN - M^2$ of `K` is a polynomial of degree 6 in
//! them. The constraints are again its per-patch Bernstein coefficients (non-negative:
//! `K ≥ 0` by the convex-hull property) and those of `L` (with the chosen sign, relative to
//! the normal $S_u \times S_v$), now non-linear. They are computed by a pipeline of sparse
//! linear and bilinear maps prepared once from the knot vectors (derivatives, then the
//! products of the tensor-product algebra: the same coefficients as
//! [`spline_algebra::curvature_numerators`]) and evaluated on any scalar: on `f64` for the
//! values, on vector dual numbers for the Jacobian (forward mode), and its hand-written
//! adjoint on vector dual numbers for the weighted sum of the constraints' Hessians that the
//! interior-point method needs (forward over reverse). Every derivative is exact: no finite
//! differences.
//!
//! The start is the convex patch of [`ParametricConvexity`]: the unconstrained fit's net
//! projected on its best plane gives the planar parametrisation, heights over it are fitted
//! under the same constraints (linear and quadratic there), and the result — convex, so
//! strictly inside — is where the full problem starts; phase I from the unconstrained fit
//! when that is not possible. Moving all three coordinates can only lower the objective
//! below that of the heights-only patch.

use crate::barrier::{BarrierOptions, BarrierProblem, BarrierReport, find_feasible_near, minimize};
use crate::constrained_parametric::ParametricConvexity;
use crate::problem::{LeastSquaresObjective, Sign};
use crate::problem::{check_convexity_degrees, check_grid};
use nalgebra::{DMatrix, DVector, SymmetricEigen, Vector2, Vector3};
use nalgebra_sparse::{CooMatrix, CsrMatrix};
use num_dual::DualSVec64;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::Surface;

mod numerators;
use numerators::NumeratorPipeline;

/// The most control points of a patch for [`SpatialConvexity`]: the Newton steps use dense
/// matrices of three unknowns per control point, and the Hessian takes one adjoint pass per
/// eight unknowns.
pub const MAX_SPATIAL_CONTROL_POINTS: usize = 100;

/// Unknowns differentiated at once by the vector dual numbers of the Jacobian and Hessian.
const LANES: usize = 8;
type Lanes = DualSVec64<LANES>;

/// The fitted patch of [`SpatialConvexity::fit_grid`].
#[derive(Clone, Debug)]
pub struct SpatialConvexFit {
    /// The patch, with `K ≥ 0` on its control points' conditions.
    pub surface: Surface<f64, Vector3<f64>>,
    /// The unconstrained least-squares patch.
    pub unconstrained: Surface<f64, Vector3<f64>>,
    /// $\tfrac12 \sum |S(u_a, v_b) - Q_{ab}|^2$.
    pub objective: f64,
    /// The same for the unconstrained patch.
    pub unconstrained_objective: f64,
    /// The same for the heights-only convex patch the solver started from, when that start
    /// was used (see the module documentation).
    pub heights_only_objective: Option<f64>,
    /// The solver's report.
    pub report: BarrierReport,
    /// `(rows of L, rows of LN − M²)`: the constraints.
    pub num_constraints: (usize, usize),
}

/// Fits a parametric patch with `K ≥ 0` and the sign of `L`, all three coordinates of its
/// control points free (see the module documentation).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_core::KnotVector;
/// use spline_shape::{Sign, SpatialConvexity};
/// // Points of a cap of the ellipsoid x²/4 + y²/4 + z² = 1 with ripples along z.
/// let knots = KnotVector::clamped(2, 0.0, 1.0, &[0.5])?;
/// let convex = SpatialConvexity::new(knots.clone(), knots, Sign::NonPositive)?;
/// let fit = convex.fit_function((9, 9), |u, v| {
///     let (x, y) = (1.2 * u - 0.6, 1.2 * v - 0.6);
///     Vector3::new(x, y, (1.0 - (x * x + y * y) / 4.0).sqrt() + 0.01 * (9.0 * x).sin())
/// })?;
/// assert!(fit.objective >= fit.unconstrained_objective);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct SpatialConvexity {
    knots: (KnotVector<f64>, KnotVector<f64>),
    sign: Sign,
    /// Settings of the interior-point method.
    pub options: BarrierOptions,
}

impl SpatialConvexity {
    /// Patches on the knot vectors `knots_u × knots_v` with `K ≥ 0` and `L` of sign `sign`
    /// relative to the normal $S_u \times S_v$ ([`Sign::NonNegative`]: the patch bends
    /// towards its normal).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] below degree 2 in a direction (no curvature to
    /// control) or for more than [`MAX_SPATIAL_CONTROL_POINTS`] control points.
    pub fn new(knots_u: KnotVector<f64>, knots_v: KnotVector<f64>, sign: Sign) -> Result<Self> {
        let (p, q) = (knots_u.degree(), knots_v.degree());
        check_convexity_degrees(p, q)?;
        let n = knots_u.num_basis() * knots_v.num_basis();
        if n > MAX_SPATIAL_CONTROL_POINTS {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "at most {MAX_SPATIAL_CONTROL_POINTS} control points for the convexity of a patch moving in space, got {n}"
                ),
            )
            .with_counts(MAX_SPATIAL_CONTROL_POINTS, n));
        }
        Ok(Self {
            knots: (knots_u, knots_v),
            sign,
            options: BarrierOptions::default(),
        })
    }

    /// Fits the points `points[a · vs.len() + b]` at `(us[a], vs[b])` under the constraints.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are `us.len() · vs.len()` points;
    /// [`ErrorKind::NonFinite`]; the errors of the least squares;
    /// [`ErrorKind::NoConvergence`] if no strictly feasible patch is found near the data or
    /// the barrier method does not converge.
    pub fn fit_grid(
        &self,
        us: &[f64],
        vs: &[f64],
        points: &[Vector3<f64>],
    ) -> Result<SpatialConvexFit> {
        let (mut problem, x_ls) = self.unconstrained(us, vs, points)?;
        let unconstrained_objective = problem.objective(&x_ls);
        let heights = self.heights_only_start(&problem, &x_ls, us, vs, points);
        let (start, heights_only_objective) = match heights {
            Some(x) => {
                let value = problem.objective(&x);
                (x, Some(value))
            }
            None => (x_ls.clone(), None),
        };
        problem.rescale(&start)?;
        let start = find_feasible_near(&problem, start, 1e-9, 1e-3, &self.options)
            .map_err(|e| e.context("no convex patch was found near the data"))?;
        let report = minimize(&problem, start, &self.options)?;
        Ok(SpatialConvexFit {
            surface: problem.patch(report.x.as_slice())?,
            unconstrained: problem.patch(x_ls.as_slice())?,
            objective: report.objective,
            unconstrained_objective,
            heights_only_objective,
            num_constraints: problem.rows,
            report,
        })
    }

    /// The problem [`SpatialConvexity::fit_grid`] solves, its constraints scaled at the
    /// unconstrained least-squares patch, and that patch's unknowns.
    ///
    /// # Errors
    /// As [`SpatialConvexity::fit_grid`].
    pub fn problem(
        &self,
        us: &[f64],
        vs: &[f64],
        points: &[Vector3<f64>],
    ) -> Result<(SpatialConvexProblem, DVector<f64>)> {
        let (mut problem, x_ls) = self.unconstrained(us, vs, points)?;
        problem.rescale(&x_ls)?;
        Ok((problem, x_ls))
    }

    /// Fits `f(u, v)` sampled on a uniform grid of `counts.0 × counts.1` parameters.
    ///
    /// # Errors
    /// [`ErrorKind::TooFewPoints`] for fewer than two samples in a direction; the errors of
    /// [`SpatialConvexity::fit_grid`].
    pub fn fit_function(
        &self,
        counts: (usize, usize),
        f: impl Fn(f64, f64) -> Vector3<f64>,
    ) -> Result<SpatialConvexFit> {
        let us = crate::constrained::uniform_samples(self.knots.0.domain(), counts.0)?;
        let vs = crate::constrained::uniform_samples(self.knots.1.domain(), counts.1)?;
        let points: Vec<Vector3<f64>> = us
            .iter()
            .flat_map(|&u| vs.iter().map(move |&v| (u, v)))
            .map(|(u, v)| f(u, v))
            .collect();
        self.fit_grid(&us, &vs, &points)
    }

    /// The problem (constraints not yet scaled) and the unconstrained least-squares patch.
    fn unconstrained(
        &self,
        us: &[f64],
        vs: &[f64],
        points: &[Vector3<f64>],
    ) -> Result<(SpatialConvexProblem, DVector<f64>)> {
        check_grid(
            us,
            vs,
            points.len(),
            |j| points[j].iter().all(|c| c.is_finite()),
            "point",
        )?;
        let knots = (&self.knots.0, &self.knots.1);
        let coordinate = |c: usize| -> Vec<f64> { points.iter().map(|p| p[c]).collect() };
        let lsq = [
            LeastSquaresObjective::grid(knots, us, vs, &coordinate(0))?,
            LeastSquaresObjective::grid(knots, us, vs, &coordinate(1))?,
            LeastSquaresObjective::grid(knots, us, vs, &coordinate(2))?,
        ];
        let n = lsq[0].dimension();
        let mut x_ls = DVector::zeros(3 * n);
        for (c, objective) in lsq.iter().enumerate() {
            x_ls.rows_mut(c * n, n).copy_from(&objective.solve()?);
        }
        let problem = SpatialConvexProblem::new(lsq, self.knots.clone(), self.sign)?;
        Ok((problem, x_ls))
    }

    /// The heights-only convex patch over the unconstrained fit's net projected on its best
    /// plane, as unknowns of the full problem, if it is strictly feasible there.
    fn heights_only_start(
        &self,
        problem: &SpatialConvexProblem,
        x_ls: &DVector<f64>,
        us: &[f64],
        vs: &[f64],
        points: &[Vector3<f64>],
    ) -> Option<DVector<f64>> {
        let n = problem.n;
        let net: Vec<Vector3<f64>> = (0..n)
            .map(|i| Vector3::new(x_ls[i], x_ls[n + i], x_ls[2 * n + i]))
            .collect();
        let frame = best_plane(&net);
        let local = |p: &Vector3<f64>| {
            let d = p - frame.origin;
            Vector3::new(
                d.dot(&frame.axes[0]),
                d.dot(&frame.axes[1]),
                d.dot(&frame.axes[2]),
            )
        };
        let base: Vec<Vector2<f64>> = net.iter().map(|p| local(p).xy()).collect();
        let base = Surface::new(self.knots.0.clone(), self.knots.1.clone(), base).ok()?;
        let mut heights = ParametricConvexity::new(base, self.sign).ok()?;
        heights.options = self.options.clone();
        let values: Vec<f64> = points.iter().map(|p| local(p).z).collect();
        let fit = heights.fit_grid(us, vs, &values).ok()?;
        let mut x = DVector::zeros(3 * n);
        for (i, q) in fit.surface.control_points().iter().enumerate() {
            let p = frame.origin + frame.axes[0] * q.x + frame.axes[1] * q.y + frame.axes[2] * q.z;
            for c in 0..3 {
                x[c * n + i] = p[c];
            }
        }
        problem.strictly_inside(&x).then_some(x)
    }
}

/// A right-handed orthonormal frame whose third axis is the normal of the least-squares
/// plane of some points.
struct Frame {
    origin: Vector3<f64>,
    axes: [Vector3<f64>; 3],
}

fn best_plane(points: &[Vector3<f64>]) -> Frame {
    let count = points.len().max(1) as f64;
    let origin = points.iter().sum::<Vector3<f64>>() / count;
    let mut scatter = nalgebra::Matrix3::zeros();
    for p in points {
        let d = p - origin;
        scatter += d * d.transpose();
    }
    let eigen = SymmetricEigen::new(scatter);
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| eigen.eigenvalues[b].total_cmp(&eigen.eigenvalues[a]));
    let e1: Vector3<f64> = eigen.eigenvectors.column(order[0]).into();
    let e2: Vector3<f64> = eigen.eigenvectors.column(order[1]).into();
    Frame {
        origin,
        axes: [e1, e2, e1.cross(&e2)],
    }
}

/// The problem of [`SpatialConvexity`]: $\min \tfrac12 \sum |S(u_a, v_b) - Q_{ab}|^2$ over
/// the coordinate-major unknowns `[x₀ … x_{n−1}, y₀ …, z₀ …]` (the control points, row-major
/// over the net) subject to $-\sigma L_k / s_L < 0$ and $-(LN - M^2)_k / s_K < 0$ for the
/// per-patch Bernstein coefficients of the numerators, with scales $s_L, s_K$ fixed at a
/// reference point (the largest coefficients there).
#[derive(Clone, Debug)]
pub struct SpatialConvexProblem {
    lsq: [LeastSquaresObjective; 3],
    knots: (KnotVector<f64>, KnotVector<f64>),
    pipeline: NumeratorPipeline,
    n: usize,
    sign: f64,
    /// `(s_L, s_K)`: the constraints' scales.
    scale: (f64, f64),
    rows: (usize, usize),
}

impl SpatialConvexProblem {
    fn new(
        lsq: [LeastSquaresObjective; 3],
        knots: (KnotVector<f64>, KnotVector<f64>),
        sign: Sign,
    ) -> Result<Self> {
        let pipeline = NumeratorPipeline::new(&knots.0, &knots.1)?;
        Ok(Self {
            n: lsq[0].dimension(),
            rows: pipeline.rows(),
            lsq,
            knots,
            pipeline,
            sign: sign.factor(),
            scale: (1.0, 1.0),
        })
    }

    /// Fixes the constraints' scales at the largest `|L_k|` and `|(LN − M²)_k|` of `x`.
    fn rescale(&mut self, x: &DVector<f64>) -> Result<()> {
        let f = self.pipeline.forward(x.as_slice());
        let largest = |v: &[f64]| v.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let (sl, sk) = (largest(&f.l), largest(&f.k));
        if !(sl.is_finite() && sk.is_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                "the curvature numerators of the start are not finite",
            ));
        }
        self.scale = (
            if sl > 0.0 { sl } else { 1.0 },
            if sk > 0.0 { sk } else { 1.0 },
        );
        Ok(())
    }

    /// The patch of the unknowns `x`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless `x` has [`BarrierProblem::dimension`] entries.
    pub fn patch(&self, x: &[f64]) -> Result<Surface<f64, Vector3<f64>>> {
        let n = self.n;
        if x.len() != 3 * n {
            return Err(Error::invalid_length("unknowns", 3 * n, x.len()));
        }
        let points = (0..n)
            .map(|i| Vector3::new(x[i], x[n + i], x[2 * n + i]))
            .collect();
        Surface::new(self.knots.0.clone(), self.knots.1.clone(), points)
    }

    /// The per-patch Bernstein coefficients of `L` and of `LN − M²` at `x` (unscaled).
    #[must_use]
    pub fn numerators(&self, x: &DVector<f64>) -> (Vec<f64>, Vec<f64>) {
        let f = self.pipeline.forward(x.as_slice());
        (f.l, f.k)
    }

    fn strictly_inside(&self, x: &DVector<f64>) -> bool {
        let (l, k) = self.numerators(x);
        l.iter().all(|&c| self.sign * c > 0.0) && k.iter().all(|&c| c > 0.0)
    }

    /// The factor from a numerator coefficient to its constraint: `−σ / s_L` or `−1 / s_K`.
    fn row_factor(&self, row: usize) -> f64 {
        if row < self.rows.0 {
            -self.sign / self.scale.0
        } else {
            -1.0 / self.scale.1
        }
    }

    /// The unknowns as vector dual numbers with unit derivatives for `first..first + LANES`.
    fn seeded(x: &DVector<f64>, first: usize) -> Vec<Lanes> {
        x.iter()
            .enumerate()
            .map(|(i, &v)| {
                let d = Lanes::from_re(v);
                if (first..first + LANES).contains(&i) {
                    d.derivative(i - first)
                } else {
                    d
                }
            })
            .collect()
    }

    /// $\sum_k w_k \nabla^2 f_k(x)$, dense: the derivative of the weighted gradient (the
    /// pipeline's adjoint) along [`LANES`] unknowns at a time, on vector dual numbers.
    fn weighted_hessian(&self, x: &DVector<f64>, weights: &DVector<f64>) -> DMatrix<f64> {
        let dim = 3 * self.n;
        let (rl, _) = self.rows;
        let w_l: Vec<f64> = (0..rl).map(|r| weights[r] * self.row_factor(r)).collect();
        let w_k: Vec<f64> = (rl..weights.len())
            .map(|r| weights[r] * self.row_factor(r))
            .collect();
        let mut hessian = DMatrix::zeros(dim, dim);
        for first in (0..dim).step_by(LANES) {
            let gradient = self
                .pipeline
                .weighted_gradient(&Self::seeded(x, first), &w_l, &w_k);
            for (i, g) in gradient.iter().enumerate() {
                if let Some(eps) = &g.eps.0 {
                    for lane in 0..LANES.min(dim - first) {
                        hessian[(i, first + lane)] = eps[lane];
                    }
                }
            }
        }
        // Exact up to rounding; symmetrise what rounding left.
        let transpose = hessian.transpose();
        (hessian + transpose) * 0.5
    }
}

impl BarrierProblem for SpatialConvexProblem {
    fn dimension(&self) -> usize {
        3 * self.n
    }

    fn num_constraints(&self) -> usize {
        self.rows.0 + self.rows.1
    }

    fn objective(&self, x: &DVector<f64>) -> f64 {
        let n = self.n;
        (0..3)
            .map(|c| self.lsq[c].value(&x.rows(c * n, n).into_owned()))
            .sum()
    }

    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64> {
        let n = self.n;
        let mut g = DVector::zeros(3 * n);
        for c in 0..3 {
            let part = self.lsq[c].gradient(&x.rows(c * n, n).into_owned());
            g.rows_mut(c * n, n).copy_from(&part);
        }
        g
    }

    fn objective_hessian(&self, _: &DVector<f64>) -> CsrMatrix<f64> {
        let n = self.n;
        let gram = self.lsq[0].hessian();
        let mut coo = CooMatrix::new(3 * n, 3 * n);
        for c in 0..3 {
            for (r, k, &v) in gram.triplet_iter() {
                coo.push(c * n + r, c * n + k, v);
            }
        }
        CsrMatrix::from(&coo)
    }

    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        let (l, k) = self.numerators(x);
        DVector::from_iterator(
            l.len() + k.len(),
            l.iter()
                .chain(&k)
                .enumerate()
                .map(|(r, &c)| c * self.row_factor(r)),
        )
    }

    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let dim = 3 * self.n;
        let mut coo = CooMatrix::new(self.num_constraints(), dim);
        for first in (0..dim).step_by(LANES) {
            let f = self.pipeline.forward(&Self::seeded(x, first));
            for (r, value) in f.l.iter().chain(&f.k).enumerate() {
                if let Some(eps) = &value.eps.0 {
                    let factor = self.row_factor(r);
                    for lane in 0..LANES.min(dim - first) {
                        if eps[lane] != 0.0 {
                            coo.push(r, first + lane, eps[lane] * factor);
                        }
                    }
                }
            }
        }
        CsrMatrix::from(&coo)
    }

    fn weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        Some(CsrMatrix::from(&CooMatrix::from(
            &self.weighted_hessian(x, weights),
        )))
    }

    fn add_weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
        out: &mut DMatrix<f64>,
    ) -> bool {
        *out += self.weighted_hessian(x, weights);
        true
    }
}
