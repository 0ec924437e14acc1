//! Overlaps: a piece of one curve that lies on the other within the tolerance along its
//! whole length (sampled points projected onto the other curve), pieces chained into
//! maximal intervals, their ends found by bisection on the distance, every interval checked
//! again by sampling, and short ones (a tangency: two curves that touch stay within the
//! tolerance over a short arc) handed back to Newton's method as points.

use super::piece::along;
use super::refine::{Candidate, jet};
use super::results::CurveOverlap;
use nalgebra::Vector2;
use spline_core::{Result, Scalar, cast, march_to_boundary};
use spline_geom::PlanarCurve;

/// A piece of an overlap: `[s.0, s.1]` on the first curve (`s.0 < s.1`), its image on the
/// second from `t.0` (the image of `s.0`) to `t.1`.
#[derive(Clone, Copy, Debug)]
pub(super) struct OverlapPiece<T> {
    pub(super) s: (T, T),
    pub(super) t: (T, T),
}

/// Samples per interval in the final check of an overlap.
const CHECK_SAMPLES: usize = 64;

/// The foot of `p` on `b` restricted to `[lo, hi]` by Newton's method on
/// $(B(t) − p) · B'(t) = 0$ from `start`: `(t, |B(t) − p|)`. Local: a point far from the
/// piece may stop at a local minimum of the distance, which the callers only take as "not
/// on the curve".
pub(super) fn foot<T: Scalar, B: PlanarCurve<T>>(
    b: &B,
    p: Vector2<T>,
    start: T,
    (lo, hi): (T, T),
) -> Result<(T, T)> {
    let eps = T::default_epsilon();
    let mut t = start.max(lo).min(hi);
    let (_, mut d) = jet(b, t)?;
    for _ in 0..60 {
        let r = d[0] - p;
        let g = r.dot(&d[1]);
        let gp = d[1].norm_squared() + r.dot(&d[2]);
        let mut step = if gp > T::zero() {
            -g / gp
        } else if g > T::zero() {
            -(hi - lo) * cast(0.125)
        } else if g < T::zero() {
            (hi - lo) * cast(0.125)
        } else {
            break;
        };
        if !step.is_finite() {
            break;
        }
        // Downhill only: halve steps that move away (so the foot stays on the branch the
        // start is on).
        let here = r.norm();
        let mut moved = None;
        for _ in 0..40 {
            let next = (t + step).max(lo).min(hi);
            let (_, dn) = jet(b, next)?;
            if (dn[0] - p).norm() <= here {
                moved = Some((next, dn));
                break;
            }
            step *= cast(0.5);
        }
        let Some((next, dn)) = moved else { break };
        let done = (next - t).abs() <= eps * cast(4.0) * (T::one() + t.abs());
        (t, d) = (next, dn);
        if done {
            break;
        }
    }
    Ok((t, (d[0] - p).norm()))
}

/// The foot on `b` (within `range`) of `a(s)`, followed from `(s0, t0)` on both curves: from
/// `t0`, and if that is not within `tolerance`, from `t0` moved as `b` runs along `a`
/// (`dt/ds = A'·B' / |B'|²` at `(s0, t0)`), the nearer. From `t0` alone the foot may stop in
/// a local minimum of the distance, as past a sharp corner of both curves when `a(s)` lies
/// beyond it; the prediction lands beyond it too. Returns `(t, |B(t) − a(s)|)`.
fn follow<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    (a, s): (&A, T),
    b: &B,
    (s0, t0): (T, T),
    range: (T, T),
    tolerance: T,
) -> Result<(T, T)> {
    let p = a.eval(s)?;
    let (t, d) = foot(b, p, t0, range)?;
    if d <= tolerance || s == s0 {
        return Ok((t, d));
    }
    let (_, da) = jet(a, s0)?;
    let (_, db) = jet(b, t0)?;
    let speed = db[1].norm_squared();
    let predicted = t0 + (s - s0) * da[1].dot(&db[1]) / speed;
    if !(speed > T::zero()) || !predicted.is_finite() || predicted == t0 {
        return Ok((t, d));
    }
    let (t2, d2) = foot(b, p, predicted, range)?;
    Ok(if d2 < d { (t2, d2) } else { (t, d) })
}

/// The best of a few samples of `[lo, hi]` as a start for [`foot`].
fn start_on<T: Scalar, B: PlanarCurve<T>>(b: &B, p: Vector2<T>, (lo, hi): (T, T)) -> Result<T> {
    let mut best = (lo, T::max_value().unwrap_or_else(|| cast(f64::MAX)));
    for k in 0..=8 {
        let t = along((lo, hi), cast(f64::from(k) / 8.0));
        let d = (b.eval(t)? - p).norm();
        if d < best.1 {
            best = (t, d);
        }
    }
    Ok(best.0)
}

