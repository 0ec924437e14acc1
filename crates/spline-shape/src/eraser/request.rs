//! Requests in words, as the tool and the Python package take them: the objective by name,
//! the allowed extrema as a count, `auto`, a list, or a count and a list, the control points as
//! a count or a deviation (one mapping for every front end, with its checks and messages).

use super::smooth_request::{
    AllowedExtrema, ControlPoints, SmoothRequest, alternating, check_count,
};
use super::{Extremum, Objective, SmoothingOptions};
use spline_core::{Error, ErrorKind, Result};
use std::str::FromStr;

impl FromStr for Objective {
    type Err = Error;

    /// `max` ([`Objective::MaxDeviation`]) or `least-squares` / `lsq`
    /// ([`Objective::LeastSquares`]).
    fn from_str(text: &str) -> Result<Self> {
        match text.trim() {
            "max" => Ok(Self::MaxDeviation),
            "least-squares" | "lsq" => Ok(Self::LeastSquares),
            other => Err(Error::new(
                ErrorKind::InvalidArgument,
                format!("unknown choice {other:?} (max or least-squares)"),
            )),
        }
    }
}

impl SmoothingOptions {
    /// Sets the allowed extrema of a request: the `given` ones when there are any (then
    /// `count`, if also given, must be their number), else `count` extrema alternating from a
    /// maximum (`max, min, max, …`), each placed automatically; with neither, the default of
    /// [`SmoothingOptions::new`] (one maximum) stays.
    ///
    /// ```
    /// use spline_shape::{ExtremumKind, SmoothingOptions};
    /// let mut options = SmoothingOptions::new(12);
    /// options.request_extrema(None, Vec::new())?;
    /// assert_eq!(options.extrema.len(), 1); // the default
    /// options.request_extrema(Some(3), Vec::new())?;
    /// assert_eq!(options.extrema[1].kind, ExtremumKind::Minimum);
    /// let given = vec!["min@0.2".parse()?];
    /// options.request_extrema(None, given.clone())?;
    /// assert_eq!(options.extrema, given);
    /// assert!(options.request_extrema(Some(2), given).is_err());
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] when `count` disagrees with the extrema given
    /// (`(given, count)` as [`Error::counts`]); [`ErrorKind::InvalidArgument`] for a count
    /// above [`MAX_CURVATURE_EXTREMA`](super::MAX_CURVATURE_EXTREMA); the options are then
    /// unchanged.
    pub fn request_extrema(&mut self, count: Option<usize>, given: Vec<Extremum>) -> Result<()> {
        match requested_extrema(count, given)? {
            Some(AllowedExtrema::Given(given)) => self.extrema = given,
            Some(AllowedExtrema::Count(k)) => self.extrema = alternating(k)?,
            Some(AllowedExtrema::Auto { .. }) | None => {}
        }
        Ok(())
    }
}

/// The extrema of a count and a list ([`SmoothingOptions::request_extrema`]): `None` with
/// neither.
fn requested_extrema(count: Option<usize>, given: Vec<Extremum>) -> Result<Option<AllowedExtrema>> {
    if !given.is_empty() {
        if let Some(k) = count.filter(|&k| k != given.len()) {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!("{k} disagrees with the {} extrema given", given.len()),
            )
            .with_counts(given.len(), k));
        }
        return Ok(Some(AllowedExtrema::Given(given)));
    }
    let Some(k) = count else {
        return Ok(None);
    };
    check_count(k)?;
    Ok(Some(AllowedExtrema::Count(k)))
}

/// The number of curvature extrema in words: a count, or `auto` (the fewest within a
/// tolerance, [`AllowedExtrema::Auto`]).
///
/// ```
/// use spline_shape::ExtremaCount;
/// assert_eq!("auto".parse::<ExtremaCount>()?, ExtremaCount::Auto);
/// assert_eq!(" 3".parse::<ExtremaCount>()?, ExtremaCount::Count(3));
/// assert!("three".parse::<ExtremaCount>().is_err());
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExtremaCount {
    /// This many, alternating from a maximum.
    Count(usize),
    /// The fewest within the tolerance.
    Auto,
}

