//! Basis functions of one direction of a surface on the stack: the values by the fixed-size
//! kernels, the derivatives in a table sized for the degree.

use spline_core::{KnotVector, MAX_ORDER, Scalar};

/// The `p + 1` basis functions non-zero in `span` at `t` into `out[..p + 1]`: the
/// fixed-size kernels of [`KnotVector::basis_values_fixed`] for degrees up to 5, the general
/// routine above.
#[inline]
pub(super) fn basis_into<T: Scalar>(
    knots: &KnotVector<T>,
    span: usize,
    t: T,
    out: &mut [T; MAX_ORDER],
) {
    #[inline(always)]
    fn fixed<T: Scalar, const N: usize>(
        knots: &KnotVector<T>,
        span: usize,
        t: T,
        out: &mut [T; MAX_ORDER],
    ) {
        out[..N].copy_from_slice(&knots.basis_values_fixed::<N>(span, t));
    }
    match knots.degree() {
        1 => fixed::<T, 2>(knots, span, t, out),
        2 => fixed::<T, 3>(knots, span, t, out),
        3 => fixed::<T, 4>(knots, span, t, out),
        4 => fixed::<T, 5>(knots, span, t, out),
        5 => fixed::<T, 6>(knots, span, t, out),
        _ => knots.basis_values(span, t, out),
    }
}

/// Working memory for basis-function derivatives, on the stack: orders above the degree
/// are zero and never stored. `LEN` entries: [`SMALL_TABLE`] for degrees up to 5 (zeroing
/// the full `MAX_ORDER²` table would cost more than the derivatives), `MAX_ORDER²` above.
pub(super) struct BasisTable<T, const LEN: usize> {
    stack: [T; LEN],
}

/// Table length for degrees up to 5: `(p + 1)²` with `p = 5`.
pub(super) const SMALL_TABLE: usize = 36;

/// The largest degree whose tables fit in [`SMALL_TABLE`].
pub(super) const SMALL_DEGREE: usize = 5;

impl<T: Scalar, const LEN: usize> BasisTable<T, LEN> {
    #[inline]
    pub(super) fn new() -> Self {
        Self {
            stack: [T::zero(); LEN],
        }
    }

    /// The derivatives of orders `0 … min(order, p)`, rows of `p + 1`.
    #[inline]
    pub(super) fn fill(&mut self, knots: &KnotVector<T>, span: usize, t: T, order: usize) -> &[T] {
        let order = order.min(knots.degree());
        let table = &mut self.stack[..(order + 1) * knots.order()];
        knots.basis_derivatives(span, t, order, table);
        table
    }
}
