//! Curvature extrema and torsion zeros of space curves (polynomial and rational), each the
//! set of sign changes of a B-spline numerator built with the product algebra.

use crate::curves::Differentiated;
use crate::features::{Normalisation, check_feature_degree, check_regular};
use crate::numerator::{Tracked, cross3, derivative3, dot3};
use crate::roots::sign_change_params;
use nalgebra::Vector3;
use spline_core::{Error, ErrorKind, Result, Scalar, cast};
use spline_geom::{BSpline, NurbsCurve, ParamCurve};

/// The curvature extrema and torsion zeros of a space curve.
#[derive(Clone, Debug, PartialEq)]
pub struct SpaceFeatures<T> {
    /// Parameters where the curvature `κ = |c′ × c″| / |c′|³` has a local extremum (a point
    /// where `κ` touches zero is a minimum).
    pub curvature_extrema: Vec<T>,
    /// Parameters where the torsion changes sign.
    pub torsion_zeros: Vec<T>,
    /// The curvature, when it is constant (the numerator of `κ′` vanishes identically).
    pub constant_curvature: Option<T>,
    /// `Some(0)` when the torsion vanishes identically (the curve lies in a plane).
    pub constant_torsion: Option<T>,
}

/// A space curve whose curvature extrema and torsion zeros can be located exactly.
pub trait SpaceCurveFeatures<T: Scalar> {
    /// The features, located to `accuracy` (absolute, in parameter units) by
    /// [`crate::sign_change_params`] on the numerators of `κ′` and of the torsion
    /// (`det(c′, c″, c‴)`, or for a rational curve the homogeneous `det(P, P′, P″, P‴)`);
    /// zeros at the ends of the domain are not reported.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] for degree below 2; [`ErrorKind::InvalidTolerance`]
    /// for an accuracy that is not positive and finite;
    /// [`ErrorKind::DegreeTooHigh`] if the numerator of `κ′` is above
    /// [`spline_core::MAX_DEGREE`] (`6p − 9` polynomial, `11p − 7` rational);
    /// [`ErrorKind::DegenerateGeometry`] if the velocity vanishes somewhere.
    fn space_features(&self, accuracy: T) -> Result<SpaceFeatures<T>>;
}

impl<T: Scalar> SpaceCurveFeatures<T> for BSpline<T, Vector3<T>> {
    fn space_features(&self, accuracy: T) -> Result<SpaceFeatures<T>> {
        NurbsCurve::from_bspline(self).space_features(accuracy)
    }
}

impl<T: Scalar> SpaceCurveFeatures<T> for NurbsCurve<T, 3> {
    fn space_features(&self, accuracy: T) -> Result<SpaceFeatures<T>> {
        let polynomial = self.is_polynomial();
        let p = self.degree();
        let degree = if polynomial { (6, 9) } else { (11, 7) };
        check_feature_degree(p, degree, "curvature-extremum")?;
        let frame = Normalisation::of(self.control_points(), self.weights());
        let numerators = build(self, &frame, polynomial, false, accuracy)?;
        let constant_curvature = if numerators.curvature.is_zero() {
            let (a, b) = self.domain();
            Some(self.curvature_magnitude((a + b) * cast::<T>(0.5))?)
        } else {
            None
        };
        let planar = numerators.torsion.is_zero();
        Ok(SpaceFeatures {
            curvature_extrema: sign_change_params(&numerators.curvature.value, accuracy)?,
            torsion_zeros: if planar {
                Vec::new()
            } else {
                sign_change_params(&numerators.torsion.value, accuracy)?
            },
            constant_curvature,
            constant_torsion: planar.then(T::zero),
        })
    }
}

