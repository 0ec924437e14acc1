//! Products of B-spline functions (thesis §5.3.3): minimal knot vectors, the per-segment
//! Bernstein product (5.38), exact conversion to B-spline form, Jacobians and the constant
//! bilinear second derivative; dot and wedge products; sums and squares.

use crate::bilinear::SparseBilinear;
use crate::maps::{SplineMap, check_same_domain};
use crate::sparse::{add_scaled, check_len, interleave_columns, matmul};
use nalgebra::{SVector, Vector2};
use nalgebra_sparse::CsrMatrix;
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, MAX_DEGREE, Result, Scalar, binomial,
};
use spline_geom::BSpline;

/// The knot vector of the product of a degree-`p` spline on `a` and a degree-`q` spline on
/// `b` (same domain): degree `p + q`, clamped on the domain, and at each interior breakpoint
/// the smallest multiplicity that represents every such product:
///
/// - a knot of both factors (multiplicities `m_a`, `m_b`): `p + q − min(p − m_a, q − m_b)`;
/// - a knot of `a` only: `q + m_a` (the product is exactly as smooth as `a` there, `C^{p − m_a}`);
/// - a knot of `b` only: `p + m_b`.
///
/// ```
/// use spline_algebra::product_knots;
/// use spline_core::KnotVector;
/// let a = KnotVector::new(3, vec![0., 0., 0., 0., 1., 2., 2., 2., 2.])?;
/// let b = KnotVector::new(2, vec![0., 0., 0., 1., 1., 1.5, 2., 2., 2.])?;
/// let w = product_knots(&a, &b)?;
/// assert_eq!(w.degree(), 5);
/// assert_eq!(w.multiplicity(1.0), 5 - (3 - 1).min(2 - 2)); // shared: C^0
/// assert_eq!(w.multiplicity(1.5), 3 + 1); // of b only: C^1
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::SpaceMismatch`] if the domains differ. [`ErrorKind::DegreeTooHigh`] if
/// `p + q` exceeds [`spline_core::MAX_DEGREE`].
pub fn product_knots<T: Scalar>(a: &KnotVector<T>, b: &KnotVector<T>) -> Result<KnotVector<T>> {
    check_same_domain(a, b, "the factors of a product")?;
    let (p, q) = (a.degree(), b.degree());
    let d = p + q;
    if d > MAX_DEGREE {
        return Err(Error::new(
            ErrorKind::DegreeTooHigh,
            format!(
                "the product of degrees {p} and {q} is above the supported maximum {MAX_DEGREE}"
            ),
        ));
    }
    let (lo, hi) = a.domain();
    let ka = a.interior_breakpoints();
    let kb = b.interior_breakpoints();
    let mut knots = Vec::with_capacity(2 * (d + 1) + (ka.len() + kb.len()) * (d + 1));
    knots.extend(std::iter::repeat_n(lo, d + 1));
    let (mut i, mut j) = (0, 0);
    while i < ka.len() || j < kb.len() {
        let (x, m) = if j >= kb.len() || (i < ka.len() && ka[i].0 < kb[j].0) {
            let (x, ma) = ka[i];
            i += 1;
            (x, q + ma)
        } else if i >= ka.len() || kb[j].0 < ka[i].0 {
            let (x, mb) = kb[j];
            j += 1;
            (x, p + mb)
        } else {
            let (x, ma) = ka[i];
            let mb = kb[j].1;
            i += 1;
            j += 1;
            let ca = p as isize - ma as isize;
            let cb = q as isize - mb as isize;
            (x, (d as isize - ca.min(cb)) as usize)
        };
        knots.extend(std::iter::repeat_n(x, m));
    }
    knots.extend(std::iter::repeat_n(hi, d + 1));
    KnotVector::new(d, knots)
}

/// The per-segment Bernstein product (thesis (5.38)) as a block-diagonal bilinear map from
/// (degree `p` pieces) × (degree `q` pieces) to degree `p + q` pieces on `segments` segments:
/// $f_i = \sum_j \binom{p}{j}\binom{q}{i-j} / \binom{p+q}{i}\\; g_j\\, h_{i-j}$.
#[must_use]
pub fn bernstein_product<T: Scalar>(p: usize, q: usize, segments: usize) -> SparseBilinear<T> {
    let d = p + q;
    let mut local: Vec<Vec<(usize, usize, T)>> = Vec::with_capacity(d + 1);
    for i in 0..=d {
        let inv = T::one() / binomial::<T>(d, i);
        local.push(
            (i.saturating_sub(q)..=p.min(i))
                .map(|j| {
                    (
                        j,
                        i - j,
                        binomial::<T>(p, j) * binomial::<T>(q, i - j) * inv,
                    )
                })
                .collect(),
        );
    }
    let per_segment: usize = local.iter().map(Vec::len).sum();
    let mut offsets = Vec::with_capacity(segments * (d + 1) + 1);
    let mut entries = Vec::with_capacity(segments * per_segment);
    offsets.push(0);
    for s in 0..segments {
        for row in &local {
            entries.extend(
                row.iter()
                    .map(|&(j, l, v)| (s * (p + 1) + j, s * (q + 1) + l, v)),
            );
            offsets.push(entries.len());
        }
    }
    SparseBilinear::from_sorted_parts(segments * (p + 1), segments * (q + 1), offsets, entries)
}

/// The product of two spline spaces on the same domain, prepared once: Bézier extraction of
/// both factors onto the union of their breakpoints, the Bernstein product of each segment
/// (5.38), and the exact conversion of the pieces to the minimal B-spline space
/// ([`product_knots`]) by blossoming (no tolerance-based knot removal).
///
/// The product is bilinear in the coefficients `a`, `b` of the factors: `c = B(a, b)`, with
/// Jacobians `B(·, b)` and `B(a, ·)` and the constant second derivative `B`
/// ([`ProductMap::bilinear`]).
///
/// ```
/// use spline_algebra::ProductMap;
/// use spline_core::KnotVector;
/// use spline_geom::BSpline;
/// let ka = KnotVector::new(1, vec![0.0f64, 0.0, 0.5, 1.0, 1.0])?;
/// let kb = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0])?;
/// let a = BSpline::new(ka.clone(), vec![1.0, -1.0, 2.0])?;
/// let b = BSpline::new(kb.clone(), vec![0.5, 2.0, 1.0])?;
/// let map = ProductMap::new(&ka, &kb)?;
/// let c = map.product(&a, &b)?;
/// for u in [0.0, 0.3, 0.5, 0.9, 1.0] {
///     assert!((c.eval(u)? - a.eval(u)? * b.eval(u)?).abs() < 1e-14);
/// }
/// let jac = map.jacobian_left(b.control_points())?; // ∂c/∂a
/// assert_eq!((jac.nrows(), jac.ncols()), (c.control_points().len(), 3));
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct ProductMap<T> {
    left: SplineMap<T>,
    right: SplineMap<T>,
    pieces: SparseBilinear<T>,
    removal: SplineMap<T>,
}

