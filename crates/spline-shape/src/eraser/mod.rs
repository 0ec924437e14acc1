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

mod closed;
mod distances;
mod driver;
mod pieces;
mod placement;
mod problem;
mod request;
mod verify;

pub use verify::{SampledExtremum, sampled_curvature_extrema};

/// The most curvature extrema a smoothing may allow (each one is a knot of the curve and a
/// slot of the placement; far more than any shape needs).
pub const MAX_CURVATURE_EXTREMA: usize = 1000;

use crate::barrier::BarrierOptions;
use nalgebra::Vector2;
use placement::{fit_with_correction, place_extrema};
use spline_algebra::planar_features;
use spline_core::{Error, ErrorKind, Result};
use spline_fit::{
    Parametrization, TwoSidedDeviation, curvature_knots_with, nurbs_book_knots, parametrize,
    two_sided_deviation,
};
use spline_geom::{Curve2, PeriodicBSpline};
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
    /// Exponents `β` of the knot density `|C′| (κ L + c)^β`
    /// ([`spline_fit::curvature_knots`]) tried in turn: the next one when no curve is found
    /// (or the curve leaves the data) with the previous one, or every one with
    /// [`SmoothingOptions::thorough`].
    pub knot_exponents: Vec<f64>,
    /// Floor `c` of the knot density.
    pub knot_floor: f64,
    /// Try every knot density and keep the closest curve (instead of the first found).
    pub thorough: bool,
    /// Centring steps of phase I, at most.
    pub max_rounds: usize,
    /// Passes of refinement of the active conditions, at most.
    pub max_refinements: usize,
    /// Settings of the interior-point solver.
    pub barrier: BarrierOptions,
    /// The data are a closed contour (the last point joins the first; a repeated first point
    /// at the end counts once): the result is a periodic curve, the allowed extrema alternate
    /// around it and are as many maxima as minima.
    pub closed: bool,
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
            knot_exponents: vec![0.3, 0.5, 0.7],
            knot_floor: 0.6,
            thorough: false,
            max_rounds: 40,
            max_refinements: 6,
            barrier: BarrierOptions {
                gap_tolerance: 1e-7,
                max_newton_iterations: 60,
                ..BarrierOptions::default()
            },
            closed: false,
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
    /// The smoothed curve, on `[0, 1]` (a closed one opened at its closing point: the same
    /// points, clamped at both ends).
    pub curve: Curve2<f64>,
    /// For closed data ([`SmoothingOptions::closed`]), the smoothed curve as a periodic
    /// B-spline of period 1 (`curve` is it opened at `0`).
    pub periodic: Option<PeriodicBSpline<f64, Vector2<f64>>>,
    /// The data point (after consecutive repetitions are dropped) where the curve starts: `0`,
    /// unless the closing point of a closed contour moved into a monotone stretch of the
    /// curvature.
    pub first_point: usize,
    /// The deviation from the data both ways: data → curve by closest points and curve →
    /// data polyline.
    pub deviation: TwoSidedDeviation<f64>,
    /// The curvature extrema of the result.
    pub extrema: Vec<CurvatureExtremum>,
    /// The inflections of the result.
    pub inflections: Vec<f64>,
    /// The number of curvature extrema of the least-squares fit of the same size.
    pub start_extrema: usize,
    /// `+1` if the data run counter-clockwise (the oriented curvature is the signed one),
    /// `−1` otherwise.
    pub orientation: f64,
    /// The exponent of the knot density of the result.
    pub knot_exponent: f64,
    /// Levels of the coarse-to-fine continuation.
    pub levels: usize,
    /// Refinement passes that split active pieces.
    pub refinements: usize,
    /// Sign conditions in the final problem.
    pub conditions: usize,
    /// Newton steps of the interior-point method in all (phase I included, every attempt).
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
/// once. The first and last data points stay at the ends of the curve.
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
    let p = options.degree;
    let n = options.control_points;
    check_options(options)?;
    let mut data = distinct(points)?;
    if options.closed && data.len() > 2 && data.last() == data.first() {
        data.pop();
    }
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
    // contour's periodic fit is opened at its closing point); 2. the allowed extrema on the
    // shape. The first piece rises towards a maximum.
    let kind_sign = |kind: ExtremumKind| match kind {
        ExtremumKind::Maximum => orientation,
        ExtremumKind::Minimum => -orientation,
    };
    let mut rotation = 0;
    let (preliminary, params, placed, first_sign) = if options.closed {
        let automatic = options
            .extrema
            .iter()
            .all(|e| e.at.is_none())
            .then_some(options.extrema.len());
        let start = closed::closed_start(&unit, p, n, automatic, orientation)?;
        // The closing point moves to a data point inside a monotone stretch.
        rotation = start.rotation;
        data.rotate_left(rotation);
        unit.rotate_left(rotation);
        let (placed, first_sign) = match start.placed {
            Some((placed, rising)) => (placed, if rising { orientation } else { -orientation }),
            None => (
                place_extrema(&start.shape, &options.extrema, orientation)?,
                kind_sign(options.extrema[0].kind),
            ),
        };
        (start.shape, start.params, placed, first_sign)
    } else {
        let params = parametrize(&unit, &Parametrization::Centripetal)?;
        let base = nurbs_book_knots(p, n, &params)?;
        let (fit, params) = fit_with_correction(&unit, &params, &base, 8)?;
        let placed = place_extrema(&fit, &options.extrema, orientation)?;
        (fit, params, placed, kind_sign(options.extrema[0].kind))
    };
    // The data the deviations are measured against: a closed contour's polyline closes.
    let mut polyline = data.clone();
    if options.closed {
        polyline.push(data[0]);
    }
    let start_extrema = planar_features(&preliminary, 1e-10)
        .map(|f| f.curvature_extrema.len())
        .unwrap_or(0);
    let fixed: Vec<(f64, usize)> = placed.iter().map(|&u| (u, p - 2)).collect();

    // 3. Attempts with knots that follow the shape, densities in turn (a closed curve's `N`
    // periodic knots are the clamped vector's `0` and its interior knots).
    let basis_count = if options.closed { n + p } else { n };
    let mut best: Option<SmoothedCurve> = None;
    let mut newton_steps = 0;
    let mut left_the_data = false;
    for &exponent in &options.knot_exponents {
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
        let found = if options.closed {
            closed::attempt_closed(&unit, &params, &knots, &placed, first_sign, options)
        } else {
            driver::attempt(&unit, &params, &knots, &placed, first_sign, options)
        };
        let found = match found {
            Ok(found) => found,
            Err(e)
                if matches!(
                    e.kind(),
                    ErrorKind::SchoenbergWhitney
                        | ErrorKind::SingularSystem
                        | ErrorKind::NonFinite
                        | ErrorKind::NoConvergence
                ) =>
            {
                None
            }
            Err(e) => return Err(e),
        };
        let Some(found) = found else { continue };
        newton_steps += found.newton_steps;
        let world = found.curve.map_control_points(|c| c * size + middle);
        let (curve, periodic) = if options.closed {
            let periodic = PeriodicBSpline::from_wrapped(&world)?;
            (periodic.open_at(0.0)?, Some(periodic))
        } else {
            (world, None)
        };
        let mut deviation = two_sided_deviation(&curve, &polyline)?;
        if options.closed {
            in_data_order(&mut deviation, rotation, data.len());
        }
        // A curve that strays from the data between data points is no answer: the curve →
        // data distance may exceed the data → curve one only by the sagitta of the data's
        // own chords.
        if deviation.to_data_excess > 3.0 * deviation.to_curve.max + 1e-3 * size {
            left_the_data = true;
            continue;
        }
        let better = best
            .as_ref()
            .is_none_or(|b| deviation.to_curve.max < b.deviation.to_curve.max);
        if better {
            // A curve whose velocity vanishes somewhere has no curvature there: no answer.
            let Ok(features) = planar_features(&curve, 1e-10) else {
                continue;
            };
            // Extrema strictly inside the domain (the ends are not extrema of a curve that
            // stops there); a closed curve's closing point is one if the curvature turns
            // there.
            let mut extrema = features
                .curvature_extrema
                .iter()
                .filter(|&&u| u > 1e-9 && u < 1.0 - 1e-9)
                .map(|&u| classify(&curve, u, orientation))
                .collect::<Result<Vec<_>>>()?;
            let mut inflections = features.inflections;
            if let Some(closed_curve) = &periodic {
                let (turns, crosses) = closing_point_features(closed_curve)?;
                if turns {
                    extrema.insert(0, classify(&curve, 0.0, orientation)?);
                }
                if crosses {
                    inflections.insert(0, 0.0);
                }
            }
            best = Some(SmoothedCurve {
                curve,
                periodic,
                first_point: rotation,
                deviation,
                extrema,
                inflections,
                start_extrema,
                orientation,
                knot_exponent: exponent,
                levels: found.levels,
                refinements: found.refinements,
                conditions: found.conditions,
                newton_steps: 0,
            });
        }
        if !options.thorough {
            break;
        }
    }
    match best {
        Some(mut result) => {
            result.newton_steps = newton_steps;
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

/// The deviations of closed data measured on the data rotated by `rotation` and closed by a
/// repeated first point, put back in the order of the `count` data points.
fn in_data_order(deviation: &mut TwoSidedDeviation<f64>, rotation: usize, count: usize) {
    let to_curve = &mut deviation.to_curve;
    to_curve.distances.truncate(count);
    to_curve.distances.rotate_right(rotation);
    deviation.params.truncate(count);
    deviation.params.rotate_right(rotation);
    to_curve.max_index = (to_curve.max_index % count + rotation) % count;
}

/// Whether the curvature of a closed curve has an extremum at its closing point (its
/// derivative changes sign across it) and whether the curve has an inflection there.
fn closing_point_features(curve: &PeriodicBSpline<f64, Vector2<f64>>) -> Result<(bool, bool)> {
    let h = 1e-6;
    let kappa = |u: f64| -> Result<f64> {
        let d = curve.derivatives(u, 2)?;
        let speed = d[1].norm();
        Ok((d[1].x * d[2].y - d[1].y * d[2].x) / (speed * speed * speed))
    };
    let (before, at, after) = (kappa(-h)?, kappa(0.0)?, kappa(h)?);
    let turns = (at - before) * (after - at) < 0.0;
    let crosses = before * after < 0.0;
    Ok((turns, crosses))
}

/// [`smooth`] with the fewest control points that bring every data point within
/// `tolerance` of the curve (the thesis: "typically less than 2 mm" for a chord of 1 m). The
/// number of control points in `options` is ignored: counts are doubled from the smallest the
/// extrema allow until one reaches the tolerance, then bisected (deviations do not always
/// fall as control points are added, so this is the fewest such a search finds).
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for a tolerance that is not positive and finite; the
/// errors of [`smooth`] for the other settings; [`ErrorKind::ToleranceExceeded`] when no
/// count up to one less than the number of data points reaches the tolerance (the message
/// gives the best deviation found).
pub fn smooth_to_tolerance(
    points: &[Vector2<f64>],
    tolerance: f64,
    options: &SmoothingOptions,
) -> Result<SmoothedCurve> {
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("the maximum deviation must be positive and finite, got {tolerance}"),
        ));
    }
    let p = options.degree;
    let smallest = p + 1 + options.extrema.len() * p.saturating_sub(2);
    let largest = distinct(points)?.len().saturating_sub(1);
    if largest < smallest {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "{} need at least {} distinct data points, got {}",
                extrema_words(options.extrema.len()),
                smallest + 1,
                largest + 1
            ),
        ));
    }
    let mut best_seen = f64::INFINITY;
    let mut run = |n: usize| -> Result<Option<SmoothedCurve>> {
        let mut o = options.clone();
        o.control_points = n;
        let result = match smooth(points, &o) {
            Ok(r) => r,
            Err(e) if e.kind() == ErrorKind::NoConvergence => {
                return Ok(None);
            }
            Err(e) => return Err(e),
        };
        best_seen = best_seen.min(result.deviation.to_curve.max);
        let ok = result.deviation.to_curve.max <= tolerance;
        Ok(ok.then_some(result))
    };
    // Doubling, then bisection between the last failure and the first success.
    let mut lo = smallest - 1; // fails by convention
    let mut n = smallest;
    let mut found = loop {
        if let Some(r) = run(n)? {
            break (n, r);
        }
        if n >= largest {
            return Err(Error::new(
                ErrorKind::ToleranceExceeded,
                format!(
                    "no curve with {} within {tolerance} of the data was found with up to {largest} control points (best deviation {best_seen:.3e})",
                    extrema_words(options.extrema.len())
                ),
            ));
        }
        lo = n;
        n = (2 * n).min(largest);
    };
    while found.0 - lo > 1 {
        let mid = lo + (found.0 - lo) / 2;
        match run(mid)? {
            Some(r) => found = (mid, r),
            None => lo = mid,
        }
    }
    Ok(found.1)
}

