//! Structural operations as sparse linear maps between spline spaces.

use crate::blossom::{SpanChoice, transfer_matrix};
use crate::sparse::{apply_points, check_len, csr_from_rows, identity, matmul};
use nalgebra_sparse::CsrMatrix;
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, binomial, from_count, to_f64,
};
use spline_geom::BSpline;

/// A linear map between two spline spaces: a sparse matrix (CSR) taking the coefficients on
/// the [`source`](SplineMap::source) knot vector to those on the
/// [`target`](SplineMap::target) knot vector.
///
/// Every structural operation of spline-geom is such a map: derivative, knot insertion and
/// refinement, degree elevation, Bézier extraction, restriction to a sub-interval. The same
/// matrix applies to control points of any [`ControlPoint`] type (functions, curves,
/// homogeneous points), coordinate by coordinate, and it *is* the Jacobian of the operation
/// with respect to the input coefficients (thesis (5.27)–(5.30)); maps compose by sparse
/// products ([`SplineMap::then`]), which is the chain rule.
///
/// ```
/// use spline_algebra::SplineMap;
/// use spline_core::KnotVector;
/// use spline_geom::BSpline;
/// let knots = KnotVector::new(2, vec![0.0f64, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0])?;
/// let f = BSpline::new(knots.clone(), vec![0.0, 1.0, 3.0, 2.0])?;
/// // Insert 0.5, then differentiate: one map, built once.
/// let map = SplineMap::insertion(&knots, 0.5, 1)?.then(&SplineMap::derivative(
///     &knots.with_inserted(0.5, 1)?, 1)?)?;
/// let df = map.apply_to(&f)?;
/// assert!((df.eval(1.5)? - f.derivatives(1.5, 1)?[1]).abs() < 1e-14);
/// assert_eq!(map.matrix().nrows(), df.control_points().len());
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct SplineMap<T> {
    matrix: CsrMatrix<T>,
    source: KnotVector<T>,
    target: KnotVector<T>,
}

/// The per-segment Bernstein space of degree `p` on the given breakpoints: every breakpoint
/// repeated `p + 1` times, so that segment `k` owns coefficients `(p+1)k … (p+1)k + p`.
///
/// # Errors
/// The errors of [`KnotVector::new`] (fewer than two breakpoints, unsorted, degree too high).
pub fn bernstein_space<T: Scalar>(degree: usize, breakpoints: &[T]) -> Result<KnotVector<T>> {
    if breakpoints.len() < 2 {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            "a piecewise Bernstein space needs at least two breakpoints",
        ));
    }
    if let Some(i) = (1..breakpoints.len()).find(|&i| !(breakpoints[i] > breakpoints[i - 1])) {
        return Err(Error::new(
            ErrorKind::UnsortedKnots,
            format!("breakpoints must increase strictly (breakpoint {i})"),
        ));
    }
    let mut knots = Vec::with_capacity(breakpoints.len() * (degree + 1));
    for &x in breakpoints {
        knots.extend(std::iter::repeat_n(x, degree + 1));
    }
    KnotVector::new(degree, knots)
}

/// The clamped knot vector of the same space on the domain: `p + 1` copies of each end.
pub(crate) fn clamped_knots<T: Scalar>(knots: &KnotVector<T>) -> KnotVector<T> {
    if knots.is_clamped() {
        return knots.clone();
    }
    let (a, b) = knots.domain();
    let p = knots.degree();
    let mut out = Vec::with_capacity(knots.len() + 2);
    out.extend(std::iter::repeat_n(a, p + 1));
    for (k, m) in knots.interior_breakpoints() {
        out.extend(std::iter::repeat_n(k, m));
    }
    out.extend(std::iter::repeat_n(b, p + 1));
    KnotVector::new_unchecked(p, out)
}

