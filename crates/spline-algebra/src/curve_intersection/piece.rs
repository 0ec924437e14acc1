//! Bézier pieces of a planar curve with their boxes, chords and fat lines: the bounds the
//! subdivision prunes with.

use nalgebra::Vector2;
use spline_core::{ControlPoint, Result, Scalar, cast};
use spline_geom::{Bezier, ParamCurve, wedge};

/// A Bézier piece of a curve: its interval, its coefficients and the box of their
/// projections (which contains the piece).
#[derive(Clone, Debug)]
pub(super) struct Piece<T: Scalar, Q: ControlPoint<T>> {
    pub(super) bezier: Bezier<T, Q>,
    pub(super) lo: Vector2<T>,
    pub(super) hi: Vector2<T>,
    /// Largest distance of a projected control point from the chord.
    pub(super) flatness: T,
    pub(super) first: Vector2<T>,
    pub(super) last: Vector2<T>,
    /// The projected control points.
    pub(super) points: Vec<Vector2<T>>,
}

impl<T: Scalar, Q: ControlPoint<T>> Piece<T, Q> {
    pub(super) fn new(bezier: Bezier<T, Q>, project: impl Fn(&Q) -> Vector2<T>) -> Self {
        let points: Vec<Vector2<T>> = bezier.control_points().iter().map(&project).collect();
        let (mut lo, mut hi) = (points[0], points[0]);
        for q in &points[1..] {
            lo = lo.inf(q);
            hi = hi.sup(q);
        }
        let (first, last) = (points[0], points[points.len() - 1]);
        let chord = last - first;
        let length = chord.norm();
        let flatness = points.iter().fold(T::zero(), |m, q| {
            let d = if length > T::zero() {
                wedge(&chord, &(q - first)).abs() / length
            } else {
                (q - first).norm()
            };
            m.max(d)
        });
        Self {
            bezier,
            lo,
            hi,
            flatness,
            first,
            last,
            points,
        }
    }

    pub(super) fn size(&self) -> T {
        (self.hi - self.lo).norm()
    }

    pub(super) fn interval(&self) -> (T, T) {
        self.bezier.interval()
    }

    /// Splits in the middle of the interval (`None` at the resolution of floating point).
    pub(super) fn split(&self, project: &impl Fn(&Q) -> Vector2<T>) -> Option<(Self, Self)> {
        self.split_at(mid(self.interval()), project)
    }

    /// Splits at `t`, strictly inside the interval (`None` otherwise).
    pub(super) fn split_at(
        &self,
        t: T,
        project: &impl Fn(&Q) -> Vector2<T>,
    ) -> Option<(Self, Self)> {
        let (a, b) = self.bezier.interval();
        if !(t > a && t < b) {
            return None;
        }
        let (l, r) = self.bezier.subdivide(t).ok()?;
        Some((Piece::new(l, project), Piece::new(r, project)))
    }

    /// The parameter where the piece reaches the fraction `f` of its chord (the projection
    /// of its point on the chord's direction), by bisection on the piece itself: the fraction
    /// goes from 0 to 1 over the interval, so bisection finds a place where it is `f`
    /// (where the speed along the piece varies, as on a rational piece with unequal
    /// weights, the parameter is not the fraction mapped onto the interval).
    pub(super) fn at_fraction(&self, f: T, project: &impl Fn(&Q) -> Vector2<T>) -> T {
        let chord = self.last - self.first;
        let length = chord.norm_squared();
        let (mut lo, mut hi) = self.interval();
        if !(length > T::zero()) {
            return along((lo, hi), f);
        }
        for _ in 0..200 {
            let m = mid((lo, hi));
            if !(m > lo && m < hi) {
                break;
            }
            let Ok(q) = self.bezier.eval(m) else { break };
            if (project(&q) - self.first).dot(&chord) / length < f {
                lo = m;
            } else {
                hi = m;
            }
        }
        mid((lo, hi))
    }

