//! Least-squares approximation of a function of one variable by a B-spline function under
//! sign constraints on its derivatives (thesis §5.1–5.4).
//!
//! The objective is $f_0(x) = \tfrac12\sum_j (s(u_j) - \gamma(u_j))^2 = \tfrac12\\|Ax - b\\|^2$
//! with $A_{ji} = N_{i,d}(u_j)$. A constraint "$s^{(k)} \ge 0$ on `[a, b]`" becomes a sign
//! condition on the control points of the derivative spline restricted to `[a, b]` (a sparse
//! linear map of `x`: derivative, then knot insertion at `a` and `b`; thesis (5.20)–(5.30)):
//! the basis is non-negative, so this is a *sufficient* condition, made less conservative by
//! refining the knots of the derived spline ([`FunctionApproximation::refinement`], the
//! remark of §6.15). The problem is a convex quadratic program solved by the log-barrier
//! method ([`crate::minimize`]) from a strictly feasible start found by phase I
//! ([`crate::find_feasible`]) from the unconstrained fit.
//!
//! A *sign change* ([`FunctionConstraint::SignChange`], §5.4) asks $s^{(k)}$ to go from one
//! sign at `a` to the other at `b` with exactly one sign change in between: the derived
//! spline restricted to `[a, b]` has `N` coefficients; its first one gets the first sign, its
//! last one the other, and the sign sequence must change exactly once (variation
//! diminishing: then $s^{(k)}$ has exactly one root in `(a, b)`, counted with multiplicity).
//! For `N ≤ 3` (a quadratic segment, the usual case for a short interval) this is just the
//! two end conditions; for larger `N` the `N − 1` possible places of the change are convex
//! problems of their own, all solved, and the best one is kept.
//!
//! ```
//! use spline_shape::{FunctionApproximation, Sign};
//! // Approximate cos u on [0, 4π] by a cubic with 11 coefficients, s ≥ 0 (thesis §5.1.3).
//! let four_pi = 4.0 * std::f64::consts::PI;
//! let approx = FunctionApproximation::uniform(3, 11, 0.0, four_pi)?.sign(0, Sign::NonNegative);
//! let fit = approx.fit_function(200, f64::cos)?;
//! assert!(fit.objective >= fit.unconstrained_objective);
//! // Every control point is positive, hence s ≥ 0 everywhere.
//! assert!(fit.spline.control_points().iter().all(|&c| c > 0.0));
//! // The independent check: dense sampling of s.
//! assert!(approx.check(&fit.spline, 16)?.iter().all(|c| c.violation <= 1e-12));
//! # Ok::<(), spline_core::Error>(())
//! ```

use crate::barrier::{BarrierOptions, BarrierReport};
use crate::problem::{
    ApproximationProblem, LeastSquaresObjective, Sign, check_interval, check_refinement,
    check_samples, derived_map, normalized_rows, solve, vstack,
};
use nalgebra_sparse::{CooMatrix, CsrMatrix};
use spline_algebra::SplineMap;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::BSpline;

/// The most sign patterns [`FunctionApproximation::fit`] solves (the product over the sign
/// changes of the number of places where each can happen).
pub const MAX_SIGN_PATTERNS: usize = 64;

/// A constraint on a derivative of a function of one variable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FunctionConstraint {
    /// $s^{(k)}$ keeps `sign` on `interval` (the whole domain for `None`).
    Sign {
        /// The derivative order `k` (0 for the function itself), at most the degree.
        order: usize,
        /// The sign to keep.
        sign: Sign,
        /// The sub-interval `[a, b]`, or `None` for the whole domain.
        interval: Option<(f64, f64)>,
    },
    /// $s^{(k)}$ has the sign `from` at `a`, the other sign at `b`, and exactly one sign
    /// change (one root) in between (thesis §5.4).
    SignChange {
        /// The derivative order `k`, at most the degree.
        order: usize,
        /// The sign at `a`.
        from: Sign,
        /// The interval `(a, b)` that holds the root.
        interval: (f64, f64),
    },
}

impl FunctionConstraint {
    /// The derivative order.
    #[must_use]
    pub fn order(&self) -> usize {
        match *self {
            Self::Sign { order, .. } | Self::SignChange { order, .. } => order,
        }
    }
}