fn check_options(options: &SmoothingOptions) -> Result<()> {
    let p = options.degree;
    if p < 3 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "smoothing needs degree 3 or more (the curvature's derivative involves c‴), got {p}"
            ),
        ));
    }
    if options.extrema.is_empty() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "allow at least one curvature extremum",
        ));
    }
    if options.extrema.len() > MAX_CURVATURE_EXTREMA {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "at most {MAX_CURVATURE_EXTREMA} curvature extrema can be allowed, got {}",
                options.extrema.len()
            ),
        ));
    }
    if options.knot_exponents.is_empty()
        || options
            .knot_exponents
            .iter()
            .any(|e| !(*e >= 0.0 && e.is_finite()))
    {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "knot density exponents must be given, finite and not negative",
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
    if options.closed && options.extrema.len() % 2 != 0 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the curvature of a closed curve has as many maxima as minima: allow an even number of extrema, got {}",
                options.extrema.len()
            ),
        ));
    }
    let mut last = 0.0;
    for e in &options.extrema {
        if let Some(u) = e.at {
            if !(u > last && u < 1.0) {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!("extremum parameter {u} must lie in (0, 1), after the previous one"),
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
    if let Some(k) = points
        .iter()
        .position(|q| !(q.x.is_finite() && q.y.is_finite()))
    {
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
