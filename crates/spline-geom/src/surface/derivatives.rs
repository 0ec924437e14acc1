//! Partial derivatives of surfaces (all orders up to a bound, or one) and evaluation on
//! grids by the tensor fast path.

use super::basis::{BasisTable, SMALL_DEGREE, SMALL_TABLE, basis_into};
use super::container::Surface;
#[cfg(doc)]
use spline_core::ErrorKind;
use spline_core::{ControlPoint, MAX_ORDER, Result, Scalar};

/// Every partial derivative at `(u, v)` finite, or the surface's overflow error.
pub(super) fn check_finite<T: Scalar, P: ControlPoint<T>>(out: &[P], u: T, v: T) -> Result<()> {
    if out.iter().all(ControlPoint::all_finite) {
        Ok(())
    } else {
        Err(spline_core::overflow(format_args!(
            "a partial derivative at (u, v) = ({}, {})",
            spline_core::to_f64(u),
            spline_core::to_f64(v)
        )))
    }
}

impl<T: Scalar, P: ControlPoint<T>> Surface<T, P> {
    /// All partial derivatives $\partial^{k+l} S / \partial u^k \partial v^l$ for
    /// `0 ≤ k, l ≤ order`, written into `out[k * (order + 1) + l]` (The NURBS Book A3.6 on the
    /// full square of orders). Orders above the degrees give zero and cost only their
    /// writing. No heap allocation.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless `out.len() = (order + 1)²`;
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn derivatives_into(&self, u: T, v: T, order: usize, out: &mut [P]) -> Result<()> {
        crate::bspline::check_same_len(crate::bspline::square_len(order)?, out.len())?;
        let (su, sv) = self.find_spans(u, v)?;
        self.derivatives_in_spans(su, sv, u, v, order, out);
        check_finite(out, u, v)
    }

    pub(crate) fn derivatives_in_spans(
        &self,
        su: usize,
        sv: usize,
        u: T,
        v: T,
        order: usize,
        out: &mut [P],
    ) {
        let (p, q) = self.degrees();
        if p.max(q) <= SMALL_DEGREE {
            let mut table_u = BasisTable::<T, SMALL_TABLE>::new();
            let mut table_v = BasisTable::<T, SMALL_TABLE>::new();
            let du = table_u.fill(&self.knots_u, su, u, order);
            let dv = table_v.fill(&self.knots_v, sv, v, order);
            let mut temp = [P::origin(); SMALL_DEGREE + 1];
            self.combine_derivatives((su, sv), (du, dv), order, &mut temp, out);
        } else {
            let mut table_u = BasisTable::<T, { MAX_ORDER * MAX_ORDER }>::new();
            let mut table_v = BasisTable::<T, { MAX_ORDER * MAX_ORDER }>::new();
            let du = table_u.fill(&self.knots_u, su, u, order);
            let dv = table_v.fill(&self.knots_v, sv, v, order);
            let mut temp = [P::origin(); MAX_ORDER];
            self.combine_derivatives((su, sv), (du, dv), order, &mut temp, out);
        }
    }

    /// The partial derivatives from the basis-derivative tables of both directions (rows
    /// of `p + 1` and `q + 1`), `temp` holding at least `q + 1` points.
    #[inline]
    fn combine_derivatives(
        &self,
        spans: (usize, usize),
        tables: (&[T], &[T]),
        order: usize,
        temp: &mut [P],
        out: &mut [P],
    ) {
        // Equal small degrees as constants (the loops unroll; the same sums in the same
        // order, so the same values).
        match self.degrees() {
            (1, 1) => self.combine_derivatives_of((1, 1), spans, tables, order, temp, out),
            (2, 2) => self.combine_derivatives_of((2, 2), spans, tables, order, temp, out),
            (3, 3) => self.combine_derivatives_of((3, 3), spans, tables, order, temp, out),
            (4, 4) => self.combine_derivatives_of((4, 4), spans, tables, order, temp, out),
            (5, 5) => self.combine_derivatives_of((5, 5), spans, tables, order, temp, out),
            degrees => self.combine_derivatives_of(degrees, spans, tables, order, temp, out),
        }
    }

