//! Rational derivatives of curves and surfaces from the homogeneous ones (The NURBS Book
//! A4.2 and A4.4).

use crate::homogeneous::Homogeneous;
use nalgebra::SVector;
use spline_core::{Error, ErrorKind, Result, Scalar, from_count};

/// Rational derivatives of a curve from the homogeneous ones (The NURBS Book A4.2):
/// $C^{(k)} = \big(A^{(k)} - \sum_{i=1}^{k} \binom{k}{i} w^{(i)} C^{(k-i)}\big) / w$.
///
/// `hom` holds the homogeneous derivatives of orders `0 … hom.len() − 1`; those above are
/// zero (orders above the degree), so the sums stop there and order `k` costs `O(p)`.
///
/// # Errors
/// [`ErrorKind::NonFinite`] when a derivative leaves the range of the scalar type (rational
/// derivatives of order `k` grow like `k!`).
pub(crate) fn rational_curve_derivatives<T: Scalar, const D: usize>(
    hom: &[Homogeneous<T, D>],
    out: &mut [SVector<T, D>],
) -> Result<()> {
    let w0 = hom[0].weight;
    let top = hom.len() - 1;
    for k in 0..out.len() {
        let mut v = if k <= top {
            hom[k].point
        } else {
            SVector::zeros()
        };
        let mut binom = T::one();
        for i in 1..=k.min(top) {
            // C(k, i) from C(k, i − 1).
            binom = binom * from_count::<T>(k - i + 1) / from_count::<T>(i);
            v -= out[k - i] * (binom * hom[i].weight);
        }
        out[k] = v / w0;
        if !out[k].iter().all(nalgebra::ComplexField::is_finite) {
            return Err(derivative_overflow(k));
        }
    }
    Ok(())
}

pub(super) fn derivative_overflow(order: usize) -> Error {
    Error::new(
        ErrorKind::NonFinite,
        format!(
            "the rational derivative of order {order} is too large for floating point (rational derivatives grow like order!)"
        ),
    )
}

/// The homogeneous partial derivatives that the rational ones of a surface of degrees
/// `(p, q)` on the square `0 ≤ k, l ≤ order` need, once `out_len` is checked to be
/// `(order + 1)²`: the orders up to `top = min(order, max(p, q))` (those above vanish) and
/// their number `(top + 1)²`.
///
/// # Errors
/// The errors of [`crate::bspline::square_len`]; [`ErrorKind::InvalidLength`] unless
/// `out_len = (order + 1)²`.
pub(super) fn homogeneous_square(
    order: usize,
    (p, q): (usize, usize),
    out_len: usize,
) -> Result<(usize, usize)> {
    crate::bspline::check_same_len(crate::bspline::square_len(order)?, out_len)?;
    let top = order.min(p.max(q));
    Ok((top, (top + 1) * (top + 1)))
}

/// Rational partial derivatives of a surface on the square `0 ≤ k, l ≤ order` from the
/// homogeneous ones (The NURBS Book A4.4). `hom` holds the homogeneous derivatives on the
/// square `0 ≤ i, j ≤ top` (row-major, rows of `top + 1`; those above are zero); `out` is
/// row-major with rows of `order + 1`.
///
/// # Errors
/// [`ErrorKind::NonFinite`] when a derivative leaves the range of the scalar type.
pub(super) fn rational_surface_derivatives<T: Scalar, const D: usize>(
    hom: &[Homogeneous<T, D>],
    top: usize,
    order: usize,
    out: &mut [SVector<T, D>],
) -> Result<()> {
    let w = order + 1;
    let hw = top + 1;
    let weight = |i: usize, j: usize| hom[i * hw + j].weight;
    let w00 = weight(0, 0);
    for k in 0..=order {
        for l in 0..=order {
            let mut v = if k <= top && l <= top {
                hom[k * hw + l].point
            } else {
                SVector::zeros()
            };
            let mut blj = T::one();
            for j in 1..=l.min(top) {
                blj = blj * from_count::<T>(l - j + 1) / from_count::<T>(j);
                v -= out[k * w + l - j] * (blj * weight(0, j));
            }
            let mut bki = T::one();
            for i in 1..=k.min(top) {
                bki = bki * from_count::<T>(k - i + 1) / from_count::<T>(i);
                v -= out[(k - i) * w + l] * (bki * weight(i, 0));
                let mut mixed = SVector::<T, D>::zeros();
                let mut blj = T::one();
                for j in 1..=l.min(top) {
                    blj = blj * from_count::<T>(l - j + 1) / from_count::<T>(j);
                    mixed += out[(k - i) * w + l - j] * (blj * weight(i, j));
                }
                v -= mixed * bki;
            }
            out[k * w + l] = v / w00;
            if !out[k * w + l].iter().all(nalgebra::ComplexField::is_finite) {
                return Err(derivative_overflow(k + l));
            }
        }
    }
    Ok(())
}
