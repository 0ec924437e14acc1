//! The curvature features of a surface together: parabolic lines, umbilics and ridges from
//! one computation of the curvature numerators, in parameters or in space for drawing
//! (above the numerators, the zero sets, the ridges and the umbilics, which do not know it).

use crate::parametric_ridges::ridges_from;
use crate::surface_numerators::{curvature_numerators, parabolic_lines_from};
use crate::umbilics::umbilics_from;
use crate::{CommonZeros, Ridges, SurfaceRidges, UvPolyline, ZeroSet};
use nalgebra::Vector3;
use spline_core::Result;
use spline_geom::{NurbsSurface, Surface};

/// The curvature features of a parametric surface in `(u, v)` ([`surface_features`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceFeatures {
    /// The parabolic lines ([`crate::parabolic_lines`]).
    pub parabolic_lines: ZeroSet,
    /// The umbilics ([`crate::umbilics`]).
    pub umbilics: CommonZeros,
    /// The red and blue ridges ([`crate::surface_ridges`]).
    pub ridges: SurfaceRidges,
}

/// The parabolic lines, umbilics and ridges of a surface with 3-D points, polynomial or
/// rational: what [`crate::parabolic_lines`], [`crate::umbilics`] and
/// [`crate::surface_ridges`] give, with the curvature numerators they share computed once.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsSurface;
/// let torus = NurbsSurface::torus(Vector3::zeros(), Vector3::z(), 2.0, 1.0)?;
/// let features = spline_algebra::surface_features(&torus, 8)?;
/// assert_eq!(features.parabolic_lines.curves.len(), 2); // the top and bottom circles
/// assert!(features.umbilics.points.is_empty());
/// // Every meridian and parallel is a ridge of constant curvature.
/// assert!(!features.ridges.red_constant.is_empty() || !features.ridges.blue_constant.is_empty());
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`crate::parabolic_lines`], [`crate::umbilics`] and [`crate::surface_ridges`].
pub fn surface_features(surface: &NurbsSurface<f64, 3>, samples: usize) -> Result<SurfaceFeatures> {
    let numerators = curvature_numerators(surface)?;
    let parabolic_lines = parabolic_lines_from(&numerators, samples)?;
    let umbilics = umbilics_from(surface, &numerators)?;
    let ridges = ridges_from(surface, &numerators, samples, &umbilics)?;
    Ok(SurfaceFeatures {
        parabolic_lines,
        umbilics,
        ridges,
    })
}

/// The curvature features of a surface as curves and points in space, ready to be drawn over
/// its picture (`spline_io::svg::feature_overlays`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceFeatureLines {
    /// The parabolic lines ([`crate::parabolic_lines`]) as polylines.
    pub parabolic: Vec<Vec<Vector3<f64>>>,
    /// The ridges where `κ₂` is extremal ([`crate::surface_ridges`], red).
    pub red_ridges: Vec<Vec<Vector3<f64>>>,
    /// The ridges where `κ₁` is extremal (blue).
    pub blue_ridges: Vec<Vec<Vector3<f64>>>,
    /// The umbilics ([`crate::umbilics`]), those at poles included.
    pub umbilics: Vec<Vector3<f64>>,
}

