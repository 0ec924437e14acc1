//! The subdivision: pairs of Bézier pieces whose boxes and fat lines meet are split until
//! they are flat (a candidate for Newton's method where their chords meet) or until one lies
//! on the other curve along its whole length (a piece of an overlap; the other piece is
//! examined further outside that one's image only). The work is bounded by the geometry: a
//! pair is split only while neither holds, which near a crossing or a tangency takes
//! `log₂(size / tolerance)` levels and near the end of an overlap as many; a piece left
//! beside an overlap is at most three quarters of the one it came from, and flat pieces
//! are split further only while longer than the shortest overlap.

use super::overlap::{OverlapPiece, lies_on};
use super::piece::{Piece, mid, segment_closest};
use super::refine::Candidate;
use nalgebra::Vector2;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, cast};
use spline_geom::PlanarCurve;

/// The largest number of piece pairs examined before the search gives up: a safety net
/// only (overlaps are found as such and the subdivision stops at flat pieces, so the work
/// is bounded by the geometry, far below this).
pub const MAX_INTERSECTION_PAIRS: usize = 1_000_000;

/// What the subdivision found: starts for Newton's method and pieces of overlaps.
pub(super) struct Found<T> {
    pub(super) starts: Vec<Candidate<T>>,
    pub(super) overlaps: Vec<OverlapPiece<T>>,
}

/// How far the coincidence test of a pair may look beyond the other piece: for two curves,
/// one piece's width on either side (a piece that straddles two pieces of the other curve
/// is then still recognised); for a curve against itself none (its neighbours would be the
/// piece itself).
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Reach {
    Neighbours,
    Piece,
}

/// Subdivides pairs of pieces whose boxes overlap until both pieces are flat (within a
/// quarter of the tolerance), one lies on the other curve within the tolerance, or they
/// cannot be split; collects a start for Newton's method where flat chords come within the
/// tolerance, and the pieces of overlaps (tested on pieces larger than `shortest`).
#[allow(clippy::too_many_arguments)]
pub(super) fn subdivide<T: Scalar, A: PlanarCurve<T>, B: PlanarCurve<T>>(
    a: &A,
    b: &B,
    pa: &[Piece<T, A::Coefficient>],
    pb: &[Piece<T, B::Coefficient>],
    (tolerance, shortest): (T, T),
    reach: Reach,
    found: &mut Found<T>,
    pairs: &mut usize,
) -> Result<()> {
    let flat = tolerance * cast(0.25);
    type Pair<T, X, Y> = (Piece<T, X>, Piece<T, Y>);
    let mut stack: Vec<Pair<T, A::Coefficient, B::Coefficient>> = Vec::new();
    for x in pa {
        for y in pb {
            stack.push((x.clone(), y.clone()));
        }
    }
    let (da0, da1) = a.domain();
    let (db0, db1) = b.domain();
    while let Some((x, y)) = stack.pop() {
        if !x.overlaps(&y, tolerance) {
            continue;
        }
        *pairs += 1;
        if *pairs > MAX_INTERSECTION_PAIRS {
            return Err(Error::new(
                ErrorKind::NoConvergence,
                format!(
                    "more than {MAX_INTERSECTION_PAIRS} pairs of pieces stay within the tolerance"
                ),
            ));
        }
        // One piece on the other curve along its whole length. Pieces shorter than an
        // overlap can be (a tangency stays within the tolerance over less than `shortest`)
        // are left to the subdivision and Newton's method.
        let long = x.size() > shortest && y.size() > shortest;
        // Which piece to split when an overlap covers too little of the other piece to
        // split that piece at its image: that one (`true` for `x`), until it does.
        let mut force = None;
        if long {
            let (x0, x1) = x.interval();
            let (y0, y1) = y.interval();
            let (ylo, yhi) = widen((y0, y1), (db0, db1), reach);
            if let Some((t0, t1)) = lies_on(a, (x0, x1), b, (ylo, yhi), tolerance, x.points.len())?
            {
                found.overlaps.push(OverlapPiece {
                    s: (x0, x1),
                    t: (t0, t1),
                });
                // The rest of `y` (beyond the image of `x`) may still cross `x`.
                if let Some(rest) = outside(&y, (t0.min(t1), t0.max(t1)), &B::project) {
                    stack.extend(rest.into_iter().map(|r| (x.clone(), r)));
                    continue;
                }
                force = Some(false);
            } else {
                let (xlo, xhi) = widen((x0, x1), (da0, da1), reach);
                let n = y.points.len();
                if let Some((s0, s1)) = lies_on(b, (y0, y1), a, (xlo, xhi), tolerance, n)? {
                    let (s, t) = if s0 <= s1 {
                        ((s0, s1), (y0, y1))
                    } else {
                        ((s1, s0), (y1, y0))
                    };
                    found.overlaps.push(OverlapPiece { s, t });
                    // The rest of `x` (beyond the image of `y`) may still cross `y`.
                    if let Some(rest) = outside(&x, s, &A::project) {
                        stack.extend(rest.into_iter().map(|r| (r, y.clone())));
                        continue;
                    }
                    force = Some(true);
                }
            }
        }
        let flat_x = x.flatness <= flat;
        let flat_y = y.flatness <= flat;
        if force.is_none() && flat_x && flat_y {
            // Flat pieces that run along each other further than a tangency can (an overlap
            // in part of each, as of two collinear segments that overlap in part) are split
            // until a part lies on the other curve; others meet at most once, where their
            // chords do.
            let slack = tolerance + x.flatness + y.flatness;
            let along_x = shared_length((&x, &y), slack).max(shared_length((&y, &x), slack));
            if !(long && along_x > shortest) {
                let pair = ((&x, &A::project), (&y, &B::project));
                if let Some(c) = chord_candidate(pair.0, pair.1, tolerance) {
                    found.starts.push(c);
                }
                continue;
            }
        }
        // Split the larger piece that is not flat (or the larger of two flat ones).
        let split_x = force.unwrap_or(if flat_x == flat_y {
            x.size() >= y.size()
        } else {
            !flat_x
        });
        let split = if split_x {
            x.split(&A::project)
                .map(|(l, r)| [(l, y.clone()), (r, y.clone())])
        } else {
            y.split(&B::project)
                .map(|(l, r)| [(x.clone(), l), (x.clone(), r)])
        };
        match split {
            Some(halves) => stack.extend(halves),
            None => {
                // At the resolution of floating point: keep the pair as a candidate.
                found.starts.push(Candidate {
                    u: mid(x.interval()),
                    v: mid(y.interval()),
                });
            }
        }
    }
    Ok(())
}

