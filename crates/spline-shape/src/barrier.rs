//! A log-barrier interior-point method for smooth inequality-constrained problems on sparse
//! matrices (Boyd & Vandenberghe ch. 11; thesis §5.2).
//!
//! Minimise $f_0(x)$ subject to $f_i(x) < 0$, `i = 1 … m`, by following the central path:
//! for increasing `t`, minimise $t f_0(x) - \sum_i \log(-f_i(x))$ with Newton's method and a
//! backtracking line search that keeps every iterate strictly feasible. The Hessian of a
//! non-convex problem (curvature constraints) can be indefinite: the Newton matrix is then
//! shifted by a multiple of the identity until its Cholesky factorisation succeeds.
//! A phase-I problem finds a strictly feasible start when the given one is not.

use nalgebra::{DMatrix, DVector};
use nalgebra_sparse::factorization::CscCholesky;
use nalgebra_sparse::{CooMatrix, CscMatrix, CsrMatrix};
use spline_core::{Error, ErrorKind, Result};

/// A smooth problem `min f0(x) s.t. f_i(x) < 0` with first and second derivatives.
pub trait BarrierProblem {
    /// The number of unknowns `n`.
    fn dimension(&self) -> usize;
    /// The number of constraints `m`.
    fn num_constraints(&self) -> usize;
    /// $f_0(x)$.
    fn objective(&self, x: &DVector<f64>) -> f64;
    /// $\nabla f_0(x)$.
    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64>;
    /// $\nabla^2 f_0(x)$ (`n × n`, symmetric; both triangles stored).
    fn objective_hessian(&self, x: &DVector<f64>) -> CsrMatrix<f64>;
    /// The constraint values $f_i(x)$; the point is strictly feasible when all are negative.
    fn constraints(&self, x: &DVector<f64>) -> DVector<f64>;
    /// The Jacobian of the constraints (`m × n`): row `i` is $\nabla f_i(x)^T$.
    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64>;
    /// $\sum_i w_i \nabla^2 f_i(x)$, or `None` when every constraint is linear.
    fn weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>>;
    /// Adds $\sum_i w_i \nabla^2 f_i(x)$ to the dense matrix `out` and returns `true`, for
    /// problems that assemble their Hessian blocks faster that way; the default returns
    /// `false` and the solver uses [`BarrierProblem::weighted_constraint_hessian`].
    fn add_weighted_constraint_hessian(
        &self,
        _x: &DVector<f64>,
        _weights: &DVector<f64>,
        _out: &mut DMatrix<f64>,
    ) -> bool {
        false
    }
}

/// Settings of [`minimize`].
#[derive(Clone, Debug)]
pub struct BarrierOptions {
    /// Stop when the duality-gap bound `m / t` is below this.
    pub gap_tolerance: f64,
    /// Stop Newton's method when half the squared Newton decrement is below this times
    /// `1 + |barrier value|`.
    pub newton_tolerance: f64,
    /// Factor by which `t` grows between centring steps (μ).
    pub t_growth: f64,
    /// Initial `t`; `None` chooses `t` so that both terms of the first gradient balance.
    pub t_initial: Option<f64>,
    /// Armijo parameter α ∈ (0, ½).
    pub armijo: f64,
    /// Backtracking factor β ∈ (0, 1).
    pub backtracking: f64,
    /// Newton iterations per centring step.
    pub max_newton_iterations: usize,
    /// Centring steps.
    pub max_outer_iterations: usize,
}

impl Default for BarrierOptions {
    fn default() -> Self {
        Self {
            gap_tolerance: 1e-8,
            newton_tolerance: 1e-10,
            t_growth: 10.0,
            t_initial: None,
            armijo: 0.01,
            backtracking: 0.5,
            max_newton_iterations: 200,
            max_outer_iterations: 60,
        }
    }
}

