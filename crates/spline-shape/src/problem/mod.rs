//! The optimisation problem shared by the constrained approximations of functions of one and
//! two variables (thesis §5.1–5.6): the least-squares objective $f_0 = \tfrac12\\|Ax - b\\|^2$,
//! linear sign constraints `G x < 0` and quadratic ones `½ xᵀ H_k x < 0` with constant
//! Hessians, as a [`BarrierProblem`].

mod grid;
mod in_place;
mod objective;

pub(crate) use grid::{check_grid, normalized_forms};
pub(crate) use objective::LeastSquaresObjective;

use crate::barrier::{
    BarrierOptions, BarrierProblem, BarrierReport, SparseRows, find_feasible, minimize,
};
use in_place::JacobianPattern;
use nalgebra::DMatrix;
use nalgebra::DVector;
use nalgebra_sparse::{CooMatrix, CsrMatrix};
use spline_algebra::{SparseBilinear, SplineMap};
use spline_core::{Error, ErrorKind, KnotVector, Result};

/// The sign a derived quantity must keep.
///
/// ```
/// use spline_shape::Sign;
/// assert_eq!(Sign::NonNegative.factor(), 1.0);
/// assert_eq!(Sign::NonNegative.opposite(), Sign::NonPositive);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// `≥ 0` (kept strictly positive by the barrier).
    NonNegative,
    /// `≤ 0` (kept strictly negative by the barrier).
    NonPositive,
}

impl Sign {
    /// `+1` for [`Sign::NonNegative`], `−1` for [`Sign::NonPositive`].
    #[must_use]
    pub fn factor(self) -> f64 {
        match self {
            Self::NonNegative => 1.0,
            Self::NonPositive => -1.0,
        }
    }

    /// The other sign.
    #[must_use]
    pub fn opposite(self) -> Self {
        match self {
            Self::NonNegative => Self::NonPositive,
            Self::NonPositive => Self::NonNegative,
        }
    }
}

/// Scales every row of `m` by `factor / ‖row‖₂` (empty rows are dropped): a constraint
/// `(G x)_i < 0` then measures the distance of `x` to its hyperplane, so that constraints of
/// different derivative orders live on one scale (the barrier itself is scale-invariant; the
/// phase-I search is not).
pub(crate) fn normalized_rows(m: &CsrMatrix<f64>, factor: f64) -> CsrMatrix<f64> {
    let kept: Vec<_> = m
        .row_iter()
        .filter_map(|row| {
            let norm = row.values().iter().map(|v| v * v).sum::<f64>().sqrt();
            (norm > 0.0).then(|| {
                row.col_indices()
                    .iter()
                    .zip(row.values())
                    .map(|(&j, &v)| (j, factor * v / norm))
                    .collect::<Vec<_>>()
            })
        })
        .collect();
    let mut coo = CooMatrix::new(kept.len(), m.ncols());
    for (i, row) in kept.into_iter().enumerate() {
        for (j, v) in row {
            coo.push(i, j, v);
        }
    }
    CsrMatrix::from(&coo)
}

/// Stacks sparse matrices with the same number of columns.
pub(crate) fn vstack(ncols: usize, blocks: &[CsrMatrix<f64>]) -> CsrMatrix<f64> {
    let nrows = blocks.iter().map(CsrMatrix::nrows).sum();
    let mut coo = CooMatrix::new(nrows, ncols);
    let mut offset = 0;
    for b in blocks {
        debug_assert_eq!(b.ncols(), ncols);
        for (i, j, v) in b.triplet_iter() {
            coo.push(offset + i, j, *v);
        }
        offset += b.nrows();
    }
    CsrMatrix::from(&coo)
}

