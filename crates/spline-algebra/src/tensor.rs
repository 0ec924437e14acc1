//! Tensor-product (bivariate) splines: structural maps with Kronecker structure, products,
//! all partial derivatives, the convexity function `s_uu s_vv − s_uv²` with its gradient and
//! constant Hessian (thesis §5.6), and the ridge polynomials of §5.7.
//!
//! The splines are [`Surface`]s of spline-geom (scalar control points for functions): the
//! row-major net, `i` along `u`, is the coefficient vector the maps act on.

use crate::bilinear::SparseBilinear;
use crate::maps::SplineMap;
use crate::product::{ProductMap, common_space};
use crate::sparse::{check_len, kron};
use nalgebra_sparse::CsrMatrix;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, binomial, cast};
use spline_geom::Surface;

/// Applies `A_u ⊗ A_v` to a row-major grid without forming the Kronecker product.
pub(crate) fn apply_tensor<T: Scalar, P: ControlPoint<T>>(
    mu: &CsrMatrix<T>,
    mv: &CsrMatrix<T>,
    grid: &[P],
) -> Vec<P> {
    let (nu, nv) = (mu.ncols(), mv.ncols());
    debug_assert_eq!(grid.len(), nu * nv);
    // Along v for every row.
    let mut rows = Vec::with_capacity(nu * mv.nrows());
    for i in 0..nu {
        rows.extend(crate::sparse::apply_points(mv, &grid[i * nv..(i + 1) * nv]));
    }
    let mv_rows = mv.nrows();
    let mut out = vec![P::origin(); mu.nrows() * mv_rows];
    for (r, row) in mu.row_iter().enumerate() {
        for (&i, &w) in row.col_indices().iter().zip(row.values()) {
            for j in 0..mv_rows {
                out[r * mv_rows + j] += rows[i * mv_rows + j] * w;
            }
        }
    }
    out
}

/// A linear map between tensor-product spline spaces with Kronecker structure: a
/// [`SplineMap`] in `u` and one in `v`, acting on row-major grids as $A_u \otimes A_v$.
///
/// ```
/// use spline_algebra::TensorMap;
/// use spline_core::KnotVector;
/// use spline_geom::Surface;
/// let k = KnotVector::new(2, vec![0.0f64, 0.0, 0.0, 1.0, 1.0, 1.0])?;
/// // s(u, v) = u² v².
/// let mut c = vec![0.0; 9];
/// c[8] = 1.0;
/// let s = Surface::new(k.clone(), k.clone(), c)?;
/// let d = TensorMap::partial_derivative(&k, &k, 1, 2)?; // ∂³/∂u∂v²
/// let suvv = d.apply(&s)?;
/// assert!((suvv.eval(0.5, 0.3)? - 2.0 * 0.5 * 2.0).abs() < 1e-14);
/// assert_eq!(d.matrix().nrows(), suvv.control_points().len());
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct TensorMap<T> {
    u: SplineMap<T>,
    v: SplineMap<T>,
}

impl<T: Scalar> TensorMap<T> {
    /// The map `u ⊗ v`.
    #[must_use]
    pub fn new(u: SplineMap<T>, v: SplineMap<T>) -> Self {
        Self { u, v }
    }

    /// A map acting in `u` only (identity in `v`).
    #[must_use]
    pub fn along_u(u: SplineMap<T>, knots_v: &KnotVector<T>) -> Self {
        Self::new(u, SplineMap::identity(knots_v))
    }

    /// A map acting in `v` only (identity in `u`).
    #[must_use]
    pub fn along_v(knots_u: &KnotVector<T>, v: SplineMap<T>) -> Self {
        Self::new(SplineMap::identity(knots_u), v)
    }

    /// The partial derivative $\partial^{k+l} / \partial u^k \partial v^l$.
    ///
    /// # Errors
    /// [`ErrorKind::OrderTooHigh`] if an order exceeds the degree in its direction.
    pub fn partial_derivative(
        knots_u: &KnotVector<T>,
        knots_v: &KnotVector<T>,
        k: usize,
        l: usize,
    ) -> Result<Self> {
        Ok(Self::new(
            SplineMap::derivative(knots_u, k)?,
            SplineMap::derivative(knots_v, l)?,
        ))
    }