/// What a dense sampling of one constraint found (see [`FunctionApproximation::check`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstraintCheck {
    /// The largest violation: $\max(0, -\sigma\\, s^{(k)}(u))$ over the samples for a sign
    /// constraint, the same at the two ends (with their signs) for a sign change; `0` when
    /// the samples satisfy the constraint.
    pub violation: f64,
    /// The number of sign changes of the sampled values on the interval (zeros skipped);
    /// a satisfied [`FunctionConstraint::SignChange`] has exactly one.
    pub sign_changes: usize,
    /// The number of samples.
    pub samples: usize,
}

/// The result of [`FunctionApproximation::fit`].
#[derive(Clone, Debug)]
pub struct FunctionFit {
    /// The constrained least-squares spline.
    pub spline: BSpline<f64, f64>,
    /// The unconstrained least-squares spline on the same knots.
    pub unconstrained: BSpline<f64, f64>,
    /// $f_0 = \tfrac12\\|Ax - b\\|^2$ of the constrained spline.
    pub objective: f64,
    /// $f_0$ of the unconstrained spline (a lower bound of `objective`).
    pub unconstrained_objective: f64,
    /// The barrier method's report for the retained sign pattern.
    pub report: BarrierReport,
    /// The number of constraints (rows) of the retained problem.
    pub num_constraints: usize,
    /// The number of sign patterns solved (1 without sign changes).
    pub patterns: usize,
}

/// Constrained least-squares approximation of a function of one variable: the knot vector,
/// the constraints, and the solver settings (a builder; see the [module](self) docs).
///
/// ```
/// use spline_shape::{FunctionApproximation, Sign};
/// use std::f64::consts::PI;
/// // Thesis §5.4, smaller: rising on [0, 2π − ε], falling on [2π + ε, 4π], one maximum
/// // in between.
/// let eps = 0.05;
/// let approx = FunctionApproximation::uniform(3, 40, 0.0, 4.0 * PI)?
///     .sign_on(1, Sign::NonNegative, 0.0, 2.0 * PI - eps)
///     .sign_on(1, Sign::NonPositive, 2.0 * PI + eps, 4.0 * PI)
///     .sign_change(1, Sign::NonNegative, 2.0 * PI - eps, 2.0 * PI + eps);
/// let fit = approx.fit_function(400, |u| -4.0 * (4.0 * u).cos() - (u - 2.0 * PI).powi(2))?;
/// let checks = approx.check(&fit.spline, 16)?;
/// assert!(checks.iter().all(|c| c.violation == 0.0));
/// assert_eq!(checks[2].sign_changes, 1); // s′ changes sign once near 2π
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct FunctionApproximation {
    knots: KnotVector<f64>,
    constraints: Vec<FunctionConstraint>,
    refinement: usize,
    options: BarrierOptions,
}

impl FunctionApproximation {
    /// An approximation on the given knot vector (its domain is the domain of the fit),
    /// without constraints yet.
    #[must_use]
    pub fn new(knots: KnotVector<f64>) -> Self {
        Self {
            knots,
            constraints: Vec::new(),
            refinement: 1,
            options: BarrierOptions::default(),
        }
    }

    /// An approximation of degree `degree` with `num_coefficients` coefficients on the
    /// clamped uniform knot vector of `[a, b]` (the setting of the thesis).
    ///
    /// # Errors
    /// The errors of [`KnotVector::clamped_uniform`].
    pub fn uniform(degree: usize, num_coefficients: usize, a: f64, b: f64) -> Result<Self> {
        Ok(Self::new(KnotVector::clamped_uniform(
            degree,
            num_coefficients,
            a,
            b,
        )?))
    }

    /// Adds a constraint (checked by [`FunctionApproximation::fit`]).
    #[must_use]
    pub fn with_constraint(mut self, constraint: FunctionConstraint) -> Self {
        self.constraints.push(constraint);
        self
    }

    /// Adds $\sigma s^{(k)} \ge 0$ on the whole domain.
    #[must_use]
    pub fn sign(self, order: usize, sign: Sign) -> Self {
        self.with_constraint(FunctionConstraint::Sign {
            order,
            sign,
            interval: None,
        })
    }

    /// Adds $\sigma s^{(k)} \ge 0$ on `[a, b]`.
    #[must_use]
    pub fn sign_on(self, order: usize, sign: Sign, a: f64, b: f64) -> Self {
        self.with_constraint(FunctionConstraint::Sign {
            order,
            sign,
            interval: Some((a, b)),
        })
    }

    /// Adds a sign change of $s^{(k)}$ in `(a, b)`, from `from` at `a` to the other sign at
    /// `b` ([`FunctionConstraint::SignChange`]).
    #[must_use]
    pub fn sign_change(self, order: usize, from: Sign, a: f64, b: f64) -> Self {
        self.with_constraint(FunctionConstraint::SignChange {
            order,
            from,
            interval: (a, b),
        })
    }

