//! Assembly of the least-squares system: normal equations (with unrolled kernels for low
//! degrees) or Givens QR, fixed control points moved to the right-hand side, the smoothing
//! term, and the streaming Schoenberg–Whitney check.

// Index loops mirror the formulas (basis index ↔ control-point index).
#![allow(clippy::needless_range_loop)]

use super::{LeastSquares, LsqMethod, Rows};
use crate::banded::{BandCholesky, BandQr};
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, MAX_ORDER, Result, Scalar, SpanBasis, cast,
    gauss_legendre, to_f64,
};

impl<T: Scalar, P: ControlPoint<T>> LeastSquares<'_, T, P> {
    /// Accumulates the system for the control points flagged in `free` (the others taking
    /// `values`), with the compressed column of each free control point.
    pub(super) fn assemble_group(
        &self,
        free: &[bool],
        values: &[P],
    ) -> Result<(Sink<T, P>, Vec<usize>)> {
        let knots = &self.knots;
        let n = knots.num_basis();
        let p = knots.degree();
        let width = p + 1;
        let all_free = free.iter().all(|&f| f);
        // Compressed column of each free control point.
        let mut column = vec![usize::MAX; n];
        let mut unknowns = 0;
        for i in 0..n {
            if free[i] {
                column[i] = unknowns;
                unknowns += 1;
            }
        }
        if unknowns == 0 {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "every control point is fixed: nothing to fit",
            ));
        }
        let mut sink = match self.method {
            LsqMethod::NormalEquations => Sink::Normal(
                BandCholesky::zeros(unknowns, p),
                vec![P::origin(); unknowns],
            ),
            LsqMethod::Qr => Sink::Qr(BandQr::new(unknowns, p)),
        };
        let mut basis = [T::zero(); MAX_ORDER];
        let mut compressed = [T::zero(); MAX_ORDER];
        // A row `row` on the basis functions first, first + 1, … with right-hand side
        // `target`: the fixed control points move to the right-hand side, the entries of
        // the free ones are compressed to their columns.
        let mut add_constrained =
            |sink: &mut Sink<T, P>, first: usize, row: &[T], w: T, mut target: P| {
                let mut start = None;
                let mut len = 0;
                for (a, &b) in row.iter().enumerate() {
                    let i = first + a;
                    if free[i] {
                        start.get_or_insert(column[i]);
                        compressed[len] = b;
                        len += 1;
                    } else {
                        target -= values[i] * b;
                    }
                }
                if let Some(s) = start {
                    sink.add(s, &mut compressed[..len], w, target);
                }
            };
        // Streaming Schoenberg–Whitney check (greedy assignment of data to free basis
        // functions in order).
        let check = self.check_sw && self.smoothing == T::zero();
        // Unrolled accumulation of the normal equations for the common case.
        let fast = match (&mut sink, all_free) {
            (Sink::Normal(matrix, rhs), true) => {
                let data = matrix.data_mut();
                let rows = Rows {
                    knots,
                    params: self.params,
                    points: self.points,
                    weights: self.weights,
                };
                let run = assemble_normal(rows, check, data, rhs);
                match run {
                    Some(Err(i)) => return Err(self.sw_error(i)),
                    Some(Ok(())) => true,
                    None => false,
                }
            }
            _ => false,
        };
        let mut next = if fast {
            None
        } else {
            (0..n).find(|&i| free[i])
        };
        let mut last_assigned: Option<T> = None;
        let mut span = p;
        let mut evaluator = SpanBasis::new();
        let data_rows = if fast { 0 } else { self.params.len() };
        for (j, (&u, &q)) in self
            .params
            .iter()
            .zip(self.points)
            .enumerate()
            .take(data_rows)
        {
            span = knots.span_in_domain_from(u, span);
            evaluator.eval(knots, span, u, &mut basis[..width]);
            let f = span - p;
            if check {
                if let Some(i) = next {
                    if span > i + p {
                        return Err(self.sw_error(i));
                    }
                    if span >= i && basis[i - f] != T::zero() && last_assigned.is_none_or(|l| u > l)
                    {
                        last_assigned = Some(u);
                        next = (i + 1..n).find(|&i| free[i]);
                    }
                }
            }
            let w = self.weights.map_or_else(T::one, |w| w[j]);
            if all_free {
                sink.add(f, &mut basis[..width], w, q);
            } else {
                add_constrained(&mut sink, f, &basis[..width], w, q);
            }
        }
        if check {
            if let Some(i) = next {
                return Err(self.sw_error(i));
            }
        }
        if self.smoothing > T::zero() {
            penalty_rows(knots, self.smoothing, |first, row, w| {
                add_constrained(&mut sink, first, row, w, P::origin());
            });
        }
        Ok((sink, column))
    }

    fn sw_error(&self, i: usize) -> Error {
        self.sw_error_with(self.params, i)
    }

    /// [`LeastSquares::sw_error`] for other parameters.
    fn sw_error_with(&self, params: &[T], i: usize) -> Error {
        let k = self.knots.knots();
        let p = self.knots.degree();
        let mut message = format!(
            "Schoenberg–Whitney conditions fail: no data parameter is left for basis function N_{i} (support [{}, {}])",
            to_f64(k[i]),
            to_f64(k[i + p + 1])
        );
        let (_, end) = self.knots.domain();
        let n = self.knots.num_basis();
        for s in i.max(p)..=(i + p).min(n - 1) {
            let (a, b) = (k[s], k[s + 1]);
            if a < b
                && !params
                    .iter()
                    .any(|&u| u >= a && (u < b || (b == end && u <= b)))
            {
                message.push_str(&format!(
                    "; knot span [{}, {}] holds no data",
                    to_f64(a),
                    to_f64(b)
                ));
                break;
            }
        }
        Error::new(ErrorKind::SchoenbergWhitney, message)
    }
}

