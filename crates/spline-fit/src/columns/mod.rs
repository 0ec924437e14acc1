//! Interpolation and least squares of many columns of data on one knot vector, with the
//! semantics of scipy 1.17's `make_interp_spline` and `make_lsq_spline`: the same knots,
//! conditions, results (to rounding) and the words of scipy's error messages. The results
//! are [`ColumnSpline`]s.
//!
//! ```
//! use spline_fit::{InterpBc, make_interp_spline};
//! // Two columns, x ↦ x² and x ↦ 1 − x, through 6 points: a cubic reproduces both.
//! let x = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
//! let y: Vec<f64> = x.iter().flat_map(|&v: &f64| [v * v, 1.0 - v]).collect();
//! let s = make_interp_spline(&x, &y, 2, 3, None, &InterpBc::NotAKnot)?;
//! assert_eq!(s.knots(), &[0.0, 0.0, 0.0, 0.0, 2.0, 3.0, 5.0, 5.0, 5.0, 5.0]);
//! let v = s.eval(&[2.5], 0, spline_geom::Extrapolate::On)?;
//! assert!((v[0] - 6.25).abs() < 1e-12 && (v[1] + 1.5).abs() < 1e-12);
//! # Ok::<(), spline_core::Error>(())
//! ```

#[macro_use]
mod chunks;
mod collocation;

use crate::banded::{BandLu, Staircase};
use crate::periodic::solve_periodic_collocation;
use chunks::{Chunk, Solved, by_chunks, check_data, invalid, knot_vector, out_of_bounds};
use spline_core::{Error, ErrorKind, KnotVector, MAX_DEGREE, MAX_ORDER, Result};
use spline_geom::ColumnSpline;

/// The boundary conditions of scipy's `make_interp_spline` (`bc_type`).
#[derive(Clone, Debug, PartialEq)]
pub enum InterpBc {
    /// `None` or `'not-a-knot'`: no extra conditions; the default knots are the not-a-knot
    /// knots ([`KnotVector::not_a_knot`]).
    NotAKnot,
    /// `'periodic'`: `y[0] = y[-1]` and the spline with the periodic knots of
    /// [`ColumnSpline::periodic_knots`], `len(x) + k − 1` coefficients with
    /// `c[i + len(x) − 1] = c[i]`.
    Periodic,
    /// Derivatives at the ends (`bc_type = (left, right)`): each a list of
    /// `(order, values)` with one value per column, order `0 … k`, added as rows of the
    /// collocation system before the data (left) and after it (right). `'clamped'` is
    /// `[(1, zeros)]`, `'natural'` `[(2, zeros)]` ([`InterpBc::natural`],
    /// [`InterpBc::clamped`]). The default knots then repeat each end `k + 1` times with
    /// every abscissa a knot.
    Ends {
        /// The conditions at `x[0]`.
        left: Vec<(usize, Vec<f64>)>,
        /// The conditions at `x[-1]`.
        right: Vec<(usize, Vec<f64>)>,
    },
}

impl InterpBc {
    /// scipy's `'natural'` for `columns` columns: zero second derivatives at both ends.
    #[must_use]
    pub fn natural(columns: usize) -> Self {
        Self::Ends {
            left: vec![(2, vec![0.0; columns])],
            right: vec![(2, vec![0.0; columns])],
        }
    }

    /// scipy's `'clamped'` for `columns` columns: zero first derivatives at both ends.
    #[must_use]
    pub fn clamped(columns: usize) -> Self {
        Self::Ends {
            left: vec![(1, vec![0.0; columns])],
            right: vec![(1, vec![0.0; columns])],
        }
    }
}

/// Derivative conditions at one end: `(order, one value per column)`.
type EndConditions = [(usize, Vec<f64>)];

/// The not-a-knot knots of scipy's `_not_a_knot(x, k)`, also for `len(x) ≤ k` (no interior
/// knots).
fn not_a_knot_knots(x: &[f64], k: usize) -> Result<Vec<f64>> {
    let n = x.len();
    Ok(if n > k {
        KnotVector::not_a_knot(k, x)?.into_knots()
    } else {
        KnotVector::bezier(k, x[0], x[n - 1])?.into_knots()
    })
}

