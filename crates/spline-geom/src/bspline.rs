//! The B-spline container and its evaluation.

use crate::pieces::{PieceCache, PieceSource};
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, MAX_ORDER, Result, Scalar, from_count,
};

/// A B-spline: a degree, a [`KnotVector`] and `n` control points of any type `P` that forms a
/// vector space over `T`.
///
/// $$ C(u) = \sum_{i=0}^{n-1} N_{i,p}(u)\\, P_i, \qquad u \in [u_p, u_n]. $$
///
/// With `P = T` it is a B-spline *function*; with `P = nalgebra::SVector<T, D>` a curve in
/// `R^D`; with homogeneous points it is the container behind a NURBS curve. The container
/// is the SYNAPS `bspline::curve` of seed 000 §2.3.1; algorithms are written once on it.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::BSpline;
/// // The example curve of seed 000 §2.3.3.
/// let curve = BSpline::from_knots(
///     3,
///     vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0],
///     vec![
///         Vector2::new(0.41705, 0.10673), Vector2::new(0.28802, 0.60088),
///         Vector2::new(0.90553, 0.46053), Vector2::new(1.3203, 0.79678),
///         Vector2::new(1.8041, 0.63012), Vector2::new(1.477, 0.13012),
///     ],
/// )?;
/// assert_eq!(curve.eval(0.0)?, Vector2::new(0.41705, 0.10673)); // clamped: first point
/// assert_eq!(curve.eval(3.0)?, Vector2::new(1.477, 0.13012));   // and last point
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone)]
pub struct BSpline<T, P> {
    knots: KnotVector<T>,
    control_points: Vec<P>,
    /// The piecewise polynomial form, built on demand (not part of the value).
    pieces: PieceCache<T, P>,
}

impl<T: PartialEq, P: PartialEq> PartialEq for BSpline<T, P> {
    fn eq(&self, other: &Self) -> bool {
        self.knots == other.knots && self.control_points == other.control_points
    }
}

impl<T: std::fmt::Debug, P: std::fmt::Debug> std::fmt::Debug for BSpline<T, P> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BSpline")
            .field("knots", &self.knots)
            .field("control_points", &self.control_points)
            .finish()
    }
}

/// Accessors, for any point type (control points, [`spline_core::SymbolicPoint`]s, lines of
/// a surface's net).
impl<T: Scalar, P> BSpline<T, P> {
    /// A B-spline whose data the caller guarantees consistent (checked in debug builds).
    ///
    /// # Panics
    /// In debug builds, if the number of control points does not match the knots.
    #[must_use]
    pub fn new_unchecked(knots: KnotVector<T>, control_points: Vec<P>) -> Self {
        debug_assert_eq!(control_points.len(), knots.num_basis());
        Self {
            knots,
            control_points,
            pieces: PieceCache::default(),
        }
    }

    /// The degree `p`.
    #[inline]
    #[must_use]
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// The knot vector.
    #[inline]
    #[must_use]
    pub fn knots(&self) -> &KnotVector<T> {
        &self.knots
    }

    /// The control points.
    #[inline]
    #[must_use]
    pub fn control_points(&self) -> &[P] {
        &self.control_points
    }

    /// The number of control points `n`.
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        self.control_points.len()
    }

    /// Always `false`: a spline has at least `p + 1` control points.
    #[inline]
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.control_points.is_empty()
    }

    /// Mutable access to the control points (their number is fixed by the knots).
    #[inline]
    pub fn control_points_mut(&mut self) -> &mut [P] {
        self.pieces.invalidate();
        &mut self.control_points
    }

    /// Inserts the sorted knots `x` (A5.4) in place, no checks: the kernel of every
    /// insertion and refinement.
    pub(crate) fn refine_sorted_unchecked(&mut self, x: &[T])
    where
        T: Scalar,
        P: spline_core::VectorSpace<T>,
    {
        self.pieces.invalidate();
        crate::transfer::refine_in_place(&mut self.knots, &mut self.control_points, x);
    }

    /// Inserts copies of one knot (`x` all equal, checked) whose span is `span`.
    pub(crate) fn insert_unchecked(&mut self, span: usize, x: &[T])
    where
        T: Scalar,
        P: spline_core::VectorSpace<T>,
    {
        self.pieces.invalidate();
        crate::transfer::refine_in_spans(&mut self.knots, &mut self.control_points, x, span, span);
    }

    /// Splits the spline into its knot vector and control points.
    #[must_use]
    pub fn into_parts(self) -> (KnotVector<T>, Vec<P>) {
        (self.knots, self.control_points)
    }

    /// The parametric domain $[u_p, u_n]$.
    #[inline]
    #[must_use]
    pub fn domain(&self) -> (T, T) {
        self.knots.domain()
    }
}

