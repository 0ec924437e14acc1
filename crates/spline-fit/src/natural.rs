//! Natural interpolating splines of even order (seed 004 "Spline naturelle d'interpolation").

use crate::interpolate::{Condition, hermite};
use crate::params::check_degree;
use crate::params::{check_points, check_strict};
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, MAX_DEGREE, Result, Scalar, from_count,
};
use spline_geom::BSpline;

/// The natural cubic spline through $(x_j, y_j)$: $\sigma(x_j) = y_j$ and
/// $\sigma''(x_0) = \sigma''(x_n) = 0$ (seed 004 "Spline naturelle", order `m = 4`), the
/// interpolant that minimises $\int \sigma''^2$ (7.9). Returned on $[x_0, x_n]$ with the
/// knots $x_0$ (×4), $x_1, …, x_{n-1}$, $x_n$ (×4), as scipy's `bc_type="natural"`.
///
/// ```
/// // Data on a straight line: the natural spline is that line.
/// let x = [0.0, 1.0, 3.0, 4.0];
/// let y = [1.0, 3.0, 7.0, 9.0];
/// let s = spline_fit::natural_cubic(&x, &y)?;
/// assert!((s.eval(2.0)? - 5.0f64).abs() < 1e-12);
/// assert!(s.derivatives(0.0, 2)?[2].abs() < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`natural_spline`].
pub fn natural_cubic<T: Scalar, P: ControlPoint<T>>(x: &[T], y: &[P]) -> Result<BSpline<T, P>> {
    natural_spline(x, y, 4)
}

/// The natural spline of even order `m = 2q` (degree `2q − 1`) through $(x_j, y_j)$,
/// `j = 0 … n` (seed 004): it interpolates, its knots are the abscissae, and outside
/// $[x_0, x_n]$ it would continue as polynomials of degree `q − 1`, that is
/// $\sigma^{(k)}(x_0) = \sigma^{(k)}(x_n) = 0$ for `k = q … 2q − 2`. It is the interpolant
/// minimising $\int (\sigma^{(q)})^2$. `m = 2` gives the broken line, `m = 4` the natural
/// cubic spline.
///
/// The result is clamped on $[x_0, x_n]$ with the interior knots $x_1, …, x_{n-1}$ (simple)
/// and `n + 2q − 1` control points; `P = T` gives a function, vector values a curve.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for an odd or zero order; [`ErrorKind::DegreeTooHigh`];
/// [`ErrorKind::InvalidLength`] if `x` and `y` differ in length; [`ErrorKind::TooFewPoints`]
/// with fewer than `max(2, q)` points (the polynomial part of degree `q − 1` would not be
/// determined); [`ErrorKind::UnsortedKnots`] unless `x` increases strictly;
/// [`ErrorKind::NonFinite`]; [`ErrorKind::SingularSystem`].
pub fn natural_spline<T: Scalar, P: ControlPoint<T>>(
    x: &[T],
    y: &[P],
    order: usize,
) -> Result<BSpline<T, P>> {
    if order == 0 || order % 2 == 1 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("natural splines have an even order m = 2q ≥ 2, got {order}"),
        )
        .with_value(from_count(order)));
    }
    if order > MAX_DEGREE + 1 {
        return Err(Error::new(
            ErrorKind::DegreeTooHigh,
            format!(
                "order {order} is above the supported maximum {}",
                MAX_DEGREE + 1
            ),
        ));
    }
    let q = order / 2;
    let p = order - 1;
    check_degree(p)?;
    if x.len() != y.len() {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("{} abscissae for {} ordinates", x.len(), y.len()),
        ));
    }
    check_points(y, 2.max(q), "a natural spline of this order")?;
    check_strict(x)?;
    let n = x.len() - 1;
    let knots_on = |x: &[T]| -> Result<KnotVector<T>> {
        let mut knots = Vec::with_capacity(n + 2 * p + 1);
        knots.extend(std::iter::repeat_n(x[0], p + 1));
        knots.extend_from_slice(&x[1..n]);
        knots.extend(std::iter::repeat_n(x[n], p + 1));
        KnotVector::new(p, knots)
    };
    let knots = knots_on(x)?;
    // The system is solved on abscissae mapped onto [0, 1] and ordinates divided by their
    // largest coordinate: the natural conditions (derivatives of orders q … 2q − 2 vanish at
    // the ends) do not change under these maps, and the coefficients of the spline in x are
    // those in t times the scale. So spacings of 1e-12 or 1e12 and ordinates near the range
    // of floating point solve as well as unit ones.
    let width = x[n] - x[0];
    let t: Vec<T> = x
        .iter()
        .enumerate()
        .map(|(j, &xj)| {
            if j == n {
                T::one()
            } else {
                (xj - x[0]) / width
            }
        })
        .collect();
    if !t.iter().all(|&v| v.is_finite()) || t.windows(2).any(|w| !(w[0] < w[1])) {
        return Err(Error::new(
            ErrorKind::SingularSystem,
            "the abscissae are too close together relative to their range to be told apart",
        ));
    }
    let scale = y.iter().fold(T::zero(), |m, p| m.max(p.max_abs()));
    let scale = if scale > T::zero() { scale } else { T::one() };
    let unit = |p: &P| P::from_coords(|i| p.coord(i) / scale);
    let normalised = knots_on(&t)?;
    let mut conditions = Vec::with_capacity(knots.num_basis());
    let mut targets = Vec::with_capacity(knots.num_basis());
    conditions.push(Condition {
        param: t[0],
        order: 0,
    });
    targets.push(unit(&y[0]));
    for k in q..=2 * q - 2 {
        conditions.push(Condition {
            param: t[0],
            order: k,
        });
        targets.push(P::origin());
    }
    for j in 1..n {
        conditions.push(Condition {
            param: t[j],
            order: 0,
        });
        targets.push(unit(&y[j]));
    }
    for k in (q..=2 * q - 2).rev() {
        conditions.push(Condition {
            param: t[n],
            order: k,
        });
        targets.push(P::origin());
    }
    conditions.push(Condition {
        param: t[n],
        order: 0,
    });
    targets.push(unit(&y[n]));
    let solved = hermite(&normalised, &conditions, targets)?;
    let points: Vec<P> = solved.control_points().iter().map(|&c| c * scale).collect();
    if !points.iter().all(ControlPoint::all_finite) {
        return Err(spline_core::overflow("a coefficient of the natural spline"));
    }
    Ok(BSpline::new_unchecked(knots, points))
}