    /// The map in `u`.
    #[must_use]
    pub fn u(&self) -> &SplineMap<T> {
        &self.u
    }

    /// The map in `v`.
    #[must_use]
    pub fn v(&self) -> &SplineMap<T> {
        &self.v
    }

    /// The full matrix $A_u \otimes A_v$ on row-major grids (the Jacobian of the output
    /// coefficients with respect to the input ones).
    #[must_use]
    pub fn matrix(&self) -> CsrMatrix<T> {
        kron(self.u.matrix(), self.v.matrix())
    }

    /// First `self`, then `next`.
    ///
    /// # Errors
    /// As [`SplineMap::then`] in either direction.
    pub fn then(&self, next: &Self) -> Result<Self> {
        Ok(Self::new(self.u.then(&next.u)?, self.v.then(&next.v)?))
    }

    /// Applies the map to row-major coefficients of any point type.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] for a wrong number of coefficients.
    pub fn apply_coefficients<P: ControlPoint<T>>(&self, grid: &[P]) -> Result<Vec<P>> {
        check_len(
            "tensor map input",
            self.u.matrix().ncols() * self.v.matrix().ncols(),
            grid.len(),
        )?;
        Ok(apply_tensor(self.u.matrix(), self.v.matrix(), grid))
    }

    /// Applies the map to a tensor-product spline on its source spaces.
    ///
    /// # Errors
    /// [`ErrorKind::SpaceMismatch`] if the spline is not on the source knot vectors.
    pub fn apply<P: ControlPoint<T>>(&self, s: &Surface<T, P>) -> Result<Surface<T, P>> {
        if s.knots_u() != self.u.source() || s.knots_v() != self.v.source() {
            return Err(Error::new(
                ErrorKind::SpaceMismatch,
                "the spline's knot vectors are not the source spaces of the map",
            ));
        }
        Ok(Surface::new_unchecked(
            self.u.target().clone(),
            self.v.target().clone(),
            apply_tensor(self.u.matrix(), self.v.matrix(), s.control_points()),
        ))
    }
}

/// The partial derivative $\partial^{k+l} s / \partial u^k \partial v^l$ as a tensor-product
/// spline of degree `(p − k, q − l)`.
///
/// # Errors
/// [`ErrorKind::OrderTooHigh`] if an order exceeds the degree in its direction.
pub fn partial<T: Scalar, P: ControlPoint<T>>(
    s: &Surface<T, P>,
    k: usize,
    l: usize,
) -> Result<Surface<T, P>> {
    TensorMap::partial_derivative(s.knots_u(), s.knots_v(), k, l)?.apply(s)
}

/// A partial derivative with its orders `(k, l)`.
pub type Partial<T, P> = ((usize, usize), Surface<T, P>);

/// All partial derivatives of total order at most `order` whose orders do not exceed the
/// degrees: `((k, l), ∂^{k+l} s / ∂u^k ∂v^l)`, by increasing total order.
///
/// # Errors
/// Never for valid splines (kept for uniformity).
pub fn partials<T: Scalar, P: ControlPoint<T>>(
    s: &Surface<T, P>,
    order: usize,
) -> Result<Vec<Partial<T, P>>> {
    let mut out = Vec::new();
    for total in 0..=order {
        for k in 0..=total {
            let l = total - k;
            if k <= s.knots_u().degree() && l <= s.knots_v().degree() {
                out.push(((k, l), partial(s, k, l)?));
            }
        }
    }
    Ok(out)
}

/// The product of two tensor-product function spaces on the same domain, prepared once:
/// the univariate [`ProductMap`]s in `u` and in `v`; the bilinear map of the product is their
/// Kronecker product.
#[derive(Clone, Debug)]
pub struct TensorProductMap<T> {
    u: ProductMap<T>,
    v: ProductMap<T>,
}

