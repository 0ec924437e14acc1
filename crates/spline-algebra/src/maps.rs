//! Structural operations as sparse linear maps between spline spaces, built by running
//! spline-geom's algorithms on symbolic control points.

use crate::sparse::{apply_points, check_len, identity, matmul};
use nalgebra_sparse::CsrMatrix;
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, SymbolicPoint, to_f64,
};
use spline_geom::BSpline;

/// A linear map between two spline spaces: a sparse matrix (CSR) taking the coefficients on
/// the [`source`](SplineMap::source) knot vector to those on the
/// [`target`](SplineMap::target) knot vector.
///
/// Every structural operation of spline-geom is such a map: derivative, knot insertion and
/// refinement, exact knot removal, degree elevation, Bézier extraction, restriction to a
/// sub-interval, clamping. The map is not a second implementation: it is the operation of
/// [`BSpline`] itself run on the symbolic control points
/// $P_0, …, P_{n-1}$ ([`spline_core::SymbolicPoint`]), whose results are the rows of the
/// matrix — so applying the map and running the operation on control points cannot
/// disagree. The same matrix applies to control points of any [`ControlPoint`] type
/// (functions, curves, homogeneous points), coordinate by coordinate, and it *is* the
/// Jacobian of the operation with respect to the input coefficients (thesis
/// (5.27)–(5.30)); maps compose by sparse products ([`SplineMap::then`]), which is the chain
/// rule.
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

/// Whether `a` and `b` are the same domain.
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
            ErrorKind::SpaceMismatch,
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

