//! The surface container: two knot vectors and a row-major control net, with its
//! constructors, accessors and evaluation.

use super::basis::basis_into;
use super::direction::Direction;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, MAX_ORDER, Result, Scalar};

/// A tensor-product B-spline surface (seed 000 (7), seed 004 (5.1)):
///
/// $$ S(u, v) = \sum_{i=0}^{n_u - 1} \sum_{j=0}^{n_v - 1} N_{i,p}(u)\\, N_{j,q}(v)\\, P_{ij},
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
    pub(super) knots_u: KnotVector<T>,
    pub(super) knots_v: KnotVector<T>,
    pub(super) control_points: Vec<P>,
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
        match self.degrees() {
            (1, 1) => self.eval_fixed::<2>(su, sv, u, v),
            (2, 2) => self.eval_fixed::<3>(su, sv, u, v),
            (3, 3) => self.eval_fixed::<4>(su, sv, u, v),
            (4, 4) => self.eval_fixed::<5>(su, sv, u, v),
            (5, 5) => self.eval_fixed::<6>(su, sv, u, v),
            _ => self.eval_general(su, sv, u, v),
        }
    }

    /// [`Surface::eval_in_spans`] for equal degrees `N − 1` in both directions: the basis
    /// functions of [`KnotVector::basis_values_fixed`] and a fully unrolled tensor sum.
    #[inline(always)]
    fn eval_fixed<const N: usize>(&self, su: usize, sv: usize, u: T, v: T) -> P {
        let nv = self.knots_v.num_basis();
        let bu = self.knots_u.basis_values_fixed::<N>(su, u);
        let bv = self.knots_v.basis_values_fixed::<N>(sv, v);
        let first = (su + 1 - N) * nv + sv + 1 - N;
        let mut acc = P::origin();
        for (r, &nu) in bu.iter().enumerate() {
            let row = &self.control_points[first + r * nv..first + r * nv + N];
            let mut inner = row[0] * bv[0];
            for s in 1..N {
                inner += row[s] * bv[s];
            }
            acc += inner * nu;
        }
        acc
    }

    fn eval_general(&self, su: usize, sv: usize, u: T, v: T) -> P {
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