    solver_settings!(
        "Splits every span of the derived splines of the sign constraints into `pieces` \
         (knot refinement, `1` = none): more, and less conservative, sign conditions on \
         control points that lie closer to the derivative. Sign changes are not refined (it \
         would multiply their sign patterns)."
    );

    /// The knot vector of the fit.
    #[must_use]
    pub fn knots(&self) -> &KnotVector<f64> {
        &self.knots
    }

    /// The constraints.
    #[must_use]
    pub fn constraints(&self) -> &[FunctionConstraint] {
        &self.constraints
    }

    fn interval_of(&self, constraint: &FunctionConstraint) -> (f64, f64) {
        match *constraint {
            FunctionConstraint::Sign { interval, .. } => {
                interval.unwrap_or_else(|| self.knots.domain())
            }
            FunctionConstraint::SignChange { interval, .. } => interval,
        }
    }

    fn validate(&self) -> Result<()> {
        check_refinement(self.refinement)?;
        for (i, c) in self.constraints.iter().enumerate() {
            let what = format!("constraint {i}");
            if c.order() > self.knots.degree() {
                return Err(
                    Error::order_too_high(c.order(), self.knots.degree(), "the degree")
                        .context(&what)
                        .with_index(i),
                );
            }
            check_interval(&self.knots, self.interval_of(c), &what)?;
        }
        Ok(())
    }