/// The interpolating spline of degree `k` through `(x_i, y_i)` for every column of `y`
/// (row-major, `len(x) × columns`): scipy's `make_interp_spline(x, y, k, t, bc_type)`.
///
/// Knots: `t` if given; otherwise the not-a-knot knots (`bc` [`InterpBc::NotAKnot`]), the
/// periodic ones ([`InterpBc::Periodic`]) or the abscissae with the ends repeated `k + 1`
/// times ([`InterpBc::Ends`]). `k = 1` without `t` gives the broken line (knots
/// `[x_0, x…, x_{-1}]`, coefficients `y`). The collocation rows (end derivatives, data,
/// end derivatives) form one band matrix, factorised once (LU with partial pivoting, as
/// LAPACK's `gbsv` in scipy) and solved for every column; periodic splines solve the cyclic
/// system of [`crate::interpolate_periodic`] for up to four columns at once.
///
/// # Errors
/// With scipy's words: "Shapes of x … and y … are incompatible", "Expect x to not have
/// duplicates", "Expect x to be a 1D strictly increasing sequence", "First and last
/// points does not match while periodic case expected" (`np.allclose` with `atol = 1e-15`),
/// "Too much info for k=1: bc_type can only be None", "For periodic case t is constructed
/// automatically", "Expect t to be a 1-D sorted array_like", "Got … knots, need at least
/// …", "Out of bounds w/ x = …", "Bad boundary conditions at …", "The number of derivatives
/// at boundaries does not match", "Colocation matrix is singular"
/// ([`ErrorKind::SingularSystem`]). Degree 0 gives scipy's knots `[x…, x_{-1}]` (the last
/// one twice) and the coefficients `y`. Degrees above [`MAX_DEGREE`] are [`ErrorKind::DegreeTooHigh`].
pub fn make_interp_spline(
    x: &[f64],
    y: &[f64],
    columns: usize,
    k: usize,
    t: Option<&[f64]>,
    bc: &InterpBc,
) -> Result<ColumnSpline> {
    check_data(x, y, columns)?;
    let n = x.len();
    if n == 0 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            "interpolation needs at least one point",
        ));
    }
    if *bc == InterpBc::Periodic {
        let scale = 1e-5;
        if let Some(j) = (0..columns).find(|&j| {
            let (a, b) = (y[j], y[(n - 1) * columns + j]);
            (a - b).abs() > 1e-15 + scale * b.abs()
        }) {
            return Err(invalid(format!(
                "First and last points does not match while periodic case expected (column {j}: {} and {})",
                y[j],
                y[(n - 1) * columns + j]
            ))
            .with_index(j));
        }
    }
    if let Some(i) = (1..n).find(|&i| x[i] == x[i - 1]) {
        return Err(Error::new(
            ErrorKind::UnsortedKnots,
            format!(
                "Expect x to not have duplicates (x[{i}] = {} repeats)",
                x[i]
            ),
        ));
    }
    if let Some(i) = (1..n).find(|&i| x[i] < x[i - 1]) {
        return Err(Error::new(
            ErrorKind::UnsortedKnots,
            format!(
                "Expect x to be a 1D strictly increasing sequence (x[{i}] = {} follows {})",
                x[i],
                x[i - 1]
            ),
        ));
    }
    if k > MAX_DEGREE {
        return Err(Error::new(
            ErrorKind::DegreeTooHigh,
            format!("degree {k} is above the supported maximum {MAX_DEGREE}"),
        ));
    }
    let ends_given = matches!(bc, InterpBc::Ends { .. });
    if k == 0 {
        if t.is_some() || ends_given {
            return Err(invalid(
                "Too much info for k=0: t and bc_type can only be None.",
            ));
        }
        // scipy's t = [x, x[-1]]: the last basis function is empty, the last span gives
        // y[-1] at x[-1] and beyond.
        let mut knots = x.to_vec();
        knots.push(x[n - 1]);
        return ColumnSpline::new(knots, y.to_vec(), 0, columns);
    }
    if k == 1 && t.is_none() {
        if ends_given {
            return Err(invalid("Too much info for k=1: bc_type can only be None."));
        }
        let mut knots = Vec::with_capacity(n + 2);
        knots.push(x[0]);
        knots.extend_from_slice(x);
        knots.push(x[n - 1]);
        return ColumnSpline::new(knots, y.to_vec(), 1, columns);
    }
    if *bc == InterpBc::Periodic && t.is_some() {
        return Err(invalid(
            "For periodic case t is constructed automatically and can not be passed manually",
        ));
    }
    let t: Vec<f64> = match (t, bc) {
        (Some(t), _) => t.to_vec(),
        (None, InterpBc::NotAKnot) => not_a_knot_knots(x, k)?,
        (None, InterpBc::Periodic) => ColumnSpline::periodic_knots(x, k),
        (None, InterpBc::Ends { .. }) => {
            let mut t = Vec::with_capacity(n + 2 * k);
            t.extend(std::iter::repeat_n(x[0], k));
            t.extend_from_slice(x);
            t.extend(std::iter::repeat_n(x[n - 1], k));
            t
        }
    };
    if let Some(v) = t.iter().find(|v| !v.is_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("Array must not contain infs or nans (knot {v})"),
        ));
    }
    if (1..t.len()).any(|i| t[i] < t[i - 1]) {
        return Err(Error::new(
            ErrorKind::UnsortedKnots,
            "Expect t to be a 1-D sorted array_like.",
        ));
    }
    if t.len() < n + k + 1 {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("Got {} knots, need at least {}.", t.len(), n + k + 1),
        )
        .with_counts(n + k + 1, t.len()));
    }
    if x[0] < t[k] || x[n - 1] > t[t.len() - k] {
        return Err(out_of_bounds(x));
    }
    if *bc == InterpBc::Periodic {
        return periodic(x, y, columns, t, k);
    }
    let (left, right): (&EndConditions, &EndConditions) = match bc {
        InterpBc::Ends { left, right } => (left, right),
        _ => (&[], &[]),
    };
    for (side, at) in [(left, x[0]), (right, x[n - 1])] {
        if side.iter().any(|(order, _)| *order > k) {
            return Err(invalid(format!("Bad boundary conditions at {at:?}.")).with_value(at));
        }
        if let Some((order, v)) = side.iter().find(|(_, v)| v.len() != columns) {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!(
                    "Bad boundary conditions at {at:?}: the derivative of order {order} has {} values for {columns} columns",
                    v.len()
                ),
            ));
        }
        if let Some(v) = side.iter().flat_map(|(_, v)| v).find(|v| !v.is_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("Array must not contain infs or nans (boundary value {v})"),
            ));
        }
    }
    let knots = knot_vector(&t, k)?;
    let nt = knots.num_basis();
    let (nleft, nright) = (left.len(), right.len());
    if nt != n + nleft + nright {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "The number of derivatives at boundaries does not match: expected {}, got {nleft}+{nright}",
                nt as i64 - n as i64
            ),
        ));
    }
    // Degrees 1 to 5: elimination without pivoting, rows of fixed width, all columns at once.
    if let Some(c) = collocation::solve(&knots, x, y, columns, left, right) {
        return ColumnSpline::from_knot_vector(knots, c, columns);
    }
    if nleft == 0 && nright == 0 {
        // Collocation only: a totally positive matrix when the data suit the knots, solved
        // without pivoting in one pass (the crate's interpolation kernel); anything else
        // goes through the pivoting band LU below, as scipy's gbsv.
        if let Ok(c) = by_chunks(columns, nt, y, &mut |chunk| {
            on_chunk!(chunk, |p| staircase(&knots, x, &p))
        }) {
            return ColumnSpline::from_knot_vector(knots, c, columns);
        }
    }
    // The rows: (order, point) conditions with their right-hand sides.
    let conditions = left
        .iter()
        .map(|(order, v)| (*order, x[0], v.as_slice()))
        .chain(
            x.iter()
                .enumerate()
                .map(|(i, &xi)| (0, xi, &y[i * columns..(i + 1) * columns])),
        )
        .chain(
            right
                .iter()
                .map(|(order, v)| (*order, x[n - 1], v.as_slice())),
        );
    let width = k + 1;
    let (a, b) = knots.domain();
    let mut firsts: Vec<usize> = Vec::with_capacity(nt);
    let mut entries: Vec<f64> = Vec::with_capacity(nt * width);
    let mut rhs = vec![0.0; nt * columns];
    let mut table = vec![0.0; width * width];
    let (mut kl, mut ku) = (0usize, 0usize);
    let mut hint = k;
    for (r, (order, at, values)) in conditions.enumerate() {
        let span = knots.span_in_domain_from(at.clamp(a, b), hint);
        hint = span;
        knots.basis_derivatives(span, at, order, &mut table[..(order + 1) * width]);
        let mut row = [0.0; MAX_ORDER];
        row[..width].copy_from_slice(&table[order * width..(order + 1) * width]);
        let first = span - k;
        for (c, v) in row[..width].iter().enumerate() {
            if *v != 0.0 {
                kl = kl.max(r.saturating_sub(first + c));
                ku = ku.max((first + c).saturating_sub(r));
            }
        }
        // Rows scaled to a largest entry of one (derivative rows on short intervals are
        // large, which would hide the collocation rows below the pivot threshold).
        let size = row[..width].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let scale = if size > 0.0 { 1.0 / size } else { 1.0 };
        for v in &mut row[..width] {
            *v *= scale;
        }
        firsts.push(first);
        entries.extend_from_slice(&row[..width]);
        for (o, &v) in rhs[r * columns..(r + 1) * columns].iter_mut().zip(values) {
            *o = v * scale;
        }
    }
    let mut lu = BandLu::zeros(nt, kl, ku, 0);
    for (r, (&first, row)) in firsts.iter().zip(entries.chunks_exact(width)).enumerate() {
        for (c, &v) in row.iter().enumerate() {
            if v != 0.0 {
                lu.add(r, first + c, v);
            }
        }
    }
    lu.factor().map_err(|e| {
        Error::new(
            ErrorKind::SingularSystem,
            format!("Colocation matrix is singular: {}", e.message()),
        )
    })?;
    let mut column = vec![0.0; nt];
    for j in 0..columns {
        for (i, v) in column.iter_mut().enumerate() {
            *v = rhs[i * columns + j];
        }
        lu.solve(&mut column);
        for (i, v) in column.iter().enumerate() {
            rhs[i * columns + j] = *v;
        }
    }
    ColumnSpline::from_knot_vector(knots, rhs, columns)
}