/// The outcome of [`minimize`].
#[derive(Clone, Debug)]
pub struct BarrierReport {
    /// The solution (strictly feasible).
    pub x: DVector<f64>,
    /// $f_0$ at the solution.
    pub objective: f64,
    /// The final barrier parameter.
    pub t: f64,
    /// The bound `m / t` on the gap to the optimum (for convex problems).
    pub duality_gap: f64,
    /// Centring steps taken.
    pub outer_iterations: usize,
    /// Newton steps taken in total.
    pub newton_iterations: usize,
    /// Centring steps that ended at the Newton iteration limit (then the method went on with
    /// a larger `t` from the improved, strictly feasible iterate). Zero for well-behaved
    /// convex problems.
    pub unfinished_centring_steps: usize,
    /// The largest constraint value at the solution (negative).
    pub max_constraint: f64,
}

/// Minimises `problem` from a strictly feasible `x0`.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] if `x0` has the wrong size or is not strictly feasible
/// (see [`find_feasible`]); [`ErrorKind::NonFinite`] if the problem produces NaN;
/// [`ErrorKind::NoConvergence`] if the iteration limits are reached;
/// [`ErrorKind::SingularSystem`] if no shift makes the Newton matrix positive definite.
pub fn minimize(
    problem: &impl BarrierProblem,
    x0: DVector<f64>,
    options: &BarrierOptions,
) -> Result<BarrierReport> {
    let n = problem.dimension();
    let m = problem.num_constraints();
    if x0.len() != n {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "starting point has {} entries, the problem {n} unknowns",
                x0.len()
            ),
        ));
    }
    let c0 = problem.constraints(&x0);
    if let Some(i) = c0.iter().position(|&c| !(c < 0.0)) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the starting point is not strictly feasible: constraint {i} = {:.3e} ≥ 0",
                c0[i]
            ),
        ));
    }
    let mut x = x0;
    let mut t = match options.t_initial {
        Some(t) => t,
        None => initial_t(problem, &x),
    };
    let mut newton_total = 0;
    let mut unfinished = 0;
    for outer in 1..=options.max_outer_iterations {
        // A centring step that runs out of Newton iterations (non-convex problems can crawl)
        // still leaves a strictly feasible, improved iterate: go on with a larger t.
        match centre(problem, &mut x, t, options, None) {
            Ok(steps) => newton_total += steps,
            Err(e) if e.kind() == ErrorKind::NoConvergence => {
                newton_total += options.max_newton_iterations;
                unfinished += 1;
            }
            Err(e) => return Err(e),
        }
        let gap = if m == 0 { 0.0 } else { m as f64 / t };
        if gap < options.gap_tolerance {
            let c = problem.constraints(&x);
            return Ok(BarrierReport {
                objective: problem.objective(&x),
                x,
                t,
                duality_gap: gap,
                outer_iterations: outer,
                newton_iterations: newton_total,
                unfinished_centring_steps: unfinished,
                max_constraint: c.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            });
        }
        t *= options.t_growth;
    }
    Err(Error::new(
        ErrorKind::NoConvergence,
        format!(
            "the barrier method did not reach the gap {:.1e} in {} centring steps",
            options.gap_tolerance, options.max_outer_iterations
        ),
    ))
}

/// Balances `t ∇f0` against `∇φ` at the start: `t = ‖∇φ‖ / ‖∇f0‖` (clamped to a sane range).
fn initial_t(problem: &impl BarrierProblem, x: &DVector<f64>) -> f64 {
    let g0 = problem.objective_gradient(x);
    let c = problem.constraints(x);
    let jac = problem.constraint_jacobian(x);
    let w = c.map(|ci| 1.0 / -ci);
    let gphi = jac.transpose() * &w;
    let (a, b) = (g0.norm(), gphi.norm());
    if a > 0.0 && b > 0.0 {
        (b / a).clamp(1e-6, 1e6)
    } else {
        1.0
    }
}

