//! Root isolation for B-spline functions: Bézier extraction, Bernstein sign changes
//! (Descartes' rule), subdivision, then Newton's method safeguarded by bisection.

use crate::maps::SplineMap;
use spline_core::{Error, ErrorKind, Result, Scalar, from_count, to_f64};
use spline_geom::BSpline;

/// A zero of a B-spline function: an isolated root (`start == end`) or an interval on which
/// the function vanishes identically (`start < end`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Zero<T> {
    /// Where the zero starts.
    pub start: T,
    /// Where it ends (equal to `start` for an isolated root).
    pub end: T,
    /// Whether the function has opposite signs just before and just after the zero (a
    /// crossing: odd multiplicity). A double root, a zero at an end of the domain, or a zero
    /// interval with the same sign on both sides is not a crossing.
    pub sign_change: bool,
}

impl<T: Scalar> Zero<T> {
    /// Whether the function vanishes on a whole interval.
    #[must_use]
    pub fn is_interval(&self) -> bool {
        self.start < self.end
    }

    /// The root, or the middle of a zero interval.
    #[must_use]
    pub fn at(&self) -> T {
        (self.start + self.end) * spline_core::cast(0.5)
    }
}

/// Sign of `x` with values within `tol` of zero counted as zero.
fn sign<T: Scalar>(x: T, tol: T) -> i8 {
    if x > tol {
        1
    } else if x < -tol {
        -1
    } else {
        0
    }
}

/// Sign changes of the coefficients (values within `tol` skipped), with the first and last
/// non-zero signs.
fn sign_pattern<T: Scalar>(b: &[T], tol: T) -> (usize, i8, i8) {
    let mut changes = 0;
    let mut first = 0;
    let mut last = 0;
    for &x in b {
        let s = sign(x, tol);
        if s == 0 {
            continue;
        }
        if first == 0 {
            first = s;
        } else if s != last {
            changes += 1;
        }
        last = s;
    }
    (changes, first, last)
}

/// Value and derivative (with respect to the local parameter) of a Bernstein polynomial.
fn bernstein_eval<T: Scalar>(b: &[T], t: T, work: &mut Vec<T>) -> (T, T) {
    let d = b.len() - 1;
    if d == 0 {
        return (b[0], T::zero());
    }
    work.clear();
    work.extend_from_slice(b);
    let s = T::one() - t;
    for level in 1..d {
        for i in 0..=d - level {
            work[i] = work[i] * s + work[i + 1] * t;
        }
    }
    (
        work[0] * s + work[1] * t,
        (work[1] - work[0]) * from_count::<T>(d),
    )
}

/// De Casteljau subdivision at 1/2.
fn halves<T: Scalar>(b: &[T]) -> (Vec<T>, Vec<T>) {
    let d = b.len() - 1;
    let half = spline_core::cast::<T>(0.5);
    let mut work = b.to_vec();
    let mut left = Vec::with_capacity(d + 1);
    let mut right = Vec::with_capacity(d + 1);
    left.push(work[0]);
    right.push(work[d]);
    for level in 1..=d {
        for i in 0..=d - level {
            work[i] = (work[i] + work[i + 1]) * half;
        }
        left.push(work[0]);
        right.push(work[d - level]);
    }
    right.reverse();
    (left, right)
}

struct Isolator<T> {
    tol: T,
    accuracy: T,
    points: Vec<T>,
    work: Vec<T>,
}

impl<T: Scalar> Isolator<T> {
    /// Roots of the Bernstein polynomial `b` on `[t0, t1]` in the open interval.
    fn isolate(&mut self, b: &[T], t0: T, t1: T) {
        let (changes, first, last) = sign_pattern(b, self.tol);
        if changes == 0 {
            return;
        }
        let half = spline_core::cast::<T>(0.5);
        let mid = (t0 + t1) * half;
        if t1 - t0 <= self.accuracy || !(mid > t0 && mid < t1) {
            // Width below the accuracy: a root (odd count) or a double root / cluster that
            // cannot be resolved further.
            self.points.push(mid);
            return;
        }
        let d = b.len() - 1;
        if changes == 1 && sign(b[0], self.tol) == first && sign(b[d], self.tol) == last {
            let root = self.newton(b, t0, t1, first);
            self.points.push(root);
            return;
        }
        let (left, right) = halves(b);
        if sign(left[d], self.tol) == 0 {
            self.points.push(mid);
        }
        self.isolate(&left, t0, mid);
        self.isolate(&right, mid, t1);
    }

