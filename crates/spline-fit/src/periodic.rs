//! Periodic interpolation and least squares: the cyclic systems behind closed curves and
//! periodic functions ([`spline_geom::PeriodicBSpline`]).

use crate::banded::{BandCholesky, BandLu};
use crate::lsq::LeastSquares;
use crate::params::{check_degree, check_points, check_strict};
use nalgebra::DMatrix;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, to_f64};
use spline_geom::{BSpline, PeriodicBSpline};

/// Solves the cyclic collocation system $C(u_j) = Q_j$, `j < N`, on the wrapped knot vector
/// `knots` (`N + 2p + 1` knots, `params` inside its domain, sorted) and returns the `N + p`
/// wrapped control points. Unknown `c` is stored at column `(c − p) mod N`, so that the
/// wrapped columns become a dense right border of a band: LU with partial pivoting,
/// `O(N p²)`.
///
/// # Errors
/// [`ErrorKind::SingularSystem`].
pub(crate) fn solve_periodic_collocation<T: Scalar, P: ControlPoint<T>>(
    knots: &KnotVector<T>,
    params: &[T],
    points: &[P],
) -> Result<Vec<P>> {
    let count = points.len();
    let p = knots.degree();
    let shift = p % count;
    let col_of = |raw: usize| (raw % count + count - shift) % count;
    let border = p.min(count);
    let first_border = count - border;
    let width = p + 1;
    let mut rows = Vec::with_capacity(count);
    let (mut kl, mut ku) = (0usize, 0usize);
    let mut span = p;
    for (j, &u) in params.iter().enumerate() {
        span = knots.span_in_domain_from(u, span);
        let mut vals = vec![T::zero(); width];
        knots.basis_values(span, u, &mut vals);
        let f = span - p;
        for (a, v) in vals.iter().enumerate() {
            let c = col_of(f + a);
            if *v != T::zero() && c < first_border {
                kl = kl.max(j.saturating_sub(c));
                ku = ku.max(c.saturating_sub(j));
            }
        }
        rows.push((f, vals));
    }
    let mut lu = BandLu::zeros(count, kl, ku, border);
    for (j, (f, vals)) in rows.iter().enumerate() {
        for (a, &v) in vals.iter().enumerate() {
            if v != T::zero() {
                lu.add(j, col_of(f + a), v);
            }
        }
    }
    lu.factor()?;
    let mut x = points.to_vec();
    lu.solve(&mut x);
    Ok((0..count + p).map(|i| x[col_of(i)]).collect())
}

/// The knots of one period that scipy's `make_interp_spline(x, y, k, bc_type="periodic")`
/// uses: the abscissae $x_0 … x_{n-2}$ for odd degrees; for even degrees $x_0$ and the
/// midpoints $(x_{j-1} + x_j)/2$, `j = 1 … n − 2`.
fn scipy_periodic_knots<T: Scalar>(x: &[T], degree: usize) -> Vec<T> {
    let n = x.len();
    if degree % 2 == 1 {
        return x[..n - 1].to_vec();
    }
    let half: T = cast(0.5);
    let mut knots = Vec::with_capacity(n - 1);
    knots.push(x[0]);
    for j in 1..n - 1 {
        knots.push(x[j] - (x[j] - x[j - 1]) * half);
    }
    knots
}

/// The periodic spline of degree `p` through `(x_j, y_j)`, `j = 0 … n − 1`, with period
/// $T = x_{n-1} - x_0$ (so $y_{n-1}$ must equal $y_0$): scipy's
/// `make_interp_spline(x, y, k=p, bc_type="periodic")` — the same knots (the abscissae for
/// odd degrees; the first abscissa and the midpoints for even ones, extended with the
/// period) and so the same spline. Works for functions (`P = T`) and for closed curves
/// through points at given parameters.
///
/// ```
/// use spline_fit::interpolate_periodic;
/// let x: Vec<f64> = (0..=8).map(|j| j as f64 * std::f64::consts::TAU / 8.0).collect();
/// let y: Vec<f64> = x.iter().map(|t| t.sin()).collect();
/// let s = interpolate_periodic(&x, &y, 3)?;
/// assert!((s.eval(0.3)? - 0.3f64.sin()).abs() < 5e-3);
/// assert!((s.eval(0.3 + std::f64::consts::TAU)? - s.eval(0.3)?).abs() < 1e-14);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidLength`] if `x` and `y` differ in length; [`ErrorKind::TooFewPoints`]
/// unless `n ≥ p + 2`; [`ErrorKind::NonFinite`]; [`ErrorKind::UnsortedKnots`] unless `x`
/// increases strictly; [`ErrorKind::InvalidArgument`] if $y_{n-1} \ne y_0$ (beyond `1e-12`
/// of the data's size); [`ErrorKind::SingularSystem`].
pub fn interpolate_periodic<T: Scalar, P: ControlPoint<T>>(
    x: &[T],
    y: &[P],
    degree: usize,
) -> Result<PeriodicBSpline<T, P>> {
    check_degree(degree)?;
    if x.len() != y.len() {
        return Err(Error::invalid_length("ordinates", x.len(), y.len()));
    }
    check_points(y, degree + 2, "periodic interpolation")?;
    check_strict(x)?;
    let n = x.len();
    let scale = y.iter().fold(T::zero(), |m, q| m.max(q.length()));
    let gap = (y[n - 1] - y[0]).length();
    if gap > scale * cast::<T>(1e-12) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "periodic interpolation needs the last value equal to the first (they differ by {:.3e})",
                to_f64(gap)
            ),
        )
        .with_value(to_f64(gap)));
    }
    let period = x[n - 1] - x[0];
    let knots = scipy_periodic_knots(x, degree);
    // The wrapped container of the space (its control points are placeholders).
    let space = PeriodicBSpline::new(degree, knots, period, vec![y[0]; n - 1])?;
    let control = solve_periodic_collocation(space.wrapped().knots(), &x[..n - 1], &y[..n - 1])?;
    let wrapped = BSpline::new(space.wrapped().knots().clone(), control)?;
    PeriodicBSpline::from_wrapped(&wrapped)
}

