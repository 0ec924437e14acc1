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

use crate::ridge_function::{
    Interval, Jet, NEAR_UMBILIC, Patch, RidgeValue, VANISHING, best_form, degenerate,
    degenerate_umbilic, ridge_value, singular_edges, snapped,
};
use crate::surface_numerators::curvature_numerators;
use crate::zero_set::{UvPolyline, bezier_patches, chain};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::NurbsSurface;
use std::collections::HashMap;

/// Finest subdivision of a patch: `2^MAX_LEVEL` boxes per patch width.
const MAX_LEVEL: u32 = 8;
/// Coarsest: `2^MIN_LEVEL` boxes per patch width, whatever `samples` asks.
const MIN_LEVEL: u32 = 4;
/// A crossing is kept when the gradient of the curvature is within this cosine of orthogonal
/// to the principal direction there (from the better-conditioned direction form: a zero of
/// a direction form is not a ridge, and there the cosine is of order one). At a root the
/// cosine is rounding, up to about `10⁻⁵` where the terms of `g` cancel strongly.
const GENUINE: f64 = 1e-3;

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
/// [`ErrorKind::InvalidArgument`] if `samples` is 0 or above 10 000; as
/// [`crate::curvature_numerators`] and [`crate::umbilics`].
pub fn surface_ridges(surface: &NurbsSurface<f64, 3>, samples: usize) -> Result<SurfaceRidges> {
    if samples == 0 || samples > 10_000 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("the samples per patch must be between 1 and 10000, got {samples}"),
        ));
    }
    let level = (samples.next_power_of_two().trailing_zeros()).clamp(MIN_LEVEL, MAX_LEVEL);
    let n = curvature_numerators(surface)?;
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
    let umbilics = crate::umbilics(surface)?;
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
    let mut pieces: [Vec<UvPolyline>; 2] = [Vec::new(), Vec::new()];
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
    for (colour, sigma) in [(0usize, -1.0), (1, 1.0)] {
        let mut marchers: Vec<Marcher<'_>> = all_factors
            .iter()
            .map(|factors| Marcher {
                factors,
                sigma,
                level,
                singular_edges: singular_edges(factors, 1e-12 * area_scale),
                slopes: factors.clone().map(|f| {
                    let b = f.bounds();
                    b.map(|x| x.lo.abs().max(x.hi.abs()))
                }),
                corners: HashMap::new(),
                crossings: HashMap::new(),
            })
            .collect();
        let constant_list = if colour == 0 {
            &mut out.red_constant
        } else {
            &mut out.blue_constant
        };
        for marcher in &mut marchers {
            let (u, v) = (marcher.factors[0].u, marcher.factors[0].v);
            if marcher.vanishes() {
                constant_list.push([[u.0, v.0], [u.1, v.1]]);
                continue;
            }
            let mut leaves = Vec::new();
            marcher.exclude(marcher.factors, 0, (0, 0), &mut leaves);
            let mut constant = Vec::new();
            for leaf in leaves {
                marcher.leaf(
                    leaf,
                    &umbilic_points,
                    &mut pieces[colour],
                    &mut out.singular,
                    &mut constant,
                );
            }
            constant_list.extend(marcher.merged(constant));
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

/// Within this fraction of a patch from an edge where the parametrisation is singular, the
/// ridge function is evaluated at this distance.
const POLE_ZONE: f64 = 1e-2;
/// Rounding of a jet evaluated from Bernstein coefficients is about `10⁻¹⁶` of their bound;
/// the scale of the ridge function counts `10⁻⁵` of it, so that rounding alone stays below
/// [`VANISHING`] of the scale.
const ROUNDING_FLOOR: f64 = 1e-5;

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

/// The marching of one colour over one patch.
struct Marcher<'a> {
    factors: &'a [Patch; 7],
    sigma: f64,
    level: u32,
    /// Bounds of `|f|`, `|∂f/∂u|`, `|∂f/∂v|` of each factor on the patch.
    slopes: [[f64; 3]; 7],
    /// `[u = u₀, u = u₁, v = v₀, v = v₁]`: edges along which `Â` vanishes (poles).
    singular_edges: [bool; 4],
    corners: HashMap<(usize, usize), Option<RidgeValue<f64>>>,
    crossings: HashMap<(usize, usize, bool, usize), Option<[f64; 2]>>,
}

impl Marcher<'_> {
    fn point(&self, i: usize, j: usize) -> [f64; 2] {
        let n = (1usize << self.level) as f64;
        let (u, v) = (self.factors[0].u, self.factors[0].v);
        [
            u.0 + (u.1 - u.0) * i as f64 / n,
            v.0 + (v.1 - v.0) * j as f64 / n,
        ]
    }

    /// The ridge function at a point; within [`POLE_ZONE`] of a patch edge where the
    /// parametrisation is singular, at that distance from the edge (the formula loses its
    /// digits as `Â → 0`).
    fn value(&self, p: [f64; 2]) -> Option<RidgeValue<f64>> {
        let (u, v) = (self.factors[0].u, self.factors[0].v);
        let mut q = p;
        for (k, (a, b)) in [(0, u), (1, v)] {
            let d = POLE_ZONE * (b - a);
            if self.singular_edges[2 * k] && q[k] < a + d {
                q[k] = a + d;
            }
            if self.singular_edges[2 * k + 1] && q[k] > b - d {
                q[k] = b - d;
            }
        }
        let jets: [Jet<f64>; 7] = std::array::from_fn(|i| self.factors[i].jet(q[0], q[1]));
        let mut r = ridge_value(&jets, self.sigma, f64::abs);
        // The rounding scale: the same formula on magnitudes, each jet's magnitude raised by
        // `ROUNDING_FLOOR` of its bound on the patch (at a point of symmetry every partial
        // derivative along one direction vanishes, and with them the local magnitudes of the
        // terms, while rounding does not).
        let symmetric = |x: f64, floor: f64| {
            let m = x.abs() + ROUNDING_FLOOR * floor;
            Interval { lo: -m, hi: m }
        };
        let magnitudes: [Jet<Interval>; 7] =
            std::array::from_fn(|i| [0, 1, 2].map(|k| symmetric(jets[i][k], self.slopes[i][k])));
        let m = ridge_value(&magnitudes, self.sigma, |x| x);
        r.scale = [m.g[0].hi, m.g[1].hi];
        let finite =
            r.g.iter()
                .chain(&r.t2)
                .chain(&r.scale)
                .all(|x| x.is_finite());
        finite.then_some(r)
    }

    /// Whether the ridge condition vanishes identically on the patch (probed at 25 interior
    /// points away from any grid), or the patch is umbilic throughout.
    fn vanishes(&self) -> bool {
        let (u, v) = (self.factors[0].u, self.factors[0].v);
        let fractions = [0.0713, 0.2981, 0.5127, 0.7339, 0.9207];
        fractions.iter().all(|&a| {
            fractions.iter().all(|&b| {
                let p = [u.0 + a * (u.1 - u.0), v.0 + b * (v.1 - v.0)];
                match self.value(p) {
                    None => true,
                    Some(r) => degenerate(&r),
                }
            })
        })
    }

    /// Boxes (at the finest level, by index) whose enclosure of `g` contains zero for both
    /// direction forms.
    fn exclude(
        &self,
        box_factors: &[Patch; 7],
        depth: u32,
        index: (usize, usize),
        leaves: &mut Vec<(usize, usize)>,
    ) {
        let bounds = box_factors.clone().map(|p| p.bounds());
        let r = ridge_value(&bounds, self.sigma, |x| x);
        if !r.g[0].contains_zero() || !r.g[1].contains_zero() {
            return;
        }
        if depth == self.level {
            leaves.push(index);
            return;
        }
        let halves = box_factors.clone().map(|p| p.halves(true));
        for (a, side) in [0usize, 1].into_iter().zip([true, false]) {
            let column: [Patch; 7] = std::array::from_fn(|i| {
                if side {
                    halves[i].0.clone()
                } else {
                    halves[i].1.clone()
                }
            });
            let quarters = column.map(|p| p.halves(false));
            for b in 0..2 {
                let child: [Patch; 7] = std::array::from_fn(|i| {
                    if b == 0 {
                        quarters[i].0.clone()
                    } else {
                        quarters[i].1.clone()
                    }
                });
                self.exclude(
                    &child,
                    depth + 1,
                    (2 * index.0 + a, 2 * index.1 + b),
                    leaves,
                );
            }
        }
    }

    /// Degenerate boxes merged into rectangles: runs along `v`, then equal runs along `u`.
    fn merged(&self, mut boxes: Vec<(usize, usize)>) -> Vec<[[f64; 2]; 2]> {
        boxes.sort_unstable();
        let mut runs: Vec<(usize, usize, usize)> = Vec::new(); // (i, j0, j1) half-open
        for (i, j) in boxes {
            match runs.last_mut() {
                Some(r) if r.0 == i && r.2 == j => r.2 = j + 1,
                _ => runs.push((i, j, j + 1)),
            }
        }
        let mut rects: Vec<(usize, usize, usize, usize)> = Vec::new(); // i0, i1, j0, j1
        for (i, j0, j1) in runs {
            match rects
                .iter_mut()
                .find(|r| r.1 == i && r.2 == j0 && r.3 == j1)
            {
                Some(r) => r.1 = i + 1,
                None => rects.push((i, i + 1, j0, j1)),
            }
        }
        rects
            .into_iter()
            .map(|(i0, i1, j0, j1)| [self.point(i0, j0), self.point(i1, j1)])
            .collect()
    }

    fn corner(&mut self, i: usize, j: usize) -> Option<RidgeValue<f64>> {
        if let Some(r) = self.corners.get(&(i, j)) {
            return *r;
        }
        let r = self.value(self.point(i, j));
        self.corners.insert((i, j), r);
        r
    }

    /// Whether the ridge condition with the better direction form vanishes at `p`.
    fn genuine(&self, p: [f64; 2]) -> bool {
        self.value(p).is_some_and(|r| {
            let best = usize::from(r.t2[1] > r.t2[0]);
            let cosine = r.g[best].abs() / (r.grad2 * r.t2[best]).sqrt();
            (cosine <= GENUINE || r.g[best].abs() <= VANISHING * r.scale[best])
                && r.delta > NEAR_UMBILIC * r.h2
        })
    }

    /// The genuine zero of `g` (form `form`) on the edge from grid node `a` to the next node
    /// along `u` (`along_u`) or `v`, if the ends have opposite signs.
    fn crossing(&mut self, a: (usize, usize), along_u: bool, form: usize) -> Option<[f64; 2]> {
        let key = (a.0, a.1, along_u, form);
        if let Some(c) = self.crossings.get(&key) {
            return *c;
        }
        let b = if along_u {
            (a.0 + 1, a.1)
        } else {
            (a.0, a.1 + 1)
        };
        let found = (|| {
            let fa = snapped(&self.corner(a.0, a.1)?, form);
            let fb = snapped(&self.corner(b.0, b.1)?, form);
            if (fa >= 0.0) == (fb >= 0.0) {
                return None;
            }
            let (pa, pb) = (self.point(a.0, a.1), self.point(b.0, b.1));
            let at = |t: f64| [pa[0] + t * (pb[0] - pa[0]), pa[1] + t * (pb[1] - pa[1])];
            let f = |t: f64| self.value(at(t)).map(|r| snapped(&r, form));
            // Illinois (regula falsi with halving of the retained end).
            let (mut t0, mut t1, mut f0, mut f1) = (0.0f64, 1.0f64, fa, fb);
            let mut side = 0i32;
            for _ in 0..100 {
                if t1 - t0 <= 1e-15 {
                    break;
                }
                let mut t = (t0 * f1 - t1 * f0) / (f1 - f0);
                if !(t > t0 && t < t1) {
                    t = 0.5 * (t0 + t1);
                }
                let ft = f(t)?;
                if (ft >= 0.0) == (f0 >= 0.0) {
                    t0 = t;
                    f0 = ft;
                    if side == 1 {
                        f1 *= 0.5;
                    }
                    side = 1;
                } else {
                    t1 = t;
                    f1 = ft;
                    if side == -1 {
                        f0 *= 0.5;
                    }
                    side = -1;
                }
            }
            let p = at(0.5 * (t0 + t1));
            self.genuine(p).then_some(p)
        })();
        self.crossings.insert(key, found);
        found
    }

    /// The pieces of ridge in the finest box `(i, j)`.
    fn leaf(
        &mut self,
        (i, j): (usize, usize),
        umbilics: &[[f64; 2]],
        pieces: &mut Vec<UvPolyline>,
        singular: &mut Vec<[f64; 2]>,
        constant: &mut Vec<(usize, usize)>,
    ) {
        let nodes = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
        let values: Vec<Option<RidgeValue<f64>>> =
            nodes.iter().map(|&(a, b)| self.corner(a, b)).collect();
        let Some(values) = values.into_iter().collect::<Option<Vec<_>>>() else {
            let (p, q) = (self.point(i, j), self.point(i + 1, j + 1));
            singular.push([0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]);
            return;
        };
        if values.iter().all(degenerate) {
            constant.push((i, j));
            return;
        }
        // The direction form that stays farther from zero over the corners.
        let strength = |form: usize| {
            values
                .iter()
                .map(|r| r.t2[form] / (r.t2[0] + r.t2[1]).max(f64::MIN_POSITIVE))
                .fold(f64::INFINITY, f64::min)
        };
        let form = usize::from(strength(1) > strength(0));
        // Edges in order around the box: bottom (v = v_j), right, top, left.
        let edges = [
            self.crossing((i, j), true, form),
            self.crossing((i + 1, j), false, form),
            self.crossing((i, j + 1), true, form),
            self.crossing((i, j), false, form),
        ];
        // A ridge along a grid line (a line of symmetry): the edge vanishes at both ends and
        // in the middle.
        for (a, b) in [(0usize, 1usize), (1, 2), (3, 2), (0, 3)] {
            let others = (0..4).filter(|&c| c != a && c != b);
            let definite = others.clone().all(|c| snapped(&values[c], form) != 0.0);
            if definite && snapped(&values[a], form) == 0.0 && snapped(&values[b], form) == 0.0 {
                let (pa, pb) = (
                    self.point(nodes[a].0, nodes[a].1),
                    self.point(nodes[b].0, nodes[b].1),
                );
                let mid = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
                if self
                    .value(mid)
                    .is_some_and(|r| snapped(&r, form) == 0.0 && !degenerate_umbilic(&r))
                {
                    pieces.push(vec![pa, pb]);
                }
            }
        }
        let found: Vec<(usize, [f64; 2])> = edges
            .iter()
            .enumerate()
            .filter_map(|(k, c)| c.map(|p| (k, p)))
            .collect();
        let (lo, hi) = (self.point(i, j), self.point(i + 1, j + 1));
        let inside = umbilics.iter().find(|p| {
            let du = 1e-9 * (hi[0] - lo[0]);
            let dv = 1e-9 * (hi[1] - lo[1]);
            p[0] >= lo[0] - du && p[0] <= hi[0] + du && p[1] >= lo[1] - dv && p[1] <= hi[1] + dv
        });
        if let Some(u) = inside {
            for (_, p) in &found {
                pieces.push(vec![*p, *u]);
            }
            return;
        }
        match found.len() {
            0 => {}
            2 => pieces.push(vec![found[0].1, found[1].1]),
            4 => {
                let centre = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
                let same = self.value(centre).is_some_and(|r| {
                    (snapped(&r, form) >= 0.0) == (snapped(&values[0], form) >= 0.0)
                });
                let p: Vec<[f64; 2]> = found.iter().map(|x| x.1).collect();
                if same {
                    pieces.push(vec![p[0], p[1]]);
                    pieces.push(vec![p[2], p[3]]);
                } else {
                    pieces.push(vec![p[3], p[0]]);
                    pieces.push(vec![p[1], p[2]]);
                }
            }
            _ => singular.push([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])]),
        }
    }
}
