//! Shape control of a surface of revolution through its meridian (thesis ch. 7): the
//! surface $(f(z) \cos\theta, f(z) \sin\theta, z)$ has Gaussian curvature
//! $K = -f''(z) / \big(f(z)\\,(1 + f'(z)^2)^2\big)$, so for a positive radius `f` its
//! parabolic circles are exactly the sign changes of `f″`. Keeping only the allowed ones is a
//! constrained approximation of the meridian function ([`FunctionApproximation`]: `f > 0`,
//! `f″` of one sign between the allowed circles, one sign change inside each allowed
//! interval). Its ridge circles are the curvature extrema of the meridian: the selective
//! eraser on the meridian profile controls them ([`control_ridge_circles`]).

use crate::constrained::{FunctionApproximation, FunctionFit};
use crate::eraser::{SmoothedCurve, SmoothingOptions, smooth};
use crate::problem::Sign;
use nalgebra::{Vector2, Vector3};
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::{Axis, BSpline, NurbsCurve, NurbsSurface, Surface};

/// The parabolic circles a meridian may have: the sign of `f″` at the bottom of the
/// meridian (`Sign::NonNegative`: concave towards the axis, `K ≤ 0`) and the intervals of
/// `z`, in increasing order and disjoint, each holding exactly one allowed parabolic
/// circle (where `f″` changes sign).
#[derive(Clone, Debug, PartialEq)]
pub struct ParabolicCircles {
    /// The sign of `f″` below the first allowed circle.
    pub first: Sign,
    /// The intervals `(a, b)` of the allowed circles.
    pub allowed: Vec<(f64, f64)>,
}

/// The result of [`control_parabolic_circles`].
#[derive(Clone, Debug)]
pub struct MeridianControl {
    /// The new meridian radius `f(z)`.
    pub meridian: BSpline<f64, f64>,
    /// The largest `|f_new(z) − f_old(z)|` on a dense sampling (20 points per sample
    /// interval).
    pub max_deviation: f64,
    /// The constrained fit (objective, solver report).
    pub fit: FunctionFit,
}

/// The meridian's knots refined `refine` times by midpoints, for a meridian of degree 3 or
/// more (`f″` continuous, `f‴` defined).
pub(crate) fn refined_knots(
    meridian: &BSpline<f64, f64>,
    refine: usize,
) -> Result<KnotVector<f64>> {
    if meridian.degree() < 3 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the meridian needs degree 3 or more (a continuous f''), got {}",
                meridian.degree()
            ),
        )
        .with_value(meridian.degree() as f64)
        .with_interval(3.0, f64::INFINITY));
    }
    if refine > 8 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("at most 8 refinements, got {refine}"),
        )
        .with_value(refine as f64)
        .with_interval(0.0, 8.0));
    }
    let mut knots: KnotVector<f64> = meridian.knots().clone();
    for _ in 0..refine {
        let breaks = knots.domain_breaks();
        let mids: Vec<f64> = breaks.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
        knots = knots.refined(&mids)?;
    }
    Ok(knots)
}

/// Checks intervals of allowed feature circles: increasing, disjoint and strictly inside
/// `(a, b)`.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] naming the first interval that is not (its position as
/// [`Error::index`], `(a, b)` as [`Error::interval`]).
pub(crate) fn check_allowed(allowed: &[(f64, f64)], (a, b): (f64, f64)) -> Result<()> {
    let mut previous = a;
    for (i, &(s, t)) in allowed.iter().enumerate() {
        if !(s > previous && t > s && t < b) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "the allowed intervals must be increasing, disjoint and inside ({a}, {b}); got ({s}, {t})"
                ),
            )
            .with_index(i)
            .with_interval(a, b));
        }
        previous = t;
    }
    Ok(())
}