/// The periodic least-squares spline: minimises
///
/// $$ \sum_k w_k^2 \lVert C(\bar u_k) - Q_k \rVert^2 + \lambda \int_a^{a+T} \lVert C''(u) \rVert^2 du $$
///
/// over the control points of the periodic space `space` (its control points are ignored),
/// for data at any parameters (reduced to the period). The normal equations of the wrapped
/// container ([`LeastSquares::normal_equations`], the one assembly of the crate) are folded
/// onto the `N` periodic unknowns; the cyclic band is solved by block elimination (banded
/// Cholesky on the first `N − p` unknowns, a dense `p × p` Schur complement), `O(N p²)`.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::least_squares_periodic;
/// use spline_geom::PeriodicBSpline;
/// // 200 points on the unit circle, a periodic cubic with 12 control points.
/// let u: Vec<f64> = (0..200).map(|k| k as f64 / 200.0).collect();
/// let q: Vec<Vector2<f64>> = u.iter().map(|t| {
///     let a = t * std::f64::consts::TAU;
///     Vector2::new(a.cos(), a.sin())
/// }).collect();
/// let knots: Vec<f64> = (0..12).map(|i| i as f64 / 12.0).collect();
/// let space = PeriodicBSpline::new(3, knots, 1.0, vec![Vector2::zeros(); 12])?;
/// let fit = least_squares_periodic(&q, &u, &space, None, 0.0)?;
/// assert!((fit.eval(0.123)?.norm() - 1.0).abs() < 1e-4);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidLength`] if points, parameters and weights differ in number;
/// [`ErrorKind::NonFinite`]; [`ErrorKind::InvalidWeight`]; [`ErrorKind::InvalidArgument`] for
/// a negative smoothing weight; [`ErrorKind::SingularSystem`] when the data do not determine
/// every control point.
pub fn least_squares_periodic<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    params: &[T],
    space: &PeriodicBSpline<T, P>,
    weights: Option<&[T]>,
    lambda: T,
) -> Result<PeriodicBSpline<T, P>> {
    if params.len() != points.len() {
        return Err(Error::invalid_length(
            "parameters",
            points.len(),
            params.len(),
        ));
    }
    if let Some(w) = weights
        && w.len() != points.len()
    {
        return Err(Error::invalid_length("weights", points.len(), w.len()));
    }
    check_points(points, 1, "periodic least squares")?;
    // Data sorted by their parameter in the period.
    let mut order: Vec<(T, usize)> = params
        .iter()
        .enumerate()
        .map(|(k, &u)| space.reduce(u).map(|r| (r, k)))
        .collect::<Result<_>>()?;
    order.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
    let sorted_params: Vec<T> = order.iter().map(|&(u, _)| u).collect();
    let sorted_points: Vec<P> = order.iter().map(|&(_, k)| points[k]).collect();
    let sorted_weights: Option<Vec<T>> =
        weights.map(|w| order.iter().map(|&(_, k)| w[k]).collect());
    let wrapped = space.wrapped();
    let mut problem = LeastSquares::new(&sorted_points, &sorted_params, wrapped.knots().clone())
        .smoothing(lambda);
    if let Some(w) = &sorted_weights {
        problem = problem.weights(w);
    }
    let normal = problem.normal_equations()?;
    let n = space.len();
    let p = space.degree();
    // Fold the N + p unknowns of the container onto the N periodic ones: entry
    // (i mod N, j mod N) at cyclic offset i − j ≤ p, stored as band[J (p + 1) + d].
    let mut gram = CyclicBand::zeros(n, p);
    let mut rhs = vec![P::origin(); n];
    for i in 0..normal.len() {
        rhs[i % n] += normal.rhs()[i];
        for j in i.saturating_sub(p)..=i {
            gram.add(j % n, i - j, normal.gram(i, j));
        }
    }
    let control = solve_cyclic(&gram, &rhs, p)?;
    PeriodicBSpline::new(p, space.period_knots().to_vec(), space.period(), control)
}

