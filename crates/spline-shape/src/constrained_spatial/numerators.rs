//! The curvature numerators of a polynomial patch as a fixed pipeline of sparse maps, built
//! once from the knot vectors and evaluated on any scalar: `f64` for the constraint values,
//! vector dual numbers for their Jacobian (forward mode), and the hand-written adjoint of
//! the pipeline on vector dual numbers for the weighted Hessian (forward over reverse).
//!
//! Per coordinate `c`, the coefficients of $S_u, S_v, S_{uu}, S_{uv}, S_{vv}$ are linear
//! maps of the control points ([`TensorMap::partial_derivative`]); $m = S_u \times S_v$ is
//! bilinear in them; `L, M, N` $= S_{uu} \cdot m,\ S_{uv} \cdot m,\ S_{vv} \cdot m$ bilinear
//! in those and `m`; and $K = LN - M^2$ bilinear in `L, M, N`
//! ([`TensorProductMap::bilinear`]). `L` and `K` end in per-patch Bernstein form
//! ([`SplineMap::bernstein`]), as [`spline_algebra::curvature_numerators`] gives them (the
//! tests compare the two).

use nalgebra_sparse::CsrMatrix;
use spline_algebra::{SparseBilinear, SplineMap, TensorMap, TensorProductMap, kron};
use spline_core::{KnotVector, Result, Scalar};

type Space = (KnotVector<f64>, KnotVector<f64>);

/// See the module documentation.
#[derive(Clone, Debug)]
pub(super) struct NumeratorPipeline {
    /// Control points per coordinate.
    n: usize,
    /// The five derivatives' coefficients from a coordinate's control points.
    derivative: [CsrMatrix<f64>; 5],
    /// `S_u ⊗ S_v → m` (one component: `m_c = S_u[c+1] S_v[c+2] − S_u[c+2] S_v[c+1]`).
    cross: SparseBilinear<f64>,
    /// `(S_uu | S_uv | S_vv) ⊗ m_c → L | M | N`.
    second: [SparseBilinear<f64>; 3],
    /// `L →` its Bernstein coefficients.
    l_bernstein: CsrMatrix<f64>,
    /// `L ⊗ N →` Bernstein coefficients of `LN`.
    ln: SparseBilinear<f64>,
    /// `M ⊗ M →` Bernstein coefficients of `M²`.
    mm: SparseBilinear<f64>,
}

/// The intermediate values of one evaluation.
pub(super) struct Forward<T> {
    /// `[derivative][coordinate]`.
    derivatives: [[Vec<T>; 3]; 5],
    m: [Vec<T>; 3],
    /// `[L, M, N]`.
    lmn: [Vec<T>; 3],
    /// Bernstein coefficients of `L`.
    pub(super) l: Vec<T>,
    /// Bernstein coefficients of `LN − M²`.
    pub(super) k: Vec<T>,
}

fn constant<T: Scalar>(v: f64) -> T {
    nalgebra::convert(v)
}

fn linear<T: Scalar>(a: &CsrMatrix<f64>, x: &[T]) -> Vec<T> {
    a.row_iter()
        .map(|row| {
            row.col_indices()
                .iter()
                .zip(row.values())
                .fold(T::zero(), |acc, (&j, &v)| acc + x[j] * constant::<T>(v))
        })
        .collect()
}

/// `x̄ += Aᵀ ȳ`.
fn linear_adjoint<T: Scalar>(a: &CsrMatrix<f64>, y_bar: &[T], x_bar: &mut [T]) {
    for (row, &yb) in a.row_iter().zip(y_bar) {
        for (&j, &v) in row.col_indices().iter().zip(row.values()) {
            x_bar[j] += yb * constant::<T>(v);
        }
    }
}

fn bilinear<T: Scalar>(b: &SparseBilinear<f64>, x: &[T], y: &[T]) -> Vec<T> {
    (0..b.nrows())
        .map(|k| {
            b.row(k).iter().fold(T::zero(), |acc, &(i, j, v)| {
                acc + x[i] * y[j] * constant::<T>(v)
            })
        })
        .collect()
}

