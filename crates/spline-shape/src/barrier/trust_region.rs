//! The dense path: Newton's method with a trust region in the barrier's local metric.

use super::objective::{barrier_gradient, barrier_value, iterate_value};
use super::options::{BarrierOptions, StallWatch, StopRule};
use super::problem::BarrierProblem;
use super::workspace::{Workspace, add_sparse};
use nalgebra::{Cholesky, DMatrix, DVector, Dyn};
use spline_core::{Error, ErrorKind, Result};

/// Newton's method with a trust region on the barrier objective for fixed `t` (dense
/// matrices): the model uses the exact Hessian, constraint curvature included, so that steps
/// along curved (non-convex) constraints are predicted well; the trust region is an ellipsoid
/// in the local metric $M = t\nabla^2 f_0 + \sum_i \nabla f_i \nabla f_i^T / f_i^2$ (the
/// Dikin ellipsoid of radius 1 is feasible for linear constraints), and the subproblem
/// $\min_d g^T d + \tfrac12 d^T H d$, $\lVert d \rVert_M \le \Delta$ is solved by
/// Moré–Sorensen's factorisations of $H + \lambda M$ from the previous multiplier, or exactly by
/// an eigendecomposition of $L^{-1} H L^{-T}$ ($M = L L^T$) where those do not settle. Steps that leave the domain or
/// whose actual decrease is poor shrink the region; the centring ends early when the steps
/// crawl ([`BarrierOptions::stall_tolerance`]). Returns the number of accepted steps.
pub(super) fn centre_trust_region(
    problem: &impl BarrierProblem,
    x: &mut DVector<f64>,
    t: f64,
    options: &BarrierOptions,
    stop: Option<StopRule<'_>>,
    ws: &mut Workspace,
) -> Result<usize> {
    let mut radius = 1.0;
    let mut accepted = 0;
    let mut f = iterate_value(problem, x, t, &mut ws.c_trial)?;
    let mut watch = StallWatch::new(options);
    // The trust-region multiplier of the last boundary step: Moré–Sorensen's start.
    let mut multiplier = 0.0;
    for _ in 0..options.max_newton_iterations {
        barrier_gradient(problem, x, t, ws)?;
        let metric = &mut ws.metric;
        metric.fill(0.0);
        problem.add_objective_hessian(x, t, metric);
        add_weighted_outer_products(metric, &ws.jac, &ws.inv);
        ws.hessian
            .as_mut_slice()
            .copy_from_slice(ws.metric.as_slice());
        if !problem.add_weighted_constraint_hessian(x, &ws.inv, &mut ws.hessian)
            && problem.weighted_constraint_hessian_into(x, &ws.inv, &mut ws.curvature)
        {
            if let Some(h) = &ws.curvature {
                add_sparse(&mut ws.hessian, h, 1.0);
            }
        }
        if !positive_definite_factor(&ws.metric, &mut ws.factor_storage, &mut ws.l) {
            return Err(Error::new(
                ErrorKind::SingularSystem,
                "the local metric of the barrier could not be made positive definite",
            ));
        }
        // Decrement in the local metric: gᵀ M⁻¹ g.
        ws.scaled_gradient.copy_from(&ws.gradient);
        if !ws.l.solve_lower_triangular_mut(&mut ws.scaled_gradient) {
            ws.scaled_gradient.copy_from(&ws.gradient);
        }
        let decrement = ws.scaled_gradient.norm_squared();
        if decrement / 2.0 <= options.newton_tolerance * (1.0 + f.abs()) {
            return Ok(accepted);
        }
        ws.l.transpose_to(&mut ws.lt);
        // The Newton step, when H is positive definite and the step fits in the region: no
        // eigendecomposition needed (the common case near the central path).
        if newton_step(ws) {
            let d = &ws.direction;
            ws.y.gemv(1.0, &ws.lt, d, 0.0);
            if d.iter().all(|v| v.is_finite()) && ws.y.norm() <= radius {
                let predicted = -0.5 * ws.gradient.dot(d);
                ws.candidate.copy_from(x);
                ws.candidate += d;
                let actual =
                    barrier_value(problem, &ws.candidate, t, &mut ws.c_trial).map(|fc| f - fc);
                let ratio = actual.map_or(-1.0, |a| a / predicted);
                if predicted > 0.0 && ratio > 0.25 {
                    if ratio > 0.75 && ws.y.norm() > 0.99 * radius {
                        radius = (2.0 * radius).min(1e6);
                    }
                    x.copy_from(&ws.candidate);
                    let before = f;
                    f -= actual.unwrap_or(0.0);
                    accepted += 1;
                    if stop.is_some_and(|stop| stop(x)) || watch.crawled(before, f) {
                        return Ok(accepted);
                    }
                    continue;
                }
            }
        }
        // The step on the region's boundary (or inside it, H indefinite): Moré–Sorensen's
        // factorisations of H + λM, warm-started from the previous λ when the region shrinks;
        // where they do not settle (the hard case), the exact solution by the
        // eigendecomposition of H̃ = L⁻¹ H L⁻ᵀ, kept for the remaining radii of this step.
        let mut eigen: Option<nalgebra::SymmetricEigen<f64, Dyn>> = None;
        let mut improved = false;
        let mut crawled = false;
        let mut stop_here = false;
        for _ in 0..60 {
            let from_factorisations = if eigen.is_none() {
                more_sorensen(ws, radius, &mut multiplier)
            } else {
                None
            };
            let (predicted, step_norm) = match from_factorisations {
                Some(found) => found,
                None => {
                    let eigen = eigen.get_or_insert_with(|| scaled_eigen(ws));
                    let (predicted, mu) = trust_region_step(eigen, radius, ws);
                    multiplier = mu;
                    ws.direction.copy_from(&ws.y);
                    if !ws.lt.solve_upper_triangular_mut(&mut ws.direction) {
                        ws.direction.copy_from(&ws.y);
                    }
                    (predicted, ws.y.norm())
                }
            };
            if !(predicted > 0.0) {
                stop_here = true;
                break;
            }
            ws.candidate.copy_from(x);
            ws.candidate += &ws.direction;
            let actual = barrier_value(problem, &ws.candidate, t, &mut ws.c_trial).map(|fc| f - fc);
            let ratio = actual.map_or(-1.0, |a| a / predicted);
            let on_boundary = step_norm > 0.99 * radius;
            if ratio < 0.25 {
                radius *= 0.25;
            } else if ratio > 0.75 && on_boundary {
                radius = (2.0 * radius).min(1e6);
            }
            if ratio > 1e-4 {
                x.copy_from(&ws.candidate);
                let before = f;
                f -= actual.unwrap_or(0.0);
                accepted += 1;
                improved = true;
                crawled = watch.crawled(before, f);
                break;
            }
            if radius < 1e-14 {
                // As central as rounding allows.
                stop_here = true;
                break;
            }
        }
        if let Some(eigen) = eigen {
            ws.eigen_storage = Some(eigen.eigenvectors);
        }
        if stop_here || !improved || crawled {
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

/// Adds $\sum_i w_i^2 \nabla f_i \nabla f_i^T$ to `metric` (the Jacobian's sparse rows and
/// the weights `w_i = 1/f_i`). Consecutive rows with the same columns (the conditions of one
/// piece, the distances of data points on one span) are summed in a small dense block
/// first, `(w² ∂_a f_i) ∂_b f_i` row after row, and the block is added to the matrix once:
/// the scattered updates of the (column-major) matrix happen once per group, not per row.
fn add_weighted_outer_products(
    metric: &mut DMatrix<f64>,
    jacobian: &super::workspace::SparseRows,
    weights: &DVector<f64>,
) {
    const SHORT_ROW: usize = 32;
    let n = metric.nrows();
    let data = metric.as_mut_slice();
    let mut scaled = [0.0; SHORT_ROW];
    let mut block = [0.0; SHORT_ROW * SHORT_ROW];
    let mut group: &[usize] = &[];
    let flush = |data: &mut [f64], group: &[usize], block: &mut [f64]| {
        if group.is_empty() {
            return;
        }
        for (&cb, block_column) in group.iter().zip(block.chunks_exact_mut(group.len())) {
            let column = &mut data[cb * n..(cb + 1) * n];
            for (&ca, v) in group.iter().zip(block_column.iter_mut()) {
                column[ca] += *v;
                *v = 0.0;
            }
        }
    };
    for ((cols, vals), &w) in jacobian.rows().zip(weights.iter()) {
        if cols.len() > SHORT_ROW {
            for (&ca, &va) in cols.iter().zip(vals) {
                let wa = w * w * va;
                for (&cb, &vb) in cols.iter().zip(vals) {
                    data[ca + cb * n] += wa * vb;
                }
            }
            continue;
        }
        if cols != group {
            flush(data, group, &mut block[..group.len() * group.len()]);
            group = cols;
        }
        let k = cols.len();
        if k == 0 {
            continue;
        }
        for (s, &v) in scaled.iter_mut().zip(vals) {
            *s = w * w * v;
        }
        let scaled = &scaled[..k];
        for (block_column, &vb) in block[..k * k].chunks_exact_mut(k).zip(vals) {
            for (b, &wa) in block_column.iter_mut().zip(scaled) {
                *b += wa * vb;
            }
        }
    }
    flush(data, group, &mut block[..group.len() * group.len()]);
}

/// Factorisations of `H + λM` that Moré–Sorensen's iteration may take for one radius.
const MORE_SORENSEN_STEPS: usize = 8;

/// How close to the radius the step's length in the metric must come.
const MORE_SORENSEN_TOLERANCE: f64 = 1e-8;

/// The trust-region step by Moré–Sorensen's method in the metric `M`: the `λ ≥ 0` with
/// `H + λM` positive definite and $\lVert d(\lambda) \rVert_M = \Delta$ for
/// $d(\lambda) = -(H + \lambda M)^{-1} g$ (or `λ = 0` with the step inside the region), by
/// Newton's method on $1/\lVert d \rVert_M - 1/\Delta$ from `lambda` — the multiplier of
/// the previous step, which changes little from one Newton step to the next (updated to the
/// one found). Each iterate costs one Cholesky factorisation (`n³/3`), against the
/// eigendecomposition's tens of `n³`. The step goes into `ws.direction`; returns the
/// predicted decrease and `‖d‖_M`, or `None` when the start is not positive definite or the
/// iteration does not settle in [`MORE_SORENSEN_STEPS`] (from the right of the root the
/// Newton iterate can overshoot past the pole; the hard case), for the eigendecomposition to
/// solve exactly.
fn more_sorensen(ws: &mut Workspace, radius: f64, lambda: &mut f64) -> Option<(f64, f64)> {
    let n = ws.n;
    let mut current = *lambda;
    for _ in 0..MORE_SORENSEN_STEPS {
        let mut storage = ws
            .hessian_storage
            .take()
            .unwrap_or_else(|| DMatrix::zeros(n, n));
        // H + λM over the contiguous storage (nalgebra's element iterators step column by
        // column and do not vectorise).
        let (target, hessian) = (storage.as_mut_slice(), ws.hessian.as_slice());
        if current > 0.0 {
            for ((s, &h), &m) in target.iter_mut().zip(hessian).zip(ws.metric.as_slice()) {
                *s = h + current * m;
            }
        } else {
            target.copy_from_slice(hessian);
        }
        let factor = match cholesky_in(storage) {
            Ok(factor) => factor,
            Err(storage) => {
                ws.hessian_storage = Some(storage);
                return None;
            }
        };
        ws.direction.copy_from(&ws.gradient);
        ws.direction.neg_mut();
        factor.solve_mut(&mut ws.direction);
        ws.hy.gemv(1.0, &ws.metric, &ws.direction, 0.0);
        let norm = ws.direction.dot(&ws.hy).max(0.0).sqrt();
        if !norm.is_finite() || norm == 0.0 {
            ws.hessian_storage = Some(factor.unpack_dirty());
            return None;
        }
        if (norm - radius).abs() <= MORE_SORENSEN_TOLERANCE * radius
            || (current == 0.0 && norm <= radius)
        {
            ws.hessian_storage = Some(factor.unpack_dirty());
            *lambda = current;
            ws.hy.gemv(1.0, &ws.hessian, &ws.direction, 0.0);
            let predicted = -(ws.gradient.dot(&ws.direction) + 0.5 * ws.direction.dot(&ws.hy));
            return Some((predicted, norm));
        }
        // Newton's step on 1/‖d‖ − 1/Δ: ‖d‖² / ‖R⁻¹ M d‖² · (‖d‖ − Δ) / Δ.
        ws.gamma.copy_from(&ws.hy);
        let solved = factor.l_dirty().solve_lower_triangular_mut(&mut ws.gamma);
        ws.hessian_storage = Some(factor.unpack_dirty());
        let w2 = ws.gamma.norm_squared();
        if !solved || !(w2 > 0.0) {
            return None;
        }
        current = (current + norm * norm / w2 * (norm - radius) / radius).max(0.0);
    }
    None
}

/// The eigendecomposition of `H̃ = L⁻¹ H L⁻ᵀ` (symmetrised), with the transposed eigenvectors
/// in `ws.qt`. nalgebra's decomposition has no in-place form: it allocates its own few
/// vectors, and this path hands it the storage of the previous eigenvectors.
fn scaled_eigen(ws: &mut Workspace) -> nalgebra::SymmetricEigen<f64, Dyn> {
    ws.left.copy_from(&ws.hessian);
    if !ws.l.solve_lower_triangular_mut(&mut ws.left) {
        ws.left.copy_from(&ws.hessian);
    }
    ws.left.transpose_to(&mut ws.scaled);
    if !ws.l.solve_lower_triangular_mut(&mut ws.scaled) {
        ws.scaled.copy_from(&ws.left);
    }
    let mut symmetric = ws
        .eigen_storage
        .take()
        .unwrap_or_else(|| DMatrix::zeros(ws.n, ws.n));
    for j in 0..ws.n {
        for i in 0..ws.n {
            symmetric[(i, j)] = (ws.scaled[(i, j)] + ws.scaled[(j, i)]) * 0.5;
        }
    }
    let eigen = symmetric.symmetric_eigen();
    super::workspace::count_eigendecomposition();
    eigen.eigenvectors.transpose_to(&mut ws.qt);
    eigen
}

/// The Newton direction `H d = −g` into the workspace's direction, if the Hessian is
/// positive definite (its Cholesky factorisation in the workspace's storage).
fn newton_step(ws: &mut Workspace) -> bool {
    let mut storage = ws
        .hessian_storage
        .take()
        .unwrap_or_else(|| DMatrix::zeros(ws.n, ws.n));
    storage
        .as_mut_slice()
        .copy_from_slice(ws.hessian.as_slice());
    let factor = match cholesky_in(storage) {
        Ok(factor) => factor,
        Err(storage) => {
            ws.hessian_storage = Some(storage);
            return false;
        }
    };
    ws.direction.copy_from(&ws.gradient);
    ws.direction.neg_mut();
    factor.solve_mut(&mut ws.direction);
    ws.hessian_storage = Some(factor.unpack_dirty());
    true
}

/// The Cholesky factorisation of `m` in its own storage, or the storage back when `m` is not
/// positive definite (nalgebra's `cholesky()` drops it then, and the next attempt would
/// allocate). `Cholesky::new_unchecked` runs the same arithmetic as `Cholesky::new`, which
/// fails at the first pivot that is zero, negative or NaN; such a pivot leaves a diagonal
/// entry of the factor that is not positive (its square root: zero or NaN), and
/// the columns before it are those of `new`, so "every diagonal entry positive" is exactly
/// `new`'s success, with the same factor.
fn cholesky_in(m: DMatrix<f64>) -> std::result::Result<Cholesky<f64, Dyn>, DMatrix<f64>> {
    let factor = Cholesky::new_unchecked(m);
    let l = factor.l_dirty();
    if (0..l.nrows()).all(|i| l[(i, i)] > 0.0) {
        Ok(factor)
    } else {
        Err(factor.unpack_dirty())
    }
}

/// The Cholesky factor of `m`, shifted by a small multiple of its largest diagonal entry if
/// needed, into `l` (lower triangle, zeros above); `storage` is the factorisation's memory.
/// `false` if no shift makes `m` positive definite.
fn positive_definite_factor(
    m: &DMatrix<f64>,
    storage: &mut Option<DMatrix<f64>>,
    l: &mut DMatrix<f64>,
) -> bool {
    let n = m.nrows();
    let scale = (0..n)
        .map(|i| m[(i, i)].abs())
        .fold(0.0, f64::max)
        .max(1e-300);
    let mut shift = 0.0;
    for _ in 0..20 {
        let mut shifted = storage.take().unwrap_or_else(|| DMatrix::zeros(n, n));
        shifted.as_mut_slice().copy_from_slice(m.as_slice());
        for i in 0..n {
            shifted[(i, i)] += shift;
        }
        match cholesky_in(shifted) {
            Ok(f) => {
                l.copy_from(f.l_dirty());
                l.fill_upper_triangle(0.0, 1);
                *storage = Some(f.unpack_dirty());
                return true;
            }
            Err(shifted) => *storage = Some(shifted),
        }
        shift = if shift == 0.0 {
            1e-12 * scale
        } else {
            shift * 100.0
        };
    }
    false
}

/// The exact solution of $\min_y \gamma^T y + \tfrac12 y^T \tilde H y$,
/// $\lVert y \rVert \le \Delta$, from the eigendecomposition of `H̃` (Moré–Sorensen by the
/// secular equation, with the hard case), into `ws.y` (the gradient is `ws.scaled_gradient`,
/// `ws.qt` the transposed eigenvectors); returns the predicted decrease and the multiplier
/// `μ` (the `λ` of `H + λM`).
fn trust_region_step(
    eigen: &nalgebra::SymmetricEigen<f64, nalgebra::Dyn>,
    radius: f64,
    ws: &mut Workspace,
) -> (f64, f64) {
    let gradient = &ws.scaled_gradient;
    let q = &eigen.eigenvectors;
    let lambda = &eigen.eigenvalues;
    ws.gamma.gemv(1.0, &ws.qt, gradient, 0.0);
    let gamma = &ws.gamma;
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
    let y = &mut ws.y;
    y.fill(0.0);
    for k in 0..n {
        let denom = lambda[k] + mu;
        if denom.abs() > 0.0 {
            let s = gamma[k] / denom;
            for (yi, qi) in y.iter_mut().zip(q.column(k).iter()) {
                *yi -= qi * s;
            }
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
        for (yi, vi) in y.iter_mut().zip(v.iter()) {
            *yi += vi * tau;
        }
    }
    for k in 0..n {
        ws.weighted[k] = lambda[k] * q.column(k).dot(&*y);
    }
    ws.hy.gemv(1.0, q, &ws.weighted, 0.0);
    (-(gradient.dot(&*y) + 0.5 * y.dot(&ws.hy)), mu)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grouped sums are `Jᵀ diag(w²) J` of the dense Jacobian (to rounding): runs of
    /// rows with the same columns, rows whose columns change, an empty row, a row longer
    /// than the block, columns out of order (a closed curve's wrapped ones sorted) and
    /// the matrix's earlier contents kept.
    #[test]
    fn grouped_outer_products_are_the_dense_product() {
        use super::super::workspace::SparseRows;
        let n = 50;
        let mut seed = 0x5851_f42d_4c95_7f2d_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut rows = SparseRows::new(n);
        let mut dense = DMatrix::zeros(0, n);
        let patterns: Vec<Vec<usize>> = vec![
            (4..12).chain([40]).collect(),
            (4..12).chain([40]).collect(),
            (4..12).chain([40]).collect(),
            (6..14).collect(),
            vec![],
            (6..14).collect(),
            (0..40).collect(),
            vec![0, 1, 2, 3, 46, 47, 48, 49],
            vec![0, 1, 2, 3, 46, 47, 48, 49],
            (10..18).chain([41]).collect(),
        ];
        for cols in &patterns {
            let row = dense.nrows();
            dense = dense.insert_row(row, 0.0);
            for &c in cols {
                let v = next();
                rows.push(c, v);
                dense[(row, c)] = v;
            }
            rows.end_row();
        }
        let weights = DVector::from_fn(
            patterns.len(),
            |i, _| if i == 2 { 0.0 } else { 1.0 + next() },
        );
        let start = DMatrix::from_fn(n, n, |i, j| (i + 2 * j) as f64 * 0.01);
        let mut metric = start.clone();
        add_weighted_outer_products(&mut metric, &rows, &weights);
        let w2 = DMatrix::from_diagonal(&weights.map(|w| w * w));
        let expected = start + dense.transpose() * w2 * &dense;
        let error = (&metric - &expected).abs().max();
        assert!(error <= 1e-14, "largest difference {error:e}");
        assert_eq!(metric[(20, 45)], expected[(20, 45)], "untouched entry");
    }

    /// `cholesky_in` succeeds exactly when nalgebra's `cholesky()` does, with the same factor
    /// bit for bit, on positive definite, semi-definite, indefinite and non-finite matrices.
    #[test]
    fn cholesky_in_is_nalgebras_cholesky() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let (mut successes, mut failures) = (0, 0);
        for case in 0..400 {
            let n = 1 + case % 9;
            let a = DMatrix::from_fn(n, n, |_, _| next());
            let mut m = &a * a.transpose();
            match case % 4 {
                0 => {}
                1 => m[(n / 2, n / 2)] -= 0.3 * n as f64,
                2 => {
                    let v = DVector::from_fn(n, |_, _| next());
                    m = &v * v.transpose();
                }
                _ => m[(n - 1, 0)] = if case % 8 == 3 { f64::NAN } else { 2.0 },
            }
            if case % 4 == 3 {
                m[(0, n - 1)] = m[(n - 1, 0)];
            }
            let expected = m.clone().cholesky();
            match (cholesky_in(m.clone()), expected) {
                (Ok(ours), Some(theirs)) => {
                    assert_eq!(ours.unpack_dirty(), theirs.unpack_dirty(), "case {case}");
                    successes += 1;
                }
                (Err(_), None) => failures += 1,
                (ours, theirs) => panic!(
                    "case {case}: ours {}, nalgebra's {}",
                    ours.is_ok(),
                    theirs.is_some()
                ),
            }
        }
        assert!(
            successes > 100 && failures > 100,
            "{successes} / {failures}"
        );
    }

    /// Moré–Sorensen's step is the eigendecomposition's exact step (to 1e-6) wherever it
    /// settles: random metrics, definite and indefinite Hessians, radii inside and beyond
    /// the Newton step, started at the exact multiplier, above it, below it and at zero;
    /// where it does not settle it says so (`None`) rather than return another step.
    #[test]
    fn more_sorensen_is_the_exact_step() {
        use crate::barrier::Workspace;
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let (mut settled, mut declined) = (0, 0);
        for case in 0..400 {
            let n = 2 + case % 9;
            let mut ws = Workspace::default();
            ws.prepare(n, 0, true);
            let a = DMatrix::from_fn(n, n, |_, _| next());
            let metric = &a * a.transpose() + DMatrix::identity(n, n) * 0.1;
            let b = DMatrix::from_fn(n, n, |_, _| next());
            let curvature = (&b + b.transpose()) * [0.0, 0.2, 0.4, 0.6, 0.8][case % 5];
            ws.metric.copy_from(&metric);
            ws.hessian.copy_from(&(&metric + curvature));
            ws.gradient.copy_from(&DVector::from_fn(n, |_, _| next()));
            assert!(positive_definite_factor(
                &ws.metric,
                &mut ws.factor_storage,
                &mut ws.l
            ));
            ws.l.transpose_to(&mut ws.lt);
            ws.scaled_gradient.copy_from(&ws.gradient);
            assert!(ws.l.solve_lower_triangular_mut(&mut ws.scaled_gradient));
            let radius = [0.05, 0.3, 1.0, 4.0][case % 4];
            let eigen = scaled_eigen(&mut ws);
            let (exact_decrease, mu) = trust_region_step(&eigen, radius, &mut ws);
            let mut exact = ws.y.clone();
            assert!(ws.lt.solve_upper_triangular_mut(&mut exact));
            let mut lambda = [mu, 1.5 * mu + 0.1, 0.7 * mu, 0.0][(case / 4) % 4];
            match more_sorensen(&mut ws, radius, &mut lambda) {
                Some((decrease, norm)) => {
                    let scale = exact.norm().max(1e-12);
                    assert!(
                        (&ws.direction - &exact).norm() <= 1e-6 * scale,
                        "case {case}: {} vs {}",
                        ws.direction,
                        exact
                    );
                    assert!(
                        (decrease - exact_decrease).abs() <= 1e-6 * exact_decrease.abs(),
                        "case {case}: {decrease} vs {exact_decrease}"
                    );
                    assert!(norm <= radius * (1.0 + 1e-8), "case {case}");
                    assert!((lambda - mu).abs() <= 1e-5 * (1.0 + mu), "case {case}");
                    settled += 1;
                }
                None => declined += 1,
            }
        }
        assert!(settled > 250, "{settled} settled, {declined} declined");
    }
}