/// The rows of the smoothing term $\lambda \int \lVert C''(u) \rVert^2 du$ (none below degree
/// 2): at the `p − 1` Gauss–Legendre nodes of every non-empty span (exact for the squared
/// second derivative), `f(first, row, weight)` receives the second derivatives of the
/// `p + 1` basis functions `first …` and the weight whose square is `λ` times the quadrature
/// weight, so that the term is $\sum (\text{weight} \cdot \text{row} \cdot c)^2$.
pub(crate) fn penalty_rows<T: Scalar>(
    knots: &KnotVector<T>,
    lambda: T,
    mut f: impl FnMut(usize, &[T], T),
) {
    let p = knots.degree();
    if p < 2 {
        return;
    }
    let width = p + 1;
    let rule = gauss_legendre::<T>(p - 1);
    let k = knots.knots();
    let mut table = [T::zero(); 3 * MAX_ORDER];
    let half: T = cast(0.5);
    for s in p..knots.num_basis() {
        let (a, b) = (k[s], k[s + 1]);
        if !(a < b) {
            continue;
        }
        let (mid, rad) = ((a + b) * half, (b - a) * half);
        for &(x, wq) in &rule {
            let u = mid + rad * x;
            knots.basis_derivatives(s, u, 2, &mut table[..3 * width]);
            f(
                s - p,
                &table[2 * width..3 * width],
                (lambda * wq * rad).sqrt(),
            );
        }
    }
}