/// The largest `|new(z) − old(z)|` at `20 · samples` equally spaced heights (ends included).
pub(crate) fn max_deviation(
    new: &BSpline<f64, f64>,
    old: &BSpline<f64, f64>,
    samples: usize,
) -> Result<f64> {
    let (a, b) = old.domain();
    let n = 20 * samples.max(2);
    let mut largest = 0.0f64;
    for k in 0..=n {
        let z = a + (b - a) * k as f64 / n as f64;
        largest = largest.max((new.eval(z)? - old.eval(z)?).abs());
    }
    Ok(largest)
}

/// The surface of revolution of the meridian radius `f(z)` about the `z` axis: the profile
/// curve `(f(z), 0, z)` (exact: `z` is the B-spline with the Greville abscissae as
/// coefficients) revolved by a full turn ([`NurbsSurface::revolution`]); `u` runs along the
/// meridian.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] unless the knot vector is clamped (then `z` is exact);
/// the errors of [`NurbsSurface::revolution`].
pub fn revolution_surface(meridian: &BSpline<f64, f64>) -> Result<NurbsSurface<f64, 3>> {
    let knots = meridian.knots();
    if !knots.is_clamped() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "a meridian function needs a clamped knot vector",
        ));
    }
    let z = knots.greville();
    let points = meridian
        .control_points()
        .iter()
        .zip(&z)
        .map(|(&r, &z)| Vector3::new(r, 0.0, z))
        .collect();
    let profile = NurbsCurve::from_bspline(&BSpline::new(knots.clone(), points)?);
    let axis = Axis::new(Vector3::zeros(), Vector3::z())?;
    NurbsSurface::revolution(&profile, &axis, 2.0 * std::f64::consts::PI)
}

/// Approximates the meridian radius `f(z)` of a surface of revolution by the closest spline
/// (least squares on `samples` equally spaced values of `f`, on `f`'s knots refined
/// `refine` times by midpoints) whose surface has only the allowed parabolic circles: `f > 0`
/// and `f″` with the signs of `circles` ([`FunctionApproximation`], sufficient conditions on
/// the control points of `f″`).
///
/// ```
/// use spline_shape::{ParabolicCircles, Sign, control_parabolic_circles};
/// // f(z) = 1 + 0.3 z² + 0.02 sin 6z on [0, 1]: f″ = 0.6 − 0.72 sin 6z changes sign twice.
/// let z: Vec<f64> = (0..=12).map(|k| f64::from(k) / 12.0).collect();
/// let r: Vec<f64> = z.iter().map(|&z| 1.0 + 0.3 * z * z + 0.02 * (6.0 * z).sin()).collect();
/// let meridian = spline_fit::interpolate_function(&z, &r, 3)?;
/// let none = ParabolicCircles { first: Sign::NonNegative, allowed: vec![] };
/// let controlled = control_parabolic_circles(&meridian, &none, 200, 0)?;
/// assert!(controlled.max_deviation < 0.01);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for a meridian of degree below 3 (`f″` must be continuous
/// for its sign changes to be circles), unordered or overlapping intervals, or intervals
/// outside the domain; the errors of [`FunctionApproximation::fit`] (no feasible meridian).
pub fn control_parabolic_circles(
    meridian: &BSpline<f64, f64>,
    circles: &ParabolicCircles,
    samples: usize,
    refine: usize,
) -> Result<MeridianControl> {
    constrain_second_derivative(meridian, circles, samples, refine, true)
}

