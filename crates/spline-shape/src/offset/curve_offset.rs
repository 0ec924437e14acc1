//! The offsets of curves, planar and in space: what an offset returns (the curve, its cusps,
//! the error bound), the curves that have offsets, and the offsets computed on their
//! projection to a plane.

use super::curve::{
    Frame, check_not_parallel, circle_factor, circle_of, fit_space_offset, sampled_cusps,
    scaled_about,
};
use super::options::OffsetOptions;
use nalgebra::{SVector, Vector2, Vector3};
use spline_algebra::offset_cusps;
use spline_core::{Error, Result, Scalar, cast};
use spline_geom::{BSpline, NurbsCurve, ParamCurve, PlanarCurve};

/// Parameter accuracy of the cusps, relative to the length of the domain.
pub const CUSP_ACCURACY: f64 = 1e-12;

/// The offset curve: an approximating B-spline, or the exact NURBS curve where there is one
/// (the offset of a circular arc is a concentric arc).
#[derive(Clone, Debug)]
pub enum OffsetShape<T: Scalar, const D: usize> {
    /// A B-spline within the tolerance of the offset.
    Polynomial(BSpline<T, SVector<T, D>>),
    /// The exact offset.
    Rational(NurbsCurve<T, D>),
}

/// A cusp of an offset: a parameter where $\kappa d = 1$ (of the curve projected to the
/// plane of the offset), so that the offset's velocity vanishes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cusp<T: Scalar, const D: usize> {
    /// The parameter on the curve (and on the offset).
    pub u: T,
    /// The point of the offset there.
    pub point: SVector<T, D>,
    /// Whether $\kappa d - 1$ changes sign there (the offset reverses direction: a corner of
    /// the approximation); otherwise the offset only stops there.
    pub sign_change: bool,
}

/// The offset of a curve: the curve, the cusps of the exact offset and the largest deviation
/// between the two measured at the check points.
#[derive(Clone, Debug)]
pub struct CurveOffset<T: Scalar, const D: usize> {
    /// The offset curve (on the domain of the original; the same parameter).
    pub curve: OffsetShape<T, D>,
    /// The cusps, increasing.
    pub cusps: Vec<Cusp<T, D>>,
    /// The largest distance between `curve` and the exact offset at the check points (zero
    /// for an exact offset).
    pub max_error: T,
}

/// Curves whose offsets this module computes (B-spline and NURBS curves in the plane or in
/// space): their projection to a plane and the cusps of the projection's offsets.
pub trait OffsetSource<T: Scalar, const D: usize>: ParamCurve<T, Point = SVector<T, D>> {
    /// The kind of the curve projected to a plane.
    type Planar: PlanarCurve<T>;

    /// The degree.
    fn offset_degree(&self) -> usize;

    /// The curve under a linear map to the plane.
    fn to_plane(&self, map: impl Fn(&SVector<T, D>) -> Vector2<T>) -> Self::Planar;

    /// The cusps of the offset of `planar` at signed distance `distance`, located to
    /// `accuracy`: `(u, sign_change)`.
    ///
    /// # Errors
    /// The errors of the cusp search (`spline_algebra::offset_cusps` for B-splines).
    fn planar_cusps(planar: &Self::Planar, distance: T, accuracy: T) -> Result<Vec<(T, bool)>>;

    /// The curve as a NURBS curve, if it is one (its offset may be exact).
    fn as_nurbs(&self) -> Option<&NurbsCurve<T, D>>;
}

impl<T: Scalar, const D: usize> OffsetSource<T, D> for BSpline<T, SVector<T, D>> {
    type Planar = BSpline<T, Vector2<T>>;

    fn offset_degree(&self) -> usize {
        self.degree()
    }

    fn to_plane(&self, map: impl Fn(&SVector<T, D>) -> Vector2<T>) -> Self::Planar {
        self.map_control_points(map)
    }

    fn planar_cusps(planar: &Self::Planar, distance: T, accuracy: T) -> Result<Vec<(T, bool)>> {
        Ok(offset_cusps(planar, distance, accuracy)?
            .iter()
            .map(|c| (c.u, c.sign_change))
            .collect())
    }

    fn as_nurbs(&self) -> Option<&NurbsCurve<T, D>> {
        None
    }
}

impl<T: Scalar, const D: usize> OffsetSource<T, D> for NurbsCurve<T, D> {
    type Planar = NurbsCurve<T, 2>;

    fn offset_degree(&self) -> usize {
        self.degree()
    }

    fn to_plane(&self, map: impl Fn(&SVector<T, D>) -> Vector2<T>) -> Self::Planar {
        self.map_control_points(map)
    }

    fn planar_cusps(planar: &Self::Planar, distance: T, accuracy: T) -> Result<Vec<(T, bool)>> {
        Ok(sampled_cusps(planar, distance, accuracy)?
            .into_iter()
            .map(|u| (u, true))
            .collect())
    }

    fn as_nurbs(&self) -> Option<&NurbsCurve<T, D>> {
        Some(self)
    }
}