    /// The single root of `b` on `[t0, t1]` (signs `s0` at the start, `−s0` at the end) by
    /// Newton's method, falling back to bisection whenever a step leaves the bracket.
    fn newton(&mut self, b: &[T], t0: T, t1: T, s0: i8) -> T {
        let width = t1 - t0;
        let half = spline_core::cast::<T>(0.5);
        let (mut lo, mut hi) = (T::zero(), T::one());
        // Start where the control polygon crosses zero.
        let d = b.len() - 1;
        let mut t = half;
        for i in 0..d {
            if sign(b[i], T::zero()) == s0 && sign(b[i + 1], T::zero()) != s0 {
                let (x0, x1) = (from_count::<T>(i), from_count::<T>(i + 1));
                let frac = b[i] / (b[i] - b[i + 1]);
                t = (x0 + (x1 - x0) * frac) / from_count::<T>(d);
                break;
            }
        }
        if !(t > lo && t < hi) {
            t = half;
        }
        for _ in 0..200 {
            let (f, df) = bernstein_eval(b, t, &mut self.work);
            if f == T::zero() {
                break;
            }
            if sign(f, T::zero()) == s0 {
                lo = t;
            } else {
                hi = t;
            }
            let newton = t - f / df;
            let next = if df != T::zero() && newton > lo && newton < hi {
                newton
            } else {
                (lo + hi) * half
            };
            let step = (next - t).abs() * width;
            t = next;
            if (hi - lo) * width <= self.accuracy || step <= self.accuracy * half {
                break;
            }
        }
        t0 + t * width
    }
}

/// All zeros of a B-spline function on its domain, in increasing order, each located to
/// within `accuracy` (absolute, in parameter units).
///
/// The function is cut into its Bézier segments; a segment whose Bernstein coefficients
/// have no sign change has no root inside (variation diminishing); one sign change with
/// non-zero end coefficients brackets exactly one root, found by Newton's method safeguarded
/// by bisection; more changes are resolved by de Casteljau subdivision. Coefficients within
/// a few ulps of the largest one count as zero, so a piece that vanishes identically is
/// reported as a zero interval, and a double root (a touching zero, no sign change) is
/// reported once with `sign_change = false` once the subdivision reaches `accuracy`.
/// Zeros closer than `accuracy` are merged. The accuracy applies to the computed Bernstein
/// pieces: a root of the exact function is only determined up to its condition number,
/// about `ε ‖f‖ / |f′(r)|`, so asking for more than that gains nothing. Whether a zero is a crossing is decided from
/// the signs of the function between consecutive zeros and discontinuities. At a
/// discontinuity (a knot where the pieces do not meet) a jump across zero is not a zero;
/// [`sign_change_params`] reports those too.
///
/// ```
/// use spline_geom::BSpline;
/// // (u − 0.25)(u − 0.75) on [0, 1]: Bernstein coefficients 3/16, −5/16, 3/16.
/// let f = BSpline::from_knots(2, vec![0.0f64, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.1875, -0.3125, 0.1875])?;
/// let zeros = spline_algebra::zeros(&f, 1e-12)?;
/// assert_eq!(zeros.len(), 2);
/// assert!((zeros[0].at() - 0.25).abs() < 1e-12 && zeros[0].sign_change);
/// assert!((zeros[1].at() - 0.75).abs() < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidTolerance`] unless `accuracy` is positive and finite.
pub fn zeros<T: Scalar>(f: &BSpline<T, T>, accuracy: T) -> Result<Vec<Zero<T>>> {
    Ok(analyse(f, accuracy)?.zeros)
}

