//! Curves seen in units near their size: the intersection search squares and multiplies
//! coordinates (norms, cross products, Newton's Jacobians), which leave the normal range of
//! `f64` for coordinates near 1e±300. Dividing every coordinate by a power of four near the
//! curves' size is exact in binary floating point and commutes with the search's square
//! roots, so the search sees the same numbers at every scale and its answer, multiplied
//! back, is the scaled answer of the unscaled problem.

use nalgebra::Vector2;
use spline_core::{ControlPoint, Result, Scalar, cast, from_count, power_of_two_scale, to_f64};
use spline_geom::ParamCurve;

/// A planar curve with its coordinates divided by `unit`.
///
/// The coefficients of the container are divided coordinate by coordinate, except the
/// weight of a homogeneous coefficient (the one coordinate a coefficient has beyond its
/// point's), so the projected curve is the curve divided by `unit`; [`Frame::of`] checks
/// this on the curve's own kind and keeps the unit 1 where it does not hold.
#[derive(Clone, Copy, Debug)]
pub(super) struct Scaled<'a, C> {
    curve: &'a C,
    unit: f64,
}

/// The unit in which a search runs: a power of four near the size of the curves.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame {
    unit: f64,
}

impl Frame {
    /// The frame for curves of `size` (their larger extent), when dividing the curve's
    /// coefficients scales its projection (both kinds of planar curve of the library).
    pub(super) fn of<T: Scalar, C: ParamCurve<T, Point = Vector2<T>>>(size: T) -> Self {
        let unit = power_of_two_scale(to_f64(size));
        if unit != 1.0 && divides_projection::<T, C>(unit) {
            Self { unit }
        } else {
            Self { unit: 1.0 }
        }
    }

    /// The frame of both curves: the same unit when each kind allows it, 1 otherwise.
    pub(super) fn of_pair<T, A, B>(size: T) -> Self
    where
        T: Scalar,
        A: ParamCurve<T, Point = Vector2<T>>,
        B: ParamCurve<T, Point = Vector2<T>>,
    {
        let (fa, fb) = (Self::of::<T, A>(size), Self::of::<T, B>(size));
        if fa.unit == fb.unit {
            fa
        } else {
            Self { unit: 1.0 }
        }
    }

    /// `curve` in this frame.
    pub(super) fn view<'a, C>(&self, curve: &'a C) -> Scaled<'a, C> {
        Scaled {
            curve,
            unit: self.unit,
        }
    }

    /// A length of the caller's units in this frame.
    pub(super) fn to_frame<T: Scalar>(self, length: T) -> T {
        length / cast::<T>(self.unit)
    }

    /// A length of this frame in the caller's units.
    pub(super) fn to_caller<T: Scalar>(self, length: T) -> T {
        length * cast::<T>(self.unit)
    }
}

/// Whether dividing a coefficient's coordinates (all but a homogeneous weight) by `unit`
/// divides its projection by `unit`, checked exactly on a coefficient with coordinates
/// 1, 2, 3, …
fn divides_projection<T: Scalar, C: ParamCurve<T, Point = Vector2<T>>>(unit: f64) -> bool {
    let sample = C::Coefficient::from_coords(|i| from_count::<T>(i + 1));
    let expected = C::project(&sample) / cast::<T>(unit);
    C::project(&divided(&sample, unit)) == expected
        && expected
            .iter()
            .all(|x| nalgebra::ComplexField::is_finite(x))
}

/// The coefficient with its coordinates divided by `unit`, the weight of a homogeneous one
/// (its last coordinate, beyond the point's two) kept.
fn divided<T: Scalar, Q: ControlPoint<T>>(q: &Q, unit: f64) -> Q {
    let cartesian = Q::DIM.min(2);
    let unit: T = cast(unit);
    Q::from_coords(|i| {
        if i < cartesian {
            q.coord(i) / unit
        } else {
            q.coord(i)
        }
    })
}

impl<T: Scalar, C: ParamCurve<T, Point = Vector2<T>>> ParamCurve<T> for Scaled<'_, C> {
    type Point = Vector2<T>;
    type Coefficient = C::Coefficient;

    fn domain(&self) -> (T, T) {
        self.curve.domain()
    }

    fn eval(&self, u: T) -> Result<Vector2<T>> {
        Ok(self.curve.eval(u)? / cast::<T>(self.unit))
    }

    fn derivatives_into(&self, u: T, out: &mut [Vector2<T>]) -> Result<()> {
        self.curve.derivatives_into(u, out)?;
        let unit: T = cast(self.unit);
        for d in out.iter_mut() {
            *d /= unit;
        }
        Ok(())
    }

    fn breaks(&self) -> Vec<T> {
        self.curve.breaks()
    }

    fn bezier_pieces(&self) -> Vec<(T, T, Vec<C::Coefficient>)> {
        let mut pieces = self.curve.bezier_pieces();
        for (_, _, coefficients) in &mut pieces {
            for q in coefficients.iter_mut() {
                *q = divided(q, self.unit);
            }
        }
        pieces
    }

    fn project(coefficient: &C::Coefficient) -> Vector2<T> {
        C::project(coefficient)
    }

    fn control_polygon(&self) -> Vec<Vector2<T>> {
        let unit: T = cast(self.unit);
        self.curve
            .control_polygon()
            .into_iter()
            .map(|p| p / unit)
            .collect()
    }
}
