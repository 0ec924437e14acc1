//! The container of many value columns on one knot vector ([`ColumnSpline`]), scipy's knot
//! checks, and what it does outside its base interval ([`Extrapolate`]); its methods are in
//! `mod.rs` and the sibling modules.

use spline_core::{BatchBasis, Error, ErrorKind, KnotVector, MAX_DEGREE, Result};
use std::sync::OnceLock;

/// [`ErrorKind::InvalidLength`] unless an output of `out_len` values holds a row of `columns`
/// values for each of `points` points.
pub(crate) fn check_rows(points: usize, columns: usize, out_len: usize) -> Result<()> {
    if points.checked_mul(columns) == Some(out_len) {
        return Ok(());
    }
    Err(Error::new(
        ErrorKind::InvalidLength,
        format!(
            "the output holds {out_len} values; {points} points of {columns} columns need {}",
            points.saturating_mul(columns)
        ),
    ))
}

/// What happens at points outside the base interval $[t_k, t_n]$ (scipy's `extrapolate`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Extrapolate {
    /// scipy's `extrapolate=False`: points outside the base interval (and NaN points) give a
    /// row of NaN, counted in the result of [`ColumnSpline::eval_into`].
    Off,
    /// scipy's `extrapolate=True` (the default): below $t_k$ the first non-empty span's
    /// polynomial, above $t_n$ the last one's.
    On,
    /// scipy's `extrapolate='periodic'`: `x` is mapped to
    /// $t_k + (x - t_k) \bmod (t_n - t_k)$ (the floor modulo of Python) first.
    Periodic,
}

impl Extrapolate {
    /// The names every front end spells (the tool's `--extrapolate`, Python's strings).
    pub const NAMES: [&'static str; 3] = ["on", "off", "periodic"];

    /// The mode called `name` (one of [`Self::NAMES`]).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] naming the choices for any other text.
    ///
    /// ```
    /// use spline_geom::Extrapolate;
    /// assert_eq!(Extrapolate::from_name("periodic")?, Extrapolate::Periodic);
    /// assert!(Extrapolate::from_name("clip").is_err());
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    pub fn from_name(name: &str) -> Result<Self> {
        match name.trim() {
            "on" => Ok(Self::On),
            "off" => Ok(Self::Off),
            "periodic" => Ok(Self::Periodic),
            other => Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "unknown extrapolation {:?} (one of {})",
                    other.chars().take(40).collect::<String>(),
                    Self::NAMES.join(", ")
                ),
            )),
        }
    }
}

/// A spline of degree `k` on a knot vector `t` with `m` columns of coefficients: the
/// container behind `scipy.interpolate.BSpline` with the trailing dimensions of `c`
/// flattened.
///
/// $$ s_j(x) = \sum_{i=0}^{n-1} c_{ij} B_{i,k}(x; t), \qquad n = \mathrm{len}(t) - k - 1. $$
///
/// **Knot vectors accepted**: at least `2k + 2` finite knots in non-decreasing order with
/// $t_k < t_n$ and `k ≤ 32` ([`MAX_DEGREE`]), as scipy accepts them. A knot may repeat more
/// than `k + 1` times (a knot inserted at a clamped end, the degree-0 interpolant's
/// `[x…, x[-1]]`): the basis functions whose support is then a single point are identically
/// zero, and evaluation works on the knot vector without them ([`ColumnSpline::knot_vector`]),
/// which is the same function. The coefficient matrix has `rows ≥ n` rows (scipy
/// allows extra rows, and its derivative and antiderivative pad `c` to `len(t)` rows in
/// FITPACK's convention; the extra rows are kept and never used), each of `m ≥ 1` finite
/// values.
///
/// **An empty end span** ($t_{n-1} = t_n$, or $t_k = t_{k+1}$ below the base interval):
/// scipy evaluates points at or beyond that end on the empty span, which gives zero for
/// `k ≥ 1` and the coefficient row of the span for `k = 0`; so does this container (the
/// spline is then discontinuous at $t_n$, as de Boor's convention has it).
#[derive(Clone, Debug)]
pub struct ColumnSpline {
    /// The knots as given (scipy's `t`).
    pub(super) t: Vec<f64>,
    /// The knots without those of identically zero basis functions: what evaluation uses.
    pub(super) knots: KnotVector<f64>,
    /// The coefficients as given (`rows × columns`, row-major).
    pub(super) coefficients: Vec<f64>,
    /// The coefficient rows of the basis functions `knots` keeps, when some were dropped.
    pub(super) reduced: Option<Vec<f64>>,
    /// What points beyond an empty end span give (below $t_k$, from $t_n$ on).
    pub(super) empty_ends: [Option<EmptyEnd>; 2],
    pub(super) rows: usize,
    pub(super) columns: usize,
    /// The span and reciprocal tables, built at the first evaluation.
    pub(super) batch: OnceLock<BatchBasis<f64>>,
}