/// The lower band and right-hand side of the normal equations of the data (added to `band`
/// and `rhs`) by the unrolled kernels (degrees ≤ 5; `None` above), with the streaming
/// Schoenberg–Whitney check when `check` (`Some(Err(i))` names the first basis function
/// left without data). With the `parallel` feature and at least [`PARALLEL_MIN_POINTS`]
/// points the data are split into chunks assembled on every core and summed.
fn assemble_normal<T: Scalar, P: ControlPoint<T>>(
    rows: Rows<'_, T, P>,
    check: bool,
    band: &mut [T],
    rhs: &mut [P],
) -> Option<std::result::Result<(), usize>> {
    #[cfg(feature = "parallel")]
    if rows.params.len() >= PARALLEL_MIN_POINTS && rows.knots.degree() <= 5 {
        return Some(super::parallel::assemble(
            (
                normal_dispatch::<T, P, true>,
                normal_dispatch::<T, P, false>,
            ),
            rows,
            check,
            band,
            rhs,
        ));
    }
    normal_dispatch::<T, P, true>(rows, check, band, rhs)
}

/// Data sets at least this large are assembled in parallel (`parallel` feature): curve fits,
/// scattered least-squares surfaces, and the grid lines of grid surface fits.
#[cfg(feature = "parallel")]
pub const PARALLEL_MIN_POINTS: usize = 1 << 14;

/// [`normal_kernel`] for the degree of `knots` (`None` above degree 5); with `ACC = false`
/// only the Schoenberg–Whitney check runs.
fn normal_dispatch<T: Scalar, P: ControlPoint<T>, const ACC: bool>(
    rows: Rows<'_, T, P>,
    check: bool,
    band: &mut [T],
    rhs: &mut [P],
) -> Option<std::result::Result<(), usize>> {
    match rows.knots.degree() {
        0 => normal_kernel::<T, P, 1, ACC>(rows, check, band, rhs),
        1 => normal_kernel::<T, P, 2, ACC>(rows, check, band, rhs),
        2 => normal_kernel::<T, P, 3, ACC>(rows, check, band, rhs),
        3 => normal_kernel::<T, P, 4, ACC>(rows, check, band, rhs),
        4 => normal_kernel::<T, P, 5, ACC>(rows, check, band, rhs),
        5 => normal_kernel::<T, P, 6, ACC>(rows, check, band, rhs),
        _ => None,
    }
}

/// Accumulates the normal equations of the data rows for degree `W − 1` known at compile
/// time (loops unrolled), with the streaming Schoenberg–Whitney check when `check`:
/// `Err(i)` names the basis function left without data. `None` is never returned (the
/// `Option` lets the caller fall back for other degrees).
#[allow(clippy::unnecessary_wraps)]
fn normal_kernel<T: Scalar, P: ControlPoint<T>, const W: usize, const ACC: bool>(
    rows: Rows<'_, T, P>,
    check: bool,
    band: &mut [T],
    rhs: &mut [P],
) -> Option<std::result::Result<(), usize>> {
    let Rows {
        knots,
        params,
        points,
        weights,
    } = rows;
    let p = W - 1;
    let n = knots.num_basis();
    let k = knots.knots();
    let mut span = p;
    let mut cached = usize::MAX;
    // 1/(u_{s+r+1} − u_{s+1+r−j}) for the current span s, j = 1 … p, r < j.
    let mut inverse = [[T::zero(); W]; W];
    let mut next = if check { 0 } else { n };
    let mut last_assigned = T::zero();
    for (j, (&u, &q)) in params.iter().zip(points).enumerate() {
        span = knots.span_in_domain_from(u, span);
        if span != cached {
            for jj in 1..W {
                for r in 0..jj {
                    inverse[jj][r] = T::one() / (k[span + r + 1] - k[span + 1 + r - jj]);
                }
            }
            cached = span;
        }
        let mut left = [T::zero(); W];
        let mut right = [T::zero(); W];
        let mut basis = [T::zero(); W];
        basis[0] = T::one();
        for jj in 1..W {
            left[jj] = u - k[span + 1 - jj];
            right[jj] = k[span + jj] - u;
            let mut saved = T::zero();
            for r in 0..jj {
                let temp = basis[r] * inverse[jj][r];
                basis[r] = saved + right[r + 1] * temp;
                saved = left[jj - r] * temp;
            }
            basis[jj] = saved;
        }
        let f = span - p;
        if next < n {
            if span > next + p {
                return Some(Err(next));
            }
            if span >= next && basis[next - f] != T::zero() && (next == 0 || u > last_assigned) {
                last_assigned = u;
                next += 1;
            }
        }
        if !ACC {
            continue;
        }
        let w2 = weights.map_or_else(T::one, |w| w[j] * w[j]);
        for a in 0..W {
            let s = basis[a] * w2;
            rhs[f + a] += q * s;
            let row = &mut band[(f + a) * W..(f + a) * W + W];
            for c in 0..=a {
                row[a - c] += s * basis[c];
            }
        }
    }
    if next < n {
        return Some(Err(next));
    }
    Some(Ok(()))
}

