//! Requests in words, as the tool and the Python package take them: the objective by name and
//! the allowed extrema as a count, a list, or both (one mapping for every front end).

use super::{Extremum, MAX_CURVATURE_EXTREMA, Objective};
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

impl Extremum {
    /// The allowed extrema of a request: the `given` ones when there are any (then `count`,
    /// if also given, must be their number), else `count` extrema alternating from a maximum
    /// (`max, min, max, …`), each placed automatically, else none.
    ///
    /// ```
    /// use spline_shape::{Extremum, ExtremumKind};
    /// let three = Extremum::resolve(Some(3), Vec::new())?;
    /// assert_eq!(three[1].kind, ExtremumKind::Minimum);
    /// let given = vec!["min@0.2".parse()?];
    /// assert_eq!(Extremum::resolve(None, given.clone())?, given);
    /// assert!(Extremum::resolve(Some(2), given).is_err());
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] when `count` disagrees with the extrema given, or for a
    /// count above [`MAX_CURVATURE_EXTREMA`].
    pub fn resolve(count: Option<usize>, given: Vec<Extremum>) -> Result<Vec<Extremum>> {
        if !given.is_empty() {
            if let Some(k) = count.filter(|&k| k != given.len()) {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!("{k} disagrees with the {} extrema given", given.len()),
                ));
            }
            return Ok(given);
        }
        let k = count.unwrap_or(0);
        if k > MAX_CURVATURE_EXTREMA {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!("at most {MAX_CURVATURE_EXTREMA} extrema can be allowed, got {k}"),
            ));
        }
        Ok((0..k)
            .map(|i| {
                if i % 2 == 0 {
                    Self::maximum()
                } else {
                    Self::minimum()
                }
            })
            .collect())
    }
}
