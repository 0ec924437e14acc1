//! Shape control of a surface of revolution through its meridian (thesis ch. 7): the
//! surface $(f(z) \cos\theta, f(z) \sin\theta, z)$ has Gaussian curvature
//! $K = -f''(z) / \big(f(z)\\,(1 + f'(z)^2)^2\big)$, so for a positive radius `f` its
//! parabolic circles are exactly the sign changes of `f″`. Keeping only the allowed ones is a
//! constrained approximation of the meridian function ([`FunctionApproximation`]: `f > 0`,
//! `f″` of one sign between the allowed circles, one sign change inside each allowed
//! interval).

use crate::constrained::{FunctionApproximation, FunctionFit};
use crate::problem::Sign;
use nalgebra::Vector3;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::{Axis, BSpline, NurbsCurve, NurbsSurface};

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
    if meridian.degree() < 3 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the meridian needs degree 3 or more (a continuous f''), got {}",
                meridian.degree()
            ),
        ));
    }
    if refine > 8 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("at most 8 refinements, got {refine}"),
        ));
    }
    let (a, b) = meridian.domain();
    let mut previous = a;
    for &(s, t) in &circles.allowed {
        if !(s > previous && t > s && t < b) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "the allowed intervals must be increasing, disjoint and inside ({a}, {b}); got ({s}, {t})"
                ),
            ));
        }
        previous = t;
    }
    let mut knots: KnotVector<f64> = meridian.knots().clone();
    for _ in 0..refine {
        let breaks = knots.domain_breaks();
        let mids: Vec<f64> = breaks.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
        knots = knots.refined(&mids)?;
    }
    let mut approximation = FunctionApproximation::new(knots).sign(0, Sign::NonNegative);
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
    let n = 20 * samples.max(2);
    let mut max_deviation = 0.0f64;
    for k in 0..=n {
        let z = a + (b - a) * k as f64 / n as f64;
        max_deviation = max_deviation.max((fit.spline.eval(z)? - meridian.eval(z)?).abs());
    }
    Ok(MeridianControl {
        meridian: fit.spline.clone(),
        max_deviation,
        fit,
    })
}
