//! The tolerances of the intersection algorithms, their check, and the size that relative
//! tolerances scale with.

use crate::surface_project::BoxTree;
use nalgebra::Vector3;
use spline_core::{ControlPoint, Error, Result, Scalar, cast, to_f64};

/// Tolerances of the intersection algorithms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances<T> {
    /// How far apart the two objects may be at a reported intersection point; by default
    /// `1e-9` of the size of the objects (the diagonal of their common bounding box).
    pub distance: Option<T>,
    /// How far a traced intersection curve (a polyline) may stray from the true curve
    /// between its points; by default `1e-4` of the size of the objects.
    pub trace: Option<T>,
    /// The sine of the angle below which a curve is tangent to a surface, or two surfaces
    /// are tangent to each other (default `1e-6`).
    pub angle: T,
}

impl<T: Scalar> Default for Tolerances<T> {
    fn default() -> Self {
        Self {
            distance: None,
            trace: None,
            angle: cast(1e-6),
        }
    }
}

impl<T: Scalar> Tolerances<T> {
    /// The distance tolerance for objects of size `scale`.
    #[must_use]
    pub fn distance_for(&self, scale: T) -> T {
        self.distance.unwrap_or(scale * cast::<T>(1e-9))
    }

    /// The tracing tolerance for objects of size `scale`.
    #[must_use]
    pub fn trace_for(&self, scale: T) -> T {
        self.trace.unwrap_or(scale * cast::<T>(1e-4))
    }
}

/// Checks that the given tolerances are positive and finite.
pub(super) fn check_tolerance<T: Scalar>(t: &Tolerances<T>) -> Result<()> {
    for (name, value) in [
        ("distance tolerance", t.distance),
        ("tracing tolerance", t.trace),
        ("angle tolerance", Some(t.angle)),
    ] {
        if let Some(x) = value {
            if !(x > T::zero() && x.is_finite()) {
                return Err(Error::invalid_tolerance(
                    name,
                    "positive and finite",
                    to_f64(x),
                ));
            }
        }
    }
    Ok(())
}

/// The diagonal of the box of a tree and more boxes (at least the smallest positive
/// number, so that relative tolerances of a point-like object stay positive).
pub(super) fn scale_of_boxes<T: Scalar>(
    tree: &BoxTree<T, Vector3<T>>,
    more: impl Iterator<Item = (Vector3<T>, Vector3<T>)>,
) -> T {
    let root = &tree.nodes[tree.root];
    let (mut lo, mut hi) = (root.lo, root.hi);
    for (a, b) in more {
        lo = lo.inf(&a);
        hi = hi.sup(&b);
    }
    // The length without overflow of the squares (objects of size 1e300).
    ControlPoint::length(&(hi - lo)).max(cast(f64::MIN_POSITIVE))
}