/// A constrained least-squares problem, ready for [`crate::minimize`]: minimise
/// $f_0(x) = \tfrac12\\|Ax - b\\|^2$ over the coefficients `x` subject to linear constraints
/// `G x < 0` (sign conditions on the control points of derivatives, each row scaled to unit
/// length so that its value is the signed distance of `x` to the hyperplane) and quadratic
/// ones $\tfrac12 x^T H_k x < 0$ with constant Hessians `H_k` (the control points of
/// $s_{uu}s_{vv} - s_{uv}^2$, thesis §5.6).
///
/// The builders [`crate::FunctionApproximation`] and [`crate::SurfaceApproximation`] make
/// these and solve them; they are public so that the derivatives can be checked and the
/// solver driven by hand.
///
/// # Panics
/// The [`BarrierProblem`] methods panic if `x` does not have [`BarrierProblem::dimension`]
/// entries (the trait has no error channel; [`crate::minimize`] checks the start).
///
/// ```
/// use spline_shape::{BarrierOptions, BarrierProblem, FunctionApproximation, Sign};
/// use spline_shape::{find_feasible, minimize};
/// let approx = FunctionApproximation::uniform(3, 8, 0.0, 1.0)?.sign(1, Sign::NonNegative);
/// let params: Vec<f64> = (0..=50).map(|j| f64::from(j) / 50.0).collect();
/// let values: Vec<f64> = params.iter().map(|u| (6.0 * u).sin() + u).collect();
/// let problem = &approx.problems(&params, &values)?[0];
/// assert_eq!(problem.num_constraints(), 7); // the 7 control points of s′
/// // A strictly increasing start: the Greville abscissae (s(u) = u).
/// let start = nalgebra::DVector::from_vec(approx.knots().greville());
/// let options = BarrierOptions::default();
/// let x0 = find_feasible(problem, start, 1e-6, &options)?;
/// let report = minimize(problem, x0, &options)?;
/// let fit = approx.fit(&params, &values)?;
/// assert!((report.objective - fit.objective).abs() < 1e-6);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct ApproximationProblem {
    lsq: LeastSquaresObjective,
    linear: CsrMatrix<f64>,
    quadratic: Option<SparseBilinear<f64>>,
    pattern: Option<HessianPattern>,
    jacobian_pattern: Option<JacobianPattern>,
}

/// The union of the sparsity patterns of the `H_k` (CSR) and, for every entry of every
/// `H_k`, its slot there: `Σ w_k H_k` is then a scatter-add, without sorting.
#[derive(Clone, Debug)]
struct HessianPattern {
    n: usize,
    offsets: Vec<usize>,
    columns: Vec<usize>,
    /// `(k, slot, value)`.
    scatter: Vec<(usize, usize, f64)>,
}

impl HessianPattern {
    fn new(n: usize, forms: &SparseBilinear<f64>) -> Self {
        let mut rows: Vec<Vec<usize>> = vec![Vec::new(); n];
        for k in 0..forms.nrows() {
            for &(j, l, _) in forms.row(k) {
                rows[j].push(l);
            }
        }
        let mut offsets = Vec::with_capacity(n + 1);
        let mut columns = Vec::new();
        offsets.push(0);
        for row in &mut rows {
            row.sort_unstable();
            row.dedup();
            columns.extend_from_slice(row);
            offsets.push(columns.len());
        }
        let mut scatter = Vec::with_capacity(forms.nnz());
        for k in 0..forms.nrows() {
            for &(j, l, v) in forms.row(k) {
                let row = &columns[offsets[j]..offsets[j + 1]];
                let slot = offsets[j] + row.partition_point(|&c| c < l);
                scatter.push((k, slot, v));
            }
        }
        Self {
            n,
            offsets,
            columns,
            scatter,
        }
    }

    fn weighted(&self, weights: &[f64]) -> CsrMatrix<f64> {
        let mut values = vec![0.0; self.columns.len()];
        for &(k, slot, v) in &self.scatter {
            values[slot] += weights[k] * v;
        }
        CsrMatrix::try_from_csr_data(
            self.n,
            self.n,
            self.offsets.clone(),
            self.columns.clone(),
            values,
        )
        .unwrap_or_else(|_| CsrMatrix::zeros(self.n, self.n))
    }
}

