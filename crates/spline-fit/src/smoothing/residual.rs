//! Smoothing to a residual target with knots placed automatically: FITPACK's `curfit`
//! (Dierckx 1975, 1982; `fpcurf`), step for step as scipy's `make_splrep` and
//! `make_splprep` replicate it, so that the same data and target give the same knots and
//! the same spline.
//!
//! 1. Knots: from the least-squares polynomial, knots are added where the residuals of the
//!    least-squares spline sum highest (at a data abscissa in the middle of the worst knot
//!    interval), more at a time while the residual falls slowly, until the least-squares
//!    residual is at most the target `s` (or the knots of interpolation are reached).
//! 2. Smoothing: with these knots, the spline minimising the jumps of its `k`-th derivative
//!    at the interior knots subject to $\sum_i (w_i \lVert y_i - s(x_i) \rVert)^2 = s$: the
//!    least-squares problem with the jump rows weighted by `1/p`, `p` found by FITPACK's
//!    rational interpolation (`fprati`) to a relative accuracy of `0.001`.

use crate::banded::BandCholesky;
use crate::interpolate::interpolate_with_knots;
use crate::lsq::{LeastSquares, LsqMethod};
use crate::params::{
    Parametrization, check_non_negative, check_points, check_weights, parametrize,
};
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, MAX_DEGREE, Result, Scalar, cast, check_params,
    from_count, to_f64,
};
use spline_geom::BSpline;

use super::fitpack_steps::{add_knot, jump_rows, knots_to_add, root_rati};

/// FITPACK's relative accuracy of the residual target (`tol` of `curfit`).
pub(super) const TOL: f64 = 0.001;

/// A spline that meets a residual target ([`smoothing_to_residual`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ResidualFit<T, P> {
    /// The spline.
    pub spline: BSpline<T, P>,
    /// Its weighted residual $f_p = \sum_i (w_i \lVert y_i - s(x_i) \rVert)^2$.
    pub residual: T,
    /// FITPACK's smoothing factor `p` (the jump rows weighted by `1/p`), or `None` for the
    /// least-squares spline (the target was met without smoothing, or `s = 0`).
    pub smoothing: Option<T>,
    /// Whether $|f_p - s| < 0.001 s$ was reached (or the least-squares spline met the
    /// target). When `false` the spline is the last iterate, as FITPACK returns it with a
    /// warning (`ier` = 2 or 3).
    pub converged: bool,
}

impl<T: Scalar, P: ControlPoint<T>> ResidualFit<T, P> {
    /// The least-squares spline (or the interpolating one, `residual` zero) as the fit: no
    /// smoothing factor, converged.
    pub(super) fn unsmoothed(spline: BSpline<T, P>, residual: T) -> Self {
        Self {
            spline,
            residual,
            smoothing: None,
            converged: true,
        }
    }
}

/// The spline of degree `k` through or near $(x_i, y_i)$ whose weighted residual
/// $\sum_i (w_i \lVert y_i - s(x_i) \rVert)^2$ is the target `s`, with knots placed
/// automatically and the jumps of the `k`-th derivative at the knots as small as possible:
/// FITPACK's `curfit`, as scipy's `make_splrep(x, y, w=w, k=k, s=s)` (weights multiply the
/// residuals, as in `splrep`). `s = 0` gives the not-a-knot interpolating spline. Vector
/// values `y` fit all coordinates at once (their squared residuals summed), as
/// `make_splprep` does for curves ([`smoothing_curve_to_residual`]).
///
/// ```
/// use spline_fit::smoothing_to_residual;
/// let x: Vec<f64> = (0..50).map(|i| f64::from(i) / 49.0).collect();
/// let y: Vec<f64> = x.iter().map(|t| (4.0 * t).sin() + 0.01 * (97.0 * t).sin()).collect();
/// let fit = smoothing_to_residual(&x, &y, None, 3, 0.003)?;
/// assert!(fit.converged && (fit.residual - 0.003).abs() < 0.003 * 1e-3);
/// assert!(fit.spline.len() < 50);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidLength`] if `x`, `y` and the weights differ in length;
/// [`ErrorKind::InvalidArgument`] unless `1 ≤ k ≤ 5` (FITPACK's degrees) and `s ≥ 0` is
/// finite; [`ErrorKind::TooFewPoints`] with `k + 1` data or fewer;
/// [`ErrorKind::UnsortedKnots`] if `x` decreases (for `s = 0`: unless it increases
/// strictly); [`ErrorKind::NonFinite`]; [`ErrorKind::InvalidWeight`] for weights that are
/// not positive and finite; [`ErrorKind::SchoenbergWhitney`] or
/// [`ErrorKind::SingularSystem`] when a system cannot be solved.
pub fn smoothing_to_residual<T: Scalar, P: ControlPoint<T>>(
    x: &[T],
    y: &[P],
    weights: Option<&[T]>,
    degree: usize,
    s: T,
) -> Result<ResidualFit<T, P>> {
    check_degree(degree, 5)?;
    let data = Data::new(x, y, weights, (degree, s), false)?;
    if s == T::zero() {
        let knots = KnotVector::not_a_knot(degree, x)?;
        let spline = interpolate_with_knots(&knots, x, y)?;
        return Ok(ResidualFit::unsmoothed(spline, T::zero()));
    }
    let knots = data.generate_knots()?;
    data.fit(&knots, knots.domain())
}

