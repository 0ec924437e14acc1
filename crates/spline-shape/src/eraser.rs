//! The selective eraser of curvature extrema (thesis ch. 6): the planar B-spline curve
//! closest to data points (least squares) whose curvature has only the allowed extrema.
//!
//! With `g = h1 h2 − 3 h3 h4` (`κ′ = g / h1^{5/2}`, thesis (6.10)), the curvature is monotone
//! on a parameter interval where `g` keeps one sign. The curve's knot vector contains the
//! parameters `u*_1 < … < u*_K` of the allowed extrema; they cut the domain into `K + 1`
//! pieces on which the curvature must increase and decrease alternately. Every per-segment
//! Bernstein coefficient of `g` is constrained to the sign of its piece (6.21): by the
//! variation-diminishing property, `g` then keeps that sign on the whole piece and the only
//! possible extrema are the `u*_k` themselves. The quartic constraints and the quadratic
//! least-squares objective go to the interior-point solver of [`crate::barrier`], started from
//! a strictly feasible point found by phase I from the least-squares fit.

use crate::barrier::{BarrierOptions, BarrierProblem, BarrierReport, find_feasible_near, minimize};
use nalgebra::{DVector, Vector2};
use nalgebra_sparse::factorization::CscCholesky;
use nalgebra_sparse::{CooMatrix, CscMatrix, CsrMatrix};
use spline_algebra::{Form, PlanarInvariants, planar_features};
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_fit::{Parametrization, closest_point, nurbs_book_knots, parametrize};
use spline_geom::{BSpline, Curve2};

/// Settings of [`erase_curvature_extrema`].
#[derive(Clone, Debug)]
pub struct EraserOptions {
    /// Degree of the curve (at least 3: the constraints involve `c‴`).
    pub degree: usize,
    /// Number of control points.
    pub control_points: usize,
    /// How many curvature extrema the curve may have.
    pub extrema: usize,
    /// Where they are, as parameters in `(0, 1)` of the chord-length parametrisation of the
    /// data; `None` takes the `extrema` strongest curvature extrema (largest `|κ|`) of the
    /// unconstrained least-squares fit.
    pub extremum_params: Option<Vec<f64>>,
    /// Whether the curvature increases on the first piece; `None` decides from the
    /// least-squares fit (the sign of `κ(u*_1) − κ(0)`).
    pub increasing_first: Option<bool>,
    /// Settings of the interior-point solver.
    pub barrier: BarrierOptions,
}

impl EraserOptions {
    /// Cubic curves with `control_points` control points and `extrema` extrema at automatic
    /// places.
    #[must_use]
    pub fn new(control_points: usize, extrema: usize) -> Self {
        Self {
            degree: 3,
            control_points,
            extrema,
            extremum_params: None,
            increasing_first: None,
            barrier: BarrierOptions {
                gap_tolerance: 1e-9,
                ..BarrierOptions::default()
            },
        }
    }
}

/// The result of [`erase_curvature_extrema`].
#[derive(Clone, Debug)]
pub struct SmoothedCurve {
    /// The constrained curve.
    pub curve: Curve2<f64>,
    /// The unconstrained least-squares curve on the same knots (the starting point).
    pub least_squares: Curve2<f64>,
    /// Chord-length parameters of the data points.
    pub params: Vec<f64>,
    /// The allowed extremum parameters `u*_k` (knots of the curve).
    pub extremum_params: Vec<f64>,
    /// Largest distance from a data point to the curve (closest-point distance).
    pub max_deviation: f64,
    /// Which data point that is.
    pub max_deviation_index: usize,
    /// Root-mean-square closest-point distance.
    pub rms_deviation: f64,
    /// The curvature extrema of the result (a subset of `extremum_params`, up to accuracy).
    pub curvature_extrema: Vec<f64>,
    /// The inflections of the result.
    pub inflections: Vec<f64>,
    /// The curvature extrema of the least-squares fit, for comparison.
    pub least_squares_extrema: Vec<f64>,
    /// Solver statistics.
    pub solver: BarrierReport,
}

