//! Ridges of parametric surfaces `S(u, v)` (polynomial or rational): where a principal
//! curvature is extremal along its own line of curvature, coloured per principal curvature
//! (thesis 7.1), found patch by patch by certified exclusion and marching.
//!
//! The exact square-root-free ridge polynomial of a bicubic patch has a degree far above
//! [`spline_core::MAX_DEGREE`] (already `Δ = Ĥ² − 4ÂK̂`, one of its factors, is of degree
//! 28 in each direction, and the condition multiplies it by products of the fundamental
//! forms of degree 20 and more), so it is never formed: the ridge function of
//! [`crate::ridge_function`] is evaluated from the curvature numerators (which are
//! exact Bernstein patches of moderate degree), as enclosures over boxes from their
//! Bernstein bounds (to exclude boxes) and pointwise (to locate the ridges in the boxes left).

mod march;

use crate::bezier_patch::Patch;
use crate::polylines::{UvPolyline, chain};
use crate::ridge_function::{best_form, degenerate, snapped};
use crate::surface_numerators::{CurvatureNumerators, curvature_numerators};
use crate::umbilics::CommonZeros;
use crate::zero_set::{bezier_patches, check_samples};
use march::{Marcher, march_all};
use spline_core::Result;
use spline_geom::NurbsSurface;

/// Finest subdivision of a patch: `2^MAX_LEVEL` boxes per patch width.
const MAX_LEVEL: u32 = 8;
/// Coarsest: `2^MIN_LEVEL` boxes per patch width, whatever `samples` asks.
const MIN_LEVEL: u32 = 4;

/// The ridges of a parametric surface ([`surface_ridges`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceRidges {
    /// Ridges of the smaller principal curvature `κ₂` (normal `S_u × S_v`), as polylines in
    /// `(u, v)`: red, as the smaller eigenvalue `λ₂` of a function's Hessian ([`crate::Ridges`]).
    pub red: Vec<UvPolyline>,
    /// Ridges of the larger principal curvature `κ₁`: blue.
    pub blue: Vec<UvPolyline>,
    /// Patches `[[u0, v0], [u1, v1]]` on which the red ridge condition vanishes identically:
    /// `κ₂` is constant along its lines of curvature there (the meridians of a torus, the
    /// parallels of any surface of revolution), every line of curvature is a degenerate ridge.
    pub red_constant: Vec<[[f64; 2]; 2]>,
    /// Likewise for `κ₁`.
    pub blue_constant: Vec<[[f64; 2]; 2]>,
    /// Centres of boxes where the ridges could not be resolved (crossings that do not pair up).
    pub singular: Vec<[f64; 2]>,
    /// The umbilics of the surface ([`crate::umbilics`], regular ones and those on singular
    /// parameter lines), where ridges of both colours meet and change colour.
    pub umbilics: Vec<[f64; 2]>,
}

