//! The selective eraser of curvature extrema (thesis ch. 6): the planar B-spline curve
//! closest to data points whose curvature has only the allowed extrema.
//!
//! With `g = h1 h2 − 3 h3 h4` (`κ′ = g / h1^{5/2}`, thesis (6.10)), the curvature is monotone
//! on a parameter interval where `g` keeps one sign. The allowed extrema are knots of the
//! curve (of multiplicity `p − 2`, so that `c‴` and hence `g` may jump there while the
//! curvature stays continuous); they cut the domain into pieces on which the curvature must
//! increase and decrease alternately. Every Bernstein coefficient of `g` on every piece is
//! constrained to the piece's sign (6.21): by the variation-diminishing property, `g` then
//! keeps that sign and the only extrema are the allowed ones.
//!
//! The method is built on spline-fit:
//! 1. centripetal parameters, a least-squares fit and parameter correction locate the shape;
//! 2. knots follow its curvature ([`spline_fit::curvature_knots_with`]), the allowed extrema
//!    are placed on it (the strongest maximum or minimum of the oriented curvature, or where
//!    the caller says) and become knots; a least-squares fit with parameter correction on
//!    these knots is the start;
//! 3. phase I of the interior-point method finds a strictly feasible curve near it;
//! 4. rounds of: the constrained least-squares problem (spline-fit's normal equations under
//!    the sign conditions) solved by the interior-point method from the current curve;
//!    parameter correction (each data point moves to its closest point, so that what is
//!    minimised is the true point-to-curve distance); with [`Objective::MaxDeviation`],
//!    Lawson's reweighting of the data towards the smallest maximum deviation; refinement of
//!    the pieces whose conditions are active (subdivision keeps the curve feasible and makes
//!    the sufficient conditions closer to `g ≥ 0` itself). The best curve is kept.

mod problem;
mod verify;

pub use verify::{SampledExtremum, sampled_curvature_extrema};

use crate::barrier::{BarrierOptions, BarrierProblem, centre};
use problem::EraserProblem;
use nalgebra::{DVector, Vector2};
use spline_algebra::planar_features;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_fit::{
    LeastSquares, Parametrization, TwoSidedDeviation, curvature_knots_with, nurbs_book_knots,
    parametrize, project_ordered, two_sided_deviation,
};
use spline_geom::{BSpline, Curve2};
use std::fmt;
use std::str::FromStr;

/// A maximum or a minimum of the curvature.
///
/// The curvature is oriented so that it is positive where the data turn counter-clockwise
/// when they are listed counter-clockwise, i.e. positive on the convex parts of a closed-ish
/// contour whatever the order of its points: the nose of an airfoil is a maximum, a flat or
/// concave stretch of its pressure side a minimum.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ExtremumKind {
    /// A local maximum of the oriented curvature.
    Maximum,
    /// A local minimum of the oriented curvature.
    Minimum,
}

impl fmt::Display for ExtremumKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Maximum => "maximum",
            Self::Minimum => "minimum",
        })
    }
}

/// An allowed curvature extremum: its kind and, optionally, its parameter in `(0, 1)`.
///
/// ```
/// use spline_shape::{Extremum, ExtremumKind};
/// let nose: Extremum = "max".parse()?;
/// let trailing: Extremum = "min@0.02".parse()?;
/// assert_eq!(nose, Extremum { kind: ExtremumKind::Maximum, at: None });
/// assert_eq!(trailing.at, Some(0.02));
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extremum {
    /// Maximum or minimum.
    pub kind: ExtremumKind,
    /// The parameter on the curve's domain `[0, 1]`; `None` places it automatically (the
    /// strongest extremum of that kind of the least-squares fit between its neighbours).
    pub at: Option<f64>,
}

impl Extremum {
    /// A maximum placed automatically.
    #[must_use]
    pub fn maximum() -> Self {
        Self {
            kind: ExtremumKind::Maximum,
            at: None,
        }
    }

    /// A minimum placed automatically.
    #[must_use]
    pub fn minimum() -> Self {
        Self {
            kind: ExtremumKind::Minimum,
            at: None,
        }
    }
}

impl FromStr for Extremum {
    type Err = Error;

