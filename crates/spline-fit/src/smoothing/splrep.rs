//! scipy 1.17's FITPACK replicas with their full signatures: `make_splrep(x, y, w, xb, xe,
//! k, s, t, nest)`, `make_splprep(x, w, u, ub, ue, k, s, t, nest)` and
//! `generate_knots(x, y, w, xb, xe, k, s, nest)` (scipy/interpolate/_fitpack_repro.py), with
//! scipy's `bc_type="periodic"` as [`SplrepOptions::periodic`]. The algorithm is
//! [`super::residual`]'s (FITPACK's `curfit`) and [`super::periodic`]'s (`percur`); this
//! module adds the interval $[x_b, x_e]$, given knots, the cap `nest`, the sequence of knot
//! vectors and scipy's parameters of curves.

use super::periodic;
use super::residual::{Data, ResidualFit, check_lengths};
pub use super::splrep_options::SplrepOptions;
use super::splrep_options::{invalid, knots_around_data};
use crate::interpolate::interpolate_with_knots;
use crate::params::check_strict;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar};

/// The not-a-knot interpolating spline (scipy's `make_interp_spline(x, y, k)`).
fn interpolation<T: Scalar, P: ControlPoint<T>>(
    x: &[T],
    y: &[P],
    k: usize,
) -> Result<ResidualFit<T, P>> {
    check_lengths(x.len(), y.len())?;
    check_strict(x)?;
    let knots = KnotVector::not_a_knot(k, x)?;
    let spline = interpolate_with_knots(&knots, x, y)?;
    Ok(ResidualFit::unsmoothed(spline, T::zero()))
}

/// scipy's `fpcheck` of given knots against the data (not periodic): `k + 1 ≤ n − k − 1 ≤ m`
/// coefficients, interior knots strictly increasing, the data inside $[t_k, t_{n-k-1}]$;
/// the Schoenberg–Whitney conditions are checked by the least-squares solve.
fn check_given_knots<T: Scalar>(x: &[T], t: &[T], k: usize) -> Result<KnotVector<T>> {
    let m = x.len();
    let n = t.len();
    if !(n >= 2 * (k + 1) && n - k - 1 <= m) {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("Need k+1 <= n-k-1 <= m. Got m = {m}, n = {n}, k = {k}"),
        ));
    }
    knots_around_data(x, t, k)
}

/// scipy's `make_splrep(x, y, w=w, xb=xb, xe=xe, k=k, s=s, t=t, nest=nest)`: the smoothing
/// spline of FITPACK's `curfit` (see [`crate::smoothing_to_residual`]) with the options of
/// scipy. For `s = 0` the not-a-knot interpolating spline (`make_interp_spline`; `t`, `w`
/// and `nest` refused, `xb`, `xe` ignored, as scipy). Otherwise knots are placed on
/// $[x_b, x_e]$ until the least-squares residual meets `s` or `nest` knots are reached
/// (skipped when `t` is given), then the jumps of the `k`-th derivative are minimised
/// subject to $\sum_i (w_i \lVert y_i - g(x_i) \rVert)^2 = s$. Vector values `y` give
/// scipy's `make_splprep` with given parameters `x`.
///
/// With [`SplrepOptions::periodic`] (scipy's `bc_type="periodic"`, FITPACK's `percur`): the
/// spline of period $x_e - x_b$, on wrapped knots, whose residual over the data but the
/// last meets `s`; knots are placed from the least-squares constant, and `s = 0` is scipy's
/// periodic interpolation (`make_interp_spline(x, y, k, bc_type="periodic")`).
///
/// ```
/// use spline_fit::{SplrepOptions, make_splrep};
/// let x: Vec<f64> = (0..40).map(|i| f64::from(i) / 39.0).collect();
/// let y: Vec<f64> = x.iter().map(|t| (6.0 * t).sin()).collect();
/// let fit = make_splrep(&x, &y, &SplrepOptions { s: 1e-3, ..Default::default() })?;
/// assert!(fit.converged && fit.spline.len() < 40);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for `t`, `w` or `nest` with `s = 0`, `nest < 2(k + 1)`,
/// `t` and `nest` together, and the errors of [`crate::smoothing_to_residual`] (but
/// degrees 1 to [`spline_core::MAX_DEGREE`]; `s` finite and non-negative, lengths, sorted
/// finite data, positive weights);
/// [`ErrorKind::OutOfDomain`] when $[x_b, x_e]$ does not contain the data or the given
/// knots' base interval does not; for given knots [`ErrorKind::InvalidLength`] unless
/// `k + 1 ≤ n − k − 1 ≤ m`, [`ErrorKind::KnotMultiplicity`] for repeated interior knots and
/// the errors of [`KnotVector::new`]; [`ErrorKind::SchoenbergWhitney`] or
/// [`ErrorKind::SingularSystem`] when a system cannot be solved. For `s = 0` the errors of
/// [`crate::interpolate_with_knots`] (strictly increasing `x`).
///
/// Periodic: at least 2 data ([`ErrorKind::TooFewPoints`]);
/// [`ErrorKind::InvalidArgument`] when the first and last values differ (beyond
/// `numpy.allclose(y[0], y[-1], atol=1e-15)`); for given knots
/// [`ErrorKind::InvalidLength`] unless `k + 1 ≤ n − k − 1 ≤ m + k − 1` and
/// [`ErrorKind::SchoenbergWhitney`] unless some cyclic shift of the data satisfies the
/// Schoenberg–Whitney conditions (FITPACK's `fpchep`); for `s = 0` the errors of
/// [`crate::interpolate_periodic`].
pub fn make_splrep<T: Scalar, P: ControlPoint<T>>(
    x: &[T],
    y: &[P],
    options: &SplrepOptions<'_, T>,
) -> Result<ResidualFit<T, P>> {
    let k = options.k;
    if options.s == T::zero() {
        options.check_interpolation()?;
        return if options.periodic {
            periodic::interpolation(x, y, k)
        } else {
            interpolation(x, y, k)
        };
    }
    let data = Data::new(x, y, options.weights, (k, options.s), options.periodic)?;
    options.check_nest()?;
    let bounds = options.bounds(x)?;
    let knots = match options.t {
        Some(t) if options.periodic => periodic::check_given_knots(x, t, k)?,
        Some(t) => check_given_knots(x, t, k)?,
        None => data.generate_knots_with(bounds, options.nest, &mut |_| {})?,
    };
    data.fit(&knots, bounds)
}

