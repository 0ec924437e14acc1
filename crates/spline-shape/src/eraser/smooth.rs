//! The eraser's pipeline: [`smooth`], the same stages for open and closed data.

use super::driver::{Attempt, Task, attempt_from};
use super::input::{check_options, distinct, frame, polygon_area};
use super::screening::{attempt_screened, recoverable};
use super::topology::{Closed, Open, Start, Topology};
use super::types::{
    CurvatureExtremum, DEVIATION_WARNING_FACTOR, DEVIATION_WARNING_FLOOR, ExtremumKind,
    SmoothedCurve, SmoothingOptions, WarmStart, extrema_words,
};
use nalgebra::Vector2;
use spline_algebra::planar_features;
use spline_core::KnotVector;
use spline_core::{Error, ErrorKind, Result};
use spline_fit::{curvature_knots_with, two_sided_deviation};
use spline_geom::Curve2;

/// Fits `points` with a planar B-spline curve whose curvature has only the allowed extrema
/// (thesis ch. 6, built on spline-fit as the module documentation describes).
///
/// The data are translated and scaled to unit size for the computation and the result is
/// mapped back, so the answer does not depend on units. Consecutive repeated points count
/// once. The first and last data points stay at the ends of the curve.
///
/// Many data points (over 4096) with the max deviation objective are solved on a working
/// set of them that grows where the others lie farther from the curve, until none does: the
/// largest distance is that of the whole problem, in a time that grows with the points
/// that decide it rather than with all of them.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_shape::{SmoothingOptions, smooth};
/// // A noisy quarter of an ellipse; its curvature rises from (0, 1) to (2, 0).
/// let points: Vec<Vector2<f64>> = (0..60)
///     .map(|k| {
///         let t = f64::from(k) / 59.0 * std::f64::consts::FRAC_PI_2;
///         let noise = 1e-3 * f64::from((k * 37) % 7) / 7.0;
///         Vector2::new(2.0 * t.sin(), t.cos() + noise)
///     })
///     .collect();
/// let mut options = SmoothingOptions::new(8);
/// options.extrema = vec!["max@0.999".parse()?]; // monotone curvature up to the end
/// let result = smooth(&points, &options)?;
/// assert_eq!(result.extrema.len(), 1);
/// assert!(result.deviation.to_curve.max < 3e-3);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for a degree below 3, no extrema or kinds that do not
/// alternate, parameters outside `(0, 1)` or not increasing, or more extrema than the control
/// points allow; [`ErrorKind::TooFewPoints`] / [`ErrorKind::NonFinite`] /
/// [`ErrorKind::DegenerateGeometry`] for unusable data; [`ErrorKind::NoConvergence`] when no
/// curve with these extrema and control points is found near the data, or the only ones
/// found leave the data (the message says what to change).
pub fn smooth(points: &[Vector2<f64>], options: &SmoothingOptions) -> Result<SmoothedCurve> {
    check_options(options)?;
    if options.closed {
        run::<Closed>(points, options, None)
    } else {
        run::<Open>(points, options, None)
    }
}