impl FromStr for ExtremaCount {
    type Err = Error;

    /// `auto` or a count (`0, 1, 2, …`).
    fn from_str(text: &str) -> Result<Self> {
        match text.trim() {
            "auto" => Ok(Self::Auto),
            count => count.parse().map(Self::Count).map_err(|_| {
                Error::new(
                    ErrorKind::Parse,
                    format!("expected a number of curvature extrema or auto, got {text:?}"),
                )
            }),
        }
    }
}

/// How a front end spells its options, for the messages of [`SmoothRequest::from_words`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OptionSpelling {
    /// The tool's flags: `--control-points N`, `--curvature-extrema auto`, `--extremum`.
    Flags,
    /// Keyword arguments: `control_points`, `curvature_extrema="auto"`, `extrema`.
    Keywords,
}

impl OptionSpelling {
    /// The number of control points, with its value where a flag takes one.
    fn control_points(self) -> &'static str {
        match self {
            Self::Flags => "--control-points N",
            Self::Keywords => "control_points",
        }
    }

    /// The maximum deviation, with its value where a flag takes one.
    fn max_deviation(self) -> &'static str {
        match self {
            Self::Flags => "--max-deviation D",
            Self::Keywords => "max_deviation",
        }
    }

    /// The number of curvature extrema.
    fn curvature_extrema(self) -> &'static str {
        match self {
            Self::Flags => "--curvature-extrema",
            Self::Keywords => "curvature_extrema",
        }
    }

    /// The number of curvature extrema set to `auto`.
    fn auto(self) -> &'static str {
        match self {
            Self::Flags => "--curvature-extrema auto",
            Self::Keywords => "curvature_extrema=\"auto\"",
        }
    }

    /// The extrema one by one.
    fn extremum(self) -> &'static str {
        match self {
            Self::Flags => "--extremum",
            Self::Keywords => "extrema",
        }
    }

    /// The objective.
    fn objective(self) -> &'static str {
        match self {
            Self::Flags => "--objective",
            Self::Keywords => "objective",
        }
    }
}

/// The options of a smoothing as a front end takes them (`spline smooth`'s flags, the Python
/// package's `smooth` keywords), before [`SmoothRequest::from_words`] checks them. What a
/// front end parses itself (numbers, JSON lists) comes as the result of its parse: a failed
/// parse is reported where the checks come to that option, so that the first problem of
/// several is the same whichever front end parsed them.
#[derive(Clone, Debug, PartialEq)]
pub struct SmoothWords<'a> {
    /// The number of control points.
    pub control_points: Option<usize>,
    /// The fewest control points within this distance ([`ControlPoints::Fewest`]); with
    /// [`ExtremaCount::Auto`], the tolerance of the extrema ([`AllowedExtrema::Auto`]).
    pub max_deviation: Option<f64>,
    /// The degree.
    pub degree: usize,
    /// The number of extrema, or `auto`.
    pub curvature_extrema: Option<Result<ExtremaCount>>,
    /// The extrema one by one: `max`, `min`, `max@U`, `min@U` ([`Extremum`]'s words).
    pub extrema: &'a [String],
    /// The objective: `max` or `least-squares` ([`Objective`]'s words).
    pub objective: &'a str,
    /// [`SmoothingOptions::thorough`].
    pub thorough: bool,
    /// [`SmoothingOptions::knot_search`].
    pub knot_search: bool,
    /// [`SmoothingOptions::closed`].
    pub closed: bool,
    /// [`SmoothingOptions::knot_exponents`] (`None`: the default).
    pub knot_exponents: Option<Result<Vec<f64>>>,
}

