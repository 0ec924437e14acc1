//! Compatible curves and surfaces (The NURBS Book §8.4, §10.3): the same degree by exact
//! elevation, the same domain by an affine reparametrisation, the same knots by refinement
//! to the merged knot vector ([`KnotVector::merged`]). Ruled surfaces, skinning, Coons and
//! Gordon surfaces combine control points of compatible pieces.

use crate::bspline::BSpline;
use crate::surface::{Direction, Surface};
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar};

/// The knot vector of `knots` mapped affinely from its domain onto `[s, e]`, with the end
/// knots exactly `s` and `e` (so that merged vectors share their ends bit for bit).
fn mapped_onto<T: Scalar>(knots: &KnotVector<T>, (s, e): (T, T)) -> Result<KnotVector<T>> {
    let (c, d) = knots.domain();
    let scale = (e - s) / (d - c);
    let mapped = knots
        .knots()
        .iter()
        .map(|&x| {
            if x == c {
                s
            } else if x == d {
                e
            } else {
                s + (x - c) * scale
            }
        })
        .collect();
    KnotVector::new(knots.degree(), mapped)
}

/// The knots of `target` missing from `knots` (each with the missing multiplicity).
fn missing<T: Scalar>(target: &KnotVector<T>, knots: &KnotVector<T>) -> Vec<T> {
    let mut extra = Vec::new();
    for (k, m) in target.interior_breakpoints() {
        extra.extend(std::iter::repeat_n(
            k,
            m.saturating_sub(knots.multiplicity(k)),
        ));
    }
    extra
}

/// The curves made compatible: clamped, elevated to the highest degree among them, mapped
/// onto the domain of the first, and refined to the union of their knot vectors (each
/// distinct knot with its largest multiplicity). Every curve keeps its shape exactly (up to
/// rounding); afterwards they share degree and knot vector, so their control points can be
/// combined (The NURBS Book §10.3).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::{BSpline, compatible_curves};
/// let line = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
///     vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)])?;
/// let arch = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 0.5, 2.0, 2.0, 2.0],
///     vec![Vector2::new(0.0, 1.0), Vector2::new(0.3, 2.0), Vector2::new(0.7, 2.0),
///          Vector2::new(1.0, 1.0)])?;
/// let same = compatible_curves(&[line.clone(), arch.clone()])?;
/// assert_eq!(same[0].knots(), same[1].knots());
/// // The arch now runs on [0, 1]: its parameter 1.0 became 0.5.
/// assert!((same[1].eval(0.5)? - arch.eval(1.0)?).norm() < 1e-15);
/// assert!((same[0].eval(0.25)? - line.eval(0.25)?).norm() < 1e-15);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] for an empty list; [`ErrorKind::DegreeTooHigh`] from
/// elevation.
pub fn compatible_curves<T: Scalar, P: ControlPoint<T>>(
    curves: &[BSpline<T, P>],
) -> Result<Vec<BSpline<T, P>>> {
    let Some(first) = curves.first() else {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            "no curves to make compatible",
        ));
    };
    let degree = curves.iter().map(BSpline::degree).max().unwrap_or(0);
    let domain = first.domain();
    let mut same = Vec::with_capacity(curves.len());
    for (k, c) in curves.iter().enumerate() {
        let elevated = c
            .clamped()
            .elevate_degree(degree - c.degree())
            .map_err(|e| e.context(format_args!("curve {k}")))?;
        let knots = mapped_onto(elevated.knots(), domain)?;
        same.push(BSpline::new_unchecked(knots, elevated.into_parts().1));
    }
    let mut target = same[0].knots().clone();
    for c in &same[1..] {
        target = target.merged(c.knots())?;
    }
    same.iter()
        .map(|c| c.refine(&missing(&target, c.knots())))
        .collect()
}

/// The surfaces made compatible in both directions, as [`compatible_curves`] does for
/// curves: the same degrees, the domain of the first, the merged knot vectors. Every surface
/// keeps its shape.
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] for an empty list; [`ErrorKind::DegreeTooHigh`] from
/// elevation.
pub fn compatible_surfaces<T: Scalar, P: ControlPoint<T>>(
    surfaces: &[Surface<T, P>],
) -> Result<Vec<Surface<T, P>>> {
    if surfaces.is_empty() {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            "no surfaces to make compatible",
        ));
    }
    let mut same: Vec<Surface<T, P>> = surfaces.iter().map(Surface::clamped).collect();
    for direction in [Direction::U, Direction::V] {
        let degree = same.iter().map(|s| s.degree(direction)).max().unwrap_or(0);
        let domain = same[0].knots(direction).domain();
        for s in &mut same {
            let elevated = s.elevate_degree(direction, degree - s.degree(direction))?;
            let knots = mapped_onto(elevated.knots(direction), domain)?;
            let (ku, kv, points) = elevated.into_parts();
            *s = match direction {
                Direction::U => Surface::new_unchecked(knots, kv, points),
                Direction::V => Surface::new_unchecked(ku, knots, points),
            };
        }
        let mut target = same[0].knots(direction).clone();
        for s in &same[1..] {
            target = target.merged(s.knots(direction))?;
        }
        for s in &mut same {
            *s = s.refine(direction, &missing(&target, s.knots(direction)))?;
        }
    }
    Ok(same)
}

/// The Boolean sum `a + b − c` of three surfaces (The NURBS Book §10.5: the Coons patch is
/// the sum of two ruled surfaces less the bilinear patch of their corners, the Gordon
/// surface that of two skins less the interpolant of their crossings): the three made
/// compatible ([`compatible_surfaces`]), their control points combined. The sum reproduces
/// a boundary or network curve wherever `c` equals one of `a` and `b` there.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_core::KnotVector;
/// use spline_geom::{Surface, boolean_sum};
/// let bilinear = |z: [f64; 4]| {
///     let k = KnotVector::clamped(1, 0.0, 1.0, &[])?;
///     let points = [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0), (1.0, 1.0)]
///         .iter()
///         .zip(z)
///         .map(|(&(x, y), z)| Vector3::new(x, y, z))
///         .collect();
///     Surface::new(k.clone(), k, points)
/// };
/// let s = boolean_sum(
///     bilinear([1.0, 1.0, 0.0, 0.0])?,
///     bilinear([0.0, 2.0, 0.0, 2.0])?,
///     bilinear([0.0, 1.0, 0.0, 0.0])?,
/// )?;
/// // x and y add up to themselves (1 + 1 − 1), the heights to 0 + 2 − 0.
/// assert!((s.eval(1.0, 1.0)? - Vector3::new(1.0, 1.0, 2.0)).norm() < 1e-15);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`compatible_surfaces`].
pub fn boolean_sum<T: Scalar, P: ControlPoint<T>>(
    a: Surface<T, P>,
    b: Surface<T, P>,
    c: Surface<T, P>,
) -> Result<Surface<T, P>> {
    let parts = compatible_surfaces(&[a, b, c])?;
    let points = parts[0]
        .control_points()
        .iter()
        .zip(parts[1].control_points())
        .zip(parts[2].control_points())
        .map(|((a, b), c)| *a + *b - *c)
        .collect();
    let (ku, kv, _) = parts[0].clone().into_parts();
    Ok(Surface::new_unchecked(ku, kv, points))
}
