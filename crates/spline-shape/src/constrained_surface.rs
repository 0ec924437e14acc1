//! Least-squares approximation of a function of two variables by a tensor-product B-spline
//! function under constraints on its differential properties (thesis §5.5–5.6).
//!
//! The samples form a grid `us × vs`; the objective is
//! $f_0(x) = \tfrac12\sum_{k,l} (s(u_k, v_l) - \gamma(u_k, v_l))^2 = \tfrac12\\|Ax - b\\|^2$
//! with $A = A_u \otimes A_v$ on the row-major coefficients $x_{ij}$ (`i` along `u`).
//!
//! - A sign constraint on a partial derivative $\partial^{k+l}s/\partial u^k\partial v^l$ on
//!   a rectangle is a sign condition on the control points of the derived tensor-product
//!   spline (a Kronecker map of `x`: partial derivative, restriction, optional refinement):
//!   linear constraints, a convex quadratic program (§5.5).
//! - Convexity (§5.6): the Hessian matrix of `s` is positive semi-definite where
//!   $s_{uu} \ge 0$ and $s_{uu}s_{vv} - s_{uv}^2 \ge 0$. The first is linear; the second is a
//!   tensor-product spline whose control points are quadratic in `x`, with gradient
//!   $(\nabla s)_{uu}s_{vv} + s_{uu}(\nabla s)_{vv} - 2(\nabla s)_{uv}s_{uv}$ and a constant
//!   Hessian ([`spline_algebra::hessian_determinant`]). The problem is no longer convex: the
//!   barrier method finds a local minimum (its Newton matrix is shifted when indefinite).
//!   It starts from a strictly convex quadratic polynomial fitted to the data (which
//!   satisfies the control-point conditions exactly), moved towards the unconstrained fit
//!   as far as feasibility allows.
//!
//! ```
//! use spline_shape::{Sign, SurfaceApproximation};
//! // sin u sin v on [0, 2π]², bicubic 6 × 6, s ≥ 0 (thesis §5.5.2, smaller).
//! let two_pi = 2.0 * std::f64::consts::PI;
//! let approx = SurfaceApproximation::uniform((3, 3), (6, 6), (0.0, two_pi), (0.0, two_pi))?
//!     .sign(0, 0, Sign::NonNegative);
//! let fit = approx.fit_function((20, 20), |u, v| u.sin() * v.sin())?;
//! assert!(fit.objective >= fit.unconstrained_objective);
//! assert!(fit.surface.control_points().iter().all(|&c| c > 0.0));
//! assert!(approx.check(&fit.surface, 8)?.iter().all(|c| c.violation <= 1e-12));
//! # Ok::<(), spline_core::Error>(())
//! ```

use crate::barrier::{BarrierOptions, BarrierReport};
use crate::constrained::{ConstraintCheck, sampled_grid, span_samples};
use crate::problem::{
    ApproximationProblem, LeastSquaresObjective, Sign, check_interval, check_samples, derived_map,
    furthest_feasible, normalized_rows, refined, solve, strictly_feasible, vstack,
};
use crate::problem::{check_grid, check_refinement, normalized_forms};
use nalgebra::{DVector, Matrix2, Matrix6, Vector6};

use spline_algebra::{SparseBilinear, SplineMap, TensorMap, hessian_determinant};
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result};
use spline_geom::Surface;

/// A rectangle `([a, b], [c, d])` of the parameter domain.
pub type Region = ((f64, f64), (f64, f64));

/// A constraint on a function of two variables.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SurfaceConstraint {
    /// $\partial^{k+l}s/\partial u^k\partial v^l$ keeps `sign` on `region` (the whole
    /// domain for `None`).
    Sign {
        /// The orders `(k, l)`, at most the degrees.
        orders: (usize, usize),
        /// The sign to keep.
        sign: Sign,
        /// The rectangle, or `None` for the whole domain.
        region: Option<Region>,
    },
    /// Convexity (`sign` = [`Sign::NonNegative`]) or concavity ([`Sign::NonPositive`]) on
    /// `region`: $\sigma s_{uu} \ge 0$ and $s_{uu}s_{vv} - s_{uv}^2 \ge 0$ (thesis §5.6).
    Convex {
        /// [`Sign::NonNegative`] for convex, [`Sign::NonPositive`] for concave.
        sign: Sign,
        /// The rectangle, or `None` for the whole domain.
        region: Option<Region>,
    },
}

