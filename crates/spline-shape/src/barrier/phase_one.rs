//! Phase I: a strictly feasible start.

use super::centring::centre;
use super::options::BarrierOptions;
use super::problem::BarrierProblem;
use super::workspace::{SparseRows, add_sparse};
use nalgebra::{DMatrix, DVector};
use nalgebra_sparse::{CooMatrix, CsrMatrix};
use spline_core::{Error, ErrorKind, Result};
use std::cell::{RefCell, RefMut};

/// Phase I: a strictly feasible point near `x0`, found by minimising `s` subject to
/// `f_i(x) < s` from `s = max f_i(x0) + 1` and stopping as soon as `s < −margin`.
/// Returns `x0` unchanged if it is already strictly feasible with that margin.
///
/// # Errors
/// [`ErrorKind::NoConvergence`] if no point with all `f_i < −margin` is found (the
/// constraints may be inconsistent); the errors of [`minimize`](super::minimize).
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
        scratch: RefCell::new(PhaseScratch::default()),
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
    // Phase I needs no accurate centring: a few Newton steps per value of t.
    let loose = BarrierOptions {
        max_newton_iterations: 30,
        ..options.clone()
    };
    for _ in 0..options.max_outer_iterations {
        // Centre, stopping as soon as the inner point is strictly feasible.
        let stop = |y: &DVector<f64>| y[n] < -margin;
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
    scratch: RefCell<PhaseScratch>,
}

/// The inner problem's arguments and results, reused between calls.
#[derive(Default)]
struct PhaseScratch {
    x: DVector<f64>,
    weights: DVector<f64>,
    values: DVector<f64>,
    rows: SparseRows,
    dense: DMatrix<f64>,
    sparse: Option<CsrMatrix<f64>>,
    sparse_objective: Option<CsrMatrix<f64>>,
}

/// `scale · inner` bordered by an empty last row and column, into `out` (in place when it
/// has that pattern already).
fn bordered(inner: &CsrMatrix<f64>, scale: f64, out: &mut Option<CsrMatrix<f64>>) {
    let (n, nnz) = (inner.nrows(), inner.nnz());
    match out {
        Some(m)
            if m.nrows() == n + 1
                && m.nnz() == nnz
                && m.row_offsets()[..=n] == *inner.row_offsets()
                && m.col_indices() == inner.col_indices() =>
        {
            for (o, v) in m.values_mut().iter_mut().zip(inner.values()) {
                *o = scale * v;
            }
        }
        _ => {
            let mut offsets = inner.row_offsets().to_vec();
            offsets.push(nnz);
            let values = inner.values().iter().map(|v| scale * v).collect();
            *out = Some(
                CsrMatrix::try_from_csr_data(
                    n + 1,
                    n + 1,
                    offsets,
                    inner.col_indices().to_vec(),
                    values,
                )
                .expect("the inner pattern, bordered"),
            );
        }
    }
}

impl PhaseScratch {
    /// The first `m` of `weights` (the inner problem's constraints') in `self.weights`.
    fn inner_weights(&mut self, weights: &DVector<f64>, m: usize) {
        if self.weights.len() != m {
            self.weights = DVector::zeros(m);
        }
        self.weights.copy_from(&weights.rows(0, m));
    }

    /// `self.dense`, `n × n` and zero.
    fn zero_dense(&mut self, n: usize) {
        if self.dense.nrows() != n {
            self.dense = DMatrix::zeros(n, n);
        }
        self.dense.fill(0.0);
    }

    /// Adds `f(v)` to `out` for every entry `v ≠ 0` of `self.dense` (`n × n`), column after
    /// column.
    fn add_dense_to(&self, n: usize, out: &mut DMatrix<f64>, f: impl Fn(f64) -> f64) {
        for j in 0..n {
            for i in 0..n {
                let v = self.dense[(i, j)];
                if v != 0.0 {
                    out[(i, j)] += f(v);
                }
            }
        }
    }
}