    /// Whether the boxes of the two pieces come within `slack` of each other and neither
    /// piece's fat line (the strip along its chord holding its control points) is
    /// separated by more than `slack` from the other's control points.
    pub(super) fn overlaps<R: ControlPoint<T>>(&self, other: &Piece<T, R>, slack: T) -> bool {
        (0..2).all(|c| self.lo[c] <= other.hi[c] + slack && other.lo[c] <= self.hi[c] + slack)
            && self.fat_line_meets(&other.points, slack)
            && other.fat_line_meets(&self.points, slack)
    }

    /// Whether the strip along the chord that holds this piece's control points comes
    /// within `slack` of the convex hull of `points` (always true for a piece whose ends
    /// coincide).
    fn fat_line_meets(&self, points: &[Vector2<T>], slack: T) -> bool {
        let chord = self.last - self.first;
        let length = chord.norm();
        if !(length > T::zero()) {
            return true;
        }
        let distance = |q: &Vector2<T>| wedge(&chord, &(q - self.first)) / length;
        let band = |ps: &[Vector2<T>]| {
            let d0 = distance(&ps[0]);
            ps[1..].iter().fold((d0, d0), |(lo, hi), q| {
                let d = distance(q);
                (lo.min(d), hi.max(d))
            })
        };
        let (lo, hi) = band(&self.points);
        let (qlo, qhi) = band(points);
        qhi >= lo - slack && qlo <= hi + slack
    }

    /// Whether the directions of the projected control polygon's legs lie in an open
    /// half-plane: the piece then has no self-intersection (its tangents stay in the cone
    /// of the legs, also for rational pieces with positive weights).
    pub(super) fn is_monotone(&self) -> bool {
        let chord = self.last - self.first;
        self.points
            .windows(2)
            .all(|w| (w[1] - w[0]).dot(&chord) > T::zero())
    }
}

/// The Bézier pieces of a curve.
pub(super) fn pieces_of<T: Scalar, C: ParamCurve<T, Point = Vector2<T>>>(
    curve: &C,
) -> Result<Vec<Piece<T, C::Coefficient>>> {
    curve
        .bezier_pieces()
        .into_iter()
        .map(|(a, b, coefficients)| {
            Bezier::with_interval(coefficients, a, b).map(|z| Piece::new(z, C::project))
        })
        .collect()
}

/// The middle of an interval.
pub(super) fn mid<T: Scalar>((a, b): (T, T)) -> T {
    along((a, b), cast(0.5))
}

/// The affine map `a + (b − a) f` of `f ∈ [0, 1]` onto the parameters from `a` to `b`
/// (either order), clamped between them: `a` and `b` exactly at `f = 0` and `f = 1`, and
/// never a rounding step beyond either (a parameter one step past the end of a domain is
/// outside it).
pub(super) fn along<T: Scalar>((a, b): (T, T), f: T) -> T {
    if f <= T::zero() {
        return a;
    }
    if f >= T::one() {
        return b;
    }
    let x = a + (b - a) * f;
    x.max(a.min(b)).min(a.max(b))
}

/// The closest points `p0 + s (p1 − p0)` and `q0 + t (q1 − q0)` of two segments and their
/// distance.
pub(super) fn segment_closest<T: Scalar>(
    p0: Vector2<T>,
    p1: Vector2<T>,
    q0: Vector2<T>,
    q1: Vector2<T>,
) -> (T, T, T) {
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.norm_squared(), d2.norm_squared(), d2.dot(&r));
    let clamp = |x: T| x.max(T::zero()).min(T::one());
    let (s, t) = if a == T::zero() && e == T::zero() {
        (T::zero(), T::zero())
    } else if a == T::zero() {
        (T::zero(), clamp(f / e))
    } else {
        let c = d1.dot(&r);
        if e == T::zero() {
            (clamp(-c / a), T::zero())
        } else {
            let b = d1.dot(&d2);
            let denom = a * e - b * b;
            let mut s = if denom > T::zero() {
                clamp((b * f - c * e) / denom)
            } else {
                T::zero()
            };
            let mut t = (b * s + f) / e;
            if t < T::zero() {
                t = T::zero();
                s = clamp(-c / a);
            } else if t > T::one() {
                t = T::one();
                s = clamp((b - c) / a);
            }
            (s, t)
        }
    };
    let distance = ((p0 + d1 * s) - (q0 + d2 * t)).norm();
    (s, t, distance)
}