/// Value of the barrier objective `t f0 − Σ log(−f_i)`, or `None` outside the domain.
fn barrier_value(problem: &impl BarrierProblem, x: &DVector<f64>, t: f64) -> Option<f64> {
    let c = problem.constraints(x);
    if c.iter().any(|&ci| !(ci < 0.0)) {
        return None;
    }
    let f = t * problem.objective(x) - c.iter().map(|&ci| (-ci).ln()).sum::<f64>();
    f.is_finite().then_some(f)
}

/// At an iterate: the constraints' Jacobian, the weights `1 / (−f_i)` and the gradient of
/// the barrier objective.
struct Gradient {
    jac: CsrMatrix<f64>,
    inv: DVector<f64>,
    gradient: DVector<f64>,
}

/// The gradient of the barrier objective, `t ∇f0 + Σ ∇f_i / (−f_i)`.
fn barrier_gradient(problem: &impl BarrierProblem, x: &DVector<f64>, t: f64) -> Result<Gradient> {
    let c = problem.constraints(x);
    let jac = problem.constraint_jacobian(x);
    let inv = c.map(|ci| 1.0 / -ci);
    let gradient = problem.objective_gradient(x) * t + jac.transpose() * &inv;
    if gradient.iter().any(|g| !g.is_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            "the barrier gradient is not finite",
        ));
    }
    Ok(Gradient { jac, inv, gradient })
}

/// A condition that ends a centring step early.
pub(crate) type StopRule<'a> = &'a dyn Fn(&DVector<f64>) -> bool;

/// Newton's method on the barrier objective for fixed `t`; returns the number of steps.
/// `stop` ends the centring early once an iterate satisfies it.
pub(crate) fn centre(
    problem: &impl BarrierProblem,
    x: &mut DVector<f64>,
    t: f64,
    options: &BarrierOptions,
    stop: Option<StopRule<'_>>,
) -> Result<usize> {
    let n = problem.dimension();
    if n <= DENSE_LIMIT {
        return centre_trust_region(problem, x, t, options, stop);
    }
    for step in 0..options.max_newton_iterations {
        let Gradient { jac, inv, gradient } = barrier_gradient(problem, x, t)?;
        // Hessian: t ∇²f0 + Σ ∇f_i ∇f_iᵀ / f_i² + Σ ∇²f_i / (−f_i). With the curvature of
        // the constraints when that keeps the Newton matrix positive definite; otherwise the
        // Gauss–Newton matrix t∇²f0 + Σ ∇f_i∇f_iᵀ/f_i² (positive semi-definite) with a small
        // shift — the standard remedy for non-convex constraints.
        let mut system = NewtonSystem::new(n);
        for (i, j, v) in problem.objective_hessian(x).triplet_iter() {
            system.add(i, j, t * v);
        }
        for (row, &w) in jac.row_iter().zip(inv.iter()) {
            system.add_outer(row.col_indices(), row.values(), w * w);
        }
        let curvature = problem.weighted_constraint_hessian(x, &inv);
        let direction = match curvature {
            Some(h) => {
                let full = system.with(&h);
                match full.solve_definite(&gradient) {
                    Some(d) => d,
                    None => system.solve_shifted(&gradient)?,
                }
            }
            None => system.solve_shifted(&gradient)?,
        };
        let decrement = -gradient.dot(&direction);
        let f = barrier_value(problem, x, t)
            .ok_or_else(|| Error::new(ErrorKind::NonFinite, "iterate left the barrier domain"))?;
        // Relative to the barrier value: at large t the gradient is a difference of large terms.
        if decrement / 2.0 <= options.newton_tolerance * (1.0 + f.abs()) {
            return Ok(step);
        }
        // Backtracking: stay strictly feasible, then Armijo.
        let slope = gradient.dot(&direction);
        let mut s = 1.0;
        loop {
            let candidate = &*x + &direction * s;
            if let Some(fc) = barrier_value(problem, &candidate, t) {
                if fc <= f + options.armijo * s * slope {
                    *x = candidate;
                    if stop.is_some_and(|stop| stop(x)) {
                        return Ok(step + 1);
                    }
                    break;
                }
            }
            s *= options.backtracking;
            if s < 1e-16 {
                // No progress possible at this t: the point is as central as rounding allows.
                return Ok(step);
            }
        }
    }
    Err(Error::new(
        ErrorKind::NoConvergence,
        format!(
            "Newton's method did not converge in {} steps (t = {t:.3e})",
            options.max_newton_iterations
        ),
    ))
}

