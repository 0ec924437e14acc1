//! The eraser on closed curves: the same problem on a periodic B-spline of period 1.
//!
//! The curve is the wrapped container of a [`PeriodicBSpline`] (`N + p` control points, the
//! last `p` repeating the first `p`; its knots extend those of one period by the period), so
//! that the sign conditions of every segment and the foot points of every data point see one
//! curve without an end: the variables are the `N` free control points, foot points cross
//! the closing point, and the pieces between the allowed extrema wrap around it (an even
//! number of extrema, alternating around the curve). The coarse-to-fine continuation runs over
//! nested periodic knot vectors, knot insertion carrying a feasible curve from one level to
//! the next.

use super::driver::{Attempt, Topology, continuation};
use super::placement::{nested_levels, new_knots};
use super::problem::EraserProblem;
use super::{Objective, SmoothingOptions};
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_fit::{
    Parametrization, closest_point, least_squares_periodic, parametrize, project_ordered,
};
use spline_geom::{BSpline, Curve2, PeriodicBSpline};

/// A closed planar curve.
pub(crate) type ClosedCurve2 = PeriodicBSpline<f64, Vector2<f64>>;

/// Centripetal parameters of closed data in `[0, 1)`: the closing chord (last point back to
/// the first) counts as one more chord.
pub(crate) fn closed_parameters(points: &[Vector2<f64>]) -> Result<Vec<f64>> {
    let mut loop_points = points.to_vec();
    loop_points.push(points[0]);
    let mut params = parametrize(&loop_points, &Parametrization::Centripetal)?;
    params.pop();
    Ok(params)
}

/// The periodic space of period 1 whose knots of one period are those of the clamped knot
/// vector `clamped` on `[0, 1]` with `N + p` basis functions: `0` and its `N − 1` interior
/// knots.
fn periodic_space(clamped: &KnotVector<f64>) -> Result<ClosedCurve2> {
    let p = clamped.degree();
    let k = clamped.knots();
    let interior = &k[p + 1..k.len() - p - 1];
    let mut period_knots = Vec::with_capacity(interior.len() + 1);
    period_knots.push(0.0);
    period_knots.extend_from_slice(interior);
    let count = period_knots.len();
    PeriodicBSpline::new(p, period_knots, 1.0, vec![Vector2::zeros(); count])
}

/// Periodic least squares on `space` with `rounds` sweeps of parameter correction (each
/// data point moves to its closest point near its parameter).
pub(crate) fn fit_closed_with_correction(
    points: &[Vector2<f64>],
    params: &[f64],
    space: &ClosedCurve2,
    rounds: usize,
) -> Result<(ClosedCurve2, Vec<f64>)> {
    let mut params = params.to_vec();
    let mut curve = least_squares_periodic(points, &params, space, None, 0.0)?;
    for _ in 0..rounds {
        params = project_ordered(&curve, points, &params)?;
        curve = least_squares_periodic(points, &params, space, None, 0.0)?;
    }
    Ok((curve, params))
}

/// The least-squares shape of closed data with `count` control points on uniform periodic
/// knots, with parameter correction: the periodic curve and the corrected parameters.
fn closed_shape(
    points: &[Vector2<f64>],
    degree: usize,
    count: usize,
) -> Result<(ClosedCurve2, Vec<f64>)> {
    let params = closed_parameters(points)?;
    let knots: Vec<f64> = (0..count).map(|i| i as f64 / count as f64).collect();
    let space = PeriodicBSpline::new(degree, knots, 1.0, vec![Vector2::zeros(); count])?;
    fit_closed_with_correction(points, &params, &space, 8)
}

/// Moves each extremum of `placed` (placed on a coarse fit) to where the curvature of
/// `shape` needs the least change to be monotone on its two sides (weighted isotonic
/// regression), within a quarter of the distance to its neighbours: the coarse fit finds the
/// large turns, the fine one their exact place.
fn refine_closed_extrema(
    shape: &ClosedCurve2,
    placed: &mut [f64],
    first_rising: bool,
    orientation: f64,
) -> Result<()> {
    let samples = closed_curvature_samples(shape, orientation)?;
    let k = placed.len();
    for i in 0..k {
        let lo = if i == 0 { 0.0 } else { placed[i - 1] };
        let hi = if i + 1 == k { 1.0 } else { placed[i + 1] };
        let reach = 0.25 * (placed[i] - lo).min(hi - placed[i]);
        let before_rising = (i % 2 == 0) == first_rising;
        let left = samples.partition_point(|s| s.0 < lo);
        let right = samples.partition_point(|s| s.0 <= hi);
        let window = &samples[left..right];
        let before = super::placement::isotonic_prefix_costs(window, before_rising);
        let reversed: Vec<(f64, f64, f64)> = window.iter().rev().copied().collect();
        // The piece after rises when the one before falls; read backwards, it falls.
        let after = super::placement::isotonic_prefix_costs(&reversed, before_rising);
        let mut best: Option<(f64, f64)> = None;
        for (j, sample) in window.iter().enumerate() {
            if (sample.0 - placed[i]).abs() > reach {
                continue;
            }
            let cost = before[j] + after[window.len() - 1 - j];
            if best.is_none_or(|(c, _)| cost < c) {
                best = Some((cost, sample.0));
            }
        }
        if let Some((_, u)) = best {
            placed[i] = u;
        }
    }
    Ok(())
}