/// [`smooth`] of data near those of an earlier result (a dragged point, a few points more
/// or fewer), started from that result: its knots, its allowed extrema and its curve, with
/// the interior-point method entering at the finest level where the curve already meets
/// the conditions (they depend on the knots, not on the data). Where the earlier result does
/// not fit the request (another number of control points, degree or extrema, other kinds
/// of extrema or other places asked for them, closed data) or the warm start finds no curve, this is [`smooth`] itself.
/// The problem is the same as [`smooth`]'s (the same conditions and objective, on the
/// earlier knots), solved from another start in a fraction of the Newton steps: the curve
/// found may differ from a fresh start's as much as fresh starts on nearby data differ
/// (measured on clarkv's drags: within 0.1 % or closer to the data).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_shape::{SmoothingOptions, smooth, smooth_from};
/// let mut points: Vec<Vector2<f64>> = (0..80)
///     .map(|k| {
///         let t = f64::from(k) / 79.0 * std::f64::consts::FRAC_PI_2;
///         Vector2::new(2.0 * t.sin(), t.cos() + 1e-3 * f64::from((k * 37) % 7) / 7.0)
///     })
///     .collect();
/// let mut options = SmoothingOptions::new(10);
/// options.extrema = vec!["max@0.999".parse()?];
/// let first = smooth(&points, &options)?;
/// points[40].y += 2e-3; // a dragged point
/// let next = smooth_from(&points, &options, &first.warm_start())?;
/// assert_eq!(next.levels, 1); // entered at the finest level
/// assert_eq!(next.extrema.len(), 1);
/// assert!(next.deviation.to_curve.max < 5e-3);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`smooth`].
pub fn smooth_from(
    points: &[Vector2<f64>],
    options: &SmoothingOptions,
    previous: &WarmStart,
) -> Result<SmoothedCurve> {
    check_options(options)?;
    let fits = !options.closed
        && !previous.closed
        && previous.first_sign.abs() == 1.0
        && previous.curve.domain() == (0.0, 1.0)
        && previous.curve.degree() == options.degree
        && previous.curve.control_points().len() == options.control_points
        && previous.allowed_extrema.len() == options.extrema.len()
        && previous.allowed_extrema.windows(2).all(|w| w[0] < w[1])
        && previous.allowed_extrema.iter().all(|&u| {
            u > 0.0 && u < 1.0 && previous.curve.knots().multiplicity(u) + 2 >= options.degree
        })
        // Extrema placed by the caller stay where they are asked.
        && options
            .extrema
            .iter()
            .zip(&previous.allowed_extrema)
            .all(|(e, &u)| e.at.is_none_or(|at| at == u));
    if options.closed {
        run::<Closed>(points, options, None)
    } else {
        run::<Open>(points, options, fits.then_some(previous))
    }
}

