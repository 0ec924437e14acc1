//! The normal equations of tensor-product least squares on scattered data, with the
//! thin-plate penalty: what [`crate::approximate_surface_scattered`] solves.

// Index loops mirror the formulas (basis index ↔ control-point index).
#![allow(clippy::needless_range_loop)]

use crate::banded::BandCholesky;
use spline_core::{ControlPoint, KnotVector, MAX_ORDER, Scalar, cast, gauss_legendre};

/// The banded normal equations (lower triangle, half-bandwidth `p n_v + q`, row-major
/// unknowns `i n_v + j`) and right-hand side of
///
/// $$ \sum_k \lVert S(u_k, v_k) - Q_k \rVert^2
///    + \lambda \iint \lVert S_{uu} \rVert^2 + 2 \lVert S_{uv} \rVert^2 + \lVert S_{vv} \rVert^2 $$
///
/// over the control points of the surface on `knots_u × knots_v`; the thin-plate term by
/// exact Gauss–Legendre quadrature on each non-empty cell. The caller has checked the data
/// (finite, parameters inside the domains, `λ ≥ 0`).
pub(crate) fn scattered_normal_equations<T: Scalar, P: ControlPoint<T>>(
    knots_u: &KnotVector<T>,
    knots_v: &KnotVector<T>,
    params: &[(T, T)],
    points: &[P],
    smoothing: T,
) -> (BandCholesky<T>, Vec<P>) {
    let (p, q) = (knots_u.degree(), knots_v.degree());
    let (nu, nv) = (knots_u.num_basis(), knots_v.num_basis());
    let bw = p * nv + q;
    let mut matrix = BandCholesky::zeros(nu * nv, bw);
    let mut rhs = vec![P::origin(); nu * nv];
    assemble_points(knots_u, knots_v, params, points, &mut matrix, &mut rhs);
    let mut idx = Vec::with_capacity((p + 1) * (q + 1));
    let mut val = Vec::with_capacity((p + 1) * (q + 1));
    let mut bu = [T::zero(); 3 * MAX_ORDER];
    let mut bv = [T::zero(); 3 * MAX_ORDER];
    if smoothing > T::zero() {
        let count = p.max(q) + 1;
        let rule = gauss_legendre::<T>(count);
        let half: T = cast(0.5);
        let two: T = cast(2.0);
        let (ku, kv) = (knots_u.knots(), knots_v.knots());
        for su in p..nu {
            if !(ku[su] < ku[su + 1]) {
                continue;
            }
            let (mu, ru) = ((ku[su] + ku[su + 1]) * half, (ku[su + 1] - ku[su]) * half);
            for sv in q..nv {
                if !(kv[sv] < kv[sv + 1]) {
                    continue;
                }
                let (mv, rv) = ((kv[sv] + kv[sv + 1]) * half, (kv[sv + 1] - kv[sv]) * half);
                for &(x, wx) in &rule {
                    let u = mu + ru * x;
                    knots_u.basis_derivatives(su, u, 2, &mut bu[..3 * (p + 1)]);
                    for &(y, wy) in &rule {
                        let v = mv + rv * y;
                        knots_v.basis_derivatives(sv, v, 2, &mut bv[..3 * (q + 1)]);
                        let w = smoothing * wx * wy * ru * rv;
                        for (du, dv, factor) in [(2, 0, T::one()), (1, 1, two), (0, 2, T::one())] {
                            tensor_row(
                                (su - p, sv - q, nv),
                                (
                                    &bu[du * (p + 1)..=du * (p + 1) + p],
                                    &bv[dv * (q + 1)..=dv * (q + 1) + q],
                                ),
                                &mut idx,
                                &mut val,
                            );
                            add_row(&mut matrix, &mut rhs, &idx, &val, P::origin(), w * factor);
                        }
                    }
                }
            }
        }
    }
    debug_assert_eq!(matrix.bandwidth(), bw);
    (matrix, rhs)
}

/// Adds `w2 · a aᵀ` (lower triangle) and `w2 · target · a` for the sparse row `a` (columns
/// `idx`, values `val`) to the normal equations.
fn add_row<T: Scalar, P: ControlPoint<T>>(
    matrix: &mut BandCholesky<T>,
    rhs: &mut [P],
    idx: &[usize],
    val: &[T],
    target: P,
    w2: T,
) {
    for (a, (&ia, &va)) in idx.iter().zip(val).enumerate() {
        let s = va * w2;
        rhs[ia] += target * s;
        for (&ib, &vb) in idx[..=a].iter().zip(&val[..=a]) {
            let (hi, lo) = if ia >= ib { (ia, ib) } else { (ib, ia) };
            matrix.add_lower(hi, lo, s * vb);
        }
    }
}

/// Adds the rows of the data points to the normal equations, point after point.
fn add_points<T: Scalar, P: ControlPoint<T>>(
    knots_u: &KnotVector<T>,
    knots_v: &KnotVector<T>,
    params: &[(T, T)],
    points: &[P],
    matrix: &mut BandCholesky<T>,
    rhs: &mut [P],
) {
    let (p, q) = (knots_u.degree(), knots_v.degree());
    let nv = knots_v.num_basis();
    let mut idx = Vec::with_capacity((p + 1) * (q + 1));
    let mut val = Vec::with_capacity((p + 1) * (q + 1));
    let mut bu = [T::zero(); MAX_ORDER];
    let mut bv = [T::zero(); MAX_ORDER];
    for (&(u, v), &point) in params.iter().zip(points) {
        let (su, sv) = (knots_u.span_in_domain(u), knots_v.span_in_domain(v));
        knots_u.basis_values(su, u, &mut bu);
        knots_v.basis_values(sv, v, &mut bv);
        tensor_row(
            (su - p, sv - q, nv),
            (&bu[..=p], &bv[..=q]),
            &mut idx,
            &mut val,
        );
        add_row(matrix, rhs, &idx, &val, point, T::one());
    }
}

