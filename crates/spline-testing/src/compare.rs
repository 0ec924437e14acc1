//! Comparisons with tolerances that scale with the data, and of curves by their values.

use nalgebra::SVector;
use spline_core::{ControlPoint, Scalar, to_f64};
use spline_geom::ParamCurve;

/// Asserts `|a_i − b_i| ≤ tol · scale(b_i)` for every entry.
fn assert_entries(a: &[f64], b: &[f64], tol: f64, what: &str, scale: impl Fn(f64) -> f64) {
    assert_eq!(
        a.len(),
        b.len(),
        "{what}: lengths {} vs {}",
        a.len(),
        b.len()
    );
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        let s = scale(*y);
        assert!(
            (x - y).abs() <= tol * s,
            "{what}[{i}]: got {x}, expected {y} (diff {:.3e}, scale {s:e})",
            (x - y).abs()
        );
    }
}

/// Asserts `|a_i − b_i| ≤ tol · max(1, |b_i|)` for every entry.
///
/// # Panics
/// When the lengths or an entry differ.
pub fn assert_close(a: &[f64], b: &[f64], tol: f64, what: &str) {
    assert_entries(a, b, tol, what, |y| y.abs().max(1.0));
}

/// Asserts `|a_i − b_i| ≤ tol · max(1, max_j |b_j|)` for every entry: a tolerance relative
/// to the size of the whole expected result.
///
/// # Panics
/// When the lengths or an entry differ.
pub fn assert_close_scaled(a: &[f64], b: &[f64], tol: f64, what: &str) {
    let scale = b.iter().fold(1f64, |m, x| m.max(x.abs()));
    assert_entries(a, b, tol, what, |_| scale);
}

/// Asserts `|got − expected| ≤ tol · max(scale, |expected|)`.
///
/// # Panics
/// When they differ.
pub fn assert_close_rel(got: f64, expected: f64, tol: f64, scale: f64, what: &str) {
    let s = scale.max(expected.abs());
    assert!(
        (got - expected).abs() <= tol * s,
        "{what}: got {got}, expected {expected} (relative difference {:.3e})",
        (got - expected).abs() / s
    );
}

/// The largest coordinate magnitude of the points (at least 1): the scale of relative
/// tolerances on them.
#[must_use]
pub fn scale_of<T: Scalar, P: ControlPoint<T>>(points: &[P]) -> f64 {
    points.iter().fold(1f64, |m, p| m.max(to_f64(p.max_abs())))
}

/// Asserts that two lists of points agree to `tol` relative to the size of `expected`
/// ([`scale_of`]), coordinate by coordinate.
///
/// # Panics
/// When the lengths or a point differ.
pub fn assert_points_close<const D: usize>(
    got: &[SVector<f64, D>],
    expected: &[SVector<f64, D>],
    tol: f64,
    what: &str,
) {
    assert_eq!(got.len(), expected.len(), "{what}: lengths");
    let scale = scale_of(expected);
    for (i, (a, b)) in got.iter().zip(expected).enumerate() {
        assert!(
            (a - b).amax() <= tol * scale,
            "{what}[{i}]: {a:?} vs {b:?} (diff {:.3e})",
            (a - b).amax()
        );
    }
}

/// The largest distance between two curves of any kind sampled at `per_span` points in
/// every piece of `a` and at every break of both (they must share the domain).
///
/// # Panics
/// If a sample cannot be evaluated (different domains).
#[must_use]
pub fn max_distance<A, B>(a: &A, b: &B, per_span: usize) -> f64
where
    A: ParamCurve<f64>,
    B: ParamCurve<f64, Point = A::Point>,
{
    let mut params = a.sample_params(per_span);
    params.extend(b.breaks());
    params
        .iter()
        .map(|&u| (a.eval(u).expect("in the domain") - b.eval(u).expect("in the domain")).length())
        .fold(0.0, f64::max)
}

/// Asserts that two curves of any kind are the same curve: equal domains and values within
/// `tol` relative to the size of `a`'s control polygon ([`max_distance`]).
///
/// # Panics
/// When they differ.
pub fn assert_same_curve<A, B>(a: &A, b: &B, tol: f64, what: &str)
where
    A: ParamCurve<f64>,
    B: ParamCurve<f64, Point = A::Point>,
{
    assert_eq!(a.domain(), b.domain(), "{what}: domains");
    let scale = scale_of(&a.control_polygon());
    let d = max_distance(a, b, 16);
    assert!(
        d <= tol * scale,
        "{what}: the curves differ by {d:.3e} (scale {scale:e})"
    );
}
