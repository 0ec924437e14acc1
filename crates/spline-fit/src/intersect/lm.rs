//! Levenberg–Marquardt in a box: the refinement of intersection points on curves and
//! surfaces.

use nalgebra::{SMatrix, SVector};
use spline_core::{Result, Scalar, cast};

/// Levenberg–Marquardt for `N` unknowns and `M` equations inside the box `bounds`: returns
/// the last iterate and its residual norm.
pub(super) fn lm_solve<T: Scalar, const M: usize, const N: usize>(
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