/// The matrix whose rows are the symbolic points of a spline.
fn matrix_of<T: Scalar>(ncols: usize, rows: &[SymbolicPoint<T>]) -> CsrMatrix<T> {
    let mut offsets = Vec::with_capacity(rows.len() + 1);
    let mut cols = Vec::new();
    let mut values = Vec::new();
    offsets.push(0);
    for row in rows {
        for &(j, v) in row.entries() {
            cols.push(j);
            values.push(v);
        }
        offsets.push(cols.len());
    }
    CsrMatrix::try_from_csr_data(rows.len(), ncols, offsets, cols, values)
        .expect("symbolic points hold sorted, distinct indices below the source size")
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
    /// [`ErrorKind::SpaceMismatch`] unless `next` starts where `self` ends.
    pub fn then(&self, next: &Self) -> Result<Self> {
        if next.source != self.target {
            return Err(Error::new(
                ErrorKind::SpaceMismatch,
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
    /// [`ErrorKind::SpaceMismatch`] if the spline's knots are not the source knots.
    pub fn apply_to<P: ControlPoint<T>>(&self, spline: &BSpline<T, P>) -> Result<BSpline<T, P>> {
        if spline.knots() != &self.source {
            return Err(Error::new(
                ErrorKind::SpaceMismatch,
                "the spline's knot vector is not the source space of the map",
            ));
        }
        Ok(BSpline::new_unchecked(
            self.target.clone(),
            apply_points(&self.matrix, spline.control_points()),
        ))
    }

    /// The map of a structural operation: `operation` run on the symbolic control points
    /// $P_0, …, P_{n-1}$ of the source space gives the rows of the matrix.
    ///
    /// ```
    /// use spline_algebra::SplineMap;
    /// use spline_core::KnotVector;
    /// let knots = KnotVector::new(1, vec![0.0, 0.0, 1.0, 2.0, 2.0])?;
    /// let split = SplineMap::of(&knots, |s| Ok(s.split(0.5)?.0))?;
    /// assert_eq!(split.apply(&[0.0, 2.0, 4.0])?, vec![0.0, 1.0]);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// The errors of `operation`.
    pub fn of(
        source: &KnotVector<T>,
        operation: impl FnOnce(&BSpline<T, SymbolicPoint<T>>) -> Result<BSpline<T, SymbolicPoint<T>>>,
    ) -> Result<Self> {
        let n = source.num_basis();
        let symbolic = BSpline::new_unchecked(source.clone(), SymbolicPoint::units(n));
        let result = operation(&symbolic)?;
        Ok(Self {
            matrix: matrix_of(n, result.control_points()),
            source: source.clone(),
            target: result.knots().clone(),
        })
    }

    /// The derivative of order `order` (thesis (5.20)–(5.21), seed 000 (6)):
    /// [`BSpline::derivative`] on symbolic points, including its treatment of knots of
    /// multiplicity `p + 1`.
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
    /// [`ErrorKind::OrderTooHigh`] if `order` exceeds the degree.
    pub fn derivative(knots: &KnotVector<T>, order: usize) -> Result<Self> {
        Self::of(knots, |s| s.derivative(order))
    }

    /// The map into any space that contains the source space on the target's domain
    /// ([`BSpline::transferred`]): same degree, target domain inside the source domain, and
    /// every source knot strictly inside the target domain at least as often in the target.
    ///
    /// # Errors
    /// [`ErrorKind::SpaceMismatch`] if the degrees differ, the target domain is not inside
    /// the source domain, or a source knot is missing from the target.
    pub fn transfer(source: &KnotVector<T>, target: &KnotVector<T>) -> Result<Self> {
        Self::of(source, |s| s.transferred(target))
    }

    /// Exact knot removal ([`BSpline::reduced`]): the map onto a *subspace* (same degree and
    /// domain, every target knot at most as often in the target as in the source). For
    /// functions that lie in the target space it returns their exact coefficients; for
    /// other functions the result is a local quasi-interpolant, not a best approximation.
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
    /// [`ErrorKind::SpaceMismatch`] if the degrees or domains differ or the target has a
    /// knot more often than the source.
    pub fn knot_removal(source: &KnotVector<T>, target: &KnotVector<T>) -> Result<Self> {
        Self::of(source, |s| s.reduced(target))
    }

    /// Inserts the knot `u` `times` times ([`BSpline::insert_knot`]).
    ///
    /// # Errors
    /// The errors of [`KnotVector::with_inserted`].
    pub fn insertion(knots: &KnotVector<T>, u: T, times: usize) -> Result<Self> {
        Self::of(knots, |s| s.insert_knot(u, times))
    }

    /// Inserts all the knots, any order, repetitions allowed ([`BSpline::refine`]).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`] or [`ErrorKind::OutOfDomain`] for a knot (with its index);
    /// [`ErrorKind::KnotMultiplicity`] if a multiplicity would exceed `p + 1`.
    pub fn refinement(knots: &KnotVector<T>, new_knots: &[T]) -> Result<Self> {
        Self::of(knots, |s| s.refine(new_knots))
    }

    /// Restriction to `[a, b]` inside the domain ([`BSpline::restricted`]): the target is
    /// clamped on `[a, b]` and keeps the interior knots with their multiplicities.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::OutOfDomain`] unless `a < b` lie in the domain.
    pub fn restriction(knots: &KnotVector<T>, a: T, b: T) -> Result<Self> {
        Self::of(knots, |s| s.restricted(a, b))
    }

    /// The clamped representation on the same domain ([`BSpline::clamped`]).
    ///
    /// # Panics
    /// Never: clamping cannot fail.
    #[must_use]
    pub fn clamping(knots: &KnotVector<T>) -> Self {
        Self::of(knots, |s| Ok(s.clamped())).expect("clamping cannot fail")
    }

    /// Bézier extraction onto the breakpoints of the domain ([`BSpline::to_bernstein`]): the
    /// target is the per-segment Bernstein space ([`KnotVector::bezier_space`]); segment `k`
    /// owns coefficients `(p+1)k … (p+1)k + p`, the control points of the `k`-th segment of
    /// [`BSpline::bezier_segments`].
    ///
    /// # Panics
    /// Never: extraction cannot fail.
    #[must_use]
    pub fn bezier_extraction(knots: &KnotVector<T>) -> Self {
        Self::of(knots, |s| Ok(s.to_bernstein())).expect("extraction cannot fail")
    }

    /// Bézier extraction onto a finer set of breakpoints (increasing, from the domain start
    /// to its end, containing every interior knot): the transfer onto
    /// [`KnotVector::bernstein`].
    ///
    /// # Errors
    /// [`ErrorKind::SpaceMismatch`] unless the breakpoints start and end at the domain ends
    /// and contain every interior knot; the errors of [`KnotVector::bernstein`].
    pub fn bernstein(knots: &KnotVector<T>, breakpoints: &[T]) -> Result<Self> {
        let target = KnotVector::bernstein(knots.degree(), breakpoints)?;
        check_same_domain(knots, &target, "Bézier extraction onto breakpoints")?;
        Self::transfer(knots, &target)
    }

    /// Degree elevation by `times` ([`BSpline::elevate_degree`], exact by blossoming): every
    /// distinct knot's multiplicity rises by `times`; unclamped knot vectors are clamped.
    ///
    /// # Errors
    /// [`ErrorKind::DegreeTooHigh`] above [`spline_core::MAX_DEGREE`].
    pub fn elevation(knots: &KnotVector<T>, times: usize) -> Result<Self> {
        if times == 0 {
            return Ok(Self::identity(knots));
        }
        Self::of(knots, |s| s.elevate_degree(times))
    }
}
