//! Polynomial expressions in the coordinate functions of a curve (the numerators of its
//! differential invariants), built from B-spline products and linear combinations, with the
//! Jacobian with respect to the control points carried along by the product rule and a bound
//! on the magnitudes that entered each coefficient (to tell rounding left by cancellation
//! from a value).

use crate::curves::Differentiated;
use crate::maps::SplineMap;
use crate::product::{ProductMap, common_space, linear_combination, product};
use crate::sparse::{add_scaled, apply_points, csr_from_rows, matmul};
use nalgebra_sparse::CsrMatrix;
use spline_core::{Result, Scalar, cast};
use spline_geom::{BSpline, Homogeneous};

/// A B-spline function with a bound on the magnitudes that entered each coefficient (sums
/// of absolute values of the terms, through products and linear combinations): where a
/// coefficient is below `1e-10` of its magnitude it is rounding left by cancellation, not
/// a value. A circle's curvature-extremum numerator, a straight segment's curvature
/// numerator cancel that way, and sign changes of the noise would be reported as features.
///
/// With `jacobian`, the sparse Jacobian of the coefficients with respect to the variables
/// of the leaves (rows: coefficients).
pub(crate) struct Tracked<T: Scalar> {
    pub(crate) value: BSpline<T, T>,
    magnitude: BSpline<T, T>,
    pub(crate) jacobian: Option<CsrMatrix<T>>,
}

impl<T: Scalar> Tracked<T> {
    /// An input (a coordinate or a derivative): its magnitudes are its coefficients' sizes.
    pub(crate) fn leaf(value: BSpline<T, T>, jacobian: Option<CsrMatrix<T>>) -> Self {
        let magnitude = value.map_control_points(|&c| c.abs());
        Self {
            value,
            magnitude,
            jacobian,
        }
    }

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

    /// The product; products of non-negative coefficients bound those of the product.
    pub(crate) fn times(&self, other: &Self) -> Result<Self> {
        let magnitude = product(&self.magnitude, &other.magnitude)?;
        let (Some(ja), Some(jb)) = (&self.jacobian, &other.jacobian) else {
            return Ok(Self {
                value: product(&self.value, &other.value)?,
                magnitude,
                jacobian: None,
            });
        };
        let map = ProductMap::new(self.value.knots(), other.value.knots())?;
        let value = map.product(&self.value, &other.value)?;
        let jacobian = add_scaled(
            T::one(),
            &matmul(&map.jacobian_left(other.value.control_points())?, ja),
            T::one(),
            &matmul(&map.jacobian_right(self.value.control_points())?, jb),
        );
        Ok(Self {
            value,
            magnitude,
            jacobian: Some(jacobian),
        })
    }

    /// `alpha · a + beta · b`, with magnitude `|alpha| |a| + |beta| |b|`.
    pub(crate) fn combination(alpha: T, a: &Self, beta: T, b: &Self) -> Result<Self> {
        let magnitude = linear_combination(alpha.abs(), &a.magnitude, beta.abs(), &b.magnitude)?;
        let (Some(ja), Some(jb)) = (&a.jacobian, &b.jacobian) else {
            return Ok(Self {
                value: linear_combination(alpha, &a.value, beta, &b.value)?,
                magnitude,
                jacobian: None,
            });
        };
        let (ma, mb) = common_space(a.value.knots(), b.value.knots())?;
        let xa = ma.apply(a.value.control_points())?;
        let xb = mb.apply(b.value.control_points())?;
        let points = xa
            .iter()
            .zip(&xb)
            .map(|(&x, &y)| alpha * x + beta * y)
            .collect();
        let jacobian = add_scaled(
            alpha,
            &matmul(ma.matrix(), ja),
            beta,
            &matmul(mb.matrix(), jb),
        );
        Ok(Self {
            value: BSpline::new_unchecked(ma.target().clone(), points),
            magnitude,
            jacobian: Some(jacobian),
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
        Self {
            value: self.value.map_control_points(|&c| c * s),
            magnitude: self.magnitude.map_control_points(|&c| c * s.abs()),
            jacobian: self.jacobian.as_ref().map(|j| j * s),
        }
    }

    /// The coefficients that are rounding of cancelled terms set to zero (and the
    /// magnitudes of what remains restarted from the values). The Jacobian is kept: a
    /// numerator that vanishes identically need not have a vanishing derivative.
    pub(crate) fn cleaned(self) -> Self {
        let threshold: T = cast(1e-10);
        let points = self
            .value
            .control_points()
            .iter()
            .zip(self.magnitude.control_points())
            .map(|(&v, &m)| {
                if v.abs() <= threshold * m {
                    T::zero()
                } else {
                    v
                }
            })
            .collect();
        Self::leaf(
            BSpline::new_unchecked(self.value.knots().clone(), points),
            self.jacobian,
        )
    }

    /// Whether every coefficient is exactly zero (after [`Tracked::cleaned`]: the function
    /// vanishes identically up to rounding).
    pub(crate) fn is_zero(&self) -> bool {
        self.value.control_points().iter().all(|c| *c == T::zero())
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
pub(crate) fn dot3<T: Scalar>(a: &[Tracked<T>; 3], b: &[Tracked<T>; 3]) -> Result<Tracked<T>> {
    a[0].times(&b[0])?
        .plus(&a[1].times(&b[1])?)?
        .plus(&a[2].times(&b[2])?)
}

/// `a × b` for 3-vectors of functions.
pub(crate) fn cross3<T: Scalar>(
    a: &[Tracked<T>; 3],
    b: &[Tracked<T>; 3],
) -> Result<[Tracked<T>; 3]> {
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
