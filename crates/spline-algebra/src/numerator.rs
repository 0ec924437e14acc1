//! Polynomial expressions in the coordinate functions of a curve (the numerators of its
//! differential invariants), built from B-spline products and linear combinations, with the
//! Jacobian with respect to the control points carried along by the product rule and a bound
//! on the magnitudes that entered each coefficient (to tell rounding left by cancellation
//! from a value).

use crate::curves::Differentiated;
use crate::maps::SplineMap;
use crate::product::{ProductMap, common_space, linear_combination, product};
use crate::sparse::{add_scaled, apply_points, csr_from_rows, matmul};
use crate::tensor::{TensorMap, TensorProductMap, tensor_linear_combination};
use nalgebra_sparse::CsrMatrix;
use spline_core::{Result, Scalar, cast};
use spline_geom::{BSpline, Homogeneous, Surface};

/// What [`Tracked`] asks of a function: coefficients, products and linear combinations
/// (the latter two with the Jacobians carried along where the kind supports them).
pub(crate) trait Function<T: Scalar>: Sized {
    fn coefficients(&self) -> &[T];
    /// The same space with other coefficients.
    fn with_coefficients(&self, coefficients: Vec<T>) -> Self;
    /// The product, and its Jacobian from those of the factors (when both are given).
    fn times(
        a: &Self,
        b: &Self,
        jacobians: Option<(&CsrMatrix<T>, &CsrMatrix<T>)>,
    ) -> Result<(Self, Option<CsrMatrix<T>>)>;
    /// `alpha · a + beta · b`, and its Jacobian.
    fn combination(
        alpha: T,
        a: &Self,
        beta: T,
        b: &Self,
        jacobians: Option<(&CsrMatrix<T>, &CsrMatrix<T>)>,
    ) -> Result<(Self, Option<CsrMatrix<T>>)>;
}

impl<T: Scalar> Function<T> for BSpline<T, T> {
    fn coefficients(&self) -> &[T] {
        self.control_points()
    }

    fn with_coefficients(&self, coefficients: Vec<T>) -> Self {
        BSpline::new_unchecked(self.knots().clone(), coefficients)
    }

    fn times(
        a: &Self,
        b: &Self,
        jacobians: Option<(&CsrMatrix<T>, &CsrMatrix<T>)>,
    ) -> Result<(Self, Option<CsrMatrix<T>>)> {
        let Some((ja, jb)) = jacobians else {
            return Ok((product(a, b)?, None));
        };
        let map = ProductMap::new(a.knots(), b.knots())?;
        let left = map.jacobian_left(b.control_points())?;
        let right = map.jacobian_right(a.control_points())?;
        let jacobian = chained_sum(T::one(), &left, ja, T::one(), &right, jb);
        Ok((map.product(a, b)?, Some(jacobian)))
    }

    fn combination(
        alpha: T,
        a: &Self,
        beta: T,
        b: &Self,
        jacobians: Option<(&CsrMatrix<T>, &CsrMatrix<T>)>,
    ) -> Result<(Self, Option<CsrMatrix<T>>)> {
        let Some((ja, jb)) = jacobians else {
            return Ok((linear_combination(alpha, a, beta, b)?, None));
        };
        let (ma, mb) = common_space(a.knots(), b.knots())?;
        let xa = ma.apply(a.control_points())?;
        let xb = mb.apply(b.control_points())?;
        let points = xa
            .iter()
            .zip(&xb)
            .map(|(&x, &y)| alpha * x + beta * y)
            .collect();
        let jacobian = chained_sum(alpha, ma.matrix(), ja, beta, mb.matrix(), jb);
        Ok((
            BSpline::new_unchecked(ma.target().clone(), points),
            Some(jacobian),
        ))
    }
}

/// `α A·J_a + β B·J_b`: the Jacobian of `α A a + β B b` (a product's rule, a combination on
/// a common space) from those of `a` and `b`.
fn chained_sum<T: Scalar>(
    alpha: T,
    a: &CsrMatrix<T>,
    ja: &CsrMatrix<T>,
    beta: T,
    b: &CsrMatrix<T>,
    jb: &CsrMatrix<T>,
) -> CsrMatrix<T> {
    add_scaled(alpha, &matmul(a, ja), beta, &matmul(b, jb))
}

/// Bivariate functions: products through the Kronecker product of the univariate bilinear
/// maps, combinations through the tensor product of the common-space maps.
impl<T: Scalar> Function<T> for Surface<T, T> {
    fn coefficients(&self) -> &[T] {
        self.control_points()
    }

    fn with_coefficients(&self, coefficients: Vec<T>) -> Self {
        Surface::new_unchecked(self.knots_u().clone(), self.knots_v().clone(), coefficients)
    }