pub(super) fn invalid(message: impl Into<String>) -> Error {
    Error::new(ErrorKind::InvalidArgument, message)
}

/// The value scipy gives beyond an end whose span is empty.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum EmptyEnd {
    /// Zero (degree ≥ 1: the recursion on an empty span vanishes).
    Zero,
    /// The coefficient row of the empty span (degree 0).
    Row(usize),
}

/// scipy's checks of a knot vector for degree `k`, with scipy's words (any multiplicity).
pub(crate) fn check_scipy_knots(t: &[f64], k: usize) -> Result<()> {
    if k > MAX_DEGREE {
        return Err(Error::new(
            ErrorKind::DegreeTooHigh,
            format!("degree {k} is above the supported maximum {MAX_DEGREE}"),
        ));
    }
    if t.len() < 2 * k + 2 {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("Need at least {} knots for degree {k}", 2 * k + 2),
        )
        .with_counts(2 * k + 2, t.len()));
    }
    if let Some(i) = t.iter().position(|v| !v.is_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("Knots should not have nans or infs (knot {i} is {})", t[i]),
        )
        .with_index(i));
    }
    if let Some(i) = (1..t.len()).find(|&i| t[i] < t[i - 1]) {
        return Err(Error::new(
            ErrorKind::UnsortedKnots,
            format!(
                "Knots must be in a non-decreasing order (knot {i} = {} follows {})",
                t[i],
                t[i - 1]
            ),
        )
        .with_index(i));
    }
    let n = t.len() - k - 1;
    if t[k] >= t[n] {
        return Err(Error::new(
            ErrorKind::EmptyDomain,
            format!(
                "Need at least two internal knots: the base interval [t[{k}], t[{n}]] = [{}, {}] is empty",
                t[k], t[n]
            ),
        ));
    }
    Ok(())
}

/// scipy's checks of a knot vector for degree `k`, with scipy's words, then the library's
/// rules (multiplicity at most `k + 1`, degree limit) through [`KnotVector::new`].
pub(crate) fn check_knots(t: Vec<f64>, k: usize) -> Result<KnotVector<f64>> {
    check_scipy_knots(&t, k)?;
    KnotVector::new(k, t)
}

/// The knots of `t` without those of the basis functions of a single point's support
/// ($t_i = t_{i+k+1}$, identically zero), with the indices of the basis functions kept; `None`
/// when every basis function has a non-empty support. Dropping knot `i` of each such function
/// leaves `k + 1` copies of every longer run, and every other basis function keeps its knots.
pub(crate) fn without_empty_basis(t: &[f64], k: usize) -> Option<(Vec<f64>, Vec<usize>)> {
    let n = t.len() - k - 1;
    let empty = |i: usize| i < n && t[i] == t[i + k + 1];
    if !(0..n).any(empty) {
        return None;
    }
    let knots = (0..t.len()).filter(|&i| !empty(i)).map(|i| t[i]).collect();
    let kept = (0..n).filter(|&i| !empty(i)).collect();
    Some((knots, kept))
}
