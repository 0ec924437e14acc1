//! Curve fits as a front end asks for them: the whole request in one value, the data scaled
//! to coordinates near 1 by a power of two and the answer scaled back. The tool's
//! `interpolate` and `approximate` and the Python package's `fit_curve` call these, so they
//! run the same computation.
//!
//! Fitting is affinely invariant: dividing the data by a power of two $2^e$ (exact in
//! floating point) and multiplying the fitted control points by it gives the fit of the
//! original data, while distances and their squares, formed on coordinates near 1, neither
//! overflow nor underflow (coordinates from 1e-300 to 1e300 fit alike).

use crate::correction::{CorrectionOptions, CorrectionReport, correct_parameters};
use crate::interpolate::{InterpolationOptions, interpolate, interpolate_closed};
use crate::lsq::{LeastSquares, LsqMethod};
use crate::params::{Parametrization, nurbs_book_knots, parametrize, parametrize_in};
use crate::report::{CurveFit, Deviation};
use spline_core::{ControlPoint, KnotVector, Result, Scalar, cast, power_of_two_scale, to_f64};

/// An interpolation request: every data point on the curve.
#[derive(Clone, Debug, PartialEq)]
pub struct InterpolationRequest<T, P> {
    /// The degree `p ≥ 1`.
    pub degree: usize,
    /// A closed curve (periodic: the data's first point is not repeated at the end; no
    /// knots or end derivatives may be given) instead of an open one.
    pub closed: bool,
    /// Parameters, knots and end derivatives (in the data's own units).
    pub options: InterpolationOptions<T, P>,
}

/// Where the knots of a least-squares fit come from.
#[derive(Clone, Debug, PartialEq)]
pub enum LsqKnots<T> {
    /// This many control points, the knots placed by The NURBS Book (9.68)–(9.69) on the
    /// data's parameters ([`nurbs_book_knots`]).
    ControlPoints(usize),
    /// The knots given; named parametrisations are mapped onto their domain.
    Given(KnotVector<T>),
}

/// A least-squares request: the options of [`LeastSquares`] and of parameter correction.
#[derive(Clone, Debug, PartialEq)]
pub struct LeastSquaresRequest<'a, T> {
    /// The degree `p ≥ 0`.
    pub degree: usize,
    /// How the data get their parameters.
    pub parametrization: Parametrization<T>,
    /// The knots.
    pub knots: LsqKnots<T>,
    /// Weights of the data (one per point), [`LeastSquares::weights`].
    pub weights: Option<&'a [T]>,
    /// Both end control points on the end data points, [`LeastSquares::pin_ends`].
    pub pin_ends: bool,
    /// Fixed control-point coordinates `(index, coordinate, value)`, the value in the data's
    /// units, [`LeastSquares::fix_coordinate`].
    pub fixed: Vec<(usize, usize, T)>,
    /// The weight λ of $\lambda \int \lVert C'' \rVert^2$, [`LeastSquares::smoothing`] (in
    /// the data's units: it weighs squares against squares, so it does not scale).
    pub smoothing: T,
    /// How the system is solved.
    pub method: LsqMethod,
    /// Parameter correction after the first fit (`None`: none).
    pub correction: Option<CorrectionOptions<T>>,
}

impl<T: Scalar> LeastSquaresRequest<'_, T> {
    /// `degree` and `knots` with everything else at its default: chord-length parameters,
    /// no weights, nothing pinned or fixed, no smoothing, normal equations, no correction.
    #[must_use]
    pub fn new(degree: usize, knots: LsqKnots<T>) -> Self {
        Self {
            degree,
            parametrization: Parametrization::default(),
            knots,
            weights: None,
            pin_ends: false,
            fixed: Vec::new(),
            smoothing: T::zero(),
            method: LsqMethod::default(),
            correction: None,
        }
    }
}

/// The answer of [`fit_least_squares`].
#[derive(Clone, Debug, PartialEq)]
pub struct LeastSquaresFit<T, P> {
    /// The curve, the data's parameters and its deviation.
    pub fit: CurveFit<T, P>,
    /// The report of parameter correction, when it was asked for.
    pub correction: Option<CorrectionReport<T>>,
}

/// The power of two near the largest coordinate of `points` (1 for no points or a zero or
/// non-finite largest coordinate, left to the fits to refuse).
fn unit_scale<T: Scalar, P: ControlPoint<T>>(points: &[P]) -> T {
    let largest = points
        .iter()
        .fold(0.0f64, |m, p| m.max(to_f64(p.max_abs())));
    cast(power_of_two_scale(largest))
}