/// [`smoothing_to_residual`] of a parametric curve through `points`, as scipy's
/// `make_splprep(points.T, w=w, k=k, s=s)`: the parameters are the chordal ones on
/// `[0, 1]`. Returns the fit and the parameters.
///
/// # Errors
/// As [`crate::parametrize`] and [`smoothing_to_residual`].
pub fn smoothing_curve_to_residual<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    weights: Option<&[T]>,
    degree: usize,
    s: T,
) -> Result<(ResidualFit<T, P>, Vec<T>)> {
    let params = parametrize(points, &Parametrization::Chordal)?;
    let fit = smoothing_to_residual(&params, points, weights, degree, s)?;
    Ok((fit, params))
}

/// Degrees `1 ..= max`: FITPACK's 1 to 5 ([`smoothing_to_residual`]), any supported one
/// for scipy's replicas (`make_splrep` has no limit).
pub(super) fn check_degree(degree: usize, max: usize) -> Result<()> {
    if (1..=max).contains(&degree) {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("smoothing to a residual target takes degrees 1 to {max}, got {degree}"),
        )
        .with_value(from_count(degree))
        .with_interval(1.0, from_count(max)))
    }
}

/// One value per abscissa: `values` of them for `m` abscissae.
pub(super) fn check_lengths(m: usize, values: usize) -> Result<()> {
    if values == m {
        Ok(())
    } else {
        Err(Error::invalid_length("one value per abscissa", m, values))
    }
}

/// The checks of the data shared by the fits to a residual target: `s` finite and
/// non-negative, one value per abscissa, at least `min_points` finite values (`who` names
/// what needs them), sorted finite abscissae not all equal, positive finite weights (one per
/// datum).
pub(super) fn check_data<T: Scalar, P: ControlPoint<T>>(
    x: &[T],
    y: &[P],
    weights: Option<&[T]>,
    s: T,
    (min_points, who): (usize, &str),
) -> Result<()> {
    check_non_negative(s, "the residual target s")?;
    let m = x.len();
    check_lengths(m, y.len())?;
    if m < min_points {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!("{who} needs at least {min_points} data, got {m}"),
        )
        .with_counts(min_points, m));
    }
    check_points(y, min_points, "smoothing")?;
    check_params(x)?;
    if !(x[0] < x[m - 1]) {
        return Err(Error::new(
            ErrorKind::EmptyDomain,
            "the abscissae must not all be equal",
        ));
    }
    if let Some(w) = weights {
        check_weights(w, m)?;
    }
    Ok(())
}

/// The validated data of a residual-target fit: plain (FITPACK's `curfit`) or periodic
/// (`percur`, whose stages are [`super::periodic`]'s).
pub(super) struct Data<'a, T, P> {
    pub(super) x: &'a [T],
    pub(super) y: &'a [P],
    pub(super) weights: Option<&'a [T]>,
    pub(super) degree: usize,
    pub(super) s: T,
    /// Whether the fit is periodic.
    pub(super) periodic: bool,
}