/// The eraser's stages, once for both topologies: the data in unit size, the start (shape and
/// placed extrema), attempts on knots that follow the shape, the closest curve found.
fn run<T: Topology>(
    points: &[Vector2<f64>],
    options: &SmoothingOptions,
    warm: Option<&WarmStart>,
) -> Result<SmoothedCurve> {
    let p = options.degree;
    let n = options.control_points;
    let mut data = distinct(points)?;
    T::count_once(&mut data);
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
    if !(size > 0.0) {
        return Err(Error::new(
            ErrorKind::DegenerateGeometry,
            "the data points all coincide",
        ));
    }
    let mut unit: Vec<Vector2<f64>> = data.iter().map(|q| (q - middle) / size).collect();
    let orientation = if polygon_area(&unit) >= 0.0 {
        1.0
    } else {
        -1.0
    };

    // 1. The shape: centripetal parameters, least squares, parameter correction (a closed
    // contour's periodic fit is opened at its closing point, which moves to a data point
    // inside a monotone stretch); 2. the allowed extrema on the shape.
    let Start {
        rotation,
        shape: preliminary,
        params,
        placed,
        first_sign,
    } = T::start(&unit, options, orientation)?;
    data.rotate_left(rotation);
    unit.rotate_left(rotation);
    // The data the deviations are measured against.
    let polyline = T::polyline(&data);
    let start_extrema = planar_features(&preliminary, 1e-10)
        .map(|f| f.curvature_extrema.len())
        .unwrap_or(0);
    let least_squares_deviation = two_sided_deviation(&preliminary, &T::polyline(&unit))?
        .to_curve
        .max
        * size;
    let fixed: Vec<(f64, usize)> = placed.iter().map(|&u| (u, p - 2)).collect();

    // 3. Attempts with knots that follow the shape, densities in turn (a closed curve's `N`
    // periodic knots are the clamped vector's `0` and its interior knots).
    let basis_count = T::basis_count(n, p);
    let mut best: Option<SmoothedCurve> = None;
    let mut newton_steps = 0;
    let mut left_the_data = false;
    // What an attempt found, measured on the data in their units; `None` when the curve
    // leaves the data between data points or has no curvature somewhere.
    let mut measure = |found: Attempt,
                       exponent: f64,
                       placed: &[f64],
                       first_sign: f64,
                       best: Option<&SmoothedCurve>|
     -> Result<Option<SmoothedCurve>> {
        newton_steps += found.newton_steps;
        let world = found.curve.map_control_points(|c| c * size + middle);
        let (curve, periodic) = T::result(world)?;
        let mut deviation = two_sided_deviation(&curve, &polyline)?;
        T::in_data_order(&mut deviation, rotation, data.len());
        // A curve that strays from the data between data points is no answer: the curve →
        // data distance may exceed the data → curve one only by the sagitta of the data's
        // own chords.
        if deviation.to_data_excess > 3.0 * deviation.to_curve.max + 1e-3 * size {
            left_the_data = true;
            return Ok(None);
        }
        let better = best.is_none_or(|b| deviation.to_curve.max < b.deviation.to_curve.max);
        if !better {
            return Ok(None);
        }
        // A curve whose velocity vanishes somewhere has no curvature there: no answer.
        let Ok(features) = T::features(&curve, periodic.as_ref()) else {
            return Ok(None);
        };
        let extrema = features
            .curvature_extrema
            .iter()
            .map(|&u| classify(&curve, u, orientation))
            .collect::<Result<Vec<_>>>()?;
        Ok(Some(SmoothedCurve {
            curve,
            periodic,
            first_point: rotation,
            deviation,
            extrema,
            inflections: features.inflections,
            start_extrema,
            least_squares_deviation,
            warnings: Vec::new(),
            orientation,
            knot_exponent: exponent,
            levels: found.levels,
            refinements: found.refinements,
            conditions: found.conditions,
            newton_steps: 0,
            allowed_extrema: placed.to_vec(),
            first_sign,
        }))
    };

    // A warm start: the earlier result's knots, extrema and curve, in this data's frame.
    // (Only where the kinds of the extrema, read on this data's orientation, give the same
    // sign on the first piece.)
    let warm = warm.filter(|w| w.first_sign == first_sign);
    if let Some(previous) = warm {
        let start = previous.curve.map_control_points(|c| (c - middle) / size);
        let task = Task {
            points: &unit,
            params: &params,
            knots: previous.curve.knots(),
            extrema: &previous.allowed_extrema,
            first_sign: previous.first_sign,
            options,
        };
        let found = match attempt_from::<T>(task, &start, true) {
            Ok(found) => found,
            Err(e) if recoverable(&e) => None,
            Err(e) => return Err(e),
        };
        if let Some(found) = found {
            best = measure(
                found,
                previous.knot_exponent,
                &previous.allowed_extrema,
                previous.first_sign,
                best.as_ref(),
            )?;
        }
    }

    // 3. Attempts with knots that follow the shape, densities in turn (a closed curve's `N`
    // periodic knots are the clamped vector's `0` and its interior knots).
    for &exponent in &options.knot_exponents {
        if best.is_some() && (warm.is_some() || !options.thorough) {
            break;
        }
        let Ok(knots) = curvature_knots_with(
            &preliminary,
            p,
            basis_count,
            exponent,
            options.knot_floor,
            &fixed,
        ) else {
            continue;
        };
        let task = Task {
            points: &unit,
            params: &params,
            knots: &knots,
            extrema: &placed,
            first_sign,
            options,
        };
        let found = match attempt_screened::<T>(task) {
            Ok(found) => found,
            Err(e) if recoverable(&e) => None,
            Err(e) => return Err(e),
        };
        let Some(found) = found else { continue };
        if let Some(better) = measure(found, exponent, &placed, first_sign, best.as_ref())? {
            best = Some(better);
        }
    }
    // 4. With `knot_search`, the interior knots moved one at a time while that brings the
    // curve closer to the data.
    if options.knot_search
        && !T::CLOSED
        && warm.is_none()
        && let Some(found) = best.take()
    {
        let knots = found.curve.knots().clone();
        let task = Task {
            points: &unit,
            params: &params,
            knots: &knots,
            extrema: &placed,
            first_sign,
            options,
        };
        let to_unit = |c: &Vector2<f64>| (c - middle) / size;
        best = Some(search_knots::<T>(task, found, to_unit, &mut measure)?);
    }
    match best {
        Some(mut result) => {
            result.newton_steps = newton_steps;
            let max = result.deviation.to_curve.max;
            if max > DEVIATION_WARNING_FACTOR * least_squares_deviation
                && max > DEVIATION_WARNING_FLOOR * size
            {
                result.warnings.push(format!(
                    "the curve is {max:.3e} from the data, {:.1} times the least-squares fit's {least_squares_deviation:.3e} with the same {n} control points: {} cannot follow the turns of the data (allow more extrema, or more control points)",
                    max / least_squares_deviation,
                    extrema_words(placed.len()),
                ));
            }
            Ok(result)
        }
        None => Err(Error::new(
            ErrorKind::NoConvergence,
            format!(
                "no curve with {} and {n} control points was found near the data{}: allow more control points or more extrema",
                extrema_words(placed.len()),
                if left_the_data {
                    " (the curves found leave the data between data points)"
                } else {
                    ""
                }
            ),
        )),
    }
}