impl<P: BarrierProblem> PhaseOne<'_, P> {
    /// The scratch memory, with the inner problem's variables of `x` in it.
    fn scratch_at(&self, x: &DVector<f64>) -> RefMut<'_, PhaseScratch> {
        let n = self.inner.dimension();
        let mut scratch = self.scratch.borrow_mut();
        if scratch.x.len() != n {
            scratch.x = DVector::zeros(n);
        }
        scratch.x.copy_from(&x.rows(0, n));
        scratch
    }

    /// The constraints at `x = (y, s)` into `out` from the inner ones `inner` at `y`:
    /// `f_i(y) − s`, the bound `−s − 2 margin − 1` on `s`, then the box `±(y_j − centre_j) −
    /// radius` coordinate after coordinate.
    fn constraints_from(&self, x: &DVector<f64>, inner: &DVector<f64>, out: &mut DVector<f64>) {
        let n = self.inner.dimension();
        let m = inner.len();
        let s = x[n];
        for (i, v) in inner.iter().enumerate() {
            out[i] = v - s;
        }
        out[m] = -s - 2.0 * self.margin - 1.0;
        for j in 0..n {
            let offset = x[j] - self.centre[j];
            out[m + 1 + 2 * j] = offset - self.radius;
            out[m + 2 + 2 * j] = -offset - self.radius;
        }
    }
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
        let inner = self.inner.constraints(&x.rows(0, n).into_owned());
        let mut c = DVector::zeros(inner.len() + 1 + 2 * n);
        self.constraints_from(x, &inner, &mut c);
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

    fn objective_gradient_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        let n = self.inner.dimension();
        out.fill(0.0);
        if self.objective_weight > 0.0 {
            let mut scratch = self.scratch_at(x);
            let s = &mut *scratch;
            if s.values.len() != n {
                s.values = DVector::zeros(n);
            }
            self.inner.objective_gradient_into(&s.x, &mut s.values);
            for (o, v) in out.rows_mut(0, n).iter_mut().zip(s.values.iter()) {
                *o = v * self.objective_weight;
            }
        }
        out[n] = 1.0;
    }

    fn add_objective_hessian(&self, x: &DVector<f64>, scale: f64, out: &mut DMatrix<f64>) {
        if self.objective_weight == 0.0 {
            return;
        }
        let n = self.inner.dimension();
        let mut scratch = self.scratch_at(x);
        let s = &mut *scratch;
        // The inner Hessian first (as its own matrix), then weighted and scaled entry by
        // entry: the sums of the owned form.
        s.zero_dense(n);
        self.inner.add_objective_hessian(&s.x, 1.0, &mut s.dense);
        s.add_dense_to(n, out, |v| scale * (self.objective_weight * v));
    }

    fn objective_hessian_into(&self, x: &DVector<f64>, out: &mut Option<CsrMatrix<f64>>) {
        let n = self.inner.dimension();
        if self.objective_weight == 0.0 {
            if !out
                .as_ref()
                .is_some_and(|m| m.nrows() == n + 1 && m.nnz() == 0)
            {
                *out = Some(CsrMatrix::zeros(n + 1, n + 1));
            }
            return;
        }
        let mut scratch = self.scratch_at(x);
        let s = &mut *scratch;
        self.inner
            .objective_hessian_into(&s.x, &mut s.sparse_objective);
        if let Some(h) = &s.sparse_objective {
            bordered(h, self.objective_weight, out);
        }
    }

    fn weighted_constraint_hessian_into(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
        out: &mut Option<CsrMatrix<f64>>,
    ) -> bool {
        let mut scratch = self.scratch_at(x);
        let s = &mut *scratch;
        s.inner_weights(weights, self.inner.num_constraints());
        if !self
            .inner
            .weighted_constraint_hessian_into(&s.x, &s.weights, &mut s.sparse)
        {
            return false;
        }
        if let Some(h) = &s.sparse {
            bordered(h, 1.0, out);
        }
        true
    }

    fn constraints_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        let m = self.inner.num_constraints();
        let mut scratch = self.scratch_at(x);
        let sc = &mut *scratch;
        if sc.values.len() != m {
            sc.values = DVector::zeros(m);
        }
        self.inner.constraints_into(&sc.x, &mut sc.values);
        self.constraints_from(x, &sc.values, out);
    }

    fn constraint_jacobian_into(&self, x: &DVector<f64>, out: &mut SparseRows) {
        let n = self.inner.dimension();
        let mut scratch = self.scratch_at(x);
        let s = &mut *scratch;
        self.inner.constraint_jacobian_into(&s.x, &mut s.rows);
        out.clear(n + 1);
        for (cols, vals) in s.rows.rows() {
            for (&c, &v) in cols.iter().zip(vals) {
                out.push(c, v);
            }
            out.push(n, -1.0);
            out.end_row();
        }
        out.push(n, -1.0);
        out.end_row();
        for j in 0..n {
            out.push(j, 1.0);
            out.end_row();
            out.push(j, -1.0);
            out.end_row();
        }
    }

    fn add_weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
        out: &mut DMatrix<f64>,
    ) -> bool {
        let n = self.inner.dimension();
        let mut scratch = self.scratch_at(x);
        let s = &mut *scratch;
        s.inner_weights(weights, self.inner.num_constraints());
        s.zero_dense(n);
        if self
            .inner
            .add_weighted_constraint_hessian(&s.x, &s.weights, &mut s.dense)
        {
            s.add_dense_to(n, out, |v| v);
        } else if self
            .inner
            .weighted_constraint_hessian_into(&s.x, &s.weights, &mut s.sparse)
        {
            if let Some(h) = &s.sparse {
                add_sparse(out, h, 1.0);
            }
        }
        true
    }
}
