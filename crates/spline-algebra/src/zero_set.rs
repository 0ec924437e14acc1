//! The zero set of a bivariate spline as curves in its parameter domain: subdivision of
//! the Bernstein patches until each is sign-definite or monotone in one direction, then
//! tracing, so that the topology is decided by the coefficients, not by a sampling step.

use crate::bezier_patch::Patch;
use crate::maps::SplineMap;
use crate::polylines::{UvPolyline, chain};
use crate::roots::zeros;
use crate::tensor::TensorMap;
use crate::threads::map_in_order;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::{BSpline, Direction, Surface};

/// Largest number of halvings of a patch before it is reported as a singular point.
const MAX_DEPTH: usize = 24;
/// Largest number of boxes examined in all (shared out among the groups of patches in
/// proportion to their number, [`trace_patches`]): a zero curve along which `f` does not
/// change sign (a double zero) is never separated by subdivision; past the budget the
/// remaining boxes are reported as singular points instead of halved further.
const BOX_BUDGET: usize = 50_000;

/// The zero set of `f(u, v)` ([`zero_set`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ZeroSet {
    /// The zero curves as polylines in `(u, v)`; every vertex is on the zero set to
    /// rounding (a root in one parameter, the other fixed), the topology is exact.
    pub curves: Vec<UvPolyline>,
    /// Rectangles `[[u0, v0], [u1, v1]]` on which `f` vanishes identically.
    pub regions: Vec<[[f64; 2]; 2]>,
    /// Points where the subdivision stopped without separating the branches (a crossing or
    /// an isolated zero of the curves, within `2⁻²⁴` of the patch size), or the centres of
    /// the boxes left when the budget of 50 000 boxes ran out (zero curves without a sign
    /// change, which subdivision cannot separate).
    pub singular: Vec<[f64; 2]>,
}

/// The zero set of a bivariate spline `f` (any knots; it is first converted to per-patch
/// Bernstein form). Each patch is subdivided (de Casteljau, [`Surface::split`]) until its
/// coefficients have one sign — then it has no zero inside, and only edges whose
/// coefficients all vanish are zero curves — or the differences of its coefficients along
/// `u` (or `v`) have one strict sign: `f` is then monotone in that direction, its zero set is
/// a graph over the other parameter whose extent is given exactly by the zeros of `f` on
/// the two edges ([`crate::zeros`]), and `samples` points per patch width are placed on it
/// by bisection. Pieces are joined end to end into polylines.
///
/// ```
/// use spline_core::KnotVector;
/// use spline_geom::Surface;
/// // f(u, v) = u + v − 1 on [0, 1]²: the zero set is the diagonal from (1, 0) to (0, 1).
/// let k = KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0])?;
/// let f = Surface::new(k.clone(), k, vec![-1.0, 0.0, 0.0, 1.0])?;
/// let zs = spline_algebra::zero_set(&f, 4)?;
/// assert_eq!(zs.curves.len(), 1);
/// assert!(zs.curves[0].iter().all(|p| (p[0] + p[1] - 1.0).abs() < 1e-12));
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] if `samples` is 0 or above 10 000;
/// [`ErrorKind::NonFinite`] if a coefficient is not finite.
pub fn zero_set(f: &Surface<f64, f64>, samples: usize) -> Result<ZeroSet> {
    check_samples(samples)?;
    if let Some(i) = f.control_points().iter().position(|c| !c.is_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("coefficient {i} of the function is not finite"),
        ));
    }
    let (bu, bv) = (f.knots_u().domain_breaks(), f.knots_v().domain_breaks());
    let patches = bezier_patches(f, &bu, &bv)?;
    let mut tracer = trace_patches(&patches, samples)?;
    let scale = (bu[bu.len() - 1] - bu[0]).max(bv[bv.len() - 1] - bv[0]);
    let width = [
        (bu[bu.len() - 1] - bu[0]) / (bu.len() - 1) as f64,
        (bv[bv.len() - 1] - bv[0]) / (bv.len() - 1) as f64,
    ];
    let pieces = merge_lines(std::mem::take(&mut tracer.pieces), width, samples);
    tracer.out.curves = chain(pieces, 1e-9 * scale);
    Ok(tracer.out)
}

/// Patches per group of [`trace_patches`]: each group is traced on its own, with its share
/// of [`BOX_BUDGET`].
const PATCHES_PER_GROUP: usize = 64;