impl<T: Scalar> ProductMap<T> {
    /// Prepares the product of the spaces `a` (degree `p`) and `b` (degree `q`).
    ///
    /// # Errors
    /// As [`product_knots`].
    pub fn new(a: &KnotVector<T>, b: &KnotVector<T>) -> Result<Self> {
        let target = product_knots(a, b)?;
        let breakpoints = target.domain_breaks();
        let left = SplineMap::transfer(a, &KnotVector::bernstein(a.degree(), &breakpoints)?)?;
        let right = SplineMap::transfer(b, &KnotVector::bernstein(b.degree(), &breakpoints)?)?;
        let segments = breakpoints.len() - 1;
        let pieces = bernstein_product(a.degree(), b.degree(), segments);
        let pieces_space = KnotVector::bernstein(a.degree() + b.degree(), &breakpoints)?;
        let removal = SplineMap::knot_removal(&pieces_space, &target)?;
        Ok(Self {
            left,
            right,
            pieces,
            removal,
        })
    }

    /// The space of the first factor.
    #[must_use]
    pub fn left(&self) -> &KnotVector<T> {
        self.left.source()
    }

    /// The space of the second factor.
    #[must_use]
    pub fn right(&self) -> &KnotVector<T> {
        self.right.source()
    }

    /// The minimal B-spline space of the product ([`product_knots`]).
    #[must_use]
    pub fn target(&self) -> &KnotVector<T> {
        self.removal.target()
    }

    /// The per-segment Bernstein space of the product (degree `p + q`, every breakpoint of
    /// either factor repeated `p + q + 1` times).
    #[must_use]
    pub fn bernstein_target(&self) -> &KnotVector<T> {
        self.removal.source()
    }

    /// The map from the per-segment Bernstein form to the minimal B-spline form.
    #[must_use]
    pub fn removal(&self) -> &SplineMap<T> {
        &self.removal
    }

    /// The Bézier extraction of the first factor onto the common segments.
    #[must_use]
    pub fn left_extraction(&self) -> &SplineMap<T> {
        &self.left
    }

    /// The Bézier extraction of the second factor onto the common segments.
    #[must_use]
    pub fn right_extraction(&self) -> &SplineMap<T> {
        &self.right
    }