/// The ridges of a parametric surface with 3-D points, polynomial or rational: the curves
/// where a principal curvature `κᵢ` is extremal along its own principal direction, `κ₁ ≥ κ₂`
/// for the normal `S_u × S_v` (blue `κ₁`, red `κ₂`; where the surface bends towards that
/// normal `κ₁` has the smaller radius, thesis 7.1's blue sphere; reversing the orientation
/// swaps the colours).
///
/// Per Bézier patch of the curvature numerators ([`crate::curvature_numerators`]) and per
/// colour, the ridge function `g` (a positive multiple of `∂κᵢ/∂tᵢ` for a polynomial
/// direction field `tᵢ`, see the module `ridge_function`) is enclosed on boxes by interval
/// arithmetic from the Bernstein bounds of `Ê … N̂`, `W` and their derivatives; boxes whose
/// enclosure excludes zero (for either direction form) hold no ridge of that colour and are
/// dropped, the others are quartered down to `2^k` boxes per patch width, `2^k` the power of two
/// at least `samples` (at least 16, at most 256). In each remaining box the direction form
/// that stays farther from zero fixes the sign of `g`; its sign changes along the box edges
/// are located by the Illinois method, kept when the ridge condition with the unit principal
/// direction vanishes there (a zero of the direction form is not a ridge), and joined across
/// the box (two crossings: a segment; four: paired by the sign at the centre; in a box
/// holding an umbilic, each joined to the umbilic). Along patch boundaries where the sign of
/// the ridge condition jumps (the third derivatives of the surface jump at a simple knot) the
/// boundary itself is a ridge, as for the meridians of [`crate::revolution_features`]. Where
/// the parametrisation is singular
/// (`Â = 0`, a pole) the function is evaluated `10⁻²` of the patch inside.
///
/// What is certain: no ridge in the dropped boxes (up to rounding), every vertex on a ridge
/// (a root of `g` on a box edge). What is not: a ridge that enters and leaves a finest box
/// through the same edge, or a loop inside one, is missed; such features are smaller than a
/// box (`1/2^k` of a patch).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsSurface;
/// // The ellipsoid with semi-axes 1.5, 2, 1: its ridges are its three principal sections.
/// let sphere = NurbsSurface::sphere(Vector3::zeros(), 1.0)?;
/// let e = sphere.map_control_points(|p| Vector3::new(1.5 * p.x, 2.0 * p.y, p.z));
/// let ridges = spline_algebra::surface_ridges(&e, 8)?;
/// for line in ridges.red.iter().chain(&ridges.blue) {
///     for p in line {
///         let x = e.eval(p[0], p[1])?;
///         assert!(x.x.abs().min(x.y.abs()).min(x.z.abs()) < 1e-6);
///     }
/// }
/// assert_eq!(ridges.umbilics.len(), 4);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`spline_core::ErrorKind::InvalidArgument`] if `samples` is 0 or above 10 000; as
/// [`crate::curvature_numerators`] and [`crate::umbilics`].
pub fn surface_ridges(surface: &NurbsSurface<f64, 3>, samples: usize) -> Result<SurfaceRidges> {
    let umbilics = crate::umbilics(surface)?;
    surface_ridges_with_umbilics(surface, samples, &umbilics)
}

/// [`surface_ridges`] with the surface's umbilics already found by [`crate::umbilics`] (a
/// caller that reports them too need not search twice).
///
/// # Errors
/// [`spline_core::ErrorKind::InvalidArgument`] if `samples` is 0 or above 10 000; as
/// [`crate::curvature_numerators`].
pub fn surface_ridges_with_umbilics(
    surface: &NurbsSurface<f64, 3>,
    samples: usize,
    umbilics: &CommonZeros,
) -> Result<SurfaceRidges> {
    check_samples(samples)?;
    ridges_from(surface, &curvature_numerators(surface)?, samples, umbilics)
}