/// Traces the patches in groups of [`PATCHES_PER_GROUP`] on every core, each group with
/// the share of [`BOX_BUDGET`] of its patches (all of it for a spline of one group); what
/// the groups find is gathered in patch order, so the result does not depend on the
/// number of threads.
fn trace_patches(patches: &[Surface<f64, f64>], samples: usize) -> Result<Tracer> {
    let mut groups: Vec<&[Surface<f64, f64>]> = patches.chunks(PATCHES_PER_GROUP).collect();
    let trace_group = |group: &[Surface<f64, f64>]| -> Result<Tracer> {
        let mut tracer = Tracer {
            samples,
            out: ZeroSet::default(),
            pieces: Vec::new(),
            budget: (BOX_BUDGET * group.len()).div_ceil(patches.len()).max(1),
        };
        for patch in group {
            tracer.patch(patch, 0)?;
        }
        Ok(tracer)
    };
    let threads = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
    let traced = map_in_order(&mut groups, threads, |g| trace_group(g));
    let mut all = Tracer {
        samples,
        out: ZeroSet::default(),
        pieces: Vec::new(),
        budget: 0,
    };
    for tracer in traced {
        let tracer = tracer?;
        all.out.regions.extend(tracer.out.regions);
        all.out.singular.extend(tracer.out.singular);
        all.pieces.extend(tracer.pieces);
    }
    Ok(all)
}

/// The Bézier patches of a bivariate spline on the grid of `breaks` (which must contain its
/// own), row by row in `u`: the per-patch Bernstein form, cut into patches.
pub(crate) fn bezier_patches(
    f: &Surface<f64, f64>,
    bu: &[f64],
    bv: &[f64],
) -> Result<Vec<Surface<f64, f64>>> {
    let (p, q) = f.degrees();
    let bern = TensorMap::new(
        SplineMap::transfer(f.knots_u(), &KnotVector::bernstein(p, bu)?)?,
        SplineMap::transfer(f.knots_v(), &KnotVector::bernstein(q, bv)?)?,
    )
    .apply(f)?;
    let nv = bern.net_size().1;
    let mut out = Vec::new();
    for a in 0..bu.len() - 1 {
        for b in 0..bv.len() - 1 {
            let c: Vec<f64> = (0..=p)
                .flat_map(|i| {
                    let row = (a * (p + 1) + i) * nv + b * (q + 1);
                    bern.control_points()[row..=row + q].to_vec()
                })
                .collect();
            out.push(Surface::new_unchecked(
                KnotVector::bernstein(p, &[bu[a], bu[a + 1]])?,
                KnotVector::bernstein(q, &[bv[b], bv[b + 1]])?,
                c,
            ));
        }
    }
    Ok(out)
}

struct Tracer {
    samples: usize,
    out: ZeroSet,
    pieces: Vec<UvPolyline>,
    budget: usize,
}

impl Tracer {
    fn patch(&mut self, s: &Surface<f64, f64>, depth: usize) -> Result<()> {
        let c = s.control_points();
        let ((u0, u1), (v0, v1)) = s.domain();
        if c.iter().all(|&x| x >= 0.0) || c.iter().all(|&x| x <= 0.0) {
            if c.iter().all(|&x| x == 0.0) {
                self.out.regions.push([[u0, v0], [u1, v1]]);
                return Ok(());
            }
            // No zero inside; whole edges whose coefficients vanish are zero curves.
            let (p, q) = s.degrees();
            let nv = q + 1;
            let edge = |pick: &dyn Fn(usize) -> usize, n: usize| (0..n).all(|k| c[pick(k)] == 0.0);
            if edge(&|j| j, nv) {
                self.pieces.push(vec![[u0, v0], [u0, v1]]);
            }
            if edge(&|j| p * nv + j, nv) {
                self.pieces.push(vec![[u1, v0], [u1, v1]]);
            }
            if edge(&|i| i * nv, p + 1) {
                self.pieces.push(vec![[u0, v0], [u1, v0]]);
            }
            if edge(&|i| i * nv + q, p + 1) {
                self.pieces.push(vec![[u0, v1], [u1, v1]]);
            }
            return Ok(());
        }
        for direction in [Direction::U, Direction::V] {
            if monotone(s, direction) {
                return self.trace(s, direction);
            }
        }
        if depth >= MAX_DEPTH || self.budget == 0 {
            self.out.singular.push([0.5 * (u0 + u1), 0.5 * (v0 + v1)]);
            return Ok(());
        }
        self.budget -= 1;
        // Halve the two directions alternately.
        let direction = if depth % 2 == 0 {
            Direction::U
        } else {
            Direction::V
        };
        let (left, right) = halve(s, direction)?;
        self.patch(&left, depth + 1)?;
        self.patch(&right, depth + 1)
    }