    /// `max`, `min`, `max@U` or `min@U` (also `maximum`, `minimum`).
    fn from_str(text: &str) -> Result<Self> {
        let (kind, at) = match text.trim().split_once('@') {
            Some((k, u)) => (k.trim(), Some(u.trim())),
            None => (text.trim(), None),
        };
        let kind = match kind {
            "max" | "maximum" => ExtremumKind::Maximum,
            "min" | "minimum" => ExtremumKind::Minimum,
            other => {
                return Err(Error::new(
                    ErrorKind::Parse,
                    format!("extremum {other:?}: expected max, min, max@U or min@U"),
                ));
            }
        };
        let at = match at {
            None => None,
            Some(u) => Some(u.parse::<f64>().map_err(|_| {
                Error::new(
                    ErrorKind::Parse,
                    format!("extremum {text:?}: {u:?} is not a number"),
                )
            })?),
        };
        Ok(Self { kind, at })
    }
}

/// What the constrained fit minimises.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Objective {
    /// The sum of squared distances from the data to the curve (thesis (6.16), with
    /// parameter correction).
    LeastSquares,
    /// The largest distance from the data to the curve, approached by Lawson's iteratively
    /// reweighted least squares (the measure of thesis Table 6.1).
    #[default]
    MaxDeviation,
}

/// Settings of [`smooth`].
#[derive(Clone, Debug)]
pub struct SmoothingOptions {
    /// Degree of the curve (at least 3: the conditions involve `c‴`).
    pub degree: usize,
    /// Number of control points.
    pub control_points: usize,
    /// The allowed curvature extrema, in the order of the data; kinds alternate.
    pub extrema: Vec<Extremum>,
    /// What is minimised.
    pub objective: Objective,
    /// Rounds of constrained solve and parameter correction, at most.
    pub max_rounds: usize,
    /// Stop after this many rounds without a better curve.
    pub patience: usize,
    /// Passes of refinement of the active conditions, at most.
    pub max_refinements: usize,
    /// Exponent `β` of the knot density `|C′| (κ L + c)^β` ([`spline_fit::curvature_knots`]).
    pub knot_exponent: f64,
    /// Floor `c` of the knot density.
    pub knot_floor: f64,
    /// Settings of the interior-point solver.
    pub barrier: BarrierOptions,
}

impl SmoothingOptions {
    /// Cubic curves with `control_points` control points and one curvature maximum placed
    /// automatically (the nose of an airfoil).
    #[must_use]
    pub fn new(control_points: usize) -> Self {
        Self {
            degree: 3,
            control_points,
            extrema: vec![Extremum::maximum()],
            objective: Objective::default(),
            max_rounds: 40,
            patience: 6,
            max_refinements: 6,
            knot_exponent: 0.5,
            knot_floor: 0.6,
            barrier: BarrierOptions {
                gap_tolerance: 1e-7,
                max_newton_iterations: 60,
                ..BarrierOptions::default()
            },
        }
    }
}

/// A curvature extremum of the result.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurvatureExtremum {
    /// Its parameter.
    pub param: f64,
    /// The point of the curve there.
    pub point: Vector2<f64>,
    /// Maximum or minimum of the oriented curvature.
    pub kind: ExtremumKind,
}

/// The result of [`smooth`].
#[derive(Clone, Debug)]
pub struct SmoothedCurve {
    /// The smoothed curve, on `[0, 1]`.
    pub curve: Curve2<f64>,
    /// The least-squares fit with parameter correction on the same knots (the start).
    pub start: Curve2<f64>,
    /// The deviation from the data both ways: data → curve by closest points and curve →
    /// data polyline.
    pub deviation: TwoSidedDeviation<f64>,
    /// The curvature extrema of the result.
    pub extrema: Vec<CurvatureExtremum>,
    /// The inflections of the result.
    pub inflections: Vec<f64>,
    /// The number of curvature extrema of the start.
    pub start_extrema: usize,
    /// `+1` if the data run counter-clockwise (the oriented curvature is the signed one),
    /// `−1` otherwise.
    pub orientation: f64,
    /// Rounds of constrained solve and parameter correction.
    pub rounds: usize,
    /// Refinement passes that split active pieces.
    pub refinements: usize,
    /// Sign conditions in the final problem.
    pub conditions: usize,
    /// Newton steps of the interior-point method in all (phase I included).
    pub newton_steps: usize,
}

/// The number of extrema as words: "1 curvature extremum", "2 curvature extrema".
fn extrema_words(k: usize) -> String {
    if k == 1 {
        "1 curvature extremum".to_owned()
    } else {
        format!("{k} curvature extrema")
    }
}