impl<'a, T: Scalar, P: ControlPoint<T>> Data<'a, T, P> {
    /// The data after [`check_degree`] and [`check_data`]: more data than `degree + 1`, or
    /// when `periodic` at least 2 whose first and last values agree.
    pub(super) fn new(
        x: &'a [T],
        y: &'a [P],
        weights: Option<&'a [T]>,
        (degree, s): (usize, T),
        periodic: bool,
    ) -> Result<Self> {
        check_degree(degree, MAX_DEGREE)?;
        if periodic {
            check_data(x, y, weights, s, (2, "periodic smoothing"))?;
            check_periodic_ends(y)?;
        } else {
            check_data(x, y, weights, s, (degree + 1, &format!("degree {degree}")))?;
        }
        Ok(Self {
            x,
            y,
            weights,
            degree,
            s,
            periodic,
        })
    }

    fn weight(&self, i: usize) -> T {
        self.weights.map_or_else(T::one, |w| w[i])
    }

    /// The residuals $(w_i \lVert y_i - s(x_i) \rVert)^2$ of a spline and their sum.
    fn residuals(&self, spline: &BSpline<T, P>) -> Result<(Vec<T>, T)> {
        let values = spline.eval_many(self.x)?;
        let mut fp = T::zero();
        let residuals = values
            .iter()
            .zip(self.y)
            .enumerate()
            .map(|(i, (f, y))| {
                let w = self.weight(i);
                let r = (*f - *y).length_squared() * w * w;
                fp += r;
                r
            })
            .collect();
        Ok((residuals, fp))
    }

    /// The weighted least-squares spline on `knots`, its residuals and their sum: by the
    /// banded normal equations while knots are placed (only the residuals count).
    pub(super) fn least_squares(
        &self,
        knots: &KnotVector<T>,
    ) -> Result<(BSpline<T, P>, Vec<T>, T)> {
        self.least_squares_by(knots, LsqMethod::NormalEquations)
    }

    /// [`Data::least_squares`] by Givens QR as FITPACK's (the condition number not squared):
    /// for the least-squares spline that is returned (a linear function fits to `1e-16`,
    /// not `1e-15`).
    pub(super) fn least_squares_qr(
        &self,
        knots: &KnotVector<T>,
    ) -> Result<(BSpline<T, P>, Vec<T>, T)> {
        self.least_squares_by(knots, LsqMethod::Qr)
    }

    fn least_squares_by(
        &self,
        knots: &KnotVector<T>,
        method: LsqMethod,
    ) -> Result<(BSpline<T, P>, Vec<T>, T)> {
        let mut lsq = LeastSquares::new(self.y, self.x, knots.clone()).method(method);
        if let Some(w) = self.weights {
            lsq = lsq.weights(w);
        }
        let spline = BSpline::new(knots.clone(), lsq.control_points()?)?;
        let (residuals, fp) = self.residuals(&spline)?;
        Ok((spline, residuals, fp))
    }

    /// The knots of FITPACK's first stage (scipy's `_generate_knots_impl`, not periodic).
    fn generate_knots(&self) -> Result<KnotVector<T>> {
        let m = self.x.len();
        self.generate_knots_with((self.x[0], self.x[m - 1]), None, &mut |_| {})
    }

    /// [`Data::generate_knots`] on $[x_b, x_e]$ with an optional cap `nest` on the number
    /// of knots (scipy's default $\max(m + k + 1, 2k + 3)$ for `None`), passing every knot
    /// vector scipy's `generate_knots` yields to `record`, in order; returns the last.
    pub(super) fn generate_knots_with(
        &self,
        (xb, xe): (T, T),
        nest: Option<usize>,
        record: &mut dyn FnMut(&KnotVector<T>),
    ) -> Result<KnotVector<T>> {
        if self.periodic {
            return self.periodic_knots((xb, xe), nest, record);
        }
        let k = self.degree;
        let m = self.x.len();
        let nest = nest.unwrap_or((m + k + 1).max(2 * k + 3));
        let polynomial = KnotVector::clamped(k, xb, xe, &[])?;
        Placement {
            x: self.x,
            s: self.s,
            nmax: m + k + 1,
            nest,
            least_squares: &|t| {
                self.least_squares(t)
                    .map(|(_, residuals, fp)| (residuals, fp))
            },
            rewrap: &Ok,
            interpolation_knots: &|| KnotVector::not_a_knot(k, self.x),
        }
        .run((polynomial, T::zero()), record)
    }