/// [`add_points`]; with the `parallel` feature, for at least [`crate::PARALLEL_MIN_POINTS`]
/// points on more than one thread (and while a partial band costs less than the points it
/// sums), the points are split into one chunk per thread, each assembled into its own band
/// and right-hand side, and the parts are added in chunk order: the same sums in another
/// order (≈ 1e-15 relative).
fn assemble_points<T: Scalar, P: ControlPoint<T>>(
    knots_u: &KnotVector<T>,
    knots_v: &KnotVector<T>,
    params: &[(T, T)],
    points: &[P],
    matrix: &mut BandCholesky<T>,
    rhs: &mut [P],
) {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        let threads = rayon::current_num_threads();
        let (n, bw) = (matrix.len(), matrix.bandwidth());
        let per_point = (knots_u.degree() + 1) * (knots_v.degree() + 1);
        let band_entries = n * (bw + 1);
        if params.len() >= crate::PARALLEL_MIN_POINTS
            && threads > 1
            && band_entries <= params.len() * per_point * per_point
        {
            let chunk = params.len().div_ceil(threads);
            let parts: Vec<(BandCholesky<T>, Vec<P>)> = params
                .par_chunks(chunk)
                .zip(points.par_chunks(chunk))
                .map(|(ps, qs)| {
                    let mut part = BandCholesky::zeros(n, bw);
                    let mut part_rhs = vec![P::origin(); n];
                    add_points(knots_u, knots_v, ps, qs, &mut part, &mut part_rhs);
                    (part, part_rhs)
                })
                .collect();
            for (mut part, part_rhs) in parts {
                for (a, &b) in matrix.data_mut().iter_mut().zip(part.data_mut().iter()) {
                    *a += b;
                }
                for (a, b) in rhs.iter_mut().zip(part_rhs) {
                    *a += b;
                }
            }
            return;
        }
    }
    add_points(knots_u, knots_v, params, points, matrix, rhs);
}

#[cfg(all(test, feature = "parallel"))]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    /// The normal equations of scattered surface data assembled in one chunk per thread (two
    /// threads) equal the sequential ones (one thread) to 1e-12 relative.
    #[test]
    fn chunked_assembly_equals_the_sequential_one() {
        let m = 2 * crate::PARALLEL_MIN_POINTS + 7;
        #[allow(clippy::cast_precision_loss)]
        let params: Vec<(f64, f64)> = (0..m)
            .map(|k| {
                let k = k as f64;
                (
                    (k * 0.618_033_988_749_895).fract(),
                    (k * 0.754_877_666_246_693).fract(),
                )
            })
            .collect();
        let points: Vec<Vector3<f64>> = params
            .iter()
            .map(|&(u, v)| Vector3::new(u, v, (5.0 * u).sin() * (3.0 * v).cos()))
            .collect();
        let ku = KnotVector::uniform(3, 12, 0.0, 1.0).expect("knots");
        let kv = KnotVector::uniform(2, 9, 0.0, 1.0).expect("knots");
        let n = ku.num_basis() * kv.num_basis();
        let bw = 3 * kv.num_basis() + 2;
        let assemble = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool")
                .install(|| {
                    let mut matrix = BandCholesky::zeros(n, bw);
                    let mut rhs = vec![Vector3::zeros(); n];
                    assemble_points(&ku, &kv, &params, &points, &mut matrix, &mut rhs);
                    (matrix.data_mut().to_vec(), rhs)
                })
        };
        let ((band1, rhs1), (band2, rhs2)) = (assemble(1), assemble(2));
        let scale = band1.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let worst = band1
            .iter()
            .zip(&band2)
            .fold(0.0f64, |s, (a, b)| s.max((a - b).abs()));
        assert!(worst <= 1e-12 * scale, "{worst:e} of {scale:e}");
        assert!(
            band1 != band2 || rhs1 != rhs2,
            "the two-thread run took the chunked path"
        );
        let rhs_scale = rhs1.iter().fold(0.0f64, |s, r| s.max(r.amax()));
        for (a, b) in rhs1.iter().zip(&rhs2) {
            assert!((a - b).amax() <= 1e-12 * rhs_scale);
        }
    }
}

/// The row of a tensor-product basis: control point `(first_u + a, first_v + b)` (index
/// `(first_u + a)·nv + first_v + b`) with the value `bu[a]·bv[b]`, written into `idx`, `val`.
fn tensor_row<T: Scalar>(
    (first_u, first_v, nv): (usize, usize, usize),
    (bu, bv): (&[T], &[T]),
    idx: &mut Vec<usize>,
    val: &mut Vec<T>,
) {
    idx.clear();
    val.clear();
    for (a, &x) in bu.iter().enumerate() {
        for (b, &y) in bv.iter().enumerate() {
            idx.push((first_u + a) * nv + first_v + b);
            val.push(x * y);
        }
    }
}