    /// The linear map from the coefficients `x` to the control points of the derived spline
    /// of a constraint: the derivative of its order restricted to its interval (and refined
    /// as set, except for sign changes). Its matrix is the Jacobian of the constraint values.
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] if the order exceeds the degree (`(degree, order)` as
    /// [`Error::counts`]); [`ErrorKind::OutOfDomain`] or [`ErrorKind::NonFinite`] for a bad
    /// interval.
    pub fn constraint_map(&self, constraint: &FunctionConstraint) -> Result<SplineMap<f64>> {
        if constraint.order() > self.knots.degree() {
            return Err(Error::order_too_high(
                constraint.order(),
                self.knots.degree(),
                "the degree",
            ));
        }
        let interval = self.interval_of(constraint);
        check_interval(&self.knots, interval, "constraint")?;
        let pieces = match constraint {
            FunctionConstraint::Sign { .. } => self.refinement,
            FunctionConstraint::SignChange { .. } => 1,
        };
        derived_map(&self.knots, constraint.order(), interval, pieces)
    }

    /// The constrained problems for samples `(params[j], values[j])`: one per sign pattern
    /// of the sign changes (a single one without sign changes). [`FunctionApproximation::fit`]
    /// solves them all and keeps the best.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] if the lengths differ or there are no samples;
    /// [`ErrorKind::NonFinite`] for a non-finite value; [`ErrorKind::OutOfDomain`] for a
    /// parameter outside the domain; [`ErrorKind::OrderTooHigh`] for a constraint whose
    /// derivative order exceeds the degree (the constraint as [`Error::index`]);
    /// [`ErrorKind::InvalidArgument`] for a refinement of 0, more than [`MAX_SIGN_PATTERNS`]
    /// patterns, or a sign change on a single piece of a piecewise-constant derivative.
    pub fn problems(&self, params: &[f64], values: &[f64]) -> Result<Vec<ApproximationProblem>> {
        self.validate()?;
        if params.len() != values.len() || params.is_empty() {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "need as many values as parameters (at least one), got {} parameters and {} values",
                    params.len(),
                    values.len()
                ),
            ));
        }
        if let Some(j) = values.iter().position(|v| !v.is_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("value {j} is not finite"),
            ));
        }
        let lsq = LeastSquaresObjective::function(&self.knots, params, values)?;
        let n = self.knots.num_basis();
        let mut fixed = Vec::new();
        let mut changes: Vec<Vec<CsrMatrix<f64>>> = Vec::new();
        for c in &self.constraints {
            let map = self.constraint_map(c)?;
            match *c {
                FunctionConstraint::Sign { sign, .. } => {
                    // σ c_i > 0  ⇔  −σ c_i < 0.
                    fixed.push(normalized_rows(map.matrix(), -sign.factor()));
                }
                FunctionConstraint::SignChange { from, .. } => {
                    if map.matrix().nrows() < 2 {
                        return Err(Error::new(
                            ErrorKind::InvalidArgument,
                            "a sign change needs an interval where the derivative has at least two coefficients (one polynomial piece of degree 0 cannot change sign)",
                        ));
                    }
                    changes.push(sign_patterns(map.matrix(), from));
                }
            }
        }
        let count = changes
            .iter()
            .try_fold(1usize, |acc, p| acc.checked_mul(p.len()))
            .filter(|&c| c <= MAX_SIGN_PATTERNS)
            .ok_or_else(|| {
                Error::new(
                    ErrorKind::InvalidArgument,
                    format!(
                        "the sign changes allow more than {MAX_SIGN_PATTERNS} sign patterns: shorten their intervals"
                    ),
                )
            })?;
        let fixed = vstack(n, &fixed);
        let mut out = Vec::with_capacity(count);
        for index in 0..count {
            let mut blocks = vec![fixed.clone()];
            let mut rest = index;
            for patterns in &changes {
                blocks.push(patterns[rest % patterns.len()].clone());
                rest /= patterns.len();
            }
            out.push(ApproximationProblem::new(
                lsq.clone(),
                vstack(n, &blocks),
                None,
            ));
        }
        Ok(out)
    }

    /// Fits the samples `(params[j], values[j])` under the constraints.
    ///
    /// # Errors
    /// The errors of [`FunctionApproximation::problems`];
    /// [`ErrorKind::SchoenbergWhitney`] if the samples do not determine every coefficient;
    /// [`ErrorKind::NoConvergence`] if no strictly feasible point is found (inconsistent
    /// constraints) or the barrier method does not converge; the errors of
    /// [`crate::minimize`].
    pub fn fit(&self, params: &[f64], values: &[f64]) -> Result<FunctionFit> {
        let problems = self.problems(params, values)?;
        let x_ls = problems[0].unconstrained_solution()?;
        let unconstrained_objective = problems[0].least_squares().value(&x_ls);
        let mut best: Option<(crate::problem::Solution, usize)> = None;
        let mut last_error = None;
        for problem in &problems {
            match solve(problem, std::slice::from_ref(&x_ls), &self.options) {
                Ok(s) => {
                    if best
                        .as_ref()
                        .is_none_or(|(b, _)| s.report.objective < b.report.objective)
                    {
                        best = Some((s, problem.num_linear_constraints()));
                    }
                }
                Err(e) => last_error = Some(e),
            }
        }
        let (solution, num_constraints) = best.ok_or_else(|| {
            last_error.unwrap_or_else(|| Error::new(ErrorKind::NoConvergence, "no solution"))
        })?;
        Ok(FunctionFit {
            spline: BSpline::new(self.knots.clone(), solution.x.as_slice().to_vec())?,
            unconstrained: BSpline::new(self.knots.clone(), x_ls.as_slice().to_vec())?,
            objective: solution.report.objective,
            unconstrained_objective,
            report: solution.report,
            num_constraints,
            patterns: problems.len(),
        })
    }

    /// Fits `samples` uniformly spaced samples of `f` on the domain (both ends included).
    ///
    /// # Errors
    /// [`ErrorKind::TooFewPoints`] for fewer than two samples; the errors of
    /// [`FunctionApproximation::fit`] (a non-finite `f(u)` is
    /// [`ErrorKind::NonFinite`]).
    pub fn fit_function(&self, samples: usize, f: impl Fn(f64) -> f64) -> Result<FunctionFit> {
        let params = uniform_samples(self.knots.domain(), samples)?;
        let values: Vec<f64> = params.iter().map(|&u| f(u)).collect();
        self.fit(&params, &values)
    }

    /// Checks the constraints on any spline of the domain by dense sampling —
    /// independently of the control-point conditions: `samples_per_span` evaluations of the
    /// derivative (by [`BSpline::derivatives`]) in every knot span of the fit inside each
    /// constraint's interval, plus the interval's ends.
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] for a constraint whose order exceeds the degree (see
    /// [`FunctionApproximation::constraint_map`]); [`ErrorKind::InvalidArgument`] for a
    /// refinement of 0 or `samples_per_span = 0`; [`ErrorKind::OutOfDomain`] if the spline
    /// does not cover the constraint intervals.
    pub fn check(
        &self,
        spline: &BSpline<f64, f64>,
        samples_per_span: usize,
    ) -> Result<Vec<ConstraintCheck>> {
        self.validate()?;
        check_samples(samples_per_span)?;
        let mut out = Vec::with_capacity(self.constraints.len());
        for c in &self.constraints {
            let (a, b) = self.interval_of(c);
            let params = span_samples(&self.knots, a, b, samples_per_span);
            let k = c.order();
            let values = params
                .iter()
                .map(|&u| spline.derivatives(u, k).map(|d| d[k]))
                .collect::<Result<Vec<f64>>>()?;
            let violation = match *c {
                FunctionConstraint::Sign { sign, .. } => values
                    .iter()
                    .fold(0.0f64, |m, &v| m.max(-sign.factor() * v)),
                FunctionConstraint::SignChange { from, .. } => {
                    let first = values[0];
                    let last = values[values.len() - 1];
                    (-from.factor() * first).max(from.factor() * last).max(0.0)
                }
            };
            out.push(ConstraintCheck {
                violation,
                sign_changes: spline_geom::sign_changes(&values),
                samples: values.len(),
            });
        }
        Ok(out)
    }
}

