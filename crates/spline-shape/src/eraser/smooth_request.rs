//! A whole smoothing request in one value, and the one call that runs it: [`smooth`],
//! [`smooth_to_tolerance`] or [`smooth_fewest_extrema`], as the request asks (what the tool's
//! `smooth` and the Python package's `smooth` call, so they run the same computation).

use super::fewest_extrema::smooth_fewest_extrema;
use super::smooth::smooth;
use super::tolerance::smooth_to_tolerance;
use super::types::{Extremum, MAX_CURVATURE_EXTREMA, Objective, SmoothedCurve, SmoothingOptions};
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result};

/// How many control points a [`SmoothRequest`] asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ControlPoints {
    /// This many ([`smooth`]).
    Count(usize),
    /// The fewest that bring every data point within `max_deviation` of the curve
    /// ([`smooth_to_tolerance`]).
    Fewest {
        /// The largest distance allowed from a data point to the curve.
        max_deviation: f64,
    },
}

/// The curvature extrema a [`SmoothRequest`] allows.
#[derive(Clone, Debug, PartialEq)]
pub enum AllowedExtrema {
    /// `k` extrema alternating from a maximum (`max, min, max, …`), each placed
    /// automatically; `Count(1)` is the default of [`SmoothingOptions::new`] (one maximum,
    /// the nose of an airfoil).
    Count(usize),
    /// These extrema, in the order of the data ([`SmoothingOptions::extrema`]).
    Given(Vec<Extremum>),
    /// The fewest (`1, 2, …`; closed `2, 4, …`) that bring every data point within
    /// `max_deviation` of the curve ([`smooth_fewest_extrema`]; `None`:
    /// [`AUTO_EXTREMA_TOLERANCE`](super::AUTO_EXTREMA_TOLERANCE) times the diagonal of the
    /// data's bounding box). Needs [`ControlPoints::Count`].
    Auto {
        /// The largest distance allowed from a data point to the curve.
        max_deviation: Option<f64>,
    },
}

/// `count` extrema alternating from a maximum, or the error of a count above
/// [`MAX_CURVATURE_EXTREMA`] (before anything is allocated).
pub(crate) fn alternating(count: usize) -> Result<Vec<Extremum>> {
    check_count(count)?;
    Ok(Extremum::alternating(count))
}

/// [`ErrorKind::InvalidArgument`] for a count of extrema above [`MAX_CURVATURE_EXTREMA`],
/// with `(MAX_CURVATURE_EXTREMA, count)` as [`Error::counts`].
pub(crate) fn check_count(count: usize) -> Result<()> {
    if count > MAX_CURVATURE_EXTREMA {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("at most {MAX_CURVATURE_EXTREMA} extrema can be allowed, got {count}"),
        )
        .with_counts(MAX_CURVATURE_EXTREMA, count));
    }
    Ok(())
}

/// A smoothing as a front end asks for it: how many control points, which curvature extrema,
/// and the settings of [`SmoothingOptions`] a front end sets (the others keep the values of
/// [`SmoothingOptions::new`]). [`SmoothRequest::run`] runs it;
/// [`SmoothRequest::from_words`] makes one from options in words (the tool's flags, the Python
/// package's keywords).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_shape::{AllowedExtrema, ControlPoints, SmoothRequest};
/// let points: Vec<Vector2<f64>> = (0..60)
///     .map(|k| {
///         let t = f64::from(k) / 59.0 * std::f64::consts::FRAC_PI_2;
///         Vector2::new(2.0 * t.sin(), t.cos() + 1e-3 * f64::from((k * 37) % 7) / 7.0)
///     })
///     .collect();
/// let mut request = SmoothRequest::new(ControlPoints::Count(8));
/// request.extrema = AllowedExtrema::Given(vec!["max@0.999".parse()?]);
/// let result = request.run(&points)?;
/// assert_eq!(result.extrema.len(), 1);
/// assert_eq!(result.control_point_count(), 8);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SmoothRequest {
    /// How many control points.
    pub control_points: ControlPoints,
    /// Which curvature extrema.
    pub extrema: AllowedExtrema,
    /// [`SmoothingOptions::degree`].
    pub degree: usize,
    /// [`SmoothingOptions::objective`].
    pub objective: Objective,
    /// [`SmoothingOptions::thorough`].
    pub thorough: bool,
    /// [`SmoothingOptions::knot_search`].
    pub knot_search: bool,
    /// [`SmoothingOptions::closed`].
    pub closed: bool,
    /// [`SmoothingOptions::knot_exponents`].
    pub knot_exponents: Vec<f64>,
}

impl SmoothRequest {
    /// `control_points` with everything else as [`SmoothingOptions::new`] has it: cubic, one
    /// curvature maximum placed automatically, the max deviation objective, open data.
    #[must_use]
    pub fn new(control_points: ControlPoints) -> Self {
        let defaults = SmoothingOptions::new(0);
        Self {
            control_points,
            extrema: AllowedExtrema::Count(1),
            degree: defaults.degree,
            objective: defaults.objective,
            thorough: defaults.thorough,
            knot_search: defaults.knot_search,
            closed: defaults.closed,
            knot_exponents: defaults.knot_exponents,
        }
    }

    /// [`SmoothingOptions`] with this request's settings, `control_points` and `extrema`.
    fn options(&self, control_points: usize, extrema: Vec<Extremum>) -> SmoothingOptions {
        let mut options = SmoothingOptions::new(control_points);
        options.degree = self.degree;
        options.objective = self.objective;
        options.thorough = self.thorough;
        options.knot_search = self.knot_search;
        options.closed = self.closed;
        options.knot_exponents.clone_from(&self.knot_exponents);
        options.extrema = extrema;
        options
    }

    /// Smooths `points` as the request asks: [`smooth`] with a count of control points and
    /// extrema counted or given, [`smooth_to_tolerance`] with [`ControlPoints::Fewest`],
    /// [`smooth_fewest_extrema`] with [`AllowedExtrema::Auto`].
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] for [`ControlPoints::Fewest`] with
    /// [`AllowedExtrema::Auto`] (one search at a time) and for a count of extrema above
    /// [`MAX_CURVATURE_EXTREMA`]; otherwise the errors of the function called.
    pub fn run(&self, points: &[Vector2<f64>]) -> Result<SmoothedCurve> {
        let extrema = match &self.extrema {
            AllowedExtrema::Count(k) => alternating(*k)?,
            AllowedExtrema::Given(given) => given.clone(),
            &AllowedExtrema::Auto { max_deviation } => {
                let ControlPoints::Count(n) = self.control_points else {
                    return Err(Error::new(
                        ErrorKind::InvalidArgument,
                        "the fewest curvature extrema are searched with a given number of control points, not with the fewest control points",
                    ));
                };
                // The search sets the extrema; those of the options are not read.
                let options = self.options(n, vec![Extremum::maximum()]);
                return smooth_fewest_extrema(points, max_deviation, &options);
            }
        };
        match self.control_points {
            ControlPoints::Count(n) => smooth(points, &self.options(n, extrema)),
            // The search sets the number of control points; that of the options is not read.
            ControlPoints::Fewest { max_deviation } => {
                smooth_to_tolerance(points, max_deviation, &self.options(0, extrema))
            }
        }
    }
}