/// `fit` of data divided by `scale`, in the data's units again (`params` are unchanged).
fn scaled_back<T: Scalar, P: ControlPoint<T>>(fit: CurveFit<T, P>, scale: T) -> CurveFit<T, P> {
    let deviation = fit.deviation;
    CurveFit {
        curve: fit.curve.map_control_points(|p| *p * scale),
        params: fit.params,
        deviation: Deviation {
            max: deviation.max * scale,
            max_index: deviation.max_index,
            rms: deviation.rms * scale,
            sum_squares: deviation.sum_squares * scale * scale,
            distances: deviation.distances.iter().map(|&d| d * scale).collect(),
        },
    }
}

/// The interpolating curve of `points` as `request` asks: [`interpolate`], or
/// [`interpolate_closed`] when closed, on the data scaled to coordinates near 1.
///
/// # Errors
/// [`spline_core::ErrorKind::InvalidArgument`] for a closed request with given knots or end
/// derivatives; the errors of [`interpolate`] and [`interpolate_closed`].
///
/// # Examples
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::{InterpolationRequest, fit_interpolation};
/// // The same data at 1 and at 1e300: the same curve, scaled.
/// let data = [[0.0, 0.0], [1.0, 2.0], [3.0, 1.0], [4.0, 3.0]];
/// let at = |s: f64| data.map(|p| Vector2::new(p[0] * s, p[1] * s));
/// let request = InterpolationRequest { degree: 3, closed: false, options: Default::default() };
/// let unit = fit_interpolation(&at(1.0), &request)?;
/// let huge = fit_interpolation(&at(1e300), &request)?;
/// for (a, b) in unit.curve.control_points().iter().zip(huge.curve.control_points()) {
///     assert!((a * 1e300 - b).norm() <= 1e-14 * b.norm());
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
pub fn fit_interpolation<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    request: &InterpolationRequest<T, P>,
) -> Result<CurveFit<T, P>> {
    let scale = unit_scale(points);
    let unit: Vec<P> = points.iter().map(|p| *p * (T::one() / scale)).collect();
    let options = &request.options;
    let fit = if request.closed {
        if !matches!(options.knots, crate::params::KnotChoice::Averaging)
            || options.start_derivative.is_some()
            || options.end_derivative.is_some()
        {
            return Err(spline_core::Error::new(
                spline_core::ErrorKind::InvalidArgument,
                "a closed interpolation chooses its own knots and takes no end derivatives",
            ));
        }
        interpolate_closed(&unit, request.degree, &options.parametrization)?
    } else {
        let down = |d: &Option<P>| d.as_ref().map(|v| *v * (T::one() / scale));
        let unit_options = InterpolationOptions {
            parametrization: options.parametrization.clone(),
            knots: options.knots.clone(),
            start_derivative: down(&options.start_derivative),
            end_derivative: down(&options.end_derivative),
        };
        interpolate(&unit, request.degree, &unit_options)?
    };
    Ok(scaled_back(fit, scale))
}

/// The least-squares curve of `points` as `request` asks ([`LeastSquares`], then
/// [`correct_parameters`] when asked), on the data scaled to coordinates near 1; with the
/// correction's report (its squared errors in the data's units).
///
/// # Errors
/// The errors of [`parametrize`], [`nurbs_book_knots`], [`LeastSquares::solve`] and
/// [`correct_parameters`].
pub fn fit_least_squares<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    request: &LeastSquaresRequest<'_, T>,
) -> Result<LeastSquaresFit<T, P>> {
    let scale = unit_scale(points);
    let unit: Vec<P> = points.iter().map(|p| *p * (T::one() / scale)).collect();
    let knots = match &request.knots {
        LsqKnots::Given(knots) => knots.clone(),
        LsqKnots::ControlPoints(n) => nurbs_book_knots(
            request.degree,
            *n,
            &parametrize(&unit, &request.parametrization)?,
        )?,
    };
    // Named parametrisations on [0, 1] are mapped onto the domain of the knots.
    let params = parametrize_in(&unit, &request.parametrization, knots.domain())?;
    let mut problem = LeastSquares::new(&unit, &params, knots)
        .smoothing(request.smoothing)
        .method(request.method);
    if let Some(w) = request.weights {
        problem = problem.weights(w);
    }
    if request.pin_ends {
        problem = problem.pin_ends();
    }
    for &(index, coord, value) in &request.fixed {
        problem = problem.fix_coordinate(index, coord, value / scale);
    }
    match &request.correction {
        None => Ok(LeastSquaresFit {
            fit: scaled_back(problem.solve()?, scale),
            correction: None,
        }),
        Some(options) => {
            let (fit, mut report) = correct_parameters(&problem, options)?;
            for e in &mut report.errors {
                *e = *e * scale * scale;
            }
            Ok(LeastSquaresFit {
                fit: scaled_back(fit, scale),
                correction: Some(report),
            })
        }
    }
}
