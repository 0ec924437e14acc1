//! The curves of features of a surface of revolution $(f(z)\cos\theta, f(z)\sin\theta, z)$
//! (thesis ch. 7): all of them are circles `z = const`, where a polynomial in the meridian
//! radius `f` and its derivatives changes sign. With $w = 1 + f'^2$ and `f > 0`:
//! - Gaussian curvature $K = -f'' / (f\\, w^2)$: the **parabolic circles** are the sign
//!   changes of `f″` (hyperbolic where `f″ > 0`);
//! - the principal curvatures are $\kappa_m = -f'' / w^{3/2}$ along the meridians and
//!   $\kappa_p = 1 / (f\\, w^{1/2})$ along the parallels; $\kappa_p$ is constant along its
//!   line of curvature (a parallel), so the **ridge circles** are the extrema of $\kappa_m$
//!   along the meridians: $\kappa_m' = -\big(f'''\\,w - 3 f' f''^2\big) / w^{5/2}$, the sign
//!   changes of $R = f''' (1 + f'^2) - 3 f' f''^2$;
//! - the **flecnodal circles** (an asymptotic line with contact of order four) are the sign
//!   changes of $F = 3 f' f'' + f f'''$ inside the hyperbolic region (digest of the thesis).
//!
//! The numerators are B-splines built with the product algebra, with their Jacobians with
//! respect to the coefficients of `f` carried along by the product rule.

use crate::curves::Differentiated;
use crate::numerator::Tracked;
use crate::roots::{sign_change_params, zeros};
use nalgebra_sparse::CsrMatrix;
use spline_core::{Error, ErrorKind, Result, Scalar, cast};
use spline_geom::BSpline;

/// The numerators whose sign changes are the feature circles of a surface of revolution,
/// each with its Jacobian with respect to the coefficients of the meridian radius `f`.
#[derive(Clone, Debug)]
pub struct RevolutionNumerators<T> {
    /// `f″`: parabolic circles.
    pub parabolic: Differentiated<T>,
    /// $R = f''' (1 + f'^2) - 3 f' f''^2$: ridge circles.
    pub ridge: Differentiated<T>,
    /// $F = 3 f' f'' + f f'''$: flecnodal circles (where `f″ > 0`).
    pub flecnodal: Differentiated<T>,
}

/// A ridge circle: an extremum of the meridian curvature $\kappa_m = -f''/(1 + f'^2)^{3/2}$
/// along the meridians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RidgeCircle<T> {
    /// Its height `z`.
    pub z: T,
    /// Whether $\kappa_m$ has a maximum there (else a minimum).
    pub maximum: bool,
}

/// The feature circles of a surface of revolution, by their heights `z`, increasing.
#[derive(Clone, Debug, PartialEq)]
pub struct RevolutionFeatures<T> {
    /// Parabolic circles (`K` changes sign).
    pub parabolic: Vec<T>,
    /// Ridge circles (the meridian curvature has an extremum).
    pub ridges: Vec<RidgeCircle<T>>,
    /// Flecnodal circles inside the hyperbolic region.
    pub flecnodal: Vec<T>,
}