impl ApproximationProblem {
    pub(crate) fn new(
        lsq: LeastSquaresObjective,
        linear: CsrMatrix<f64>,
        quadratic: Option<SparseBilinear<f64>>,
    ) -> Self {
        let pattern = quadratic
            .as_ref()
            .map(|q| HessianPattern::new(lsq.dimension(), q));
        let jacobian_pattern = quadratic.as_ref().map(JacobianPattern::new);
        Self {
            lsq,
            linear,
            quadratic,
            pattern,
            jacobian_pattern,
        }
    }

    pub(crate) fn least_squares(&self) -> &LeastSquaresObjective {
        &self.lsq
    }

    /// The number of linear constraints (they come first).
    #[must_use]
    pub fn num_linear_constraints(&self) -> usize {
        self.linear.nrows()
    }

    /// The number of quadratic constraints (they come after the linear ones).
    #[must_use]
    pub fn num_quadratic_constraints(&self) -> usize {
        self.quadratic.as_ref().map_or(0, SparseBilinear::nrows)
    }

    /// The minimiser of $f_0$ without constraints, $x = (A^TA)^{-1}A^Tb$.
    ///
    /// # Errors
    /// [`ErrorKind::SchoenbergWhitney`] if the samples leave a coefficient undetermined;
    /// [`ErrorKind::SingularSystem`] if the normal equations cannot be solved accurately.
    pub fn unconstrained_solution(&self) -> Result<DVector<f64>> {
        self.lsq.solve()
    }
}

impl BarrierProblem for ApproximationProblem {
    fn dimension(&self) -> usize {
        self.lsq.dimension()
    }

    fn num_constraints(&self) -> usize {
        self.linear.nrows() + self.num_quadratic_constraints()
    }

    fn objective(&self, x: &DVector<f64>) -> f64 {
        self.lsq.value(x)
    }

    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64> {
        self.lsq.gradient(x)
    }

    fn objective_hessian(&self, _: &DVector<f64>) -> CsrMatrix<f64> {
        self.lsq.hessian().clone()
    }

    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        let lin = &self.linear * x;
        match &self.quadratic {
            None => lin,
            Some(h) => {
                let q = h
                    .apply(x.as_slice(), x.as_slice())
                    .expect("x has `dimension()` entries");
                DVector::from_iterator(
                    lin.len() + q.len(),
                    lin.iter().copied().chain(q.iter().map(|v| 0.5 * v)),
                )
            }
        }
    }

    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        match &self.quadratic {
            None => self.linear.clone(),
            Some(h) => {
                let jac = h
                    .jacobian_left(x.as_slice())
                    .expect("x has `dimension()` entries");
                vstack(self.dimension(), &[self.linear.clone(), jac])
            }
        }
    }

    fn weighted_constraint_hessian(
        &self,
        _: &DVector<f64>,
        weights: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        let pattern = self.pattern.as_ref()?;
        Some(pattern.weighted(&weights.as_slice()[self.linear.nrows()..]))
    }

    fn objective_gradient_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        self.lsq.gradient_into(x, out);
    }

    fn constraints_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        self.constraints_in_place(x, out);
    }

    fn constraint_jacobian_into(&self, x: &DVector<f64>, out: &mut SparseRows) {
        self.jacobian_in_place(x, out);
    }

    fn add_objective_hessian(&self, _: &DVector<f64>, scale: f64, out: &mut DMatrix<f64>) {
        for (i, j, v) in self.lsq.hessian().triplet_iter() {
            out[(i, j)] += scale * v;
        }
    }

    fn objective_hessian_into(&self, _: &DVector<f64>, out: &mut Option<CsrMatrix<f64>>) {
        let h = self.lsq.hessian();
        match out {
            Some(m) if m.pattern() == h.pattern() => m.values_mut().copy_from_slice(h.values()),
            _ => *out = Some(h.clone()),
        }
    }

    fn weighted_constraint_hessian_into(
        &self,
        _: &DVector<f64>,
        weights: &DVector<f64>,
        out: &mut Option<CsrMatrix<f64>>,
    ) -> bool {
        self.weighted_hessian_in_place(weights.as_slice(), out)
    }
}

