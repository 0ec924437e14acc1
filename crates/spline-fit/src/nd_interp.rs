//! Interpolation on rectilinear grids in any number of dimensions: scipy's
//! `scipy.interpolate.make_ndbspl(points, values, k)` (scipy 1.17), solved exactly
//! dimension by dimension.

use crate::banded::BandLu;
use crate::params::check_strict;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::NdSpline;

/// The tensor-product spline through data on a rectilinear grid, as scipy's
/// `make_ndbspl(points, values, k)`: degree `k[e]` in dimension `e` on the not-a-knot knots
/// of scipy's `make_interp_spline` for the abscissae `points[e]`
/// ([`KnotVector::not_a_knot`]: for odd degrees the abscissae without the first and last
/// $(k + 1)/2$, for even degrees the midpoints without the first and last $k/2$, the ends
/// repeated $k + 1$ times), with
///
/// $$ s_j(x_{i_1}, …, x_{i_d}) = v_{i_1 … i_d, j} $$
///
/// for every grid point and each of the `columns` value columns. `values` holds
/// $m_1 \times \dots \times m_d \times$ `columns` numbers, row-major (scipy's `values` with
/// the trailing dimensions flattened); the coefficients have the same shape. The spline
/// extrapolates (scipy's default).
///
/// The collocation matrix is the Kronecker product of the `d` one-dimensional ones, so the
/// system is solved one dimension at a time: each banded collocation matrix is factorised
/// once (LU with partial pivoting) and applied to every grid line along its dimension, in
/// $O(N \sum_e k_e)$ for $N$ values. The solution is exact to rounding, where scipy's
/// default iterative solver (`gcrotmk`, `atol = 1e-6`) stops at its tolerance: scipy's
/// `make_ndbspl(..., solver=scipy.sparse.linalg.spsolve)` gives the same coefficients to
/// rounding.
///
/// ```
/// use spline_fit::make_ndbspl;
/// // f(x, y) = x + 2y on a 4 × 5 grid, cubic in both dimensions: reproduced exactly.
/// let x = [0.0, 1.0, 2.0, 3.0];
/// let y = [0.0, 0.5, 1.0, 2.0, 4.0];
/// let values: Vec<f64> = x.iter().flat_map(|a| y.iter().map(move |b| a + 2.0 * b)).collect();
/// let s = make_ndbspl(&[&x, &y], &values, &[3, 3], 1)?;
/// let v = s.eval(&[1.5, 3.0], &[])?;
/// assert!((v[0] - 7.5).abs() < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] without dimensions, for `columns == 0` or a degree 0
/// (scipy's not-a-knot knots of degree 0 do not interpolate); [`ErrorKind::InvalidLength`]
/// for a number of degrees other than `d` (with `(d, len(k))` as
/// [`spline_core::Error::counts`]); [`ErrorKind::TooFewPoints`] with `k[e]` abscissae or fewer in some
/// dimension; [`ErrorKind::NonFinite`] for non-finite abscissae or values;
/// [`ErrorKind::UnsortedKnots`] unless the abscissae of each dimension increase strictly
/// (scipy's docstring allows decreasing ones, which its `NdBSpline` then refuses);
/// [`ErrorKind::InvalidLength`] unless `values.len()` $= m_1 \cdots m_d \cdot$ `columns`;
/// [`ErrorKind::SingularSystem`] if a collocation matrix cannot be factorised. Every
/// message about one dimension names it.
pub fn make_ndbspl(
    points: &[&[f64]],
    values: &[f64],
    k: &[usize],
    columns: usize,
) -> Result<NdSpline> {
    let d = points.len();
    if d == 0 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "grid interpolation needs at least one dimension",
        )
        .with_counts(1, 0));
    }
    if k.len() != d {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!("len(points) = {d} != len(k) = {}", k.len()),
        )
        .with_counts(d, k.len()));
    }
    if columns == 0 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "grid interpolation needs at least one value column",
        )
        .with_counts(1, 0));
    }
    let mut knots = Vec::with_capacity(d);
    for (e, (&x, &ke)) in points.iter().zip(k).enumerate() {
        if ke == 0 {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "degree 0 in dimension {e}: grid interpolation needs degrees of at least 1"
                ),
            )
            .with_index(e)
            .with_value(0.0)
            .with_interval(1.0, f64::INFINITY));
        }
        if x.len() <= ke {
            return Err(Error::new(
                ErrorKind::TooFewPoints,
                format!(
                    "There are {} points in dimension {e}, but order {ke} requires at least {} points per dimension.",
                    x.len(),
                    ke + 1
                ),
            )
            .with_counts(ke + 1, x.len()));
        }
        check_strict(x).map_err(|err| err.context(format_args!("dimension {e}")))?;
        knots.push(
            KnotVector::not_a_knot(ke, x)
                .map_err(|err| err.context(format_args!("dimension {e}")))?,
        );
    }
    let total = points
        .iter()
        .try_fold(columns, |acc, x| acc.checked_mul(x.len()));
    if total != Some(values.len()) {
        let shape: Vec<String> = points.iter().map(|x| x.len().to_string()).collect();
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "the values of a ({}) grid with {columns} columns are {} numbers, got {}",
                shape.join(", "),
                total.map_or_else(|| "too many".to_string(), |t| t.to_string()),
                values.len()
            ),
        ));
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("value {i} is not finite ({})", values[i]),
        )
        .with_index(i));
    }
    let mut coefficients = values.to_vec();
    // Solve along each dimension: the array is (before, m_e, after) with `after` the
    // product of the later sizes and the columns.
    let mut after = columns;
    let mut afters = vec![0; d];
    for e in (0..d).rev() {
        afters[e] = after;
        after *= points[e].len();
    }
    let mut line = Vec::new();
    for e in 0..d {
        let lu = collocation(&knots[e], points[e])
            .map_err(|err| err.context(format_args!("dimension {e}")))?;
        let m = points[e].len();
        let after = afters[e];
        let block = m * after;
        line.clear();
        line.resize(block, 0.0);
        for chunk in coefficients.chunks_exact_mut(block) {
            // Transpose the block so that each grid line is contiguous, solve, transpose back.
            for (i, row) in chunk.chunks_exact(after).enumerate() {
                for (j, &v) in row.iter().enumerate() {
                    line[j * m + i] = v;
                }
            }
            for l in line.chunks_exact_mut(m) {
                lu.solve(l);
            }
            for (i, row) in chunk.chunks_exact_mut(after).enumerate() {
                for (j, v) in row.iter_mut().enumerate() {
                    *v = line[j * m + i];
                }
            }
        }
    }
    if let Some(i) = coefficients.iter().position(|v| !v.is_finite()) {
        return Err(Error::new(
            ErrorKind::SingularSystem,
            format!(
                "the grid interpolation overflowed at coefficient {i} (the collocation systems are too ill-conditioned)"
            ),
        ));
    }
    NdSpline::from_knot_vectors(knots, coefficients, columns, true)
}

/// The factorised collocation matrix $A_{ij} = B_j(x_i)$ of one dimension.
fn collocation(knots: &KnotVector<f64>, x: &[f64]) -> Result<BandLu<f64>> {
    let p = knots.degree();
    let n = x.len();
    let spans: Vec<usize> = x.iter().map(|&u| knots.span_in_domain(u)).collect();
    let (mut kl, mut ku) = (0, 0);
    for (i, &s) in spans.iter().enumerate() {
        kl = kl.max(i.saturating_sub(s - p));
        ku = ku.max(s.saturating_sub(i));
    }
    let mut lu = BandLu::zeros(n, kl, ku, 0);
    let mut basis = vec![0.0; p + 1];
    for (i, (&u, &s)) in x.iter().zip(&spans).enumerate() {
        knots.basis_values(s, u, &mut basis);
        for (r, &b) in basis.iter().enumerate() {
            if b != 0.0 {
                lu.add(i, s - p + r, b);
            }
        }
    }
    lu.factor()?;
    Ok(lu)
}

#[cfg(test)]
mod tests;