/// Fits `points` with a planar B-spline curve whose curvature has only the allowed extrema
/// (thesis ch. 6, built on spline-fit as the module documentation describes).
///
/// The data are translated and scaled to unit size for the computation and the result is
/// mapped back, so the answer does not depend on units. Consecutive repeated points count
/// once.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for a degree below 3, no extrema or kinds that do not
/// alternate, parameters outside `(0, 1)` or not increasing, or more extrema than the control
/// points allow; [`ErrorKind::TooFewPoints`] / [`ErrorKind::NonFinite`] /
/// [`ErrorKind::DegenerateGeometry`] for unusable data; [`ErrorKind::NoConvergence`] when no
/// curve with these extrema and control points is found near the data (the message says what
/// to change).
pub fn smooth(points: &[Vector2<f64>], options: &SmoothingOptions) -> Result<SmoothedCurve> {
    let p = options.degree;
    let n = options.control_points;
    check_options(options)?;
    let data = distinct(points)?;
    if data.len() < n + 1 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "{n} control points need more than {n} distinct data points, got {}",
                data.len()
            ),
        ));
    }
    // Unit size: translate to the centre of the bounding box, scale by its diagonal.
    let (middle, size) = frame(&data);
    let unit: Vec<Vector2<f64>> = data.iter().map(|q| (q - middle) / size).collect();
    let orientation = if polygon_area(&unit) >= 0.0 { 1.0 } else { -1.0 };

    // 1. The shape: centripetal parameters, least squares, parameter correction.
    let mut params = parametrize(&unit, &Parametrization::Centripetal)?;
    let base = nurbs_book_knots(p, n, &params)?;
    let (preliminary, corrected) = fit_with_correction(&unit, &params, &base, None, 8)?;
    params = corrected;

    // 2. Extrema on the shape, knots that follow it, the least-squares start.
    let placed = place_extrema(&preliminary, &options.extrema, orientation)?;
    let fixed: Vec<(f64, usize)> = placed.iter().map(|&u| (u, p - 2)).collect();
    let (knots, start, params) = start_on_feature_knots(
        &unit,
        &params,
        &preliminary,
        &fixed,
        options,
    )?;
    let start_extrema = planar_features(&start, 1e-10)
        .map(|f| f.curvature_extrema.len())
        .unwrap_or(0);

    // 3. Coarse to fine: the knot vectors of the levels are nested (every other free knot
    //    dropped at each coarser level, the extremum knots kept), so that knot insertion
    //    carries a strictly feasible curve of one level to the next one unchanged.
    let first_sign = match options.extrema[0].kind {
        ExtremumKind::Maximum => orientation,
        ExtremumKind::Minimum => -orientation,
    };
    let not_found = || {
        Error::new(
            ErrorKind::NoConvergence,
            format!(
                "no curve with {} and {n} control points was found near the data: allow more control points or more extrema",
                extrema_words(placed.len())
            ),
        )
    };
    let levels = nested_levels(&knots, &placed)?;
    let mut solver = Solver {
        options,
        newton_steps: 0,
        phase_one_steps: 0,
    };
    let mut params = params;
    let mut current: Option<Curve2<f64>> = None;
    let mut last_problem = None;
    let mut refinements = 0;
    let mut unit_squared: Option<f64> = None;
    for (level, level_knots) in levels.iter().enumerate() {
        let finest = level + 1 == levels.len();
        let mut problem = EraserProblem::new(
            level_knots,
            &unit,
            &params,
            options.objective,
            placed.clone(),
            first_sign,
        )?;
        let control: Vec<Vector2<f64>> = match &current {
            // The same curve on the finer knots.
            Some(curve) => curve.refine(&new_knots(curve.knots(), level_knots))?.control_points().to_vec(),
            None => {
                let (fit, corrected) =
                    fit_with_correction(&unit, &params, level_knots, None, 12)?;
                params = corrected;
                problem = EraserProblem::new(
                    level_knots,
                    &unit,
                    &params,
                    options.objective,
                    placed.clone(),
                    first_sign,
                )?;
                fit.control_points().to_vec()
            }
        };
        // Fixed parameters on the coarse levels (a coarse curve could otherwise fit the data
        // degenerately, all of them near one end); corrected between levels.
        problem.set_projection(finest);
        if current.is_some() {
            let before = BSpline::new(level_knots.clone(), control.clone())?;
            params = project_ordered(&before, &unit, &params)?;
            let last = params.len() - 1;
            params[0] = 0.0;
            params[last] = 1.0;
            problem.set_anchors(&params);
        }
        let x0 = problem.variables(&control, 0.0);
        let largest = problem
            .squared_distances(&x0)
            .iter()
            .copied()
            .fold(0.0, f64::max);
        // One unit of squared distance for all levels: the largest at the coarsest start.
        let unit_of_levels = *unit_squared.get_or_insert(largest.max(1e-24));
        problem.set_unit(unit_of_levels);
        let mut x = problem.variables(&control, 1.25 * largest.max(1e-24) / unit_of_levels);
        if finest || std::env::var_os("SPLINE_EXC_ALL").is_some() {
            problem.set_excursions(&x, 2.0 * largest.max(1e-24).sqrt());
        }
        problem.rescale(&x);
        let feasible = problem
            .constraints(&x)
            .iter()
            .all(|&c| c < 0.0);
        if !feasible {
            let z = x.get(2 * level_knots.num_basis()).copied().unwrap_or(0.0);
            match solver.phase_one(&mut problem, &control, z) {
                Some(found) => x = found,
                // Too coarse to hold the allowed shape: start again one level finer.
                None if !finest => continue,
                None => return Err(not_found()),
            }
        }
        let gap = if finest {
            options.barrier.gap_tolerance
        } else {
            1e-4
        };
        let max_refinements = if finest { options.max_refinements } else { 0 };
        refinements = solver.phase_two(&mut problem, &mut x, gap, max_refinements)?;
        let curve = BSpline::new(level_knots.clone(), problem.control_points(&x))?;
        params = problem.anchors();
        current = Some(curve);
        last_problem = Some(problem);
    }
    let problem = last_problem.ok_or_else(not_found)?;
    let x_best = problem.variables(
        current.as_ref().ok_or_else(not_found)?.control_points(),
        0.0,
    );
    let rounds = levels.len();
    let newton_steps = solver.newton_steps + solver.phase_one_steps;
    let control: Vec<Vector2<f64>> = problem
        .control_points(&x_best)
        .into_iter()
        .map(|c| c * size + middle)
        .collect();
    let curve = BSpline::new(knots.clone(), control)?;
    let start = start.map_control_points(|c| c * size + middle);
    let deviation = two_sided_deviation(&curve, &data)?;
    let features = planar_features(&curve, 1e-10)?;
    let extrema = features
        .curvature_extrema
        .iter()
        .map(|&u| classify(&curve, u, orientation))
        .collect::<Result<Vec<_>>>()?;
    Ok(SmoothedCurve {
        curve,
        start,
        deviation,
        extrema,
        inflections: features.inflections,
        start_extrema,
        orientation,
        rounds,
        refinements,
        conditions: problem.num_conditions(),
        newton_steps,
    })
}

