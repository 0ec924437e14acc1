//! The marching of the ridges of both colours over each Bézier patch of the curvature
//! numerators: exclusion on boxes shared by the colours, then crossings on the edges of
//! the finest boxes left; the patches are independent and run on every core.

use crate::bezier_patch::{LineRestriction, Patch};
use crate::polylines::UvPolyline;
use crate::ridge_function::{
    Jet, Magnitude, NEAR_UMBILIC, RidgeValue, VANISHING, degenerate, degenerate_umbilic,
    ridge_value, snapped,
};
use crate::threads::map_in_order;
use rustc_hash::FxHashMap as HashMap;

/// A crossing is kept when the gradient of the curvature is within this cosine of orthogonal
/// to the principal direction there (from the better-conditioned direction form: a zero of
/// a direction form is not a ridge, and there the cosine is of order one). At a root the
/// cosine is rounding, up to about `10⁻⁵` where the terms of `g` cancel strongly.
const GENUINE: f64 = 1e-3;

/// `|g|` at most this fraction of the sum of the magnitudes of its terms is zero to the
/// rounding of its evaluation (a few units in the last place of the largest term): the
/// location of a crossing stops there.
const ROOT_ROUNDING: f64 = 1e-14;

/// Within this fraction of a patch from an edge where the parametrisation is singular, the
/// ridge function is evaluated at this distance.
const POLE_ZONE: f64 = 1e-2;
/// Rounding of a jet evaluated from Bernstein coefficients is about `10⁻¹⁶` of their bound;
/// the scale of the ridge function counts `10⁻⁵` of it, so that rounding alone stays below
/// [`VANISHING`] of the scale.
const ROUNDING_FLOOR: f64 = 1e-5;

/// The marching of one colour over one patch.
pub(super) struct Marcher<'a> {
    pub(super) factors: &'a [Patch; 7],
    sigma: f64,
    pub(super) level: u32,
    /// Bounds of `|f|`, `|∂f/∂u|`, `|∂f/∂v|` of each factor on the patch.
    slopes: [[f64; 3]; 7],
    /// `[u = u₀, u = u₁, v = v₀, v = v₁]`: edges along which `Â` vanishes (poles).
    singular_edges: [bool; 4],
    corners: HashMap<(usize, usize), Option<RidgeValue<f64>>>,
    crossings: HashMap<(usize, usize, bool, usize), Option<[f64; 2]>>,
    /// The factors restricted to the grid lines met so far, by `(along_u, k)`: the line
    /// `v = v_k` along `u`, or `u = u_k` along `v` ([`Marcher::line_through`]).
    lines: HashMap<(bool, usize), [LineRestriction; 7]>,
}

impl<'a> Marcher<'a> {
    /// The marcher of colour `sigma` on a patch's factors `[Ê, F̂, Ĝ, L̂, M̂, N̂, W]`.
    fn new(factors: &'a [Patch; 7], sigma: f64, level: u32, area_scale: f64) -> Self {
        Self {
            factors,
            sigma,
            level,
            singular_edges: singular_edges(factors, 1e-12 * area_scale),
            slopes: factors.clone().map(|f| {
                let b = f.bounds();
                b.map(|x| x.lo.abs().max(x.hi.abs()))
            }),
            corners: HashMap::default(),
            crossings: HashMap::default(),
            lines: HashMap::default(),
        }
    }

    pub(super) fn point(&self, i: usize, j: usize) -> [f64; 2] {
        let n = (1usize << self.level) as f64;
        let (u, v) = (self.factors[0].u, self.factors[0].v);
        [
            u.0 + (u.1 - u.0) * i as f64 / n,
            v.0 + (v.1 - v.0) * j as f64 / n,
        ]
    }

    /// The point at which the ridge function stands for its value at `p`: `p` itself, or
    /// within [`POLE_ZONE`] of a patch edge where the parametrisation is singular, the
    /// point at that distance from the edge (the formula loses its digits as `Â → 0`).
    fn evaluated_at(&self, p: [f64; 2]) -> [f64; 2] {
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
        q
    }