impl<T: Scalar> TensorProductMap<T> {
    /// Prepares the product of the spaces `(ua, va)` and `(ub, vb)`.
    ///
    /// # Errors
    /// As [`crate::product_knots`] in either direction.
    pub fn new(
        (ua, va): (&KnotVector<T>, &KnotVector<T>),
        (ub, vb): (&KnotVector<T>, &KnotVector<T>),
    ) -> Result<Self> {
        Ok(Self {
            u: ProductMap::new(ua, ub)?,
            v: ProductMap::new(va, vb)?,
        })
    }

    /// The product in `u`.
    #[must_use]
    pub fn u(&self) -> &ProductMap<T> {
        &self.u
    }

    /// The product in `v`.
    #[must_use]
    pub fn v(&self) -> &ProductMap<T> {
        &self.v
    }

    /// The product `a(u, v) b(u, v)` in the minimal tensor-product space: Bézier extraction
    /// of both factors in both directions, the Bernstein product patch by patch, and the
    /// exact conversion to B-spline form in both directions.
    ///
    /// # Errors
    /// [`ErrorKind::SpaceMismatch`] if the factors are not on the prepared spaces.
    pub fn product(&self, a: &Surface<T, T>, b: &Surface<T, T>) -> Result<Surface<T, T>> {
        if a.knots_u() != self.u.left()
            || a.knots_v() != self.v.left()
            || b.knots_u() != self.u.right()
            || b.knots_v() != self.v.right()
        {
            return Err(Error::new(
                ErrorKind::SpaceMismatch,
                "the factors are not on the knot vectors this product was prepared for",
            ));
        }
        let pa = apply_tensor(
            self.u.left_extraction().matrix(),
            self.v.left_extraction().matrix(),
            a.control_points(),
        );
        let pb = apply_tensor(
            self.u.right_extraction().matrix(),
            self.v.right_extraction().matrix(),
            b.control_points(),
        );
        let (pu, qu) = (self.u.left().degree(), self.u.right().degree());
        let (pv, qv) = (self.v.left().degree(), self.v.right().degree());
        let (du, dv) = (pu + qu, pv + qv);
        let su = self.u.bernstein_target().num_basis() / (du + 1);
        let sv = self.v.bernstein_target().num_basis() / (dv + 1);
        let weights = |p: usize, q: usize| -> Vec<Vec<T>> {
            (0..=p + q)
                .map(|i| {
                    (0..=p)
                        .map(|j| {
                            if j <= i && i - j <= q {
                                binomial::<T>(p, j) * binomial::<T>(q, i - j)
                                    / binomial::<T>(p + q, i)
                            } else {
                                T::zero()
                            }
                        })
                        .collect()
                })
                .collect()
        };
        let (wu, wv) = (weights(pu, qu), weights(pv, qv));
        let (nav, nbv, ncv) = (sv * (pv + 1), sv * (qv + 1), sv * (dv + 1));
        let mut pieces = vec![T::zero(); su * (du + 1) * ncv];
        for s in 0..su {
            for t in 0..sv {
                for i1 in 0..=pu {
                    for j1 in 0..=pv {
                        let x = pa[(s * (pu + 1) + i1) * nav + t * (pv + 1) + j1];
                        if x == T::zero() {
                            continue;
                        }
                        for i2 in 0..=qu {
                            let wi = wu[i1 + i2][i1];
                            for j2 in 0..=qv {
                                let y = pb[(s * (qu + 1) + i2) * nbv + t * (qv + 1) + j2];
                                let w = wi * wv[j1 + j2][j1];
                                pieces[(s * (du + 1) + i1 + i2) * ncv + t * (dv + 1) + j1 + j2] +=
                                    w * x * y;
                            }
                        }
                    }
                }
            }
        }
        Ok(Surface::new_unchecked(
            self.u.target().clone(),
            self.v.target().clone(),
            apply_tensor(
                self.u.removal().matrix(),
                self.v.removal().matrix(),
                &pieces,
            ),
        ))
    }

