//! The normal equations of a large curve fit assembled in chunks on every core (`parallel`
//! feature): each chunk of the data adds its rows into its own band and right-hand side,
//! and the parts are summed in chunk order. The Schoenberg–Whitney check is a greedy scan in
//! data order; it runs alongside the chunks (without the sums) on one of the threads.
//!
//! The kernels come from the caller (`assemble`'s per-degree dispatch, the one-pass square
//! sum): this module knows how to split and sum, not what a chunk computes.

use super::Rows;
use rayon::prelude::*;
use spline_core::{ControlPoint, KnotVector, Scalar};

/// Points per chunk at least (smaller chunks cost more in partial bands than they gain).
const MIN_CHUNK: usize = 4096;

/// Items per chunk for `len` items: about four chunks per thread, at least [`MIN_CHUNK`].
pub(crate) fn chunk_len(len: usize) -> usize {
    len.div_ceil(4 * rayon::current_num_threads())
        .max(MIN_CHUNK)
}

/// Whether every point is finite and the parameters are non-decreasing inside the domain of
/// `knots` (one comparison per entry, in chunks on every core; the chunks' boundaries after).
pub(super) fn data_valid<T: Scalar, P: ControlPoint<T>>(
    knots: &KnotVector<T>,
    params: &[T],
    points: &[P],
) -> bool {
    let (a, b) = knots.domain();
    let chunk = chunk_len(params.len());
    // `a ≤ u ≤ b` fails for NaN too.
    params.len() == points.len()
        && params
            .par_chunks(chunk)
            .zip(points.par_chunks(chunk))
            .all(|(ps, qs)| {
                qs.iter().all(ControlPoint::all_finite)
                    && ps.iter().all(|&u| u >= a && u <= b)
                    && ps.is_sorted_by(|x, y| x <= y)
            })
        && (chunk..params.len())
            .step_by(chunk)
            .all(|i| params[i - 1] <= params[i])
}

/// $\sum_k w_k^2 |q_k|^2$ in chunks on every core, the partial sums added in chunk order
/// (the same value for the same number of threads).
pub(super) fn weighted_square_sum<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    weights: Option<&[T]>,
    chunk_sum: impl Fn(&[P], Option<&[T]>) -> T + Sync,
) -> T {
    let chunk = chunk_len(points.len());
    let parts: Vec<T> = points
        .par_chunks(chunk)
        .enumerate()
        .map(|(c, qs)| {
            let ws = weights.map(|w| &w[c * chunk..c * chunk + qs.len()]);
            chunk_sum(qs, ws)
        })
        .collect();
    parts.into_iter().fold(T::zero(), |s, part| s + part)
}

/// The sequential assembly kernel the chunks run: `(rows, check, band, rhs)` as
/// `assemble`'s per-degree dispatch takes them, `None` for an unsupported degree. `ACC =
/// false` of the dispatch is the check alone.
pub(super) type Kernel<T, P> =
    fn(Rows<'_, T, P>, bool, &mut [T], &mut [P]) -> Option<std::result::Result<(), usize>>;

/// Adds the normal equations of the data to `band` and `rhs` (degree at most 5): as the
/// sequential kernel `sums`, the sums in another order; `check_only` runs the
/// Schoenberg–Whitney check beside them.
pub(super) fn assemble<T: Scalar, P: ControlPoint<T>>(
    (sums, check_only): (Kernel<T, P>, Kernel<T, P>),
    rows: Rows<'_, T, P>,
    check: bool,
    band: &mut [T],
    rhs: &mut [P],
) -> std::result::Result<(), usize> {
    let Rows {
        params,
        points,
        weights,
        ..
    } = rows;
    let chunk = chunk_len(params.len());
    let (band_len, rhs_len) = (band.len(), rhs.len());
    let (checked, parts) = rayon::join(
        || {
            if check {
                // The check alone: no sums, the buffers untouched.
                check_only(rows, true, &mut [], &mut [])
            } else {
                Some(Ok(()))
            }
        },
        || {
            params
                .par_chunks(chunk)
                .zip(points.par_chunks(chunk))
                .enumerate()
                .map(|(c, (ps, qs))| {
                    let ws = weights.map(|w| &w[c * chunk..c * chunk + ps.len()]);
                    let mut part_band = vec![T::zero(); band_len];
                    let mut part_rhs = vec![P::origin(); rhs_len];
                    let part = Rows {
                        params: ps,
                        points: qs,
                        weights: ws,
                        ..rows
                    };
                    sums(part, false, &mut part_band, &mut part_rhs);
                    (part_band, part_rhs)
                })
                .collect::<Vec<_>>()
        },
    );
    if let Some(Err(i)) = checked {
        return Err(i);
    }
    for (part_band, part_rhs) in parts {
        for (b, v) in band.iter_mut().zip(part_band) {
            *b += v;
        }
        for (r, v) in rhs.iter_mut().zip(part_rhs) {
            *r += v;
        }
    }
    Ok(())
}
