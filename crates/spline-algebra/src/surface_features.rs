//! The curvature features of a surface together: parabolic lines, umbilics and ridges from
//! one computation of the curvature numerators, in parameters or in space for drawing
//! (above the numerators, the zero sets, the ridges and the umbilics, which do not know it).

use crate::parametric_ridges::ridges_from;
use crate::surface_numerators::{curvature_numerators, parabolic_lines_from};
use crate::umbilics::umbilics_from;
use crate::{CommonZeros, SurfaceRidges, ZeroSet};
use nalgebra::Vector3;
use spline_core::Result;
use spline_geom::NurbsSurface;

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
    let lift = |curves: &[Vec<[f64; 2]>]| -> Result<Vec<Vec<Vector3<f64>>>> {
        curves
            .iter()
            .map(|curve| curve.iter().map(|p| surface.eval(p[0], p[1])).collect())
            .collect()
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
