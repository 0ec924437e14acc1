//! The options of scipy's `make_splrep`, `make_splprep` and `generate_knots`, and their
//! checks: read by the non-periodic replicas ([`super::splrep`]) and the periodic ones
//! ([`super::periodic`]) alike.

use spline_core::{Error, ErrorKind, KnotVector, Result, Scalar, to_f64};

/// The optional arguments of scipy's `make_splrep`, `make_splprep` and `generate_knots`
/// (for curves `xb`, `xe` are scipy's `ub`, `ue`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplrepOptions<'a, T> {
    /// Weights `w` (one per datum, positive): they multiply the residuals,
    /// $\sum_i (w_i \lVert y_i - g(x_i) \rVert)^2 \le s$. `None`: all ones.
    pub weights: Option<&'a [T]>,
    /// The start $x_b$ of the interval (`None`: the first abscissa); at most `x[0]`.
    pub xb: Option<T>,
    /// The end $x_e$ of the interval (`None`: the last abscissa); at least `x[m − 1]`.
    pub xe: Option<T>,
    /// The degree `k`: 1 to [`spline_core::MAX_DEGREE`] when `s > 0` (scipy's replicas
    /// set no limit; FITPACK's `curfit` and `percur` take 1 to 5, odd ones recommended).
    pub k: usize,
    /// The smoothing condition `s ≥ 0`; `0` is not-a-knot interpolation.
    pub s: T,
    /// Given knots (`make_splrep`/`make_splprep` only): no knots are placed, only the
    /// smoothing stage runs on them.
    pub t: Option<&'a [T]>,
    /// The cap on the number of knots placed (at least `2(k + 1)`); `None`: scipy's
    /// $\max(m + k + 1, 2k + 3)$ ($\max(m + 2k, 2k + 3)$ when periodic).
    pub nest: Option<usize>,
    /// scipy's `bc_type="periodic"` (FITPACK's `percur`): the spline of period
    /// $x_e - x_b$ whose values and first `k − 1` derivatives agree at $x_b$ and $x_e$. The
    /// first and last values must agree (as `numpy.allclose` with `atol=1e-15`); the last
    /// datum is the first one a period later and does not count in the residual. The
    /// knots are wrapped ($t_{k-j} = t_{n-k-1-j} - T$, $t_{n-k-1+j} = t_{k+j} + T$) and the
    /// last `k` coefficients repeat the first `k`. `false`: scipy's `"not-a-knot"`.
    pub periodic: bool,
}

impl<T: Scalar> Default for SplrepOptions<'_, T> {
    /// scipy's defaults: cubic, `s = 0`, everything else `None`.
    fn default() -> Self {
        Self {
            weights: None,
            xb: None,
            xe: None,
            k: 3,
            s: T::zero(),
            t: None,
            nest: None,
            periodic: false,
        }
    }
}

pub(super) fn invalid(message: impl Into<String>) -> Error {
    Error::new(ErrorKind::InvalidArgument, message)
}

impl<T: Scalar> SplrepOptions<'_, T> {
    /// For `s = 0`: scipy refuses `t`, `w` and `nest`.
    pub(super) fn check_interpolation(&self) -> Result<()> {
        if self.t.is_some() || self.weights.is_some() || self.nest.is_some() {
            return Err(invalid(
                "s == 0 is for interpolation only: t, w and nest must not be given",
            ));
        }
        Ok(())
    }

    /// The interval $[x_b, x_e]$ for sorted abscissae `x` (validated already).
    pub(super) fn bounds(&self, x: &[T]) -> Result<(T, T)> {
        let m = x.len();
        let xb = self.xb.unwrap_or(x[0]);
        let xe = self.xe.unwrap_or(x[m - 1]);
        if !(xb.is_finite() && xe.is_finite()) {
            return Err(Error::non_finite(format_args!(
                "the interval [{}, {}]",
                to_f64(xb),
                to_f64(xe)
            )));
        }
        if !(xb <= x[0] && xe >= x[m - 1]) {
            return Err(Error::new(
                ErrorKind::OutOfDomain,
                format!(
                    "the interval [xb, xe] = [{}, {}] must contain the abscissae [{}, {}]",
                    to_f64(xb),
                    to_f64(xe),
                    to_f64(x[0]),
                    to_f64(x[m - 1])
                ),
            ));
        }
        Ok((xb, xe))
    }

    /// scipy's check of `nest`: at least `2(k + 1)`, and not together with `t`.
    pub(super) fn check_nest(&self) -> Result<()> {
        if let Some(nest) = self.nest {
            let k = self.k;
            if nest < 2 * (k + 1) {
                return Err(invalid(format!(
                    "`nest` too small: nest = {nest} < 2*(k+1) = {}.",
                    2 * (k + 1)
                ))
                .with_counts(2 * (k + 1), nest));
            }
            if self.t.is_some() {
                return Err(invalid("Either supply `t` or `nest`."));
            }
        }
        Ok(())
    }
}

/// The checks of given knots that scipy's `fpcheck` and `fpchep` share, after their counts:
/// a valid knot vector, interior knots strictly increasing, the data inside
/// $[t_k, t_{n-k-1}]$.
pub(super) fn knots_around_data<T: Scalar>(x: &[T], t: &[T], k: usize) -> Result<KnotVector<T>> {
    let m = x.len();
    let n = t.len();
    let knots = KnotVector::new(k, t.to_vec())?;
    if let Some(j) = (k + 1..n - k).find(|&j| !(t[j] > t[j - 1])) {
        return Err(Error::new(
            ErrorKind::KnotMultiplicity,
            format!(
                "Internal knots must be distinct: knots {} and {j} are both {}",
                j - 1,
                to_f64(t[j])
            ),
        ));
    }
    if !(t[k] <= x[0] && x[m - 1] <= t[n - k - 1]) {
        return Err(Error::new(
            ErrorKind::OutOfDomain,
            format!(
                "Out of bounds: the data [{}, {}] must lie in [t[k], t[n-k-1]] = [{}, {}]",
                to_f64(x[0]),
                to_f64(x[m - 1]),
                to_f64(t[k]),
                to_f64(t[n - k - 1])
            ),
        ));
    }
    Ok(knots)
}
