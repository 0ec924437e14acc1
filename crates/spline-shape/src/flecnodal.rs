//! Control of the flecnodal circles of a surface of revolution through its meridian
//! (thesis ch. 7, with the condition of the digest): on the surface
//! $(f(z)\cos\theta, f(z)\sin\theta, z)$ an asymptotic line has contact of order four with
//! its tangent where $F = 3 f' f'' + f f'''$ changes sign inside the hyperbolic region
//! (`f″ > 0`). `F` is a quadratic form of the coefficients `x` of `f` — each of its B-spline
//! coefficients is $\tfrac12 x^T H_k x$, with the constant $H_k$ read off the Jacobian of
//! [`spline_algebra::revolution_numerators`] at the unit coefficient vectors — so its sign
//! pattern is a set of quadratic constraints of the same [`ApproximationProblem`] as the
//! parabolic circles: `f > 0`, `f″ > 0` on the controlled interval (it stays hyperbolic, so
//! every sign change of `F` there is a flecnodal circle), `F` of one sign between the
//! allowed circles (coefficients of `F` restricted to each piece), and exactly one sign
//! change inside each allowed interval (the restricted coefficients strictly monotone: by
//! variation diminishing at most one zero, and the neighbouring pieces' end values give
//! one).

use crate::barrier::BarrierOptions;
use crate::constrained::{FunctionFit, uniform_samples};
use crate::problem::normalized_forms;
use crate::problem::{
    ApproximationProblem, LeastSquaresObjective, Sign, derived_map, normalized_rows, refined,
    solve, vstack,
};
use crate::revolution::{MeridianControl, check_allowed, refined_knots};
use nalgebra_sparse::{CooMatrix, CsrMatrix};
use spline_algebra::{SparseBilinear, SplineMap, revolution_numerators};
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::BSpline;

/// The flecnodal circles a meridian may have on an interval of heights.
#[derive(Clone, Debug, PartialEq)]
pub struct FlecnodalCircles {
    /// The heights `(a, b)` where `F` is controlled; `f″ > 0` is kept there.
    pub interval: (f64, f64),
    /// The sign of `F` at `a`.
    pub first: Sign,
    /// The intervals, increasing, disjoint and inside `interval`, each holding exactly one
    /// allowed flecnodal circle.
    pub allowed: Vec<(f64, f64)>,
}

