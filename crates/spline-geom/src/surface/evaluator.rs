//! The surface evaluator: a tensor-product surface's piecewise polynomial form, built once,
//! behind one-point calls (what [`crate::CurveEvaluator`] is for curves).
//!
//! For every non-empty patch `[u_s, u_{s+1}) × [v_t, v_{t+1})` the form holds the Taylor
//! coefficients about the patch's lower corner,
//!
//! $$ S(u, v) = \sum_{a=0}^{p} \sum_{b=0}^{q} c_{ab}\\,(u - u_s)^a (v - v_t)^b, \qquad
//! c_{ab} = \frac{1}{a!\\,b!} \frac{\partial^{a+b} S}{\partial u^a \partial v^b}(u_s^+, v_t^+), $$
//!
//! from the surface's own partial derivatives (`c_00` is its own point at the corner), and a
//! [`SpanTable`] per direction finds the patch in constant time. A point then costs two table
//! lookups and `(p + 1)(q + 1) − 1` multiply-adds (Horner's scheme in `v` on each of the
//! `p + 1` rows, then in `u`): no division, no basis functions, no search.

use super::container::Surface;
use super::derivatives::check_finite;
use crate::bspline::{check_same_len, square_len};
use spline_core::{ControlPoint, KnotVector, Result, Scalar, SpanTable, from_count};

/// Degrees up to this have a cached form (above, the power form loses accuracy and the
/// evaluator answers through the surface).
const MAX_FORM_DEGREE: usize = 5;

/// The largest ratio of `Σ |c_ab| h_u^a h_v^b` to the largest control point of a patch for
/// which the form is used: it bounds Horner's rounding against the tensor sum of the basis
/// functions. It is the square of the curves' bound (32 per direction): the ratio is at most
/// `3^p 3^q`, so up to bicubic patches it always holds (a loss of at most about ten bits
/// against the control points' size, `1e-13` relative in `f64`).
const CONDITION: usize = 1024;

/// The homogeneous derivatives a rational evaluator keeps on the stack: orders up to 5.
pub(crate) const SMALL_SQUARE: usize = (MAX_FORM_DEGREE + 1) * (MAX_FORM_DEGREE + 1);

/// One-point evaluation of a [`Surface`] through its piecewise polynomial form, built once by
/// [`Surface::evaluator`] (see the module's formula): two constant-time span lookups and
/// `(p + 1)(q + 1) − 1` multiply-adds per point, first and higher partial derivatives from
/// the same coefficients.
///
/// Values agree with [`Surface::eval`] to the rounding of Horner's scheme (at most about a
/// thousand units in the last place of the control points' size, usually a few; a patch whose form would lose more makes the
/// evaluator answer through the surface, as do degrees 0 and above 5 and the domain's far
/// edges `u = u_{n_u}` or `v = v_{n_v}`, where the form would extrapolate). Errors are the
/// surface's: a parameter outside the domain or not finite.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::{KnotVector, Surface};
/// let knots = KnotVector::clamped_uniform(3, 6, 0.0, 1.0)?;
/// let net = (0..6)
///     .map(|i| (0..6).map(|j| Vector3::new(i as f64, j as f64, ((i * j) % 5) as f64)).collect())
///     .collect();
/// let s = Surface::from_net(knots.clone(), knots, net)?;
/// let evaluator = s.evaluator();
/// for (u, v) in [(0.0, 0.0), (0.3, 0.71), (0.5, 1.0), (1.0, 1.0)] {
///     let (fast, exact): (Vector3<f64>, Vector3<f64>) = (evaluator.eval(u, v)?, s.eval(u, v)?);
///     assert!((fast - exact).amax() < 1e-13);
/// }
/// assert!(evaluator.eval(1.5, 0.0).is_err());
/// # Ok::<(), spline_core::Error>(())
/// ```
pub struct SurfaceEvaluator<'a, T, P> {
    surface: &'a Surface<T, P>,
    form: Option<Patches<T, P>>,
}

impl<T: Scalar, P: ControlPoint<T>> Surface<T, P> {
    /// An evaluator for many one-point calls: builds the piecewise polynomial form of every
    /// patch now (a few evaluations per patch) and borrows the surface. See
    /// [`SurfaceEvaluator`].
    #[must_use]
    pub fn evaluator(&self) -> SurfaceEvaluator<'_, T, P> {
        SurfaceEvaluator {
            surface: self,
            form: Patches::new(self),
        }
    }
}