fn check_options(options: &SmoothingOptions) -> Result<()> {
    let p = options.degree;
    if p < 3 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("smoothing needs degree 3 or more (the curvature's derivative involves c‴), got {p}"),
        ));
    }
    if options.extrema.is_empty() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "allow at least one curvature extremum",
        ));
    }
    for w in options.extrema.windows(2) {
        if w[0].kind == w[1].kind {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "curvature extrema alternate: a {} must be followed by a {}",
                    w[0].kind,
                    match w[0].kind {
                        ExtremumKind::Maximum => ExtremumKind::Minimum,
                        ExtremumKind::Minimum => ExtremumKind::Maximum,
                    }
                ),
            ));
        }
    }
    let mut last = 0.0;
    for e in &options.extrema {
        if let Some(u) = e.at {
            if !(u > last && u < 1.0) {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!(
                        "extremum parameter {u} must lie in (0, 1), after the previous one"
                    ),
                ));
            }
            last = u;
        }
    }
    let k = options.extrema.len();
    let n = options.control_points;
    // One span per piece at least, and room for the extremum knots of multiplicity p − 2.
    let needed = p + 1 + k * (p - 2);
    if n < needed {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{} need at least {needed} control points of degree {p}, got {n}",
                extrema_words(k)
            ),
        ));
    }
    Ok(())
}