    fn times(
        a: &Self,
        b: &Self,
        jacobians: Option<(&CsrMatrix<T>, &CsrMatrix<T>)>,
    ) -> Result<(Self, Option<CsrMatrix<T>>)> {
        let map = TensorProductMap::new((a.knots_u(), a.knots_v()), (b.knots_u(), b.knots_v()))?;
        let value = map.product(a, b)?;
        let Some((ja, jb)) = jacobians else {
            return Ok((value, None));
        };
        let bilinear = map.bilinear();
        let left = bilinear.jacobian_left(b.control_points())?;
        let right = bilinear.jacobian_right(a.control_points())?;
        let jacobian = chained_sum(T::one(), &left, ja, T::one(), &right, jb);
        Ok((value, Some(jacobian)))
    }

    fn combination(
        alpha: T,
        a: &Self,
        beta: T,
        b: &Self,
        jacobians: Option<(&CsrMatrix<T>, &CsrMatrix<T>)>,
    ) -> Result<(Self, Option<CsrMatrix<T>>)> {
        let value = tensor_linear_combination(alpha, a, beta, b)?;
        let Some((ja, jb)) = jacobians else {
            return Ok((value, None));
        };
        let (au, bu) = common_space(a.knots_u(), b.knots_u())?;
        let (av, bv) = common_space(a.knots_v(), b.knots_v())?;
        let jacobian = chained_sum(
            alpha,
            &TensorMap::new(au, av).matrix(),
            ja,
            beta,
            &TensorMap::new(bu, bv).matrix(),
            jb,
        );
        Ok((value, Some(jacobian)))
    }
}

/// A function (univariate [`BSpline`] or bivariate [`Surface`]) with a bound on the
/// magnitudes that entered each coefficient (sums of absolute values of the terms, through
/// products and linear combinations): where a coefficient is below `1e-10` of its magnitude
/// it is rounding left by cancellation, not a value. A circle's curvature-extremum
/// numerator, a straight segment's curvature numerator, a torus's Gaussian-curvature
/// numerator on its parabolic circles cancel that way, and sign changes of the noise would
/// be reported as features.
///
/// With `jacobian`, the sparse Jacobian of the coefficients with respect to the
/// variables of the leaves (rows: coefficients).
pub(crate) struct Tracked<T: Scalar, F = BSpline<T, T>> {
    pub(crate) value: F,
    magnitude: F,
    pub(crate) jacobian: Option<CsrMatrix<T>>,
}

impl<T: Scalar, F: Function<T>> Tracked<T, F> {
    /// An input (a coordinate or a derivative): its magnitudes are its coefficients' sizes.
    pub(crate) fn leaf(value: F, jacobian: Option<CsrMatrix<T>>) -> Self {
        let magnitude =
            value.with_coefficients(value.coefficients().iter().map(|&c| c.abs()).collect());
        Self {
            value,
            magnitude,
            jacobian,
        }
    }

    fn jacobians<'a>(a: &'a Self, b: &'a Self) -> Option<(&'a CsrMatrix<T>, &'a CsrMatrix<T>)> {
        a.jacobian.as_ref().zip(b.jacobian.as_ref())
    }

    /// The product; products of non-negative coefficients bound those of the product.
    pub(crate) fn times(&self, other: &Self) -> Result<Self> {
        let (magnitude, _) = F::times(&self.magnitude, &other.magnitude, None)?;
        let (value, jacobian) = F::times(&self.value, &other.value, Self::jacobians(self, other))?;
        Ok(Self {
            value,
            magnitude,
            jacobian,
        })
    }

    /// `alpha · a + beta · b`, with magnitude `|alpha| |a| + |beta| |b|`.
    pub(crate) fn combination(alpha: T, a: &Self, beta: T, b: &Self) -> Result<Self> {
        let (magnitude, _) =
            F::combination(alpha.abs(), &a.magnitude, beta.abs(), &b.magnitude, None)?;
        let (value, jacobian) =
            F::combination(alpha, &a.value, beta, &b.value, Self::jacobians(a, b))?;
        Ok(Self {
            value,
            magnitude,
            jacobian,
        })
    }

    /// `a + b`.
    pub(crate) fn plus(&self, other: &Self) -> Result<Self> {
        Self::combination(T::one(), self, T::one(), other)
    }

    /// `a − b`.
    pub(crate) fn minus(&self, other: &Self) -> Result<Self> {
        Self::combination(T::one(), self, -T::one(), other)
    }

    /// `s · a`.
    pub(crate) fn scaled(&self, s: T) -> Self {
        let scale =
            |f: &F, s: T| f.with_coefficients(f.coefficients().iter().map(|&c| c * s).collect());
        Self {
            value: scale(&self.value, s),
            magnitude: scale(&self.magnitude, s.abs()),
            jacobian: self.jacobian.as_ref().map(|j| j * s),
        }
    }

    /// The coefficients that are rounding of cancelled terms set to zero (and the
    /// magnitudes of what remains restarted from the values). The Jacobian is kept: a
    /// numerator that vanishes identically need not have a vanishing derivative.
    pub(crate) fn cleaned(self) -> Self {
        self.cleaned_below(cast(1e-10))
    }

    /// [`Tracked::cleaned`] with the coefficients below `threshold` times their magnitude
    /// taken for rounding.
    fn cleaned_below(self, threshold: T) -> Self {
        let points = self
            .value
            .coefficients()
            .iter()
            .zip(self.magnitude.coefficients())
            .map(|(&v, &m)| {
                if v.abs() <= threshold * m {
                    T::zero()
                } else {
                    v
                }
            })
            .collect();
        Self::leaf(self.value.with_coefficients(points), self.jacobian)
    }

    /// The numerators of curves when `clean` (with derivatives they keep their rounding, so
    /// that derivatives of their derivatives — dual numbers run through the Jacobians — stay
    /// exact). A curve's numerator is one chain of products whose rounding stays within a
    /// few hundred ulps of the magnitudes (the circles and ellipses of the tests cancel below
    /// it), so its threshold is 1e-13: at the surfaces' 1e-10 a random rational space cubic lost the
    /// true size of the coefficients near a curvature minimum and placed it 2e-4 off
    /// (issue 25).
    pub(crate) fn cleaned_if(self, clean: bool) -> Self {
        if clean {
            self.cleaned_below(cast(1e-13))
        } else {
            self
        }
    }

    /// Whether every coefficient is exactly zero (after [`Tracked::cleaned`]: the function
    /// vanishes identically up to rounding).
    pub(crate) fn is_zero(&self) -> bool {
        self.value.coefficients().iter().all(|c| *c == T::zero())
    }
}

