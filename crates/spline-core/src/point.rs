//! The control-point trait: anything that forms a vector space over the scalar.

use crate::Scalar;
use nalgebra::SVector;
use std::fmt::Debug;
use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// A control point: an element of a vector space over `T` with `DIM` coordinates.
///
/// Implemented for the scalar `T` itself (B-spline *functions*, `DIM = 1`) and for
/// `nalgebra::SVector<T, D>` (curves and surfaces in `R^D`, homogeneous points of NURBS).
/// Spline algorithms only need the affine combinations this trait provides; coordinates are
/// exposed for serialisation and geometry.
///
/// Methods are named to avoid clashing with [`nalgebra::ComplexField`] on scalars:
/// `origin` (not `zero`), `length` (not `norm`), `all_finite` (not `is_finite`).
pub trait ControlPoint<T: Scalar>:
    Copy
    + Debug
    + PartialEq
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<T, Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + Send
    + Sync
    + 'static
{
    /// Number of coordinates.
    const DIM: usize;

    /// The zero vector.
    fn origin() -> Self;

    /// Coordinate `i` (`0 <= i < DIM`).
    ///
    /// # Panics
    /// Panics if `i >= DIM`.
    fn coord(&self, i: usize) -> T;

    /// Sets coordinate `i`.
    ///
    /// # Panics
    /// Panics if `i >= DIM`.
    fn set_coord(&mut self, i: usize, value: T);

    /// Builds a point from its coordinates.
    fn from_coords(mut coordinate: impl FnMut(usize) -> T) -> Self {
        let mut point = Self::origin();
        for i in 0..Self::DIM {
            point.set_coord(i, coordinate(i));
        }
        point
    }

    /// Euclidean inner product.
    fn dot(&self, other: &Self) -> T {
        let mut sum = T::zero();
        for i in 0..Self::DIM {
            sum += self.coord(i) * other.coord(i);
        }
        sum
    }

    /// Squared Euclidean length.
    fn length_squared(&self) -> T {
        self.dot(self)
    }

    /// Euclidean length.
    fn length(&self) -> T {
        self.length_squared().sqrt()
    }

    /// Whether every coordinate is finite.
    fn all_finite(&self) -> bool {
        (0..Self::DIM).all(|i| self.coord(i).is_finite())
    }

    /// Largest absolute coordinate (the max norm).
    fn max_abs(&self) -> T {
        let mut m = T::zero();
        for i in 0..Self::DIM {
            m = m.max(self.coord(i).abs());
        }
        m
    }
}

impl<T: Scalar> ControlPoint<T> for T {
    const DIM: usize = 1;

    #[inline]
    fn origin() -> Self {
        T::zero()
    }

    #[inline]
    fn coord(&self, i: usize) -> T {
        assert!(i == 0, "coordinate {i} of a scalar");
        *self
    }

    #[inline]
    fn set_coord(&mut self, i: usize, value: T) {
        assert!(i == 0, "coordinate {i} of a scalar");
        *self = value;
    }

    #[inline]
    fn dot(&self, other: &Self) -> T {
        *self * *other
    }
}

impl<T: Scalar, const D: usize> ControlPoint<T> for SVector<T, D> {
    const DIM: usize = D;

    #[inline]
    fn origin() -> Self {
        Self::zeros()
    }

    #[inline]
    fn coord(&self, i: usize) -> T {
        self[i]
    }

    #[inline]
    fn set_coord(&mut self, i: usize, value: T) {
        self[i] = value;
    }

    #[inline]
    fn dot(&self, other: &Self) -> T {
        SVector::dot(self, other)
    }
}

/// Linear interpolation `(1 − t) a + t b`.
#[inline]
pub fn lerp<T: Scalar, P: ControlPoint<T>>(a: P, b: P, t: T) -> P {
    a * (T::one() - t) + b * t
}
