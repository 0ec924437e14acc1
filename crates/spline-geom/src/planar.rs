//! The scale-invariant formulas of differential geometry behind [`crate::ParamCurve`] and
//! [`crate::PlanarCurve`]: unit vectors, signed curvature (planar), curvature magnitude (any
//! dimension).

use nalgebra::Vector2;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, to_f64};

fn degenerate(u: f64) -> Error {
    Error::new(
        ErrorKind::DegenerateGeometry,
        format!(
            "the curve has zero velocity at u = {u}: tangent and curvature are undefined there"
        ),
    )
}

/// `v / |v|` computed on `v / max|v_i|`, so that the length neither overflows nor underflows;
/// `None` for the zero vector.
pub(crate) fn unit<T: Scalar, P: ControlPoint<T>>(v: P) -> Option<P> {
    let scale = v.max_abs();
    if !(scale > T::zero()) || !scale.is_finite() {
        return None;
    }
    let w = v * (T::one() / scale);
    // 1/scale overflows for subnormal scales: divide instead.
    let w = if w.all_finite() {
        w
    } else {
        P::from_coords(|i| v.coord(i) / scale)
    };
    Some(w * (T::one() / w.length()))
}

/// `v / s` coordinate by coordinate (exact scaling when `s` is a power of two; no overflow for
/// `|v_i| ≤ s`).
fn divided<T: Scalar, P: ControlPoint<T>>(v: &P, s: T) -> P {
    P::from_coords(|i| v.coord(i) / s)
}

/// Curvature from the first two derivatives, invariant under scaling of the coordinates:
/// `C'` and `C''` are divided by their largest coordinates `s1`, `s2` before any power is
/// formed, and `κ = g(Ĉ', Ĉ'') · (s2 / s1) / s1`, where `g` is the formula on the scaled
/// vectors (`signed`: the planar wedge, otherwise the magnitude).
///
/// # Errors
/// [`ErrorKind::DegenerateGeometry`] where the velocity vanishes;
/// [`ErrorKind::NonFinite`] when the curvature is out of the range of the scalar type.
pub(crate) fn scaled_curvature<T: Scalar, P: ControlPoint<T>>(
    d1: &P,
    d2: &P,
    u: T,
    formula: impl Fn(&P, &P) -> T,
) -> Result<T> {
    let s1 = d1.max_abs();
    if !(s1 > T::zero()) {
        return Err(degenerate(to_f64(u)));
    }
    if !(s1.is_finite() && d2.all_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!(
                "the derivatives at u = {} are too large for floating point: curvature is not computable there",
                to_f64(u)
            ),
        ));
    }
    let s2 = d2.max_abs();
    let a = divided(d1, s1);
    let (b, s2) = if s2 > T::zero() {
        (divided(d2, s2), s2)
    } else {
        (P::origin(), T::one())
    };
    let kappa = formula(&a, &b) * ((s2 / s1) / s1);
    if kappa.is_finite() {
        Ok(kappa)
    } else {
        Err(Error::new(
            ErrorKind::NonFinite,
            format!(
                "the curvature at u = {} is too large for floating point",
                to_f64(u)
            ),
        ))
    }
}

/// `a ∧ b / |a|³` for scaled derivatives.
pub(crate) fn signed_formula<T: Scalar>(a: &Vector2<T>, b: &Vector2<T>) -> T {
    let n2 = a.norm_squared();
    wedge(a, b) / (n2 * n2.sqrt())
}

/// `sqrt(|a|²|b|² − (a·b)²) / |a|³` for scaled derivatives, any dimension.
pub(crate) fn magnitude_formula<T: Scalar, P: ControlPoint<T>>(a: &P, b: &P) -> T {
    let n2 = a.length_squared();
    let cross2 = (n2 * b.length_squared() - a.dot(b).powi(2)).max(T::zero());
    cross2.sqrt() / (n2 * n2.sqrt())
}

pub(crate) fn zero_velocity<T: Scalar>(u: T) -> Error {
    degenerate(to_f64(u))
}

/// The wedge product $a \wedge b = a_x b_y - a_y b_x$ of planar vectors.
#[inline]
pub fn wedge<T: Scalar>(a: &Vector2<T>, b: &Vector2<T>) -> T {
    a.x * b.y - a.y * b.x
}
