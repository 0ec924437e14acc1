//! Overlaps: a piece of one curve that lies on the other within the tolerance along its
//! whole length (sampled points projected onto the other curve), pieces chained into
//! maximal intervals, their ends found by bisection on the distance, every interval checked
//! again by sampling, and short ones (a tangency: two curves that touch stay within the
//! tolerance over a short arc) handed back to Newton's method as points.

use super::refine::jet;
use super::{Candidate, CurveOverlap};
use nalgebra::Vector2;
use spline_core::{Result, Scalar, cast};
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

/// The best of a few samples of `[lo, hi]` as a start for [`foot`].
fn start_on<T: Scalar, B: PlanarCurve<T>>(b: &B, p: Vector2<T>, (lo, hi): (T, T)) -> Result<T> {
    let mut best = (lo, T::max_value().unwrap_or_else(|| cast(f64::MAX)));
    for k in 0..=8 {
        let t = lo + (hi - lo) * cast::<T>(f64::from(k) / 8.0);
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
    let at = |k: usize| x0 + (x1 - x0) * cast::<T>(k as f64 / (samples - 1) as f64);
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
            let (t, d) = foot(b, a.eval(at(next))?, feet[k], range)?;
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

/// Where `a(s)` lies on `b` within the tolerance, from the foot `guess`: its foot.
fn on_b<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    s: T,
    guess: T,
    setting: &Setting<T>,
) -> Result<Option<T>> {
    let (t, d) = foot(b, a.eval(s)?, guess, b.domain())?;
    let apart = !setting.same || t - s > (b.domain().1 - b.domain().0) * cast(1e-9);
    Ok((d <= setting.tolerance && apart).then_some(t))
}

/// From `(s, t)` on both curves towards `limit` (where `a` is not on `b`, or the end of the
/// domain): the last `(s, t)` on both, by doubling steps then bisection.
fn reach_end<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    (s, t): (T, T),
    limit: T,
    setting: &Setting<T>,
) -> Result<(T, T)> {
    let eps = T::default_epsilon();
    let mut good = (s, t);
    let mut bad = None;
    let mut step = (limit - s) * cast(1e-6);
    while good.0 != limit {
        let next = if (step.abs()) >= (limit - good.0).abs() {
            limit
        } else {
            good.0 + step
        };
        match on_b(a, b, next, good.1, setting)? {
            Some(t) => good = (next, t),
            None => {
                bad = Some(next);
                break;
            }
        }
        step *= cast(2.0);
    }
    if let Some(mut bad) = bad {
        for _ in 0..80 {
            let m = (good.0 + bad) * cast(0.5);
            if !((m - good.0).abs() > eps * (T::one() + m.abs()))
                || !((bad - m).abs() > eps * (T::one() + m.abs()))
            {
                break;
            }
            match on_b(a, b, m, good.1, setting)? {
                Some(t) => good = (m, t),
                None => bad = m,
            }
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
    Ok((out, starts))
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
    let at = |k: usize| start.0 + (end.0 - start.0) * cast::<T>(k as f64 / (n - 1) as f64);
    let guess = |k: usize| start.1 + (end.1 - start.1) * cast::<T>(k as f64 / (n - 1) as f64);
    let mut feet: Vec<Option<T>> = Vec::with_capacity(n);
    for k in 0..n {
        let previous = feet.last().copied().flatten().unwrap_or_else(|| guess(k));
        let t = match k {
            0 => Some(start.1),
            _ if k == n - 1 => Some(end.1),
            _ => on_b(a, b, at(k), previous, setting)?,
        };
        feet.push(t);
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
    let mut t = lo.1;
    for (k, gap) in gaps.iter_mut().enumerate() {
        let f: T = cast(k as f64 / N as f64);
        let s = lo.0 + (hi.0 - lo.0) * f;
        let guess = if k == 0 { lo.1 } else { t };
        let (foot_t, d) = foot(b, a.eval(s)?, guess, b.domain())?;
        t = foot_t;
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