/// The memory of repeated least-squares solves on one knot vector (parameter correction):
/// the band of the normal equations, factored in place, and the right-hand side.
#[derive(Clone, Debug)]
pub(crate) struct LsqWorkspace<T, P> {
    band: BandCholesky<T>,
    rhs: Vec<P>,
}

impl<T: Scalar, P: ControlPoint<T>> LeastSquares<'_, T, P> {
    /// The control points of the fit to the points at `params` (instead of the problem's
    /// parameters), written into `out` through `workspace`, which keeps its memory between
    /// calls: no allocation once it has its size. Only for the plain problem — every control
    /// point free, no smoothing, normal equations, degree at most 5 (the unrolled kernels);
    /// returns `Ok(false)` without touching `out` otherwise. The sums and the factorisation
    /// are those of [`LeastSquares::control_points`].
    ///
    /// # Errors
    /// As [`LeastSquares::control_points`].
    pub(crate) fn control_points_into(
        &self,
        params: &[T],
        workspace: &mut Option<LsqWorkspace<T, P>>,
        out: &mut [P],
    ) -> Result<bool> {
        let p = self.knots.degree();
        let n = self.knots.num_basis();
        if self.pin_ends
            || !self.fixed_points.is_empty()
            || !self.fixed_coords.is_empty()
            || self.smoothing != T::zero()
            || self.method != LsqMethod::NormalEquations
            || p > 5
            || out.len() != n
        {
            return Ok(false);
        }
        self.validate_with(params)?;
        let ws = match workspace {
            Some(ws) if ws.band.len() == n && ws.band.bandwidth() == p => ws,
            _ => workspace.insert(LsqWorkspace {
                band: BandCholesky::zeros(n, p),
                rhs: vec![P::origin(); n],
            }),
        };
        ws.band.clear();
        ws.rhs.iter_mut().for_each(|r| *r = P::origin());
        let rows = Rows {
            knots: &self.knots,
            params,
            points: self.points,
            weights: self.weights,
        };
        let data = ws.band.data_mut();
        let run = normal_dispatch::<T, P, true>(rows, self.check_sw, data, &mut ws.rhs);
        if let Some(Err(i)) = run {
            return Err(self.sw_error_with(params, i));
        }
        ws.band.factor(&|c| format!("control point {c}"))?;
        ws.band.solve(&mut ws.rhs);
        out.copy_from_slice(&ws.rhs);
        Ok(true)
    }
}

pub(super) enum Sink<T, P> {
    Normal(BandCholesky<T>, Vec<P>),
    Qr(BandQr<T, P>),
}

impl<T: Scalar, P: ControlPoint<T>> Sink<T, P> {
    #[inline]
    fn add(&mut self, first: usize, row: &mut [T], weight: T, target: P) {
        match self {
            Self::Normal(matrix, rhs) => {
                let w2 = weight * weight;
                matrix.add_outer(first, row, w2);
                for (slot, &v) in rhs[first..first + row.len()].iter_mut().zip(row.iter()) {
                    *slot += target * (v * w2);
                }
            }
            Self::Qr(qr) => {
                for v in row.iter_mut() {
                    *v *= weight;
                }
                qr.add_row(first, row, target * weight);
            }
        }
    }
}
