//! Basis functions for the fitting loops.

use spline_core::{KnotVector, Scalar};

/// Small degrees use stack arrays of this size.
const SMALL: usize = 8;

/// Evaluates the `p + 1` basis functions non-zero in a span (The NURBS Book A2.2) with the
/// reciprocals of the knot differences of the span computed once and kept while the span
/// does not change: the fitting loops visit spans in order, so for least squares the
/// per-point cost drops to a few multiplications, and for interpolation the divisions are
/// independent of each other (pipelined) instead of chained.
#[derive(Clone, Debug)]
pub(crate) struct BasisEval<T> {
    span: usize,
    /// `inverse[j (j − 1)/2 + r]` = $1/(u_{s+r+1} - u_{s+1-j+r})$ for `j = 1 … p`, `r < j`.
    inverse: [T; SMALL * (SMALL - 1) / 2],
}

impl<T: Scalar> BasisEval<T> {
    pub(crate) fn new() -> Self {
        Self {
            span: usize::MAX,
            inverse: [T::zero(); SMALL * (SMALL - 1) / 2],
        }
    }

    /// The basis functions non-zero in `span` at `u` into `out[..p + 1]`.
    #[inline]
    pub(crate) fn eval(&mut self, knots: &KnotVector<T>, span: usize, u: T, out: &mut [T]) {
        let p = knots.degree();
        if p >= SMALL {
            knots.basis_values(span, u, out);
            return;
        }
        let k = knots.knots();
        if span != self.span {
            if span == self.span.wrapping_add(1) {
                // Moving one span right: row j shifts by one, one new reciprocal per row.
                let mut idx = 0;
                for j in 1..=p {
                    self.inverse.copy_within(idx + 1..idx + j, idx);
                    self.inverse[idx + j - 1] = T::one() / (k[span + j] - k[span]);
                    idx += j;
                }
            } else {
                let mut idx = 0;
                for j in 1..=p {
                    for r in 0..j {
                        self.inverse[idx] = T::one() / (k[span + r + 1] - k[span + 1 + r - j]);
                        idx += 1;
                    }
                }
            }
            self.span = span;
        }
        let mut left = [T::zero(); SMALL];
        let mut right = [T::zero(); SMALL];
        out[0] = T::one();
        let mut idx = 0;
        for j in 1..=p {
            left[j] = u - k[span + 1 - j];
            right[j] = k[span + j] - u;
            let mut saved = T::zero();
            for r in 0..j {
                let temp = out[r] * self.inverse[idx + r];
                out[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            out[j] = saved;
            idx += j;
        }
    }
}