/// [`surface_ridges_with_umbilics`] from the surface's curvature numerators, already
/// computed.
pub(crate) fn ridges_from(
    surface: &NurbsSurface<f64, 3>,
    n: &CurvatureNumerators<f64>,
    samples: usize,
    umbilics: &CommonZeros,
) -> Result<SurfaceRidges> {
    check_samples(samples)?;
    let level = (samples.next_power_of_two().trailing_zeros()).clamp(MIN_LEVEL, MAX_LEVEL);
    let bu = n.first[0].knots_u().domain_breaks();
    let bv = n.first[0].knots_v().domain_breaks();
    let mut columns: Vec<Vec<Patch>> = Vec::new();
    for s in n.first.iter().chain(&n.second) {
        columns.push(bezier_patches(s, &bu, &bv)?.iter().map(Patch::of).collect());
    }
    let polynomial = surface.weights().iter().all(|&w| w == surface.weights()[0]);
    let weights = if polynomial {
        None
    } else {
        let w = surface.homogeneous().map_control_points(|c| c.weight);
        Some(bezier_patches(&w, &bu, &bv)?)
    };
    let mut umbilic_points = umbilics.points.clone();
    umbilic_points.extend(&umbilics.poles);
    let area_scale = n
        .area
        .control_points()
        .iter()
        .fold(0.0f64, |m, &x| m.max(x.abs()));
    let mut out = SurfaceRidges {
        umbilics: umbilic_points.clone(),
        ..SurfaceRidges::default()
    };
    let all_factors: Vec<[Patch; 7]> = (0..columns[0].len())
        .map(|k| {
            let first = &columns[0][k];
            let w = match &weights {
                Some(w) => Patch::of(&w[k]),
                None => Patch::one(first.u, first.v),
            };
            std::array::from_fn(|i| {
                if i < 6 {
                    columns[i][k].clone()
                } else {
                    w.clone()
                }
            })
        })
        .collect();
    let (pairs, mut found) = march_all(&all_factors, level, area_scale, &umbilic_points);
    let (red, blue): (Vec<Marcher<'_>>, Vec<Marcher<'_>>) =
        pairs.into_iter().map(|[r, b]| (r, b)).unzip();
    let mut pieces: [Vec<UvPolyline>; 2] = [Vec::new(), Vec::new()];
    for (colour, mut marchers) in [red, blue].into_iter().enumerate() {
        let constant_list = if colour == 0 {
            &mut out.red_constant
        } else {
            &mut out.blue_constant
        };
        for patch in &mut found {
            let f = std::mem::take(&mut patch[colour]);
            pieces[colour].extend(f.pieces);
            out.singular.extend(f.singular);
            constant_list.extend(f.constant);
        }
        jumps(&mut marchers, bv.len() - 1, &mut pieces[colour]);
    }
    let ((u0, u1), (v0, v1)) = surface.domain();
    let tol = 1e-9 * (u1 - u0).max(v1 - v0);
    // Segments along grid lines are found from both sides: keep one of each.
    let key = |p: &[f64; 2]| [(p[0] / tol).round() as i64, (p[1] / tol).round() as i64];
    for list in &mut pieces {
        let mut seen = std::collections::HashSet::new();
        list.retain(|piece| {
            if piece.len() != 2 {
                return true;
            }
            let (a, b) = (key(&piece[0]), key(&piece[1]));
            seen.insert(if a <= b { (a, b) } else { (b, a) })
        });
    }
    let [red, blue] = pieces;
    out.red = chain(red, tol);
    out.blue = chain(blue, tol);
    Ok(out)
}

/// Ridges along patch boundaries where the ridge function jumps in sign (the third
/// derivatives of the surface jump across a simple knot): at the finest grid nodes of each
/// interior patch edge, the signs of `D_t κ` from the two sides (each with its better
/// direction form, oriented alike) differ; runs of such nodes are segments of ridge.
fn jumps(marchers: &mut [Marcher<'_>], patches_v: usize, pieces: &mut Vec<UvPolyline>) {
    let n = 1usize << marchers.first().map_or(0, |m| m.level);
    let count = marchers.len();
    for k in 0..count {
        // The neighbour across u (next row of patches) and across v (next column).
        for across_u in [true, false] {
            let other = if across_u { k + patches_v } else { k + 1 };
            if other >= count || (!across_u && (k + 1) % patches_v == 0) {
                continue;
            }
            let mut run: Option<[f64; 2]> = None;
            for j in 0..=n {
                // Node j on the shared edge, as seen from either patch.
                let (a, b) = if across_u {
                    ((n, j), (0, j))
                } else {
                    ((j, n), (j, 0))
                };
                let p = marchers[k].point(a.0, a.1);
                let flip = match (
                    marchers[k].corner(a.0, a.1),
                    marchers[other].corner(b.0, b.1),
                ) {
                    (Some(x), Some(y)) if !degenerate(&x) && !degenerate(&y) => {
                        let (fx, fy) = (best_form(&x), best_form(&y));
                        let (tx, ty) = (x.t[fx], y.t[fy]);
                        let aligned = tx[0] * ty[0] + tx[1] * ty[1] >= 0.0;
                        let (gx, gy) = (snapped(&x, fx), snapped(&y, fy));
                        gx != 0.0 && gy != 0.0 && ((gx > 0.0) == (gy > 0.0)) != aligned
                    }
                    _ => false,
                };
                match (flip, run) {
                    (true, Some(start)) => {
                        pieces.push(vec![start, p]);
                        run = Some(p);
                    }
                    (true, None) => run = Some(p),
                    (false, _) => run = None,
                }
            }
        }
    }
}
