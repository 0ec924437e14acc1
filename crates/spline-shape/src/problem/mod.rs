//! The optimisation problem shared by the constrained approximations of functions of one and
//! two variables (thesis §5.1–5.6): the least-squares objective $f_0 = \tfrac12\\|Ax - b\\|^2$,
//! linear sign constraints `G x < 0` and quadratic ones `½ xᵀ H_k x < 0` with constant
//! Hessians, as a [`BarrierProblem`].

mod approximation;
mod grid;
mod in_place;
mod objective;
mod patterns;
mod rows;

pub use approximation::ApproximationProblem;
pub(crate) use grid::{check_grid, normalized_forms};
pub(crate) use objective::LeastSquaresObjective;
pub(crate) use rows::{normalized_rows, vstack};

use crate::barrier::{
    BarrierOptions, BarrierProblem, BarrierReport, SparseRows, find_feasible, minimize,
};
use nalgebra::DMatrix;
use nalgebra::DVector;
use nalgebra_sparse::{CooMatrix, CsrMatrix};
use spline_algebra::SplineMap;
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

/// [`ErrorKind::InvalidArgument`] for a refinement of 0 (each span split into no piece).
pub(crate) fn check_refinement(refinement: usize) -> Result<()> {
    if refinement == 0 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "the refinement must split each span into at least one piece",
        )
        .with_value(0.0)
        .with_interval(1.0, f64::INFINITY));
    }
    Ok(())
}

/// [`ErrorKind::InvalidArgument`] below degree 2 in a direction of a patch whose convexity
/// is controlled (no curvature there).
pub(crate) fn check_convexity_degrees(p: usize, q: usize) -> Result<()> {
    if p < 2 || q < 2 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "convexity of a patch needs degree 2 or more in both directions, got ({p}, {q})"
            ),
        )
        .with_value(p.min(q) as f64)
        .with_interval(2.0, f64::INFINITY));
    }
    Ok(())
}

/// Whether every constraint is negative at `x`.
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