/// Whether `a` on `[x0, x1]` lies on `b` restricted to `range` within `tolerance`: `4 n + 1`
/// samples (`n` control points) are projected, each must be within the tolerance and their
/// feet must run in one direction. Returns the images of `x0` and `x1`.
pub(super) fn lies_on<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    (x0, x1): (T, T),
    b: &B,
    range: (T, T),
    tolerance: T,
    n: usize,
) -> Result<Option<(T, T)>> {
    let samples = 4 * n + 1;
    let half = samples / 2;
    let at = |k: usize| along((x0, x1), cast(k as f64 / (samples - 1) as f64));
    // The middle first: most pairs fail there.
    let p = a.eval(at(half))?;
    let (t_mid, d) = foot(b, p, start_on(b, p, range)?, range)?;
    if !(d <= tolerance) {
        return Ok(None);
    }
    let mut feet = vec![t_mid; samples];
    for (from, to, step) in [(half, samples - 1, 1isize), (half, 0, -1)] {
        let mut k = from;
        while k != to {
            let next = (k as isize + step) as usize;
            let (t, d) = follow((a, at(next)), b, (at(k), feet[k]), range, tolerance)?;
            if !(d <= tolerance) {
                return Ok(None);
            }
            feet[next] = t;
            k = next;
        }
    }
    let rising = feet.windows(2).all(|w| w[1] >= w[0]);
    let falling = feet.windows(2).all(|w| w[1] <= w[0]);
    if !(rising || falling) || feet[0] == feet[samples - 1] {
        return Ok(None);
    }
    Ok(Some((feet[0], feet[samples - 1])))
}

/// What an overlap search needs to know of the pair.
pub(super) struct Setting<T> {
    pub(super) tolerance: T,
    /// The larger extent of the two curves.
    pub(super) size: T,
    /// A curve against itself: the two sides must stay apart (`s < t`).
    pub(super) same: bool,
}

impl<T: Scalar> Setting<T> {
    /// The distance under which two intersections are one: `√(8 tolerance · size)`, the
    /// half-width of the arc over which a circle of radius `size` stays within the
    /// tolerance of its tangent.
    pub(super) fn radius(&self) -> T {
        (self.tolerance * self.size * cast(8.0)).sqrt()
    }

    /// The shortest overlap: `8 √(tolerance · size)` (and four tolerances). Two curves that
    /// touch stay within the tolerance over about `√(8 tolerance / Δκ)`, less than this
    /// unless their curvatures agree within about `1/size` there.
    pub(super) fn shortest(&self) -> T {
        ((self.tolerance * self.size).sqrt() * cast(8.0)).max(self.tolerance * cast(4.0))
    }
}

/// Where `a(s)` lies on `b` within the tolerance, followed from `from` on both curves
/// ([`follow`]): its foot.
fn on_b<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    s: T,
    from: (T, T),
    setting: &Setting<T>,
) -> Result<Option<T>> {
    let (t, d) = follow((a, s), b, from, b.domain(), setting.tolerance)?;
    Ok((d <= setting.tolerance && apart(b, s, t, setting)).then_some(t))
}

/// Whether `(s, t)` may be a point of an overlap: always for two curves; for a curve against
/// itself, `t` after `s` by more than rounding.
fn apart<T: Scalar, B: PlanarCurve<T>>(b: &B, s: T, t: T, setting: &Setting<T>) -> bool {
    !setting.same || t - s > (b.domain().1 - b.domain().0) * cast(1e-9)
}

/// From `(s, t)` on both curves towards `limit` (where `a` is not on `b`, or the end of the
/// domain): the last `(s, t)` on both, by doubling steps then bisection. Where the run ends
/// because `b` does (its foot at an end of its domain), the end is the foot of `b`'s end on
/// `a`: exact, not merely where `a` leaves the tolerance.
fn reach_end<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    (s, t): (T, T),
    limit: T,
    setting: &Setting<T>,
) -> Result<(T, T)> {
    let (mut good, off) = march_to_boundary((s, t), limit, |m, good| on_b(a, b, m, good, setting))?;
    let far = off.unwrap_or(limit);
    let (db0, db1) = b.domain();
    if good.0 != limit && (good.1 == db0 || good.1 == db1) {
        // The end lies between the start and the first point off `b`.
        let range = (s.min(far), s.max(far));
        let (end, d) = foot(a, b.eval(good.1)?, good.0, range)?;
        if d <= setting.tolerance && apart(b, end, good.1, setting) {
            good.0 = end;
        }
    }
    Ok(good)
}