/// The number of control points of the fit on which `k` extrema are placed: `2k + 2` (room for
/// the turns of `k` monotone pieces), at least `p + 1`, at most `count`.
fn placement_count(degree: usize, count: usize, k: usize) -> usize {
    (2 * k + 2).max(degree + 1).min(count)
}

/// Where the smoothing of a closed contour starts.
pub(crate) struct ClosedStart {
    /// The data point that becomes the first (the closing point of the curve).
    pub(crate) rotation: usize,
    /// The least-squares shape of the rotated data, opened at its closing point.
    pub(crate) shape: Curve2<f64>,
    /// The parameters of the rotated data on it.
    pub(crate) params: Vec<f64>,
    /// With automatic extrema: their parameters and whether the first piece rises.
    pub(crate) placed: Option<(Vec<f64>, bool)>,
}

/// The shape of closed `points` (normalised) with `count` control points; with
/// `automatic = Some(k)` (every extremum placed automatically), the data are first rotated so
/// that the closing point falls inside a monotone stretch of the curvature
/// ([`closed_seam`]) and the `k` extrema are placed round the curve
/// ([`place_closed_extrema`]).
pub(crate) fn closed_start(
    points: &[Vector2<f64>],
    degree: usize,
    count: usize,
    automatic: Option<usize>,
    orientation: f64,
) -> Result<ClosedStart> {
    let (shape, params) = closed_shape(points, degree, count)?;
    let Some(k) = automatic else {
        return Ok(ClosedStart {
            rotation: 0,
            shape: shape.open_at(0.0)?,
            params,
            placed: None,
        });
    };
    // The extrema are placed on a coarse fit: its curvature keeps the shape's large turns and
    // not the wiggles that the eraser is to remove.
    let coarse = placement_count(degree, count, k);
    let (rough, _) = closed_shape(points, degree, coarse)?;
    let seam = closed_seam(&rough, k, orientation)?;
    let cyclic = |u: f64| (u - seam).rem_euclid(1.0).min((seam - u).rem_euclid(1.0));
    let rotation = (0..params.len())
        .min_by(|&a, &b| cyclic(params[a]).total_cmp(&cyclic(params[b])))
        .unwrap_or(0);
    let mut rotated = points.to_vec();
    rotated.rotate_left(rotation);
    let (shape, params) = closed_shape(&rotated, degree, count)?;
    let (rough, _) = closed_shape(&rotated, degree, coarse)?;
    let (on_rough, first_rising) = place_closed_extrema(&rough, k, orientation)?;
    // The two fits are parametrised differently: each extremum goes to the parameter of the
    // closest point of the shape.
    let opened = shape.open_at(0.0)?;
    let mut placed = Vec::with_capacity(k);
    for u in on_rough {
        let hit = closest_point(&opened, rough.eval(u)?)?;
        placed.push(hit.param);
    }
    refine_closed_extrema(&shape, &mut placed, first_rising, orientation)?;
    if placed.windows(2).any(|w| !(w[1] > w[0])) || placed.iter().any(|&u| !(u > 0.0 && u < 1.0)) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the {k} automatic curvature extrema of the closed curve do not come in order: give their parameters"
            ),
        ));
    }
    Ok(ClosedStart {
        rotation,
        shape: opened,
        params,
        placed: Some((placed, first_rising)),
    })
}

/// Closed curves: nested periodic knot vectors (those of [`nested_levels`], each with the
/// closing point `0` as a knot); the containers are the wrapped ones.
struct Closed {
    levels: Vec<(KnotVector<f64>, ClosedCurve2)>,
}

impl Topology for Closed {
    type Curve = ClosedCurve2;

    fn num_levels(&self) -> usize {
        self.levels.len()
    }