/// The most problems [`search_knots`] solves.
const KNOT_SEARCH_SOLVES: usize = 400;

/// The largest and smallest steps of [`search_knots`], in parts of the gap to the
/// neighbouring knot.
const KNOT_SEARCH_STEPS: (f64, f64) = (0.25, 1.0 / 32.0);

/// [`SmoothingOptions::knot_search`]: a pattern search over the free interior knots of
/// `found` (those not at an allowed extremum, not repeated). Each in turn moves by a step
/// towards either neighbour (a part of the gap to it, so the order of the knots holds) and
/// the problem is solved on the moved knots, from the closest curve's control points so far
/// where that works (`to_unit` maps them to the data's unit frame) and afresh otherwise; a
/// move that brings the curve closer is kept. The step halves after a pass over the knots without a
/// move kept, from a quarter of the gap down to 1/32, and the search stops after
/// [`KNOT_SEARCH_SOLVES`] problems. The result is `found` or closer to the data.
fn search_knots<T: Topology>(
    task: Task<'_>,
    found: SmoothedCurve,
    to_unit: impl Fn(&Vector2<f64>) -> Vector2<f64>,
    measure: &mut impl FnMut(
        Attempt,
        f64,
        &[f64],
        f64,
        Option<&SmoothedCurve>,
    ) -> Result<Option<SmoothedCurve>>,
) -> Result<SmoothedCurve> {
    let p = found.curve.degree();
    let exponent = found.knot_exponent;
    let mut knots = found.curve.knots().knots().to_vec();
    let mut best = found;
    let (mut step, smallest) = KNOT_SEARCH_STEPS;
    let mut solves = 0;
    'search: while step >= smallest {
        let mut moved = false;
        for i in p + 1..knots.len() - p - 1 {
            let free = !task.extrema.contains(&knots[i])
                && knots[i] != knots[i - 1]
                && knots[i] != knots[i + 1];
            if !free {
                continue;
            }
            for towards in [i + 1, i - 1] {
                if solves == KNOT_SEARCH_SOLVES {
                    break 'search;
                }
                solves += 1;
                let mut trial = knots.clone();
                trial[i] += step * (knots[towards] - knots[i]);
                let Ok(trial_knots) = KnotVector::new(p, trial.clone()) else {
                    continue;
                };
                let moved_task = Task {
                    knots: &trial_knots,
                    ..task
                };
                let points = best.curve.control_points().iter().map(&to_unit).collect();
                let start = Curve2::new_unchecked(trial_knots.clone(), points);
                let warm = attempt_from::<T>(moved_task, &start, false);
                let found = match warm {
                    Ok(Some(found)) => Ok(Some(found)),
                    Ok(None) => attempt_screened::<T>(moved_task),
                    Err(e) if recoverable(&e) => attempt_screened::<T>(moved_task),
                    Err(e) => Err(e),
                };
                let found = match found {
                    Ok(Some(found)) => found,
                    Ok(None) => continue,
                    Err(e) if recoverable(&e) => continue,
                    Err(e) => return Err(e),
                };
                if let Some(closer) =
                    measure(found, exponent, task.extrema, task.first_sign, Some(&best))?
                {
                    best = closer;
                    knots = trial;
                    moved = true;
                    break;
                }
            }
        }
        if !moved {
            step /= 2.0;
        }
    }
    Ok(best)
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