/// Newton's method with a trust region on the barrier objective for fixed `t` (dense
/// matrices): the model uses the exact Hessian, constraint curvature included, so that steps
/// along curved (non-convex) constraints are predicted well; the trust region is an ellipsoid
/// in the local metric $M = t\nabla^2 f_0 + \sum_i \nabla f_i \nabla f_i^T / f_i^2$ (the
/// Dikin ellipsoid of radius 1 is feasible for linear constraints), and the subproblem
/// $\min_d g^T d + \tfrac12 d^T H d$, $\lVert d \rVert_M \le \Delta$ is solved exactly by an
/// eigendecomposition of $L^{-1} H L^{-T}$ ($M = L L^T$). Steps that leave the domain or
/// whose actual decrease is poor shrink the region. Returns the number of accepted steps.
fn centre_trust_region(
    problem: &impl BarrierProblem,
    x: &mut DVector<f64>,
    t: f64,
    options: &BarrierOptions,
    stop: Option<StopRule<'_>>,
) -> Result<usize> {
    let n = problem.dimension();
    let mut radius = 1.0;
    let mut accepted = 0;
    let mut f = barrier_value(problem, x, t)
        .ok_or_else(|| Error::new(ErrorKind::NonFinite, "iterate left the barrier domain"))?;
    for _ in 0..options.max_newton_iterations {
        let Gradient { jac, inv, gradient } = barrier_gradient(problem, x, t)?;
        let mut metric = DMatrix::zeros(n, n);
        for (i, j, v) in problem.objective_hessian(x).triplet_iter() {
            metric[(i, j)] += t * v;
        }
        for (row, &w) in jac.row_iter().zip(inv.iter()) {
            let (cols, vals) = (row.col_indices(), row.values());
            for (&ca, &va) in cols.iter().zip(vals) {
                let wa = w * w * va;
                for (&cb, &vb) in cols.iter().zip(vals) {
                    metric[(ca, cb)] += wa * vb;
                }
            }
        }
        let mut hessian = metric.clone();
        if !problem.add_weighted_constraint_hessian(x, &inv, &mut hessian) {
            if let Some(h) = problem.weighted_constraint_hessian(x, &inv) {
                for (i, j, v) in h.triplet_iter() {
                    hessian[(i, j)] += v;
                }
            }
        }
        let Some(factor) = positive_definite_factor(&metric) else {
            return Err(Error::new(
                ErrorKind::SingularSystem,
                "the local metric of the barrier could not be made positive definite",
            ));
        };
        // Decrement in the local metric: gᵀ M⁻¹ g.
        let scaled_gradient = factor
            .l()
            .solve_lower_triangular(&gradient)
            .unwrap_or_else(|| gradient.clone());
        let decrement = scaled_gradient.norm_squared();
        if decrement / 2.0 <= options.newton_tolerance * (1.0 + f.abs()) {
            return Ok(accepted);
        }
        let l = factor.l();
        // The Newton step, when H is positive definite and the step fits in the region: no
        // eigendecomposition needed (the common case near the central path).
        if let Some(h_factor) = hessian.clone().cholesky() {
            let d = h_factor.solve(&(-&gradient));
            let y = l.transpose() * &d;
            if d.iter().all(|v| v.is_finite()) && y.norm() <= radius {
                let predicted = -0.5 * gradient.dot(&d);
                let candidate = &*x + &d;
                let actual = barrier_value(problem, &candidate, t).map(|fc| f - fc);
                let ratio = actual.map_or(-1.0, |a| a / predicted);
                if predicted > 0.0 && ratio > 0.25 {
                    if ratio > 0.75 && y.norm() > 0.99 * radius {
                        radius = (2.0 * radius).min(1e6);
                    }
                    *x = candidate;
                    f -= actual.unwrap_or(0.0);
                    accepted += 1;
                    if stop.is_some_and(|stop| stop(x)) {
                        return Ok(accepted);
                    }
                    continue;
                }
            }
        }
        // H̃ = L⁻¹ H L⁻ᵀ.
        let left = l
            .solve_lower_triangular(&hessian)
            .unwrap_or_else(|| hessian.clone());
        let scaled = l
            .solve_lower_triangular(&left.transpose())
            .unwrap_or_else(|| left.clone());
        let scaled = (&scaled + scaled.transpose()) * 0.5;
        let eigen = scaled.symmetric_eigen();
        let mut improved = false;
        for _ in 0..60 {
            let (y, predicted) = trust_region_step(&eigen, &scaled_gradient, radius);
            if !(predicted > 0.0) {
                return Ok(accepted);
            }
            let d = l
                .transpose()
                .solve_upper_triangular(&y)
                .unwrap_or(y.clone());
            let candidate = &*x + &d;
            let actual = barrier_value(problem, &candidate, t).map(|fc| f - fc);
            let ratio = actual.map_or(-1.0, |a| a / predicted);
            let on_boundary = y.norm() > 0.99 * radius;
            if ratio < 0.25 {
                radius *= 0.25;
            } else if ratio > 0.75 && on_boundary {
                radius = (2.0 * radius).min(1e6);
            }
            if ratio > 1e-4 {
                *x = candidate;
                f -= actual.unwrap_or(0.0);
                accepted += 1;
                improved = true;
                break;
            }
            if radius < 1e-14 {
                // As central as rounding allows.
                return Ok(accepted);
            }
        }
        if !improved {
            return Ok(accepted);
        }
        if stop.is_some_and(|stop| stop(x)) {
            return Ok(accepted);
        }
    }
    Err(Error::new(
        ErrorKind::NoConvergence,
        format!(
            "Newton's method did not converge in {} steps (t = {t:.3e})",
            options.max_newton_iterations
        ),
    ))
}