    fn fit(
        &self,
        level: usize,
        points: &[Vector2<f64>],
        params: &[f64],
    ) -> Result<(Self::Curve, Vec<f64>)> {
        fit_closed_with_correction(points, params, &self.levels[level].1, 12)
    }

    fn problem(
        &self,
        level: usize,
        points: &[Vector2<f64>],
        params: &[f64],
        objective: Objective,
        extrema: &[f64],
        first_sign: f64,
    ) -> Result<EraserProblem> {
        EraserProblem::new_closed(
            self.levels[level].1.wrapped().knots(),
            points,
            params,
            objective,
            extrema.to_vec(),
            first_sign,
        )
    }

    fn control_points(curve: &Self::Curve) -> Vec<Vector2<f64>> {
        curve.wrapped().control_points().to_vec()
    }

    fn solution(
        &self,
        level: usize,
        control: Vec<Vector2<f64>>,
    ) -> Result<(Self::Curve, Curve2<f64>)> {
        let wrapped = BSpline::new(self.levels[level].1.wrapped().knots().clone(), control)?;
        Ok((PeriodicBSpline::from_wrapped(&wrapped)?, wrapped))
    }

    fn next(
        &self,
        level: usize,
        curve: &Self::Curve,
        anchors: Vec<f64>,
        points: &[Vector2<f64>],
    ) -> Result<(Self::Curve, Vec<f64>)> {
        let mut refined = curve.clone();
        for u in new_knots(&self.levels[level].0, &self.levels[level + 1].0) {
            refined = refined.insert_knot(u, 1)?;
        }
        let params = project_ordered(&refined, points, &sorted_in_period(&anchors))?;
        Ok((refined, params))
    }
}

/// The constrained fit of closed `points` (normalised, at `params` in `[0, 1)`) on the
/// periodic knots of `clamped` (see [`periodic_space`]), with the allowed extrema at the
/// knots `extrema` and the sign of the first piece `first_sign`: the continuation of open
/// curves over nested periodic knot vectors. The attempt's curve is the wrapped container.
/// `None` when no strictly feasible curve was found.
pub(crate) fn attempt_closed(
    points: &[Vector2<f64>],
    params: &[f64],
    clamped: &KnotVector<f64>,
    extrema: &[f64],
    first_sign: f64,
    options: &SmoothingOptions,
) -> Result<Option<Attempt>> {
    if extrema.len() % 2 != 0 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "a closed curve has as many curvature maxima as minima",
        ));
    }
    // Levels with fewer knots than a periodic curve of degree p needs are skipped.
    let levels: Vec<(KnotVector<f64>, ClosedCurve2)> = nested_levels(clamped, extrema)?
        .into_iter()
        .filter_map(|level| periodic_space(&level).ok().map(|space| (level, space)))
        .collect();
    if levels.is_empty() {
        return Ok(None);
    }
    continuation(
        &Closed { levels },
        points,
        params,
        extrema,
        first_sign,
        options,
    )
}

/// Foot-point parameters as [`project_ordered`] takes them: in `[0, 1]` and not decreasing
/// (a foot point that crossed the closing point is moved back to its end of the period).
fn sorted_in_period(params: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = params.iter().map(|u| u.clamp(0.0, 1.0)).collect();
    for k in 1..out.len() {
        if out[k] < out[k - 1] {
            out[k] = out[k - 1];
        }
    }
    out
}

/// Samples round a closed curve for the placement of its extrema.
const PLACEMENT_SAMPLES: usize = 400;

/// `(u, oriented κ(u), arc-length weight)` at [`PLACEMENT_SAMPLES`] parameters of one period.
fn closed_curvature_samples(
    curve: &ClosedCurve2,
    orientation: f64,
) -> Result<Vec<(f64, f64, f64)>> {
    let du = 1.0 / PLACEMENT_SAMPLES as f64;
    (0..PLACEMENT_SAMPLES)
        .map(|k| {
            let u = k as f64 * du;
            let d = curve.derivatives(u, 2)?;
            let speed = d[1].norm();
            let kappa = (d[1].x * d[2].y - d[1].y * d[2].x) / (speed * speed * speed);
            Ok((u, orientation * kappa, speed * du))
        })
        .collect()
}

/// `cost[i][j − i]`: the weighted least-squares cost of making `values[i..=j]` monotone
/// (increasing or not), for every window.
fn window_costs(values: &[(f64, f64, f64)], increasing: bool) -> Vec<Vec<f64>> {
    (0..values.len())
        .map(|i| super::placement::isotonic_prefix_costs(&values[i..], increasing))
        .collect()
}