    /// The Bernstein product of the segments (5.38), a bilinear map on extracted pieces.
    #[must_use]
    pub fn bernstein_pieces(&self) -> &SparseBilinear<T> {
        &self.pieces
    }

    fn check(&self, a: &[T], b: &[T]) -> Result<()> {
        check_len("first factor", self.left.matrix().ncols(), a.len())?;
        check_len("second factor", self.right.matrix().ncols(), b.len())
    }

    /// The coefficients of the product in per-segment Bernstein form (on
    /// [`ProductMap::bernstein_target`]).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] for wrong coefficient counts.
    pub fn apply_bernstein(&self, a: &[T], b: &[T]) -> Result<Vec<T>> {
        self.check(a, b)?;
        let pa = self.left.apply(a)?;
        let pb = self.right.apply(b)?;
        Ok(self.pieces.apply_unchecked(&pa, &pb))
    }

    /// The coefficients of the product on [`ProductMap::target`].
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] for wrong coefficient counts.
    pub fn apply(&self, a: &[T], b: &[T]) -> Result<Vec<T>> {
        self.removal.apply(&self.apply_bernstein(a, b)?)
    }

    /// The product of two splines on the prepared spaces.
    ///
    /// # Errors
    /// [`ErrorKind::SpaceMismatch`] if the knot vectors are not the prepared ones;
    /// [`ErrorKind::NonFinite`] when a coefficient is too large for the scalar type.
    pub fn product(&self, a: &BSpline<T, T>, b: &BSpline<T, T>) -> Result<BSpline<T, T>> {
        if a.knots() != self.left() || b.knots() != self.right() {
            return Err(Error::new(
                ErrorKind::SpaceMismatch,
                "the factors are not on the knot vectors this product was prepared for",
            ));
        }
        let coefficients = self.apply(a.control_points(), b.control_points())?;
        if !coefficients.iter().all(|&c| c.is_finite()) {
            return Err(spline_core::overflow("a coefficient of the product"));
        }
        Ok(BSpline::new_unchecked(self.target().clone(), coefficients))
    }

    /// $\partial c / \partial a$ (depends on `b` only), `target × left` sparse.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] for a wrong `b`.
    pub fn jacobian_left(&self, b: &[T]) -> Result<CsrMatrix<T>> {
        Ok(matmul(
            self.removal.matrix(),
            &self.bernstein_jacobian_left(b)?,
        ))
    }

    /// $\partial c / \partial b$ (depends on `a` only), `target × right` sparse.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] for a wrong `a`.
    pub fn jacobian_right(&self, a: &[T]) -> Result<CsrMatrix<T>> {
        Ok(matmul(
            self.removal.matrix(),
            &self.bernstein_jacobian_right(a)?,
        ))
    }

    /// [`ProductMap::jacobian_left`] for the per-segment Bernstein form.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] for a wrong `b`.
    pub fn bernstein_jacobian_left(&self, b: &[T]) -> Result<CsrMatrix<T>> {
        let pb = self.right.apply(b)?;
        Ok(matmul(&self.pieces.contract(&pb, true), self.left.matrix()))
    }

    /// [`ProductMap::jacobian_right`] for the per-segment Bernstein form.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] for a wrong `a`.
    pub fn bernstein_jacobian_right(&self, a: &[T]) -> Result<CsrMatrix<T>> {
        let pa = self.left.apply(a)?;
        Ok(matmul(
            &self.pieces.contract(&pa, false),
            self.right.matrix(),
        ))
    }

    /// The product as a bilinear map of the factors' coefficients in per-segment Bernstein
    /// form.
    ///
    /// # Panics
    /// Never: the `expect`s only state internal invariants (matching dimensions).
    #[must_use]
    pub fn bernstein_bilinear(&self) -> SparseBilinear<T> {
        self.pieces
            .compose(self.left.matrix(), self.right.matrix())
            .expect("matching dimensions")
    }

    /// The product as a bilinear map `c = B(a, b)` into the minimal B-spline space: the
    /// constant second derivative $\partial^2 c_k / \partial a_j \partial b_l = B_{kjl}$
    /// (thesis (5.37)).
    ///
    /// # Panics
    /// Never: the `expect`s only state internal invariants (matching dimensions).
    #[must_use]
    pub fn bilinear(&self) -> SparseBilinear<T> {
        self.bernstein_bilinear()
            .then(self.removal.matrix())
            .expect("matching dimensions")
    }
}