/// The points without consecutive repetitions; all finite, at least two distinct.
fn distinct(points: &[Vector2<f64>]) -> Result<Vec<Vector2<f64>>> {
    if let Some(k) = points.iter().position(|q| !(q.x.is_finite() && q.y.is_finite())) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("data point {k} is not finite"),
        ));
    }
    let mut out: Vec<Vector2<f64>> = Vec::with_capacity(points.len());
    for q in points {
        if out.last() != Some(q) {
            out.push(*q);
        }
    }
    if out.len() < 2 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            "smoothing needs at least two distinct data points",
        ));
    }
    Ok(out)
}

/// Centre and diagonal of the bounding box.
fn frame(points: &[Vector2<f64>]) -> (Vector2<f64>, f64) {
    let mut lo = points[0];
    let mut hi = points[0];
    for q in points {
        lo = lo.inf(q);
        hi = hi.sup(q);
    }
    ((lo + hi) * 0.5, (hi - lo).norm())
}

/// Twice the signed area of the polygon closed by its chord (positive counter-clockwise).
fn polygon_area(points: &[Vector2<f64>]) -> f64 {
    let mut sum = 0.0;
    for k in 0..points.len() {
        let a = points[k];
        let b = points[(k + 1) % points.len()];
        sum += a.x * b.y - a.y * b.x;
    }
    sum
}


/// Least squares on `knots` with `rounds` of parameter correction (projection of each point
/// on the curve, in order); returns the last fit and the corrected parameters.
fn fit_with_correction(
    points: &[Vector2<f64>],
    params: &[f64],
    knots: &KnotVector<f64>,
    weights: Option<&[f64]>,
    rounds: usize,
) -> Result<(Curve2<f64>, Vec<f64>)> {
    let mut params = params.to_vec();
    let fit = |params: &[f64]| -> Result<Curve2<f64>> {
        let mut problem = LeastSquares::new(points, params, knots.clone());
        if let Some(w) = weights {
            problem = problem.weights(w);
        }
        BSpline::new(knots.clone(), problem.control_points()?)
    };
    let mut curve = fit(&params)?;
    for _ in 0..rounds {
        params = project_ordered(&curve, points, &params)?;
        curve = fit(&params)?;
    }
    Ok((curve, params))
}

/// `(u, oriented κ(u), arc-length weight)` of `curve` on a dense grid.
fn curvature_samples(curve: &Curve2<f64>, orientation: f64) -> Result<Vec<(f64, f64, f64)>> {
    let samples = 2000;
    let du = 1.0 / samples as f64;
    (0..=samples)
        .map(|k| {
            let u = k as f64 * du;
            let d = curve.derivatives(u, 1)?;
            Ok((u, orientation * curve.signed_curvature(u)?, d[1].norm() * du))
        })
        .collect()
}

/// The weighted least-squares cost of making `values` monotone (pool adjacent violators).
fn isotonic_cost(values: &[(f64, f64, f64)], increasing: bool) -> f64 {
    // Blocks of (weighted sum, weight, sum of w·v²).
    let mut blocks: Vec<(f64, f64, f64)> = Vec::with_capacity(values.len());
    for &(_, v, w) in values {
        let v = if increasing { v } else { -v };
        let w = w.max(1e-300);
        blocks.push((w * v, w, w * v * v));
        while blocks.len() > 1 {
            let (s1, w1, q1) = blocks[blocks.len() - 2];
            let (s2, w2, q2) = blocks[blocks.len() - 1];
            if s1 / w1 > s2 / w2 {
                blocks.pop();
                let last = blocks.len() - 1;
                blocks[last] = (s1 + s2, w1 + w2, q1 + q2);
            } else {
                break;
            }
        }
    }
    blocks.iter().map(|(s, w, q)| q - s * s / w).sum()
}