    /// The ridge function at a point ([`Marcher::evaluated_at`]).
    fn value(&self, p: [f64; 2]) -> Option<RidgeValue<f64>> {
        let q = self.evaluated_at(p);
        self.ridge_from_jets(&Patch::jets(self.factors, q[0], q[1]))
    }

    /// The ridge function at a point `p` of a grid line along `u` (`along_u`) or `v`, from
    /// the factors restricted to that line ([`Marcher::line_through`]).
    fn value_on_line(
        &self,
        lines: &[LineRestriction; 7],
        along_u: bool,
        p: [f64; 2],
    ) -> Option<RidgeValue<f64>> {
        let q = self.evaluated_at(p);
        self.ridge_from_jets(&LineRestriction::jets(lines, q[usize::from(!along_u)]))
    }

    /// The factors restricted to the grid line through `p` along `u` (`along_u`) or `v`
    /// (at the clamped position across it: [`Marcher::evaluated_at`]).
    fn line_through(&self, p: [f64; 2], along_u: bool) -> [LineRestriction; 7] {
        let q = self.evaluated_at(p);
        let fixed = if along_u { q[1] } else { q[0] };
        std::array::from_fn(|i| self.factors[i].restricted(along_u, fixed))
    }

    /// The ridge function from the jets of the factors, with its rounding scale: the same
    /// formula on magnitudes, each jet's magnitude raised by `ROUNDING_FLOOR` of its bound
    /// on the patch (at a point of symmetry every partial derivative along one direction
    /// vanishes, and with them the local magnitudes of the terms, while rounding does not).
    fn ridge_from_jets(&self, jets: &[Jet<f64>; 7]) -> Option<RidgeValue<f64>> {
        let mut r = ridge_value(jets, self.sigma, f64::abs);
        let magnitudes: [Jet<Magnitude>; 7] = std::array::from_fn(|i| {
            [0, 1, 2].map(|k| Magnitude(jets[i][k].abs() + ROUNDING_FLOOR * self.slopes[i][k]))
        });
        let m = ridge_value(&magnitudes, self.sigma, |x| x);
        r.scale = [m.g[0].0, m.g[1].0];
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

    /// The ridge function at the grid node `(i, j)` (from the factors restricted to the
    /// grid line `v = v_j`: equal to [`Marcher::value`] there, bit for bit).
    pub(super) fn corner(&mut self, i: usize, j: usize) -> Option<RidgeValue<f64>> {
        if let Some(r) = self.corners.get(&(i, j)) {
            return *r;
        }
        self.ensure_line(true, j);
        let r = self.value_on_line(&self.lines[&(true, j)], true, self.point(i, j));
        self.corners.insert((i, j), r);
        r
    }

    /// Restricts the factors to the grid line `v = v_k` (`along_u`) or `u = u_k`, once.
    fn ensure_line(&mut self, along_u: bool, k: usize) {
        if !self.lines.contains_key(&(along_u, k)) {
            let p = if along_u {
                self.point(0, k)
            } else {
                self.point(k, 0)
            };
            let line = self.line_through(p, along_u);
            self.lines.insert((along_u, k), line);
        }
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
        let found = self.locate_crossing(a, b, along_u, form);
        self.crossings.insert(key, found);
        found
    }

    /// The genuine zero of `g` (form `form`) between the neighbouring grid nodes `a` and
    /// `b` along `u` (`along_u`) or `v`, by the Illinois method on the factors restricted to
    /// that grid line (each value along it then costs O(degree) per factor).
    fn locate_crossing(
        &mut self,
        a: (usize, usize),
        b: (usize, usize),
        along_u: bool,
        form: usize,
    ) -> Option<[f64; 2]> {
        let fa = snapped(&self.corner(a.0, a.1)?, form);
        let fb = snapped(&self.corner(b.0, b.1)?, form);
        if (fa >= 0.0) == (fb >= 0.0) {
            return None;
        }
        let key = if along_u { (true, a.1) } else { (false, a.0) };
        self.ensure_line(key.0, key.1);
        let line = &self.lines[&key];
        let (pa, pb) = (self.point(a.0, a.1), self.point(b.0, b.1));
        let at = |t: f64| [pa[0] + t * (pb[0] - pa[0]), pa[1] + t * (pb[1] - pa[1])];
        // Between two definite ends the raw `g` is followed to its root (snapped, it is zero
        // on a zone of about `VANISHING` of its terms around the root, where the method
        // could only bisect), and the search stops where `g` is zero to rounding. An end
        // snapped to zero is a root at the rounding of `g` there: its raw sign may not
        // bracket one, so the snapped values are followed to the edge of that zone.
        let raw = fa != 0.0 && fb != 0.0;
        let f = |t: f64| {
            self.value_on_line(line, along_u, at(t)).map(|r| {
                if raw {
                    (r.g[form], ROOT_ROUNDING * r.scale[form])
                } else {
                    (snapped(&r, form), -1.0)
                }
            })
        };
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
            let (ft, rounding) = f(t)?;
            if ft.abs() <= rounding {
                // `g` is zero to the rounding of its terms: no step can do better.
                (t0, t1) = (t, t);
                break;
            }
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

/// What one patch gives for one colour, in the order the marching finds it.
#[derive(Default)]
pub(super) struct Found {
    pub(super) pieces: Vec<UvPolyline>,
    pub(super) singular: Vec<[f64; 2]>,
    pub(super) constant: Vec<[[f64; 2]; 2]>,
}

/// Both colours (`[red, blue]`) on one patch: a colour whose condition vanishes identically
/// gives the whole patch as constant, the other boxes are excluded together and marched per
/// colour.
fn march_patch(pair: &mut [Marcher<'_>; 2], umbilics: &[[f64; 2]]) -> [Found; 2] {
    let mut found = [Found::default(), Found::default()];
    let live = [!pair[0].vanishes(), !pair[1].vanishes()];
    let mut leaves = [Vec::new(), Vec::new()];
    let mut scratch: Vec<Subdivision> = (0..pair[0].level)
        .map(|_| Subdivision::like(pair[0].factors))
        .collect();
    exclude(
        pair,
        pair[0].factors,
        (0, (0, 0)),
        live,
        &mut leaves,
        &mut scratch,
    );
    for ((marcher, out), (live, leaves)) in pair
        .iter_mut()
        .zip(&mut found)
        .zip(live.into_iter().zip(leaves))
    {
        if !live {
            let (u, v) = (marcher.factors[0].u, marcher.factors[0].v);
            out.constant.push([[u.0, v.0], [u.1, v.1]]);
            continue;
        }
        let mut constant = Vec::new();
        for leaf in leaves {
            marcher.leaf(
                leaf,
                umbilics,
                &mut out.pieces,
                &mut out.singular,
                &mut constant,
            );
        }
        out.constant = marcher.merged(constant);
        // Only the corners are asked for again (the ridges along patch boundaries): the
        // memory of the rest goes now, not when every patch is done.
        marcher.crossings = HashMap::default();
        marcher.lines = HashMap::default();
    }
    found
}

/// The factors of the four children of a box (and of its two halves along `u` on the way),
/// one per depth of [`exclude`]: their buffers are reused from box to box.
struct Subdivision {
    halves: [[Patch; 7]; 2],
    quarters: [[Patch; 7]; 4],
}

impl Subdivision {
    /// Buffers the size of `factors`.
    fn like(factors: &[Patch; 7]) -> Self {
        Self {
            halves: std::array::from_fn(|_| factors.clone()),
            quarters: std::array::from_fn(|_| factors.clone()),
        }
    }
}

/// Boxes (at the finest level, by index) whose enclosure of `g` contains zero for both
/// direction forms, per colour still `live`; the subdivision of the factors is shared, its
/// children written into `scratch` (one [`Subdivision`] per level below this box's).
fn exclude(
    pair: &[Marcher<'_>; 2],
    box_factors: &[Patch; 7],
    (depth, index): (u32, (usize, usize)),
    mut live: [bool; 2],
    leaves: &mut [Vec<(usize, usize)>; 2],
    scratch: &mut [Subdivision],
) {
    let bounds = box_factors.each_ref().map(Patch::bounds);
    for (marcher, live) in pair.iter().zip(&mut live) {
        if *live {
            let r = ridge_value(&bounds, marcher.sigma, |x| x);
            *live = r.g[0].contains_zero() && r.g[1].contains_zero();
        }
    }
    if live == [false, false] {
        return;
    }
    let Some((here, deeper)) = scratch.split_first_mut().filter(|_| depth < pair[0].level) else {
        for (list, live) in leaves.iter_mut().zip(live) {
            if live {
                list.push(index);
            }
        }
        return;
    };
    let Subdivision { halves, quarters } = here;
    let [low, high] = halves;
    for (k, factor) in box_factors.iter().enumerate() {
        factor.halves_into(true, &mut low[k], &mut high[k]);
    }
    for (a, column) in [&*low, &*high].into_iter().enumerate() {
        let (first, second) = quarters.split_at_mut(2 * a + 1);
        let (bottom, top) = (&mut first[2 * a], &mut second[0]);
        for (k, factor) in column.iter().enumerate() {
            factor.halves_into(false, &mut bottom[k], &mut top[k]);
        }
    }
    for (a, b) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
        exclude(
            pair,
            &quarters[2 * a + b],
            (depth + 1, (2 * index.0 + a, 2 * index.1 + b)),
            live,
            leaves,
            deeper,
        );
    }
}

/// Patches per thread below which the marching stays on the calling thread.
const PATCHES_PER_THREAD: usize = 4;

/// The marchers of both colours on every patch (`[red, blue]` each, for the ridges along
/// patch boundaries afterwards) and what each patch gives, in patch order whatever the
/// number of threads (the result is the sequential one, bit for bit).
pub(super) fn march_all<'a>(
    factors: &'a [[Patch; 7]],
    level: u32,
    area_scale: f64,
    umbilics: &[[f64; 2]],
) -> (Vec<[Marcher<'a>; 2]>, Vec<[Found; 2]>) {
    let mut pairs: Vec<[Marcher<'a>; 2]> = factors
        .iter()
        .map(|f| [-1.0, 1.0].map(|sigma| Marcher::new(f, sigma, level, area_scale)))
        .collect();
    let threads = std::thread::available_parallelism()
        .map_or(1, std::num::NonZero::get)
        .min(pairs.len() / PATCHES_PER_THREAD)
        .max(1);
    let found = map_in_order(&mut pairs, threads, |p| march_patch(p, umbilics));
    (pairs, found)
}

/// The edges `[u = u₀, u = u₁, v = v₀, v = v₁]` of a patch along which `Â = ÊĜ − F̂²`
/// vanishes (below `floor` at five points).
fn singular_edges(factors: &[Patch; 7], floor: f64) -> [bool; 4] {
    let (u, v) = (factors[0].u, factors[0].v);
    let area = |p: [f64; 2]| {
        let [e, f, g] = [0, 1, 2].map(|i| factors[i].jet(p[0], p[1])[0]);
        e * g - f * f
    };
    let along = |k: usize, t: f64| match k {
        0 => [u.0, v.0 + t * (v.1 - v.0)],
        1 => [u.1, v.0 + t * (v.1 - v.0)],
        2 => [u.0 + t * (u.1 - u.0), v.0],
        _ => [u.0 + t * (u.1 - u.0), v.1],
    };
    std::array::from_fn(|k| {
        [0.0, 0.25, 0.5, 0.75, 1.0]
            .iter()
            .all(|&t| area(along(k, t)).abs() <= floor)
    })
}
