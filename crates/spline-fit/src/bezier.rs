//! Bézier interpolation and least squares (seed 003 TD2 and TD3); with parameter correction
//! as a front end asks for it in `bezier_request.rs` ([`crate::fit_bezier_least_squares`]).

use crate::interpolate::interpolate_with_knots;
use crate::lsq::LeastSquares;
use crate::params::{Parametrization, check_points, parametrize};
use crate::params::{check_degree, map_to_domain};
use crate::report::Deviation;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar};
use spline_geom::Bezier;

/// A fitted Bézier curve with the parameters of the data and its deviation from them.
#[derive(Clone, Debug, PartialEq)]
pub struct BezierFit<T, P> {
    /// The curve, on the interval `[a, b]` of the fit.
    pub curve: Bezier<T, P>,
    /// The parameter of each data point.
    pub params: Vec<T>,
    /// The distances of the data from the curve at those parameters.
    pub deviation: Deviation<T>,
}

fn params_on<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    parametrization: &Parametrization<T>,
    (a, b): (T, T),
) -> Result<Vec<T>> {
    if !(a.is_finite() && b.is_finite() && a < b) {
        return Err(Error::new(
            ErrorKind::EmptyDomain,
            "the parameter interval [a, b] must be finite with a < b",
        ));
    }
    let mut params = parametrize(points, parametrization)?;
    if !matches!(parametrization, Parametrization::Given(_)) {
        map_to_domain(&mut params, (a, b));
    }
    Ok(params)
}

fn finish<T: Scalar, P: ControlPoint<T>>(
    control: Vec<P>,
    (a, b): (T, T),
    params: Vec<T>,
    points: &[P],
) -> Result<BezierFit<T, P>> {
    let curve = Bezier::with_interval(control, a, b)?;
    let distances = params
        .iter()
        .zip(points)
        .map(|(&t, q)| Ok((curve.eval(t)? - *q).length()))
        .collect::<Result<Vec<T>>>()?;
    Ok(BezierFit {
        curve,
        params,
        deviation: Deviation::from_distances(distances),
    })
}

/// The Bézier curve of degree `n` through the `n + 1` points $P_i$ at parameters $t_i$ of
/// `[a, b]` (seed 003 TD2): $x(t_i) = P_i$ with $x(t) = \sum_i b_i B_i^n((t-a)/(b-a))$.
///
/// Uniform ("équidistante") parameters are $t_i = a + \frac{i}{n}(b - a)$ (the TD's
/// $\frac{i}{n+1}$, `i = 0 … n + 1`, counts one point too many); chordal parameters are
/// proportional to the distances between the points. On the same points the two curves
/// differ: with uneven spacing uniform parameters give loops and overshoots where chordal
/// ones follow the polygon (see the tests). The Bernstein collocation matrix is totally
/// positive for increasing parameters and is solved without pivoting.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::{Parametrization, bezier_interpolate};
/// let p = [Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(3.0, 1.0)];
/// let fit = bezier_interpolate(&p, &Parametrization::Chordal, (0.0, 1.0))?;
/// assert_eq!(fit.curve.degree(), 2);
/// assert!(fit.deviation.max < 1e-14);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] with fewer than two points; [`ErrorKind::DegreeTooHigh`]
/// above [`spline_core::MAX_DEGREE`]` + 1` points; [`ErrorKind::EmptyDomain`] unless
/// `a < b`; the parametrisation errors of [`parametrize`]; [`ErrorKind::UnsortedKnots`] for
/// given parameters that do not increase strictly; [`ErrorKind::OutOfDomain`];
/// [`ErrorKind::SingularSystem`].
pub fn bezier_interpolate<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    parametrization: &Parametrization<T>,
    interval: (T, T),
) -> Result<BezierFit<T, P>> {
    check_points(points, 2, "Bézier interpolation")?;
    let degree = points.len() - 1;
    check_degree(degree)?;
    let params = params_on(points, parametrization, interval)?;
    let knots = KnotVector::bezier(degree, interval.0, interval.1)?;
    let curve = interpolate_with_knots(&knots, &params, points)?;
    let (_, control) = curve.into_parts();
    finish(control, interval, params, points)
}

/// The Bézier curve of degree `n` on `[a, b]` closest in the least-squares sense to the
/// `N + 1` points (seed 003 TD3): $\sum_k w_k^2 \lVert P_k - x(t_k) \rVert^2 \to \min$
/// (unit weights when `weights` is `None`), by the normal equations of the Bernstein basis.
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] with `N < n`; the errors of [`bezier_interpolate`] and of
/// [`LeastSquares::solve`].
pub fn bezier_least_squares<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    degree: usize,
    parametrization: &Parametrization<T>,
    interval: (T, T),
    weights: Option<&[T]>,
) -> Result<BezierFit<T, P>> {
    let params = least_squares_params(points, degree, parametrization, interval)?;
    let control = bezier_control(points, &params, degree, interval, weights)?;
    finish(control, interval, params, points)
}

/// The checks of a Bézier least-squares fit of degree `degree` and the data's parameters on
/// `interval`.
pub(crate) fn least_squares_params<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    degree: usize,
    parametrization: &Parametrization<T>,
    interval: (T, T),
) -> Result<Vec<T>> {
    check_degree(degree)?;
    check_points(points, (degree + 1).max(2), "a Bézier fit of this degree")?;
    params_on(points, parametrization, interval)
}

pub(crate) fn bezier_control<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    params: &[T],
    degree: usize,
    interval: (T, T),
    weights: Option<&[T]>,
) -> Result<Vec<P>> {
    let knots = KnotVector::bezier(degree, interval.0, interval.1)?;
    let mut problem = LeastSquares::new(points, params, knots);
    if let Some(w) = weights {
        problem = problem.weights(w);
    }
    problem.control_points()
}
