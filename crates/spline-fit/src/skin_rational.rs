//! Skinning rational sections with positive weights.

use crate::skin::skin;
use spline_core::{Error, ErrorKind, Result, Scalar, to_f64};
use spline_geom::{NurbsCurve, NurbsSurface};

/// A NURBS surface skinned through rational sections, with the parameter of each section
/// and the degree across them.
#[derive(Clone, Debug)]
pub struct SkinnedNurbs<T: Scalar, const D: usize> {
    /// The surface: $S(u, v_k)$ is section `k`.
    pub surface: NurbsSurface<T, D>,
    /// The parameters $v_k$ of the sections.
    pub params: Vec<T>,
    /// The degree across the sections: the one asked for (at most the number of sections
    /// less one), or lower where that one gives a weight that is not positive.
    pub degree_v: usize,
}

/// The surface through rational sections ([`skin`] on their homogeneous points), its
/// weights kept positive. Interpolating the weights of the sections across them at a
/// degree above 1 can overshoot below zero when they vary fast (four conics with middle
/// weights 1, 8, 0.2, 8 gave a weight of −19.7 at degree 3): the degree across the
/// sections is then lowered, one at a time, until every weight is positive. At degree 1
/// the net's weights are those of the compatible sections (convex combinations of the
/// given weights), so a surface is always found; [`SkinnedNurbs::degree_v`] says which
/// degree it has.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::skin_rational;
/// use spline_geom::NurbsCurve;
/// let conic = |z: f64, w: f64| NurbsCurve::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector3::new(0.0, 0.0, z), Vector3::new(1.0, 1.0, z), Vector3::new(2.0, 0.0, z)],
///     vec![1.0, w, 1.0]);
/// let sections = [conic(0.0, 1.0)?, conic(1.0, 8.0)?, conic(2.0, 0.2)?, conic(3.0, 8.0)?];
/// let skinned = skin_rational(&sections, 3, None)?;
/// assert!(skinned.surface.weights().iter().all(|&w| w > 0.0));
/// for (c, &v) in sections.iter().zip(&skinned.params) {
///     assert!((skinned.surface.eval(0.3, v)? - c.eval(0.3)?).norm() < 1e-12);
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`skin`]; [`ErrorKind::NoConvergence`] if even degree 1 gave a weight that is not
/// positive (the sections' weights span more than the floating-point range), the message
/// saying so as the library's failure, not as a value given.
pub fn skin_rational<T: Scalar, const D: usize>(
    sections: &[NurbsCurve<T, D>],
    degree_v: usize,
    params: Option<&[T]>,
) -> Result<SkinnedNurbs<T, D>> {
    let homogeneous: Vec<_> = sections.iter().map(|c| c.homogeneous().clone()).collect();
    // Degree 0 and too few sections are refused by `skin`.
    let mut degree = degree_v.min(sections.len().saturating_sub(1).max(1));
    loop {
        let skinned = skin(&homogeneous, degree, params)?;
        let net = skinned.surface.control_points();
        let lowest = net
            .iter()
            .map(|h| h.weight)
            .fold(net[0].weight, |m, w| if w < m { w } else { m });
        if net
            .iter()
            .all(|h| h.weight > T::zero() && h.weight.is_finite())
        {
            return Ok(SkinnedNurbs {
                surface: NurbsSurface::from_homogeneous(skinned.surface)?,
                params: skinned.params,
                degree_v: degree,
            });
        }
        if degree <= 1 {
            return Err(Error::new(
                ErrorKind::NoConvergence,
                format!(
                    "skinning the rational sections gave a weight of {} in the surface's net even at degree 1 across them",
                    to_f64(lowest)
                ),
            ));
        }
        degree -= 1;
    }
}
