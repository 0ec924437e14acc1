//! The normal equations of a large curve fit assembled in chunks on every core (`parallel`
//! feature): each chunk of the data adds its rows into its own band and right-hand side,
//! and the parts are summed in chunk order. The Schoenberg–Whitney check is a greedy scan in
//! data order; it runs alongside the chunks (without the sums) on one of the threads.

use super::assemble::normal_dispatch;
use rayon::prelude::*;
use spline_core::{ControlPoint, KnotVector, Scalar};

/// Points per chunk at least (smaller chunks cost more in partial bands than they gain).
const MIN_CHUNK: usize = 4096;

/// Adds the normal equations of the data to `band` and `rhs` (degree at most 5): as the
/// sequential kernel, the sums in another order.
pub(super) fn assemble<T: Scalar, P: ControlPoint<T>>(
    knots: &KnotVector<T>,
    params: &[T],
    points: &[P],
    weights: Option<&[T]>,
    check: bool,
    band: &mut [T],
    rhs: &mut [P],
) -> std::result::Result<(), usize> {
    let chunk = params
        .len()
        .div_ceil(4 * rayon::current_num_threads())
        .max(MIN_CHUNK);
    let (band_len, rhs_len) = (band.len(), rhs.len());
    let (checked, parts) = rayon::join(
        || {
            if check {
                // The check alone: no sums, the buffers untouched.
                normal_dispatch::<T, P, false>(
                    knots,
                    params,
                    points,
                    weights,
                    true,
                    &mut [],
                    &mut [],
                )
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
                    normal_dispatch::<T, P, true>(
                        knots,
                        ps,
                        qs,
                        ws,
                        false,
                        &mut part_band,
                        &mut part_rhs,
                    );
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