impl<T: Scalar, P: ControlPoint<T>> BSpline<T, P> {
    /// A B-spline from a validated knot vector and its control points.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are exactly `n = len(knots) − p − 1` control
    /// points; [`ErrorKind::NonFinite`] if a coordinate is NaN or infinite.
    pub fn new(knots: KnotVector<T>, control_points: Vec<P>) -> Result<Self> {
        if control_points.len() != knots.num_basis() {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "{} knots of a degree-{} spline need {} control points, got {}",
                    knots.len(),
                    knots.degree(),
                    knots.num_basis(),
                    control_points.len()
                ),
            ));
        }
        if let Some(i) = control_points.iter().position(|p| !p.all_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("control point {i} is not finite"),
            ));
        }
        Ok(Self {
            knots,
            control_points,
            pieces: PieceCache::default(),
        })
    }

    /// A B-spline from a degree, raw knots and control points; validates everything.
    ///
    /// # Errors
    /// The errors of [`KnotVector::new`] and [`BSpline::new`].
    pub fn from_knots(degree: usize, knots: Vec<T>, control_points: Vec<P>) -> Result<Self> {
        Self::new(KnotVector::new(degree, knots)?, control_points)
    }

    /// The same knots with other control points (of any type).
    ///
    /// # Errors
    /// As [`BSpline::new`].
    pub fn with_control_points<Q: ControlPoint<T>>(
        &self,
        control_points: Vec<Q>,
    ) -> Result<BSpline<T, Q>> {
        BSpline::new(self.knots.clone(), control_points)
    }

    /// Applies `f` to every control point: by affine invariance, applying an affine map to
    /// the control points applies it to the curve.
    #[must_use]
    pub fn map_control_points<Q: ControlPoint<T>>(&self, f: impl FnMut(&P) -> Q) -> BSpline<T, Q> {
        BSpline::new_unchecked(
            self.knots.clone(),
            self.control_points.iter().map(f).collect(),
        )
    }

    /// The point at `u` from a known span (no checks). Degrees 1 to 5 use fixed-size
    /// kernels.
    #[inline]
    pub(crate) fn eval_in_span(&self, span: usize, u: T) -> P {
        match self.degree() {
            1 => self.combine_fixed::<2>(span, u),
            2 => self.combine_fixed::<3>(span, u),
            3 => self.combine_fixed::<4>(span, u),
            4 => self.combine_fixed::<5>(span, u),
            5 => self.combine_fixed::<6>(span, u),
            _ => self.combine_general(span, u),
        }
    }

    #[inline(always)]
    fn combine_fixed<const N: usize>(&self, span: usize, u: T) -> P {
        let basis = self.knots.basis_values_fixed::<N>(span, u);
        let points = &self.control_points[span + 1 - N..=span];
        let mut acc = points[0] * basis[0];
        for r in 1..N {
            acc += points[r] * basis[r];
        }
        acc
    }

    fn combine_general(&self, span: usize, u: T) -> P {
        let p = self.degree();
        let mut basis = [T::zero(); MAX_ORDER];
        self.knots.basis_values(span, u, &mut basis);
        let points = &self.control_points[span - p..=span];
        let mut acc = points[0] * basis[0];
        for r in 1..=p {
            acc += points[r] * basis[r];
        }
        acc
    }

    /// The point $C(u)$: basis functions (The NURBS Book A2.2) combined with the `p + 1`
    /// control points of the span. See [`BSpline::de_boor`] for the classic triangular scheme.
    ///
    /// A curve of degree 1 to 5 evaluated more times than it has spans caches a table that
    /// finds the span in constant time (with its piecewise polynomial form, which the batches
    /// use); the point itself stays the triangular scheme's, bit for bit (algorithms such as
    /// curve intersection rely on its rounding matching the derivatives'). For many
    /// one-point calls at the cached form's speed, use [`BSpline::evaluator`].
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    #[inline]
    pub fn eval(&self, u: T) -> Result<P> {
        let span = self.span_of(u)?;
        Ok(self.eval_in_span(span, u))
    }

    /// The point $C(u)$ by de Boor's algorithm (seed 000 Algorithm 2): repeated affine
    /// combinations of the `p + 1` control points of the span, in place on the stack.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn de_boor(&self, u: T) -> Result<P> {
        let span = self.knots.find_span(u)?;
        let p = self.degree();
        let knots = self.knots.knots();
        let mut d = [P::origin(); MAX_ORDER];
        d[..=p].copy_from_slice(&self.control_points[span - p..=span]);
        for r in 1..=p {
            for j in (r..=p).rev() {
                let i = span - p + j;
                let alpha = (u - knots[i]) / (knots[i + p + 1 - r] - knots[i]);
                d[j] = d[j - 1] * (T::one() - alpha) + d[j] * alpha;
            }
        }
        Ok(d[p])
    }

    /// $C(u), C'(u), …, C^{(k)}(u)$ with `k = out.len() − 1`, written into `out`. Orders above
    /// the degree are zero and cost only their writing. No heap allocation.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for `u`;
    /// [`ErrorKind::NonFinite`] when a derivative is too large for the scalar type.
    pub fn derivatives_into(&self, u: T, out: &mut [P]) -> Result<()> {
        let span = self.span_of(u)?;
        self.derivatives_in_span(span, u, out);
        check_finite_derivatives(out, u)
    }

    /// The span of `u` for the one-point methods: from the cached table when it is built
    /// (counting the call otherwise, see [`BSpline::eval`]), else by bisection.
    #[inline(always)]
    pub(crate) fn span_of(&self, u: T) -> Result<usize> {
        match self.pieces.get() {
            Some(Some(pieces)) => {
                if let Some(span) = pieces.span_inside(&self.knots, u) {
                    return Ok(span);
                }
            }
            Some(None) => {}
            None => self
                .pieces
                .count_call(self, self.knots.num_basis() - self.degree()),
        }
        self.knots.find_span(u)
    }

    /// The cached piecewise polynomial form, built now if needed (`None` where the degree
    /// or the conditioning has none).
    pub(crate) fn cached_pieces(&self) -> Option<&crate::pieces::Pieces<T, P>> {
        self.pieces.get_or_build(self)
    }

    pub(crate) fn derivatives_in_span(&self, span: usize, u: T, out: &mut [P]) {
        if out.is_empty() {
            return;
        }
        match self.degree() {
            1 => return self.derivatives_fixed::<2>(span, u, out),
            2 => return self.derivatives_fixed::<3>(span, u, out),
            3 => return self.derivatives_fixed::<4>(span, u, out),
            4 => return self.derivatives_fixed::<5>(span, u, out),
            5 => return self.derivatives_fixed::<6>(span, u, out),
            _ => {}
        }
        let p = self.degree();
        // Orders above the degree are zero: only the others are computed.
        let order = (out.len() - 1).min(p);
        let width = p + 1;
        let mut stack = [T::zero(); MAX_ORDER * MAX_ORDER];
        let table = &mut stack[..(order + 1) * width];
        self.knots.basis_derivatives(span, u, order, table);
        let points = &self.control_points[span - p..=span];
        for (k, slot) in out.iter_mut().enumerate() {
            if k > p {
                *slot = P::origin();
                continue;
            }
            let row = &table[k * width..(k + 1) * width];
            let mut acc = points[0] * row[0];
            for r in 1..=p {
                acc += points[r] * row[r];
            }
            *slot = acc;
        }
    }

    /// Derivatives for a fixed degree `N − 1` from the derivative control points of the span
    /// and the basis functions of lower degrees (The NURBS Book A3.3–A3.4).
    fn derivatives_fixed<const N: usize>(&self, span: usize, u: T, out: &mut [P]) {
        let p = N - 1;
        let rows = self.knots.basis_by_degree_fixed::<N>(span, u);
        let knots = self.knots.knots();
        let mut q = [P::origin(); N];
        q.copy_from_slice(&self.control_points[span - p..=span]);
        for (k, slot) in out.iter_mut().enumerate() {
            if k > p {
                *slot = P::origin();
                continue;
            }
            if k > 0 {
                let factor = from_count::<T>(p - k + 1);
                for i in 0..=p - k {
                    let den = knots[span + i + 1] - knots[span - p + i + k];
                    q[i] = (q[i + 1] - q[i]) * (factor / den);
                }
            }
            let basis = &rows[p - k];
            let mut acc = q[0] * basis[0];
            for i in 1..=p - k {
                acc += q[i] * basis[i];
            }
            *slot = acc;
        }
    }

    /// The derivatives $C^{(j)}(u)$ for `j = 0 … order`.
    ///
    /// ```
    /// use spline_geom::BSpline;
    /// // f(u) = u² on [0, 1] as a quadratic Bézier function.
    /// let f = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0])?;
    /// assert_eq!(f.derivatives(0.5, 3)?, vec![0.25, 1.0, 2.0, 0.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] above [`spline_core::MAX_DERIVATIVE_ORDER`];
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`].
    pub fn derivatives(&self, u: T, order: usize) -> Result<Vec<P>> {
        spline_core::check_derivative_order(order)?;
        let mut out = vec![P::origin(); order + 1];
        self.derivatives_into(u, &mut out)?;
        Ok(out)
    }

    /// Evaluates at many parameters into `out` (same length), in any order. For degrees 1 to 5
    /// a batch of at least as many parameters as spans builds the cached piecewise polynomial
    /// form (see [`BSpline::eval`]): the span from a table in constant time, then `p`
    /// multiply-adds per point. All parameters are checked before anything is written.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] if the lengths differ; [`ErrorKind::NonFinite`] or
    /// [`ErrorKind::OutOfDomain`] for the first bad parameter.
    pub fn eval_many_into(&self, params: &[T], out: &mut [P]) -> Result<()> {
        self.eval_many_map(params, out, |point| point)
    }

    /// [`BSpline::eval_many_into`] writing `map(C(u))`: the batch kernel shared with rational
    /// curves (which project each homogeneous point).
    #[inline]
    pub(crate) fn eval_many_map<Q>(
        &self,
        params: &[T],
        out: &mut [Q],
        map: impl Fn(P) -> Q,
    ) -> Result<()> {
        check_same_len(params.len(), out.len())?;
        self.check_params_in_domain(params)?;
        let pieces = match self.pieces.get() {
            Some(pieces) => pieces,
            None if params.len() >= self.knots.num_basis() - self.degree() => {
                self.pieces.get_or_build(self)
            }
            None => None,
        };
        if let Some(pieces) = pieces {
            pieces.eval_many_map(&self.knots, params, out, map, |u| {
                self.eval_in_span(self.knots.span_in_domain(u), u)
            });
        } else {
            let mut span = self.degree();
            for (slot, &u) in out.iter_mut().zip(params) {
                span = self.knots.span_in_domain_from(u, span);
                *slot = map(self.eval_in_span(span, u));
            }
        }
        Ok(())
    }

    /// Evaluates at many parameters.
    ///
    /// # Errors
    /// As [`BSpline::eval_many_into`].
    pub fn eval_many(&self, params: &[T]) -> Result<Vec<P>> {
        let mut out = vec![P::origin(); params.len()];
        self.eval_many_into(params, &mut out)?;
        Ok(out)
    }

    /// Derivatives up to `order` at many parameters: `out[i * (order + 1) + k]` $= C^{(k)}(u_i)$.
    ///
    /// # Errors
    /// As [`BSpline::eval_many_into`]; `out.len()` must be `params.len() (order + 1)`.
    pub fn derivatives_many_into(&self, params: &[T], order: usize, out: &mut [P]) -> Result<()> {
        let needed = order
            .checked_add(1)
            .and_then(|rows| rows.checked_mul(params.len()))
            .ok_or_else(|| {
                Error::new(
                    ErrorKind::InvalidLength,
                    format!(
                        "{} parameters with derivatives up to order {order} do not fit in memory",
                        params.len()
                    ),
                )
            })?;
        check_same_len(needed, out.len())?;
        self.check_params_in_domain(params)?;
        let mut span = self.degree();
        for (chunk, &u) in out.chunks_exact_mut(order + 1).zip(params) {
            span = self.knots.span_in_domain_from(u, span);
            self.derivatives_in_span(span, u, chunk);
        }
        Ok(())
    }
}

impl<T: Scalar, P: ControlPoint<T>> BSpline<T, P> {
    /// Checks a batch of parameters with one comparison each (NaN fails it); the error
    /// names the first bad parameter.
    fn check_params_in_domain(&self, params: &[T]) -> Result<()> {
        let (a, b) = self.domain();
        // Branch-free over chunks (it vectorises); only a failure looks for the first bad one.
        let inside = |chunk: &[T]| chunk.iter().fold(true, |ok, &u| ok & (u >= a) & (u <= b));
        if params.chunks(256).all(inside) {
            return Ok(());
        }
        match params.iter().position(|&u| !(u >= a && u <= b)) {
            None => Ok(()),
            Some(i) => Err(self
                .knots
                .check_param(params[i])
                .err()
                .unwrap_or_else(|| {
                    Error::new(ErrorKind::OutOfDomain, "parameter outside the domain")
                })
                .context(format_args!("parameter {i}"))),
        }
    }
}

/// `(order + 1)²`, the number of partial derivatives of a surface up to `order` in each
/// direction, without overflow.
pub(crate) fn square_len(order: usize) -> Result<usize> {
    order
        .checked_add(1)
        .and_then(|w| w.checked_mul(w))
        .ok_or_else(|| {
            Error::new(
                ErrorKind::InvalidArgument,
                format!("derivatives up to order {order} do not fit in memory"),
            )
        })
}

/// [`ErrorKind::NonFinite`] naming the first derivative that overflowed.
pub(crate) fn check_finite_derivatives<T: Scalar, P: ControlPoint<T>>(
    out: &[P],
    u: T,
) -> Result<()> {
    match out.iter().position(|p| !p.all_finite()) {
        None => Ok(()),
        Some(k) => Err(spline_core::overflow(format_args!(
            "the derivative of order {k} at u = {}",
            spline_core::to_f64(u)
        ))),
    }
}

pub(crate) fn check_same_len(expected: usize, got: usize) -> Result<()> {
    if expected == got {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::InvalidLength,
            format!("output buffer holds {got} entries, {expected} needed"),
        ))
    }
}

impl<T: Scalar, const D: usize> BSpline<T, nalgebra::SVector<T, D>> {
    /// The curve under the affine map $x \mapsto A x + b$ (B-splines are affinely invariant:
    /// mapping the control points maps the curve).
    ///
    /// ```
    /// use nalgebra::{Matrix2, Vector2};
    /// use spline_geom::BSpline;
    /// let c = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0], vec![Vector2::new(1.0, 0.0), Vector2::new(2.0, 0.0)])?;
    /// let rotated = c.transformed(&Matrix2::new(0.0, -1.0, 1.0, 0.0), &Vector2::new(0.0, 1.0));
    /// assert_eq!(rotated.eval(1.0)?, Vector2::new(0.0, 3.0));
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    #[must_use]
    pub fn transformed(
        &self,
        matrix: &nalgebra::SMatrix<T, D, D>,
        translation: &nalgebra::SVector<T, D>,
    ) -> Self {
        self.map_control_points(|p| matrix * p + translation)
    }
}

impl<T: Scalar, P: ControlPoint<T>> PieceSource<T, P> for BSpline<T, P> {
    fn knots(&self) -> &KnotVector<T> {
        &self.knots
    }

    fn control_points(&self) -> &[P] {
        BSpline::control_points(self)
    }

    fn eval_in_span(&self, span: usize, u: T) -> P {
        BSpline::eval_in_span(self, span, u)
    }

    fn derivatives_in_span(&self, span: usize, u: T, out: &mut [P]) {
        BSpline::derivatives_in_span(self, span, u, out);
    }
}