/// Whether `u` and `v` are the same domain.
pub(crate) fn check_same_domain<T: Scalar>(
    a: &KnotVector<T>,
    b: &KnotVector<T>,
    what: &str,
) -> Result<()> {
    if a.domain() == b.domain() {
        Ok(())
    } else {
        let (a0, a1) = a.domain();
        let (b0, b1) = b.domain();
        Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{what} need the same domain, got [{}, {}] and [{}, {}]",
                to_f64(a0),
                to_f64(a1),
                to_f64(b0),
                to_f64(b1)
            ),
        ))
    }
}

/// The block-diagonal matrix raising every Bernstein segment of degree `p` by `times`.
pub(crate) fn bernstein_elevation<T: Scalar>(
    p: usize,
    times: usize,
    segments: usize,
) -> CsrMatrix<T> {
    let ph = p + times;
    let mut local = vec![vec![T::zero(); p + 1]; ph + 1];
    for (i, row) in local.iter_mut().enumerate() {
        let inv = T::one() / binomial::<T>(ph, i);
        for (j, slot) in row
            .iter_mut()
            .enumerate()
            .take(p.min(i) + 1)
            .skip(i.saturating_sub(times))
        {
            *slot = inv * binomial::<T>(p, j) * binomial::<T>(times, i - j);
        }
    }
    let mut rows = Vec::with_capacity(segments * (ph + 1));
    for s in 0..segments {
        for row in &local {
            rows.push(
                row.iter()
                    .enumerate()
                    .filter(|(_, v)| **v != T::zero())
                    .map(|(j, &v)| (s * (p + 1) + j, v))
                    .collect(),
            );
        }
    }
    csr_from_rows(segments * (p + 1), rows)
}

