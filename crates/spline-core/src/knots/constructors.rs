//! The classic knot vectors: clamped and unclamped uniform, Bézier, clamped with given
//! interior knots, averaging and not-a-knot.

use super::{KnotVector, MAX_DEGREE, check_interval, check_params};
use crate::error::{Error, ErrorKind, Result};
use crate::scalar::{Scalar, from_count, to_f64};

impl<T: Scalar> KnotVector<T> {
    /// `p + 1` copies of `a`, `n − p − 1` uniformly spaced interior knots, `p + 1` copies of `b`.
    ///
    /// ```
    /// let k = spline_core::KnotVector::clamped_uniform(2, 5, 0.0, 1.0)?;
    /// assert_eq!(k.knots(), &[0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::TooFewPoints`] if `num_basis < degree + 1`; [`ErrorKind::EmptyDomain`]
    /// unless `a < b`; the errors of [`KnotVector::new`].
    pub fn clamped_uniform(degree: usize, num_basis: usize, a: T, b: T) -> Result<Self> {
        check_count(degree, num_basis)?;
        check_interval(a, b)?;
        let segments = num_basis - degree;
        let interior: Vec<T> = (1..segments)
            .map(|j| a + (b - a) * from_count::<T>(j) / from_count::<T>(segments))
            .collect();
        Self::clamped(degree, a, b, &interior)
    }

    /// Uniformly spaced, unclamped knots whose domain `[u_p, u_n]` is `[a, b]`.
    ///
    /// # Errors
    /// As [`KnotVector::clamped_uniform`].
    pub fn uniform(degree: usize, num_basis: usize, a: T, b: T) -> Result<Self> {
        check_count(degree, num_basis)?;
        check_interval(a, b)?;
        let segments = from_count::<T>(num_basis - degree);
        let knots = (0..num_basis + degree + 1)
            .map(|j| {
                let offset = from_count::<T>(j) - from_count::<T>(degree);
                a + (b - a) * offset / segments
            })
            .collect();
        Self::new(degree, knots)
    }

    /// The knot vector of a single Bézier segment on `[a, b]`: `p + 1` copies of each end.
    ///
    /// # Errors
    /// As [`KnotVector::new`]; [`ErrorKind::EmptyDomain`] unless `a < b`.
    pub fn bezier(degree: usize, a: T, b: T) -> Result<Self> {
        Self::clamped(degree, a, b, &[])
    }

    /// A clamped knot vector on `[a, b]` with the given interior knots (sorted, repeated as
    /// wanted).
    ///
    /// # Errors
    /// As [`KnotVector::new`].
    pub fn clamped(degree: usize, a: T, b: T, interior: &[T]) -> Result<Self> {
        check_interval(a, b)?;
        let mut knots = Vec::with_capacity(interior.len() + 2 * degree + 2);
        knots.extend(std::iter::repeat_n(a, degree + 1));
        knots.extend_from_slice(interior);
        knots.extend(std::iter::repeat_n(b, degree + 1));
        if let Some(i) = interior.iter().position(|&k| !(k > a && k < b)) {
            let k = interior[i];
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "interior knot {} is not strictly inside ({}, {})",
                    to_f64(k),
                    to_f64(a),
                    to_f64(b)
                ),
            )
            .with_index(i)
            .with_value(to_f64(k))
            .with_interval(to_f64(a), to_f64(b)));
        }
        Self::new(degree, knots)
    }

    /// Knots by averaging the parameters of the data (seed 004 (7.6), The NURBS Book (9.8)):
    /// clamped on `[ū_0, ū_m]` with interior knots $u_{j+p} = \frac1p \sum_{i=j}^{j+p-1} \bar u_i$,
    /// `j = 1 … m − p`, for `m + 1` parameters. With these knots the interpolation matrix is
    /// non-singular (Schoenberg–Whitney holds). Degree 0 uses the midpoints between parameters.
    ///
    /// ```
    /// let k = spline_core::KnotVector::averaging(2, &[0.0, 0.25, 0.5, 0.75, 1.0])?;
    /// assert_eq!(k.knots(), &[0.0, 0.0, 0.0, 0.375, 0.625, 1.0, 1.0, 1.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::TooFewPoints`] with fewer than `p + 1` parameters; [`ErrorKind::NonFinite`];
    /// [`ErrorKind::UnsortedKnots`] if the parameters decrease; the errors of
    /// [`KnotVector::new`] (e.g. when repeated parameters give too many equal knots).
    pub fn averaging(degree: usize, params: &[T]) -> Result<Self> {
        check_count(degree, params.len())?;
        check_params(params)?;
        let count = params.len();
        let (a, b) = (params[0], params[count - 1]);
        let interior: Vec<T> = if degree == 0 {
            params
                .windows(2)
                .map(|w| (w[0] + w[1]) * crate::cast(0.5))
                .collect()
        } else {
            let p = from_count::<T>(degree);
            (1..count - degree)
                .map(|j| params[j..j + degree].iter().fold(T::zero(), |s, &x| s + x) / p)
                .collect()
        };
        let mut knots = Vec::with_capacity(count + degree + 1);
        knots.extend(std::iter::repeat_n(a, degree + 1));
        knots.extend(interior);
        knots.extend(std::iter::repeat_n(b, degree + 1));
        Self::new(degree, knots)
    }

    /// The knots of not-a-knot interpolation at `x_0 ≤ … ≤ x_m` (de Boor XIII (12), the rule
    /// of scipy's `make_interp_spline` and of FITPACK): clamped on $[x_0, x_m]$; for odd
    /// degrees the interior knots are the abscissae without the first and last
    /// $(p + 1)/2$; for even degrees the midpoints $(x_{j-1} + x_j)/2$ without the first
    /// and last $p/2$. The interpolant then has `m + 1` control points.
    ///
    /// ```
    /// let k = spline_core::KnotVector::not_a_knot(3, &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0])?;
    /// assert_eq!(k.knots(), &[0.0, 0.0, 0.0, 0.0, 2.0, 3.0, 5.0, 5.0, 5.0, 5.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::TooFewPoints`] with `p` abscissae or fewer; the errors of
    /// [`check_params`] and [`KnotVector::new`].
    pub fn not_a_knot(degree: usize, x: &[T]) -> Result<Self> {
        check_count(degree, x.len())?;
        check_params(x)?;
        let m = x.len();
        let half: T = crate::cast(0.5);
        let interior: Vec<T> = if degree % 2 == 1 {
            let k2 = degree.div_ceil(2);
            x[k2..m - k2].to_vec()
        } else {
            let k2 = degree / 2;
            (1..m)
                .map(|j| (x[j - 1] + x[j]) * half)
                .skip(k2)
                .take((m - 1).saturating_sub(2 * k2))
                .collect()
        };
        let mut knots = Vec::with_capacity(m + degree + 1);
        knots.extend(std::iter::repeat_n(x[0], degree + 1));
        knots.extend(interior);
        knots.extend(std::iter::repeat_n(x[m - 1], degree + 1));
        Self::new(degree, knots)
    }
}

/// At least `degree + 1` basis functions (or points), and a supported degree.
fn check_count(degree: usize, count: usize) -> Result<()> {
    if count <= degree {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "degree {degree} needs at least {} control points or data points, got {count}",
                degree + 1
            ),
        ));
    }
    if degree > MAX_DEGREE {
        return Err(Error::new(
            ErrorKind::DegreeTooHigh,
            format!("degree {degree} is above the supported maximum {MAX_DEGREE}"),
        ));
    }
    Ok(())
}