/// `x̄_i += Σ v y_j z̄_k`, `ȳ_j += Σ v x_i z̄_k` over the entries `(k, i, j, v)`.
fn bilinear_adjoint<T: Scalar>(
    b: &SparseBilinear<f64>,
    (x, y): (&[T], &[T]),
    z_bar: &[T],
    x_bar: &mut [T],
    y_bar: &mut [T],
) {
    for (k, &zb) in z_bar.iter().enumerate() {
        for &(i, j, v) in b.row(k) {
            let w = zb * constant::<T>(v);
            x_bar[i] += w * y[j];
            y_bar[j] += w * x[i];
        }
    }
}

/// `a + sign · b`.
fn sum<T: Scalar>(mut a: Vec<T>, b: &[T], sign: T) -> Vec<T> {
    for (x, &y) in a.iter_mut().zip(b) {
        *x += sign * y;
    }
    a
}

fn product(a: &Space, b: &Space) -> Result<(SparseBilinear<f64>, Space)> {
    let map = TensorProductMap::new((&a.0, &a.1), (&b.0, &b.1))?;
    let target = (map.u().target().clone(), map.v().target().clone());
    Ok((map.bilinear(), target))
}

impl NumeratorPipeline {
    /// The pipeline of polynomial patches on `knots_u × knots_v`.
    ///
    /// # Errors
    /// The errors of the maps (degrees below 2, degrees of the products above
    /// [`spline_core::MAX_DEGREE`]).
    pub(super) fn new(knots_u: &KnotVector<f64>, knots_v: &KnotVector<f64>) -> Result<Self> {
        let maps: [TensorMap<f64>; 5] = [
            TensorMap::partial_derivative(knots_u, knots_v, 1, 0)?,
            TensorMap::partial_derivative(knots_u, knots_v, 0, 1)?,
            TensorMap::partial_derivative(knots_u, knots_v, 2, 0)?,
            TensorMap::partial_derivative(knots_u, knots_v, 1, 1)?,
            TensorMap::partial_derivative(knots_u, knots_v, 0, 2)?,
        ];
        let spaces: Vec<Space> = maps
            .iter()
            .map(|m| (m.u().target().clone(), m.v().target().clone()))
            .collect();
        let (cross, m_space) = product(&spaces[0], &spaces[1])?;
        let (l_map, l_space) = product(&spaces[2], &m_space)?;
        let (m_map, m2_space) = product(&spaces[3], &m_space)?;
        let (n_map, n_space) = product(&spaces[4], &m_space)?;
        let (breaks_u, breaks_v) = (knots_u.domain_breaks(), knots_v.domain_breaks());
        let bernstein = |s: &Space| -> Result<CsrMatrix<f64>> {
            Ok(kron(
                SplineMap::bernstein(&s.0, &breaks_u)?.matrix(),
                SplineMap::bernstein(&s.1, &breaks_v)?.matrix(),
            ))
        };
        let (ln, ln_space) = product(&l_space, &n_space)?;
        let (mm, mm_space) = product(&m2_space, &m2_space)?;
        Ok(Self {
            n: knots_u.num_basis() * knots_v.num_basis(),
            derivative: maps.map(|m| m.matrix()),
            cross,
            second: [l_map, m_map, n_map],
            l_bernstein: bernstein(&l_space)?,
            ln: ln.then(&bernstein(&ln_space)?)?,
            mm: mm.then(&bernstein(&mm_space)?)?,
        })
    }

    /// `(rows of L, rows of LN − M²)`.
    pub(super) fn rows(&self) -> (usize, usize) {
        (self.l_bernstein.nrows(), self.ln.nrows())
    }

