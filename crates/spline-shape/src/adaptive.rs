//! Shape optimisation coupled with an adaptation of the parametrisation (seed 000 §3, after
//! Clarich & Désidéri): find the arc from `(0, 0)` to `(1, 0)`, vertical at `(0, 0)`, that
//! minimises $J = \mathcal P^2 / \mathcal A$ (perimeter squared over the area under it). The
//! minimiser is the upper half of the circle of centre `(½, 0)` and radius `½`, `J = 2π`.
//!
//! Each iteration (seed 000 §3.3–3.4):
//! 1. **adapt the parametrisation**: least squares through `N + 1` points of the current shape
//!    with chord-length parameters, averaging knots and the fixed coordinates
//!    `x_0 = x_1 = y_0 = y_n = 0`, `x_n = 1` (so the curve starts vertically at the origin and
//!    ends at `(1, 0)`), giving a regular control polygon for the same shape;
//! 2. **optimise**: with the abscissae of the control points frozen, minimise `J` over the
//!    free ordinates `y_1 … y_{n−1}` by the Nelder–Mead simplex method (derivative free);
//! 3. sample the optimised curve at its `N + 1` parameters for the next adaptation.
//!
//! `𝒫` is the adaptive arc length; `𝒜 = ∫ y x′ dt` is integrated exactly by Gauss–Legendre
//! quadrature on every knot span (`y x′` is a polynomial of degree `2d − 1` there).

use argmin::core::{CostFunction, Executor};
use argmin::solver::neldermead::NelderMead;
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, KnotVector, Result, gauss_legendre};
use spline_fit::{LeastSquares, Parametrization, parametrize};
use spline_geom::{BSpline, Curve2};

/// Settings of [`optimise_perimeter_over_area`].
#[derive(Clone, Debug)]
pub struct AdaptiveOptions {
    /// Degree `d` of the curve.
    pub degree: usize,
    /// Number of control points `n + 1`.
    pub control_points: usize,
    /// Number of sample points `N + 1` of each adaptation of the parametrisation.
    pub samples: usize,
    /// Number of outer iterations (adaptation + optimisation).
    pub iterations: usize,
    /// Nelder–Mead stops when the standard deviation of the simplex's costs is below this.
    pub simplex_tolerance: f64,
    /// Largest number of Nelder–Mead iterations per optimisation.
    pub max_simplex_iterations: u64,
    /// Absolute accuracy of the perimeter.
    pub arc_length_accuracy: f64,
}

impl Default for AdaptiveOptions {
    /// The setting of seed 000 Table 1: `n = 10`, `d = 3`, `N = 10`, eight iterations.
    fn default() -> Self {
        Self {
            degree: 3,
            control_points: 11,
            samples: 11,
            iterations: 8,
            simplex_tolerance: 1e-12,
            max_simplex_iterations: 20_000,
            arc_length_accuracy: 1e-12,
        }
    }
}

/// One iteration of [`optimise_perimeter_over_area`].
#[derive(Clone, Debug)]
pub struct AdaptiveIteration {
    /// The curve after the optimisation step.
    pub curve: Curve2<f64>,
    /// `J = 𝒫² / 𝒜` of that curve.
    pub criterion: f64,
    /// Its perimeter `𝒫`.
    pub perimeter: f64,
    /// The area `𝒜` under it.
    pub area: f64,
    /// Nelder–Mead iterations used.
    pub simplex_iterations: u64,
}

/// The perimeter $\mathcal P = \int \lVert c'\rVert$, the area $\mathcal A = \int y\\,x'\\,dt$
/// and $J = \mathcal P^2 / \mathcal A$ of a planar curve.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::BSpline;
/// // y = 4x(1 − x) as a quadratic Bézier curve: area 2/3.
/// let arch = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(0.0, 0.0), Vector2::new(0.5, 2.0), Vector2::new(1.0, 0.0)])?;
/// let (_, _, area) = spline_shape::perimeter_squared_over_area(&arch, 1e-12)?;
/// assert!((area - 2.0 / 3.0).abs() < 1e-14);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::DegenerateGeometry`] if the area is not positive; the errors of the arc length.
pub fn perimeter_squared_over_area(curve: &Curve2<f64>, accuracy: f64) -> Result<(f64, f64, f64)> {
    let perimeter = curve.arc_length(accuracy)?;
    let rule = gauss_legendre::<f64>(curve.degree().max(1));
    let breaks = curve.knots().domain_breaks();
    let mut area = 0.0;
    let mut ders = [Vector2::zeros(); 2];
    for w in breaks.windows(2) {
        let (half, mid) = (0.5 * (w[1] - w[0]), 0.5 * (w[0] + w[1]));
        for &(x, weight) in &rule {
            curve.derivatives_into(mid + half * x, &mut ders)?;
            area += weight * half * ders[0].y * ders[1].x;
        }
    }
    if !(area > 0.0) {
        return Err(Error::new(
            ErrorKind::DegenerateGeometry,
            format!("the area under the curve is not positive ({area:.3e})"),
        ));
    }
    Ok((perimeter * perimeter / area, perimeter, area))
}

