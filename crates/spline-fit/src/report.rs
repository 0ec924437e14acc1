//! Deviation reports of fits.

use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, from_count};
use spline_geom::BSpline;

/// How far a fitted curve passes from the data: $d_k = \lVert C(\bar u_k) - Q_k \rVert$.
#[derive(Clone, Debug, PartialEq)]
pub struct Deviation<T> {
    /// The largest distance $\max_k d_k$.
    pub max: T,
    /// The index `k` of the data point farthest from the curve (the first one on ties).
    pub max_index: usize,
    /// The root mean square $\sqrt{\frac{1}{m+1} \sum_k d_k^2}$ (unweighted).
    pub rms: T,
    /// The sum of squares $\sum_k d_k^2$ (unweighted).
    pub sum_squares: T,
    /// Every distance $d_k$, in the order of the data.
    pub distances: Vec<T>,
}

impl<T: Scalar> Deviation<T> {
    /// Computes the report from the distances.
    ///
    /// # Panics
    /// If `distances` is empty.
    #[must_use]
    pub fn from_distances(distances: Vec<T>) -> Self {
        assert!(!distances.is_empty(), "a deviation report needs data");
        let mut max = T::zero();
        let mut max_index = 0;
        let mut sum_squares = T::zero();
        for (k, &d) in distances.iter().enumerate() {
            if d > max {
                max = d;
                max_index = k;
            }
            sum_squares += d * d;
        }
        let rms = (sum_squares / from_count::<T>(distances.len())).sqrt();
        Self {
            max,
            max_index,
            rms,
            sum_squares,
            distances,
        }
    }

    /// The indices of the data points farther than `tolerance` from the curve.
    #[must_use]
    pub fn exceeding(&self, tolerance: T) -> Vec<usize> {
        self.distances
            .iter()
            .enumerate()
            .filter(|&(_, &d)| d > tolerance)
            .map(|(k, _)| k)
            .collect()
    }
}

/// The deviation of `curve` from the `points` at their parameters.
///
/// ```
/// use spline_fit::deviation;
/// use spline_geom::BSpline;
/// let line = BSpline::from_knots(1, vec![0.0f64, 0.0, 1.0, 1.0], vec![0.0, 1.0])?;
/// let report = deviation(&line, &[0.0, 0.5, 1.0], &[0.0, 0.75, 1.0])?;
/// assert_eq!(report.max_index, 1);
/// assert!((report.max - 0.25).abs() < 1e-15);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidLength`] if the lengths differ or there are no points; the errors of
/// [`BSpline::eval_many`] for parameters outside the domain.
pub fn deviation<T: Scalar, P: ControlPoint<T>>(
    curve: &BSpline<T, P>,
    params: &[T],
    points: &[P],
) -> Result<Deviation<T>> {
    if params.len() != points.len() || points.is_empty() {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "{} parameters for {} points (need one per point, at least one)",
                params.len(),
                points.len()
            ),
        ));
    }
    let values = curve.eval_many(params)?;
    Ok(Deviation::from_distances(
        values
            .iter()
            .zip(points)
            .map(|(c, q)| (*c - *q).length())
            .collect(),
    ))
}

/// A fitted curve with the parameters of the data and its deviation from them.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveFit<T, P> {
    /// The curve.
    pub curve: BSpline<T, P>,
    /// The parameter of each data point.
    pub params: Vec<T>,
    /// The distances of the data from the curve at those parameters.
    pub deviation: Deviation<T>,
}

impl<T: Scalar, P: ControlPoint<T>> CurveFit<T, P> {
    pub(crate) fn new(curve: BSpline<T, P>, params: Vec<T>, points: &[P]) -> Result<Self> {
        let deviation = deviation(&curve, &params, points)?;
        Ok(Self {
            curve,
            params,
            deviation,
        })
    }
}
