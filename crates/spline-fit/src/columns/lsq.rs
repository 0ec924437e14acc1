//! scipy's `make_lsq_spline` on many value columns, through the crate's least squares.

use super::{Chunk, Solved, by_chunks, check_data, knot_vector, out_of_bounds};
use crate::lsq::{LeastSquares, LsqMethod};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::ColumnSpline;

/// The least-squares spline of degree `k` on knots `t` for every column of `y` (row-major,
/// `len(x) × columns`): scipy's `make_lsq_spline(x, y, t, k, w, method)`, minimising
/// $\sum_i w_i^2 (s_j(x_i) - y_{ij})^2$ for each column `j` (weights multiply residuals).
///
/// Runs the crate's least-squares path ([`LeastSquares`]: Givens QR of the banded design
/// matrix for [`LsqMethod::Qr`], scipy's default `'qr'`; banded normal equations and
/// Cholesky for [`LsqMethod::NormalEquations`], scipy's `'norm-eq'`) with up to four
/// columns as the coordinates of one point type, so one factorisation serves four columns.
///
/// # Errors
/// With scipy's words: "Need more x points" (fewer than `k + 1`), "Expect t to be a 1D
/// strictly increasing sequence" (decreasing knots), "Shapes of x … and y … are
/// incompatible", "Out of bounds w/ x = …", "Shapes of x … and w … are incompatible",
/// "Expect x to be a 1D strictly increasing sequence" (norm-eq) or "… non-decreasing
/// sequence" (qr), "Schoenberg-Whitney condition is violated" ([`ErrorKind::SchoenbergWhitney`],
/// when a basis function has no data of its own); [`ErrorKind::InvalidWeight`] for weights
/// that are not positive and finite; the errors of [`ColumnSpline::new`] for the knots.
pub fn make_lsq_spline(
    x: &[f64],
    y: &[f64],
    columns: usize,
    t: &[f64],
    k: usize,
    w: Option<&[f64]>,
    method: LsqMethod,
) -> Result<ColumnSpline> {
    if x.len() < k + 1 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!("Need more x points: {} for degree {k}", x.len()),
        ));
    }
    if (1..t.len()).any(|i| t[i] < t[i - 1]) {
        return Err(Error::new(
            ErrorKind::UnsortedKnots,
            "Expect t to be a 1D strictly increasing sequence.",
        ));
    }
    check_data(x, y, columns)?;
    let knots = knot_vector(t, k)?;
    if k > 0 && x.iter().any(|&v| v < t[k] || v > t[t.len() - k]) {
        return Err(out_of_bounds(x));
    }
    if let Some(w) = w
        && w.len() != x.len()
    {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "Shapes of x ({},) and w ({},) are incompatible",
                x.len(),
                w.len()
            ),
        ));
    }
    match method {
        LsqMethod::NormalEquations => {
            if (1..x.len()).any(|i| x[i] <= x[i - 1]) {
                return Err(Error::new(
                    ErrorKind::UnsortedKnots,
                    "Expect x to be a 1D strictly increasing sequence.",
                ));
            }
        }
        LsqMethod::Qr => {
            if (1..x.len()).any(|i| x[i] < x[i - 1]) {
                return Err(Error::new(
                    ErrorKind::UnsortedKnots,
                    "Expect x to be a 1D non-decreasing sequence.",
                ));
            }
        }
    }
    let n = knots.num_basis();
    let c = by_chunks(columns, n, y, &mut |chunk| {
        on_chunk!(chunk, |p| {
            let mut problem = LeastSquares::new(&p, x, knots.clone()).method(method);
            if let Some(w) = w {
                problem = problem.weights(w);
            }
            problem.control_points().map_err(|e| {
                if e.kind() == ErrorKind::SchoenbergWhitney {
                    Error::new(
                        ErrorKind::SchoenbergWhitney,
                        format!("Schoenberg-Whitney condition is violated: {}", e.message()),
                    )
                } else {
                    e
                }
            })
        })
    })?;
    ColumnSpline::from_knot_vector(knots, c, columns)
}