    /// `f` is monotone along `along`: its zero set is `{(φ(t), t)}` over the set of `t`
    /// (the other parameter) where the values on the two edges `along = lo, hi` do not
    /// have the same strict sign.
    fn trace(&mut self, s: &Surface<f64, f64>, along: Direction) -> Result<()> {
        let ((u0, u1), (v0, v1)) = s.domain();
        let (lo, hi, t0, t1) = match along {
            Direction::U => (u0, u1, v0, v1),
            Direction::V => (v0, v1, u0, u1),
        };
        let patch = Patch::of(s);
        let a = bezier_iso_curve(&patch, along, lo)?;
        let b = bezier_iso_curve(&patch, along, hi)?;
        let accuracy = 1e-14 * (t1 - t0).abs().max(f64::MIN_POSITIVE);
        let mut breaks = vec![t0, t1];
        for edge in [&a, &b] {
            for z in zeros(edge, accuracy)? {
                breaks.push(z.start);
                breaks.push(z.end);
            }
        }
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        // Components: maximal runs of sub-intervals on which a · b ≤ 0.
        let mut components: Vec<(f64, f64)> = Vec::new();
        for w in breaks.windows(2) {
            let mid = 0.5 * (w[0] + w[1]);
            if a.eval(mid)? * b.eval(mid)? <= 0.0 {
                match components.last_mut() {
                    Some(last) if last.1 == w[0] => last.1 = w[1],
                    _ => components.push((w[0], w[1])),
                }
            }
        }
        for (ta, tb) in components {
            let n = ((self.samples as f64 * (tb - ta) / (t1 - t0)).ceil() as usize).max(1);
            let mut piece = Vec::with_capacity(n + 1);
            for k in 0..=n {
                let t = if k == n {
                    tb
                } else {
                    ta + (tb - ta) * k as f64 / n as f64
                };
                let line = bezier_iso_curve(&patch, along.other(), t)?;
                let r = monotone_root(&line, lo, hi)?;
                piece.push(match along {
                    Direction::U => [r, t],
                    Direction::V => [t, r],
                });
            }
            self.pieces.push(piece);
        }
        Ok(())
    }
}

/// One Bézier patch halved in `direction` (de Casteljau at the middle of its interval: the
/// same patches as [`Surface::split`] there, without the general knot insertion).
fn halve(
    s: &Surface<f64, f64>,
    direction: Direction,
) -> Result<(Surface<f64, f64>, Surface<f64, f64>)> {
    let (left, right) = Patch::of(s).halves(direction == Direction::U);
    Ok((bezier_surface(left)?, bezier_surface(right)?))
}

/// A Bézier patch as a surface on its domain.
fn bezier_surface(patch: Patch) -> Result<Surface<f64, f64>> {
    Ok(Surface::new_unchecked(
        KnotVector::bernstein(patch.p, &[patch.u.0, patch.u.1])?,
        KnotVector::bernstein(patch.q, &[patch.v.0, patch.v.1])?,
        patch.c,
    ))
}

/// A Bézier patch with the parameter of direction `fixed` held at `value`, as a Bézier
/// curve in the other parameter ([`Surface::iso_curve`] of one patch, from the patch
/// restricted to the line: `O(p q)`).
fn bezier_iso_curve(patch: &Patch, fixed: Direction, value: f64) -> Result<BSpline<f64, f64>> {
    let along_u = fixed == Direction::V;
    let (degree, (a, b)) = if along_u {
        (patch.p, patch.u)
    } else {
        (patch.q, patch.v)
    };
    Ok(BSpline::new_unchecked(
        KnotVector::bernstein(degree, &[a, b])?,
        patch.restricted(along_u, value).into_values(),
    ))
}