    /// The product as a bilinear map of the row-major coefficients: the Kronecker product of
    /// the univariate bilinear maps (the constant second derivative).
    #[must_use]
    pub fn bilinear(&self) -> SparseBilinear<T> {
        self.u.bilinear().kron(&self.v.bilinear())
    }
}

/// The product of two bivariate B-spline functions on the same domain.
///
/// ```
/// use spline_algebra::tensor_product;
/// use spline_core::KnotVector;
/// use spline_geom::Surface;
/// let k = KnotVector::new(1, vec![0.0f64, 0.0, 1.0, 1.0])?;
/// // s(u, v) = u v, so s² = u² v².
/// let s = Surface::new(k.clone(), k, vec![0.0, 0.0, 0.0, 1.0])?;
/// assert_eq!(s.eval(0.5, 0.25)?, 0.125);
/// let square = tensor_product(&s, &s)?;
/// assert_eq!(square.degrees(), (2, 2));
/// assert!((square.eval(0.5, 0.25)? - 0.015625).abs() < 1e-15);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`TensorProductMap::new`].
pub fn tensor_product<T: Scalar>(a: &Surface<T, T>, b: &Surface<T, T>) -> Result<Surface<T, T>> {
    TensorProductMap::new((a.knots_u(), a.knots_v()), (b.knots_u(), b.knots_v()))?.product(a, b)
}

/// `alpha · a + beta · b` for tensor-product splines on the same domain (degrees raised and
/// knots merged per direction by [`common_space`]).
///
/// # Errors
/// As [`common_space`] in either direction.
pub fn tensor_linear_combination<T: Scalar, P: ControlPoint<T>>(
    alpha: T,
    a: &Surface<T, P>,
    beta: T,
    b: &Surface<T, P>,
) -> Result<Surface<T, P>> {
    let (au, bu) = common_space(a.knots_u(), b.knots_u())?;
    let (av, bv) = common_space(a.knots_v(), b.knots_v())?;
    let xa = TensorMap::new(au, av).apply(a)?;
    let xb = TensorMap::new(bu, bv).apply(b)?;
    let coefficients = xa
        .control_points()
        .iter()
        .zip(xb.control_points())
        .map(|(&x, &y)| x * alpha + y * beta)
        .collect();
    Ok(Surface::new_unchecked(
        xa.knots_u().clone(),
        xa.knots_v().clone(),
        coefficients,
    ))
}

/// A bivariate function quadratic in the coefficients `x` of another one, `q(x) = B(x, x)`,
/// with its gradient and constant Hessian.
#[derive(Clone, Debug)]
pub struct QuadraticFunction<T> {
    /// The function.
    pub value: Surface<T, T>,
    /// $\partial\\, \text{coefficient}_k / \partial x_j$.
    pub gradient: CsrMatrix<T>,
    /// The constant Hessian: row `k` is the Hessian of coefficient `k`.
    pub hessian: SparseBilinear<T>,
}

/// The bilinear map `(x, y) ↦ P(L x, R y)` of a tensor product `P` fed by linear maps.
fn fed_product<T: Scalar>(
    product: &TensorProductMap<T>,
    left: &TensorMap<T>,
    right: &TensorMap<T>,
) -> Result<SparseBilinear<T>> {
    product.bilinear().compose(&left.matrix(), &right.matrix())
}