/// Parameters of the allowed extrema: given ones as they are; automatic ones, from left to
/// right, where the curvature of `fit` needs the least change to become monotone on both
/// sides (weighted isotonic regression along the arc length, between the neighbouring
/// extrema).
fn place_extrema(fit: &Curve2<f64>, extrema: &[Extremum], orientation: f64) -> Result<Vec<f64>> {
    let samples = curvature_samples(fit, orientation)?;
    let mut slots: Vec<Option<f64>> = extrema.iter().map(|e| e.at).collect();
    for i in 0..extrema.len() {
        if slots[i].is_some() {
            continue;
        }
        let lo = (0..i).rev().find_map(|j| slots[j]).unwrap_or(0.0);
        let hi = (i + 1..extrema.len()).find_map(|j| slots[j]).unwrap_or(1.0);
        let margin = 0.01;
        let left = samples.partition_point(|s| s.0 < lo);
        let right = samples.partition_point(|s| s.0 <= hi);
        let rising_before = extrema[i].kind == ExtremumKind::Maximum;
        let mut best: Option<(f64, f64)> = None;
        for k in (left..right).step_by(4) {
            let u = samples[k].0;
            if !(u > lo + margin && u < hi - margin) {
                continue;
            }
            let cost = isotonic_cost(&samples[left..=k], rising_before)
                + isotonic_cost(&samples[k..right], !rising_before);
            if best.is_none_or(|(c, _)| cost < c) {
                best = Some((cost, u));
            }
        }
        let Some((_, u)) = best else {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "no room for curvature extremum {} between {lo} and {hi}: give its parameter",
                    i + 1
                ),
            ));
        };
        slots[i] = Some(u);
    }
    let placed: Vec<f64> = slots.into_iter().map(|s| s.expect("placed")).collect();
    if placed.windows(2).any(|w| !(w[1] > w[0])) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "the automatic extrema do not come in the order given: give their parameters",
        ));
    }
    Ok(placed)
}

/// Knots following the curvature of `preliminary` with the extremum knots, and the
/// least-squares start on them (parameter correction included). Falls back to flatter knot
/// densities when a knot span ends up without data.
fn start_on_feature_knots(
    points: &[Vector2<f64>],
    params: &[f64],
    preliminary: &Curve2<f64>,
    fixed: &[(f64, usize)],
    options: &SmoothingOptions,
) -> Result<(KnotVector<f64>, Curve2<f64>, Vec<f64>)> {
    let mut last = None;
    for exponent in [options.knot_exponent, 0.5 * options.knot_exponent, 0.0] {
        let knots = curvature_knots_with(
            preliminary,
            options.degree,
            options.control_points,
            exponent,
            options.knot_floor,
            fixed,
        )?;
        match fit_with_correction(points, params, &knots, None, 12) {
            Ok((start, params)) => return Ok((knots, start, params)),
            Err(e) if e.kind() == ErrorKind::SchoenbergWhitney || e.kind() == ErrorKind::SingularSystem => {
                last = Some(e);
            }
            Err(e) => return Err(e),
        }
    }
    Err(last.expect("at least one attempt"))
}

/// The kind of the extremum of the oriented curvature at `u`.
fn classify(curve: &Curve2<f64>, u: f64, orientation: f64) -> Result<CurvatureExtremum> {
    let (a, b) = curve.domain();
    let h = 1e-6 * (b - a);
    let k = |t: f64| -> Result<f64> { Ok(orientation * curve.signed_curvature(t.clamp(a, b))?) };
    let centre = k(u)?;
    let side = k(u - h)?.max(k(u + h)?);
    let kind = if centre >= side {
        ExtremumKind::Maximum
    } else {
        ExtremumKind::Minimum
    };
    Ok(CurvatureExtremum {
        param: u,
        point: curve.eval(u)?,
        kind,
    })
}

/// The knots of `fine` that `coarse` lacks (with multiplicity).
fn new_knots(coarse: &KnotVector<f64>, fine: &KnotVector<f64>) -> Vec<f64> {
    let mut out = Vec::new();
    let (c, f) = (coarse.knots(), fine.knots());
    let (mut i, mut j) = (0, 0);
    while j < f.len() {
        if i < c.len() && c[i] == f[j] {
            i += 1;
        } else {
            out.push(f[j]);
        }
        j += 1;
    }
    out
}

/// Nested knot vectors from coarse to `knots`: each coarser level drops every other interior
/// knot that is not an extremum knot, down to the extremum knots alone.
fn nested_levels(knots: &KnotVector<f64>, extrema: &[f64]) -> Result<Vec<KnotVector<f64>>> {
    let p = knots.degree();
    let (a, b) = knots.domain();
    let interior: Vec<f64> = knots.knots()[p + 1..knots.num_basis()].to_vec();
    let fixed: Vec<f64> = interior
        .iter()
        .copied()
        .filter(|u| extrema.contains(u))
        .collect();
    let mut free: Vec<f64> = interior
        .iter()
        .copied()
        .filter(|u| !extrema.contains(u))
        .collect();
    let mut levels = Vec::new();
    loop {
        let mut all = fixed.clone();
        all.extend(&free);
        all.sort_by(f64::total_cmp);
        levels.push(KnotVector::clamped(p, a, b, &all)?);
        if free.is_empty() {
            break;
        }
        // Keep every other free knot (the odd positions), at least halving.
        free = free.iter().skip(1).step_by(2).copied().collect();
    }
    levels.reverse();
    Ok(levels)
}