    /// [`Surface::combine_derivatives`] for the degrees `(p, q)` passed in.
    #[inline(always)]
    fn combine_derivatives_of(
        &self,
        (p, q): (usize, usize),
        (su, sv): (usize, usize),
        (du, dv): (&[T], &[T]),
        order: usize,
        temp: &mut [P],
        out: &mut [P],
    ) {
        let nv = self.knots_v.num_basis();
        let width = order + 1;
        out.iter_mut().for_each(|o| *o = P::origin());
        for k in 0..=order.min(p) {
            let nu_k = &du[k * (p + 1)..(k + 1) * (p + 1)];
            temp[..=q].iter_mut().for_each(|t| *t = P::origin());
            for (r, &c) in nu_k.iter().enumerate() {
                let start = (su - p + r) * nv + sv - q;
                let row = &self.control_points[start..=start + q];
                for (t, &pt) in temp[..=q].iter_mut().zip(row) {
                    *t += pt * c;
                }
            }
            for l in 0..=order.min(q) {
                let nv_l = &dv[l * (q + 1)..(l + 1) * (q + 1)];
                let mut acc = temp[0] * nv_l[0];
                for s in 1..=q {
                    acc += temp[s] * nv_l[s];
                }
                out[k * width + l] = acc;
            }
        }
    }