impl<T: Scalar, P: ControlPoint<T>> SurfaceEvaluator<'_, T, P> {
    /// The surface evaluated.
    #[must_use]
    pub fn surface(&self) -> &Surface<T, P> {
        self.surface
    }

    /// Whether the piecewise polynomial form is in use (`false`: every call goes through the
    /// surface, see [`SurfaceEvaluator`]).
    #[must_use]
    pub fn has_form(&self) -> bool {
        self.form.is_some()
    }

    /// The point $S(u, v)$.
    ///
    /// # Errors
    /// [`spline_core::ErrorKind::NonFinite`] or [`spline_core::ErrorKind::OutOfDomain`], as
    /// [`Surface::eval`].
    #[inline]
    pub fn eval(&self, u: T, v: T) -> Result<P> {
        if let Some(point) = self
            .form
            .as_ref()
            .and_then(|form| form.eval_inside(self.surface, u, v))
        {
            return Ok(point);
        }
        self.surface.eval(u, v)
    }

    /// All partial derivatives $\partial^{k+l} S / \partial u^k \partial v^l$ for
    /// `0 ≤ k, l ≤ order`, written into `out[k * (order + 1) + l]` as
    /// [`Surface::derivatives_into`] does (order 1: `[S, S_v, S_u, S_uv]`). Orders above the
    /// degrees are zero. No heap allocation.
    ///
    /// ```
    /// use spline_geom::{KnotVector, Surface};
    /// // s(u, v) = u² v on [0, 1]².
    /// let s = Surface::new(KnotVector::bezier(2, 0.0, 1.0)?, KnotVector::bezier(1, 0.0, 1.0)?,
    ///     vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0])?;
    /// let mut d = [0.0f64; 9];
    /// s.evaluator().derivatives_into(0.5, 0.25, 2, &mut d)?;
    /// // [s, s_v, s_vv, s_u, s_uv, s_uvv, s_uu, s_uuv, s_uuvv]
    /// let expected = [0.0625, 0.25, 0.0, 0.25, 1.0, 0.0, 0.5, 2.0, 0.0];
    /// assert!(d.iter().zip(expected).all(|(a, b): (&f64, f64)| (a - b).abs() < 1e-15));
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Surface::derivatives_into`]: [`spline_core::ErrorKind::InvalidLength`] unless
    /// `out.len() = (order + 1)²`; [`spline_core::ErrorKind::NonFinite`] or
    /// [`spline_core::ErrorKind::OutOfDomain`] for the parameters;
    /// [`spline_core::ErrorKind::NonFinite`] when a derivative overflows.
    #[inline]
    pub fn derivatives_into(&self, u: T, v: T, order: usize, out: &mut [P]) -> Result<()> {
        check_same_len(square_len(order)?, out.len())?;
        if self.derivatives_unchecked(u, v, order, out) {
            check_finite(out, u, v)
        } else {
            self.surface.derivatives_into(u, v, order, out)
        }
    }

    /// The derivatives from the form, `false` (and `out` untouched) where the form does not
    /// answer (`out` has the right length).
    #[inline]
    pub(crate) fn derivatives_unchecked(&self, u: T, v: T, order: usize, out: &mut [P]) -> bool {
        self.form
            .as_ref()
            .is_some_and(|form| form.derivatives_inside(self.surface, u, v, order, out))
    }
}

/// The Taylor coefficients of every patch and the two span tables.
struct Patches<T, P> {
    table_u: SpanTable,
    table_v: SpanTable,
    /// The domain `[start_u, end_u) × [start_v, end_v)` the form answers in.
    start_u: T,
    end_u: T,
    start_v: T,
    end_v: T,
    /// Spans in `v` (`n_v − q`): the stride between rows of patches.
    columns: usize,
    /// `(p + 1)(q + 1)` coefficients per patch, `c_ab` at `a (q + 1) + b`; patch
    /// `(s − p) columns + (t − q)` (zero for empty patches).
    coefficients: Vec<P>,
    /// `falling[j][k]` $= k!/(k-j)!$ for `j ≤ k ≤ 5`: the factor of the `k`-th coefficient in
    /// the `j`-th derivative.
    falling: [[T; MAX_FORM_DEGREE + 1]; MAX_FORM_DEGREE + 1],
}

impl<T: Scalar, P: ControlPoint<T>> Patches<T, P> {
    /// The form of `surface`, or `None` for degree 0 or above [`MAX_FORM_DEGREE`] in either
    /// direction, or where a patch's form would lose accuracy (see [`CONDITION`]).
    fn new(surface: &Surface<T, P>) -> Option<Self> {
        let (p, q) = surface.degrees();
        if !(1..=MAX_FORM_DEGREE).contains(&p) || !(1..=MAX_FORM_DEGREE).contains(&q) {
            return None;
        }
        let (ku, kv) = (surface.knots_u(), surface.knots_v());
        let (nu, nv) = surface.net_size();
        let (ka, kb) = (ku.knots(), kv.knots());
        let size = (p + 1) * (q + 1);
        let columns = nv - q;
        let mut coefficients = vec![P::origin(); (nu - p) * columns * size];
        let inverse_factorials = inverse_factorials::<T>();
        let order = p.max(q);
        let mut derivatives = [P::origin(); SMALL_SQUARE];
        let derivatives = &mut derivatives[..(order + 1) * (order + 1)];
        for s in p..nu {
            if ka[s] == ka[s + 1] {
                continue;
            }
            for t in q..nv {
                if kb[t] == kb[t + 1] {
                    continue;
                }
                let (u, v) = (ka[s], kb[t]);
                surface.derivatives_in_spans(s, t, u, v, order, derivatives);
                let first = ((s - p) * columns + t - q) * size;
                let patch = &mut coefficients[first..first + size];
                for a in 0..=p {
                    for b in 0..=q {
                        patch[a * (q + 1) + b] = derivatives[a * (order + 1) + b]
                            * (inverse_factorials[a] * inverse_factorials[b]);
                    }
                }
                patch[0] = surface.eval_in_spans(s, t, u, v);
                if !well_conditioned(surface, patch, (s, t), (ka[s + 1] - u, kb[t + 1] - v)) {
                    return None;
                }
            }
        }
        let ((start_u, end_u), (start_v, end_v)) = surface.domain();
        Some(Self {
            table_u: SpanTable::new(ku),
            table_v: SpanTable::new(kv),
            start_u,
            end_u,
            start_v,
            end_v,
            columns,
            coefficients,
            falling: falling_factorials(),
        })
    }

    /// Whether the form answers at `(u, v)`: inside the half-open domain (not NaN).
    #[inline(always)]
    fn inside(&self, u: T, v: T) -> bool {
        u >= self.start_u && u < self.end_u && v >= self.start_v && v < self.end_v
    }

    /// $S(u, v)$ from the form, `None` outside the half-open domain.
    #[inline(always)]
    fn eval_inside(&self, surface: &Surface<T, P>, u: T, v: T) -> Option<P> {
        if !self.inside(u, v) {
            return None;
        }
        let (ku, kv) = (surface.knots_u(), surface.knots_v());
        let su = self.table_u.span(ku, u);
        let sv = self.table_v.span(kv, v);
        // Equal small degrees as constants (the loops unroll; the same sums in the same
        // order as the general case).
        Some(match surface.degrees() {
            (1, 1) => self.horner_of::<2, 2>(ku, kv, (su, sv), u, v),
            (2, 2) => self.horner_of::<3, 3>(ku, kv, (su, sv), u, v),
            (3, 3) => self.horner_of::<4, 4>(ku, kv, (su, sv), u, v),
            (4, 4) => self.horner_of::<5, 5>(ku, kv, (su, sv), u, v),
            (5, 5) => self.horner_of::<6, 6>(ku, kv, (su, sv), u, v),
            (p, q) => self.horner_dyn(ku, kv, (p, q), (su, sv), u, v),
        })
    }

    /// Horner's scheme on the patch of `(su, sv)` for degrees `N − 1`, `M − 1`.
    #[inline(always)]
    fn horner_of<const N: usize, const M: usize>(
        &self,
        ku: &KnotVector<T>,
        kv: &KnotVector<T>,
        (su, sv): (usize, usize),
        u: T,
        v: T,
    ) -> P {
        let first = ((su + 1 - N) * self.columns + sv + 1 - M) * (N * M);
        let patch = &self.coefficients[first..first + N * M];
        let t = u - ku.knots()[su];
        let s = v - kv.knots()[sv];
        let row = |a: usize| -> P {
            let c: &[P; M] = patch[a * M..(a + 1) * M]
                .try_into()
                .expect("M coefficients per row");
            let mut acc = c[M - 1];
            for b in (0..M - 1).rev() {
                acc = acc * s + c[b];
            }
            acc
        };
        let mut acc = row(N - 1);
        for a in (0..N - 1).rev() {
            acc = acc * t + row(a);
        }
        acc
    }

    /// [`Patches::horner_of`] for degrees known at run time.
    fn horner_dyn(
        &self,
        ku: &KnotVector<T>,
        kv: &KnotVector<T>,
        (p, q): (usize, usize),
        (su, sv): (usize, usize),
        u: T,
        v: T,
    ) -> P {
        let m = q + 1;
        let first = ((su - p) * self.columns + sv - q) * ((p + 1) * m);
        let patch = &self.coefficients[first..first + (p + 1) * m];
        let t = u - ku.knots()[su];
        let s = v - kv.knots()[sv];
        let row = |a: usize| -> P {
            let c = &patch[a * m..(a + 1) * m];
            let mut acc = c[q];
            for b in (0..q).rev() {
                acc = acc * s + c[b];
            }
            acc
        };
        let mut acc = row(p);
        for a in (0..p).rev() {
            acc = acc * t + row(a);
        }
        acc
    }

    /// The partial derivatives on the square `0 ≤ k, l ≤ order` from the form; `false`
    /// outside the half-open domain, with `out` untouched. For each `l`, the `p + 1` rows
    /// $r_a = \sum_{b \ge l} \frac{b!}{(b-l)!} c_{ab} s^{b-l}$ (Horner in `v`), then each `k`
    /// by Horner in `u` on the rows.
    #[inline]
    fn derivatives_inside(
        &self,
        surface: &Surface<T, P>,
        u: T,
        v: T,
        order: usize,
        out: &mut [P],
    ) -> bool {
        if !self.inside(u, v) {
            return false;
        }
        let (ku, kv) = (surface.knots_u(), surface.knots_v());
        let su = self.table_u.span(ku, u);
        let sv = self.table_v.span(kv, v);
        let (p, q) = surface.degrees();
        let m = q + 1;
        let first = ((su - p) * self.columns + sv - q) * ((p + 1) * m);
        let patch = &self.coefficients[first..first + (p + 1) * m];
        let t = u - ku.knots()[su];
        let s = v - kv.knots()[sv];
        let width = order + 1;
        out.iter_mut().for_each(|o| *o = P::origin());
        let mut rows = [P::origin(); MAX_FORM_DEGREE + 1];
        for l in 0..=order.min(q) {
            let fl = &self.falling[l];
            for (a, slot) in rows[..=p].iter_mut().enumerate() {
                let c = &patch[a * m..(a + 1) * m];
                let mut acc = c[q] * fl[q];
                for b in (l..q).rev() {
                    acc = acc * s + c[b] * fl[b];
                }
                *slot = acc;
            }
            for k in 0..=order.min(p) {
                let fk = &self.falling[k];
                let mut acc = rows[p] * fk[p];
                for a in (k..p).rev() {
                    acc = acc * t + rows[a] * fk[a];
                }
                out[k * width + l] = acc;
            }
        }
        true
    }
}

/// `1/k!` for `k = 0 … 5`.
fn inverse_factorials<T: Scalar>() -> [T; MAX_FORM_DEGREE + 1] {
    let mut out = [T::one(); MAX_FORM_DEGREE + 1];
    let mut factorial = T::one();
    for (k, slot) in out.iter_mut().enumerate().skip(1) {
        factorial *= from_count::<T>(k);
        *slot = T::one() / factorial;
    }
    out
}

/// `[j][k]` $= k!/(k-j)!$ for `j ≤ k`, zero below.
fn falling_factorials<T: Scalar>() -> [[T; MAX_FORM_DEGREE + 1]; MAX_FORM_DEGREE + 1] {
    let mut out = [[T::zero(); MAX_FORM_DEGREE + 1]; MAX_FORM_DEGREE + 1];
    for (j, row) in out.iter_mut().enumerate() {
        for (k, slot) in row.iter_mut().enumerate().skip(j) {
            *slot = from_count::<T>(((k - j + 1)..=k).product::<usize>());
        }
    }
    out
}

/// Whether a patch's coefficients are finite and Horner's rounding on them stays within
/// [`CONDITION`] times the rounding of the patch's largest control point.
fn well_conditioned<T: Scalar, P: ControlPoint<T>>(
    surface: &Surface<T, P>,
    patch: &[P],
    (s, t): (usize, usize),
    (hu, hv): (T, T),
) -> bool {
    let (p, q) = surface.degrees();
    let nv = surface.net_size().1;
    let mut spread = T::zero();
    let mut power_u = T::one();
    for a in 0..=p {
        let mut power = power_u;
        for b in 0..=q {
            spread += patch[a * (q + 1) + b].max_abs() * power;
            power *= hv;
        }
        power_u *= hu;
    }
    let points = surface.control_points();
    let mut largest = T::zero();
    for i in s - p..=s {
        for point in &points[i * nv + t - q..=i * nv + t] {
            largest = largest.max(point.max_abs());
        }
    }
    patch.iter().all(ControlPoint::all_finite) && spread <= from_count::<T>(CONDITION) * largest
}