/// The Cholesky factor of `m`, shifted by a small multiple of its largest diagonal entry if
/// needed.
fn positive_definite_factor(m: &DMatrix<f64>) -> Option<nalgebra::Cholesky<f64, nalgebra::Dyn>> {
    let n = m.nrows();
    let scale = (0..n)
        .map(|i| m[(i, i)].abs())
        .fold(0.0, f64::max)
        .max(1e-300);
    let mut shift = 0.0;
    for _ in 0..20 {
        let mut shifted = m.clone();
        for i in 0..n {
            shifted[(i, i)] += shift;
        }
        if let Some(f) = shifted.cholesky() {
            return Some(f);
        }
        shift = if shift == 0.0 {
            1e-12 * scale
        } else {
            shift * 100.0
        };
    }
    None
}

/// The exact solution of $\min_y \gamma^T y + \tfrac12 y^T \tilde H y$,
/// $\lVert y \rVert \le \Delta$, from the eigendecomposition of `H̃` (Moré–Sorensen by the
/// secular equation, with the hard case), and the predicted decrease.
fn trust_region_step(
    eigen: &nalgebra::SymmetricEigen<f64, nalgebra::Dyn>,
    gradient: &DVector<f64>,
    radius: f64,
) -> (DVector<f64>, f64) {
    let q = &eigen.eigenvectors;
    let lambda = &eigen.eigenvalues;
    let gamma = q.transpose() * gradient;
    let n = lambda.len();
    let lmin = lambda.iter().copied().fold(f64::INFINITY, f64::min);
    let norm_at = |mu: f64| -> f64 {
        gamma
            .iter()
            .zip(lambda.iter())
            .map(|(g, l)| (g / (l + mu)).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let mu = if lmin > 0.0 && norm_at(0.0) <= radius {
        0.0
    } else {
        // ‖y(μ)‖ decreases in μ > −λ_min: bisection on a bracket, then Newton on 1/‖y‖.
        let mut lo = (-lmin).max(0.0);
        let scale = lambda.iter().fold(0.0f64, |m, l| m.max(l.abs())) + gradient.norm() / radius;
        let mut hi = lo + scale.max(1e-300);
        while norm_at(hi) > radius {
            hi = lo + 2.0 * (hi - lo);
        }
        if norm_at(lo * (1.0 + 1e-15) + 1e-300) < radius {
            // Hard case: the minimal-eigenvalue direction is (nearly) orthogonal to γ.
            lo
        } else {
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if norm_at(mid) > radius {
                    lo = mid;
                } else {
                    hi = mid;
                }
                if hi - lo <= 1e-12 * hi {
                    break;
                }
            }
            hi
        }
    };
    let mut y = DVector::zeros(n);
    for k in 0..n {
        let denom = lambda[k] + mu;
        if denom.abs() > 0.0 {
            y -= q.column(k) * (gamma[k] / denom);
        }
    }
    if mu > 0.0 && y.norm() < radius * (1.0 - 1e-8) {
        // Hard case: complete along the eigenvector of the smallest eigenvalue.
        let k = (0..n)
            .min_by(|&a, &b| lambda[a].total_cmp(&lambda[b]))
            .expect("non-empty");
        let v = q.column(k);
        let yy = y.norm_squared();
        let yv = y.dot(&v);
        let tau = -yv + (yv * yv + radius * radius - yy).max(0.0).sqrt();
        y += v * tau;
    }
    let hy = q * DVector::from_iterator(n, (0..n).map(|k| lambda[k] * q.column(k).dot(&y)));
    let predicted = -(gradient.dot(&y) + 0.5 * y.dot(&hy));
    (y, predicted)
}

/// The Newton matrix of one step: dense for small problems (the eraser's curves, the
/// functions of thesis ch. 5), sparse (COO, then a sparse Cholesky factorisation) above
/// [`DENSE_LIMIT`] unknowns.
#[derive(Clone)]
enum NewtonSystem {
    Dense(DMatrix<f64>),
    Sparse(CooMatrix<f64>),
}

/// Problems with at most this many unknowns use dense matrices.
const DENSE_LIMIT: usize = 400;

impl NewtonSystem {
    fn new(n: usize) -> Self {
        if n <= DENSE_LIMIT {
            Self::Dense(DMatrix::zeros(n, n))
        } else {
            Self::Sparse(CooMatrix::new(n, n))
        }
    }

    fn add(&mut self, i: usize, j: usize, v: f64) {
        match self {
            Self::Dense(m) => m[(i, j)] += v,
            Self::Sparse(m) => m.push(i, j, v),
        }
    }

    /// Adds `w · a aᵀ` for a sparse vector `a`.
    fn add_outer(&mut self, cols: &[usize], vals: &[f64], w: f64) {
        for (&ca, &va) in cols.iter().zip(vals) {
            let wa = w * va;
            for (&cb, &vb) in cols.iter().zip(vals) {
                self.add(ca, cb, wa * vb);
            }
        }
    }

    /// This matrix plus `h`.
    fn with(&self, h: &CsrMatrix<f64>) -> Self {
        let mut out = self.clone();
        for (i, j, v) in h.triplet_iter() {
            out.add(i, j, *v);
        }
        out
    }

    /// Solves `H d = −g` if `H` is positive definite.
    fn solve_definite(&self, gradient: &DVector<f64>) -> Option<DVector<f64>> {
        let d = match self {
            Self::Dense(m) => m.clone().cholesky()?.solve(&(-gradient)),
            Self::Sparse(m) => {
                let factor = CscCholesky::factor(&CscMatrix::from(m)).ok()?;
                let d = factor.solve(&(-gradient));
                DVector::from_column_slice(d.as_slice())
            }
        };
        d.iter().all(|v| v.is_finite()).then_some(d)
    }

    /// Solves `H d = −g`, adding `δ I` with growing `δ` while `H` is not positive definite.
    fn solve_shifted(&self, gradient: &DVector<f64>) -> Result<DVector<f64>> {
        let n = gradient.len();
        let scale = match self {
            Self::Dense(m) => (0..n).map(|i| m[(i, i)].abs()).fold(0.0, f64::max),
            Self::Sparse(m) => {
                let csc = CscMatrix::from(m);
                (0..n)
                    .map(|i| csc.get_entry(i, i).map_or(0.0, |e| e.into_value().abs()))
                    .fold(0.0, f64::max)
            }
        }
        .max(1e-300);
        let mut shift = 0.0;
        for _ in 0..40 {
            let mut shifted = self.clone();
            if shift > 0.0 {
                for i in 0..n {
                    shifted.add(i, i, shift);
                }
            }
            if let Some(d) = shifted.solve_definite(gradient) {
                return Ok(d);
            }
            shift = if shift == 0.0 {
                1e-10 * scale
            } else {
                shift * 10.0
            };
        }
        Err(Error::new(
            ErrorKind::SingularSystem,
            "the Newton matrix could not be made positive definite",
        ))
    }
}

/// Phase I: a strictly feasible point near `x0`, found by minimising `s` subject to
/// `f_i(x) < s` from `s = max f_i(x0) + 1` and stopping as soon as `s < −margin`.
/// Returns `x0` unchanged if it is already strictly feasible with that margin.
///
/// # Errors
/// [`ErrorKind::NoConvergence`] if no point with all `f_i < −margin` is found (the
/// constraints may be inconsistent); the errors of [`minimize`].
pub fn find_feasible(
    problem: &impl BarrierProblem,
    x0: DVector<f64>,
    margin: f64,
    options: &BarrierOptions,
) -> Result<DVector<f64>> {
    find_feasible_near(problem, x0, margin, 0.0, options)
}

/// [`find_feasible`] with `s + w f_0(x)` as phase-I objective: the pull towards small
/// `f_0` keeps the search near good points. Non-convex constraints that are homogeneous in
/// `x` (curvature conditions vanish on a curve shrunk to a point) otherwise let phase I
/// drift to a degenerate point where every `f_i` tends to zero.
///
/// # Errors
/// As [`find_feasible`].
pub fn find_feasible_near(
    problem: &impl BarrierProblem,
    x0: DVector<f64>,
    margin: f64,
    objective_weight: f64,
    options: &BarrierOptions,
) -> Result<DVector<f64>> {
    let c = problem.constraints(&x0);
    let worst = c.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if worst < -margin || problem.num_constraints() == 0 {
        return Ok(x0);
    }
    let radius = 1e3 * (1.0 + x0.amax());
    let phase = PhaseOne {
        inner: problem,
        margin,
        centre: x0.clone(),
        radius,
        objective_weight,
    };
    let n = problem.dimension();
    let mut start = DVector::zeros(n + 1);
    start.rows_mut(0, n).copy_from(&x0);
    start[n] = worst + 1.0;
    let mut x = start;
    // On the central path `s ≈ max f_i + m/t`: start where that offset is a tenth of the
    // initial infeasibility, not where the barrier would push `s` up.
    let m = (problem.num_constraints() + 1) as f64;
    let mut t = (10.0 * m / (worst.abs() + 1.0)).max(1.0);
    for _ in 0..options.max_outer_iterations {
        // Centre, stopping as soon as the inner point is strictly feasible.
        let stop = |y: &DVector<f64>| y[n] < -margin;
        // Phase I needs no accurate centring: a few Newton steps per value of t.
        let loose = BarrierOptions {
            max_newton_iterations: 30,
            ..options.clone()
        };
        match centre(&phase, &mut x, t, &loose, Some(&stop)) {
            Ok(_) => {}
            Err(e) if e.kind() == ErrorKind::NoConvergence => {}
            Err(e) => return Err(e),
        }
        if x[n] < -margin {
            return Ok(x.rows(0, n).into_owned());
        }
        t *= options.t_growth;
    }
    Err(Error::new(
        ErrorKind::NoConvergence,
        format!(
            "no strictly feasible point found (best max f_i = {:.3e})",
            x[n]
        ),
    ))
}

/// `min s` over `(x, s)` with `f_i(x) − s < 0`, `s > −2 margin − 1` and `x` in a box around
/// the start (both keep the problem bounded).
struct PhaseOne<'a, P> {
    inner: &'a P,
    margin: f64,
    /// Centre and half-width of the box `|x_j − centre_j| < radius` that keeps phase I
    /// bounded when the feasible set is not.
    centre: DVector<f64>,
    radius: f64,
    /// Weight of `f0` added to the objective `s` ([`find_feasible_near`]).
    objective_weight: f64,
}