/// Least squares through `points` (chord-length parameters, averaging knots) with the fixed
/// coordinates of seed 000 §3.3.
fn adapt(points: &[Vector2<f64>], options: &AdaptiveOptions) -> Result<(Curve2<f64>, Vec<f64>)> {
    let params = parametrize(points, &Parametrization::Chordal)?;
    let knots = averaging_knots(options.degree, options.control_points, &params)?;
    let n = options.control_points - 1;
    let fit = LeastSquares::new(points, &params, knots)
        .fix_coordinate(0, 0, 0.0)
        .fix_coordinate(1, 0, 0.0)
        .fix_coordinate(0, 1, 0.0)
        .fix_coordinate(n, 1, 0.0)
        .fix_coordinate(n, 0, 1.0)
        .solve()?;
    Ok((fit.curve, params))
}

/// Clamped knots on `[0, 1]` for `count` control points, interior knots averaging the
/// parameters `t` (seed 000 §3.3, in the form of seed 004 (7.6) for `count ≤ N + 1`).
fn averaging_knots(degree: usize, count: usize, params: &[f64]) -> Result<KnotVector<f64>> {
    if count == params.len() {
        return KnotVector::averaging(degree, params);
    }
    spline_fit::nurbs_book_knots(degree, count, params)
}

struct Criterion<'a> {
    template: &'a Curve2<f64>,
    accuracy: f64,
}

impl Criterion<'_> {
    fn curve(&self, free: &[f64]) -> Curve2<f64> {
        let mut points = self.template.control_points().to_vec();
        let last = points.len() - 1;
        for (p, &y) in points[1..last].iter_mut().zip(free) {
            p.y = y;
        }
        BSpline::new_unchecked(self.template.knots().clone(), points)
    }
}

impl CostFunction for Criterion<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, free: &Vec<f64>) -> std::result::Result<f64, argmin::core::Error> {
        // Shapes with no area (or a loop below the axis) are simply very bad.
        Ok(
            perimeter_squared_over_area(&self.curve(free), self.accuracy)
                .map_or(1e300, |(j, _, _)| j),
        )
    }
}

/// The largest number of outer iterations [`optimise_perimeter_over_area`] takes.
pub const MAX_ADAPTIVE_ITERATIONS: usize = 1000;
/// The largest number of samples of one adaptation.
pub const MAX_ADAPTIVE_SAMPLES: usize = 100_000;
/// The largest number of control points.
pub const MAX_ADAPTIVE_CONTROL_POINTS: usize = 1000;
/// The largest number of Nelder–Mead iterations of one optimisation.
pub const MAX_SIMPLEX_ITERATIONS: u64 = 10_000_000;

/// The initial shape when none is given: 41 points of the upper half of the ellipse through
/// `(0, 0)` and `(1, 0)` with semi-axes 0.5 and 0.3 (the last point exactly `(1, 0)`).
///
/// ```
/// let shape = spline_shape::default_initial_shape();
/// assert_eq!(shape.len(), 41);
/// assert_eq!((shape[0].x, shape[0].y, shape[40].x, shape[40].y), (0.0, 0.0, 1.0, 0.0));
/// assert!((shape[20].y - 0.3).abs() < 1e-15);
/// ```
#[must_use]
pub fn default_initial_shape() -> Vec<Vector2<f64>> {
    (0..41)
        .map(|i| {
            let t = std::f64::consts::PI * f64::from(i) / 40.0;
            if i == 40 {
                Vector2::new(1.0, 0.0)
            } else {
                Vector2::new(0.5 - 0.5 * t.cos(), 0.3 * t.sin())
            }
        })
        .collect()
}

