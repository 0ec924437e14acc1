//! The eraser's vocabulary: the allowed extrema, the objective, the options and the result.

use crate::barrier::BarrierOptions;
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result};
use spline_fit::TwoSidedDeviation;
use spline_geom::{Curve2, PeriodicBSpline};
use std::fmt;
use std::str::FromStr;

/// The most curvature extrema a smoothing may allow (each one is a knot of the curve and a
/// slot of the placement; far more than any shape needs).
pub const MAX_CURVATURE_EXTREMA: usize = 1000;

/// A smoothed curve whose largest deviation exceeds this factor times that of the
/// least-squares fit with the same control points, and [`DEVIATION_WARNING_FLOOR`] of the
/// data's size, carries a warning ([`SmoothedCurve::warnings`]). With 20 control points and
/// one maximum: 8.1 and 17.6 times on the sharp-nosed plates UIUC goe417a and goe531 (9.6
/// and 11.2 mm from a chord of 1 m), 12 to 39 times on glennmartin3, m23 and e377 of
/// `data/airfoils` (5.5 to 15 mm; m23 and e377 come within 0.3 mm with two extrema);
/// ratios up to 10 occur on smooth airfoils whose least-squares fit is very close (0.3 mm),
/// hence the floor.
pub const DEVIATION_WARNING_FACTOR: f64 = 4.0;

/// Deviations below this fraction of the diagonal of the data's bounding box never warn
/// (`0.005`: 5 mm on an airfoil of chord 1 m; [`DEVIATION_WARNING_FACTOR`]).
pub const DEVIATION_WARNING_FLOOR: f64 = 5e-3;

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

    /// `count` extrema alternating from a maximum (`max, min, max, …`), each placed
    /// automatically.
    pub(crate) fn alternating(count: usize) -> Vec<Self> {
        (0..count)
            .map(|i| {
                if i % 2 == 0 {
                    Self::maximum()
                } else {
                    Self::minimum()
                }
            })
            .collect()
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

/// Settings of [`smooth`](super::smooth).
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
    /// After the knot densities, move the free interior knots one at a time while that
    /// brings the curve closer to the data (a pattern search: each knot by a quarter of the
    /// gap to a neighbour, then an eighth, down to 1/32; at most 400 problems solved).
    /// Open data and fresh starts only; tens to hundreds of times the time of one attempt,
    /// for the last tenths of a millimetre of Table 6.1 (ah81k144wfKlappe with 15 control
    /// points: 1.54 mm → 1.24 mm).
    pub knot_search: bool,
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
            knot_search: false,
            max_rounds: 40,
            max_refinements: 6,
            barrier: BarrierOptions {
                // The bound m/t on the objective's distance to the optimum, in units of the
                // start's largest squared distance. Measured on the UIUC airfoils: 1e-5 gives
                // the deviations of 1e-7 (median and p90 to 3 digits, geometric mean of the
                // ratios 0.99994, no refusal more or less), 4 % faster (two centrings less).
                gap_tolerance: 1e-5,
                max_newton_iterations: 60,
                // The fit's valleys (control points sliding along the curve) make Newton
                // crawl at large t. Measured on the 2,174 UIUC airfoils (20 control points):
                // 1e-5 is 1.8x faster than no rule with the deviation's p90 0.9 % higher,
                // 3e-6 1.7x faster with median and p90 no higher, 1e-6 1.5x.
                stall_tolerance: 3e-6,
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

/// The result of [`smooth`](super::smooth).
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
    /// The largest data → curve distance of that least-squares fit (with parameter
    /// correction, the start of the eraser): how close the curve could come without the
    /// conditions on its curvature.
    pub least_squares_deviation: f64,
    /// Sentences for the caller, empty when all is well: one when the allowed extrema cost
    /// more than [`DEVIATION_WARNING_FACTOR`] times [`SmoothedCurve::least_squares_deviation`]
    /// (the data have more turns of the curvature than allowed, or turns sharper than the
    /// curve can follow with them).
    pub warnings: Vec<String>,
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
    /// The parameters of the knots where the curvature may have its extrema (knots of
    /// [`SmoothedCurve::curve`], in `(0, 1)`).
    pub allowed_extrema: Vec<f64>,
    /// The sign of `g = h1 h2 − 3 h3 h4` on the first piece between allowed extrema.
    pub first_sign: f64,
}

impl SmoothedCurve {
    /// The curve as the front ends hand it out: for closed data, the wrapped container of
    /// [`SmoothedCurve::periodic`] (the same points on `[0, 1]` as an unclamped curve whose
    /// last `p` control points repeat the first `p`); otherwise [`SmoothedCurve::curve`].
    #[must_use]
    pub fn output_curve(&self) -> &Curve2<f64> {
        self.periodic
            .as_ref()
            .map_or(&self.curve, PeriodicBSpline::wrapped)
    }

    /// The number of control points of the result: the distinct ones of a closed curve
    /// ([`PeriodicBSpline::len`]), otherwise those of [`SmoothedCurve::curve`] (the number
    /// asked for, or found by [`smooth_to_tolerance`](super::smooth_to_tolerance)).
    #[must_use]
    pub fn control_point_count(&self) -> usize {
        self.periodic
            .as_ref()
            .map_or(self.curve.control_points().len(), PeriodicBSpline::len)
    }

    /// The result's line of a batch summary ([`SmoothSummary::new`]).
    #[must_use]
    pub fn summary(&self) -> SmoothSummary {
        SmoothSummary {
            control_points: Some(self.curve.control_points().len()),
            max_deviation: Some(self.deviation.to_curve.max),
            max_deviation_to_data: Some(self.deviation.to_data),
            extrema: Some(self.extrema.len()),
            error: None,
            warnings: self.warnings.clone(),
        }
    }

    /// What [`smooth_from`](super::smooth_from) needs to start from this result.
    #[must_use]
    pub fn warm_start(&self) -> WarmStart {
        WarmStart {
            curve: self.curve.clone(),
            allowed_extrema: self.allowed_extrema.clone(),
            first_sign: self.first_sign,
            knot_exponent: self.knot_exponent,
            closed: self.periodic.is_some(),
        }
    }
}

/// One smoothing of a batch in a line, the same for every front end (the line of
/// `summary.jsonl` that `spline smooth DIR --out OUT` writes for each input, and the Python
/// package's `smooth_file`): a few numbers of the result, or the error. The front end adds the
/// input's name and the time taken.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SmoothSummary {
    /// The number of control points of [`SmoothedCurve::curve`] (a closed result opened at
    /// its closing point: `p` more than [`SmoothedCurve::control_point_count`]).
    pub control_points: Option<usize>,
    /// The largest data → curve distance ([`TwoSidedDeviation::to_curve`]).
    pub max_deviation: Option<f64>,
    /// The largest curve → data polyline distance ([`TwoSidedDeviation::to_data`]).
    pub max_deviation_to_data: Option<f64>,
    /// The number of curvature extrema of the result.
    pub extrema: Option<usize>,
    /// The error's message when the smoothing (or reading the input) failed; the fields above
    /// are then `None`.
    pub error: Option<String>,
    /// [`SmoothedCurve::warnings`] (empty on failure).
    pub warnings: Vec<String>,
}

