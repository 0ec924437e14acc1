//! The penalised least-squares spline (scipy's `make_smoothing_spline`): the smoothing
//! weight given or chosen by generalised cross-validation.

use super::band_inverse::inverse_band;
use crate::banded::BandCholesky;
use crate::lsq::{LeastSquares, penalty_rows};
use crate::natural::natural_cubic;
use crate::params::{
    Parametrization, check_non_negative, check_points, check_weights, parametrize,
};
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, from_count, to_f64};
use spline_geom::BSpline;

/// How the weight $\lambda$ of the roughness penalty is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SmoothingParameter<T> {
    /// A given $\lambda \ge 0$ (`0` gives the natural interpolating spline).
    Lambda(T),
    /// The minimiser of the generalised cross-validation score over $[0, n]$ (`n` data),
    /// found as scipy does: Brent's bounded search (`minimize_scalar(method="Bounded")`,
    /// absolute tolerance `1e-5` in $\lambda$), so that the same data give the same
    /// $\lambda$.
    Gcv,
}

/// A smoothing spline and how it was chosen.
#[derive(Clone, Debug, PartialEq)]
pub struct SmoothingFit<T, P> {
    /// The cubic spline: knots at the abscissae (the first and last four times).
    pub spline: BSpline<T, P>,
    /// The weight $\lambda$ of the penalty.
    pub lambda: T,
    /// The generalised cross-validation score
    /// $V(\lambda) = \frac{\frac1n \sum_i \lVert y_i - f(x_i) \rVert^2}{(1 - \operatorname{tr} H / n)^2}$
    /// at $\lambda$ (scipy's numerator: residuals not weighted); infinite where
    /// $\operatorname{tr} H = n$ (the interpolating spline, $\lambda = 0$ excepted: `0`).
    pub gcv: T,
    /// The trace of the influence matrix $H$ (the effective number of parameters).
    pub trace: T,
    /// The weighted residual $\sum_i w_i \lVert y_i - f(x_i) \rVert^2$.
    pub residual: T,
}

/// The smoothing spline of scipy's `make_smoothing_spline`: the cubic spline $f$ with
/// knots at the abscissae that minimises
///
/// $$ \sum_{i} w_i \lVert y_i - f(x_i) \rVert^2 + \lambda \int_{x_0}^{x_{n-1}} \lVert f''(u) \rVert^2 du $$
///
/// (weights not squared, as scipy's), with $\lambda$ given or chosen by generalised
/// cross-validation ([`SmoothingParameter::Gcv`]). The minimiser over all `C²` functions is
/// this natural cubic spline; it is computed in the B-spline basis of the knots
/// $x_0$ (×4), $x_1, …, x_{n-2}$, $x_{n-1}$ (×4) from the banded normal equations
/// $(B^T W B + \lambda \Omega) c = B^T W y$ (Cholesky, `O(n)`); the trace of the influence
/// matrix $B (B^T W B + \lambda \Omega)^{-1} B^T W$ comes from the band of the inverse
/// (Hutchinson and de Hoog 1985), also `O(n)` per value of $\lambda$.
///
/// `P = T` gives a function; vector values a function into $\mathbb{R}^D$ with one
/// $\lambda$ for all coordinates (the score sums their residuals; scipy would choose one
/// $\lambda$ per coordinate). For a parametric curve through points see
/// [`smoothing_curve`].
///
/// ```
/// use spline_fit::{SmoothingParameter, smoothing_spline};
/// let x: Vec<f64> = (0..40).map(|i| f64::from(i) / 39.0).collect();
/// let y: Vec<f64> = x.iter().enumerate()
///     .map(|(i, t)| (6.0 * t).sin() + if i % 2 == 0 { 0.05 } else { -0.05 })
///     .collect();
/// let fit = smoothing_spline(&x, &y, None, SmoothingParameter::Gcv)?;
/// assert!(fit.lambda > 0.0 && fit.trace < 40.0);
/// assert!((fit.spline.eval(0.5)? - 3f64.sin()).abs() < 0.05);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidLength`] if `x`, `y` and the weights differ in length;
/// [`ErrorKind::TooFewPoints`] with fewer than 5 data; [`ErrorKind::UnsortedKnots`] unless
/// `x` increases strictly; [`ErrorKind::NonFinite`]; [`ErrorKind::InvalidWeight`] for
/// weights that are not positive and finite; [`ErrorKind::InvalidArgument`] for a negative
/// or non-finite $\lambda$; [`ErrorKind::SingularSystem`] when the system cannot be solved.
pub fn smoothing_spline<T: Scalar, P: ControlPoint<T>>(
    x: &[T],
    y: &[P],
    weights: Option<&[T]>,
    parameter: SmoothingParameter<T>,
) -> Result<SmoothingFit<T, P>> {
    let problem = Penalised::new(x, y, weights)?;
    let lambda = match parameter {
        SmoothingParameter::Lambda(l) => {
            check_non_negative(l, "the smoothing weight λ")?;
            l
        }
        SmoothingParameter::Gcv => {
            let upper = from_count::<T>(x.len());
            super::brent::fminbound(|l| problem.score(l).map(|s| s.gcv), T::zero(), upper)
                .map_err(|e| e.context("choosing λ by generalised cross-validation"))?
        }
    };
    if lambda == T::zero() {
        // The natural interpolating spline: every residual is zero, H = I.
        let spline = natural_cubic(x, y)?;
        return Ok(SmoothingFit {
            spline,
            lambda,
            gcv: T::zero(),
            trace: from_count(x.len()),
            residual: T::zero(),
        });
    }
    let score = problem.score(lambda)?;
    Ok(SmoothingFit {
        spline: score.spline,
        lambda,
        gcv: score.gcv,
        trace: score.trace,
        residual: score.residual,
    })
}

