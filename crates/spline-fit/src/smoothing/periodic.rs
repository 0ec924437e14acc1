//! FITPACK's periodic smoothing (`percur`, driver `fpperi`; Dierckx 1982), as scipy 1.17's
//! `make_splrep(..., bc_type="periodic")` replicates it: the spline of period
//! $x_e - x_b$ whose weighted residual over the data but the last (the first one a period
//! later) meets the target `s`.
//!
//! The knot vector of a periodic spline of degree `k` with interior knots
//! $x_b = t_k < t_{k+1} < … < t_{n-k-1} = x_e$ is wrapped: $t_{k-j} = t_{n-k-1-j} - T$ and
//! $t_{n-k-1+j} = t_{k+j} + T$, `j = 1 … k`; its `n − k − 1` coefficients repeat the first
//! `k` ($c_{n_7 + j} = c_j$, $n_7 = n - 2k - 1$ free ones), so that the values and the first
//! `k − 1` derivatives agree at $x_b$ and $x_e$. Every least-squares system then lives on the
//! `n₇` free coefficients, where coefficient `i` of the knot vector is free coefficient
//! `i mod n₇`: the Gram matrix is a cyclic band, factored in natural order by
//! [`ProfileCholesky`] (`O(n₇ k²)`, the triangle FITPACK's Givens rotations produce).
//!
//! The stages are those of [`super::residual`]: knots added where the residuals are largest
//! (starting from the least-squares constant, then one interior knot at the middle datum),
//! then the jumps of the `k`-th derivative at the interior knots minimised subject to the
//! residual target.

use super::fitpack_steps::jump_rows;
use super::profile::ProfileCholesky;
use super::residual::{
    Data, Placement, ResidualFit, TOL, check_degree, check_lengths, check_periodic_ends, smoothed,
};
use super::splrep_options::knots_around_data;
use crate::interpolate::interpolate_with_knots;
use crate::lsq::LeastSquares;
use crate::periodic::interpolate_periodic;
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, MAX_DEGREE, Result, Scalar, cast, check_params,
    from_count,
};
use spline_geom::BSpline;

/// The periodic least-squares spline on a knot vector.
struct Lsq<T, P> {
    spline: BSpline<T, P>,
    /// $(w_i \lVert y_i - g(x_i) \rVert)^2$ for every datum, the last one included (scipy
    /// 1.17 places knots with it; FITPACK counts the first one twice instead: the same
    /// when the knots are wrapped and the end weights equal).
    residuals: Vec<T>,
    /// Their sum over the data but the last: the residual.
    fp: T,
    /// The sum of the diagonal of the triangular factor (FITPACK's start of `p`).
    diagonal: T,
}

/// The wrapped knots around one period `t[k] = xb … t[n − k − 1] = xe` (FITPACK's
/// `fpperi`, scipy's `_generate_knots_impl`).
fn wrap<T: Scalar>(t: &mut [T], k: usize, (xb, xe): (T, T)) {
    let n = t.len();
    let per = xe - xb;
    t[k] = xb;
    t[n - k - 1] = xe;
    for j in 1..=k {
        t[k - j] = t[n - k - j - 1] - per;
        t[n - k + j - 1] = t[k + j] + per;
    }
}

/// The knots of scipy's periodic interpolation (`_periodic_knots(x, k)`): the abscissae for
/// odd `k`, for even `k` the first and last abscissae with the midpoints between, extended
/// by `k` knots on each side with the spacings of the other end (`len(x) + 2k` knots).
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] with fewer than 2 abscissae; [`ErrorKind::NonFinite`] and
/// [`ErrorKind::UnsortedKnots`] for abscissae that are not finite and sorted; the errors of
/// [`KnotVector::new`] (repeated abscissae).
pub(super) fn periodic_interpolation_knots<T: Scalar>(x: &[T], k: usize) -> Result<KnotVector<T>> {
    let m = x.len();
    if m < 2 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!("periodic knots need at least 2 abscissae, got {m}"),
        )
        .with_counts(2, m));
    }
    check_params(x)?;
    let half: T = cast(0.5);
    let mut xc = x.to_vec();
    if k % 2 == 0 {
        for i in 1..m - 1 {
            xc[i] = x[i] - (x[i] - x[i - 1]) * half;
        }
    }
    let dx: Vec<T> = xc.windows(2).map(|w| w[1] - w[0]).collect();
    let mut t = vec![T::zero(); m + 2 * k];
    t[k..k + m].copy_from_slice(&xc);
    let n = t.len();
    for i in 0..k {
        t[k - i - 1] = t[k - i] - dx[m - 2 - i % (m - 1)];
        t[n - k + i] = t[n - k + i - 1] + dx[i % (m - 1)];
    }
    KnotVector::new(k, t)
}

