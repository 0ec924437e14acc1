//! Homogeneous points: the control points of the B-spline containers behind NURBS.

use nalgebra::SVector;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, VectorSpace, to_f64};
use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// A point of $\mathbb{R}^{D+1}$ in homogeneous form $(w P, w)$: the control points of the
/// B-spline curve (6.4) of seed 004 whose central projection
/// $\Pi(x_1, …, x_{D+1}) = (x_1, …, x_D) / x_{D+1}$ is a NURBS curve (6.5).
///
/// It is a [`ControlPoint`] with `DIM = D + 1` (coordinates `0 … D − 1` are `w P`, coordinate
/// `D` is `w`), so every algorithm written for [`crate::BSpline`] and [`crate::Surface`]
/// works on NURBS unchanged, in homogeneous space. (Stable Rust cannot name the type
/// `SVector<T, {D + 1}>`, hence this type.)
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::Homogeneous;
/// let h = Homogeneous::from_cartesian(Vector2::new(1.0, 2.0), 0.5)?;
/// assert_eq!(h.point, Vector2::new(0.5, 1.0)); // w P
/// assert_eq!(h.project(), Vector2::new(1.0, 2.0));
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Homogeneous<T, const D: usize> {
    /// The weighted point $w P$.
    pub point: SVector<T, D>,
    /// The weight $w$.
    pub weight: T,
}

impl<T: Scalar, const D: usize> Homogeneous<T, D> {
    /// The homogeneous point $(w P, w)$ from raw parts (no checks).
    #[inline]
    #[must_use]
    pub fn new(weighted_point: SVector<T, D>, weight: T) -> Self {
        Self {
            point: weighted_point,
            weight,
        }
    }

    /// $(w P, w)$ from a Cartesian point and its weight.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidWeight`] unless `weight` is positive and finite;
    /// [`ErrorKind::NonFinite`] if a coordinate is not finite.
    pub fn from_cartesian(point: SVector<T, D>, weight: T) -> Result<Self> {
        check_weight(weight)?;
        if !point.iter().all(nalgebra::ComplexField::is_finite) {
            return Err(Error::new(ErrorKind::NonFinite, "point is not finite"));
        }
        Ok(Self::new(point * weight, weight))
    }

    /// The Cartesian point $\Pi(wP, w) = P$ (the weight must not be zero).
    #[inline]
    #[must_use]
    pub fn project(&self) -> SVector<T, D> {
        self.point / self.weight
    }
}

/// Checks that a weight is positive and finite.
///
/// # Errors
/// [`ErrorKind::InvalidWeight`] for zero, negative, NaN or infinite weights.
pub(crate) fn check_weight<T: Scalar>(weight: T) -> Result<()> {
    if weight.is_finite() && weight > T::zero() {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::InvalidWeight,
            format!(
                "weights must be positive and finite, got {}",
                to_f64(weight)
            ),
        ))
    }
}

/// Checks every weight of a list, naming the first bad one.
pub(crate) fn check_weights<T: Scalar>(weights: impl IntoIterator<Item = T>) -> Result<()> {
    for (i, w) in weights.into_iter().enumerate() {
        check_weight(w).map_err(|e| e.context(format_args!("weight {i}")))?;
    }
    Ok(())
}

impl<T: Scalar, const D: usize> Add for Homogeneous<T, D> {
    type Output = Self;
    #[inline]
    fn add(self, rhs: Self) -> Self {
        Self::new(self.point + rhs.point, self.weight + rhs.weight)
    }
}

impl<T: Scalar, const D: usize> Sub for Homogeneous<T, D> {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        Self::new(self.point - rhs.point, self.weight - rhs.weight)
    }
}

impl<T: Scalar, const D: usize> Mul<T> for Homogeneous<T, D> {
    type Output = Self;
    #[inline]
    fn mul(self, rhs: T) -> Self {
        Self::new(self.point * rhs, self.weight * rhs)
    }
}

impl<T: Scalar, const D: usize> Neg for Homogeneous<T, D> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::new(-self.point, -self.weight)
    }
}

impl<T: Scalar, const D: usize> AddAssign for Homogeneous<T, D> {
    #[inline]
    fn add_assign(&mut self, rhs: Self) {
        self.point += rhs.point;
        self.weight += rhs.weight;
    }
}

impl<T: Scalar, const D: usize> SubAssign for Homogeneous<T, D> {
    #[inline]
    fn sub_assign(&mut self, rhs: Self) {
        self.point -= rhs.point;
        self.weight -= rhs.weight;
    }
}

impl<T: Scalar, const D: usize> VectorSpace<T> for Homogeneous<T, D> {
    spline_core::vector_space_by_operators!(T; Homogeneous<T, D>);
}

impl<T: Scalar, const D: usize> ControlPoint<T> for Homogeneous<T, D> {
    const DIM: usize = D + 1;

    #[inline]
    fn origin() -> Self {
        Self::new(SVector::zeros(), T::zero())
    }

    #[inline]
    fn coord(&self, i: usize) -> T {
        if i == D { self.weight } else { self.point[i] }
    }

    #[inline]
    fn set_coord(&mut self, i: usize, value: T) {
        if i == D {
            self.weight = value;
        } else {
            self.point[i] = value;
        }
    }

    #[inline]
    fn dot(&self, other: &Self) -> T {
        self.point.dot(&other.point) + self.weight * other.weight
    }
}