fn analyse<T: Scalar>(f: &BSpline<T, T>, accuracy: T) -> Result<Analysis<T>> {
    if !(accuracy > T::zero() && accuracy.is_finite()) {
        return Err(Error::new(
            ErrorKind::InvalidTolerance,
            format!(
                "the accuracy must be positive and finite, got {}",
                to_f64(accuracy)
            ),
        )
        .with_value(to_f64(accuracy))
        .with_interval(0.0, f64::INFINITY));
    }
    let (a, b) = f.domain();
    let d = f.degree();
    let pieces = SplineMap::bezier_extraction(f.knots()).apply(f.control_points())?;
    let breakpoints = f.knots().domain_breaks();
    let scale = pieces.iter().fold(T::zero(), |m, &x| m.max(x.abs()));
    if scale == T::zero() {
        return Ok(Analysis {
            zeros: vec![Zero {
                start: a,
                end: b,
                sign_change: false,
            }],
            jumps: Vec::new(),
        });
    }
    // What counts as zero is relative to the coefficients where the function is evaluated
    // (the B-spline coefficients that support the span: the Bézier coefficients of a piece
    // are convex combinations of them), not to the largest coefficient anywhere: a function
    // of size 1e6 on one span and 1e20 on another keeps its sign changes on the first.
    let unit = T::default_epsilon() * from_count::<T>(16 * (d + 1));
    let tol = scale * unit;
    let coefficients = f.control_points();
    let local_tol = |u: T| -> T {
        f.knots().find_span(u).map_or(tol, |k| {
            coefficients[k.saturating_sub(d)..=k]
                .iter()
                .fold(T::zero(), |m, &x| m.max(x.abs()))
                * unit
        })
    };
    let mut iso = Isolator {
        tol,
        accuracy,
        points: Vec::new(),
        work: Vec::with_capacity(d + 1),
    };
    let mut intervals: Vec<(T, T)> = Vec::new();
    // Discontinuities: breakpoints where the pieces do not meet. They separate the regions
    // on which signs are compared.
    let mut jumps: Vec<(T, i8, i8)> = Vec::new();
    let segments: Vec<&[T]> = pieces.chunks_exact(d + 1).collect();
    for (s, coeffs) in segments.iter().enumerate() {
        let (t0, t1) = (breakpoints[s], breakpoints[s + 1]);
        let tol = local_tol((t0 + t1) * spline_core::cast(0.5));
        iso.tol = tol;
        if s > 0 {
            // Each side's sign is judged against the coefficients of its own span: a
            // numerator of size 1e7 left of a knot and 1e22 right of it changes sign there
            // (issue 25: a random space cubic's curvature maximum at a knot near the end).
            let left = segments[s - 1][d];
            let left_tol = local_tol((breakpoints[s - 1] + t0) * spline_core::cast(0.5));
            if (left - coeffs[0]).abs() > tol.max(left_tol) {
                jumps.push((t0, sign(left, left_tol), sign(coeffs[0], tol)));
            }
        }
        if coeffs.iter().all(|&x| x.abs() <= tol) {
            match intervals.last_mut() {
                Some(last) if last.1 == t0 => last.1 = t1,
                _ => intervals.push((t0, t1)),
            }
            continue;
        }
        if sign(coeffs[0], tol) == 0 {
            iso.points.push(t0);
        }
        if sign(coeffs[d], tol) == 0 {
            iso.points.push(t1);
        }
        iso.isolate(coeffs, t0, t1);
    }
    // Merge: sort the events, absorb points into intervals and clusters into one point.
    let mut events: Vec<(T, T)> = intervals;
    events.extend(iso.points.iter().map(|&x| (x, x)));
    events.sort_by(|x, y| x.0.partial_cmp(&y.0).expect("finite parameters"));
    let mut merged: Vec<(T, T)> = Vec::with_capacity(events.len());
    for (s, e) in events {
        match merged.last_mut() {
            Some(last) if s - last.1 <= accuracy => {
                if last.0 == last.1 && s == e {
                    // Two nearby points: keep their middle.
                    let m = (last.0 + e) * spline_core::cast(0.5);
                    *last = (m, m);
                } else if last.0 == last.1 {
                    *last = (s.min(last.0), e.max(last.1));
                } else {
                    last.1 = last.1.max(e);
                }
            }
            _ => merged.push((s, e)),
        }
    }
    // Signs between consecutive zeros and discontinuities decide the crossings.
    let sign_at = |u: T| -> i8 { f.eval(u).map_or(0, |v| sign(v, local_tol(u))) };
    let half = spline_core::cast::<T>(0.5);
    let mut out = Vec::with_capacity(merged.len());
    for (i, &(s, e)) in merged.iter().enumerate() {
        let before = if s <= a {
            0
        } else {
            let mut prev = if i == 0 { a } else { merged[i - 1].1 };
            for &(x, _, _) in &jumps {
                if x > prev && x < s {
                    prev = x;
                }
            }
            sign_at((prev + s) * half)
        };
        let after = if e >= b {
            0
        } else {
            let mut next = merged.get(i + 1).map_or(b, |z| z.0);
            for &(x, _, _) in jumps.iter().rev() {
                if x > e && x < next {
                    next = x;
                }
            }
            sign_at((e + next) * half)
        };
        out.push(Zero {
            start: s,
            end: e,
            sign_change: before != 0 && after != 0 && before != after,
        });
    }
    Ok(Analysis {
        zeros: out,
        jumps: jumps
            .into_iter()
            .filter(|&(_, l, r)| l != 0 && r != 0 && l != r)
            .map(|(x, _, _)| x)
            .collect(),
    })
}

/// The zeros of a function and the discontinuities where it jumps across zero.
struct Analysis<T> {
    zeros: Vec<Zero<T>>,
    jumps: Vec<T>,
}

/// All parameters where a B-spline function changes sign on its domain, in increasing
/// order: its crossing zeros ([`zeros`] with `sign_change`; the middle of a zero interval)
/// and the knots where it is discontinuous and jumps from one sign to the other (as `g`
/// of a cubic curve does at simple knots).
///
/// ```
/// use spline_geom::BSpline;
/// // A piecewise-constant function −1 on [0, 1), +1 on [1, 2]: a sign change at the jump.
/// let f = BSpline::from_knots(0, vec![0.0, 1.0, 2.0], vec![-1.0, 1.0])?;
/// assert!(spline_algebra::zeros(&f, 1e-12)?.is_empty());
/// assert_eq!(spline_algebra::sign_change_params(&f, 1e-12)?, vec![1.0]);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`zeros`].
///
/// # Panics
/// Never: parameters are finite, so they compare.
pub fn sign_change_params<T: Scalar>(f: &BSpline<T, T>, accuracy: T) -> Result<Vec<T>> {
    let analysis = analyse(f, accuracy)?;
    let mut out: Vec<T> = analysis
        .zeros
        .iter()
        .filter(|z| z.sign_change)
        .map(Zero::at)
        .chain(analysis.jumps)
        .collect();
    out.sort_by(|x, y| x.partial_cmp(y).expect("finite parameters"));
    out.dedup();
    Ok(out)
}