impl<P: BarrierProblem> BarrierProblem for PhaseOne<'_, P> {
    fn dimension(&self) -> usize {
        self.inner.dimension() + 1
    }
    fn num_constraints(&self) -> usize {
        self.inner.num_constraints() + 1 + 2 * self.inner.dimension()
    }
    fn objective(&self, x: &DVector<f64>) -> f64 {
        let n = self.inner.dimension();
        let pull = if self.objective_weight > 0.0 {
            self.objective_weight * self.inner.objective(&x.rows(0, n).into_owned())
        } else {
            0.0
        };
        x[n] + pull
    }
    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64> {
        let n = self.inner.dimension();
        let mut g = DVector::zeros(x.len());
        if self.objective_weight > 0.0 {
            let inner = self.inner.objective_gradient(&x.rows(0, n).into_owned());
            g.rows_mut(0, n).copy_from(&(inner * self.objective_weight));
        }
        g[n] = 1.0;
        g
    }
    fn objective_hessian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let n = self.inner.dimension();
        if self.objective_weight == 0.0 {
            return CsrMatrix::zeros(x.len(), x.len());
        }
        let inner = self.inner.objective_hessian(&x.rows(0, n).into_owned());
        let mut coo = CooMatrix::new(n + 1, n + 1);
        for (i, j, v) in inner.triplet_iter() {
            coo.push(i, j, self.objective_weight * v);
        }
        CsrMatrix::from(&coo)
    }
    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        let n = self.inner.dimension();
        let s = x[n];
        let inner = self.inner.constraints(&x.rows(0, n).into_owned());
        let m = inner.len();
        let mut c = DVector::zeros(m + 1 + 2 * n);
        for (i, v) in inner.iter().enumerate() {
            c[i] = v - s;
        }
        c[m] = -s - 2.0 * self.margin - 1.0;
        for j in 0..n {
            let offset = x[j] - self.centre[j];
            c[m + 1 + 2 * j] = offset - self.radius;
            c[m + 2 + 2 * j] = -offset - self.radius;
        }
        c
    }
    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let n = self.inner.dimension();
        let inner = self.inner.constraint_jacobian(&x.rows(0, n).into_owned());
        let m = inner.nrows();
        let mut coo = CooMatrix::new(m + 1 + 2 * n, n + 1);
        for (i, j, v) in inner.triplet_iter() {
            coo.push(i, j, *v);
        }
        for i in 0..m {
            coo.push(i, n, -1.0);
        }
        coo.push(m, n, -1.0);
        for j in 0..n {
            coo.push(m + 1 + 2 * j, j, 1.0);
            coo.push(m + 2 + 2 * j, j, -1.0);
        }
        CsrMatrix::from(&coo)
    }
    fn weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        let n = self.inner.dimension();
        let w = weights.rows(0, self.inner.num_constraints()).into_owned();
        self.inner
            .weighted_constraint_hessian(&x.rows(0, n).into_owned(), &w)
            .map(|h| {
                let mut coo = CooMatrix::new(n + 1, n + 1);
                for (i, j, v) in h.triplet_iter() {
                    coo.push(i, j, *v);
                }
                CsrMatrix::from(&coo)
            })
    }
}