/// The numerators of `κ′` and of the torsion of a rational space curve with their
/// Jacobians with respect to the weighted control points $[w_0 x_0, w_0 y_0, w_0 z_0, w_0,
/// w_1 x_1, \dots]$.
///
/// With `P = (X̄, W)` the homogeneous container, $N = \bar X' W - \bar X W'$ (so
/// $C' = N / W^2$) and $M = W \bar X' \times \bar X'' + W' \bar X'' \times \bar X + W''
/// \bar X \times \bar X'$ (so $C' \times C'' = M / W^3$), the curvature is
/// $\kappa^2 = W^6 |M|^2 / |N|^6$ and
/// $$(\kappa^2)' = \frac{2 W^5}{|N|^8} \Big( (M \cdot M') W |N|^2 + 3 W' |M|^2 |N|^2 -
/// 3 W |M|^2 (N \cdot N') \Big),$$
/// the bracket being the curvature numerator (degree `11p − 7`). The torsion numerator is
/// $-\det(P, P', P'', P''') = W^4 \det(C', C'', C''')$ (degree `4p − 6`), positive where
/// the torsion is.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsCurve;
/// // The twisted cubic (u, u², u³) on [0, 1]: torsion 3 / (9u⁴ + 9u² + 1) · … > 0.
/// let c = NurbsCurve::from_knots(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0], vec![
///     Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0 / 3.0, 0.0, 0.0),
///     Vector3::new(2.0 / 3.0, 1.0 / 3.0, 0.0), Vector3::new(1.0, 1.0, 1.0)],
///     vec![1.0, 2.0, 1.0, 1.0])?;
/// let n = spline_algebra::space_numerators(&c)?;
/// assert_eq!(n.torsion.jacobian.ncols(), 16);
/// assert!(n.torsion.value.eval(0.5)? > 0.0);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for degree below 2; [`ErrorKind::DegreeTooHigh`] if
/// `11p − 7` exceeds [`spline_core::MAX_DEGREE`] (degree 4 and above).
pub fn space_numerators<T: Scalar>(curve: &NurbsCurve<T, 3>) -> Result<SpaceNumerators<T>> {
    check_feature_degree(curve.degree(), (11, 7), "curvature-extremum")?;
    let n = build(curve, &Normalisation::identity(), false, true, T::zero())?;
    Ok(SpaceNumerators {
        curvature_extremum: n.curvature.differentiated(),
        torsion: n.torsion.differentiated(),
    })
}

/// The Hessians of the numerators of [`space_numerators`] with respect to the weighted
/// control points `x = (w x, w y, w z, w)` of each point: `[curvature_extremum, torsion]`,
/// row `k` of each the symmetric matrix $\partial^2 c_k / \partial x \partial x$ (the exact
/// Jacobians run on dual numbers, one variable seeded at a time: `4n` runs).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsCurve;
/// let curve = NurbsCurve::from_knots(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
///     vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 0.0, 0.5),
///          Vector3::new(1.0, 1.0, 0.0), Vector3::new(0.0, 1.0, 1.0)],
///     vec![1.0, 0.8, 1.2, 1.0])?;
/// let [g, t] = spline_algebra::space_numerator_hessians(&curve)?;
/// assert_eq!((g.left_dim(), t.left_dim()), (16, 16));
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`space_numerators`].
pub fn space_numerator_hessians(
    curve: &NurbsCurve<f64, 3>,
) -> Result<[crate::SparseBilinear<f64>; 2]> {
    crate::features::numerator_hessians(curve, |dual| {
        let n = space_numerators(dual)?;
        Ok([n.curvature_extremum, n.torsion])
    })
}

/// The feature numerators of a space curve ([`space_numerators`]).
#[derive(Clone, Debug)]
pub struct SpaceNumerators<T> {
    /// Its sign is the sign of the derivative of the curvature.
    pub curvature_extremum: Differentiated<T>,
    /// Its sign is the sign of the torsion.
    pub torsion: Differentiated<T>,
}

/// The torsion $\tau = \det(c', c'', c''') / |c' \times c''|^2$ of a space curve at `u`.
///
/// # Errors
/// As the curve's derivatives; [`ErrorKind::DegenerateGeometry`] where `c′ × c″ = 0` (the
/// torsion is undefined there).
pub fn torsion<T: Scalar, C: ParamCurve<T, Point = Vector3<T>>>(curve: &C, u: T) -> Result<T> {
    let d = curve.derivatives(u, 3)?;
    let m = d[1].cross(&d[2]);
    let mm = m.norm_squared();
    if mm == T::zero() {
        return Err(Error::new(
            ErrorKind::DegenerateGeometry,
            format!(
                "the torsion is undefined at u = {}: c' and c'' are parallel",
                spline_core::to_f64(u)
            ),
        ));
    }
    Ok(m.dot(&d[3]) / mm)
}

struct Numerators<T: Scalar> {
    curvature: Tracked<T>,
    torsion: Tracked<T>,
}

