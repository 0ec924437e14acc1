//! The start of the eraser on closed curves: the least-squares shape round the contour, where
//! its closing point goes (inside a monotone stretch of the curvature) and where the allowed
//! extrema go round it (the best split of the curvature into alternately rising and falling
//! pieces).

use super::placement::{
    curvature_samples, fit_with_correction, isotonic_prefix_costs, refine_extrema,
};
use super::topology::{Closed, ClosedCurve2};
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result};
use spline_fit::{Parametrization, closest_point, parametrize_above_noise};
use spline_geom::{Curve2, PeriodicBSpline};

/// Centripetal parameters of closed data in `[0, 1)`, measured above the data's noise
/// ([`parametrize_above_noise`]): the closing chord (last point back to the first) counts as
/// one more chord.
pub(crate) fn closed_parameters(points: &[Vector2<f64>]) -> Result<Vec<f64>> {
    let mut loop_points = points.to_vec();
    loop_points.push(points[0]);
    let mut params = parametrize_above_noise(&loop_points, &Parametrization::Centripetal)?;
    params.pop();
    Ok(params)
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
    fit_with_correction::<Closed>(points, &params, &space, 8)
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
    refine_extrema(
        &curvature_samples(&shape, PLACEMENT_SAMPLES, true, orientation)?,
        &mut placed,
        first_rising,
    );
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

/// Samples round a closed curve for the placement of its extrema.
const PLACEMENT_SAMPLES: usize = 400;

/// `cost[i][j − i]`: the weighted least-squares cost of making `values[i..=j]` monotone
/// (increasing or not), for every window.
fn window_costs(values: &[(f64, f64, f64)], increasing: bool) -> Vec<Vec<f64>> {
    (0..values.len())
        .map(|i| isotonic_prefix_costs(&values[i..], increasing))
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
    let samples = curvature_samples(curve, PLACEMENT_SAMPLES, true, orientation)?;
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
    let samples = curvature_samples(curve, PLACEMENT_SAMPLES, true, orientation)?;
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
    use crate::eraser::Objective;
    use crate::eraser::problem::EraserProblem;
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
            let mut problem = EraserProblem::new(
                &knots,
                true,
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