    /// The fit on `knots` (given or placed) in $[x_b, x_e]$ = `bounds`: their least-squares
    /// spline when it has no interior knots, else FITPACK's second stage ([`Data::smooth`])
    /// from it.
    pub(super) fn fit(&self, knots: &KnotVector<T>, bounds: (T, T)) -> Result<ResidualFit<T, P>> {
        if self.periodic {
            return self.periodic_fit(knots, bounds.1 - bounds.0);
        }
        let (lsq, _, fp) = self.least_squares_qr(knots)?;
        if knots.len() == 2 * (self.degree + 1) {
            return Ok(ResidualFit::unsmoothed(lsq, fp));
        }
        self.smooth(knots, fp, bounds)
    }

    /// FITPACK's second stage on `knots` (scipy's `F` and `root_rati`); `fp_lsq` is the
    /// residual of the least-squares spline on them, `bounds` the interval of the
    /// least-squares polynomial that starts the search.
    pub(super) fn smooth(
        &self,
        knots: &KnotVector<T>,
        fp_lsq: T,
        bounds: (T, T),
    ) -> Result<ResidualFit<T, P>> {
        let k = self.degree;
        let s = self.s;
        let mut lsq = LeastSquares::new(self.y, self.x, knots.clone());
        if let Some(w) = self.weights {
            lsq = lsq.weights(w);
        }
        let normal = lsq.normal_equations()?;
        let nc = knots.num_basis();
        // Initial p = nc / Σ R_ii, R the triangular factor of the weighted design matrix
        // (the Cholesky factor of the Gram matrix, positive diagonal as FITPACK's).
        let mut gram = BandCholesky::zeros(nc, k);
        for i in 0..nc {
            for j in i.saturating_sub(k)..=i {
                gram.add_lower(i, j, normal.gram(i, j));
            }
        }
        gram.factor(&|i| format!("coefficient {i}"))?;
        let diagonal = (0..nc).fold(T::zero(), |acc, i| acc + gram.lower(i, i));
        let p0 = from_count::<T>(nc) / diagonal;
        let jumps = jump_rows(knots.knots(), k);
        let solve = |p: T| -> Result<(BSpline<T, P>, T)> {
            let mut matrix = BandCholesky::zeros(nc, k + 1);
            for i in 0..nc {
                for j in i.saturating_sub(k)..=i {
                    matrix.add_lower(i, j, normal.gram(i, j));
                }
            }
            let scale = T::one() / (p * p);
            for (first, row) in &jumps {
                matrix.add_outer(*first, row, scale);
            }
            matrix.factor(&|i| format!("coefficient {i} of the smoothing spline"))?;
            let mut c = normal.rhs().to_vec();
            matrix.solve(&mut c);
            let spline = BSpline::new(knots.clone(), c)?;
            let (_, fp) = self.residuals(&spline)?;
            Ok((spline, fp - s))
        };
        let polynomial = KnotVector::clamped(k, bounds.0, bounds.1, &[])?;
        let fp0 = self.least_squares(&polynomial)?.2 - s;
        smoothed(s, p0, (fp0, fp_lsq - s), solve)
    }
}

/// The residuals of a spline at every datum and the residual.
type Residuals<T> = (Vec<T>, T);

/// FITPACK's first stage, plain (`fpcurf`, [`Data`]) or periodic (`fpperi`): the data and
/// the limits, and what differs between the two ([`Placement::run`]).
pub(super) struct Placement<'f, T> {
    /// The abscissae.
    pub(super) x: &'f [T],
    /// The residual target `s`.
    pub(super) s: T,
    /// The number of knots of interpolation.
    pub(super) nmax: usize,
    /// The cap on the number of knots placed.
    pub(super) nest: usize,
    /// The residuals $(w_i \lVert y_i - g(x_i) \rVert)^2$ of the least-squares spline `g`
    /// on a knot vector at every datum, and the residual (their sum over the data that
    /// count).
    pub(super) least_squares: &'f dyn Fn(&KnotVector<T>) -> Result<Residuals<T>>,
    /// The knot vector after knots were added: as it is, or wrapped again round the period.
    pub(super) rewrap: &'f dyn Fn(KnotVector<T>) -> Result<KnotVector<T>>,
    /// The knots of interpolation: the last vector when `nmax` knots would be reached.
    pub(super) interpolation_knots: &'f dyn Fn() -> Result<KnotVector<T>>,
}

