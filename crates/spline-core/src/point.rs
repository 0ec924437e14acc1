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
    VectorSpace<T>
    + Copy
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

    /// Euclidean length, without underflow or overflow of the squares: coordinates of any
    /// magnitude the scalar holds (`3e-300, 4e-300` has length `5e-300`, not 0; `3e300,
    /// 4e300` has `5e300`, not infinity).
    fn length(&self) -> T {
        let squared = self.length_squared();
        // The squares are exact enough between these bounds; outside them (or when they
        // underflow to 0 or overflow), the point is scaled by its largest coordinate first.
        if squared > crate::cast::<T>(1e-290) && squared < crate::cast::<T>(1e290) {
            return squared.sqrt();
        }
        let largest = self.max_abs();
        if !(largest > T::zero()) || !largest.is_finite() {
            return squared.sqrt();
        }
        // Divided, not multiplied by the inverse: 1/largest overflows for subnormal points.
        let mut scaled = T::zero();
        for i in 0..Self::DIM {
            let c = self.coord(i) / largest;
            scaled += c * c;
        }
        largest * scaled.sqrt()
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

    #[inline]
    fn length(&self) -> T {
        self.abs()
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

/// An element of a vector space over `T`: what the structural algorithms (knot insertion,
/// refinement, removal, degree elevation, derivative, Bézier extraction) need of a control
/// point, and nothing more — no coordinates, no `Copy`.
///
/// Every [`ControlPoint`] is one (it is a supertrait), and so is the [`SymbolicPoint`]: a sparse row $\sum_i a_i P_i$ over unknown control points. Running a
/// structural algorithm on points gives the new control points; running the *same* code on
/// symbolic points `P_0, …, P_{n−1}` gives the rows of its matrix, the Jacobian of the
/// operation (the SYNAPS idea: one algorithm, any point type).
///
/// ```
/// use spline_core::{SymbolicPoint, VectorSpace};
/// let (a, b) = (SymbolicPoint::<f64>::unit(0), SymbolicPoint::unit(2));
/// let mid = a.combine(0.5, &b, 0.5); // ½ P_0 + ½ P_2
/// assert_eq!(mid.entries(), &[(0, 0.5), (2, 0.5)]);
/// assert_eq!(1.0f64.combine(0.5, &3.0, 0.5), 2.0);
/// ```
pub trait VectorSpace<T: Scalar>: Clone + Debug {
    /// The zero vector.
    fn zero_vector() -> Self;

    /// `a · self + b · other`.
    #[must_use]
    fn combine(&self, a: T, other: &Self, b: T) -> Self;

    /// `a · self`.
    #[must_use]
    fn scaled(&self, a: T) -> Self;

    /// `self += a · other`.
    fn add_scaled(&mut self, other: &Self, a: T);

    /// Whether every coordinate (coefficient) is finite.
    fn is_finite_vector(&self) -> bool;
}

/// The [`VectorSpace`] operations of a `Copy` type with the arithmetic operators (scalars,
/// `nalgebra` vectors, homogeneous points), for control-point types of other crates.
#[macro_export]
macro_rules! vector_space_by_operators {
    ($t:ident; $type:ty) => {
        #[inline(always)]
        fn zero_vector() -> Self {
            <$type as $crate::ControlPoint<$t>>::origin()
        }

        #[inline(always)]
        fn combine(&self, a: $t, other: &Self, b: $t) -> Self {
            *self * a + *other * b
        }

        #[inline(always)]
        fn scaled(&self, a: $t) -> Self {
            *self * a
        }

        #[inline(always)]
        fn add_scaled(&mut self, other: &Self, a: $t) {
            *self += *other * a;
        }

        #[inline(always)]
        fn is_finite_vector(&self) -> bool {
            <$type as $crate::ControlPoint<$t>>::all_finite(self)
        }
    };
}

impl<T: Scalar> VectorSpace<T> for T {
    vector_space_by_operators!(T; T);
}

impl<T: Scalar, const D: usize> VectorSpace<T> for SVector<T, D> {
    vector_space_by_operators!(T; SVector<T, D>);
}

/// A symbolic control point: the linear form $\sum_i a_i P_i$ over unknown control points
/// `P_i`, stored as `(i, a_i)` pairs sorted by `i` without zeros.
///
/// A [`VectorSpace`], so every structural algorithm runs on it unchanged: started from the
/// unit forms `P_0, …, P_{n−1}`, it returns the rows of the operation's matrix.
#[derive(Clone, Debug, PartialEq)]
pub struct SymbolicPoint<T> {
    entries: Vec<(usize, T)>,
}

impl<T: Scalar> SymbolicPoint<T> {
    /// The unknown control point `P_i` itself.
    #[must_use]
    pub fn unit(i: usize) -> Self {
        Self {
            entries: vec![(i, T::one())],
        }
    }

    /// The `n` unit forms `P_0, …, P_{n−1}`.
    #[must_use]
    pub fn units(n: usize) -> Vec<Self> {
        (0..n).map(Self::unit).collect()
    }

    /// The `(index, coefficient)` pairs, sorted by index.
    #[must_use]
    pub fn entries(&self) -> &[(usize, T)] {
        &self.entries
    }

    /// Consumes the form, returning its pairs.
    #[must_use]
    pub fn into_entries(self) -> Vec<(usize, T)> {
        self.entries
    }

    /// The form evaluated at actual points: $\sum_i a_i P_i$.
    ///
    /// # Panics
    /// If an index is not below `points.len()`.
    #[must_use]
    pub fn eval<V: VectorSpace<T>>(&self, points: &[V]) -> V {
        let mut acc = V::zero_vector();
        for &(i, a) in &self.entries {
            acc.add_scaled(&points[i], a);
        }
        acc
    }

    /// `a · x + b · y` of two sorted pair lists, zeros dropped.
    fn merge(x: &[(usize, T)], a: T, y: &[(usize, T)], b: T) -> Vec<(usize, T)> {
        let mut out = Vec::with_capacity(x.len() + y.len());
        let (mut i, mut j) = (0, 0);
        let mut push = |k: usize, v: T| {
            if v != T::zero() {
                out.push((k, v));
            }
        };
        while i < x.len() || j < y.len() {
            match (x.get(i), y.get(j)) {
                (Some(&(k, v)), Some(&(l, _))) if k < l => {
                    push(k, v * a);
                    i += 1;
                }
                (Some(&(k, v)), Some(&(l, w))) if k == l => {
                    push(k, v * a + w * b);
                    i += 1;
                    j += 1;
                }
                (_, Some(&(l, w))) => {
                    push(l, w * b);
                    j += 1;
                }
                (Some(&(k, v)), None) => {
                    push(k, v * a);
                    i += 1;
                }
                (None, None) => unreachable!("loop condition"),
            }
        }
        out
    }
}

impl<T: Scalar> VectorSpace<T> for SymbolicPoint<T> {
    fn zero_vector() -> Self {
        Self {
            entries: Vec::new(),
        }
    }

    fn combine(&self, a: T, other: &Self, b: T) -> Self {
        Self {
            entries: Self::merge(&self.entries, a, &other.entries, b),
        }
    }

    fn scaled(&self, a: T) -> Self {
        Self {
            entries: self
                .entries
                .iter()
                .map(|&(i, v)| (i, v * a))
                .filter(|&(_, v)| v != T::zero())
                .collect(),
        }
    }

    fn add_scaled(&mut self, other: &Self, a: T) {
        if other.entries.is_empty() {
            return;
        }
        self.entries = Self::merge(&self.entries, T::one(), &other.entries, a);
    }

    fn is_finite_vector(&self) -> bool {
        self.entries.iter().all(|(_, v)| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::ControlPoint;
    use nalgebra::{Vector2, Vector3};

    #[test]
    fn length_holds_at_every_magnitude() {
        // 3-4-5 at scales where the squares underflow or overflow.
        for scale in [1e-300, 1e-200, 1e-160, 1.0, 1e160, 1e200, 1e300] {
            let p = Vector2::new(3.0 * scale, -4.0 * scale);
            let length = ControlPoint::<f64>::length(&p);
            assert!(
                (length / (5.0 * scale) - 1.0).abs() < 4.0 * f64::EPSILON,
                "scale {scale}: {length}"
            );
        }
        // Subnormal coordinates, zero, a scalar.
        let tiny = Vector3::new(0.0, 3e-320, 4e-320);
        assert!((ControlPoint::<f64>::length(&tiny) / 5e-320 - 1.0).abs() < 1e-3);
        assert_eq!(ControlPoint::<f64>::length(&Vector2::new(0.0, 0.0)), 0.0);
        assert_eq!(ControlPoint::<f64>::length(&-2e-300f64), 2e-300);
        // Non-finite coordinates stay non-finite (validation elsewhere catches them).
        assert!(ControlPoint::<f64>::length(&Vector2::new(f64::INFINITY, 1.0)).is_infinite());
        assert!(ControlPoint::<f64>::length(&Vector2::new(f64::NAN, 1.0)).is_nan());
    }
}
