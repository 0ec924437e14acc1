//! The parameter-correction algorithm of seed 003 (TD 3, "Algorithme de correction des
//! paramètres").

use crate::bezier::{BezierFit, bezier_control};
use crate::lsq::LeastSquares;
use crate::report::{CurveFit, Deviation};
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, to_f64};
use spline_geom::{BSpline, Bezier};

/// The largest number of correction sweeps (and of step halvings) that
/// [`CorrectionOptions`] may ask for: each sweep projects every point, so the limit bounds
/// the time by the size of the data, and the report holds one angle and one error per sweep.
pub const MAX_CORRECTION_ITERATIONS: usize = 10_000;

/// The stopping rules of [`correct_parameters`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CorrectionOptions<T> {
    /// `L`: the largest number of correction sweeps.
    pub max_iterations: usize,
    /// `ε`: stop when $|\pi/2 - \alpha| < \varepsilon$ (radians), α the largest angle between
    /// a residual and the tangent.
    pub angle_tolerance: T,
    /// How many times step 5 may halve $\Delta C_i$ before leaving $t_i$ unchanged.
    pub max_halvings: usize,
}

impl<T: Scalar> Default for CorrectionOptions<T> {
    /// `L = 20`, `ε = 10⁻³` rad, 30 halvings.
    fn default() -> Self {
        Self {
            max_iterations: 20,
            angle_tolerance: cast(1e-3),
            max_halvings: 30,
        }
    }
}

/// What parameter correction did.
#[derive(Clone, Debug, PartialEq)]
pub struct CorrectionReport<T> {
    /// Correction sweeps performed (`j` at the end).
    pub iterations: usize,
    /// Whether the angle criterion stopped the iteration (otherwise `L` did).
    pub converged: bool,
    /// α after each sweep.
    pub angles: Vec<T>,
    /// The weighted sum of squared distances $\sum_k w_k^2 \lVert D_k \rVert^2$ of the
    /// least-squares fit before the first sweep and after each sweep's refit:
    /// non-increasing.
    pub errors: Vec<T>,
}

impl<T: Scalar> CorrectionReport<T> {
    /// The angle criterion after the last sweep: $\lvert \pi/2 - \alpha \rvert$, how far
    /// the residuals are from normal to the curve; `None` before any sweep.
    ///
    /// ```
    /// use spline_fit::CorrectionReport;
    /// let report = CorrectionReport { iterations: 2, converged: true,
    ///     angles: vec![1.2f64, 1.5707], errors: vec![1.0, 0.5, 0.4] };
    /// assert!((report.angle_error().unwrap() - 9.63267948966e-5).abs() < 1e-15);
    /// ```
    #[must_use]
    pub fn angle_error(&self) -> Option<T> {
        self.angles
            .last()
            .map(|&alpha| (T::frac_pi_2() - alpha).abs())
    }
}

/// Evaluates a fitted curve: point and first derivative at a parameter.
type Evaluator<'a, T, P, C> = &'a dyn Fn(&C, T) -> Result<(P, P)>;