/// Collocation at `x` (as many points as basis functions) by elimination without pivoting,
/// or an error when a row has no diagonal entry or a negligible pivot.
fn staircase<P: spline_core::ControlPoint<f64>>(
    knots: &KnotVector<f64>,
    x: &[f64],
    points: &[P],
) -> Result<Vec<P>> {
    let k = knots.degree();
    let width = k + 1;
    let (a, b) = knots.domain();
    let mut system = Staircase::with_capacity(x.len(), width);
    let mut row = [0.0; MAX_ORDER];
    let mut span = k;
    for (i, (&u, &q)) in x.iter().zip(points).enumerate() {
        span = knots.span_in_domain_from(u.clamp(a, b), span);
        let first = span - k;
        if i < first || i > span {
            return Err(Error::new(
                ErrorKind::SchoenbergWhitney,
                "collocation row without a diagonal entry",
            ));
        }
        knots.basis_values(span, u, &mut row[..width]);
        system.push_row(first, &row[..width], q)?;
    }
    Ok(system.solve())
}

/// scipy's periodic interpolation on the knots `t` (`len(x) + 2k`): the cyclic collocation
/// of [`crate::interpolate_periodic`] at `x[..n−1]`.
fn periodic(x: &[f64], y: &[f64], columns: usize, t: Vec<f64>, k: usize) -> Result<ColumnSpline> {
    let n = x.len();
    if n < 2 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            "periodic interpolation needs at least 2 points",
        ));
    }
    let knots = KnotVector::new(k, t)?;
    let rows = knots.num_basis();
    let params = &x[..n - 1];
    let data = &y[..(n - 1) * columns];
    let c = by_chunks(columns, rows, data, &mut |chunk| {
        on_chunk!(chunk, |p| solve_periodic_collocation(&knots, params, &p))
    })?;
    ColumnSpline::from_knot_vector(knots, c, columns)
}

// After the macro `on_chunk!`, which it uses.
mod lsq;
pub use lsq::make_lsq_spline;

#[cfg(test)]
mod tests;