impl<T: Scalar> SplineMap<T> {
    /// A map from its parts.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless the matrix is `target.num_basis() ×
    /// source.num_basis()`.
    pub fn from_parts(
        matrix: CsrMatrix<T>,
        source: KnotVector<T>,
        target: KnotVector<T>,
    ) -> Result<Self> {
        if matrix.nrows() != target.num_basis() || matrix.ncols() != source.num_basis() {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "a map from {} to {} coefficients cannot have a {}×{} matrix",
                    source.num_basis(),
                    target.num_basis(),
                    matrix.nrows(),
                    matrix.ncols()
                ),
            ));
        }
        Ok(Self {
            matrix,
            source,
            target,
        })
    }

    /// The identity map of a space.
    #[must_use]
    pub fn identity(knots: &KnotVector<T>) -> Self {
        Self {
            matrix: identity(knots.num_basis()),
            source: knots.clone(),
            target: knots.clone(),
        }
    }

    /// The sparse matrix: `target.num_basis()` rows, `source.num_basis()` columns. It is the
    /// Jacobian of the output coefficients with respect to the input ones.
    #[must_use]
    pub fn matrix(&self) -> &CsrMatrix<T> {
        &self.matrix
    }

    /// The matrix, consuming the map.
    #[must_use]
    pub fn into_matrix(self) -> CsrMatrix<T> {
        self.matrix
    }

    /// The input space.
    #[must_use]
    pub fn source(&self) -> &KnotVector<T> {
        &self.source
    }

    /// The output space.
    #[must_use]
    pub fn target(&self) -> &KnotVector<T> {
        &self.target
    }

    /// The composition "first `self`, then `next`" (matrix `next · self`): the chain rule.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] unless `next` starts where `self` ends.
    pub fn then(&self, next: &Self) -> Result<Self> {
        if next.source != self.target {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "cannot compose maps: the second map does not start in the space where the first one ends",
            ));
        }
        Ok(Self {
            matrix: matmul(&next.matrix, &self.matrix),
            source: self.source.clone(),
            target: next.target.clone(),
        })
    }

    /// Applies the map to coefficients of any point type.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are `source.num_basis()` points.
    pub fn apply<P: ControlPoint<T>>(&self, points: &[P]) -> Result<Vec<P>> {
        check_len("map input", self.matrix.ncols(), points.len())?;
        Ok(apply_points(&self.matrix, points))
    }

    /// Applies the map to a spline on the source knots, giving the spline on the target
    /// knots.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] if the spline's knots are not the source knots.
    pub fn apply_to<P: ControlPoint<T>>(&self, spline: &BSpline<T, P>) -> Result<BSpline<T, P>> {
        if spline.knots() != &self.source {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "the spline's knot vector is not the source space of the map",
            ));
        }
        Ok(BSpline::new_unchecked(
            self.target.clone(),
            apply_points(&self.matrix, spline.control_points()),
        ))
    }

    /// The derivative of order `order` (thesis (5.20)–(5.21), seed 000 (6)): the target is
    /// the degree-`(p − order)` space of [`BSpline::derivative`], whose result this map
    /// reproduces, including its treatment of knots of multiplicity `p + 1`.
    ///
    /// ```
    /// use spline_algebra::SplineMap;
    /// use spline_core::KnotVector;
    /// let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0])?;
    /// let d = SplineMap::derivative(&knots, 1)?;
    /// // (x1 − x0)·2, (x2 − x1)·2
    /// assert_eq!(d.apply(&[0.0, 1.0, 3.0])?, vec![2.0, 4.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] if `order` exceeds the degree.
    pub fn derivative(knots: &KnotVector<T>, order: usize) -> Result<Self> {
        if order > knots.degree() {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "derivative order {order} exceeds the degree {} (higher derivatives are zero)",
                    knots.degree()
                ),
            ));
        }
        let mut map = Self::identity(knots);
        for _ in 0..order {
            map = map.then(&Self::first_derivative(&map.target))?;
        }
        Ok(map)
    }

    fn first_derivative(knots: &KnotVector<T>) -> Self {
        let p = knots.degree();
        let t = knots.knots();
        let n = knots.num_basis();
        let pt = from_count::<T>(p);
        let mut rows = Vec::with_capacity(n - 1);
        let mut new_knots = Vec::with_capacity(t.len() - 2);
        for (i, &k) in t[1..t.len() - 1].iter().enumerate() {
            if i < n - 1 {
                let denom = t[i + p + 1] - t[i + 1];
                if denom > T::zero() {
                    let s = pt / denom;
                    rows.push(vec![(i, -s), (i + 1, s)]);
                    new_knots.push(k);
                }
            } else {
                new_knots.push(k);
            }
        }
        let target = KnotVector::new_unchecked(p - 1, new_knots);
        Self {
            matrix: csr_from_rows(n, rows),
            source: knots.clone(),
            target,
        }
    }

    /// The map into any space that contains the source space on the target's domain: same
    /// degree, target domain inside the source domain, and every source knot strictly
    /// inside the target domain at least as often in the target. Each row is a blossom of
    /// the source basis (the Oslo algorithm), so the map is exact.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] if the degrees differ, the target domain is not inside
    /// the source domain, or a source knot is missing from the target.
    pub fn transfer(source: &KnotVector<T>, target: &KnotVector<T>) -> Result<Self> {
        check_nested(source, target, true)?;
        Ok(Self::transfer_unchecked(source, target))
    }

    pub(crate) fn transfer_unchecked(source: &KnotVector<T>, target: &KnotVector<T>) -> Self {
        Self::transfer_with(source, target, SpanChoice::Refine)
    }

    pub(crate) fn removal_unchecked(source: &KnotVector<T>, target: &KnotVector<T>) -> Self {
        Self::transfer_with(source, target, SpanChoice::Remove)
    }

    fn transfer_with(source: &KnotVector<T>, target: &KnotVector<T>, choice: SpanChoice) -> Self {
        let matrix = if source == target {
            identity(source.num_basis())
        } else {
            transfer_matrix(source, target, choice)
        };
        Self {
            matrix,
            source: source.clone(),
            target: target.clone(),
        }
    }

    /// Exact knot removal: the map onto a *subspace* (same degree and domain, every target
    /// knot at most as often in the target as in the source). For functions that lie in the
    /// target space it returns their exact coefficients; each row is the blossom of one
    /// polynomial piece at the target knots, on the piece where the blossom extrapolates
    /// least — no tolerance, no sequential removal. For other functions the result is a
    /// local quasi-interpolant, not a best approximation.
    ///
    /// ```
    /// use spline_algebra::SplineMap;
    /// use spline_core::KnotVector;
    /// let coarse = KnotVector::new(3, vec![0.0f64, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 2.0])?;
    /// let fine = coarse.with_inserted(1.0, 2)?.with_inserted(0.5, 1)?;
    /// let up = SplineMap::transfer(&coarse, &fine)?;
    /// let down = SplineMap::knot_removal(&fine, &coarse)?;
    /// let x = [1.0, -2.0, 0.5, 3.0, 1.0];
    /// let back = down.apply(&up.apply(&x)?)?;
    /// assert!(back.iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-14));
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] if the degrees or domains differ or the target has a
    /// knot more often than the source.
    pub fn knot_removal(source: &KnotVector<T>, target: &KnotVector<T>) -> Result<Self> {
        check_nested(target, source, false)?;
        check_same_domain(source, target, "knot removal")?;
        Ok(Self::removal_unchecked(source, target))
    }

    /// Inserts the knot `u` `times` times; reproduces [`BSpline::insert_knot`].
    ///
    /// # Errors
    /// The errors of [`KnotVector::with_inserted`].
    pub fn insertion(knots: &KnotVector<T>, u: T, times: usize) -> Result<Self> {
        let target = knots.with_inserted(u, times)?;
        Ok(Self::transfer_unchecked(knots, &target))
    }

    /// Inserts all the knots (any order, repetitions allowed); reproduces
    /// [`BSpline::refine`].
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for a knot (with its index);
    /// [`ErrorKind::KnotMultiplicity`] if a multiplicity would exceed `p + 1`.
    ///
    /// # Panics
    /// Never: the `expect`s only state internal invariants (matching dimensions).
    pub fn refinement(knots: &KnotVector<T>, new_knots: &[T]) -> Result<Self> {
        for (j, &u) in new_knots.iter().enumerate() {
            knots
                .check_param(u)
                .map_err(|e| e.context(format_args!("knot {j}")))?;
        }
        let mut all = knots.knots().to_vec();
        all.extend_from_slice(new_knots);
        all.sort_by(|a, b| a.partial_cmp(b).expect("finite knots"));
        let target = KnotVector::new(knots.degree(), all)?;
        Ok(Self::transfer_unchecked(knots, &target))
    }

    /// Restriction to `[a, b]` inside the domain: the target is clamped on `[a, b]` and keeps
    /// the interior knots with their multiplicities, as [`BSpline::split`] followed by
    /// [`BSpline::clamped`] gives.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::OutOfDomain`] unless `a < b` lie in the domain.
    pub fn restriction(knots: &KnotVector<T>, a: T, b: T) -> Result<Self> {
        knots.check_param(a)?;
        knots.check_param(b)?;
        if !(a < b) {
            return Err(Error::new(
                ErrorKind::OutOfDomain,
                format!(
                    "restriction to an empty interval [{}, {}]",
                    to_f64(a),
                    to_f64(b)
                ),
            ));
        }
        let p = knots.degree();
        let mut target = Vec::with_capacity(knots.len() + 2 * p + 2);
        target.extend(std::iter::repeat_n(a, p + 1));
        target.extend(knots.knots().iter().copied().filter(|&k| k > a && k < b));
        target.extend(std::iter::repeat_n(b, p + 1));
        let target = KnotVector::new(p, target)?;
        Ok(Self::transfer_unchecked(knots, &target))
    }

    /// The clamped representation on the same domain ([`BSpline::clamped`]).
    #[must_use]
    pub fn clamping(knots: &KnotVector<T>) -> Self {
        Self::transfer_unchecked(knots, &clamped_knots(knots))
    }

    /// Bézier extraction onto the breakpoints of the domain: the target is the per-segment
    /// Bernstein space ([`bernstein_space`]); segment `k` (the `k`-th non-empty span) owns
    /// coefficients `(p+1)k … (p+1)k + p`, the control points of the `k`-th segment of
    /// [`BSpline::bezier_segments`].
    ///
    /// # Panics
    /// Never: the `expect`s only state internal invariants (matching dimensions).
    #[must_use]
    pub fn bezier_extraction(knots: &KnotVector<T>) -> Self {
        let target = bernstein_space(knots.degree(), &knots.domain_breaks())
            .expect("the domain breakpoints of a valid knot vector");
        Self::transfer_unchecked(knots, &target)
    }

    /// Bézier extraction onto a finer set of breakpoints (increasing, from the domain start
    /// to its end, containing every interior knot).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] unless the breakpoints start and end at the domain
    /// ends and contain every interior knot; the errors of [`bernstein_space`].
    pub fn bernstein(knots: &KnotVector<T>, breakpoints: &[T]) -> Result<Self> {
        let target = bernstein_space(knots.degree(), breakpoints)?;
        check_same_domain(knots, &target, "Bézier extraction onto breakpoints")?;
        check_nested(knots, &target, true)?;
        Ok(Self::transfer_unchecked(knots, &target))
    }

    /// Degree elevation by `times`: every distinct knot's multiplicity rises by `times`;
    /// unclamped knot vectors are clamped first, as in [`BSpline::elevate_degree`].
    /// Built as Bézier extraction, Bernstein elevation of each segment, and exact knot
    /// removal down to the elevated space.
    ///
    /// # Errors
    /// [`ErrorKind::DegreeTooHigh`] above [`spline_core::MAX_DEGREE`].
    pub fn elevation(knots: &KnotVector<T>, times: usize) -> Result<Self> {
        if times == 0 {
            return Ok(Self::identity(knots));
        }
        let p = knots.degree();
        spline_core::check_elevated_degree(p, times)?;
        let target = clamped_knots(knots).elevated(times)?;
        let extraction = Self::bezier_extraction(knots);
        let segments = extraction.target.num_basis() / (p + 1);
        let breakpoints = knots.domain_breaks();
        let elevated_pieces = bernstein_space(p + times, &breakpoints)?;
        let removal = Self::removal_unchecked(&elevated_pieces, &target);
        let matrix = matmul(
            &removal.matrix,
            &matmul(&bernstein_elevation(p, times, segments), &extraction.matrix),
        );
        Ok(Self {
            matrix,
            source: knots.clone(),
            target,
        })
    }
}