/// Runs the algorithm on an abstract fitter: `fit(params, curve)` fits `curve` (a container
/// of the right size) to the parameters, `eval` evaluates the point and first
/// derivative, `(a, b)` is the parameter interval. Nothing is allocated per sweep beyond
/// what `fit` allocates (the report's vectors are sized for `L` sweeps up front).
#[allow(clippy::too_many_arguments)]
fn run<T: Scalar, P: ControlPoint<T>, C>(
    points: &[P],
    params: &mut [T],
    weights: Option<&[T]>,
    (a, b): (T, T),
    options: &CorrectionOptions<T>,
    mut curve: C,
    fit: &mut dyn FnMut(&[T], &mut C) -> Result<()>,
    eval: Evaluator<'_, T, P, C>,
) -> Result<(C, CorrectionReport<T>)> {
    // 1. μ: length of the polygon {P_k}.
    let mu = points
        .windows(2)
        .fold(T::zero(), |s, w| s + (w[1] - w[0]).length());
    if !(mu > T::zero()) {
        return Err(Error::new(
            ErrorKind::DegenerateGeometry,
            "parameter correction needs points that are not all equal",
        ));
    }
    let scale = (b - a) / mu;
    let half: T = cast(0.5);
    let half_pi = T::frac_pi_2();
    let error_of = |curve: &C, params: &[T]| -> Result<T> {
        let mut s = T::zero();
        for (k, (&t, q)) in params.iter().zip(points).enumerate() {
            let w = weights.map_or_else(T::one, |w| w[k]);
            let d = (*q - eval(curve, t)?.0).length();
            s += w * w * d * d;
        }
        Ok(s)
    };
    let mut report = CorrectionReport {
        iterations: 0,
        converged: false,
        angles: Vec::with_capacity(options.max_iterations),
        errors: Vec::with_capacity(options.max_iterations + 1),
    };
    // 2. The least-squares curve for the current parameters.
    fit(params, &mut curve)?;
    report.errors.push(error_of(&curve, params)?);
    let last = params.len() - 1;
    while report.iterations < options.max_iterations {
        let mut alpha = T::zero();
        // 3. FOR i = 0 TO N.
        for i in 0..=last {
            let (x, dx) = eval(&curve, params[i])?;
            let d = points[i] - x;
            let d_norm = d.length();
            let speed = dx.length();
            let lo = if i == 0 { a } else { params[i - 1] };
            let hi = if i == last { b } else { params[i + 1] };
            let mut accepted = None;
            if speed > T::zero() && d_norm > T::zero() {
                // 4. ΔC_i = <D_i, x'(t_i)> / ‖x'(t_i)‖.
                let mut delta = d.dot(&dx) / speed;
                for _ in 0..=options.max_halvings {
                    // 5. t* = t_i + ΔC_i (b − a)/μ, kept in [a, b] and in order.
                    let t = params[i] + delta * scale;
                    if t >= lo && t <= hi && t != params[i] {
                        let (xs, dxs) = eval(&curve, t)?;
                        let ds = points[i] - xs;
                        if d_norm > ds.length() {
                            accepted = Some((t, ds, dxs));
                            break;
                        }
                    }
                    delta *= half;
                }
            }
            // 6. α_i = arccos(<D*_i, x'(t*_i)> / (‖D*_i‖ ‖x'(t*_i)‖)), at the kept parameter.
            let (ds, dxs) = match accepted {
                Some((t, ds, dxs)) => {
                    params[i] = t;
                    (ds, dxs)
                }
                None => (d, dx),
            };
            let denom = ds.length() * dxs.length();
            let alpha_i = if denom > T::zero() {
                (ds.dot(&dxs) / denom).max(-T::one()).min(T::one()).acos()
            } else {
                // The point lies on the curve (or the curve stops): nothing to correct.
                half_pi
            };
            alpha = alpha.max(alpha_i);
        }
        // 7. α = max α_i, j = j + 1, refit, test |π/2 − α| < ε.
        report.iterations += 1;
        report.angles.push(alpha);
        fit(params, &mut curve)?;
        report.errors.push(error_of(&curve, params)?);
        if (half_pi - alpha).abs() < options.angle_tolerance {
            report.converged = true;
            break;
        }
    }
    Ok((curve, report))
}

/// A curve evaluated before its first fit (an internal invariant: [`run`] fits first).
fn not_fitted() -> Error {
    Error::new(ErrorKind::InvalidArgument, "the curve was not fitted")
}

