//! Tensor-product B-spline surfaces: the container, evaluation (seed 000 Algorithm 4, with a
//! tensor fast path for grids), partial derivatives, derivative surfaces, iso-parametric
//! curves, and every structural algorithm in either direction.
//!
//! Structural algorithms are the curve algorithms of [`BSpline`] applied to the lines of the
//! control net (seed 000 §1.4.4: "apply the basic curve algorithms in each direction"): a
//! knot inserted in `u` is inserted into each of the `n_v` curves formed by a column
//! $P_{0j}, …, P_{n_u - 1, j}$ of the net. Nothing is implemented twice.

use crate::bezier::bezier_as_bspline;
use crate::bspline::BSpline;
use crate::structural::relative_scale;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, MAX_ORDER, Result, Scalar, to_f64};
use std::fmt;

/// A parametric direction of a surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Direction {
    /// The first parameter `u` (the index `i` of the control net `P_ij`).
    U,
    /// The second parameter `v` (the index `j`).
    V,
}

impl Direction {
    /// The other direction.
    #[must_use]
    pub fn other(self) -> Self {
        match self {
            Self::U => Self::V,
            Self::V => Self::U,
        }
    }
}

impl fmt::Display for Direction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::U => "u",
            Self::V => "v",
        })
    }
}

/// A tensor-product B-spline surface (seed 000 (7), seed 004 (5.1)):
///
/// $$ S(u, v) = \sum_{i=0}^{n_u - 1} \sum_{j=0}^{n_v - 1} N_{i,p}(u)\, N_{j,q}(v)\, P_{ij},
/// \qquad (u, v) \in [u_p, u_{n_u}] \times [v_q, v_{n_v}]. $$
///
/// Two validated [`KnotVector`]s (each carries its degree) and an `n_u × n_v` control net of
/// any [`ControlPoint`] type, stored row-major: `control_points()[i * n_v + j]` is $P_{ij}$,
/// `i` along `u`, `j` along `v`. With [`crate::Homogeneous`] control points it is the
/// container behind a [`crate::NurbsSurface`].
///
/// The evaluation conventions of curves apply in each direction: right limits at interior
/// knots, left limits at the end of the domain; partial derivatives above the degrees are
/// zero.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::{KnotVector, Surface};
/// // The bilinear patch z = u v on [0, 1]².
/// let s = Surface::from_net(
///     KnotVector::bezier(1, 0.0, 1.0)?,
///     KnotVector::bezier(1, 0.0, 1.0)?,
///     vec![
///         vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 1.0, 0.0)],
///         vec![Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 1.0, 1.0)],
///     ],
/// )?;
/// assert_eq!(s.eval(0.5, 0.25)?, Vector3::new(0.5, 0.25, 0.125));
/// let d = s.derivatives(0.5, 0.25, 1)?; // d[k][l] = ∂^{k+l} S / ∂u^k ∂v^l
/// assert_eq!(d[1][1], Vector3::new(0.0, 0.0, 1.0));
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Surface<T, P> {
    knots_u: KnotVector<T>,
    knots_v: KnotVector<T>,
    control_points: Vec<P>,
}

/// The `p + 1` basis functions non-zero in `span` at `t` into `out[..p + 1]`: the
/// fixed-size kernels of [`KnotVector::basis_values_fixed`] for degrees up to 5, the general
/// routine above.
#[inline]
fn basis_into<T: Scalar>(knots: &KnotVector<T>, span: usize, t: T, out: &mut [T; MAX_ORDER]) {
    #[inline(always)]
    fn fixed<T: Scalar, const N: usize>(
        knots: &KnotVector<T>,
        span: usize,
        t: T,
        out: &mut [T; MAX_ORDER],
    ) {
        out[..N].copy_from_slice(&knots.basis_values_fixed::<N>(span, t));
    }
    match knots.degree() {
        1 => fixed::<T, 2>(knots, span, t, out),
        2 => fixed::<T, 3>(knots, span, t, out),
        3 => fixed::<T, 4>(knots, span, t, out),
        4 => fixed::<T, 5>(knots, span, t, out),
        5 => fixed::<T, 6>(knots, span, t, out),
        _ => knots.basis_values(span, t, out),
    }
}