/// The numerators of the feature circles of the surface of revolution of the meridian radius
/// `f(z)` ([`RevolutionNumerators`]).
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for a degree below 3 (`f‴` is needed); the errors of the
/// product algebra.
pub fn revolution_numerators<T: Scalar>(
    meridian: &BSpline<T, T>,
) -> Result<RevolutionNumerators<T>> {
    if meridian.degree() < 3 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the features of a surface of revolution need a meridian of degree 3 or more (f''' enters), got {}",
                meridian.degree()
            ),
        )
        .with_value(meridian.degree() as f64)
        .with_interval(3.0, f64::INFINITY));
    }
    let n = meridian.control_points().len();
    let identity = CsrMatrix::identity(n);
    let f = Tracked::leaf(meridian.clone(), Some(identity));
    let d1 = f.derivative(1)?;
    let d2 = f.derivative(2)?;
    let d3 = f.derivative(3)?;
    // R = f‴ + f‴ f′² − 3 f′ f″².
    let d1_squared = d1.times(&d1)?;
    let ridge = d3
        .plus(&d3.times(&d1_squared)?)?
        .minus(&d1.times(&d2.times(&d2)?)?.scaled(cast(3.0)))?
        .cleaned();
    // F = 3 f′ f″ + f f‴.
    let flecnodal = d1
        .times(&d2)?
        .scaled(cast(3.0))
        .plus(&f.times(&d3)?)?
        .cleaned();
    Ok(RevolutionNumerators {
        parabolic: d2.cleaned().differentiated(),
        ridge: ridge.differentiated(),
        flecnodal: flecnodal.differentiated(),
    })
}

/// The feature circles of the surface of revolution of the meridian radius `f(z)`: parabolic
/// circles, ridge circles with their kind and flecnodal circles, each where its numerator
/// changes sign (crossings found by the root isolation of [`zeros`], jumps at knots where
/// the third derivative is discontinuous included; `accuracy` in `z`).
///
/// ```
/// use spline_geom::BSpline;
/// // f(z) = 2 + z³ − z on [−1, 1] (a Bézier cubic): f″ = 6z, one parabolic circle at z = 0.
/// let f = BSpline::from_knots(
///     3,
///     vec![-1.0f64, -1.0, -1.0, -1.0, 1.0, 1.0, 1.0, 1.0],
///     vec![2.0, 10.0 / 3.0, 2.0 / 3.0, 2.0],
/// )?;
/// let features = spline_algebra::revolution_features(&f, 1e-12)?;
/// assert_eq!(features.parabolic.len(), 1);
/// assert!(f64::abs(features.parabolic[0]) < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for a degree below 3 or a radius that reaches zero on the
/// domain (the surface meets its axis); the errors of [`revolution_numerators`] and
/// [`zeros`].
pub fn revolution_features<T: Scalar>(
    meridian: &BSpline<T, T>,
    accuracy: T,
) -> Result<RevolutionFeatures<T>> {
    let numerators = revolution_numerators(meridian)?;
    let (a, b) = meridian.domain();
    let radius_zeros = zeros(meridian, accuracy)?;
    if let Some(zero) = radius_zeros.first() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "the meridian radius reaches zero at z = {} (the surface meets its axis there)",
                spline_core::to_f64(zero.at())
            ),
        )
        .with_value(spline_core::to_f64(zero.at())));
    }
    let positive = meridian.eval(a)? > T::zero();
    if !positive {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "the meridian radius must be positive",
        ));
    }
    let inside = |z: &T| *z > a && *z < b;
    let parabolic: Vec<T> = sign_change_params(&numerators.parabolic.value, accuracy)?
        .into_iter()
        .filter(inside)
        .collect();
    let ridge = &numerators.ridge.value;
    let ridges = sign_change_params(ridge, accuracy)?
        .into_iter()
        .filter(inside)
        .map(|z| {
            // κ_m′ = −R / w^{5/2}: κ_m rises then falls (a maximum) where R goes from
            // negative to positive.
            let step = accuracy.max((b - a) * cast(1e-9));
            let before = ridge.eval((z - step).max(a))?;
            let after = ridge.eval((z + step).min(b))?;
            Ok(RidgeCircle {
                z,
                maximum: before < after,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let second = &numerators.parabolic.value;
    let flecnodal = sign_change_params(&numerators.flecnodal.value, accuracy)?
        .into_iter()
        .filter(inside)
        .map(|z| second.eval(z).map(|f2| (z, f2)))
        .collect::<Result<Vec<_>>>()?
        .into_iter()
        .filter(|&(_, f2)| f2 > T::zero())
        .map(|(z, _)| z)
        .collect();
    Ok(RevolutionFeatures {
        parabolic,
        ridges,
        flecnodal,
    })
}
