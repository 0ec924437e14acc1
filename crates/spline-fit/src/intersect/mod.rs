//! Intersections with surfaces: curve–surface points and surface–surface curves (issue 12's
//! curve–curve intersection lives with the curves).

mod curve_surface;
mod curve_surface_overlap;
mod march;
mod splines;

pub use curve_surface::{CurveSurfaceHit, intersect_curve_surface};
pub use curve_surface_overlap::{
    CurveSurfaceIntersections, CurveSurfaceOverlap, intersect_curve_surface_with_overlaps,
};
pub use march::{IntersectionCurve, MAX_TRACE_POINTS, intersect_surfaces};
pub use splines::{
    IntersectionSpline, SurfaceIntersection, intersect_surfaces_as_splines, intersection_splines,
};

use crate::surface_project::BoxTree;
use nalgebra::{SMatrix, SVector, Vector3};
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
fn check_tolerance<T: Scalar>(t: &Tolerances<T>) -> Result<()> {
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
fn scale_of_boxes<T: Scalar>(
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

/// Levenberg–Marquardt for `N` unknowns and `M` equations inside the box `bounds`: returns
/// the last iterate and its residual norm.
fn lm_solve<T: Scalar, const M: usize, const N: usize>(
    residual: impl Fn(&SVector<T, N>) -> Result<(SVector<T, M>, SMatrix<T, M, N>)>,
    start: SVector<T, N>,
    (lower, upper): (SVector<T, N>, SVector<T, N>),
) -> Result<(SVector<T, N>, T)> {
    let clamp = |x: SVector<T, N>| x.sup(&lower).inf(&upper);
    let mut x = clamp(start);
    let (mut f, mut j) = residual(&x)?;
    let mut norm = f.norm();
    let mut mu: T = cast(1e-6);
    let eps = T::default_epsilon();
    for _ in 0..100 {
        if !(norm > T::zero()) {
            break;
        }
        let a = j.transpose() * j;
        let g = j.transpose() * f;
        let mut accepted = false;
        for _ in 0..40 {
            let mut damped = a;
            let mut floor = T::zero();
            for k in 0..N {
                floor = floor.max(a[(k, k)]);
            }
            for k in 0..N {
                damped[(k, k)] += mu * (a[(k, k)] + floor * eps);
            }
            let Some(chol) = damped.cholesky() else {
                mu *= cast::<T>(10.0);
                continue;
            };
            let step = chol.solve(&(-g));
            if mu < cast::<T>(1e-3) && step.norm() <= eps * (T::one() + x.norm()) {
                // A Gauss–Newton step below the rounding of x: converged (damping that
                // grows on rejections would only shorten it further).
                break;
            }
            let candidate = clamp(x + step);
            let (fc, jc) = residual(&candidate)?;
            let nc = fc.norm();
            if nc < norm {
                let moved = (candidate - x).norm();
                (x, f, j, norm) = (candidate, fc, jc, nc);
                mu = (mu * cast::<T>(0.3)).max(cast(1e-12));
                accepted = moved > eps * (T::one() + x.norm());
                break;
            }
            mu *= cast::<T>(4.0);
        }
        if !accepted {
            break;
        }
    }
    Ok((x, norm))
}
