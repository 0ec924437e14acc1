//! The dense path: Newton's method with a trust region in the barrier's local metric.

use super::{BarrierOptions, BarrierProblem, Gradient, StopRule, barrier_gradient, barrier_value};
use nalgebra::{DMatrix, DVector};
use spline_core::{Error, ErrorKind, Result};

/// Newton's method with a trust region on the barrier objective for fixed `t` (dense
/// matrices): the model uses the exact Hessian, constraint curvature included, so that steps
/// along curved (non-convex) constraints are predicted well; the trust region is an ellipsoid
/// in the local metric $M = t\nabla^2 f_0 + \sum_i \nabla f_i \nabla f_i^T / f_i^2$ (the
/// Dikin ellipsoid of radius 1 is feasible for linear constraints), and the subproblem
/// $\min_d g^T d + \tfrac12 d^T H d$, $\lVert d \rVert_M \le \Delta$ is solved exactly by an
/// eigendecomposition of $L^{-1} H L^{-T}$ ($M = L L^T$). Steps that leave the domain or
/// whose actual decrease is poor shrink the region. Returns the number of accepted steps.
pub(super) fn centre_trust_region(
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
