//! Requests in words, as the tool and the Python package take them: the objective by name and
//! the allowed extrema as a count, a list, or both (one mapping for every front end).

use super::{Extremum, MAX_CURVATURE_EXTREMA, Objective, SmoothingOptions};
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
    /// above [`MAX_CURVATURE_EXTREMA`]; the options are then unchanged.
    pub fn request_extrema(&mut self, count: Option<usize>, given: Vec<Extremum>) -> Result<()> {
        if !given.is_empty() {
            if let Some(k) = count.filter(|&k| k != given.len()) {
                return Err(Error::new(
                    ErrorKind::InvalidLength,
                    format!("{k} disagrees with the {} extrema given", given.len()),
                )
                .with_counts(given.len(), k));
            }
            self.extrema = given;
            return Ok(());
        }
        let Some(k) = count else {
            return Ok(());
        };
        if k > MAX_CURVATURE_EXTREMA {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!("at most {MAX_CURVATURE_EXTREMA} extrema can be allowed, got {k}"),
            )
            .with_counts(MAX_CURVATURE_EXTREMA, k));
        }
        self.extrema = Extremum::alternating(k);
        Ok(())
    }
}