/// The best split of `values` into `k + 1` monotone pieces alternating in direction, the
/// first and the last (one piece across the closing point) rising when `first_rising`, every
/// piece at least `min_width` samples wide: the total cost and the `k` indices where the
/// pieces meet (the extrema).
fn alternating_split(
    rising: &[Vec<f64>],
    falling: &[Vec<f64>],
    k: usize,
    first_rising: bool,
    min_width: usize,
) -> Option<(f64, Vec<usize>)> {
    let m = rising.len();
    let cost = |piece: usize, i: usize, j: usize| -> f64 {
        let up = (piece % 2 == 0) == first_rising;
        if up {
            rising[i][j - i]
        } else {
            falling[i][j - i]
        }
    };
    // best[piece][j]: the least cost of pieces 0..=piece covering samples 0..=j, piece ending
    // at j; from[piece][j]: where it starts.
    let mut best = vec![vec![f64::INFINITY; m]; k + 1];
    let mut from = vec![vec![0usize; m]; k + 1];
    for (j, first) in best[0].iter_mut().enumerate().skip(min_width - 1) {
        *first = cost(0, 0, j);
    }
    for piece in 1..=k {
        for j in 0..m {
            for i in 1..=j {
                if j + 1 - i < min_width || !best[piece - 1][i - 1].is_finite() {
                    continue;
                }
                let total = best[piece - 1][i - 1] + cost(piece, i, j);
                if total < best[piece][j] {
                    best[piece][j] = total;
                    from[piece][j] = i;
                }
            }
        }
    }
    let total = best[k][m - 1];
    if !total.is_finite() {
        return None;
    }
    let mut cuts = vec![0; k];
    let mut j = m - 1;
    for piece in (1..=k).rev() {
        let i = from[piece][j];
        cuts[piece - 1] = i;
        j = i - 1;
    }
    Some((total, cuts))
}

/// Where the `k` allowed extrema of a closed curve go (all placed automatically): the split
/// of the curvature of `curve` round its period into `k` monotone pieces, alternately rising
/// and falling, that needs the least change (weighted isotonic regression along the arc
/// length), over rotations of the closing point. Returns the parameter where a closing point
/// inside a monotone piece (halfway between the last extremum and the first) should go.
pub(crate) fn closed_seam(curve: &ClosedCurve2, k: usize, orientation: f64) -> Result<f64> {
    let samples = closed_curvature_samples(curve, orientation)?;
    let m = samples.len();
    let min_width = (m / 100).max(2);
    let mut best: Option<(f64, f64)> = None;
    let rotations = 16;
    for r in 0..rotations {
        let shift = r * m / rotations;
        let rotated: Vec<(f64, f64, f64)> = (0..m).map(|i| samples[(i + shift) % m]).collect();
        let rising = window_costs(&rotated, true);
        let falling = window_costs(&rotated, false);
        for first_rising in [true, false] {
            let Some((cost, cuts)) =
                alternating_split(&rising, &falling, k, first_rising, min_width)
            else {
                continue;
            };
            if best.is_none_or(|(c, _)| cost < c) {
                // Halfway (cyclically) from the last extremum to the first.
                let last = cuts[k - 1];
                let middle = (last + (cuts[0] + m - last) / 2 + shift) % m;
                best = Some((cost, samples[middle].0));
            }
        }
    }
    best.map(|(_, u)| u).ok_or_else(|| {
        Error::new(
            ErrorKind::InvalidArgument,
            format!("a closed curve sampled at {m} points has no room for {k} curvature extrema"),
        )
    })
}