/// Working memory for basis-function derivatives, on the stack: orders above the degree
/// are zero and never stored.
struct BasisTable<T> {
    stack: [T; MAX_ORDER * MAX_ORDER],
}

impl<T: Scalar> BasisTable<T> {
    fn new() -> Self {
        Self {
            stack: [T::zero(); MAX_ORDER * MAX_ORDER],
        }
    }

    /// The derivatives of orders `0 … min(order, p)`, rows of `p + 1`.
    fn fill(&mut self, knots: &KnotVector<T>, span: usize, t: T, order: usize) -> &[T] {
        let order = order.min(knots.degree());
        let table = &mut self.stack[..(order + 1) * knots.order()];
        knots.basis_derivatives(span, t, order, table);
        table
    }
}

impl<T: Scalar, P: ControlPoint<T>> Surface<T, P> {
    /// A surface from its two knot vectors and its control net, row-major
    /// (`control_points[i * n_v + j]` is $P_{ij}$).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are exactly `n_u n_v` control points;
    /// [`ErrorKind::NonFinite`] if a coordinate is NaN or infinite.
    pub fn new(
        knots_u: KnotVector<T>,
        knots_v: KnotVector<T>,
        control_points: Vec<P>,
    ) -> Result<Self> {
        let (nu, nv) = (knots_u.num_basis(), knots_v.num_basis());
        if control_points.len() != nu * nv {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "the knot vectors (degrees {} and {}) need a net of {nu} × {nv} = {} control points, got {}",
                    knots_u.degree(),
                    knots_v.degree(),
                    nu * nv,
                    control_points.len()
                ),
            ));
        }
        if let Some(k) = control_points.iter().position(|p| !p.all_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("control point ({}, {}) is not finite", k / nv, k % nv),
            ));
        }
        Ok(Self::new_unchecked(knots_u, knots_v, control_points))
    }

    /// A surface from a control net given as rows: `net[i][j]` is $P_{ij}$, `i` along `u`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] if the net does not have `n_u` rows of `n_v` points each
    /// (the message names the first bad row); [`ErrorKind::NonFinite`].
    pub fn from_net(
        knots_u: KnotVector<T>,
        knots_v: KnotVector<T>,
        net: Vec<Vec<P>>,
    ) -> Result<Self> {
        let control_points = flatten_net(&knots_u, &knots_v, net, "control points")?;
        Self::new(knots_u, knots_v, control_points)
    }

    /// A surface from degrees, raw knots and a net of rows; validates everything.
    ///
    /// # Errors
    /// The errors of [`KnotVector::new`] and [`Surface::from_net`].
    pub fn from_knots(
        degrees: (usize, usize),
        knots_u: Vec<T>,
        knots_v: Vec<T>,
        net: Vec<Vec<P>>,
    ) -> Result<Self> {
        let ku = KnotVector::new(degrees.0, knots_u).map_err(|e| e.context("knots in u"))?;
        let kv = KnotVector::new(degrees.1, knots_v).map_err(|e| e.context("knots in v"))?;
        Self::from_net(ku, kv, net)
    }

    /// The Bézier patch (seed 004 (5.2)) of the net `net[i][j]` on $[0, 1]^2$: degrees
    /// `net.len() − 1` and `net[0].len() − 1`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] for an empty or ragged net;
    /// [`ErrorKind::DegreeTooHigh`] above [`spline_core::MAX_DEGREE`]; [`ErrorKind::NonFinite`].
    pub fn bezier(net: Vec<Vec<P>>) -> Result<Self> {
        let rows = net.len();
        let cols = net.first().map_or(0, Vec::len);
        if rows == 0 || cols == 0 {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                "a Bézier patch needs at least one control point",
            ));
        }
        Self::from_net(
            KnotVector::bezier(rows - 1, T::zero(), T::one())?,
            KnotVector::bezier(cols - 1, T::zero(), T::one())?,
            net,
        )
    }

    /// A surface whose data the caller guarantees consistent (checked in debug builds).
    ///
    /// # Panics
    /// In debug builds, if the number of control points does not match the knots.
    #[must_use]
    pub fn new_unchecked(
        knots_u: KnotVector<T>,
        knots_v: KnotVector<T>,
        control_points: Vec<P>,
    ) -> Self {
        debug_assert_eq!(
            control_points.len(),
            knots_u.num_basis() * knots_v.num_basis()
        );
        Self {
            knots_u,
            knots_v,
            control_points,
        }
    }

    /// The degrees `(p, q)` in `u` and `v`.
    #[inline]
    #[must_use]
    pub fn degrees(&self) -> (usize, usize) {
        (self.knots_u.degree(), self.knots_v.degree())
    }

    /// The degree in one direction.
    #[inline]
    #[must_use]
    pub fn degree(&self, direction: Direction) -> usize {
        self.knots(direction).degree()
    }

    /// The knot vector in `u`.
    #[inline]
    #[must_use]
    pub fn knots_u(&self) -> &KnotVector<T> {
        &self.knots_u
    }

    /// The knot vector in `v`.
    #[inline]
    #[must_use]
    pub fn knots_v(&self) -> &KnotVector<T> {
        &self.knots_v
    }

    /// The knot vector in one direction.
    #[inline]
    #[must_use]
    pub fn knots(&self, direction: Direction) -> &KnotVector<T> {
        match direction {
            Direction::U => &self.knots_u,
            Direction::V => &self.knots_v,
        }
    }

    /// The size `(n_u, n_v)` of the control net.
    #[inline]
    #[must_use]
    pub fn net_size(&self) -> (usize, usize) {
        (self.knots_u.num_basis(), self.knots_v.num_basis())
    }

    /// The control net, row-major (`[i * n_v + j]` is $P_{ij}$).
    #[inline]
    #[must_use]
    pub fn control_points(&self) -> &[P] {
        &self.control_points
    }

    /// Mutable access to the control net (its size is fixed by the knots).
    #[inline]
    pub fn control_points_mut(&mut self) -> &mut [P] {
        &mut self.control_points
    }

    /// The control point $P_{ij}$.
    ///
    /// # Panics
    /// If `i ≥ n_u` or `j ≥ n_v`.
    #[inline]
    #[must_use]
    pub fn control_point(&self, i: usize, j: usize) -> P {
        let (nu, nv) = self.net_size();
        assert!(
            i < nu && j < nv,
            "control point ({i}, {j}) of a {nu} × {nv} net"
        );
        self.control_points[i * nv + j]
    }

    /// The control net as rows: `[i][j]` is $P_{ij}$.
    #[must_use]
    pub fn control_net(&self) -> Vec<Vec<P>> {
        let nv = self.knots_v.num_basis();
        self.control_points
            .chunks_exact(nv)
            .map(<[P]>::to_vec)
            .collect()
    }

    /// Splits the surface into its knot vectors and control points.
    #[must_use]
    pub fn into_parts(self) -> (KnotVector<T>, KnotVector<T>, Vec<P>) {
        (self.knots_u, self.knots_v, self.control_points)
    }

    /// The parametric domain `((u_min, u_max), (v_min, v_max))`.
    #[inline]
    #[must_use]
    pub fn domain(&self) -> ((T, T), (T, T)) {
        (self.knots_u.domain(), self.knots_v.domain())
    }

    /// Applies `f` to every control point (by affine invariance, an affine map of the
    /// control points maps the surface).
    #[must_use]
    pub fn map_control_points<Q: ControlPoint<T>>(&self, f: impl FnMut(&P) -> Q) -> Surface<T, Q> {
        Surface::new_unchecked(
            self.knots_u.clone(),
            self.knots_v.clone(),
            self.control_points.iter().map(f).collect(),
        )
    }

    /// The knot spans of `(u, v)`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`], naming the parameter.
    #[inline]
    pub(crate) fn find_spans(&self, u: T, v: T) -> Result<(usize, usize)> {
        let su = self.knots_u.find_span(u).map_err(|e| e.context("u"))?;
        let sv = self.knots_v.find_span(v).map_err(|e| e.context("v"))?;
        Ok((su, sv))
    }

    /// The point from known spans (no checks): $\sum_r N_r(u) \sum_s N_s(v) P_{rs}$ over the
    /// `(p + 1)(q + 1)` control points of the spans.
    #[inline]
    pub(crate) fn eval_in_spans(&self, su: usize, sv: usize, u: T, v: T) -> P {
        let (p, q) = self.degrees();
        let nv = self.knots_v.num_basis();
        let mut bu = [T::zero(); MAX_ORDER];
        let mut bv = [T::zero(); MAX_ORDER];
        basis_into(&self.knots_u, su, u, &mut bu);
        basis_into(&self.knots_v, sv, v, &mut bv);
        let mut acc = P::origin();
        for (r, &nu) in bu[..=p].iter().enumerate() {
            let start = (su - p + r) * nv + sv - q;
            let row = &self.control_points[start..=start + q];
            let mut inner = row[0] * bv[0];
            for s in 1..=q {
                inner += row[s] * bv[s];
            }
            acc += inner * nu;
        }
        acc
    }

    /// The point $S(u, v)$ from the basis functions of both directions and the
    /// `(p + 1)(q + 1)` control points of the spans (seed 004 (5.12)).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    #[inline]
    pub fn eval(&self, u: T, v: T) -> Result<P> {
        let (su, sv) = self.find_spans(u, v)?;
        Ok(self.eval_in_spans(su, sv, u, v))
    }

    /// The point $S(u, v)$ by seed 000 Algorithm 4: de Boor's algorithm in `v` on the
    /// `p + 1` rows of the span, then in `u` on the results (all on the stack).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn de_boor(&self, u: T, v: T) -> Result<P> {
        let (su, sv) = self.find_spans(u, v)?;
        let (p, q) = self.degrees();
        let nv = self.knots_v.num_basis();
        let mut column = [P::origin(); MAX_ORDER];
        let mut row = [P::origin(); MAX_ORDER];
        for (r, slot) in column[..=p].iter_mut().enumerate() {
            let start = (su - p + r) * nv + sv - q;
            row[..=q].copy_from_slice(&self.control_points[start..=start + q]);
            *slot = de_boor_local(&self.knots_v, sv, v, &mut row);
        }
        Ok(de_boor_local(&self.knots_u, su, u, &mut column))
    }

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
        let nv = self.knots_v.num_basis();
        let width = order + 1;
        let mut table_u = BasisTable::new();
        let mut table_v = BasisTable::new();
        let du = table_u.fill(&self.knots_u, su, u, order);
        let dv = table_v.fill(&self.knots_v, sv, v, order);
        out.iter_mut().for_each(|o| *o = P::origin());
        let mut temp = [P::origin(); MAX_ORDER];
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
    /// [`ErrorKind::InvalidArgument`] above [`spline_core::MAX_DERIVATIVE_ORDER`];
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
        let mut table_u = BasisTable::new();
        let mut table_v = BasisTable::new();
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

    /// The `n_v` curves (direction `U`) formed by the columns $P_{0j}, …, P_{n_u-1,j}$ of
    /// the net with the knots in `u`, or the `n_u` curves (direction `V`) formed by its rows
    /// with the knots in `v`. A surface is a curve of such curves (seed 004 (5.3), (5.6)).
    #[must_use]
    pub fn control_curves(&self, direction: Direction) -> Vec<BSpline<T, P>> {
        let (nu, nv) = self.net_size();
        match direction {
            Direction::U => (0..nv)
                .map(|j| {
                    BSpline::new_unchecked(
                        self.knots_u.clone(),
                        (0..nu).map(|i| self.control_points[i * nv + j]).collect(),
                    )
                })
                .collect(),
            Direction::V => self
                .control_points
                .chunks_exact(nv)
                .map(|row| BSpline::new_unchecked(self.knots_v.clone(), row.to_vec()))
                .collect(),
        }
    }

    /// Reassembles a surface from [`Surface::control_curves`] (all with the same knots).
    fn from_control_curves(
        direction: Direction,
        other: KnotVector<T>,
        curves: &[BSpline<T, P>],
    ) -> Self {
        let knots = curves[0].knots().clone();
        debug_assert!(curves.iter().all(|c| c.knots() == &knots));
        match direction {
            Direction::U => {
                let nu = knots.num_basis();
                let nv = curves.len();
                let mut points = Vec::with_capacity(nu * nv);
                for i in 0..nu {
                    points.extend(curves.iter().map(|c| c.control_points()[i]));
                }
                Self::new_unchecked(knots, other, points)
            }
            Direction::V => {
                let points = curves
                    .iter()
                    .flat_map(|c| c.control_points().iter().copied())
                    .collect();
                Self::new_unchecked(other, knots, points)
            }
        }
    }

    /// Applies a curve algorithm to every control curve in `direction` (see
    /// [`Surface::control_curves`]) and reassembles the surface. `f` must map curves with
    /// equal knots to curves with equal knots, as every structural algorithm does.
    ///
    /// ```
    /// use spline_geom::{Direction, Surface};
    /// let s = Surface::bezier(vec![vec![0.0, 1.0], vec![2.0, 3.0], vec![4.0, 6.0]])?;
    /// let r = s.map_curves(Direction::U, |c| Ok(c.reversed()))?;
    /// assert_eq!(r.eval(0.25, 0.5)?, s.eval(0.75, 0.5)?);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// The first error of `f`; [`ErrorKind::InvalidArgument`] if `f` returns curves with
    /// different knot vectors.
    pub fn map_curves(
        &self,
        direction: Direction,
        mut f: impl FnMut(&BSpline<T, P>) -> Result<BSpline<T, P>>,
    ) -> Result<Self> {
        let curves = self
            .control_curves(direction)
            .iter()
            .map(&mut f)
            .collect::<Result<Vec<_>>>()?;
        if curves.windows(2).any(|w| w[0].knots() != w[1].knots()) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "the control curves ended with different knot vectors",
            ));
        }
        Ok(Self::from_control_curves(
            direction,
            self.knots(direction.other()).clone(),
            &curves,
        ))
    }

    /// The iso-parametric curve `v ↦ S(u, v)` at fixed `u` (seed 004 (5.6)): a B-spline in
    /// `v` with control points $P_j(u) = \sum_i N_i(u) P_{ij}$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn curve_at_u(&self, u: T) -> Result<BSpline<T, P>> {
        let points = self
            .control_curves(Direction::U)
            .iter()
            .map(|c| c.eval(u))
            .collect::<Result<Vec<_>>>()?;
        Ok(BSpline::new_unchecked(self.knots_v.clone(), points))
    }

    /// The iso-parametric curve `u ↦ S(u, v)` at fixed `v` (seed 004 (5.3)): a B-spline in
    /// `u` with control points $P_i(v) = \sum_j N_j(v) P_{ij}$.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn curve_at_v(&self, v: T) -> Result<BSpline<T, P>> {
        let points = self
            .control_curves(Direction::V)
            .iter()
            .map(|c| c.eval(v))
            .collect::<Result<Vec<_>>>()?;
        Ok(BSpline::new_unchecked(self.knots_u.clone(), points))
    }

    /// The iso-parametric curve with the parameter of direction `fixed` held at `value`:
    /// [`Surface::curve_at_u`] or [`Surface::curve_at_v`].
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn iso_curve(&self, fixed: Direction, value: T) -> Result<BSpline<T, P>> {
        match fixed {
            Direction::U => self.curve_at_u(value),
            Direction::V => self.curve_at_v(value),
        }
    }

    /// The partial derivative $\partial^{k+l} S / \partial u^k \partial v^l$ as a B-spline
    /// surface of degrees `(p − k, q − l)` (seed 004 (5.10)–(5.11), applied `k` and `l`
    /// times), built with [`BSpline::derivative`] on the control curves.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] if `k > p` or `l > q` (those derivatives are zero).
    pub fn derivative_surface(&self, k: usize, l: usize) -> Result<Self> {
        let mut s = self.clone();
        if k > 0 {
            s = s
                .map_curves(Direction::U, |c| c.derivative(k))
                .map_err(|e| e.context("direction u"))?;
        }
        if l > 0 {
            s = s
                .map_curves(Direction::V, |c| c.derivative(l))
                .map_err(|e| e.context("direction v"))?;
        }
        Ok(s)
    }

    /// Inserts the knot `t` `times` times in `direction` (seed 000 FIG. 12) without changing
    /// the surface.
    ///
    /// ```
    /// use spline_geom::{Direction, Surface};
    /// let s = Surface::bezier(vec![vec![0.0f64, 1.0, 0.5], vec![2.0, 3.0, 1.0], vec![4.0, 6.0, 2.0]])?;
    /// let t = s.insert_knot(Direction::V, 0.25, 2)?;
    /// assert_eq!(t.net_size(), (3, 5));
    /// assert!((t.eval(0.3, 0.7)? - s.eval(0.3, 0.7)?).abs() < 1e-15);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSpline::insert_knot`].
    pub fn insert_knot(&self, direction: Direction, t: T, times: usize) -> Result<Self> {
        self.map_curves(direction, |c| c.insert_knot(t, times))
            .map_err(|e| e.context(format_args!("direction {direction}")))
    }

    /// Inserts many knots in `direction` at once (knot refinement, The NURBS Book A5.5).
    ///
    /// # Errors
    /// As [`BSpline::refine`].
    pub fn refine(&self, direction: Direction, knots: &[T]) -> Result<Self> {
        self.map_curves(direction, |c| c.refine(knots))
            .map_err(|e| e.context(format_args!("direction {direction}")))
    }

    /// Removes the interior knot `t` of `direction` `times` times if the surface moves by at
    /// most `tolerance` (absolute). Every control curve is checked exactly (see
    /// [`BSpline::remove_knot_within`]); by the partition of unity in the other direction,
    /// the largest change of a control curve bounds the change of the surface.
    ///
    /// # Errors
    /// As [`BSpline::remove_knot_within`].
    pub fn remove_knot_within(
        &self,
        direction: Direction,
        t: T,
        times: usize,
        tolerance: T,
    ) -> Result<Self> {
        self.map_curves(direction, |c| c.remove_knot_within(t, times, tolerance))
            .map_err(|e| e.context(format_args!("direction {direction}")))
    }

    /// [`Surface::remove_knot_within`] with a tolerance relative to the size of the control
    /// net (its largest coordinate magnitude, or 1 if that is smaller).
    ///
    /// # Errors
    /// As [`BSpline::remove_knot_within`].
    pub fn remove_knot(
        &self,
        direction: Direction,
        t: T,
        times: usize,
        relative_tolerance: T,
    ) -> Result<Self> {
        let scale = relative_scale(self.control_points.iter().map(ControlPoint::max_abs));
        self.remove_knot_within(direction, t, times, relative_tolerance * scale)
    }

    /// Raises the degree in `direction` by `times` (seed 000 FIG. 13; The NURBS Book A5.10).
    ///
    /// # Errors
    /// As [`BSpline::elevate_degree`].
    pub fn elevate_degree(&self, direction: Direction, times: usize) -> Result<Self> {
        self.map_curves(direction, |c| c.elevate_degree(times))
            .map_err(|e| e.context(format_args!("direction {direction}")))
    }

    /// Splits the surface at `t` in `direction` (seed 000 FIG. 11) into two surfaces, both
    /// clamped at `t`, on the two halves of the domain.
    ///
    /// # Errors
    /// As [`BSpline::split`].
    pub fn split(&self, direction: Direction, t: T) -> Result<(Self, Self)> {
        let (a, b) = self.knots(direction).domain();
        if !(t.is_finite() && t > a && t < b) {
            return Err(Error::new(
                ErrorKind::OutOfDomain,
                format!(
                    "split parameter {} must lie strictly inside the domain [{}, {}] of direction {direction}",
                    to_f64(t),
                    to_f64(a),
                    to_f64(b)
                ),
            ));
        }
        let mut lefts = Vec::new();
        let mut rights = Vec::new();
        for c in self.control_curves(direction) {
            let (l, r) = c.split(t)?;
            lefts.push(l);
            rights.push(r);
        }
        let other = self.knots(direction.other()).clone();
        Ok((
            Self::from_control_curves(direction, other.clone(), &lefts),
            Self::from_control_curves(direction, other, &rights),
        ))
    }

    /// [`Surface::map_curves`] for an infallible curve algorithm.
    fn map_curves_with(
        &self,
        direction: Direction,
        f: impl FnMut(&BSpline<T, P>) -> BSpline<T, P>,
    ) -> Self {
        let curves: Vec<_> = self.control_curves(direction).iter().map(f).collect();
        Self::from_control_curves(direction, self.knots(direction.other()).clone(), &curves)
    }

    /// The same surface with clamped knots in both directions (it then interpolates the
    /// four corners of its net, seed 004 (5.9)).
    #[must_use]
    pub fn clamped(&self) -> Self {
        self.map_curves_with(Direction::U, BSpline::clamped)
            .map_curves_with(Direction::V, BSpline::clamped)
    }

    /// The same surface traversed backwards in `direction`.
    #[must_use]
    pub fn reversed(&self, direction: Direction) -> Self {
        self.map_curves_with(direction, BSpline::reversed)
    }

    /// The same surface with the domain of `direction` mapped affinely onto `[a, b]`.
    ///
    /// # Errors
    /// [`ErrorKind::EmptyDomain`] unless `a < b`; [`ErrorKind::NonFinite`].
    pub fn reparametrized(&self, direction: Direction, a: T, b: T) -> Result<Self> {
        let knots = self.knots(direction).reparametrized(a, b)?;
        Ok(match direction {
            Direction::U => {
                Self::new_unchecked(knots, self.knots_v.clone(), self.control_points.clone())
            }
            Direction::V => {
                Self::new_unchecked(self.knots_u.clone(), knots, self.control_points.clone())
            }
        })
    }

    /// The surface with `u` and `v` exchanged: $\tilde S(v, u) = S(u, v)$.
    #[must_use]
    pub fn transposed(&self) -> Self {
        let (nu, nv) = self.net_size();
        let mut points = Vec::with_capacity(nu * nv);
        for j in 0..nv {
            points.extend((0..nu).map(|i| self.control_points[i * nv + j]));
        }
        Self::new_unchecked(self.knots_v.clone(), self.knots_u.clone(), points)
    }

    /// The strips of the surface between consecutive distinct knots of `direction`, each a
    /// Bézier in that direction on its own interval.
    fn bezier_strips(&self, direction: Direction) -> Vec<Self> {
        let segments: Vec<_> = self
            .control_curves(direction)
            .iter()
            .map(BSpline::bezier_segments)
            .collect();
        let other = self.knots(direction.other()).clone();
        (0..segments[0].len())
            .map(|s| {
                let curves: Vec<_> = segments
                    .iter()
                    .map(|segs| bezier_as_bspline(&segs[s]))
                    .collect();
                Self::from_control_curves(direction, other.clone(), &curves)
            })
            .collect()
    }

    /// The Bézier patches of the surface: `[a][b]` is the patch over the `a`-th non-empty
    /// knot span in `u` and the `b`-th in `v`, a Bézier surface (seed 004 (5.2)) on that
    /// rectangle (knots of multiplicity `p + 1`, `q + 1` at its ends).
    #[must_use]
    pub fn bezier_patches(&self) -> Vec<Vec<Self>> {
        self.bezier_strips(Direction::U)
            .iter()
            .map(|strip| strip.bezier_strips(Direction::V))
            .collect()
    }
}