/// Fits `points` with a planar B-spline curve whose curvature has exactly the allowed extrema
/// (thesis ch. 6).
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for degree below 3, more extrema than spans, or extremum
/// parameters outside `(0, 1)` or too close together; the errors of the parametrisation and
/// least squares (too few or duplicate points, empty spans); [`ErrorKind::NoConvergence`]
/// when no curve satisfies the constraints (try more control points or other locations).
pub fn erase_curvature_extrema(
    points: &[Vector2<f64>],
    options: &EraserOptions,
) -> Result<SmoothedCurve> {
    let p = options.degree;
    if p < 3 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("the eraser needs degree 3 or more (g involves c‴), got {p}"),
        ));
    }
    let params = parametrize(points, &Parametrization::Chordal)?;
    let base = nurbs_book_knots(p, options.control_points, &params)?;
    let n = options.control_points;
    if options.extrema + 1 > n - p {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{} curvature extrema need at least {} knot spans; {n} control points of degree {p} give {}",
                options.extrema,
                options.extrema + 1,
                n - p
            ),
        ));
    }
    // The least-squares fit on the base knots locates the extrema when they are not given.
    let targets = match &options.extremum_params {
        Some(given) => {
            if given.len() != options.extrema {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    format!(
                        "{} extremum parameters given for {} extrema",
                        given.len(),
                        options.extrema
                    ),
                ));
            }
            let mut v = given.clone();
            v.sort_by(f64::total_cmp);
            v
        }
        None => {
            let (fit, _) = LeastSquaresSystem::new(&base, &params, points)?.solve()?;
            strongest_extrema(&fit, options.extrema)?
        }
    };
    if let Some(&u) = targets.iter().find(|&&u| !(u > 0.0 && u < 1.0)) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("extremum parameter {u} is not inside (0, 1)"),
        ));
    }
    let knots = knots_with(&base, &targets)?;
    let system = LeastSquaresSystem::new(&knots, &params, points)?;
    let (least_squares, x_ls) = system.solve()?;
    let least_squares_extrema = planar_features(&least_squares, 1e-10)
        .map(|f| f.curvature_extrema)
        .unwrap_or_default();
    let increasing_first = match options.increasing_first {
        Some(b) => b,
        None => {
            let k0 = least_squares.signed_curvature(0.0)?;
            let k1 = least_squares.signed_curvature(targets.first().copied().unwrap_or(1.0))?;
            k1 >= k0
        }
    };
    let invariants = PlanarInvariants::new(&knots)?;
    let mut signs = piece_signs(&invariants, &targets, increasing_first);
    // Constraints scaled to order one at the start (a positive factor per constraint does
    // not change the feasible set, but the coefficients of g differ by orders of magnitude
    // between the nose and the flat parts of an airfoil).
    let g0 = invariants.g_value(&to_points(&x_ls), Form::Bernstein)?;
    let largest = g0
        .control_points()
        .iter()
        .fold(0.0f64, |m, g| m.max(g.abs()));
    for (sign, g) in signs.iter_mut().zip(g0.control_points()) {
        *sign /= g.abs().max(1e-3 * largest).max(f64::MIN_POSITIVE);
    }
    let problem = EraserProblem {
        system,
        invariants,
        signs,
    };
    // Phase I: pure at first; if it drifts to a degenerate curve (g → 0 on a curve shrunk to
    // a point, where every constraint tends to zero), again with a growing pull towards the
    // data.
    let f_ls = problem.objective(&x_ls).max(1e-12);
    let mut start = None;
    let mut last_error = None;
    for weight in [0.0, 1e-4, 1e-3, 1e-2] {
        match find_feasible_near(&problem, x_ls.clone(), 0.0, weight / f_ls, &options.barrier) {
            Ok(x) => {
                start = Some(x);
                break;
            }
            Err(e) => last_error = Some(e),
        }
    }
    let start = match (start, last_error) {
        (Some(x), _) => x,
        (None, Some(e)) => return Err(e),
        (None, None) => unreachable!("at least one attempt"),
    };
    let report = minimize(&problem, start, &options.barrier)?;
    let curve = BSpline::new(knots, to_points(&report.x))?;
    let mut max = (0.0, 0);
    let mut sum = 0.0;
    for (k, q) in points.iter().enumerate() {
        let d = closest_point(&curve, *q)?.distance;
        if d > max.0 {
            max = (d, k);
        }
        sum += d * d;
    }
    let features = planar_features(&curve, 1e-10)?;
    Ok(SmoothedCurve {
        rms_deviation: (sum / points.len() as f64).sqrt(),
        max_deviation: max.0,
        max_deviation_index: max.1,
        curvature_extrema: features.curvature_extrema,
        inflections: features.inflections,
        least_squares_extrema,
        extremum_params: targets,
        params,
        least_squares,
        curve,
        solver: report,
    })
}