/// The closest spline to `function` (least squares on `samples` values, knots refined
/// `refine` times) whose second derivative has the sign pattern of `pattern`, and which stays
/// non-negative when `positive`.
fn constrain_second_derivative(
    meridian: &BSpline<f64, f64>,
    circles: &ParabolicCircles,
    samples: usize,
    refine: usize,
    positive: bool,
) -> Result<MeridianControl> {
    let knots = refined_knots(meridian, refine)?;
    let (a, b) = meridian.domain();
    check_allowed(&circles.allowed, (a, b))?;
    let mut approximation = FunctionApproximation::new(knots);
    if positive {
        approximation = approximation.sign(0, Sign::NonNegative);
    }
    let flip = |s: Sign| match s {
        Sign::NonNegative => Sign::NonPositive,
        Sign::NonPositive => Sign::NonNegative,
    };
    let mut sign = circles.first;
    let mut start = a;
    for &(s, t) in &circles.allowed {
        approximation = approximation
            .sign_on(2, sign, start, s)
            .sign_change(2, sign, s, t);
        sign = flip(sign);
        start = t;
    }
    approximation = approximation.sign_on(2, sign, start, b);
    let fit = approximation.fit_function(samples, |z| meridian.eval(z).unwrap_or(f64::NAN))?;
    let max_deviation = max_deviation(&fit.spline, meridian, samples)?;
    Ok(MeridianControl {
        meridian: fit.spline.clone(),
        max_deviation,
        fit,
    })
}

/// The result of [`control_ridge_circles`].
#[derive(Clone, Debug)]
pub struct RidgeControl {
    /// The new meridian as a planar profile `(r(t), z(t))` (a parametric curve: the eraser's
    /// result), with its deviations and curvature extrema.
    pub profile: SmoothedCurve,
    /// The surface of revolution of the profile about the `z` axis (`u` along the profile).
    pub surface: NurbsSurface<f64, 3>,
    /// The heights `z` of the ridge circles of the result (the curvature extrema of the
    /// profile).
    pub ridge_circles: Vec<f64>,
}

/// Controls the ridge circles of the surface of revolution of the meridian radius `f(z)`
/// (thesis ch. 7): its ridge circles are the extrema of the meridian's curvature along the
/// meridians ([`spline_algebra::revolution_features`]), so the selective eraser on the
/// meridian profile `(f(z), z)` ([`smooth`], sampled at `samples` heights) keeps exactly the
/// allowed ones. `options` says how many control points and which extrema (their kinds
/// refer to the curvature of the profile traversed upwards, oriented as the eraser orients
/// it); the result is a parametric profile, revolved by a full turn.
///
/// ```
/// use spline_shape::{SmoothingOptions, control_ridge_circles};
/// // f(z) = 1 + 0.3 z² + 0.01 sin 12z: the wiggle adds ridge circles.
/// let z: Vec<f64> = (0..=24).map(|k| f64::from(k) / 24.0).collect();
/// let r: Vec<f64> = z.iter().map(|&z| 1.0 + 0.3 * z * z + 0.01 * (12.0 * z).sin()).collect();
/// let meridian = spline_fit::interpolate_function(&z, &r, 3)?;
/// let mut options = SmoothingOptions::new(10);
/// options.extrema = vec!["min@0.5".parse()?]; // one ridge circle, halfway up
/// let controlled = control_ridge_circles(&meridian, 200, &options)?;
/// assert_eq!(controlled.ridge_circles.len(), 1);
/// assert!(controlled.profile.deviation.to_curve.max < 0.02);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for fewer than 2 or more than 100,000 samples, or a radius
/// that is not positive at a sample; the errors of [`smooth`] and of the revolution.
pub fn control_ridge_circles(
    meridian: &BSpline<f64, f64>,
    samples: usize,
    options: &SmoothingOptions,
) -> Result<RidgeControl> {
    if !(2..=100_000).contains(&samples) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("between 2 and 100000 samples of the meridian, got {samples}"),
        )
        .with_value(samples as f64)
        .with_interval(2.0, 100_000.0));
    }
    let (a, b) = meridian.domain();
    let points: Vec<Vector2<f64>> = (0..samples)
        .map(|k| {
            let z = a + (b - a) * k as f64 / (samples - 1) as f64;
            let r = meridian.eval(z)?;
            if !(r > 0.0) {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!("the meridian radius must be positive, got {r} at z = {z}"),
                )
                .with_value(r)
                .with_interval(0.0, f64::INFINITY));
            }
            Ok(Vector2::new(r, z))
        })
        .collect::<Result<_>>()?;
    let profile = smooth(&points, options)?;
    let spatial = profile
        .curve
        .map_control_points(|p| Vector3::new(p.x, 0.0, p.y));
    let axis = Axis::new(Vector3::zeros(), Vector3::z())?;
    let surface = NurbsSurface::revolution(
        &NurbsCurve::from_bspline(&spatial),
        &axis,
        2.0 * std::f64::consts::PI,
    )?;
    let ridge_circles = profile.extrema.iter().map(|e| e.point.y).collect();
    Ok(RidgeControl {
        profile,
        surface,
        ridge_circles,
    })
}