/// de Boor's triangular scheme on the `p + 1` points of span `span`, in place.
fn de_boor_local<T: Scalar, P: ControlPoint<T>>(
    knots: &KnotVector<T>,
    span: usize,
    t: T,
    d: &mut [P; MAX_ORDER],
) -> P {
    let p = knots.degree();
    let k = knots.knots();
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = span - p + j;
            let alpha = (t - k[i]) / (k[i + p + 1 - r] - k[i]);
            d[j] = d[j - 1] * (T::one() - alpha) + d[j] * alpha;
        }
    }
    d[p]
}

/// Flattens a net of rows, checking its shape against the knot vectors.
pub(crate) fn flatten_net<T: Scalar, Q: Clone>(
    knots_u: &KnotVector<T>,
    knots_v: &KnotVector<T>,
    net: Vec<Vec<Q>>,
    what: &str,
) -> Result<Vec<Q>> {
    let (nu, nv) = (knots_u.num_basis(), knots_v.num_basis());
    if net.len() != nu {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "{} knots of degree {} in u need {nu} rows of {what}, got {}",
                knots_u.len(),
                knots_u.degree(),
                net.len()
            ),
        ));
    }
    if let Some(i) = net.iter().position(|row| row.len() != nv) {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "{} knots of degree {} in v need {nv} {what} in every row, row {i} has {}",
                knots_v.len(),
                knots_v.degree(),
                net[i].len()
            ),
        ));
    }
    Ok(net.into_iter().flatten().collect())
}