/// scipy's `make_interp_spline(x, y, k, bc_type="periodic")`: for `k = 1` the broken line
/// (knots `x[0], x…, x[-1]`), otherwise [`interpolate_periodic`] as a spline on
/// [`periodic_interpolation_knots`]. The last value is taken equal to the first (they were
/// checked to agree).
pub(super) fn interpolation<T: Scalar, P: ControlPoint<T>>(
    x: &[T],
    y: &[P],
    k: usize,
) -> Result<ResidualFit<T, P>> {
    check_degree(k, MAX_DEGREE)?;
    check_lengths(x.len(), y.len())?;
    if y.is_empty() {
        return Err(Error::new(ErrorKind::TooFewPoints, "no data").with_counts(2, 0));
    }
    check_periodic_ends(y)?;
    let mut values = y.to_vec();
    let m = values.len();
    values[m - 1] = values[0];
    let spline = if k == 1 {
        let knots = KnotVector::not_a_knot(1, x)?;
        interpolate_with_knots(&knots, x, &values)?
    } else {
        // scipy's knots (the wrapped ones extended by its spacings, not by the period).
        let periodic = interpolate_periodic(x, &values, k)?;
        let control = periodic.wrapped().control_points().to_vec();
        BSpline::new(periodic_interpolation_knots(x, k)?, control)?
    };
    Ok(ResidualFit::unsmoothed(spline, T::zero()))
}

/// FITPACK's `fpchep` for given knots of a periodic spline: `k + 1 ≤ n − k − 1 ≤ m + k − 1`,
/// the knots of one period strictly increasing, the data inside it, and the
/// Schoenberg–Whitney conditions for some cyclic shift of the data but the last.
pub(super) fn check_given_knots<T: Scalar>(x: &[T], t: &[T], k: usize) -> Result<KnotVector<T>> {
    let m = x.len();
    let n = t.len();
    let nk1 = n.saturating_sub(k + 1);
    if !(nk1 > k && nk1 < m + k) {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("Need k+1 <= n-k-1 <= m+k-1. Got m = {m}, n = {n}, k = {k}"),
        ));
    }
    let knots = knots_around_data(x, t, k)?;
    if !schoenberg_whitney(x, t, k) {
        return Err(Error::new(
            ErrorKind::SchoenbergWhitney,
            "Schoenberg-Whitney condition is violated: no cyclic shift of the data puts a \
             distinct datum strictly inside the support of every periodic basis function",
        ));
    }
    Ok(knots)
}

/// `fpchep`'s condition 5: for some start `s` (among the data in the first `k + 1` knot
/// intervals), the data `x[s] … x[m − 2], x[0] + T … x[s − 1] + T` can be matched greedily,
/// one distinct datum $t_j < \xi_j < t_{j+k+1}$ per `j = k … n − k − 2`.
fn schoenberg_whitney<T: Scalar>(x: &[T], t: &[T], k: usize) -> bool {
    let m = x.len();
    let n = t.len();
    let nk1 = n - k - 1;
    let m1 = m - 1;
    // FITPACK's bound on the shifts: the data before the (k + 1)-th knot after t[k].
    let mut l1 = k; // 0-based t index
    let mut passed = 0;
    let mut last = m;
    'bound: for (l, &xi) in x.iter().enumerate() {
        while !(xi < t[l1 + 1] || l + 1 == nk1) {
            l1 += 1;
            passed += 1;
            if passed > k {
                last = l + 1;
                break 'bound;
            }
        }
    }
    let per = t[nk1] - t[k];
    (1..last.min(m)).any(|start| {
        let mut i = start;
        let end = start + m1;
        for j in k..nk1 {
            let (tj, tl) = (t[j], t[j + k + 1]);
            loop {
                if i >= end {
                    return false;
                }
                let xi = if i < m1 { x[i] } else { x[i - m1] + per };
                i += 1;
                if xi <= tj {
                    continue;
                }
                if xi >= tl {
                    return false;
                }
                break;
            }
        }
        true
    })
}