/// Whether the differences of the coefficients along `direction` all have one strict sign
/// (then so has the partial derivative: `f` is strictly monotone in that direction).
fn monotone(s: &Surface<f64, f64>, direction: Direction) -> bool {
    let (p, q) = s.degrees();
    let c = s.control_points();
    let nv = q + 1;
    let diffs: Vec<f64> = match direction {
        Direction::U => (0..p)
            .flat_map(|i| (0..=q).map(move |j| c[(i + 1) * nv + j] - c[i * nv + j]))
            .collect(),
        Direction::V => (0..=p)
            .flat_map(|i| (0..q).map(move |j| c[i * nv + j + 1] - c[i * nv + j]))
            .collect(),
    };
    !diffs.is_empty() && (diffs.iter().all(|&d| d > 0.0) || diffs.iter().all(|&d| d < 0.0))
}

/// The root of a monotone function on `[lo, hi]` (an end where it vanishes there, or the
/// end of smaller magnitude where rounding leaves both ends with one sign), by the Illinois
/// method (regula falsi halving the value at an end kept twice) with a bisection wherever
/// two steps did not halve the bracket, until the bracket is two adjacent floats.
fn monotone_root(f: &BSpline<f64, f64>, lo: f64, hi: f64) -> Result<f64> {
    let (fa, fb) = (f.eval(lo)?, f.eval(hi)?);
    if fa == 0.0 {
        return Ok(lo);
    }
    if fb == 0.0 {
        return Ok(hi);
    }
    if fa.signum() == fb.signum() {
        return Ok(if fa.abs() <= fb.abs() { lo } else { hi });
    }
    let (mut a, mut b, mut fa, mut fb) = (lo, hi, fa, fb);
    let mut kept = 0i8; // +1: `a` kept last time, −1: `b`.
    let mut widths = [b - a; 2]; // the bracket one and two steps ago
    for _ in 0..400 {
        let mid = 0.5 * (a + b);
        if mid <= a || mid >= b {
            break;
        }
        let secant = (a * fb - b * fa) / (fb - fa);
        let m = if b - a > 0.5 * widths[1] || !(secant > a && secant < b) {
            mid
        } else {
            secant
        };
        widths = [b - a, widths[0]];
        let fm = f.eval(m)?;
        if fm == 0.0 {
            return Ok(m);
        }
        if fm.signum() == fa.signum() {
            (a, fa) = (m, fm);
            if kept == -1 {
                fb *= 0.5;
            }
            kept = -1;
        } else {
            (b, fb) = (m, fm);
            if kept == 1 {
                fa *= 0.5;
            }
            kept = 1;
        }
    }
    Ok(0.5 * (a + b))
}

/// Pieces lying on one parameter line (a patch edge on which `f` vanishes, found from both
/// neighbouring patches) merged into maximal segments and resampled (`samples` points per
/// patch width); the other pieces unchanged.
fn merge_lines(pieces: Vec<UvPolyline>, width: [f64; 2], samples: usize) -> Vec<UvPolyline> {
    let mut lines: Vec<(usize, f64, f64, f64)> = Vec::new(); // (fixed axis, value, from, to)
    let mut out = Vec::new();
    for piece in pieces {
        let fixed = (0..2).find(|&k| piece.iter().all(|p| p[k] == piece[0][k]));
        match fixed {
            Some(k) if piece.len() >= 2 => {
                let (a, b) = piece
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                        (a.min(p[1 - k]), b.max(p[1 - k]))
                    });
                lines.push((k, piece[0][k], a, b));
            }
            _ => out.push(piece),
        }
    }
    lines.sort_by(|x, y| {
        (x.0, x.1, x.2)
            .partial_cmp(&(y.0, y.1, y.2))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let mut merged: Vec<(usize, f64, f64, f64)> = Vec::new();
    for l in lines {
        match merged.last_mut() {
            Some(m) if m.0 == l.0 && m.1 == l.1 && l.2 <= m.3 => m.3 = m.3.max(l.3),
            _ => merged.push(l),
        }
    }
    for (k, value, a, b) in merged {
        let n = ((samples as f64 * (b - a) / width[1 - k]).ceil() as usize).max(1);
        out.push(
            (0..=n)
                .map(|j| {
                    let t = if j == n {
                        b
                    } else {
                        a + (b - a) * j as f64 / n as f64
                    };
                    if k == 0 { [value, t] } else { [t, value] }
                })
                .collect(),
        );
    }
    out
}

/// The samples per patch of a zero set or of ridges: 1 to 10 000.
pub(crate) fn check_samples(samples: usize) -> Result<()> {
    if samples == 0 || samples > 10_000 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!("the samples per patch must be between 1 and 10000, got {samples}"),
        )
        .with_value(samples as f64)
        .with_interval(1.0, 10_000.0));
    }
    Ok(())
}