/// The interior-point machinery of the eraser, with its step counts.
struct Solver<'a> {
    options: &'a SmoothingOptions,
    newton_steps: usize,
    phase_one_steps: usize,
}

impl Solver<'_> {
    /// One centring step at `t` (an unfinished one still improves the iterate), then the
    /// foot points follow the curve.
    fn centre(
        &mut self,
        problem: &EraserProblem,
        x: &mut DVector<f64>,
        t: f64,
        stop: Option<&dyn Fn(&DVector<f64>) -> bool>,
        phase_one: bool,
    ) -> Result<()> {
        let steps = match centre(problem, x, t, &self.options.barrier, stop) {
            Ok(steps) => steps,
            Err(e) if e.kind() == ErrorKind::NoConvergence => {
                self.options.barrier.max_newton_iterations
            }
            Err(e) => return Err(e),
        };
        if phase_one {
            self.phase_one_steps += steps;
        } else {
            self.newton_steps += steps;
        }
        problem.commit(x);
        Ok(())
    }

    /// Phase I from `control`: `τ` as a variable, `min τ + pull · fit` until `τ < 0`, the
    /// pull weakening as `t` grows; with shifts per condition first, then one shift for all.
    /// `None` if no strictly feasible curve is found.
    fn phase_one(
        &mut self,
        problem: &mut EraserProblem,
        control: &[Vector2<f64>],
        z: f64,
    ) -> Option<DVector<f64>> {
        for uniform in [false, true] {
            let x = problem.variables(control, z);
            problem.start_homotopy(&x, 0.1, uniform);
            problem.set_relaxed(true, 1.0);
            let mut y = problem.variables(control, z);
            let index = problem.tau_index();
            let mut t = problem.num_constraints() as f64;
            let mut found = false;
            let mut best_tau = f64::INFINITY;
            let mut stalled = 0;
            for _ in 0..self.options.max_rounds {
                let feasible = |v: &DVector<f64>| v[index] < 0.0;
                if self.centre(problem, &mut y, t, Some(&feasible), true).is_err() {
                    break;
                }
                if std::env::var_os("SPLINE_DEBUG").is_some() {
                    eprintln!("  phase I (uniform {uniform}) t {t:.1e} tau {:.3e} z {:.3e} pull {:.1e}", y[index], y[index - 1], problem.pull());
                }
                if y[index] < 0.0 {
                    found = true;
                    break;
                }
                // τ creeping towards zero from above: a degenerate configuration (g ≡ 0 on
                // a piece), not a way to feasibility.
                if y[index] > 0.5 * best_tau {
                    stalled += 1;
                    if stalled >= 3 {
                        break;
                    }
                } else {
                    stalled = 0;
                }
                best_tau = best_tau.min(y[index]);
                t *= self.options.barrier.t_growth;
                let pull = problem.pull() / self.options.barrier.t_growth;
                problem.set_relaxed(true, pull);
            }
            problem.set_relaxed(false, 1.0);
            problem.set_tau(0.0);
            if found {
                return Some(y.rows(0, index).into_owned());
            }
        }
        None
    }

    /// Phase II from a strictly feasible `x`: path following until the gap bound `m/t`
    /// is below `gap`, refining active conditions (at most `max_refinements` passes).
    /// Returns the number of refinement passes that split something.
    fn phase_two(
        &mut self,
        problem: &mut EraserProblem,
        x: &mut DVector<f64>,
        gap: f64,
        max_refinements: usize,
    ) -> Result<usize> {
        let mut t = 10.0 * problem.num_constraints() as f64;
        let mut refinements = 0;
        loop {
            self.centre(problem, x, t, None, false)?;
            if refinements < max_refinements && problem.refine_active(x, 1e-3, 1.0 / 64.0) > 0 {
                refinements += 1;
            }
            if std::env::var_os("SPLINE_DEBUG").is_some() {
                eprintln!("  path t {t:.2e}: objective {:.5e} pieces {}", problem.objective(x), problem.num_pieces());
            }
            if problem.num_constraints() as f64 / t < gap {
                return Ok(refinements);
            }
            t *= self.options.barrier.t_growth;
        }
    }
}