/// The allowed extrema of a closed curve whose closing point lies inside a monotone piece
/// (after [`closed_seam`]): their parameters and whether the first piece rises.
pub(crate) fn place_closed_extrema(
    curve: &ClosedCurve2,
    k: usize,
    orientation: f64,
) -> Result<(Vec<f64>, bool)> {
    let samples = closed_curvature_samples(curve, orientation)?;
    let m = samples.len();
    let min_width = (m / 100).max(2);
    let rising = window_costs(&samples, true);
    let falling = window_costs(&samples, false);
    let mut best: Option<(f64, Vec<usize>, bool)> = None;
    for first_rising in [true, false] {
        if let Some((cost, cuts)) = alternating_split(&rising, &falling, k, first_rising, min_width)
            && best.as_ref().is_none_or(|(c, _, _)| cost < *c)
        {
            best = Some((cost, cuts, first_rising));
        }
    }
    let (_, cuts, first_rising) = best.ok_or_else(|| {
        Error::new(
            ErrorKind::InvalidArgument,
            format!("a closed curve sampled at {m} points has no room for {k} curvature extrema"),
        )
    })?;
    // An extremum between the last sample of one piece and the first of the next.
    let du = 1.0 / m as f64;
    Ok((
        cuts.iter().map(|&i| samples[i].0 - 0.5 * du).collect(),
        first_rising,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::barrier::BarrierProblem;
    use nalgebra::DVector;

    /// The closed problem of a wobbly contour: derivatives of every function of the barrier
    /// method against central differences (the wrapped control points fold onto the free
    /// ones, so a wrong fold shows here).
    #[test]
    fn closed_problem_derivatives_match_differences() {
        let points: Vec<Vector2<f64>> = (0..50)
            .map(|k| {
                let t = std::f64::consts::TAU * f64::from(k) / 50.0;
                let r = 0.4 + 0.01 * (7.0 * t).sin();
                Vector2::new(1.5 * r * t.cos(), r * t.sin())
            })
            .collect();
        let (shape, params) = closed_shape(&points, 3, 12).unwrap();
        let knots = shape.wrapped().knots().clone();
        let control = shape.wrapped().control_points().to_vec();
        for objective in [Objective::MaxDeviation, Objective::LeastSquares] {
            let mut problem = EraserProblem::new_closed(
                &knots,
                &points,
                &params,
                objective,
                vec![0.2, 0.45, 0.7, 0.95],
                1.0,
            )
            .unwrap();
            problem.set_projection(true);
            let x0 = problem.variables(&control, 1.5);
            problem.set_excursions(&x0, 0.05);
            problem.rescale(&x0);
            problem.commit(&x0);
            problem.start_homotopy(&x0, 0.1);
            problem.set_relaxed(true, 0.7);
            let mut x = problem.variables(&control, 1.5);
            let tau = problem.tau_index();
            x[tau] = 0.3;
            let dim = problem.dimension();
            assert_eq!(dim, x.len());
            let h = 1e-6;
            let gradient = problem.objective_gradient(&x);
            let jacobian = problem.constraint_jacobian(&x);
            let m = problem.num_constraints();
            let weights = DVector::from_fn(m, |i, _| 0.5 + (i % 7) as f64 / 7.0);
            let hessian = {
                let mut dense = nalgebra::DMatrix::zeros(dim, dim);
                problem.add_weighted_constraint_hessian(&x, &weights, &mut dense);
                dense
            };
            let objective_hessian = nalgebra::DMatrix::from(&problem.objective_hessian(&x));
            let jac_dense = nalgebra::DMatrix::from(&jacobian);
            for k in 0..dim {
                let mut plus = x.clone();
                let mut minus = x.clone();
                plus[k] += h;
                minus[k] -= h;
                let df = (problem.objective(&plus) - problem.objective(&minus)) / (2.0 * h);
                assert!(
                    (df - gradient[k]).abs() < 1e-5 * (1.0 + df.abs()),
                    "{objective:?} ∂f/∂x{k}: {df} vs {}",
                    gradient[k]
                );
                let (cp, cm) = (problem.constraints(&plus), problem.constraints(&minus));
                let dg_p = problem.objective_gradient(&plus);
                let dg_m = problem.objective_gradient(&minus);
                let jp = nalgebra::DMatrix::from(&problem.constraint_jacobian(&plus));
                let jm = nalgebra::DMatrix::from(&problem.constraint_jacobian(&minus));
                for i in 0..m {
                    let dc = (cp[i] - cm[i]) / (2.0 * h);
                    assert!(
                        (dc - jac_dense[(i, k)]).abs() < 1e-5 * (1.0 + dc.abs()),
                        "{objective:?} ∂c{i}/∂x{k}: {dc} vs {}",
                        jac_dense[(i, k)]
                    );
                }
                for l in 0..dim {
                    let d2f = (dg_p[l] - dg_m[l]) / (2.0 * h);
                    assert!(
                        (d2f - objective_hessian[(l, k)]).abs() < 1e-4 * (1.0 + d2f.abs()),
                        "{objective:?} ∂²f/∂x{l}∂x{k}: {d2f} vs {}",
                        objective_hessian[(l, k)]
                    );
                    let d2c: f64 = (0..m)
                        .map(|i| weights[i] * (jp[(i, l)] - jm[(i, l)]) / (2.0 * h))
                        .sum();
                    assert!(
                        (d2c - hessian[(l, k)]).abs() < 1e-4 * (1.0 + d2c.abs()),
                        "{objective:?} Σ w ∂²c/∂x{l}∂x{k}: {d2c} vs {}",
                        hessian[(l, k)]
                    );
                }
            }
        }
    }
}