/// The constraints of a problem plus the box `|x_i − c_i| < R`, for the phase-I search only:
/// phase I minimises the largest constraint value, and without a bound its barrier is
/// unbounded below whenever the feasible set is (a constraint such as `x_i > 0` can be
/// relaxed for ever by moving `x` away).
struct Boxed<'a> {
    inner: &'a ApproximationProblem,
    centre: DVector<f64>,
    radius: f64,
}

impl BarrierProblem for Boxed<'_> {
    fn dimension(&self) -> usize {
        self.inner.dimension()
    }
    fn num_constraints(&self) -> usize {
        self.inner.num_constraints() + 2 * self.dimension()
    }
    fn objective(&self, x: &DVector<f64>) -> f64 {
        self.inner.objective(x)
    }
    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64> {
        self.inner.objective_gradient(x)
    }
    fn objective_hessian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        self.inner.objective_hessian(x)
    }
    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        let inner = self.inner.constraints(x);
        let d = x - &self.centre;
        DVector::from_iterator(
            self.num_constraints(),
            inner
                .iter()
                .copied()
                .chain(d.iter().map(|v| v - self.radius))
                .chain(d.iter().map(|v| -v - self.radius)),
        )
    }
    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let n = self.dimension();
        let mut coo = CooMatrix::new(n, n);
        let mut neg = CooMatrix::new(n, n);
        for i in 0..n {
            coo.push(i, i, 1.0);
            neg.push(i, i, -1.0);
        }
        vstack(
            n,
            &[
                self.inner.constraint_jacobian(x),
                CsrMatrix::from(&coo),
                CsrMatrix::from(&neg),
            ],
        )
    }
    fn weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        let w = weights.rows(0, self.inner.num_constraints()).into_owned();
        self.inner.weighted_constraint_hessian(x, &w)
    }
    fn objective_gradient_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        self.inner.objective_gradient_into(x, out);
    }
    fn add_objective_hessian(&self, x: &DVector<f64>, scale: f64, out: &mut DMatrix<f64>) {
        self.inner.add_objective_hessian(x, scale, out);
    }
    fn objective_hessian_into(&self, x: &DVector<f64>, out: &mut Option<CsrMatrix<f64>>) {
        self.inner.objective_hessian_into(x, out);
    }
    fn constraints_into(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        let m = self.inner.num_constraints();
        let n = self.dimension();
        self.inner.constraints_in_place(x, out);
        for i in 0..n {
            let d = x[i] - self.centre[i];
            out[m + i] = d - self.radius;
            out[m + n + i] = -d - self.radius;
        }
    }
    fn constraint_jacobian_into(&self, x: &DVector<f64>, out: &mut SparseRows) {
        let n = self.dimension();
        self.inner.jacobian_in_place(x, out);
        for i in 0..n {
            out.push(i, 1.0);
            out.end_row();
        }
        for i in 0..n {
            out.push(i, -1.0);
            out.end_row();
        }
    }
    fn weighted_constraint_hessian_into(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
        out: &mut Option<CsrMatrix<f64>>,
    ) -> bool {
        let _ = x;
        let m = self.inner.num_constraints();
        self.inner
            .weighted_hessian_in_place(&weights.as_slice()[..m], out)
    }
}

/// Whether every constraint is negative at `x`.
/// [`ErrorKind::InvalidArgument`] for no samples per span (of a constraint check).
pub(crate) fn check_samples(samples_per_span: usize) -> Result<()> {
    if samples_per_span == 0 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "need at least one sample per span",
        )
        .with_value(0.0)
        .with_interval(1.0, f64::INFINITY));
    }
    Ok(())
}

pub(crate) fn strictly_feasible(problem: &ApproximationProblem, x: &DVector<f64>) -> bool {
    problem.constraints(x).iter().all(|&c| c < 0.0)
}