/// The parabolic lines, ridges ([`crate::surface_ridges`]) and umbilics (those at poles
/// included) of a surface, mapped into space, the lines with `samples` points per patch
/// width.
///
/// # Errors
/// As [`crate::parabolic_lines`], [`crate::surface_ridges`] and [`crate::umbilics`].
pub fn surface_feature_lines(
    surface: &NurbsSurface<f64, 3>,
    samples: usize,
) -> Result<SurfaceFeatureLines> {
    let lift = |curves: &[UvPolyline]| -> Result<Vec<Vec<Vector3<f64>>>> {
        Ok(on_surface(surface, curves)?
            .into_iter()
            .map(|line| line.points)
            .collect())
    };
    let SurfaceFeatures {
        parabolic_lines,
        umbilics,
        ridges,
    } = surface_features(surface, samples)?;
    Ok(SurfaceFeatureLines {
        parabolic: lift(&parabolic_lines.curves)?,
        red_ridges: lift(&ridges.red)?,
        blue_ridges: lift(&ridges.blue)?,
        umbilics: umbilics
            .points
            .iter()
            .chain(&umbilics.poles)
            .map(|p| surface.eval(p[0], p[1]))
            .collect::<Result<_>>()?,
    })
}
/// A feature curve in the parameter plane with its points on the surface (or on the graph
/// of a function), vertex by vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LiftedPolyline {
    /// The vertices in `(u, v)`.
    pub uv: UvPolyline,
    /// The same vertices on the surface: `S(u, v)`, or `(u, v, s(u, v))` on a graph.
    pub points: Vec<Vector3<f64>>,
}

/// Polylines in `(u, v)` with their points `S(u, v)` on the surface.
///
/// # Errors
/// As [`NurbsSurface::eval`] (a vertex outside the domain).
pub fn on_surface(
    surface: &NurbsSurface<f64, 3>,
    curves: &[UvPolyline],
) -> Result<Vec<LiftedPolyline>> {
    lift(curves, |u, v| surface.eval(u, v))
}

/// Polylines in `(u, v)` with their points `(u, v, s(u, v))` on the graph of a function.
///
/// # Errors
/// As [`Surface::eval`] (a vertex outside the domain).
pub fn on_graph(s: &Surface<f64, f64>, curves: &[UvPolyline]) -> Result<Vec<LiftedPolyline>> {
    lift(curves, |u, v| s.eval(u, v).map(|z| Vector3::new(u, v, z)))
}

fn lift(
    curves: &[UvPolyline],
    point: impl Fn(f64, f64) -> Result<Vector3<f64>>,
) -> Result<Vec<LiftedPolyline>> {
    curves
        .iter()
        .map(|uv| {
            Ok(LiftedPolyline {
                points: uv
                    .iter()
                    .map(|p| point(p[0], p[1]))
                    .collect::<Result<_>>()?,
                uv: uv.clone(),
            })
        })
        .collect()
}

/// The curvature features of a function `s(u, v)`, taken as its graph `(u, v, s)`
/// ([`function_features`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FunctionFeatures {
    /// The parabolic lines: the zero set of the Hessian determinant
    /// `s_uu s_vv − s_uv²` ([`crate::hessian_determinant`]), whose sign is the sign of the
    /// graph's Gaussian curvature.
    pub parabolic_lines: ZeroSet,
    /// The red and blue ridges of thesis §5.7 ([`crate::ridges`]).
    pub ridges: Ridges,
}

/// The parabolic lines and ridges of the graph of a function, the lines with `samples`
/// points per patch width.
///
/// ```
/// use spline_core::KnotVector;
/// use spline_geom::Surface;
/// // s(u, v) = u² − v² on [−1, 1]²: a saddle, K < 0 everywhere, no parabolic line.
/// let knots = KnotVector::new(2, vec![-1.0, -1.0, -1.0, 1.0, 1.0, 1.0])?;
/// let (a, c) = ([1.0, -1.0, 1.0], [-1.0, 1.0, -1.0]); // Bézier coefficients of u², −v²
/// let coefficients = (0..3).flat_map(|i| (0..3).map(move |j| a[i] + c[j])).collect();
/// let saddle = Surface::new(knots.clone(), knots, coefficients)?;
/// let features = spline_algebra::function_features(&saddle, 8)?;
/// assert!(features.parabolic_lines.curves.is_empty());
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`crate::hessian_determinant`], [`crate::zero_set`] and [`crate::ridges`].
pub fn function_features(s: &Surface<f64, f64>, samples: usize) -> Result<FunctionFeatures> {
    let determinant = crate::hessian_determinant(s)?;
    Ok(FunctionFeatures {
        parabolic_lines: crate::zero_set(&determinant.value, samples)?,
        ridges: crate::ridges(s, samples)?,
    })
}