/// The stages of a periodic fit (`Data` with `periodic`).
impl<T: Scalar, P: ControlPoint<T>> Data<'_, T, P> {
    /// The number of data used: all but the last.
    fn used(&self) -> usize {
        self.x.len() - 1
    }

    /// The Gram matrix and right-hand side of the weighted least squares on `knots`, folded
    /// onto the free coefficients, in a cyclic band of half-bandwidth `band ≥ k`.
    fn folded(
        &self,
        knots: &KnotVector<T>,
        band: usize,
    ) -> Result<(ProfileCholesky<T>, Vec<P>, usize)> {
        let m1 = self.used();
        let k = self.degree;
        let mut problem = LeastSquares::new(&self.y[..m1], &self.x[..m1], knots.clone());
        if let Some(w) = self.weights {
            problem = problem.weights(&w[..m1]);
        }
        let normal = problem.normal_equations()?;
        let nk1 = knots.num_basis();
        let n7 = nk1 - k;
        let mut gram = ProfileCholesky::cyclic(n7, band);
        let mut rhs = vec![P::origin(); n7];
        for i in 0..nk1 {
            rhs[i % n7] += normal.rhs()[i];
            for j in i.saturating_sub(k)..=i {
                let v = normal.gram(i, j);
                let (a, b) = (i % n7, j % n7);
                // Both (i, j) and (j, i) land on the diagonal when they wrap onto each other.
                gram.add(a, b, if i != j && a == b { v + v } else { v });
            }
        }
        Ok((gram, rhs, n7))
    }

    /// The spline of the free coefficients `free` on `knots` (coefficient `i` is
    /// `free[i mod n₇]`), its residual at every datum and their sum over all but the last.
    fn spline(&self, knots: &KnotVector<T>, free: &[P]) -> Result<(BSpline<T, P>, Vec<T>, T)> {
        let n7 = free.len();
        let control = (0..knots.num_basis()).map(|i| free[i % n7]).collect();
        let spline = BSpline::new(knots.clone(), control)?;
        let values = spline.eval_many(self.x)?;
        let residuals: Vec<T> = values
            .iter()
            .zip(self.y)
            .enumerate()
            .map(|(i, (g, y))| {
                let w = self.weights.map_or_else(T::one, |w| w[i]);
                (*g - *y).length_squared() * w * w
            })
            .collect();
        let fp = residuals[..self.used()]
            .iter()
            .fold(T::zero(), |acc, &r| acc + r);
        Ok((spline, residuals, fp))
    }

    /// The periodic least-squares spline on `knots`.
    fn periodic_least_squares(&self, knots: &KnotVector<T>) -> Result<Lsq<T, P>> {
        let (mut gram, mut c, n7) = self.folded(knots, self.degree)?;
        gram.factor(&|i| format!("periodic coefficient {i}"))?;
        gram.solve(&mut c);
        let diagonal = (0..n7).fold(T::zero(), |acc, i| acc + gram.diagonal(i));
        let (spline, residuals, fp) = self.spline(knots, &c)?;
        Ok(Lsq {
            spline,
            residuals,
            fp,
            diagonal,
        })
    }

    /// The knots of the least-squares constant: one period from `x[0]` to `x[m − 1]`
    /// (`per` long) with `k` more on each side.
    fn constant_knots(&self, per: T) -> Result<KnotVector<T>> {
        let k = self.degree;
        let m = self.x.len();
        let mut t = vec![T::zero(); 2 * k + 2];
        for i in 0..=k {
            t[i] = self.x[0] - from_count::<T>(k - i) * per;
            t[i + k + 1] = self.x[m - 1] + from_count::<T>(i) * per;
        }
        KnotVector::new(k, t)
    }

    /// FITPACK's first stage (`fpperi` part 1, scipy's `_generate_knots_impl` with
    /// `periodic=True`) on $[x_b, x_e]$ with the cap `nest` (default
    /// $\max(m + 2k, 2k + 3)$), passing every knot vector to `record`; returns the last.
    pub(super) fn periodic_knots(
        &self,
        bounds: (T, T),
        nest: Option<usize>,
        record: &mut dyn FnMut(&KnotVector<T>),
    ) -> Result<KnotVector<T>> {
        let k = self.degree;
        let m = self.x.len();
        let s = self.s;
        let nest = nest.unwrap_or((m + 2 * k).max(2 * k + 3));
        let nmax = m + 2 * k;
        let constant = self.constant_knots(bounds.1 - bounds.0)?;
        let fp = self.periodic_least_squares(&constant)?.fp;
        if fp - s < s * cast::<T>(TOL) || nmax == 2 * (k + 1) {
            record(&constant);
            return Ok(constant);
        }
        // One interior knot at the middle datum; the others are set by `wrap`.
        let mut t = vec![T::zero(); 2 * k + 3];
        t[k + 1] = self.x[m.div_ceil(2) - 1];
        let wrapped = |mut t: Vec<T>| {
            wrap(&mut t, k, bounds);
            KnotVector::new(k, t)
        };
        let start = wrapped(t)?;
        Placement {
            x: self.x,
            s,
            nmax,
            nest,
            least_squares: &|t| {
                self.periodic_least_squares(t)
                    .map(|lsq| (lsq.residuals, lsq.fp))
            },
            // While knots are added one by one (and refitted for their residuals), those
            // beyond the period stay those of the last wrap, as scipy's.
            rewrap: &|knots| wrapped(knots.into_knots()),
            interpolation_knots: &|| periodic_interpolation_knots(self.x, k),
        }
        .run((start, fp), record)
    }

    /// The fit on `knots` (given or placed): their least-squares spline when it has no
    /// interior knots, else FITPACK's second stage ([`Data::periodic_smooth`]) from it, with
    /// the least-squares constant of period `per`.
    pub(super) fn periodic_fit(&self, knots: &KnotVector<T>, per: T) -> Result<ResidualFit<T, P>> {
        let lsq = self.periodic_least_squares(knots)?;
        if knots.len() == 2 * (self.degree + 1) {
            return Ok(ResidualFit::unsmoothed(lsq.spline, lsq.fp));
        }
        self.periodic_smooth(knots, &lsq, per)
    }

    /// FITPACK's second stage on `knots` (`fpperi` part 2, scipy's `Fperiodic` and
    /// `root_rati`), starting from their least-squares spline `lsq`; `per` is the period of
    /// the least-squares constant (`p = 0`).
    fn periodic_smooth(
        &self,
        knots: &KnotVector<T>,
        lsq: &Lsq<T, P>,
        per: T,
    ) -> Result<ResidualFit<T, P>> {
        let k = self.degree;
        let s = self.s;
        let (gram, rhs, n7) = self.folded(knots, k + 1)?;
        let p0 = from_count::<T>(n7) / lsq.diagonal;
        let fp0 = self.periodic_least_squares(&self.constant_knots(per)?)?.fp - s;
        // The jump rows on the free coefficients (entries wrapping onto each other summed).
        let jumps: Vec<Vec<(usize, T)>> = jump_rows(knots.knots(), k)
            .into_iter()
            .map(|(first, row)| {
                let mut folded: Vec<(usize, T)> = Vec::with_capacity(row.len());
                for (a, v) in row.into_iter().enumerate() {
                    let i = (first + a) % n7;
                    match folded.iter_mut().find(|(j, _)| *j == i) {
                        Some((_, acc)) => *acc += v,
                        None => folded.push((i, v)),
                    }
                }
                folded
            })
            .collect();
        let solve = |p: T| -> Result<(BSpline<T, P>, T)> {
            let mut matrix = gram.clone();
            let scale = T::one() / (p * p);
            for row in &jumps {
                for (a, &(i, vi)) in row.iter().enumerate() {
                    for &(j, vj) in &row[..=a] {
                        matrix.add(i, j, vi * vj * scale);
                    }
                }
            }
            matrix.factor(&|i| format!("periodic coefficient {i} of the smoothing spline"))?;
            let mut c = rhs.clone();
            matrix.solve(&mut c);
            let (spline, _, fp) = self.spline(knots, &c)?;
            Ok((spline, fp - s))
        };
        smoothed(s, p0, (fp0, lsq.fp - s), solve)
    }
}

/// The knots of scipy's periodic interpolation as `generate_knots` gives them (`s = 0`):
/// [`periodic_interpolation_knots`], the not-a-knot ones for `k = 1`.
///
/// # Errors
/// As [`check_degree`] and those knots.
pub(super) fn interpolation_knots<T: Scalar>(x: &[T], k: usize) -> Result<KnotVector<T>> {
    check_degree(k, MAX_DEGREE)?;
    if k == 1 {
        KnotVector::not_a_knot(1, x)
    } else {
        periodic_interpolation_knots(x, k)
    }
}