/// The parts of `piece` outside `[lo, hi]` (the image of the other piece, which lies on
/// this curve there), or `None` when the image covers less than a quarter of the piece (it
/// lies mostly on a neighbour; the pair is then subdivided as any other, so every step
/// leaves at most three quarters of the piece to examine).
fn outside<T: Scalar, Q: ControlPoint<T>>(
    piece: &Piece<T, Q>,
    (lo, hi): (T, T),
    project: &impl Fn(&Q) -> Vector2<T>,
) -> Option<Vec<Piece<T, Q>>> {
    let (p0, p1) = piece.interval();
    let covered = hi.min(p1) - lo.max(p0);
    if !(covered * cast(4.0) >= p1 - p0) {
        return None;
    }
    let mut rest = Vec::new();
    let mut right = Some(piece.clone());
    if lo > p0 {
        let (l, r) = piece.split_at(lo, project)?;
        rest.push(l);
        right = Some(r);
    }
    if hi < p1 {
        if let Some(r) = right.and_then(|r| r.split_at(hi, project)) {
            rest.push(r.1);
        }
    }
    Some(rest)
}

/// The length of `x`'s chord within `slack` of the rectangle along `y`'s chord (its
/// length, `slack` on either side and beyond either end): about `2 slack / sin θ` where the
/// chords cross at an angle `θ`, the length of the common part where they run along each
/// other.
fn shared_length<T: Scalar, QX: ControlPoint<T>, QY: ControlPoint<T>>(
    (x, y): (&Piece<T, QX>, &Piece<T, QY>),
    slack: T,
) -> T {
    let d = y.last - y.first;
    let length = d.norm();
    let dx = x.last - x.first;
    if !(length > T::zero()) {
        return T::zero();
    }
    let (e, n) = (d / length, Vector2::new(-d.y, d.x) / length);
    let r = x.first - y.first;
    // a + b s within [lo, hi], for s in [0, 1].
    let clip = |(s0, s1): (T, T), a: T, b: T, lo: T, hi: T| {
        if b == T::zero() {
            return if a >= lo && a <= hi {
                (s0, s1)
            } else {
                (T::one(), T::zero())
            };
        }
        let (p, q) = ((lo - a) / b, (hi - a) / b);
        (s0.max(p.min(q)), s1.min(p.max(q)))
    };
    let unit = (T::zero(), T::one());
    let across = clip(unit, n.dot(&r), n.dot(&dx), -slack, slack);
    let (s0, s1) = clip(across, e.dot(&r), e.dot(&dx), -slack, length + slack);
    (s1 - s0).max(T::zero()) * dx.norm()
}

/// The interval of a piece widened by its width on either side within the domain.
fn widen<T: Scalar>((lo, hi): (T, T), (d0, d1): (T, T), reach: Reach) -> (T, T) {
    match reach {
        Reach::Piece => (lo, hi),
        Reach::Neighbours => {
            let w = hi - lo;
            ((lo - w).max(d0), (hi + w).min(d1))
        }
    }
}

/// The start of Newton's method for two flat pieces: where their chords come closest, if
/// that is within the tolerance (plus the flatness of the pieces), the parameters where the
/// pieces reach those points' fractions of their chords ([`Piece::at_fraction`]: the
/// fraction mapped onto the interval is no parameter where the speed along the piece
/// varies, as on a rational piece with unequal weights, and Newton's method may not recover
/// from such a start).
fn chord_candidate<T: Scalar, QA: ControlPoint<T>, QB: ControlPoint<T>>(
    (pa, project_a): (&Piece<T, QA>, &impl Fn(&QA) -> Vector2<T>),
    (pb, project_b): (&Piece<T, QB>, &impl Fn(&QB) -> Vector2<T>),
    tolerance: T,
) -> Option<Candidate<T>> {
    let (s, t, distance) = segment_closest(pa.first, pa.last, pb.first, pb.last);
    if distance > tolerance + pa.flatness + pb.flatness {
        return None;
    }
    Some(Candidate {
        u: pa.at_fraction(s, project_a),
        v: pb.at_fraction(t, project_b),
    })
}