/// Checks that `fine` contains `coarse` on `fine`'s domain (`refine = true`: error messages
/// speak of the target; otherwise of a removal).
fn check_nested<T: Scalar>(
    coarse: &KnotVector<T>,
    fine: &KnotVector<T>,
    refine: bool,
) -> Result<()> {
    let what = if refine { "transfer" } else { "knot removal" };
    if coarse.degree() != fine.degree() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{what} between degrees {} and {}: elevate the degree first",
                coarse.degree(),
                fine.degree()
            ),
        ));
    }
    let (source, target) = if refine {
        (coarse, fine)
    } else {
        (fine, coarse)
    };
    let (sa, sb) = source.domain();
    let (ta, tb) = target.domain();
    if ta < sa || tb > sb {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{what}: the target domain [{}, {}] is not inside the source domain [{}, {}]",
                to_f64(ta),
                to_f64(tb),
                to_f64(sa),
                to_f64(sb)
            ),
        ));
    }
    let (fa, fb) = fine.domain();
    for (k, m) in coarse.breakpoints() {
        if k > fa && k < fb && fine.multiplicity(k) < m {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "{what}: knot {} appears {m} times in the coarser space but only {} times in the finer one",
                    to_f64(k),
                    fine.multiplicity(k)
                ),
            ));
        }
    }
    Ok(())
}
