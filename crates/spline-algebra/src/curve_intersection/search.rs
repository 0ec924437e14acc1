//! The subdivision: pairs of Bézier pieces whose boxes and fat lines meet are split until
//! they are flat (a candidate for Newton's method where their chords meet) or until one lies
//! on the other curve along its whole length (a piece of an overlap). The work is bounded by
//! the geometry: a pair is split only while neither holds, which near a crossing or a
//! tangency takes `log₂(size / tolerance)` levels and near the end of an overlap as many.

use super::overlap::{OverlapPiece, lies_on};
use super::piece::{Piece, mid, segment_closest};
use super::{Candidate, MAX_INTERSECTION_PAIRS};
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, cast};
use spline_geom::PlanarCurve;

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
        if x.size() > shortest && y.size() > shortest {
            let (x0, x1) = x.interval();
            let (y0, y1) = y.interval();
            let (ylo, yhi) = widen((y0, y1), (db0, db1), reach);
            if let Some((t0, t1)) = lies_on(a, (x0, x1), b, (ylo, yhi), tolerance, x.points.len())?
            {
                found.overlaps.push(OverlapPiece {
                    s: (x0, x1),
                    t: (t0, t1),
                });
                continue;
            }
            let (xlo, xhi) = widen((x0, x1), (da0, da1), reach);
            if let Some((s0, s1)) = lies_on(b, (y0, y1), a, (xlo, xhi), tolerance, y.points.len())?
            {
                let (s, t) = if s0 <= s1 {
                    ((s0, s1), (y0, y1))
                } else {
                    ((s1, s0), (y1, y0))
                };
                found.overlaps.push(OverlapPiece { s, t });
                continue;
            }
        }
        let flat_x = x.flatness <= flat;
        let flat_y = y.flatness <= flat;
        if flat_x && flat_y {
            if let Some(c) = chord_candidate(&x, &y, tolerance) {
                found.starts.push(c);
            }
            continue;
        }
        // Split the larger piece that is not flat.
        let split_x = !flat_x && (flat_y || x.size() >= y.size());
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

/// The start of Newton's method for two flat pieces: the closest points of their chords,
/// if those come within the tolerance (plus the flatness of the pieces).
fn chord_candidate<T: Scalar, QA: ControlPoint<T>, QB: ControlPoint<T>>(
    pa: &Piece<T, QA>,
    pb: &Piece<T, QB>,
    tolerance: T,
) -> Option<Candidate<T>> {
    let (s, t, distance) = segment_closest(pa.first, pa.last, pb.first, pb.last);
    if distance > tolerance + pa.flatness + pb.flatness {
        return None;
    }
    let (a0, a1) = pa.interval();
    let (b0, b1) = pb.interval();
    Some(Candidate {
        u: a0 + (a1 - a0) * s,
        v: b0 + (b1 - b0) * t,
    })
}