impl SmoothRequest {
    /// The request of a front end's options: a number of control points or a maximum
    /// deviation (both only with `auto` extrema, whose tolerance the deviation then is), the
    /// extrema by count (`auto`: [`AllowedExtrema::Auto`]), one by one, or both (then the
    /// count must be their number), by default one maximum. Messages name the options as
    /// `spelling` spells them.
    ///
    /// ```
    /// use spline_shape::{
    ///     AllowedExtrema, ControlPoints, OptionSpelling, SmoothRequest, SmoothWords,
    /// };
    /// let words = SmoothWords {
    ///     control_points: Some(20),
    ///     max_deviation: Some(1e-3),
    ///     degree: 3,
    ///     curvature_extrema: Some("auto".parse()),
    ///     extrema: &[],
    ///     objective: "max",
    ///     thorough: false,
    ///     knot_search: false,
    ///     closed: false,
    ///     knot_exponents: None,
    /// };
    /// let request = SmoothRequest::from_words(words.clone(), OptionSpelling::Flags)?;
    /// assert_eq!(request.control_points, ControlPoints::Count(20));
    /// assert_eq!(request.extrema, AllowedExtrema::Auto { max_deviation: Some(1e-3) });
    /// let neither = SmoothWords { control_points: None, max_deviation: None, ..words };
    /// let message = SmoothRequest::from_words(neither, OptionSpelling::Keywords).unwrap_err();
    /// assert_eq!(message.to_string(), "give control_points or max_deviation");
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] for neither a number of control points nor a maximum
    /// deviation, both without `auto`, `auto` without a number of control points, `auto` with
    /// extrema given one by one, or a count above
    /// [`MAX_CURVATURE_EXTREMA`](super::MAX_CURVATURE_EXTREMA) (with [`Error::counts`]);
    /// [`ErrorKind::InvalidLength`] for a count that disagrees with the extrema given
    /// (`(given, count)` as [`Error::counts`]); the [`ErrorKind::Parse`] or
    /// [`ErrorKind::InvalidArgument`] errors of [`Objective`]'s and [`Extremum`]'s words;
    /// the errors of the front end's parses in [`SmoothWords`]. Messages about one option
    /// start with its name, as `spelling` spells it. Of several problems, the first reported
    /// is that of the control points, then of the knot density exponents, the objective, the
    /// extrema one by one, their number.
    pub fn from_words(words: SmoothWords<'_>, spelling: OptionSpelling) -> Result<Self> {
        let auto = matches!(words.curvature_extrema, Some(Ok(ExtremaCount::Auto)));
        let (cp, md) = (spelling.control_points(), spelling.max_deviation());
        let control = match (words.control_points, words.max_deviation) {
            (Some(n), None) => ControlPoints::Count(n),
            (Some(n), Some(_)) if auto => ControlPoints::Count(n),
            (None, Some(_)) if auto => {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!("{} needs {cp}", spelling.auto()),
                ));
            }
            (None, Some(max_deviation)) => ControlPoints::Fewest { max_deviation },
            (None, None) => {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!("give {cp} or {md}"),
                ));
            }
            (Some(_), Some(_)) => {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!(
                        "give {cp} or {md}, not both (both only with {})",
                        spelling.auto()
                    ),
                ));
            }
        };
        let mut request = Self::new(control);
        request.degree = words.degree;
        request.thorough = words.thorough;
        request.knot_search = words.knot_search;
        request.closed = words.closed;
        if let Some(exponents) = words.knot_exponents {
            request.knot_exponents = exponents?;
        }
        request.objective = words
            .objective
            .parse::<Objective>()
            .map_err(|e| e.context(spelling.objective()))?;
        let given = words
            .extrema
            .iter()
            .map(|t| {
                t.parse::<Extremum>()
                    .map_err(|e| e.context(spelling.extremum()))
            })
            .collect::<Result<Vec<_>>>()?;
        let count = match words.curvature_extrema.transpose()? {
            Some(ExtremaCount::Auto) if !given.is_empty() => {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!(
                        "{} chooses the extrema: give no {}",
                        spelling.auto(),
                        spelling.extremum()
                    ),
                ));
            }
            Some(ExtremaCount::Auto) => {
                request.extrema = AllowedExtrema::Auto {
                    max_deviation: words.max_deviation,
                };
                return Ok(request);
            }
            Some(ExtremaCount::Count(k)) => Some(k),
            None => None,
        };
        request.extrema = requested_extrema(count, given)
            .map_err(|e| e.context(spelling.curvature_extrema()))?
            .unwrap_or(AllowedExtrema::Count(1));
        Ok(request)
    }
}