fn check_inputs<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    params: &[T],
    options: &CorrectionOptions<T>,
) -> Result<()> {
    if points.len() != params.len() || points.len() < 2 {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "parameter correction needs one parameter per point and at least two points, got {} parameters for {} points",
                params.len(),
                points.len()
            ),
        ));
    }
    if options.max_iterations > MAX_CORRECTION_ITERATIONS {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{} correction sweeps are more than the supported maximum {MAX_CORRECTION_ITERATIONS}",
                options.max_iterations
            ),
        )
        .with_counts(MAX_CORRECTION_ITERATIONS, options.max_iterations));
    }
    if options.max_halvings > MAX_CORRECTION_ITERATIONS {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{} halvings are more than the supported maximum {MAX_CORRECTION_ITERATIONS}",
                options.max_halvings
            ),
        )
        .with_counts(MAX_CORRECTION_ITERATIONS, options.max_halvings));
    }
    if !(options.angle_tolerance > T::zero()) {
        return Err(Error::new(
            ErrorKind::InvalidTolerance,
            format!(
                "the angle tolerance must be positive, got {}",
                to_f64(options.angle_tolerance)
            ),
        )
        .with_value(to_f64(options.angle_tolerance))
        .with_interval(0.0, f64::INFINITY));
    }
    Ok(())
}

/// Least squares with parameter correction (seed 003, implemented as written): starting from
/// `problem`'s parameters, repeat — fit the least-squares curve `x`; for each point,
/// $\Delta C_i = \langle D_i, x'(t_i)\rangle / \lVert x'(t_i)\rVert$ with
/// $D_i = P_i - x(t_i)$, try $t_i^* = t_i + \Delta C_i (b-a)/\mu$ (μ the length of the data
/// polygon), halving $\Delta C_i$ until $\lVert D_i^* \rVert < \lVert D_i \rVert$ with
/// $t_i^*$ in `[a, b]` and between its neighbours (the parameters stay ordered), then take
/// the angle $\alpha_i$ between $D_i^*$ and $x'(t_i^*)$ — until
/// $|\pi/2 - \max_i \alpha_i| < \varepsilon$ or `L` sweeps. The curve is refitted after
/// the last sweep. A point whose step cannot be improved within `max_halvings` halvings
/// keeps its parameter.
///
/// Each sweep lowers every $\lVert D_i \rVert$ for the current curve and the refit can
/// only lower the sum further, so the errors in the report never increase.
///
/// `problem` carries the knots, weights, constraints and method of each refit; its
/// parameters are the starting values.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::{CorrectionOptions, LeastSquares, correct_parameters, nurbs_book_knots};
/// let points: Vec<Vector2<f64>> = (0..=30)
///     .map(|k| { let t = k as f64 / 30.0 * 3.0; Vector2::new(t, t.sin()) })
///     .collect();
/// let params: Vec<f64> = (0..=30).map(|k| k as f64 / 30.0).collect();
/// let knots = nurbs_book_knots(3, 6, &params)?;
/// let (fit, report) = correct_parameters(
///     &LeastSquares::new(&points, &params, knots),
///     &CorrectionOptions::default(),
/// )?;
/// assert!(report.errors.windows(2).all(|e| e[1] <= e[0]));
/// assert!(fit.deviation.max < 1e-2);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidLength`] with fewer than two points; [`ErrorKind::InvalidTolerance`]
/// for a non-positive angle tolerance; [`ErrorKind::InvalidArgument`] for more than
/// [`MAX_CORRECTION_ITERATIONS`] sweeps or halvings (with `(maximum, asked)` as
/// [`spline_core::Error::counts`]); [`ErrorKind::DegenerateGeometry`] when all points
/// coincide; the errors of [`LeastSquares::solve`] at any refit.
pub fn correct_parameters<T: Scalar, P: ControlPoint<T>>(
    problem: &LeastSquares<'_, T, P>,
    options: &CorrectionOptions<T>,
) -> Result<(CurveFit<T, P>, CorrectionReport<T>)> {
    let points = problem.points_ref();
    let mut params = problem.params_ref().to_vec();
    check_inputs(points, &params, options)?;
    let knots: KnotVector<T> = problem.knots_ref().clone();
    let domain = knots.domain();
    // Each refit writes the control points of the one curve through a reused workspace
    // (the plain problem; others refit as a new least-squares problem).
    let mut workspace = None;
    let mut fit = |params: &[T], curve: &mut BSpline<T, P>| -> Result<()> {
        if !problem.control_points_into(params, &mut workspace, curve.control_points_mut())? {
            let control = problem.with_params(params).control_points()?;
            curve.control_points_mut().copy_from_slice(&control);
        }
        Ok(())
    };
    let curve = BSpline::new_unchecked(knots.clone(), vec![P::origin(); knots.num_basis()]);
    let eval = |curve: &BSpline<T, P>, t: T| -> Result<(P, P)> {
        let mut out = [P::origin(); 2];
        curve.derivatives_into(t, &mut out)?;
        Ok((out[0], out[1]))
    };
    let (curve, report) = run(
        points,
        &mut params,
        problem.weights_ref(),
        domain,
        options,
        curve,
        &mut fit,
        &eval,
    )?;
    Ok((CurveFit::new(curve, params, points)?, report))
}