/// The `count` curvature extrema of `fit` with the largest `|κ|`, in increasing order.
fn strongest_extrema(fit: &Curve2<f64>, count: usize) -> Result<Vec<f64>> {
    let candidates = planar_features(fit, 1e-10)?.curvature_extrema;
    if candidates.len() < count {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the least-squares fit has only {} curvature extrema; give --extremum-at for {count}",
                candidates.len()
            ),
        ));
    }
    let mut scored: Vec<(f64, f64)> = candidates
        .iter()
        .map(|&u| Ok((fit.signed_curvature(u)?.abs(), u)))
        .collect::<Result<_>>()?;
    scored.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut chosen: Vec<f64> = scored.into_iter().take(count).map(|(_, u)| u).collect();
    chosen.sort_by(f64::total_cmp);
    Ok(chosen)
}

/// `base` with each target made a knot: the nearest interior knot moves there (so the number
/// of control points is kept); without interior knots the target is inserted.
fn knots_with(base: &KnotVector<f64>, targets: &[f64]) -> Result<KnotVector<f64>> {
    let p = base.degree();
    let n = base.num_basis();
    let mut interior: Vec<f64> = base.knots()[p + 1..n].to_vec();
    for &u in targets {
        if interior.contains(&u) {
            continue; // already a knot
        }
        let free: Vec<usize> = (0..interior.len())
            .filter(|&i| !targets.contains(&interior[i]))
            .collect();
        match free
            .iter()
            .min_by(|&&i, &&j| (interior[i] - u).abs().total_cmp(&(interior[j] - u).abs()))
        {
            Some(&i) => interior[i] = u,
            None => interior.push(u),
        }
        interior.sort_by(f64::total_cmp);
    }
    if interior.windows(2).any(|w| w[0] == w[1]) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "two extremum parameters fall on the same knot: use more control points",
        ));
    }
    let (a, b) = base.domain();
    KnotVector::clamped(p, a, b, &interior)
}

/// For each per-segment Bernstein coefficient of `g`: `+1` where the curvature must increase
/// (`g > 0`), `−1` where it must decrease.
fn piece_signs(
    invariants: &PlanarInvariants<f64>,
    targets: &[f64],
    increasing_first: bool,
) -> Vec<f64> {
    let space = invariants.g_space(Form::Bernstein);
    let knots = space.knots();
    let q = space.degree();
    (0..space.num_basis())
        .map(|k| {
            // Coefficient k belongs to the segment [knots[k + ...]]; its support starts at
            // knots[k] for the first coefficient of a segment and its span is the one where
            // knots[k + q] < knots[k + q + 1] — any interior point of the support works.
            let lo = knots[k];
            let hi = knots[k + q + 1];
            let mid = 0.5 * (lo + hi);
            let piece = targets.iter().filter(|&&t| t <= mid).count();
            let increasing = increasing_first == (piece % 2 == 0);
            if increasing { 1.0 } else { -1.0 }
        })
        .collect()
}

fn to_points(x: &DVector<f64>) -> Vec<Vector2<f64>> {
    x.as_slice()
        .chunks_exact(2)
        .map(|c| Vector2::new(c[0], c[1]))
        .collect()
}

/// `½‖A X − Q‖²` on interleaved variables `X = [x_1, y_1, …]`.
struct LeastSquaresSystem {
    knots: KnotVector<f64>,
    /// `AᵀA ⊗ I₂`.
    hessian: CsrMatrix<f64>,
    /// `(A ⊗ I₂)ᵀ Q`.
    rhs: DVector<f64>,
    /// `½ QᵀQ`.
    constant: f64,
}

