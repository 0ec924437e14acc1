//! The curvature features of a surface gathered in space for drawing: parabolic lines,
//! ridges and umbilics (above the numerators, the zero sets, the ridges and the umbilics,
//! which do not know it).

use nalgebra::Vector3;
use spline_core::Result;
use spline_geom::NurbsSurface;

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
    let parabolic = lift(&crate::parabolic_lines(surface, samples)?.curves)?;
    let ridges = crate::surface_ridges(surface, samples)?;
    let umbilics = crate::umbilics(surface)?;
    Ok(SurfaceFeatureLines {
        parabolic,
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