/// The result of [`SurfaceApproximation::fit_grid`] (a function: scalar control points, `P`
/// = `f64`) and of [`crate::ParametricConvexity::fit_grid`] (the patch `(X, Y, z)`, `P` =
/// `Vector3<f64>`: [`crate::ParametricConvexFit`]).
#[derive(Clone, Debug)]
pub struct ConstrainedSurfaceFit<P = f64> {
    /// The constrained least-squares surface.
    pub surface: Surface<f64, P>,
    /// The unconstrained least-squares surface on the same knots.
    pub unconstrained: Surface<f64, P>,
    /// $f_0 = \tfrac12\\|Ax - b\\|^2$ of the constrained surface: half the sum of the
    /// squared errors of the heights at the samples.
    pub objective: f64,
    /// $f_0$ of the unconstrained surface.
    pub unconstrained_objective: f64,
    /// The barrier method's report.
    pub report: BarrierReport,
    /// The number of linear and of quadratic constraints.
    pub num_constraints: (usize, usize),
}

impl<P: ControlPoint<f64>> ConstrainedSurfaceFit<P> {
    /// Solves `problem` from its unconstrained least-squares solution, or, when `inside`
    /// gives a strictly feasible point, from the point furthest from it towards that
    /// solution found strictly feasible; `surface` makes the surfaces of the solutions.
    ///
    /// # Errors
    /// As [`ApproximationProblem::unconstrained_solution`], `inside`, the solver and
    /// `surface`.
    pub(crate) fn solve(
        problem: &ApproximationProblem,
        inside: impl FnOnce() -> Result<Option<DVector<f64>>>,
        options: &BarrierOptions,
        surface: impl Fn(&DVector<f64>) -> Result<Surface<f64, P>>,
    ) -> Result<Self> {
        let x_ls = problem.unconstrained_solution()?;
        let unconstrained_objective = problem.least_squares().value(&x_ls);
        let mut start = x_ls.clone();
        if let Some(inside) = inside()? {
            if strictly_feasible(problem, &inside) {
                start = furthest_feasible(problem, &inside, &x_ls);
            }
        }
        let solution = solve(problem, std::slice::from_ref(&start), options)?;
        Ok(Self {
            surface: surface(&solution.x)?,
            unconstrained: surface(&x_ls)?,
            objective: solution.report.objective,
            unconstrained_objective,
            num_constraints: (
                problem.num_linear_constraints(),
                problem.num_quadratic_constraints(),
            ),
            report: solution.report,
        })
    }
}

/// Constrained least-squares approximation of a function of two variables on a grid of
/// samples (a builder; see the [module](self) docs).
///
/// ```
/// use spline_shape::SurfaceApproximation;
/// // A convex fit of a saddle-free but wavy function (thesis §5.6, smaller).
/// let d = (-1.0, 1.0);
/// let approx = SurfaceApproximation::uniform((3, 3), (5, 5), d, d)?.convex();
/// let fit = approx.fit_function((12, 12), |u, v| u * u + v * v + 0.3 * (4.0 * u).sin())?;
/// assert!(fit.objective >= fit.unconstrained_objective);
/// assert!(approx.check(&fit.surface, 8)?[0].violation <= 1e-9);
/// assert!(approx.check(&fit.unconstrained, 8)?[0].violation > 0.0);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct SurfaceApproximation {
    knots_u: KnotVector<f64>,
    knots_v: KnotVector<f64>,
    constraints: Vec<SurfaceConstraint>,
    refinement: usize,
    options: BarrierOptions,
}

impl SurfaceApproximation {
    /// An approximation on the given knot vectors, without constraints yet.
    #[must_use]
    pub fn new(knots_u: KnotVector<f64>, knots_v: KnotVector<f64>) -> Self {
        Self {
            knots_u,
            knots_v,
            constraints: Vec::new(),
            refinement: 1,
            options: BarrierOptions::default(),
        }
    }