    /// Evaluates the pipeline at the coordinate-major unknowns `x` (`3n` entries).
    pub(super) fn forward<T: Scalar>(&self, x: &[T]) -> Forward<T> {
        let n = self.n;
        let derivatives: [[Vec<T>; 3]; 5] = std::array::from_fn(|d| {
            std::array::from_fn(|c| linear(&self.derivative[d], &x[c * n..(c + 1) * n]))
        });
        let (su, sv) = (&derivatives[0], &derivatives[1]);
        let m: [Vec<T>; 3] = std::array::from_fn(|c| {
            let (a, b) = ((c + 1) % 3, (c + 2) % 3);
            sum(
                bilinear(&self.cross, &su[a], &sv[b]),
                &bilinear(&self.cross, &su[b], &sv[a]),
                -T::one(),
            )
        });
        let lmn: [Vec<T>; 3] = std::array::from_fn(|s| {
            (0..3).fold(vec![T::zero(); self.second[s].nrows()], |acc, c| {
                sum(
                    acc,
                    &bilinear(&self.second[s], &derivatives[2 + s][c], &m[c]),
                    T::one(),
                )
            })
        });
        let l = linear(&self.l_bernstein, &lmn[0]);
        let k = sum(
            bilinear(&self.ln, &lmn[0], &lmn[2]),
            &bilinear(&self.mm, &lmn[1], &lmn[1]),
            -T::one(),
        );
        Forward {
            derivatives,
            m,
            lmn,
            l,
            k,
        }
    }

    /// The gradient of $\sum_r w^L_r L_r + \sum_r w^K_r K_r$ (Bernstein coefficients) with
    /// respect to the coordinate-major unknowns, by the adjoint of [`Self::forward`].
    pub(super) fn weighted_gradient<T: Scalar>(&self, x: &[T], w_l: &[f64], w_k: &[f64]) -> Vec<T> {
        let f = self.forward(x);
        let k_bar: Vec<T> = w_k.iter().map(|&w| constant(w)).collect();
        let l_in: Vec<T> = w_l.iter().map(|&w| constant(w)).collect();
        let mut lmn_bar: [Vec<T>; 3] =
            std::array::from_fn(|s| vec![T::zero(); self.second[s].nrows()]);
        linear_adjoint(&self.l_bernstein, &l_in, &mut lmn_bar[0]);
        {
            let [l_bar, m_bar, n_bar] = &mut lmn_bar;
            bilinear_adjoint(&self.ln, (&f.lmn[0], &f.lmn[2]), &k_bar, l_bar, n_bar);
            let minus: Vec<T> = k_bar.iter().map(|&w| -w).collect();
            let mut other = vec![T::zero(); m_bar.len()];
            bilinear_adjoint(&self.mm, (&f.lmn[1], &f.lmn[1]), &minus, m_bar, &mut other);
            for (a, b) in m_bar.iter_mut().zip(other) {
                *a += b;
            }
        }
        let mut d_bar: [[Vec<T>; 3]; 5] = std::array::from_fn(|d| {
            std::array::from_fn(|_| vec![T::zero(); self.derivative[d].nrows()])
        });
        let mut m_bar: [Vec<T>; 3] = std::array::from_fn(|_| vec![T::zero(); self.cross.nrows()]);
        for (s, bar) in lmn_bar.iter().enumerate() {
            for c in 0..3 {
                bilinear_adjoint(
                    &self.second[s],
                    (&f.derivatives[2 + s][c], &f.m[c]),
                    bar,
                    &mut d_bar[2 + s][c],
                    &mut m_bar[c],
                );
            }
        }
        for (c, bar) in m_bar.iter().enumerate() {
            let (a, b) = ((c + 1) % 3, (c + 2) % 3);
            let minus: Vec<T> = bar.iter().map(|&w| -w).collect();
            let [su_bar, sv_bar, ..] = &mut d_bar;
            bilinear_adjoint(
                &self.cross,
                (&f.derivatives[0][a], &f.derivatives[1][b]),
                bar,
                &mut su_bar[a],
                &mut sv_bar[b],
            );
            bilinear_adjoint(
                &self.cross,
                (&f.derivatives[0][b], &f.derivatives[1][a]),
                &minus,
                &mut su_bar[b],
                &mut sv_bar[a],
            );
        }
        let n = self.n;
        let mut x_bar = vec![T::zero(); 3 * n];
        for (d, per_coordinate) in d_bar.iter().enumerate() {
            for (c, bar) in per_coordinate.iter().enumerate() {
                linear_adjoint(&self.derivative[d], bar, &mut x_bar[c * n..(c + 1) * n]);
            }
        }
        x_bar
    }
}