/// The determinant of the Hessian matrix, $s_{uu} s_{vv} - s_{uv}^2$ (thesis §5.6: with
/// `s_uu ≥ 0` it characterises convexity), as a tensor-product B-spline whose coefficients
/// are quadratic in the coefficients `x` of `s`; the gradient is
/// $(\nabla s)_{uu} s_{vv} + s_{uu} (\nabla s)_{vv} - 2 (\nabla s)_{uv} s_{uv}$ and the Hessian
/// is constant.
///
/// # Errors
/// [`ErrorKind::OrderTooHigh`] unless both degrees are at least 2 (a second derivative is
/// taken in each direction).
pub fn hessian_determinant<T: Scalar>(s: &Surface<T, T>) -> Result<QuadraticFunction<T>> {
    let (ku, kv) = (s.knots_u(), s.knots_v());
    let duu = TensorMap::partial_derivative(ku, kv, 2, 0)?;
    let dvv = TensorMap::partial_derivative(ku, kv, 0, 2)?;
    let duv = TensorMap::partial_derivative(ku, kv, 1, 1)?;
    let p1 = TensorProductMap::new(
        (duu.u().target(), duu.v().target()),
        (dvv.u().target(), dvv.v().target()),
    )?;
    let p2 = TensorProductMap::new(
        (duv.u().target(), duv.v().target()),
        (duv.u().target(), duv.v().target()),
    )?;
    let target_u = p1.u().target().merged(p2.u().target())?;
    let target_v = p1.v().target().merged(p2.v().target())?;
    let r1 = TensorMap::new(
        SplineMap::transfer(p1.u().target(), &target_u)?,
        SplineMap::transfer(p1.v().target(), &target_v)?,
    );
    let r2 = TensorMap::new(
        SplineMap::transfer(p2.u().target(), &target_u)?,
        SplineMap::transfer(p2.v().target(), &target_v)?,
    );
    let b1 = fed_product(&p1, &duu, &dvv)?.then(&r1.matrix())?;
    let b2 = fed_product(&p2, &duv, &duv)?.then(&r2.matrix())?;
    let form = b1.combine(T::one(), &b2, -T::one())?;
    let (value, gradient) = form.quadratic(s.control_points())?;
    Ok(QuadraticFunction {
        value: Surface::new_unchecked(target_u, target_v, value),
        gradient,
        hessian: form.symmetrized()?,
    })
}

/// The partial derivative, or the zero function (degree 0, one coefficient) when an order
/// exceeds the degree.
fn partial_or_zero<T: Scalar>(s: &Surface<T, T>, k: usize, l: usize) -> Result<Surface<T, T>> {
    if k <= s.knots_u().degree() && l <= s.knots_v().degree() {
        return partial(s, k, l);
    }
    let (ua, ub) = s.knots_u().domain();
    let (va, vb) = s.knots_v().domain();
    Ok(Surface::new_unchecked(
        KnotVector::new(0, vec![ua, ub])?,
        KnotVector::new(0, vec![va, vb])?,
        vec![T::zero()],
    ))
}