    /// Degrees `(p, q)`, `(n_u, n_v)` coefficients, clamped uniform knots on `[a, b] × [c, d]`.
    ///
    /// # Errors
    /// The errors of [`KnotVector::clamped_uniform`] in either direction.
    pub fn uniform(
        degrees: (usize, usize),
        counts: (usize, usize),
        (a, b): (f64, f64),
        (c, d): (f64, f64),
    ) -> Result<Self> {
        Ok(Self::new(
            KnotVector::clamped_uniform(degrees.0, counts.0, a, b)
                .map_err(|e| e.context("knots in u"))?,
            KnotVector::clamped_uniform(degrees.1, counts.1, c, d)
                .map_err(|e| e.context("knots in v"))?,
        ))
    }

    /// Adds a constraint (checked by [`SurfaceApproximation::fit_grid`]).
    #[must_use]
    pub fn with_constraint(mut self, constraint: SurfaceConstraint) -> Self {
        self.constraints.push(constraint);
        self
    }

    /// Adds $\sigma\\,\partial^{k+l}s/\partial u^k\partial v^l \ge 0$ on the whole domain.
    #[must_use]
    pub fn sign(self, k: usize, l: usize, sign: Sign) -> Self {
        self.with_constraint(SurfaceConstraint::Sign {
            orders: (k, l),
            sign,
            region: None,
        })
    }

    /// Adds $\sigma\\,\partial^{k+l}s/\partial u^k\partial v^l \ge 0$ on a rectangle.
    #[must_use]
    pub fn sign_on(self, k: usize, l: usize, sign: Sign, region: Region) -> Self {
        self.with_constraint(SurfaceConstraint::Sign {
            orders: (k, l),
            sign,
            region: Some(region),
        })
    }

    /// Adds convexity on the whole domain.
    #[must_use]
    pub fn convex(self) -> Self {
        self.with_constraint(SurfaceConstraint::Convex {
            sign: Sign::NonNegative,
            region: None,
        })
    }

    /// Adds concavity on the whole domain.
    #[must_use]
    pub fn concave(self) -> Self {
        self.with_constraint(SurfaceConstraint::Convex {
            sign: Sign::NonPositive,
            region: None,
        })
    }

    solver_settings!(
        "Splits every span of the derived splines into `pieces` in both directions (`1` = \
         none): less conservative sign conditions."
    );

    /// The knot vectors `(u, v)`.
    #[must_use]
    pub fn knots(&self) -> (&KnotVector<f64>, &KnotVector<f64>) {
        (&self.knots_u, &self.knots_v)
    }

    /// The constraints.
    #[must_use]
    pub fn constraints(&self) -> &[SurfaceConstraint] {
        &self.constraints
    }

    fn region_of(&self, region: Option<Region>) -> Region {
        region.unwrap_or_else(|| (self.knots_u.domain(), self.knots_v.domain()))
    }

    fn validate(&self) -> Result<()> {
        check_refinement(self.refinement)?;
        let (p, q) = (self.knots_u.degree(), self.knots_v.degree());
        for (i, c) in self.constraints.iter().enumerate() {
            let what = format!("constraint {i}");
            let (orders, region) = match *c {
                SurfaceConstraint::Sign { orders, region, .. } => (orders, region),
                SurfaceConstraint::Convex { region, .. } => ((2, 2), region),
            };
            if orders.0 > p || orders.1 > q {
                // The counts of the first direction whose order is too high.
                let (degree, order) = if orders.0 > p {
                    (p, orders.0)
                } else {
                    (q, orders.1)
                };
                return Err(Error::new(
                    ErrorKind::OrderTooHigh,
                    format!(
                        "{what}: derivative orders ({}, {}) exceed the degrees ({p}, {q})",
                        orders.0, orders.1
                    ),
                )
                .with_index(i)
                .with_counts(degree, order));
            }
            let (ru, rv) = self.region_of(region);
            check_interval(&self.knots_u, ru, &format!("{what} (u)"))?;
            check_interval(&self.knots_v, rv, &format!("{what} (v)"))?;
        }
        Ok(())
    }