/// The sign patterns of a sign change on the coefficient rows of its derived spline: the
/// rows of `G` with `G c < 0` meaning "the first coefficients have `from`, the rest the
/// other sign", one matrix per place of the change; for up to three coefficients, only the
/// ends (the middle one may have either sign).
fn sign_patterns(map: &CsrMatrix<f64>, from: Sign) -> Vec<CsrMatrix<f64>> {
    let n = map.nrows();
    let s = from.factor();
    let pattern = |rows: &[(usize, f64)]| {
        let mut coo = CooMatrix::new(rows.len(), map.ncols());
        for (r, &(i, sign)) in rows.iter().enumerate() {
            let row = map.row(i);
            for (&j, &v) in row.col_indices().iter().zip(row.values()) {
                coo.push(r, j, -sign * v);
            }
        }
        normalized_rows(&CsrMatrix::from(&coo), 1.0)
    };
    if n <= 3 {
        return vec![pattern(&[(0, s), (n - 1, -s)])];
    }
    (0..n - 1)
        .map(|split| {
            let rows: Vec<(usize, f64)> = (0..n)
                .map(|i| (i, if i <= split { s } else { -s }))
                .collect();
            pattern(&rows)
        })
        .collect()
}

/// `count` uniformly spaced parameters on `[a, b]`, both ends included.
pub(crate) fn uniform_samples((a, b): (f64, f64), count: usize) -> Result<Vec<f64>> {
    if count < 2 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!("need at least two samples, got {count}"),
        ));
    }
    #[allow(clippy::cast_precision_loss)]
    let last = (count - 1) as f64;
    #[allow(clippy::cast_precision_loss)]
    Ok((0..count)
        .map(|j| {
            if j + 1 == count {
                b
            } else {
                a + (b - a) * j as f64 / last
            }
        })
        .collect())
}

/// The points `(us[a], vs[b])` of a grid, row after row (`b` fastest).
pub(crate) fn grid_pairs<'a>(
    us: &'a [f64],
    vs: &'a [f64],
) -> impl Iterator<Item = (f64, f64)> + 'a {
    us.iter()
        .flat_map(move |&u| vs.iter().map(move |&v| (u, v)))
}

/// `f` sampled on the grid of `counts.0 × counts.1` [`uniform_samples`] of the rectangle
/// `domains`: the samples in each direction and the values, row after row.
///
/// # Errors
/// As [`uniform_samples`] and `f`.
pub(crate) fn sampled_grid(
    domains: ((f64, f64), (f64, f64)),
    counts: (usize, usize),
    mut f: impl FnMut(f64, f64) -> Result<f64>,
) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>)> {
    let us = uniform_samples(domains.0, counts.0)?;
    let vs = uniform_samples(domains.1, counts.1)?;
    let values = grid_pairs(&us, &vs)
        .map(|(u, v)| f(u, v))
        .collect::<Result<_>>()?;
    Ok((us, vs, values))
}

/// Parameters in `[a, b]`: the knots of `knots` inside, each span split into `per_span`.
pub(crate) fn span_samples(knots: &KnotVector<f64>, a: f64, b: f64, per_span: usize) -> Vec<f64> {
    let mut breaks = vec![a];
    breaks.extend(
        knots
            .breakpoints()
            .into_iter()
            .map(|(k, _)| k)
            .filter(|&k| k > a && k < b),
    );
    breaks.push(b);
    let mut out = Vec::with_capacity((breaks.len() - 1) * per_span + 1);
    for w in breaks.windows(2) {
        #[allow(clippy::cast_precision_loss)]
        out.extend((0..per_span).map(|j| w[0] + (w[1] - w[0]) * j as f64 / per_span as f64));
    }
    out.push(b);
    out
}
