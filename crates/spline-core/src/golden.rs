//! Golden-section search for the largest value of a function on an interval.

use crate::{Result, Scalar, cast};

/// Golden-section search for the maximum of `f` on `[lo, hi]` (`f` unimodal there): at most
/// 60 steps, each shrinking the bracket by the golden ratio, stopping early once the bracket
/// is no wider than `tolerance · (1 + |lo|)` (`0`: only when it has collapsed). Returns the
/// last two interior points as `(f(x), x)`, the lower one first; the caller takes the
/// larger value (and compares it with what it sampled before).
///
/// ```
/// let peak = |x: f64| Ok(-(x - 0.3) * (x - 0.3));
/// let [(f1, x1), (f2, x2)] = spline_core::golden_section_max(peak, (0.0, 1.0), f64::EPSILON)?;
/// let x = if f2 > f1 { x2 } else { x1 };
/// assert!((x - 0.3).abs() < 1e-7);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// The first error of `f`.
pub fn golden_section_max<T: Scalar>(
    mut f: impl FnMut(T) -> Result<T>,
    (lo, hi): (T, T),
    tolerance: T,
) -> Result<[(T, T); 2]> {
    let ratio: T = cast(0.618_033_988_749_894_9);
    let (mut lo, mut hi) = (lo, hi);
    let mut x1 = hi - (hi - lo) * ratio;
    let mut x2 = lo + (hi - lo) * ratio;
    let (mut f1, mut f2) = (f(x1)?, f(x2)?);
    for _ in 0..60 {
        if !(hi - lo > tolerance * (T::one() + lo.abs())) {
            break;
        }
        if f1 > f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - (hi - lo) * ratio;
            f1 = f(x1)?;
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + (hi - lo) * ratio;
            f2 = f(x2)?;
        }
    }
    Ok([(f1, x1), (f2, x2)])
}