impl SmoothSummary {
    /// The line of an outcome: [`SmoothedCurve::summary`], or the error's message alone.
    #[must_use]
    pub fn new(outcome: &Result<SmoothedCurve>) -> Self {
        match outcome {
            Ok(result) => result.summary(),
            Err(e) => Self::failed(e),
        }
    }

    /// The line of a failure: its message and no numbers.
    #[must_use]
    pub fn failed(error: impl fmt::Display) -> Self {
        Self {
            error: Some(error.to_string()),
            ..Self::default()
        }
    }
}

/// Where an earlier [`smooth`](super::smooth) ended ([`SmoothedCurve::warm_start`]): the
/// start of [`smooth_from`](super::smooth_from) on nearby data. A front end that keeps no
/// state can send it to its page and back: every field is plain data.
#[derive(Clone, Debug, PartialEq)]
pub struct WarmStart {
    /// The earlier curve (open, on `[0, 1]`, in the data's units).
    pub curve: Curve2<f64>,
    /// Its knots where the curvature may have its extrema.
    pub allowed_extrema: Vec<f64>,
    /// The sign of `g` on its first piece (`±1`).
    pub first_sign: f64,
    /// The exponent of the knot density its knots came from.
    pub knot_exponent: f64,
    /// Whether it was a closed curve (closed data start afresh).
    pub closed: bool,
}

/// The number of extrema as words: "1 curvature extremum", "2 curvature extrema".
pub(crate) fn extrema_words(k: usize) -> String {
    if k == 1 {
        "1 curvature extremum".to_owned()
    } else {
        format!("{k} curvature extrema")
    }
}