/// The numerators in the coordinates of `frame`; `polynomial` uses the lower-degree forms
/// for unit weights (`W ≡ 1`): `M = c′ × c″`, `(M · M′) |c′|² − 3 |M|² (c′ · c″)` and
/// `det(c′, c″, c‴)`.
fn build<T: Scalar>(
    curve: &NurbsCurve<T, 3>,
    frame: &Normalisation<T, 3>,
    polynomial: bool,
    jacobian: bool,
    accuracy: T,
) -> Result<Numerators<T>> {
    let mut leaves = frame.leaves(curve.homogeneous(), jacobian);
    let w = leaves.pop().expect("four leaves");
    let x: [Tracked<T>; 3] = leaves
        .try_into()
        .map_err(|_| Error::new(ErrorKind::InvalidArgument, "three coordinates"))?;
    let three: T = cast(3.0);
    let x1 = derivative3(&x, 1)?;
    let x2 = derivative3(&x, 2)?;
    let x3 = if curve.degree() >= 3 {
        Some(derivative3(&x, 3)?)
    } else {
        None
    };
    if polynomial {
        let m = cross3(&x1, &x2)?;
        let h1 = dot3(&x1, &x1)?;
        if accuracy > T::zero() {
            check_regular(&h1.value, accuracy)?;
        }
        let h3 = dot3(&x1, &x2)?;
        let mm = dot3(&m, &m)?;
        let (torsion, curvature) = match &x3 {
            Some(x3) => {
                let m1 = cross3(&x1, x3)?;
                let torsion = dot3(&m, x3)?;
                let curvature = dot3(&m, &m1)?
                    .times(&h1)?
                    .minus(&mm.times(&h3)?.scaled(three))?;
                (torsion, curvature)
            }
            // A quadratic lies in a plane, and `M′ = c′ × c‴ = 0`.
            None => (mm.scaled(T::zero()), mm.times(&h3)?.scaled(-three)),
        };
        return Ok(Numerators {
            curvature: curvature.cleaned_if(!jacobian),
            torsion: torsion.cleaned_if(!jacobian),
        });
    }
    let w1 = w.derivative(1)?;
    let w2 = w.derivative(2)?;
    let scale3 = |a: &[Tracked<T>; 3], s: &Tracked<T>| -> Result<[Tracked<T>; 3]> {
        Ok([a[0].times(s)?, a[1].times(s)?, a[2].times(s)?])
    };
    let minus3 = |a: [Tracked<T>; 3], b: [Tracked<T>; 3]| -> Result<[Tracked<T>; 3]> {
        let [a0, a1, a2] = a;
        let [b0, b1, b2] = b;
        Ok([a0.minus(&b0)?, a1.minus(&b1)?, a2.minus(&b2)?])
    };
    let plus3 = |a: [Tracked<T>; 3], b: [Tracked<T>; 3]| -> Result<[Tracked<T>; 3]> {
        let [a0, a1, a2] = a;
        let [b0, b1, b2] = b;
        Ok([a0.plus(&b0)?, a1.plus(&b1)?, a2.plus(&b2)?])
    };
    let n = minus3(scale3(&x1, &w)?, scale3(&x, &w1)?)?;
    let n1 = minus3(scale3(&x2, &w)?, scale3(&x, &w2)?)?;
    let m = plus3(
        plus3(
            scale3(&cross3(&x1, &x2)?, &w)?,
            scale3(&cross3(&x2, &x)?, &w1)?,
        )?,
        scale3(&cross3(&x, &x1)?, &w2)?,
    )?;
    let b = dot3(&n, &n)?;
    if accuracy > T::zero() {
        check_regular(&b.value, accuracy)?;
    }
    let mm = dot3(&m, &m)?;
    let m1 = derivative3(&m, 1)?;
    let curvature = dot3(&m, &m1)?
        .times(&w)?
        .times(&b)?
        .plus(&w1.times(&mm)?.times(&b)?.scaled(three))?
        .minus(&w.times(&mm)?.times(&dot3(&n, &n1)?)?.scaled(three))?;
    // −det(P, P′, P″, P‴) = W det(X̄′, X̄″, X̄‴) − W′ det(X̄, X̄″, X̄‴)
    //                       + W″ det(X̄, X̄′, X̄‴) − W‴ det(X̄, X̄′, X̄″).
    let torsion = match &x3 {
        Some(x3) => {
            let w3 = w.derivative(3)?;
            let a = cross3(&x2, x3)?;
            let c = cross3(&x, &x1)?;
            w.times(&dot3(&x1, &a)?)?
                .minus(&w1.times(&dot3(&x, &a)?)?)?
                .plus(&w2.times(&dot3(&c, x3)?)?)?
                .minus(&w3.times(&dot3(&c, &x2)?)?)?
        }
        // Degree 2: X̄‴ = W‴ = 0 and the determinant has the zero column P‴.
        None => mm.scaled(T::zero()),
    };
    Ok(Numerators {
        curvature: curvature.cleaned_if(!jacobian),
        torsion: torsion.cleaned_if(!jacobian),
    })
}