/// The result of [`control_translation_parabolic_lines`].
#[derive(Clone, Debug)]
pub struct TranslationControl {
    /// The new profile `g(x)` (with its deviation and fit).
    pub first: MeridianControl,
    /// The new profile `h(y)`.
    pub second: MeridianControl,
    /// The translation surface `(x, y, g(x) + h(y))` of the two profiles
    /// ([`Surface::translation`]).
    pub surface: Surface<f64, Vector3<f64>>,
}

/// The translation surface $(x, y, g(x) + h(y))$ of two profile curves in perpendicular
/// planes, `(x, 0, g(x))` and `(0, y, h(y))` ([`Surface::translation`]): its Gaussian
/// curvature is $g''\, h'' / (1 + g'^2 + h'^2)^2$, so its parabolic lines are the lines
/// `x = const` through the inflections of `g` and `y = const` through those of `h`.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] unless both knot vectors are clamped; the errors of
/// [`Surface::translation`].
pub fn translation_surface(
    first: &BSpline<f64, f64>,
    second: &BSpline<f64, f64>,
) -> Result<Surface<f64, Vector3<f64>>> {
    let profile = |f: &BSpline<f64, f64>, along: usize| -> Result<BSpline<f64, Vector3<f64>>> {
        let knots = f.knots();
        if !knots.is_clamped() {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "a profile function needs a clamped knot vector",
            ));
        }
        // The abscissa is exact with the Greville abscissae as coefficients.
        let points = f
            .control_points()
            .iter()
            .zip(knots.greville())
            .map(|(&value, t)| {
                let mut p = Vector3::new(0.0, 0.0, value);
                p[along] = t;
                p
            })
            .collect();
        BSpline::new(knots.clone(), points)
    };
    let a = profile(first, 0)?;
    let b = profile(second, 1)?;
    // S = a(x) + b(y) − b(y₀) + b(y₀): put back the start of the second profile.
    let start = b.eval(b.domain().0)?;
    Ok(Surface::translation(&a, &b)?.map_control_points(|p| p + start))
}

/// Controls the parabolic lines of the translation surface $(x, y, g(x) + h(y))$
/// ([`translation_surface`]) through its two profiles: each is approximated by the closest
/// function whose second derivative has the sign pattern asked (`lines_x` for `g`,
/// `lines_y` for `h`; a [`ParabolicCircles`] pattern: the sign at the start and the
/// intervals each holding one allowed inflection), so that only the allowed parabolic lines
/// remain.
///
/// # Errors
/// As [`control_parabolic_circles`] for each profile (without the positivity of a radius);
/// the errors of [`translation_surface`].
pub fn control_translation_parabolic_lines(
    first: &BSpline<f64, f64>,
    second: &BSpline<f64, f64>,
    lines_x: &ParabolicCircles,
    lines_y: &ParabolicCircles,
    samples: usize,
) -> Result<TranslationControl> {
    let first = constrain_second_derivative(first, lines_x, samples, 0, false)
        .map_err(|e| e.context("the first profile"))?;
    let second = constrain_second_derivative(second, lines_y, samples, 0, false)
        .map_err(|e| e.context("the second profile"))?;
    let surface = translation_surface(&first.meridian, &second.meridian)?;
    Ok(TranslationControl {
        first,
        second,
        surface,
    })
}