/// [`smoothing_spline`] of a parametric curve through `points`: the parameters of
/// `parametrization` (named choices on `[0, 1]`) are the abscissae, the points the values.
/// Returns the fit and the parameters.
///
/// # Errors
/// As [`crate::parametrize`] and [`smoothing_spline`] (the parameters must increase
/// strictly: no two consecutive points may coincide with chordal parameters).
pub fn smoothing_curve<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    parametrization: &Parametrization<T>,
    weights: Option<&[T]>,
    parameter: SmoothingParameter<T>,
) -> Result<(SmoothingFit<T, P>, Vec<T>)> {
    let params = parametrize(points, parametrization)?;
    let fit = smoothing_spline(&params, points, weights, parameter)?;
    Ok((fit, params))
}

/// The assembled penalised problem: Gram matrix `G = Bᵀ W B`, right-hand side `Bᵀ W y`
/// and penalty `Ω` (half-bandwidth 3 each) on the knots of the data.
struct Penalised<'a, T, P> {
    x: &'a [T],
    y: &'a [P],
    weights: Option<&'a [T]>,
    knots: KnotVector<T>,
    gram: Vec<T>,
    penalty: Vec<T>,
    rhs: Vec<P>,
}

/// One evaluation of the penalised problem at a value of λ.
struct Score<T, P> {
    spline: BSpline<T, P>,
    gcv: T,
    trace: T,
    residual: T,
}

/// Half-bandwidth of the cubic systems.
const BW: usize = 3;

impl<'a, T: Scalar, P: ControlPoint<T>> Penalised<'a, T, P> {
    fn new(x: &'a [T], y: &'a [P], weights: Option<&'a [T]>) -> Result<Self> {
        let m = x.len();
        if y.len() != m {
            return Err(Error::invalid_length(
                "smoothing needs one value per abscissa",
                m,
                y.len(),
            ));
        }
        if m < 5 {
            return Err(Error::new(
                ErrorKind::TooFewPoints,
                format!("a smoothing spline needs at least 5 data, got {m}"),
            )
            .with_counts(5, m));
        }
        check_points(y, 5, "smoothing")?;
        crate::params::check_strict(x)?;
        let knots = KnotVector::clamped(3, x[0], x[m - 1], &x[1..m - 1])?;
        let sqrt_weights: Option<Vec<T>> = match weights {
            None => None,
            Some(w) => {
                check_weights(w, m)?;
                Some(w.iter().map(|v| v.sqrt()).collect())
            }
        };
        let mut lsq = LeastSquares::new(y, x, knots.clone());
        if let Some(w) = &sqrt_weights {
            lsq = lsq.weights(w);
        }
        let normal = lsq.normal_equations()?;
        let n = knots.num_basis();
        let w = BW + 1;
        let mut gram = vec![T::zero(); n * w];
        for i in 0..n {
            for d in 0..=BW.min(i) {
                gram[i * w + d] = normal.gram(i, i - d);
            }
        }
        let mut penalty = vec![T::zero(); n * w];
        penalty_rows(&knots, T::one(), |first, row, weight| {
            let w2 = weight * weight;
            for (a, &ra) in row.iter().enumerate() {
                for (c, &rc) in row[..=a].iter().enumerate() {
                    penalty[(first + a) * w + (a - c)] += w2 * ra * rc;
                }
            }
        });
        Ok(Self {
            x,
            y,
            weights,
            knots,
            gram,
            penalty,
            rhs: normal.rhs().to_vec(),
        })
    }

    /// Solves at `lambda > 0` and scores the result.
    fn score(&self, lambda: T) -> Result<Score<T, P>> {
        let n = self.knots.num_basis();
        let w = BW + 1;
        let mut matrix = BandCholesky::zeros(n, BW);
        for i in 0..n {
            for d in 0..=BW.min(i) {
                let v = self.gram[i * w + d] + lambda * self.penalty[i * w + d];
                matrix.add_lower(i, i - d, v);
            }
        }
        matrix.factor(&|i| {
            format!(
                "coefficient {i} of the smoothing spline (λ = {})",
                to_f64(lambda)
            )
        })?;
        let mut c = self.rhs.clone();
        matrix.solve(&mut c);
        let spline = BSpline::new(self.knots.clone(), c)?;
        let values = spline.eval_many(self.x)?;
        let (mut plain, mut weighted) = (T::zero(), T::zero());
        for (k, (f, y)) in values.iter().zip(self.y).enumerate() {
            let r2 = (*f - *y).length_squared();
            plain += r2;
            weighted += r2 * self.weights.map_or_else(T::one, |w| w[k]);
        }
        let z = inverse_band(&matrix, n);
        let mut trace = T::zero();
        for i in 0..n {
            trace += z[i * w] * self.gram[i * w];
            for d in 1..=BW.min(i) {
                trace += (z[i * w + d] * self.gram[i * w + d]) * spline_core::cast(2.0);
            }
        }
        let m = from_count::<T>(self.x.len());
        let denominator = (T::one() - trace / m).powi(2);
        // Not finite where tr H = n (λ → 0): the search then treats the point as worse,
        // as scipy's does.
        let gcv = (plain / m) / denominator;
        Ok(Score {
            spline,
            gcv,
            trace,
            residual: weighted,
        })
    }
}