/// Runs the coupled optimisation from an initial shape given by points from `(0, 0)` to
/// `(1, 0)` (at least `control_points` of them), and returns every iteration.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for 0 iterations or more than [`MAX_ADAPTIVE_ITERATIONS`]
/// (the value and the range as fields), more than [`MAX_ADAPTIVE_SAMPLES`] samples,
/// [`MAX_ADAPTIVE_CONTROL_POINTS`] control points or [`MAX_SIMPLEX_ITERATIONS`] simplex
/// iterations; for degree 0, fewer samples than control points, fewer
/// than `degree + 2` control points (the two counts of the failed inequality as
/// [`Error::counts`]), or data that do not start at `(0, 0)` and end at `(1, 0)`;
/// [`ErrorKind::InvalidTolerance`] for a negative `simplex_tolerance`; the errors of the
/// least-squares fits; [`ErrorKind::NoConvergence`] if Nelder–Mead fails.
pub fn optimise_perimeter_over_area(
    initial: &[Vector2<f64>],
    options: &AdaptiveOptions,
) -> Result<Vec<AdaptiveIteration>> {
    if options.iterations == 0 || options.iterations > MAX_ADAPTIVE_ITERATIONS {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "iterations must be 1 to {MAX_ADAPTIVE_ITERATIONS}, got {}",
                options.iterations
            ),
        )
        .with_value(options.iterations as f64)
        .with_interval(1.0, MAX_ADAPTIVE_ITERATIONS as f64));
    }
    if options.samples > MAX_ADAPTIVE_SAMPLES
        || options.control_points > MAX_ADAPTIVE_CONTROL_POINTS
        || options.max_simplex_iterations > MAX_SIMPLEX_ITERATIONS
    {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "at most {MAX_ADAPTIVE_SAMPLES} samples, {MAX_ADAPTIVE_CONTROL_POINTS} control points and {MAX_SIMPLEX_ITERATIONS} simplex iterations"
            ),
        ));
    }
    let d = options.degree;
    if d == 0 {
        // A piecewise-constant curve jumps between its values: it has no tangent, no
        // perimeter as a continuous curve and no area under it (refused before any work).
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "degree must be at least 1: a piecewise-constant curve encloses no area",
        )
        .with_value(0.0)
        .with_interval(1.0, f64::INFINITY));
    }
    if options.control_points < d + 2 || options.samples < options.control_points {
        // The counts of the first inequality that fails.
        let (expected, found) = if options.control_points < d + 2 {
            (d + 2, options.control_points)
        } else {
            (options.control_points, options.samples)
        };
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "need degree + 2 ≤ control points ≤ samples, got degree {d}, {} control points, {} samples",
                options.control_points, options.samples
            ),
        )
        .with_counts(expected, found));
    }
    let ends_ok = |p: Option<&Vector2<f64>>, x: f64| {
        p.is_some_and(|p| (p - Vector2::new(x, 0.0)).norm() < 1e-9)
    };
    if !ends_ok(initial.first(), 0.0) || !ends_ok(initial.last(), 1.0) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "the initial shape must run from (0, 0) to (1, 0)",
        ));
    }
    let (mut curve, _) = adapt(initial, options)?;
    let mut samples: Vec<Vector2<f64>> = curve.eval_many(&uniform(options.samples))?;
    let mut history = Vec::with_capacity(options.iterations);
    for _ in 0..options.iterations {
        let (adapted, params) = adapt(&samples, options)?;
        let criterion = Criterion {
            template: &adapted,
            accuracy: options.arc_length_accuracy,
        };
        let start: Vec<f64> = adapted.control_points()[1..options.control_points - 1]
            .iter()
            .map(|p| p.y)
            .collect();
        let scale = start.iter().fold(0.0f64, |m, y| m.max(y.abs())).max(1e-3);
        let mut simplex = vec![start.clone()];
        for i in 0..start.len() {
            let mut vertex = start.clone();
            vertex[i] += 0.05 * scale;
            simplex.push(vertex);
        }
        let solver = NelderMead::new(simplex)
            .with_sd_tolerance(options.simplex_tolerance)
            .map_err(|e| {
                // Nelder–Mead refuses only a negative standard-deviation tolerance.
                Error::new(ErrorKind::InvalidTolerance, e.to_string())
                    .with_value(options.simplex_tolerance)
                    .with_interval(0.0, f64::INFINITY)
            })?;
        let result = Executor::new(criterion, solver)
            .configure(|state| state.max_iters(options.max_simplex_iterations))
            .run()
            .map_err(|e| {
                Error::new(ErrorKind::NoConvergence, format!("Nelder–Mead failed: {e}"))
            })?;
        let best =
            result.state.best_param.clone().ok_or_else(|| {
                Error::new(ErrorKind::NoConvergence, "Nelder–Mead returned no point")
            })?;
        let criterion = Criterion {
            template: &adapted,
            accuracy: options.arc_length_accuracy,
        };
        curve = criterion.curve(&best);
        let (j, perimeter, area) =
            perimeter_squared_over_area(&curve, options.arc_length_accuracy)?;
        history.push(AdaptiveIteration {
            curve: curve.clone(),
            criterion: j,
            perimeter,
            area,
            simplex_iterations: result.state.iter,
        });
        samples = curve.eval_many(&params)?;
    }
    Ok(history)
}

fn uniform(count: usize) -> Vec<f64> {
    (0..count)
        .map(|i| {
            if i + 1 == count {
                1.0
            } else {
                i as f64 / (count - 1) as f64
            }
        })
        .collect()
}