/// The ridge (extremality) polynomials of thesis §5.7, with the corrections of the digest:
/// `(a² d − b², a′² d − b′²)` = `(e₁ e₂ d, f₁ f₂ d)`, where
/// $d = (s_{uu} - s_{vv})^2 + 4 s_{uv}^2$,
/// $c_1 = (s_{uuu} + s_{uvv})/2$, $c_2 = 2(s_{uu} - s_{vv})(s_{uuu} - s_{uvv}) + 8 s_{uv} s_{uuv}$,
/// $c_3 = (s_{uuv} + s_{vvv})/2$, $c_4 = 2(s_{uu} - s_{vv})(s_{uuv} - s_{vvv}) + 8 s_{uv} s_{uvv}$,
/// $c_5 = s_{uu} + s_{vv}$,
/// $a = s_{uv} c_1 - s_{uu} c_3 + c_5 c_3/2 + c_4/8$,
/// $b = s_{uv} c_2/4 - s_{uu} c_4/4 + c_5 c_4/8 + d\\, c_3/2$,
/// $a' = s_{vv} c_1 - c_5 c_1/2 - c_2/8 - s_{uv} c_3$,
/// $b' = s_{vv} c_2/4 - c_5 c_2/8 - c_1 d/2 - s_{uv} c_4/4$.
/// Here $e_{1,2} = \lambda_{1,2,u} s_{uv} + \lambda_{1,2,v} (\lambda_{1,2} - s_{uu})$ and
/// $f_{1,2} = \lambda_{1,2,u} (s_{vv} - \lambda_{1,2}) - \lambda_{1,2,v} s_{uv}$ for the
/// eigenvalues $\lambda_{1,2} = (c_5 \pm \sqrt d)/2$ of the Hessian of `s`, whose derivatives
/// are $\lambda_u = c_1 \pm c_2/(4\sqrt d)$, $\lambda_v = c_3 \pm c_4/(4\sqrt d)$. Both are
/// computed exactly as tensor-product B-splines by the product algebra (degrees grow fast:
/// `(18, 18)` for a bicubic `s`). Third derivatives above the degree are zero.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] unless both degrees are at least 2;
/// [`ErrorKind::DegreeTooHigh`] if a product exceeds [`spline_core::MAX_DEGREE`].
pub fn ridge_polynomials<T: Scalar>(s: &Surface<T, T>) -> Result<(Surface<T, T>, Surface<T, T>)> {
    let low = s.knots_u().degree().min(s.knots_v().degree());
    if low < 2 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "ridge polynomials need degree 2 or more in both directions",
        )
        .with_value(low as f64)
        .with_interval(2.0, f64::INFINITY));
    }
    let d = |k, l| partial_or_zero(s, k, l);
    let (suu, svv, suv) = (d(2, 0)?, d(0, 2)?, d(1, 1)?);
    let (suuu, suuv, suvv, svvv) = (d(3, 0)?, d(2, 1)?, d(1, 2)?, d(0, 3)?);
    let mul = tensor_product::<T>;
    let lin = |x: f64, a: &Surface<T, T>, y: f64, b: &Surface<T, T>| {
        tensor_linear_combination(cast::<T>(x), a, cast::<T>(y), b)
    };
    let diff = lin(1.0, &suu, -1.0, &svv)?;
    let dd = lin(1.0, &mul(&diff, &diff)?, 4.0, &mul(&suv, &suv)?)?;
    let c1 = lin(0.5, &suuu, 0.5, &suvv)?;
    let c2 = lin(
        2.0,
        &mul(&diff, &lin(1.0, &suuu, -1.0, &suvv)?)?,
        8.0,
        &mul(&suv, &suuv)?,
    )?;
    let c3 = lin(0.5, &suuv, 0.5, &svvv)?;
    let c4 = lin(
        2.0,
        &mul(&diff, &lin(1.0, &suuv, -1.0, &svvv)?)?,
        8.0,
        &mul(&suv, &suvv)?,
    )?;
    let c5 = lin(1.0, &suu, 1.0, &svv)?;
    let sum = |terms: &[(f64, Surface<T, T>)]| -> Result<Surface<T, T>> {
        let mut acc = terms[0].1.clone();
        let mut first = terms[0].0;
        for (w, t) in &terms[1..] {
            acc = lin(first, &acc, *w, t)?;
            first = 1.0;
        }
        if first != 1.0 {
            acc = lin(first, &acc, 0.0, &acc.clone())?;
        }
        Ok(acc)
    };
    let a = sum(&[
        (1.0, mul(&suv, &c1)?),
        (-1.0, mul(&suu, &c3)?),
        (0.5, mul(&c5, &c3)?),
        (0.125, c4.clone()),
    ])?;
    let b = sum(&[
        (0.25, mul(&suv, &c2)?),
        (-0.25, mul(&suu, &c4)?),
        (0.125, mul(&c5, &c4)?),
        (0.5, mul(&dd, &c3)?),
    ])?;
    let a2 = sum(&[
        (1.0, mul(&svv, &c1)?),
        (-0.5, mul(&c5, &c1)?),
        (-0.125, c2.clone()),
        (-1.0, mul(&suv, &c3)?),
    ])?;
    let b2 = sum(&[
        (0.25, mul(&svv, &c2)?),
        (-0.125, mul(&c5, &c2)?),
        (-0.5, mul(&c1, &dd)?),
        (-0.25, mul(&suv, &c4)?),
    ])?;
    let first = lin(1.0, &mul(&mul(&a, &a)?, &dd)?, -1.0, &mul(&b, &b)?)?;
    let second = lin(1.0, &mul(&mul(&a2, &a2)?, &dd)?, -1.0, &mul(&b2, &b2)?)?;
    Ok((first, second))
}
