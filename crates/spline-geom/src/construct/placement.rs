//! Where circles and surfaces of revolution are placed: frames of planes and axes of
//! revolution.

use super::checks::{check_vector, degenerate};
use super::vectors::{perpendicular, safe_norm};
use nalgebra::{SVector, Vector3};
#[cfg(doc)]
use spline_core::ErrorKind;
use spline_core::{Result, Scalar};

/// An orthonormal frame of a plane in $\mathbb{R}^D$ (`D ≥ 2`): an origin and two
/// perpendicular unit vectors. Circles and arcs are built in such a frame.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::Frame;
/// let f = Frame::with_normal(Vector3::new(0.0, 0.0, 1.0), Vector3::new(0.0, 0.0, 2.0))?;
/// assert_eq!(f.x_axis(), Vector3::new(1.0, 0.0, 0.0));
/// assert_eq!(f.y_axis(), Vector3::new(0.0, 1.0, 0.0));
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame<T, const D: usize> {
    origin: SVector<T, D>,
    x_axis: SVector<T, D>,
    y_axis: SVector<T, D>,
}

impl<T: Scalar, const D: usize> Frame<T, D> {
    /// The frame at `origin` whose x axis points along `x_direction` and whose y axis is the
    /// unit vector of `y_direction` made perpendicular to it (Gram–Schmidt).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] if `x_direction` is zero
    /// or `y_direction` is (numerically) parallel to it.
    pub fn new(
        origin: SVector<T, D>,
        x_direction: SVector<T, D>,
        y_direction: SVector<T, D>,
    ) -> Result<Self> {
        check_vector(&origin, "the origin")?;
        check_vector(&x_direction, "the x direction")?;
        check_vector(&y_direction, "the y direction")?;
        let xl = safe_norm(&x_direction);
        if !(xl > T::zero()) {
            return Err(degenerate("the x direction of a frame must not be zero"));
        }
        let x_axis = x_direction / xl;
        let y = y_direction - x_axis * x_axis.dot(&y_direction);
        let yl = safe_norm(&y);
        if !(yl > T::default_epsilon().sqrt() * safe_norm(&y_direction)) {
            return Err(degenerate(
                "the y direction of a frame must not be zero or parallel to the x direction",
            ));
        }
        Ok(Self {
            origin,
            x_axis,
            y_axis: y / yl,
        })
    }

    /// The origin.
    #[must_use]
    pub fn origin(&self) -> SVector<T, D> {
        self.origin
    }

    /// The unit x axis.
    #[must_use]
    pub fn x_axis(&self) -> SVector<T, D> {
        self.x_axis
    }

    /// The unit y axis.
    #[must_use]
    pub fn y_axis(&self) -> SVector<T, D> {
        self.y_axis
    }

    /// The point `origin + x X + y Y`.
    #[must_use]
    pub fn point(&self, x: T, y: T) -> SVector<T, D> {
        self.origin + self.x_axis * x + self.y_axis * y
    }
}

impl<T: Scalar> Frame<T, 2> {
    /// The standard frame of the plane moved to `origin`.
    #[must_use]
    pub fn planar(origin: nalgebra::Vector2<T>) -> Self {
        Self {
            origin,
            x_axis: nalgebra::Vector2::x(),
            y_axis: nalgebra::Vector2::y(),
        }
    }
}

impl<T: Scalar> Frame<T, 3> {
    /// A frame of the plane through `origin` perpendicular to `normal`, right-handed about
    /// it (`x × y = n / |n|`). The x axis is the coordinate axis least aligned with the
    /// normal, projected on the plane; for `n = z` the frame is `(x, y)`.
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] for a zero normal.
    pub fn with_normal(origin: Vector3<T>, normal: Vector3<T>) -> Result<Self> {
        check_vector(&origin, "the center")?;
        check_vector(&normal, "the normal")?;
        let len = safe_norm(&normal);
        if !(len > T::zero()) {
            return Err(degenerate("the normal of a plane must not be zero"));
        }
        let n = normal / len;
        let x = perpendicular(&n);
        Ok(Self {
            origin,
            x_axis: x,
            y_axis: n.cross(&x),
        })
    }
}

/// An axis of revolution: a point and a unit direction.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::{Axis, ErrorKind};
/// let axis = Axis::new(Vector3::new(1.0, 0.0, 0.0), Vector3::new(0.0, 0.0, 2.0))?;
/// assert_eq!(axis.direction(), Vector3::new(0.0, 0.0, 1.0));
/// let bad = Axis::new(Vector3::new(1.0, 0.0, 0.0), Vector3::zeros());
/// assert_eq!(bad.unwrap_err().kind(), ErrorKind::DegenerateGeometry);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axis<T> {
    point: Vector3<T>,
    direction: Vector3<T>,
}

impl<T: Scalar> Axis<T> {
    /// The axis through `point` along `direction` (normalised).
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] for a zero direction.
    pub fn new(point: Vector3<T>, direction: Vector3<T>) -> Result<Self> {
        check_vector(&point, "the axis point")?;
        check_vector(&direction, "the axis direction")?;
        let len = safe_norm(&direction);
        if !(len > T::zero()) {
            return Err(degenerate("the direction of an axis must not be zero"));
        }
        Ok(Self {
            point,
            direction: direction / len,
        })
    }

    /// A point of the axis.
    #[must_use]
    pub fn point(&self) -> Vector3<T> {
        self.point
    }

    /// The unit direction.
    #[must_use]
    pub fn direction(&self) -> Vector3<T> {
        self.direction
    }

    /// The orthogonal projection of `p` on the axis.
    #[must_use]
    pub fn project(&self, p: &Vector3<T>) -> Vector3<T> {
        self.point + self.direction * self.direction.dot(&(p - self.point))
    }
}