    /// The Kronecker map from the coefficients to the control points of a partial
    /// derivative restricted to a rectangle and refined as set.
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] if an order exceeds its degree;
    /// [`ErrorKind::OutOfDomain`] or [`ErrorKind::NonFinite`] for a bad rectangle.
    pub fn derivative_map(
        &self,
        (k, l): (usize, usize),
        region: Option<Region>,
    ) -> Result<TensorMap<f64>> {
        let (ru, rv) = self.region_of(region);
        check_interval(&self.knots_u, ru, "region (u)")?;
        check_interval(&self.knots_v, rv, "region (v)")?;
        Ok(TensorMap::new(
            derived_map(&self.knots_u, k, ru, self.refinement)?,
            derived_map(&self.knots_v, l, rv, self.refinement)?,
        ))
    }

    /// The control points of $s_{uu}s_{vv} - s_{uv}^2$ restricted to a rectangle and refined
    /// as set, as a quadratic map of the coefficients, with the knot vectors `(u, v)` of
    /// that spline: row `k` of the bilinear map is the constant Hessian $H_k$, and
    /// coefficient `k` is $\tfrac12 x^T H_k x$ (row-major, `i` along `u`).
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] unless both degrees are at least 2;
    /// [`ErrorKind::OutOfDomain`] or [`ErrorKind::NonFinite`] for a bad rectangle.
    pub fn determinant_map(
        &self,
        region: Option<Region>,
    ) -> Result<(SparseBilinear<f64>, KnotVector<f64>, KnotVector<f64>)> {
        let (ru, rv) = self.region_of(region);
        check_interval(&self.knots_u, ru, "region (u)")?;
        check_interval(&self.knots_v, rv, "region (v)")?;
        let zero = Surface::new(
            self.knots_u.clone(),
            self.knots_v.clone(),
            vec![0.0; self.knots_u.num_basis() * self.knots_v.num_basis()],
        )?;
        let det = hessian_determinant(&zero)?;
        let (ku, kv) = (det.value.knots_u(), det.value.knots_v());
        let mu = refined(SplineMap::restriction(ku, ru.0, ru.1)?, self.refinement)?;
        let mv = refined(SplineMap::restriction(kv, rv.0, rv.1)?, self.refinement)?;
        let map = TensorMap::new(mu, mv);
        Ok((
            det.hessian.then(&map.matrix())?,
            map.u().target().clone(),
            map.v().target().clone(),
        ))
    }

    /// The constrained problem for the grid samples `values[a · vs.len() + b]` at
    /// `(us[a], vs[b])`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are `us.len() · vs.len() > 0` values;
    /// [`ErrorKind::NonFinite`] for a non-finite value; [`ErrorKind::OutOfDomain`] for a
    /// parameter outside the domain; [`ErrorKind::OrderTooHigh`] for a constraint whose
    /// derivative orders exceed the degrees (a convexity constraint below degree 2), with
    /// the constraint as [`Error::index`] and `(degree, order)` of the first such direction
    /// as [`Error::counts`]; [`ErrorKind::InvalidArgument`] for a refinement of 0.
    pub fn problem(&self, us: &[f64], vs: &[f64], values: &[f64]) -> Result<ApproximationProblem> {
        self.validate()?;
        check_grid(us, vs, values.len(), |j| values[j].is_finite(), "value")?;
        let lsq = LeastSquaresObjective::grid((&self.knots_u, &self.knots_v), us, vs, values)?;
        let n = self.knots_u.num_basis() * self.knots_v.num_basis();
        let mut linear = Vec::new();
        let mut quadratic: Option<SparseBilinear<f64>> = None;
        for c in &self.constraints {
            match *c {
                SurfaceConstraint::Sign {
                    orders,
                    sign,
                    region,
                } => {
                    let map = self.derivative_map(orders, region)?;
                    linear.push(normalized_rows(&map.matrix(), -sign.factor()));
                }
                SurfaceConstraint::Convex { sign, region } => {
                    let map = self.derivative_map((2, 0), region)?;
                    linear.push(normalized_rows(&map.matrix(), -sign.factor()));
                    let det = normalized_forms(&self.determinant_map(region)?.0)?;
                    quadratic = Some(match quadratic {
                        None => det,
                        Some(q) => stack_forms(&q, &det)?,
                    });
                }
            }
        }
        Ok(ApproximationProblem::new(
            lsq,
            vstack(n, &linear),
            quadratic,
        ))
    }

    /// Fits grid samples under the constraints (see [`SurfaceApproximation::problem`]).
    ///
    /// # Errors
    /// The errors of [`SurfaceApproximation::problem`]; [`ErrorKind::SchoenbergWhitney`] if
    /// the grid does not determine every coefficient; [`ErrorKind::NoConvergence`] if no
    /// strictly feasible point is found or the barrier method does not converge.
    pub fn fit_grid(
        &self,
        us: &[f64],
        vs: &[f64],
        values: &[f64],
    ) -> Result<ConstrainedSurfaceFit> {
        let problem = self.problem(us, vs, values)?;
        // Phase I on the non-convex constraints can stall at a local minimum of the largest
        // violation: start instead from a strictly convex quadratic fitted to the data,
        // moved as far towards the unconstrained fit as feasibility allows.
        let convex = self.constraints.iter().find_map(|c| match c {
            SurfaceConstraint::Convex { sign, .. } => Some(*sign),
            SurfaceConstraint::Sign { .. } => None,
        });
        let inside = || {
            convex
                .map(|sign| self.quadratic_start(&problem, sign, us, vs, values))
                .transpose()
        };
        ConstrainedSurfaceFit::solve(&problem, inside, &self.options, |x| {
            Surface::new(
                self.knots_u.clone(),
                self.knots_v.clone(),
                x.as_slice().to_vec(),
            )
        })
    }

    /// Fits `f` sampled on a uniform grid of `counts.0 × counts.1` points of the domain
    /// (boundaries included).
    ///
    /// # Errors
    /// [`ErrorKind::TooFewPoints`] for fewer than two samples in a direction; the errors
    /// of [`SurfaceApproximation::fit_grid`].
    pub fn fit_function(
        &self,
        counts: (usize, usize),
        f: impl Fn(f64, f64) -> f64,
    ) -> Result<ConstrainedSurfaceFit> {
        let domains = (self.knots_u.domain(), self.knots_v.domain());
        let (us, vs, values) = sampled_grid(domains, counts, |u, v| Ok(f(u, v)))?;
        self.fit_grid(&us, &vs, &values)
    }

    /// The coefficients of a strictly convex (`sign` = +) or concave quadratic polynomial
    /// close to the data: the least-squares quadratic, its Hessian's eigenvalues (times
    /// `sign`) raised to at least a tenth of the largest one. A quadratic is represented
    /// exactly, and then $s_{uu}$ and $s_{uu}s_{vv} - s_{uv}^2$ are positive constants whose
    /// control points all equal them: the constraints of convexity hold strictly.
    fn quadratic_start(
        &self,
        problem: &ApproximationProblem,
        sign: Sign,
        us: &[f64],
        vs: &[f64],
        values: &[f64],
    ) -> Result<DVector<f64>> {
        let centre = |k: &KnotVector<f64>| {
            let (a, b) = k.domain();
            ((a + b) / 2.0, (b - a) / 2.0)
        };
        let ((cu, hu), (cv, hv)) = (centre(&self.knots_u), centre(&self.knots_v));
        let basis = |u: f64, v: f64| {
            let (x, y) = ((u - cu) / hu, (v - cv) / hv);
            [1.0, x, y, x * x, x * y, y * y]
        };
        let mut normal = Matrix6::<f64>::zeros();
        let mut rhs = Vector6::<f64>::zeros();
        for (a, &u) in us.iter().enumerate() {
            for (b, &v) in vs.iter().enumerate() {
                let phi = Vector6::from(basis(u, v));
                normal += phi * phi.transpose();
                rhs += phi * values[a * vs.len() + b];
            }
        }
        // A tiny ridge keeps degenerate grids (one row of samples) solvable.
        let ridge = 1e-12 * (1.0 + normal.diagonal().amax());
        let c = (normal + Matrix6::identity() * ridge)
            .cholesky()
            .map_or_else(Vector6::zeros, |ch| ch.solve(&rhs));
        let s = sign.factor();
        let hessian = Matrix2::new(2.0 * c[3], c[4], c[4], 2.0 * c[5]) * s;
        let eigen = hessian.symmetric_eigen();
        let floor = (0.1 * eigen.eigenvalues.max())
            .max(1e-3 * (1.0 + values.iter().fold(0.0f64, |m, v| m.max(v.abs()))));
        let lifted = eigen.eigenvectors
            * Matrix2::from_diagonal(&eigen.eigenvalues.map(|l| l.max(floor)))
            * eigen.eigenvectors.transpose()
            * s;
        let q = [
            c[0],
            c[1],
            c[2],
            lifted[(0, 0)] / 2.0,
            lifted[(0, 1)],
            lifted[(1, 1)] / 2.0,
        ];
        let grid = DVector::from_iterator(
            us.len() * vs.len(),
            us.iter().flat_map(|&u| {
                vs.iter()
                    .map(move |&v| basis(u, v).iter().zip(&q).map(|(b, c)| b * c).sum())
            }),
        );
        problem.least_squares().solve_for(grid.as_slice())
    }

    /// Checks the constraints on any surface of the domain by dense sampling (with
    /// [`Surface::derivatives`]): `samples_per_span` points per knot span of the fit in each
    /// direction inside each constraint's rectangle. For convexity the violation is the
    /// larger of $\max(0, -\sigma s_{uu})$ and $\max(0, -(s_{uu}s_{vv} - s_{uv}^2))$.
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] for a constraint whose orders exceed the degrees;
    /// [`ErrorKind::InvalidArgument`] for a refinement of 0 or `samples_per_span = 0`;
    /// [`ErrorKind::OutOfDomain`] if the surface does not cover the constraint rectangles.
    pub fn check(
        &self,
        surface: &Surface<f64, f64>,
        samples_per_span: usize,
    ) -> Result<Vec<ConstraintCheck>> {
        self.validate()?;
        check_samples(samples_per_span)?;
        let mut out = Vec::with_capacity(self.constraints.len());
        for c in &self.constraints {
            let region = match *c {
                SurfaceConstraint::Sign { region, .. }
                | SurfaceConstraint::Convex { region, .. } => region,
            };
            let ((a, b), (cc, d)) = self.region_of(region);
            let us = span_samples(&self.knots_u, a, b, samples_per_span);
            let vs = span_samples(&self.knots_v, cc, d, samples_per_span);
            let mut violation = 0.0f64;
            for &u in &us {
                for &v in &vs {
                    let worst = match *c {
                        SurfaceConstraint::Sign {
                            orders: (k, l),
                            sign,
                            ..
                        } => -sign.factor() * surface.derivatives(u, v, k.max(l))?[k][l],
                        SurfaceConstraint::Convex { sign, .. } => {
                            let s = surface.derivatives(u, v, 2)?;
                            let det = s[2][0] * s[0][2] - s[1][1] * s[1][1];
                            (-sign.factor() * s[2][0]).max(-det)
                        }
                    };
                    violation = violation.max(worst);
                }
            }
            out.push(ConstraintCheck {
                violation,
                sign_changes: 0,
                samples: us.len() * vs.len(),
            });
        }
        Ok(out)
    }
}

/// Two families of forms, one after the other.
fn stack_forms(a: &SparseBilinear<f64>, b: &SparseBilinear<f64>) -> Result<SparseBilinear<f64>> {
    let rows = (0..a.nrows())
        .map(|k| a.row(k).to_vec())
        .chain((0..b.nrows()).map(|k| b.row(k).to_vec()))
        .collect();
    SparseBilinear::from_rows(a.left_dim(), a.right_dim(), rows)
}