/// Approximates the meridian radius `f(z)` (least squares on `samples` equally spaced values,
/// on `f`'s knots refined `refine` times by midpoints) by the closest spline whose surface of
/// revolution has only the allowed flecnodal circles on `circles.interval` (see the module
/// documentation).
///
/// ```
/// use spline_shape::{FlecnodalCircles, Sign, control_flecnodal_circles};
/// // A neck f = 1 + z²/2 with a ripple: F = 3f′f″ + ff‴ changes sign many times.
/// let z: Vec<f64> = (0..=40).map(|k| -1.0 + f64::from(k) / 20.0).collect();
/// let r: Vec<f64> = z.iter().map(|&z| 1.0 + 0.5 * z * z + 0.004 * (12.0 * z).sin()).collect();
/// let meridian = spline_fit::interpolate_function(&z, &r, 3)?;
/// let circles = FlecnodalCircles {
///     interval: (-1.0, 1.0),
///     first: Sign::NonPositive,
///     allowed: vec![(-0.3, 0.3)],
/// };
/// let controlled = control_flecnodal_circles(&meridian, &circles, 200, 0)?;
/// let features = spline_algebra::revolution_features(&controlled.meridian, 1e-10)?;
/// assert_eq!(features.flecnodal.len(), 1);
/// assert!(controlled.max_deviation < 0.02);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for a meridian of degree below 3, more than 8 refinements,
/// an interval outside the domain, or allowed intervals that are not increasing, disjoint
/// and inside it; [`ErrorKind::TooFewPoints`] for fewer than two samples;
/// [`ErrorKind::NoConvergence`] if no meridian with the pattern is found near the data.
pub fn control_flecnodal_circles(
    meridian: &BSpline<f64, f64>,
    circles: &FlecnodalCircles,
    samples: usize,
    refine: usize,
) -> Result<MeridianControl> {
    let knots = refined_knots(meridian, refine)?;
    let (lo, hi) = meridian.domain();
    let (a, b) = circles.interval;
    if !(a >= lo && b <= hi && a < b) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("the controlled interval ({a}, {b}) must lie inside the domain ({lo}, {hi})"),
        )
        .with_interval(lo, hi));
    }
    check_allowed(&circles.allowed, (a, b))?;
    let params = uniform_samples((lo, hi), samples)?;
    let values: Vec<f64> = params
        .iter()
        .map(|&z| meridian.eval(z))
        .collect::<Result<_>>()?;
    let lsq = LeastSquaresObjective::function(&knots, &params, &values)?;
    let n = knots.num_basis();
    // f > 0 everywhere, f″ > 0 on the interval.
    let linear = vstack(
        n,
        &[
            normalized_rows(derived_map(&knots, 0, (lo, hi), 1)?.matrix(), -1.0),
            normalized_rows(derived_map(&knots, 2, (a, b), 2)?.matrix(), -1.0),
        ],
    );
    let (forms, f_knots) = flecnodal_forms(&knots)?;
    let mut rows: Vec<Vec<(usize, usize, f64)>> = Vec::new();
    let mut push = |output: &CsrMatrix<f64>| -> Result<()> {
        let piece = normalized_forms(&forms.then(output)?)?;
        rows.extend((0..piece.nrows()).map(|k| piece.row(k).to_vec()));
        Ok(())
    };
    // Cut points a rounding away from a knot of F (which is discontinuous at the knots of
    // `f`: full multiplicity there) would leave a span of width 1e-17: use the knot.
    let snap = |x: f64| {
        f_knots
            .knots()
            .iter()
            .copied()
            .find(|k| (k - x).abs() <= 1e-12 * (hi - lo))
            .unwrap_or(x)
    };
    let (a, b) = (snap(a), snap(b));
    let mut sign = circles.first.factor();
    let mut start = a;
    for &(s, t) in &circles.allowed {
        let (s, t) = (snap(s), snap(t));
        // σ F > 0 on [start, s] (refined: tighter bounds).
        let piece = refined(SplineMap::restriction(&f_knots, start, s)?, 2)?;
        push(&(piece.matrix() * sign))?;
        // Strictly monotone from σ to −σ on (s, t): −σ (c_{i+1} − c_i) > 0.
        let change = SplineMap::restriction(&f_knots, s, t)?;
        push(&(differences(change.matrix().nrows()) * change.matrix() * -sign))?;
        sign = -sign;
        start = t;
    }
    let piece = refined(SplineMap::restriction(&f_knots, start, b)?, 2)?;
    push(&(piece.matrix() * sign))?;
    let quadratic = SparseBilinear::from_rows(n, n, rows)?;
    let num_constraints = linear.nrows() + quadratic.nrows();
    let problem = ApproximationProblem::new(lsq, linear, Some(quadratic));
    let x_ls = problem.unconstrained_solution()?;
    let unconstrained_objective = problem.least_squares().value(&x_ls);
    let options = BarrierOptions::default();
    let solution = solve(&problem, std::slice::from_ref(&x_ls), &options)
        .map_err(|e| e.context("no meridian with the allowed flecnodal circles was found"))?;
    let spline = BSpline::new(knots.clone(), solution.x.as_slice().to_vec())?;
    let max_deviation = crate::revolution::max_deviation(&spline, meridian, samples)?;
    Ok(MeridianControl {
        meridian: spline.clone(),
        max_deviation,
        fit: FunctionFit {
            spline,
            unconstrained: BSpline::new(knots, x_ls.as_slice().to_vec())?,
            objective: solution.report.objective,
            unconstrained_objective,
            report: solution.report,
            num_constraints,
            patterns: 1,
        },
    })
}

/// The coefficients of `F = 3f′f″ + ff‴` as quadratic forms `x^T H_k x` of the coefficients
/// of `f` (so `F_k = ½ x^T H_k x` is what [`ApproximationProblem`] evaluates), and the knot
/// vector of `F`.
fn flecnodal_forms(knots: &KnotVector<f64>) -> Result<(SparseBilinear<f64>, KnotVector<f64>)> {
    let n = knots.num_basis();
    let mut rows: Vec<Vec<(usize, usize, f64)>> = Vec::new();
    let mut f_knots = None;
    let mut unit = vec![0.0; n];
    for l in 0..n {
        unit[l] = 1.0;
        let numerators = revolution_numerators(&BSpline::new(knots.clone(), unit.clone())?)?;
        unit[l] = 0.0;
        // ∇F_k(x) = H_k x: at x = e_l, row k of the Jacobian is column l of H_k.
        let jacobian = &numerators.flecnodal.jacobian;
        if rows.is_empty() {
            rows = vec![Vec::new(); jacobian.nrows()];
            f_knots = Some(numerators.flecnodal.value.knots().clone());
        }
        for (k, j, &v) in jacobian.triplet_iter() {
            if v != 0.0 {
                rows[k].push((j, l, v));
            }
        }
    }
    let f_knots = f_knots
        .ok_or_else(|| Error::new(ErrorKind::InvalidArgument, "a meridian needs coefficients"))?;
    Ok((SparseBilinear::from_rows(n, n, rows)?, f_knots))
}

/// The `(m − 1) × m` matrix of consecutive differences `c_{i+1} − c_i`.
fn differences(m: usize) -> CsrMatrix<f64> {
    let mut coo = CooMatrix::new(m.saturating_sub(1), m);
    for i in 0..m.saturating_sub(1) {
        coo.push(i, i, -1.0);
        coo.push(i, i + 1, 1.0);
    }
    CsrMatrix::from(&coo)
}