/// A symmetric matrix whose entries lie at cyclic distance ≤ `p` from the diagonal:
/// `band[i (p + 1) + d]` $= G_{i, (i + d) \bmod N}$ (dense when `N` is small, where the
/// offsets would overlap).
struct CyclicBand<T> {
    n: usize,
    p: usize,
    band: Vec<T>,
    dense: Option<DMatrix<T>>,
}

impl<T: Scalar> CyclicBand<T> {
    fn zeros(n: usize, p: usize) -> Self {
        let small = n <= 4 * p + 4;
        Self {
            n,
            p,
            band: if small {
                Vec::new()
            } else {
                vec![T::zero(); n * (p + 1)]
            },
            dense: small.then(|| DMatrix::zeros(n, n)),
        }
    }

    /// Adds `g` to $G_{j, j+d}$ and its mirror.
    fn add(&mut self, j: usize, d: usize, g: T) {
        let n = self.n;
        match &mut self.dense {
            Some(m) => {
                let i = (j + d) % n;
                m[(i, j)] += g;
                if d != 0 {
                    m[(j, i)] += g;
                }
            }
            None => self.band[j * (self.p + 1) + d] += g,
        }
    }

    fn get(&self, i: usize, j: usize) -> T {
        if let Some(m) = &self.dense {
            return m[(i, j)];
        }
        let (n, p) = (self.n, self.p);
        let forward = (j + n - i) % n;
        if forward <= p {
            return self.band[i * (p + 1) + forward];
        }
        let backward = (i + n - j) % n;
        if backward <= p {
            self.band[j * (p + 1) + backward]
        } else {
            T::zero()
        }
    }
}

/// Solves the symmetric positive definite cyclic band system `G x = r` (half-bandwidth `p`):
/// dense Cholesky for small `N`, otherwise banded Cholesky of the leading `N − p` block and
/// a dense Schur complement for the last `p` unknowns.
fn solve_cyclic<T: Scalar, P: ControlPoint<T>>(
    gram: &CyclicBand<T>,
    rhs: &[P],
    p: usize,
) -> Result<Vec<P>> {
    let n = rhs.len();
    let singular = || {
        Error::new(
            ErrorKind::SingularSystem,
            "the periodic least-squares system is singular: the data do not determine every control point",
        )
    };
    let dim = P::DIM;
    let solve_dense = |g: DMatrix<T>, r: &[P]| -> Result<Vec<P>> {
        let chol = g.cholesky().ok_or_else(singular)?;
        let mut b = DMatrix::<T>::from_fn(r.len(), dim, |i, c| r[i].coord(c));
        chol.solve_mut(&mut b);
        Ok((0..r.len())
            .map(|i| P::from_coords(|c| b[(i, c)]))
            .collect())
    };
    if let Some(dense) = &gram.dense {
        return solve_dense(dense.clone(), rhs);
    }
    let k = n - p;
    let mut a = BandCholesky::zeros(k, p);
    for i in 0..k {
        for j in i.saturating_sub(p)..=i {
            a.add_lower(i, j, gram.get(i, j));
        }
    }
    a.factor(&|i| format!("control point {i}"))
        .map_err(|_| singular())?;
    // A⁻¹ B (p columns) and A⁻¹ r₁.
    let mut ainv_b: Vec<Vec<T>> = (0..p)
        .map(|c| (0..k).map(|i| gram.get(i, k + c)).collect())
        .collect();
    for col in &mut ainv_b {
        a.solve(col);
    }
    let mut y = rhs[..k].to_vec();
    a.solve(&mut y);
    let mut schur = DMatrix::<T>::from_fn(p, p, |r, c| gram.get(k + r, k + c));
    let mut r2: Vec<P> = rhs[k..].to_vec();
    for r in 0..p {
        for i in 0..k {
            let b_ir = gram.get(i, k + r);
            if b_ir == T::zero() {
                continue;
            }
            for c in 0..p {
                schur[(r, c)] -= b_ir * ainv_b[c][i];
            }
            r2[r] -= y[i] * b_ir;
        }
    }
    let x2 = solve_dense(schur, &r2)?;
    let mut x = y;
    for (i, xi) in x.iter_mut().enumerate() {
        for (c, x2c) in x2.iter().enumerate() {
            *xi -= *x2c * ainv_b[c][i];
        }
    }
    x.extend(x2);
    if x.iter().all(ControlPoint::all_finite) {
        Ok(x)
    } else {
        Err(singular())
    }
}