/// A Bézier curve and its hodograph.
type WithHodograph<T, P> = (Bezier<T, P>, Bezier<T, P>);

/// Parameter correction for the Bézier least squares of seed 003 TD3: as
/// [`correct_parameters`], each refit by [`crate::bezier_least_squares`] of degree `degree`
/// on `[a, b]` from the starting `params` (non-decreasing, in `[a, b]`).
///
/// # Errors
/// As [`correct_parameters`] and [`crate::bezier_least_squares`].
pub fn correct_parameters_bezier<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    params: &[T],
    degree: usize,
    interval: (T, T),
    options: &CorrectionOptions<T>,
) -> Result<(BezierFit<T, P>, CorrectionReport<T>)> {
    let start = params;
    let mut params = start.to_vec();
    check_inputs(points, &params, options)?;
    // Each refit writes the control points through a reused least-squares workspace into
    // the curve, and the hodograph in place: no allocation per sweep.
    let knots = KnotVector::bezier(degree, interval.0, interval.1)?;
    let problem = LeastSquares::new(points, start, knots);
    let mut workspace = None;
    let mut control = vec![P::origin(); degree + 1];
    let mut fit = |params: &[T], curve: &mut Option<WithHodograph<T, P>>| -> Result<()> {
        if !problem.control_points_into(params, &mut workspace, &mut control)? {
            control = bezier_control(points, params, degree, interval, None)?;
        }
        match curve {
            // (Non-finite control points go the other way, whose check reports them.)
            Some((bezier, hodograph)) if control.iter().all(ControlPoint::all_finite) => {
                bezier.control_points_mut().copy_from_slice(&control);
                bezier.derivative_into(hodograph);
            }
            _ => {
                let bezier = Bezier::with_interval(control.clone(), interval.0, interval.1)?;
                let hodograph = bezier.derivative();
                *curve = Some((bezier, hodograph));
            }
        }
        Ok(())
    };
    let eval = |curve: &Option<WithHodograph<T, P>>, t: T| -> Result<(P, P)> {
        let (curve, hodograph) = curve.as_ref().ok_or_else(not_fitted)?;
        Ok((curve.eval(t)?, hodograph.eval(t)?))
    };
    let (curve, report) = run(
        points,
        &mut params,
        None,
        interval,
        options,
        None,
        &mut fit,
        &eval,
    )?;
    let (curve, _) = curve.ok_or_else(not_fitted)?;
    let distances = params
        .iter()
        .zip(points)
        .map(|(&t, q)| Ok((curve.eval(t)? - *q).length()))
        .collect::<Result<Vec<T>>>()?;
    Ok((
        BezierFit {
            curve,
            params,
            deviation: Deviation::from_distances(distances),
        },
        report,
    ))
}