impl<T: Scalar> Tracked<T> {
    /// Coordinate `k` of the homogeneous control points (`k = D` is the weight) after the
    /// affine map `f`, with the Jacobian of `f`'s result with respect to the interleaved
    /// homogeneous coordinates $[w_i x_i, w_i y_i, \dots, w_i]$ when `derivative` gives
    /// `∂f/∂(coordinate j)` for each `j`.
    pub(crate) fn coordinate<const D: usize>(
        h: &BSpline<T, Homogeneous<T, D>>,
        f: impl Fn(&Homogeneous<T, D>) -> T,
        derivative: Option<&[T]>,
    ) -> Self {
        let value = h.map_control_points(f);
        let jacobian = derivative.map(|d| {
            let rows = (0..h.control_points().len())
                .map(|i| {
                    d.iter()
                        .enumerate()
                        .filter(|(_, v)| **v != T::zero())
                        .map(|(j, &v)| (i * (D + 1) + j, v))
                        .collect()
                })
                .collect();
            csr_from_rows(h.control_points().len() * (D + 1), rows)
        });
        Self::leaf(value, jacobian)
    }

    /// The derivative; its magnitudes are those of the operands through the absolute
    /// values of the derivative map.
    pub(crate) fn derivative(&self, order: usize) -> Result<Self> {
        let map = SplineMap::derivative(self.value.knots(), order)?;
        let value = map.apply_to(&self.value)?;
        let matrix = map.matrix();
        let mut abs = matrix.clone();
        abs.values_mut().iter_mut().for_each(|v| *v = v.abs());
        let magnitude = BSpline::new_unchecked(
            value.knots().clone(),
            apply_points(&abs, self.magnitude.control_points()),
        );
        let jacobian = self.jacobian.as_ref().map(|j| matmul(matrix, j));
        Ok(Self {
            value,
            magnitude,
            jacobian,
        })
    }

    /// The value with its Jacobian (empty if none was tracked).
    pub(crate) fn differentiated(self) -> Differentiated<T> {
        let n = self.value.control_points().len();
        Differentiated {
            jacobian: self.jacobian.unwrap_or_else(|| CsrMatrix::zeros(n, 0)),
            value: self.value,
        }
    }
}

/// `a · b` for 3-vectors of functions.
pub(crate) fn dot3<T: Scalar, F: Function<T>>(
    a: &[Tracked<T, F>; 3],
    b: &[Tracked<T, F>; 3],
) -> Result<Tracked<T, F>> {
    a[0].times(&b[0])?
        .plus(&a[1].times(&b[1])?)?
        .plus(&a[2].times(&b[2])?)
}

/// `a × b` for 3-vectors of functions.
pub(crate) fn cross3<T: Scalar, F: Function<T>>(
    a: &[Tracked<T, F>; 3],
    b: &[Tracked<T, F>; 3],
) -> Result<[Tracked<T, F>; 3]> {
    let c = |i: usize, j: usize| a[i].times(&b[j])?.minus(&a[j].times(&b[i])?);
    Ok([c(1, 2)?, c(2, 0)?, c(0, 1)?])
}

/// The componentwise derivative of a 3-vector of functions.
pub(crate) fn derivative3<T: Scalar>(a: &[Tracked<T>; 3], order: usize) -> Result<[Tracked<T>; 3]> {
    Ok([
        a[0].derivative(order)?,
        a[1].derivative(order)?,
        a[2].derivative(order)?,
    ])
}
