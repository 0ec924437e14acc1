//! A Bézier least-squares fit as a front end asks for it: the fit and, optionally, parameter
//! correction in one call ([`fit_bezier_least_squares`]), as `requests.rs` does for
//! B-splines.

use crate::bezier::{BezierFit, bezier_least_squares, least_squares_params};
use crate::correction::{CorrectionOptions, CorrectionReport, correct_parameters_bezier};
use crate::params::Parametrization;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar};

/// A Bézier least-squares request: the options of [`bezier_least_squares`] and of parameter
/// correction ([`correct_parameters_bezier`]), as [`crate::LeastSquaresRequest`] gathers
/// those of a B-spline fit.
#[derive(Clone, Debug, PartialEq)]
pub struct BezierLeastSquaresRequest<'a, T> {
    /// The degree `n`.
    pub degree: usize,
    /// How the data get their parameters (named ones are mapped onto `interval`).
    pub parametrization: Parametrization<T>,
    /// The parameter interval `[a, b]` of the curve.
    pub interval: (T, T),
    /// Weights of the data (one per point); only without correction, whose refits are
    /// unweighted.
    pub weights: Option<&'a [T]>,
    /// Parameter correction after the first fit (`None`: none).
    pub correction: Option<CorrectionOptions<T>>,
}

impl<T: Scalar> BezierLeastSquaresRequest<'_, T> {
    /// `degree` with everything else at its default: chord-length parameters on `[0, 1]`,
    /// no weights, no correction.
    #[must_use]
    pub fn new(degree: usize) -> Self {
        Self {
            degree,
            parametrization: Parametrization::default(),
            interval: (T::zero(), T::one()),
            weights: None,
            correction: None,
        }
    }
}

/// The answer of [`fit_bezier_least_squares`].
#[derive(Clone, Debug, PartialEq)]
pub struct BezierLeastSquaresFit<T, P> {
    /// The curve, the data's parameters (corrected, when correction was asked for) and its
    /// deviation from the data at them.
    pub fit: BezierFit<T, P>,
    /// The report of parameter correction, when it was asked for.
    pub correction: Option<CorrectionReport<T>>,
}

/// The least-squares Bézier curve of `points` as `request` asks: [`bezier_least_squares`],
/// or with `request.correction` [`correct_parameters_bezier`] from the request's parameters
/// (the same curve, parameters and deviation as [`bezier_least_squares`] followed by
/// [`correct_parameters_bezier`] from its parameters, without the first fit's extra solve).
/// Unlike [`crate::fit_least_squares`], the data are fitted in their own units (not scaled
/// to coordinates near 1).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::{BezierLeastSquaresRequest, CorrectionOptions, fit_bezier_least_squares};
/// let points: Vec<Vector2<f64>> = (0..=20)
///     .map(|k| { let t = f64::from(k) / 20.0 * 3.0; Vector2::new(t, t.sin()) })
///     .collect();
/// let plain = fit_bezier_least_squares(&points, &BezierLeastSquaresRequest::new(4))?;
/// let corrected = fit_bezier_least_squares(&points, &BezierLeastSquaresRequest {
///     correction: Some(CorrectionOptions::default()),
///     ..BezierLeastSquaresRequest::new(4)
/// })?;
/// let report = corrected.correction.expect("asked for");
/// assert!(report.errors.windows(2).all(|e| e[1] <= e[0]));
/// assert!(corrected.fit.deviation.rms <= plain.fit.deviation.rms);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for weights with correction; the errors of
/// [`bezier_least_squares`] and of [`correct_parameters_bezier`].
pub fn fit_bezier_least_squares<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    request: &BezierLeastSquaresRequest<'_, T>,
) -> Result<BezierLeastSquaresFit<T, P>> {
    let (degree, interval) = (request.degree, request.interval);
    let Some(options) = &request.correction else {
        return Ok(BezierLeastSquaresFit {
            fit: bezier_least_squares(
                points,
                degree,
                &request.parametrization,
                interval,
                request.weights,
            )?,
            correction: None,
        });
    };
    if request.weights.is_some() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "parameter correction of a Bézier fit refits without weights: give weights or correction, not both",
        ));
    }
    let params = least_squares_params(points, degree, &request.parametrization, interval)?;
    let (fit, report) = correct_parameters_bezier(points, &params, degree, interval, options)?;
    Ok(BezierLeastSquaresFit {
        fit,
        correction: Some(report),
    })
}

#[cfg(test)]
mod tests {
    use super::{BezierLeastSquaresRequest, fit_bezier_least_squares};
    use crate::bezier::bezier_least_squares;
    use crate::correction::{CorrectionOptions, correct_parameters_bezier};
    use crate::params::Parametrization;
    use nalgebra::Vector2;
    use spline_core::ErrorKind;

    fn data() -> Vec<Vector2<f64>> {
        (0..=24)
            .map(|k| {
                let t = f64::from(k) / 24.0 * 4.0;
                Vector2::new(t + 0.1 * (3.0 * t).sin(), (1.3 * t).sin() + 0.05 * t * t)
            })
            .collect()
    }

    /// One call gives bit for bit what the two calls gave (least squares, then correction
    /// from its parameters): curve, parameters, deviation and report; without correction,
    /// what `bezier_least_squares` gives.
    #[test]
    fn one_call_is_the_two_calls() {
        let points = data();
        for parametrization in [
            Parametrization::Uniform,
            Parametrization::Chordal,
            Parametrization::Centripetal,
        ] {
            for (degree, interval) in [(3, (0.0, 1.0)), (5, (-1.0, 2.0))] {
                let options = CorrectionOptions {
                    max_iterations: 7,
                    ..CorrectionOptions::default()
                };
                let start = bezier_least_squares(&points, degree, &parametrization, interval, None)
                    .unwrap();
                let (two, report) =
                    correct_parameters_bezier(&points, &start.params, degree, interval, &options)
                        .unwrap();
                let request = BezierLeastSquaresRequest {
                    parametrization: parametrization.clone(),
                    interval,
                    ..BezierLeastSquaresRequest::new(degree)
                };
                let plain = fit_bezier_least_squares(&points, &request).unwrap();
                assert_eq!(plain.fit, start);
                assert_eq!(plain.correction, None);
                let one = fit_bezier_least_squares(
                    &points,
                    &BezierLeastSquaresRequest {
                        correction: Some(options),
                        ..request
                    },
                )
                .unwrap();
                assert_eq!(one.fit.curve, two.curve);
                assert_eq!(one.fit.params, two.params);
                assert_eq!(one.fit.deviation, two.deviation);
                assert_eq!(one.correction, Some(report));
            }
        }
    }

    /// Weights go to the plain fit; with correction (unweighted refits) they are refused.
    #[test]
    fn weights_and_correction_do_not_mix() {
        let points = data();
        let weights = vec![2.0; points.len()];
        let request = BezierLeastSquaresRequest {
            weights: Some(&weights),
            ..BezierLeastSquaresRequest::new(3)
        };
        let weighted = fit_bezier_least_squares(&points, &request).unwrap();
        let direct = bezier_least_squares(
            &points,
            3,
            &Parametrization::Chordal,
            (0.0, 1.0),
            Some(&weights),
        )
        .unwrap();
        assert_eq!(weighted.fit, direct);
        let refused = fit_bezier_least_squares(
            &points,
            &BezierLeastSquaresRequest {
                correction: Some(CorrectionOptions::default()),
                ..request
            },
        )
        .unwrap_err();
        assert_eq!(refused.kind(), ErrorKind::InvalidArgument);
    }
}