/// scipy's parameters of `make_splprep` when `u` is not given: cumulative chord lengths
/// divided by the total, $u_0 = 0$, $u_j = \sum_{i \le j} \lVert x_i - x_{i-1} \rVert / L$
/// (summed and divided in scipy's order, so the same numbers).
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] with fewer than 2 points; [`ErrorKind::NonFinite`] for
/// non-finite points; [`ErrorKind::DegenerateGeometry`] when all points coincide (scipy
/// would divide by zero).
pub fn chord_length_parameters<T: Scalar, P: ControlPoint<T>>(points: &[P]) -> Result<Vec<T>> {
    if points.len() < 2 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!("parameters need at least 2 points, got {}", points.len()),
        )
        .with_counts(2, points.len()));
    }
    if let Some(i) = points.iter().position(|p| !p.all_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("data point {i} is not finite"),
        )
        .with_index(i));
    }
    let mut u = Vec::with_capacity(points.len());
    u.push(T::zero());
    let mut sum = T::zero();
    for pair in points.windows(2) {
        let d = pair[1] - pair[0];
        let squares = (0..P::DIM).fold(T::zero(), |acc, c| acc + d.coord(c) * d.coord(c));
        sum += squares.sqrt();
        u.push(sum);
    }
    if !(sum > T::zero() && sum.is_finite()) {
        return Err(Error::new(
            ErrorKind::DegenerateGeometry,
            "the points all coincide (or their chord length overflows): no chord-length parameters",
        ));
    }
    for v in &mut u[1..] {
        *v /= sum;
    }
    Ok(u)
}

/// scipy's `make_splprep(x, w=w, u=u, ub=ub, ue=ue, k=k, s=s, t=t, nest=nest)` for the
/// curve through `points` (scipy's `x` transposed: one point per datum): the parameters are
/// `u` or [`chord_length_parameters`], then [`make_splrep`] with the points as values
/// (`options.xb`, `options.xe` are `ub`, `ue`). Returns the fit and the parameters.
/// Periodic (a closed curve, the last point equal to the first) with `s = 0` is the
/// periodic interpolation here; scipy's `make_splprep` ignores `bc_type` when `s = 0` and
/// interpolates with not-a-knot ends (the Python package keeps scipy's behaviour).
///
/// # Errors
/// As [`chord_length_parameters`] (when `u` is `None`) and [`make_splrep`];
/// [`ErrorKind::InvalidLength`] unless `u` has one parameter per point.
pub fn make_splprep<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    u: Option<&[T]>,
    options: &SplrepOptions<'_, T>,
) -> Result<(ResidualFit<T, P>, Vec<T>)> {
    let u = match u {
        Some(u) => {
            if u.len() != points.len() {
                return Err(Error::invalid_length(
                    "one parameter per point",
                    points.len(),
                    u.len(),
                ));
            }
            u.to_vec()
        }
        None => chord_length_parameters(points)?,
    };
    let fit = make_splrep(&u, points, options)?;
    Ok((fit, u))
}

/// scipy's `generate_knots(x, y, w=w, xb=xb, xe=xe, k=k, s=s, nest=nest)`: every knot vector
/// FITPACK's first stage tries, in order: the polynomial's ($x_b$, $x_e$ each `k + 1`
/// times), then after each least-squares fit whose residual exceeds `s` the vector with
/// the knots added; it ends when the residual meets `s` (the last vector is the one that
/// met it), when `nest` knots are reached, or with the not-a-knot knots of interpolation
/// when `m + k + 1` would be. For `s = 0` the one vector is the not-a-knot one.
/// Periodic: the least-squares constant's first (one period `x[0] … x[m − 1]` and `k` more
/// knots each side), then from one interior knot at the middle datum the wrapped vectors,
/// ending with scipy's periodic interpolation knots when `m + 2k` would be reached; for
/// `s = 0` those (the not-a-knot ones for `k = 1`, as scipy). `options.t` must be `None`.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for `options.t`, and as [`make_splrep`].
pub fn generate_knots<T: Scalar, P: ControlPoint<T>>(
    x: &[T],
    y: &[P],
    options: &SplrepOptions<'_, T>,
) -> Result<Vec<Vec<T>>> {
    if options.t.is_some() {
        return Err(invalid(
            "generate_knots places the knots: t must not be given",
        ));
    }
    let k = options.k;
    if options.s == T::zero() {
        options.check_interpolation()?;
        let knots = if options.periodic {
            periodic::interpolation_knots(x, k)?
        } else {
            KnotVector::not_a_knot(k, x)?
        };
        return Ok(vec![knots.into_knots()]);
    }
    let data = Data::new(x, y, options.weights, (k, options.s), options.periodic)?;
    options.check_nest()?;
    let bounds = options.bounds(x)?;
    let mut sequence = Vec::new();
    data.generate_knots_with(bounds, options.nest, &mut |t| {
        sequence.push(t.knots().to_vec());
    })?;
    Ok(sequence)
}

#[cfg(test)]
mod tests;
