//! The edge of the stretch where a condition holds, found from inside.

use crate::{Result, Scalar, cast};

/// From `start = (x₀, state)`, where `on` holds, towards `limit`: the last parameter at which
/// it still holds, by steps that double from `10⁻⁶` of the way, then bisection between the
/// last parameter on and the first one off down to rounding. `on(x, good)` gives the state
/// at `x` (from the last good point `good`: a foot point carried along, say) or `None`
/// where the condition fails. Returns the last good point and the first parameter the steps
/// found off (`None` when the condition holds up to `limit`). The march of an overlap
/// along a curve, to where the other curve or the surface leaves it.
///
/// ```
/// use spline_core::march_to_boundary;
/// // x² < 2 from 1 towards 3: the edge is √2.
/// let ((edge, ()), off) = march_to_boundary((1.0f64, ()), 3.0, |x, _| {
///     Ok((x * x < 2.0).then_some(()))
/// })?;
/// assert!((edge - 2f64.sqrt()).abs() < 1e-15);
/// assert!(off.is_some_and(|x| x > 2f64.sqrt()));
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// The errors of `on`.
pub fn march_to_boundary<T: Scalar, S: Copy>(
    start: (T, S),
    limit: T,
    on: impl Fn(T, (T, S)) -> Result<Option<S>>,
) -> Result<((T, S), Option<T>)> {
    let eps = T::default_epsilon();
    let mut good = start;
    let mut off = None;
    let mut step = (limit - start.0) * cast(1e-6);
    while good.0 != limit {
        let next = if step.abs() >= (limit - good.0).abs() {
            limit
        } else {
            good.0 + step
        };
        match on(next, good)? {
            Some(state) => good = (next, state),
            None => {
                off = Some(next);
                break;
            }
        }
        step *= cast(2.0);
    }
    if let Some(mut bad) = off {
        for _ in 0..80 {
            let m = (good.0 + bad) * cast(0.5);
            if !((m - good.0).abs() > eps * (T::one() + m.abs()))
                || !((bad - m).abs() > eps * (T::one() + m.abs()))
            {
                break;
            }
            match on(m, good)? {
                Some(state) => good = (m, state),
                None => bad = m,
            }
        }
    }
    Ok((good, off))
}
