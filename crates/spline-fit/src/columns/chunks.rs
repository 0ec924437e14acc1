//! What the column-wise fits share: the checks of the data in scipy's words, and the
//! columns taken four at a time as the coordinates of points (one factorisation a chunk).

use nalgebra::SVector;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::ColumnSpline;

/// Applies a function generic over the point type to a chunk.
macro_rules! on_chunk {
    ($chunk:expr, |$p:ident| $body:expr) => {
        match $chunk {
            Chunk::One($p) => $body.map(Solved::One),
            Chunk::Two($p) => $body.map(Solved::Two),
            Chunk::Three($p) => $body.map(Solved::Three),
            Chunk::Four($p) => $body.map(Solved::Four),
        }
    };
}

pub(super) fn invalid(message: impl Into<String>) -> Error {
    Error::new(ErrorKind::InvalidArgument, message)
}

/// Checks `x` (finite, strictly increasing, as scipy words it) and `y` (`len(x) × columns`,
/// finite).
pub(super) fn check_data(x: &[f64], y: &[f64], columns: usize) -> Result<()> {
    if columns == 0 {
        return Err(invalid("the data need at least one column").with_counts(1, 0));
    }
    if Some(y.len()) != x.len().checked_mul(columns) {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "Shapes of x ({},) and y ({} values of {columns} columns) are incompatible",
                x.len(),
                y.len()
            ),
        ));
    }
    if let Some(v) = x.iter().chain(y).find(|v| !v.is_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("Array must not contain infs or nans (found {v})"),
        ));
    }
    Ok(())
}

/// The knots checked as [`ColumnSpline::new`] checks them (scipy's words).
pub(super) fn knot_vector(t: &[f64], k: usize) -> Result<KnotVector<f64>> {
    ColumnSpline::check_knots(t.to_vec(), k)
}

/// scipy's error for data outside the knots.
pub(super) fn out_of_bounds(x: &[f64]) -> Error {
    Error::new(
        ErrorKind::OutOfDomain,
        format!(
            "Out of bounds w/ x = [{}, …, {}]: the data leave the knots' base interval",
            x[0],
            x[x.len() - 1]
        ),
    )
}

/// Columns `j0 … j0 + D − 1` of `y` as points.
pub(super) fn chunk<const D: usize>(y: &[f64], columns: usize, j0: usize) -> Vec<SVector<f64, D>> {
    y.chunks_exact(columns)
        .map(|row| SVector::<f64, D>::from_fn(|d, _| row[j0 + d]))
        .collect()
}

/// Writes points back into columns `j0 …` of the row-major `out`.
pub(super) fn unchunk<const D: usize>(
    points: &[SVector<f64, D>],
    out: &mut [f64],
    columns: usize,
    j0: usize,
) {
    for (row, p) in out.chunks_exact_mut(columns).zip(points) {
        row[j0..j0 + D].copy_from_slice(p.as_slice());
    }
}

/// Runs `solve` on the columns in chunks of up to four (one factorisation per chunk, the
/// columns as the coordinates of points) and assembles the `rows × columns` result.
pub(super) fn by_chunks(
    columns: usize,
    rows: usize,
    y: &[f64],
    solve: &mut dyn FnMut(Chunk) -> Result<Solved>,
) -> Result<Vec<f64>> {
    let mut out = vec![0.0; rows * columns];
    let mut j0 = 0;
    while j0 < columns {
        let width = (columns - j0).min(4);
        let solved = match width {
            1 => solve(Chunk::One(chunk::<1>(y, columns, j0)))?,
            2 => solve(Chunk::Two(chunk::<2>(y, columns, j0)))?,
            3 => solve(Chunk::Three(chunk::<3>(y, columns, j0)))?,
            _ => solve(Chunk::Four(chunk::<4>(y, columns, j0)))?,
        };
        match solved {
            Solved::One(p) => unchunk(&p, &mut out, columns, j0),
            Solved::Two(p) => unchunk(&p, &mut out, columns, j0),
            Solved::Three(p) => unchunk(&p, &mut out, columns, j0),
            Solved::Four(p) => unchunk(&p, &mut out, columns, j0),
        }
        j0 += width;
    }
    Ok(out)
}

/// Up to four columns of data as points.
pub(super) enum Chunk {
    One(Vec<SVector<f64, 1>>),
    Two(Vec<SVector<f64, 2>>),
    Three(Vec<SVector<f64, 3>>),
    Four(Vec<SVector<f64, 4>>),
}

/// The coefficients of a [`Chunk`].
pub(super) enum Solved {
    One(Vec<SVector<f64, 1>>),
    Two(Vec<SVector<f64, 2>>),
    Three(Vec<SVector<f64, 3>>),
    Four(Vec<SVector<f64, 4>>),
}