/// The overlaps, and starts for Newton's method where runs were too short.
pub(super) type Resolved<T> = (Vec<CurveOverlap<T>>, Vec<Candidate<T>>);

/// Chains the pieces into maximal intervals, checks each by sampling and returns the
/// overlaps and, for runs too short to be one (a tangency), starts for Newton's method.
pub(super) fn overlaps<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    mut pieces: Vec<OverlapPiece<T>>,
    setting: &Setting<T>,
) -> Result<Resolved<T>> {
    let (da0, da1) = a.domain();
    pieces.sort_by(|x, y| {
        x.s.0
            .partial_cmp(&y.s.0)
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    // Chains of pieces: consecutive in s, with images that continue each other.
    let mut chains: Vec<OverlapPiece<T>> = Vec::new();
    let gap_s = (da1 - da0) * cast(1e-6);
    for p in pieces {
        let joined = chains.iter_mut().find(|c| {
            if p.s.0 > c.s.1 + gap_s {
                return false;
            }
            // The chain's image at p.s.0, linearly.
            let w = c.s.1 - c.s.0;
            let f = if w > T::zero() {
                (p.s.0 - c.s.0) / w
            } else {
                T::zero()
            };
            let image = c.t.0 + (c.t.1 - c.t.0) * f.min(T::one());
            let width = (c.t.1 - c.t.0).abs() + (p.t.1 - p.t.0).abs();
            (image - p.t.0).abs() <= width * cast(1e-3) + gap_s
        });
        match joined {
            Some(c) => {
                if p.s.1 > c.s.1 {
                    c.s.1 = p.s.1;
                    c.t.1 = p.t.1;
                }
            }
            None => chains.push(p),
        }
    }
    let mut out: Vec<CurveOverlap<T>> = Vec::new();
    let mut starts = Vec::new();
    for c in chains {
        // Already inside an overlap found from another chain.
        if out.iter().any(|o| {
            let (tl, th) = (o.v.0.min(o.v.1), o.v.0.max(o.v.1));
            c.s.0 >= o.u.0 - gap_s
                && c.s.1 <= o.u.1 + gap_s
                && c.t.0.min(c.t.1) >= tl - gap_s
                && c.t.0.max(c.t.1) <= th + gap_s
        }) {
            continue;
        }
        let start = reach_end(a, b, (c.s.0, c.t.0), da0, setting)?;
        let end = reach_end(a, b, (c.s.1, c.t.1), da1, setting)?;
        check_runs(a, b, start, end, setting, &mut out, &mut starts)?;
    }
    let (db0, db1) = b.domain();
    let margins = ((da1 - da0) * cast(1e-9), (db1 - db0) * cast(1e-9));
    Ok((merge_contiguous(out, margins), starts))
}

/// One maximal overlap for overlaps that meet or overlap each other on both curves (the
/// runs found from either side of a sharp corner of both curves end past it, each where
/// the other curve leaves the tolerance), in increasing `u.0`; an overlap inside another
/// is dropped. `margins`: the gaps on either curve's parameters that count as meeting.
fn merge_contiguous<T: Scalar>(
    mut found: Vec<CurveOverlap<T>>,
    (margin_u, margin_v): (T, T),
) -> Vec<CurveOverlap<T>> {
    found.sort_by(|x, y| {
        x.u.0
            .partial_cmp(&y.u.0)
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let mut out: Vec<CurveOverlap<T>> = Vec::with_capacity(found.len());
    for o in found {
        // `v` measured along the direction of the overlaps.
        let forward = |v: T, reversed: bool| if reversed { -v } else { v };
        let joined = out.iter_mut().find(|m| {
            let r = m.reversed;
            m.reversed == o.reversed
                && o.u.0 <= m.u.1 + margin_u
                && forward(o.v.0, r) <= forward(m.v.1, r) + margin_v
                && forward(o.v.0, r) >= forward(m.v.0, r) - margin_v
        });
        match joined {
            Some(m) => {
                if o.u.1 > m.u.1 {
                    m.u.1 = o.u.1;
                    m.v.1 = o.v.1;
                    m.points.1 = o.points.1;
                }
            }
            None => out.push(o),
        }
    }
    out
}

/// Samples `[start.0, end.0]`: every run of samples on both curves becomes an overlap with
/// its ends found by bisection, or a start for Newton's method when it is too short.
fn check_runs<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    start: (T, T),
    end: (T, T),
    setting: &Setting<T>,
    out: &mut Vec<CurveOverlap<T>>,
    starts: &mut Vec<Candidate<T>>,
) -> Result<()> {
    let n = CHECK_SAMPLES;
    let at = |k: usize| along((start.0, end.0), cast(k as f64 / (n - 1) as f64));
    let guess = |k: usize| along((start.1, end.1), cast(k as f64 / (n - 1) as f64));
    let mut feet: Vec<Option<T>> = Vec::with_capacity(n);
    for k in 0..n {
        let from = match feet.last().copied().flatten() {
            Some(t) => (at(k - 1), t),
            None => (at(k), guess(k)),
        };
        let t = match k {
            0 => Some(start.1),
            _ if k == n - 1 => Some(end.1),
            _ => on_b(a, b, at(k), from, setting)?,
        };
        feet.push(t);
    }
    // Samples missed from the side before (a foot tracked from there stops in a local
    // minimum of the distance, as past a sharp corner of both curves), tried from the side
    // after.
    for k in (1..n - 1).rev() {
        if let (None, Some(next)) = (feet[k], feet[k + 1]) {
            feet[k] = on_b(a, b, at(k), (at(k + 1), next), setting)?;
        }
    }
    let mut k = 0;
    while k < n {
        if feet[k].is_none() {
            k += 1;
            continue;
        }
        let first = k;
        while k + 1 < n && feet[k + 1].is_some() {
            k += 1;
        }
        let last = k;
        k += 1;
        let mut lo = (at(first), feet[first].unwrap_or(start.1));
        let mut hi = (at(last), feet[last].unwrap_or(end.1));
        if first > 0 {
            lo = reach_end(a, b, lo, at(first - 1), setting)?;
        }
        if last + 1 < n {
            hi = reach_end(a, b, hi, at(last + 1), setting)?;
        }
        let (pa, pb) = (a.eval(lo.0)?, a.eval(hi.0)?);
        let length = (pb - pa).norm();
        let long = length > setting.shortest() && !is_contact(a, b, lo, hi, setting.tolerance)?;
        if long {
            out.push(CurveOverlap {
                u: (lo.0, hi.0),
                v: (lo.1, hi.1),
                reversed: hi.1 < lo.1,
                points: (pa, pb),
            });
        } else {
            starts.push(Candidate {
                u: (lo.0 + hi.0) * cast(0.5),
                v: (lo.1 + hi.1) * cast(0.5),
            });
        }
    }
    Ok(())
}

/// Whether the distance between the curves along `[lo.0, hi.0]` grows from a minimum like
/// that of two curves touching rather than staying flat as along an overlap: it spans at
/// least half the tolerance, and it is at the rounding of the points (a thousandth of the
/// tolerance) at fewer than half of 17 samples. Two arcs that coincide are at rounding
/// along most of the run (their ends diverging over a short part of it); two arcs a
/// constant distance apart within the tolerance do not vary.
fn is_contact<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    lo: (T, T),
    hi: (T, T),
    tolerance: T,
) -> Result<bool> {
    const N: usize = 16;
    let mut gaps = [T::zero(); N + 1];
    let mut from = lo;
    for (k, gap) in gaps.iter_mut().enumerate() {
        let s = along((lo.0, hi.0), cast(k as f64 / N as f64));
        let (t, d) = follow((a, s), b, from, b.domain(), tolerance)?;
        from = (s, t);
        *gap = d;
    }
    let smallest = gaps.iter().fold(gaps[0], |m, &g| m.min(g));
    let largest = gaps.iter().fold(gaps[0], |m, &g| m.max(g));
    let rounding = tolerance * cast(1e-3);
    let at_rounding = gaps.iter().filter(|&&g| g <= rounding).count();
    Ok(largest - smallest >= tolerance * cast(0.5) && 2 * at_rounding < N + 1)
}

/// Whether an intersection at `(u, v)` belongs to one of the overlaps (its parameters in
/// both intervals, up to a margin).
pub(super) fn within<T: Scalar>(overlaps: &[CurveOverlap<T>], u: T, v: T) -> bool {
    overlaps.iter().any(|o| {
        let (tl, th) = (o.v.0.min(o.v.1), o.v.0.max(o.v.1));
        let ms = (o.u.1 - o.u.0) * cast(1e-3);
        let mt = (th - tl) * cast(1e-3);
        u >= o.u.0 - ms && u <= o.u.1 + ms && v >= tl - mt && v <= th + mt
    })
}