/// A product with its Jacobians with respect to the coefficients of both factors.
#[derive(Clone, Debug)]
pub struct ProductJacobians<T> {
    /// The product (minimal B-spline form).
    pub product: BSpline<T, T>,
    /// Derivatives of the product's coefficients with respect to those of the first factor
    /// (interleaved coordinates `[x1, y1, …]` for vector-valued factors).
    pub jacobian_a: CsrMatrix<T>,
    /// Derivatives with respect to the second factor.
    pub jacobian_b: CsrMatrix<T>,
}

/// The product `a(u) b(u)` of two B-spline functions on the same domain, in the minimal
/// B-spline space of [`product_knots`].
///
/// ```
/// use spline_core::KnotVector;
/// use spline_geom::BSpline;
/// let a = BSpline::from_knots(1, vec![0.0f64, 0.0, 1.0, 1.0], vec![0.0, 1.0])?; // u
/// let c = spline_algebra::product(&a, &a)?; // u²
/// assert_eq!(c.degree(), 2);
/// assert!((c.eval(0.5)? - 0.25).abs() < 1e-15);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`product_knots`].
pub fn product<T: Scalar>(a: &BSpline<T, T>, b: &BSpline<T, T>) -> Result<BSpline<T, T>> {
    ProductMap::new(a.knots(), b.knots())?.product(a, b)
}

/// [`product`] with the Jacobians of the product's coefficients.
///
/// # Errors
/// As [`product_knots`].
pub fn product_with_jacobians<T: Scalar>(
    a: &BSpline<T, T>,
    b: &BSpline<T, T>,
) -> Result<ProductJacobians<T>> {
    let map = ProductMap::new(a.knots(), b.knots())?;
    Ok(ProductJacobians {
        product: map.product(a, b)?,
        jacobian_a: map.jacobian_left(b.control_points())?,
        jacobian_b: map.jacobian_right(a.control_points())?,
    })
}

/// A square with its derivatives with respect to the coefficients of the factor.
#[derive(Clone, Debug)]
pub struct Square<T> {
    /// `a(u)²` in the minimal B-spline space.
    pub value: BSpline<T, T>,
    /// $B(\cdot, a) + B(a, \cdot)$.
    pub jacobian: CsrMatrix<T>,
    /// The constant Hessian $B + B^{\mathsf T}$ (row `k`: Hessian of coefficient `k`).
    pub hessian: SparseBilinear<T>,
}

/// The square `a(u)²` with its Jacobian and its constant Hessian.
///
/// # Errors
/// [`ErrorKind::DegreeTooHigh`] if `2p` exceeds [`spline_core::MAX_DEGREE`].
pub fn square<T: Scalar>(a: &BSpline<T, T>) -> Result<Square<T>> {
    let map = ProductMap::new(a.knots(), a.knots())?;
    let bilinear = map.bilinear();
    let (value, jacobian) = bilinear.quadratic(a.control_points())?;
    Ok(Square {
        value: BSpline::new_unchecked(map.target().clone(), value),
        jacobian,
        hessian: bilinear.symmetrized()?,
    })
}

fn coordinates<T: Scalar, P: ControlPoint<T>>(points: &[P], c: usize) -> Vec<T> {
    points.iter().map(|p| p.coord(c)).collect()
}

/// The dot product `a(u) · b(u)` of two vector-valued splines on the same domain, with the
/// Jacobians with respect to the interleaved coordinates `[a0_x, a0_y, …]`.
///
/// # Errors
/// As [`product_knots`].
pub fn dot_product<T: Scalar, const D: usize>(
    a: &BSpline<T, SVector<T, D>>,
    b: &BSpline<T, SVector<T, D>>,
) -> Result<ProductJacobians<T>> {
    let terms: Vec<(usize, usize, T)> = (0..D).map(|c| (c, c, T::one())).collect();
    combined_product(a, b, &terms)
}

/// The wedge product `a(u) ∧ b(u) = a_x b_y − a_y b_x` of two planar splines on the same
/// domain, with the Jacobians with respect to the interleaved coordinates.
///
/// # Errors
/// As [`product_knots`].
pub fn wedge_product<T: Scalar>(
    a: &BSpline<T, Vector2<T>>,
    b: &BSpline<T, Vector2<T>>,
) -> Result<ProductJacobians<T>> {
    combined_product(a, b, &[(0, 1, T::one()), (1, 0, -T::one())])
}