impl LeastSquaresSystem {
    fn new(knots: &KnotVector<f64>, params: &[f64], points: &[Vector2<f64>]) -> Result<Self> {
        let n = knots.num_basis();
        let p = knots.degree();
        let mut coo = CooMatrix::new(2 * n, 2 * n);
        let mut rhs = DVector::zeros(2 * n);
        let mut constant = 0.0;
        let mut basis = vec![0.0; p + 1];
        for (&u, q) in params.iter().zip(points) {
            let span = knots.find_span(u)?;
            knots.basis_values(span, u, &mut basis);
            for (a, &na) in basis.iter().enumerate() {
                let i = span - p + a;
                rhs[2 * i] += na * q.x;
                rhs[2 * i + 1] += na * q.y;
                for (b, &nb) in basis.iter().enumerate() {
                    let j = span - p + b;
                    coo.push(2 * i, 2 * j, na * nb);
                    coo.push(2 * i + 1, 2 * j + 1, na * nb);
                }
            }
            constant += 0.5 * q.norm_squared();
        }
        Ok(Self {
            knots: knots.clone(),
            hessian: CsrMatrix::from(&coo),
            rhs,
            constant,
        })
    }

    /// The unconstrained minimiser.
    fn solve(&self) -> Result<(Curve2<f64>, DVector<f64>)> {
        let csc = CscMatrix::from(&self.hessian);
        let factor = CscCholesky::factor(&csc).map_err(|_| {
            Error::new(
                ErrorKind::SchoenbergWhitney,
                "the least-squares system is singular: some knot span holds too few data points",
            )
        })?;
        let x = factor.solve(&self.rhs);
        let x = DVector::from_column_slice(x.as_slice());
        Ok((BSpline::new(self.knots.clone(), to_points(&x))?, x))
    }
}

struct EraserProblem {
    system: LeastSquaresSystem,
    invariants: PlanarInvariants<f64>,
    /// Positive: the coefficient must be positive; negative: negative. The magnitude scales
    /// the constraint.
    signs: Vec<f64>,
}

impl BarrierProblem for EraserProblem {
    fn dimension(&self) -> usize {
        self.system.rhs.len()
    }
    fn num_constraints(&self) -> usize {
        self.signs.len()
    }
    fn objective(&self, x: &DVector<f64>) -> f64 {
        0.5 * x.dot(&(&self.system.hessian * x)) - self.system.rhs.dot(x) + self.system.constant
    }
    fn objective_gradient(&self, x: &DVector<f64>) -> DVector<f64> {
        &self.system.hessian * x - &self.system.rhs
    }
    fn objective_hessian(&self, _: &DVector<f64>) -> CsrMatrix<f64> {
        self.system.hessian.clone()
    }
    fn constraints(&self, x: &DVector<f64>) -> DVector<f64> {
        match self.invariants.g_value(&to_points(x), Form::Bernstein) {
            Ok(g) => DVector::from_iterator(
                self.signs.len(),
                g.control_points()
                    .iter()
                    .zip(&self.signs)
                    .map(|(gk, s)| -s * gk),
            ),
            Err(_) => DVector::from_element(self.signs.len(), f64::NAN),
        }
    }
    fn constraint_jacobian(&self, x: &DVector<f64>) -> CsrMatrix<f64> {
        let g = self
            .invariants
            .g(&to_points(x), Form::Bernstein)
            .expect("dimensions match");
        let mut jac = g.jacobian;
        for (mut row, &s) in jac.row_iter_mut().zip(&self.signs) {
            for v in row.values_mut() {
                *v *= -s;
            }
        }
        jac
    }
    fn weighted_constraint_hessian(
        &self,
        x: &DVector<f64>,
        weights: &DVector<f64>,
    ) -> Option<CsrMatrix<f64>> {
        let h = self
            .invariants
            .g_hessian(&to_points(x), Form::Bernstein)
            .expect("dimensions match");
        let n = x.len();
        let mut coo = CooMatrix::new(n, n);
        for (k, (&w, &s)) in weights.iter().zip(&self.signs).enumerate() {
            for &(i, j, v) in h.row(k) {
                coo.push(i, j, -s * w * v);
            }
        }
        Some(CsrMatrix::from(&coo))
    }
}