/// The offset $O(u) = C(u) + d\,N(u)$ of a planar curve (B-spline or NURBS) at signed
/// distance `distance` ($N$ the unit normal to the left of the tangent) within
/// `options.tolerance`. A circular arc (a NURBS curve whose points all lie on one circle)
/// has its exact offset: the concentric arc of radius $r \mp d$, its control points scaled
/// about the centre. Otherwise the cusps ($\kappa d = 1$: exactly for B-splines,
/// `spline_algebra::offset_cusps`; by the sign changes of $\kappa d - 1$ on a grid for NURBS),
/// located to [`CUSP_ACCURACY`] of the domain, then the approximation
/// (`spline_fit::offset_curve`) with the cusps where $\kappa d - 1$ changes sign as `C⁰`
/// corners.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{BSpline, ParamCurve};
/// use spline_shape::{OffsetOptions, offset_planar_curve};
/// // y = x² on [−1, 1], offset by 1 toward the concave side: two cusps.
/// let parabola = BSpline::from_knots(2, vec![-1.0, -1.0, -1.0, 1.0, 1.0, 1.0], vec![
///     Vector2::new(-1.0, 1.0), Vector2::new(0.0, -1.0), Vector2::new(1.0, 1.0)])?;
/// let offset = offset_planar_curve(&parabola, 1.0, &OffsetOptions::default())?;
/// assert_eq!(offset.cusps.len(), 2);
/// assert!(offset.max_error <= 1e-6);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`spline_core::ErrorKind::NonFinite`] for a non-finite distance;
/// [`spline_core::ErrorKind::DegenerateGeometry`] when the offset of a circular arc collapses
/// to its centre; the errors of the cusp search and of `spline_fit::offset_curve` (a
/// corner of the curve, a tolerance that cannot be met).
pub fn offset_planar_curve<T: Scalar, C: OffsetSource<T, 2>>(
    curve: &C,
    distance: T,
    options: &OffsetOptions<T>,
) -> Result<CurveOffset<T, 2>> {
    offset_in_frame(curve, &Frame::planar(), distance, options)
}

/// The offset of a space curve along a reference direction `V` (Open CASCADE's
/// `Geom_OffsetCurve`): $O(u) = C(u) + d\,\frac{T \times V}{\lVert T \times V \rVert}$ within
/// `options.tolerance`. The point moves perpendicular to `V`, so this is the planar offset at
/// distance $-d$ of the curve projected to the plane perpendicular to `V` (in the frame
/// $e_1, e_2$ with $e_1 \times e_2 = V$), the component along `V` unchanged: its cusps are
/// those of the projection, and a NURBS curve whose projection is a circular arc has an
/// exact offset.
///
/// # Errors
/// [`spline_core::ErrorKind::NonFinite`] for a non-finite distance or direction;
/// [`spline_core::ErrorKind::DegenerateGeometry`] for a direction of zero length or parallel
/// to the tangent somewhere (`|T × V| < 10⁻⁹` on a grid of 1024 steps per piece), or an
/// offset of a circular arc that collapses to its centre; as [`offset_planar_curve`]
/// otherwise.
pub fn offset_space_curve<T: Scalar, C: OffsetSource<T, 3>>(
    curve: &C,
    distance: T,
    direction: &Vector3<T>,
    options: &OffsetOptions<T>,
) -> Result<CurveOffset<T, 3>> {
    let frame = Frame::perpendicular_to(direction)?;
    check_not_parallel(curve, &frame)?;
    offset_in_frame(curve, &frame, -distance, options)
}

/// The offset moving each point by `distance` times the unit normal of the curve's
/// projection to the frame's plane.
fn offset_in_frame<T: Scalar, const D: usize, C: OffsetSource<T, D>>(
    curve: &C,
    frame: &Frame<T, D>,
    distance: T,
    options: &OffsetOptions<T>,
) -> Result<CurveOffset<T, D>> {
    if !distance.is_finite() {
        return Err(Error::non_finite("the offset distance"));
    }
    let planar = curve.to_plane(|p| frame.project(p));
    if let Some(nurbs) = curve.as_nurbs() {
        if let Some(circle) = circle_of(&planar, curve.offset_degree()) {
            let factor = circle_factor(&circle, distance)?;
            return Ok(CurveOffset {
                curve: OffsetShape::Rational(scaled_about(nurbs, frame, &circle, factor)),
                cusps: Vec::new(),
                max_error: T::zero(),
            });
        }
    }
    let (a, b) = curve.domain();
    let found = C::planar_cusps(&planar, distance, cast::<T>(CUSP_ACCURACY) * (b - a))?;
    let corners: Vec<T> = found.iter().filter(|c| c.1).map(|c| c.0).collect();
    let (fitted, max_error) = if D == 2 {
        let fit = spline_fit::offset_curve(
            &planar,
            distance,
            options.degree,
            options.tolerance,
            &corners,
        )?;
        let widen = |q: &Vector2<T>| SVector::<T, D>::from_fn(|i, _| q[i.min(1)]);
        (fit.curve.map_control_points(widen), fit.max_error)
    } else {
        fit_space_offset(
            curve,
            &planar,
            frame,
            distance,
            &corners,
            (options.degree, options.tolerance),
        )?
    };
    let cusps = found
        .iter()
        .map(|&(u, sign_change)| {
            Ok(Cusp {
                u,
                point: curve.eval(u)? + frame.lift(&planar.unit_normal(u)?) * distance,
                sign_change,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(CurveOffset {
        curve: OffsetShape::Polynomial(fitted),
        cusps,
        max_error,
    })
}