impl<T: Scalar> Placement<'_, T> {
    /// The stage from the knot vector `start`, whose predecessor left the residual `fp`
    /// (zero when there is none): while the least-squares residual exceeds the target,
    /// knots are added [`knots_to_add`] at a time by [`add_knot`], until the residual meets
    /// the target, `nest` knots are reached (that vector is the last) or `nmax` would be
    /// (then the knots of interpolation). Every knot vector fitted is passed to `record`, in
    /// order; returns the last.
    pub(super) fn run(
        &self,
        (start, mut fp): (KnotVector<T>, T),
        record: &mut dyn FnMut(&KnotVector<T>),
    ) -> Result<KnotVector<T>> {
        let s = self.s;
        let acc = s * cast::<T>(TOL);
        let nmin = 2 * (start.degree() + 1);
        let mut knots = start;
        let mut nplus = 1usize;
        for _ in 0..self.x.len() {
            record(&knots);
            let fpold = fp;
            let (mut residuals, new_fp) = (self.least_squares)(&knots)?;
            fp = new_fp;
            let fpms = fp - s;
            if fpms.abs() < acc || fpms < T::zero() {
                return Ok(knots);
            }
            nplus = if knots.len() == nmin {
                1
            } else {
                knots_to_add(nplus, fpold - fp, fpms, acc)
            };
            for j in 0..nplus {
                knots = add_knot(self.x, &knots, &residuals)?;
                let n = knots.len();
                if n >= self.nmax {
                    let knots = (self.interpolation_knots)()?;
                    record(&knots);
                    return Ok(knots);
                }
                if n >= self.nest {
                    record(&knots);
                    return Ok(knots);
                }
                if j + 1 < nplus {
                    residuals = (self.least_squares)(&knots)?.0;
                }
            }
            knots = (self.rewrap)(knots)?;
        }
        Ok(knots)
    }
}

/// FITPACK's second stage after its start ([`root_rati`] to the relative accuracy
/// [`TOL`] of the target `s`), as the fit: `solve(p)` gives the spline for `p` and its
/// residual minus `s`; `p0` starts the search, `(f0, finf)` are those residuals minus `s`
/// at `p = 0` and `p = ∞`.
pub(super) fn smoothed<T: Scalar, P: ControlPoint<T>>(
    s: T,
    p0: T,
    (f0, finf): (T, T),
    solve: impl FnMut(T) -> Result<(BSpline<T, P>, T)>,
) -> Result<ResidualFit<T, P>> {
    let acc = s * cast::<T>(TOL);
    let (spline, f, p, converged) = root_rati(p0, (f0, finf), acc, solve)?;
    Ok(ResidualFit {
        spline,
        residual: f + s,
        smoothing: Some(p),
        converged,
    })
}

/// scipy's test that data are periodic: every coordinate of the first and the last value
/// agree as `numpy.allclose(y[0], y[-1], atol=1e-15)` has it (relative `1e-5` of the last).
pub(super) fn check_periodic_ends<T: Scalar, P: ControlPoint<T>>(y: &[P]) -> Result<()> {
    let (first, last) = (y[0], y[y.len() - 1]);
    let close = (0..P::DIM).all(|c| {
        let (a, b) = (first.coord(c), last.coord(c));
        (a - b).abs() <= cast::<T>(1e-15) + cast::<T>(1e-5) * b.abs()
    });
    if close {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "First and last points does not match which is required for `bc_type='periodic'`: \
                 the first value is {:?}, the last {:?}",
                (0..P::DIM)
                    .map(|c| to_f64(first.coord(c)))
                    .collect::<Vec<_>>(),
                (0..P::DIM)
                    .map(|c| to_f64(last.coord(c)))
                    .collect::<Vec<_>>()
            ),
        ))
    }
}