/// `Σ w · a_i(u) b_j(u)` over the terms `(i, j, w)` of coordinates.
fn combined_product<T: Scalar, P: ControlPoint<T>>(
    a: &BSpline<T, P>,
    b: &BSpline<T, P>,
    terms: &[(usize, usize, T)],
) -> Result<ProductJacobians<T>> {
    let map = ProductMap::new(a.knots(), b.knots())?;
    let dim = P::DIM;
    let na = a.control_points().len();
    let nb = b.control_points().len();
    let nt = map.target().num_basis();
    let mut value = vec![T::zero(); nt];
    let mut jacobian_a = CsrMatrix::zeros(nt, dim * na);
    let mut jacobian_b = CsrMatrix::zeros(nt, dim * nb);
    for &(i, j, w) in terms {
        let ai = coordinates(a.control_points(), i);
        let bj = coordinates(b.control_points(), j);
        for (v, x) in value.iter_mut().zip(map.apply(&ai, &bj)?) {
            *v += w * x;
        }
        let ja = interleave_columns(&map.jacobian_left(&bj)?, dim, i);
        let jb = interleave_columns(&map.jacobian_right(&ai)?, dim, j);
        jacobian_a = add_scaled(T::one(), &jacobian_a, w, &ja);
        jacobian_b = add_scaled(T::one(), &jacobian_b, w, &jb);
    }
    Ok(ProductJacobians {
        product: BSpline::new_unchecked(map.target().clone(), value),
        jacobian_a,
        jacobian_b,
    })
}

/// Maps taking two spaces on the same domain into a common space that contains both: degree
/// `max(p, q)` (by [`SplineMap::elevation`]) and the union of the knots (largest
/// multiplicities, clamped on the domain unless both knot vectors already agree).
///
/// # Errors
/// [`ErrorKind::SpaceMismatch`] if the domains differ.
pub fn common_space<T: Scalar>(
    a: &KnotVector<T>,
    b: &KnotVector<T>,
) -> Result<(SplineMap<T>, SplineMap<T>)> {
    check_same_domain(a, b, "a sum of splines")?;
    let d = a.degree().max(b.degree());
    let ea = SplineMap::elevation(a, d - a.degree())?;
    let eb = SplineMap::elevation(b, d - b.degree())?;
    if ea.target() == eb.target() {
        return Ok((ea, eb));
    }
    let target = ea.target().to_clamped().merged(&eb.target().to_clamped())?;
    let ta = SplineMap::transfer(ea.target(), &target)?;
    let tb = SplineMap::transfer(eb.target(), &target)?;
    Ok((ea.then(&ta)?, eb.then(&tb)?))
}

/// `alpha · a(u) + beta · b(u)` for splines of any point type on the same domain, in the
/// common space of [`common_space`].
///
/// ```
/// use spline_geom::BSpline;
/// let a = BSpline::from_knots(1, vec![0.0f64, 0.0, 1.0, 1.0], vec![0.0, 1.0])?;
/// let b = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0], vec![1.0, 0.0, 2.0, 1.0])?;
/// let s = spline_algebra::linear_combination(2.0, &a, -1.0, &b)?;
/// assert!((s.eval(0.7)? - (2.0 * a.eval(0.7)? - b.eval(0.7)?)).abs() < 1e-14);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`common_space`].
pub fn linear_combination<T: Scalar, P: ControlPoint<T>>(
    alpha: T,
    a: &BSpline<T, P>,
    beta: T,
    b: &BSpline<T, P>,
) -> Result<BSpline<T, P>> {
    let (ma, mb) = common_space(a.knots(), b.knots())?;
    let xa = ma.apply(a.control_points())?;
    let xb = mb.apply(b.control_points())?;
    let points = xa
        .into_iter()
        .zip(xb)
        .map(|(x, y)| x * alpha + y * beta)
        .collect();
    Ok(BSpline::new_unchecked(ma.target().clone(), points))
}

/// The sum `a(u) + b(u)` ([`linear_combination`]).
///
/// # Errors
/// As [`common_space`].
pub fn sum<T: Scalar, P: ControlPoint<T>>(
    a: &BSpline<T, P>,
    b: &BSpline<T, P>,
) -> Result<BSpline<T, P>> {
    linear_combination(T::one(), a, T::one(), b)
}

/// The difference `a(u) − b(u)` ([`linear_combination`]).
///
/// # Errors
/// As [`common_space`].
pub fn difference<T: Scalar, P: ControlPoint<T>>(
    a: &BSpline<T, P>,
    b: &BSpline<T, P>,
) -> Result<BSpline<T, P>> {
    linear_combination(T::one(), a, -T::one(), b)
}

/// `s · a(u)`: scaling the control points.
#[must_use]
pub fn scale<T: Scalar, P: ControlPoint<T>>(a: &BSpline<T, P>, s: T) -> BSpline<T, P> {
    a.map_control_points(|p| *p * s)
}