/// The point of the segment from the strictly feasible `from` towards `to` that is furthest
/// along it among those found strictly feasible by bisection (`to` itself if feasible).
pub(crate) fn furthest_feasible(
    problem: &ApproximationProblem,
    from: &DVector<f64>,
    to: &DVector<f64>,
) -> DVector<f64> {
    let at = |l: f64| from + (to - from) * l;
    if strictly_feasible(problem, to) {
        return to.clone();
    }
    let (mut good, mut bad) = (0.0, 1.0);
    for _ in 0..40 {
        let mid = 0.5 * (good + bad);
        if strictly_feasible(problem, &at(mid)) {
            good = mid;
        } else {
            bad = mid;
        }
    }
    // Step back a little from the boundary, if that stays feasible (the set need not be
    // convex).
    let inside = at(0.95 * good);
    if strictly_feasible(problem, &inside) {
        inside
    } else {
        at(good)
    }
}

/// The outcome of [`solve`]: the solution and the solver's report.
pub(crate) struct Solution {
    pub(crate) x: DVector<f64>,
    pub(crate) report: BarrierReport,
}

/// Finds a strictly feasible point from the first start that phase I (inside a box of
/// radius `10 (1 + ‖start‖∞)` around it) can repair, then runs the barrier method from it.
pub(crate) fn solve(
    problem: &ApproximationProblem,
    starts: &[DVector<f64>],
    options: &BarrierOptions,
) -> Result<Solution> {
    let mut last = None;
    for start in starts {
        let scale = 1.0 + start.amax();
        let boxed = Boxed {
            inner: problem,
            centre: start.clone(),
            radius: 10.0 * scale,
        };
        match find_feasible(&boxed, start.clone(), 1e-6 * scale, options)
            .and_then(|x0| minimize(problem, x0, options))
        {
            Ok(report) => {
                return Ok(Solution {
                    x: report.x.clone(),
                    report,
                });
            }
            Err(e) => last = Some(e),
        }
    }
    Err(last.unwrap_or_else(|| Error::new(ErrorKind::InvalidArgument, "no starting point")))
}

/// Checks an interval `[a, b]` inside the domain of `knots`.
pub(crate) fn check_interval(
    knots: &KnotVector<f64>,
    (a, b): (f64, f64),
    what: &str,
) -> Result<()> {
    knots
        .check_param(a)
        .and_then(|()| knots.check_param(b))
        .map_err(|e| e.context(what))?;
    if !(a < b) {
        return Err(Error::new(
            ErrorKind::OutOfDomain,
            format!("{what}: the interval [{a}, {b}] is empty"),
        ));
    }
    Ok(())
}

/// Inserts `pieces − 1` uniformly spaced knots into every non-empty span of the target of
/// `map` (nothing for `pieces ≤ 1` or a target of degree 0, whose coefficients already are
/// the values).
pub(crate) fn refined(map: SplineMap<f64>, pieces: usize) -> Result<SplineMap<f64>> {
    let target = map.target();
    if pieces <= 1 || target.degree() == 0 {
        return Ok(map);
    }
    let breaks = target.domain_breaks();
    #[allow(clippy::cast_precision_loss)]
    let new: Vec<f64> = breaks
        .windows(2)
        .flat_map(|w| (1..pieces).map(move |j| w[0] + (w[1] - w[0]) * j as f64 / pieces as f64))
        .collect();
    let refinement = SplineMap::refinement(target, &new)?;
    map.then(&refinement)
}

/// The map from the coefficients on `knots` to those of the derivative of order `order`
/// restricted to `interval` (clamped there, so that its first and last coefficients are the
/// values at the ends) and refined `pieces` times: sign conditions on its coefficients are
/// sufficient conditions on the sign of the derivative on the interval.
pub(crate) fn derived_map(
    knots: &KnotVector<f64>,
    order: usize,
    interval: (f64, f64),
    pieces: usize,
) -> Result<SplineMap<f64>> {
    let derivative = SplineMap::derivative(knots, order)?;
    let restriction = SplineMap::restriction(derivative.target(), interval.0, interval.1)?;
    refined(derivative.then(&restriction)?, pieces)
}