    /// The partial derivatives `[k][l]` $= \partial^{k+l} S / \partial u^k \partial v^l$ for
    /// `0 ≤ k, l ≤ order`.
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] above [`spline_core::MAX_DERIVATIVE_ORDER`];
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn derivatives(&self, u: T, v: T, order: usize) -> Result<Vec<Vec<P>>> {
        spline_core::check_derivative_order(order)?;
        let mut flat = vec![P::origin(); (order + 1) * (order + 1)];
        self.derivatives_into(u, v, order, &mut flat)?;
        Ok(flat.chunks_exact(order + 1).map(<[P]>::to_vec).collect())
    }

    /// The single partial derivative $\partial^{k+l} S / \partial u^k \partial v^l$ at
    /// `(u, v)`: the `k`-th basis derivatives in `u` and the `l`-th in `v` against the
    /// `(p + 1)(q + 1)` control points of the spans. Zero when `k > p` or `l > q`. No heap
    /// allocation for `k, l ≤ 3`.
    ///
    /// ```
    /// use spline_geom::{KnotVector, Surface};
    /// let k = KnotVector::bezier(2, 0.0f64, 1.0)?;
    /// // s(u, v) = u² v².
    /// let mut c = vec![0.0; 9];
    /// c[8] = 1.0;
    /// let s = Surface::new(k.clone(), k, c)?;
    /// assert!((s.derivative_at(0.5, 0.3, 1, 2)? - 2.0 * 0.5 * 2.0).abs() < 1e-14);
    /// assert_eq!(s.derivative_at(0.5, 0.3, 3, 0)?, 0.0);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn derivative_at(&self, u: T, v: T, k: usize, l: usize) -> Result<P> {
        let (su, sv) = self.find_spans(u, v)?;
        let (p, q) = self.degrees();
        if k > p || l > q {
            return Ok(P::origin());
        }
        let nv = self.knots_v.num_basis();
        let mut table_u = BasisTable::<T, { MAX_ORDER * MAX_ORDER }>::new();
        let mut table_v = BasisTable::<T, { MAX_ORDER * MAX_ORDER }>::new();
        let du = &table_u.fill(&self.knots_u, su, u, k)[k * (p + 1)..];
        let dv = &table_v.fill(&self.knots_v, sv, v, l)[l * (q + 1)..];
        let mut acc = P::origin();
        for (r, &a) in du.iter().enumerate() {
            let start = (su - p + r) * nv + sv - q;
            let row = &self.control_points[start..=start + q];
            let mut inner = row[0] * dv[0];
            for s in 1..=q {
                inner += row[s] * dv[s];
            }
            acc += inner * a;
        }
        Ok(acc)
    }

    /// Evaluates on the grid `us × vs` into `out[a * vs.len() + b]` $= S(u_a, v_b)$.
    ///
    /// The tensor fast path: the basis functions of every `v` are computed once; for each
    /// `u` the `n_v` points $\sum_i N_i(u) P_{ij}$ of the curve `v ↦ S(u, v)` are formed
    /// once (seed 004 (5.3)); then each grid point costs `q + 1` multiply-adds instead of
    /// two basis evaluations and `(p + 1)(q + 1)` multiply-adds. Parameters may come in any
    /// order (increasing order takes a constant-time span search). All parameters are
    /// checked before anything is written.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless `out.len() = us.len() · vs.len()`;
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for the first bad parameter.
    pub fn eval_grid_into(&self, us: &[T], vs: &[T], out: &mut [P]) -> Result<()> {
        crate::bspline::check_same_len(us.len() * vs.len(), out.len())?;
        for (i, &u) in us.iter().enumerate() {
            self.knots_u
                .check_param(u)
                .map_err(|e| e.context(format_args!("u parameter {i}")))?;
        }
        for (j, &v) in vs.iter().enumerate() {
            self.knots_v
                .check_param(v)
                .map_err(|e| e.context(format_args!("v parameter {j}")))?;
        }
        if vs.is_empty() {
            return Ok(());
        }
        let (p, q) = self.degrees();
        let nv = self.knots_v.num_basis();
        // Basis functions of every v: spans and q + 1 values each.
        let mut v_spans = Vec::with_capacity(vs.len());
        let mut v_basis = vec![T::zero(); vs.len() * (q + 1)];
        let mut span = q;
        let mut scratch = [T::zero(); MAX_ORDER];
        for (b, &v) in vs.iter().enumerate() {
            span = self.knots_v.span_in_domain_from(v, span);
            basis_into(&self.knots_v, span, v, &mut scratch);
            v_basis[b * (q + 1)..(b + 1) * (q + 1)].copy_from_slice(&scratch[..=q]);
            v_spans.push(span);
        }
        let mut curve = vec![P::origin(); nv];
        let mut bu = [T::zero(); MAX_ORDER];
        let mut su = p;
        for (row_out, &u) in out.chunks_exact_mut(vs.len()).zip(us) {
            su = self.knots_u.span_in_domain_from(u, su);
            basis_into(&self.knots_u, su, u, &mut bu);
            // The control points of the iso-curve v ↦ S(u, v).
            let first = (su - p) * nv;
            curve.copy_from_slice(&self.control_points[first..first + nv]);
            curve.iter_mut().for_each(|c| *c = *c * bu[0]);
            for (r, &c) in bu[1..=p].iter().enumerate() {
                let start = (su - p + r + 1) * nv;
                for (acc, &pt) in curve
                    .iter_mut()
                    .zip(&self.control_points[start..start + nv])
                {
                    *acc += pt * c;
                }
            }
            match q {
                1 => grid_row::<T, P, 2>(&curve, &v_spans, &v_basis, row_out),
                2 => grid_row::<T, P, 3>(&curve, &v_spans, &v_basis, row_out),
                3 => grid_row::<T, P, 4>(&curve, &v_spans, &v_basis, row_out),
                4 => grid_row::<T, P, 5>(&curve, &v_spans, &v_basis, row_out),
                5 => grid_row::<T, P, 6>(&curve, &v_spans, &v_basis, row_out),
                _ => {
                    for ((slot, &sv), basis) in row_out
                        .iter_mut()
                        .zip(&v_spans)
                        .zip(v_basis.chunks_exact(q + 1))
                    {
                        let pts = &curve[sv - q..=sv];
                        let mut acc = pts[0] * basis[0];
                        for s in 1..=q {
                            acc += pts[s] * basis[s];
                        }
                        *slot = acc;
                    }
                }
            }
        }
        Ok(())
    }

    /// Evaluates on the grid `us × vs` (see [`Surface::eval_grid_into`]); the result is
    /// row-major, `[a * vs.len() + b]` $= S(u_a, v_b)$.
    ///
    /// # Errors
    /// As [`Surface::eval_grid_into`].
    pub fn eval_grid(&self, us: &[T], vs: &[T]) -> Result<Vec<P>> {
        let mut out = vec![P::origin(); us.len() * vs.len()];
        self.eval_grid_into(us, vs, &mut out)?;
        Ok(out)
    }
}

/// One row of a grid for `N = q + 1`: the iso-curve's `N` control points of each `v`'s span
/// combined with its basis values, in arrays of exactly `N` entries (same sums, same order,
/// as the general loop).
#[inline(always)]
fn grid_row<T: Scalar, P: ControlPoint<T>, const N: usize>(
    curve: &[P],
    v_spans: &[usize],
    v_basis: &[T],
    row_out: &mut [P],
) {
    for ((slot, &sv), basis) in row_out.iter_mut().zip(v_spans).zip(v_basis.chunks_exact(N)) {
        let pts: &[P; N] = curve[sv + 1 - N..=sv].try_into().expect("N points");
        let basis: &[T; N] = basis.try_into().expect("N basis values");
        let mut acc = pts[0] * basis[0];
        for s in 1..N {
            acc += pts[s] * basis[s];
        }
        *slot = acc;
    }
}
