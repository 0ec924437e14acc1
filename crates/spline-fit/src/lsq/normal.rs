//! The assembled normal equations of curve and function fits, and of tensor-product fits
//! on grids: the one least-squares objective that constrained methods (spline-shape)
//! minimise under their constraints.

use super::LeastSquares;
use crate::banded::BandCholesky;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast};

/// The assembled normal equations of a least-squares problem
/// ([`LeastSquares::normal_equations`]): the banded Gram matrix $G = A^T W^2 A$ (plus the
/// smoothing term), the right-hand side $r = A^T W^2 Q$ and the constant
/// $\tfrac12 \sum_k w_k^2 \lVert Q_k \rVert^2$, so that the objective is
/// $f_0(c) = \tfrac12 c^T G c - r^T c + \text{constant}$ (coordinate by coordinate).
#[derive(Clone, Debug)]
pub struct NormalEquations<T, P> {
    pub(super) knots: KnotVector<T>,
    pub(super) matrix: BandCholesky<T>,
    pub(super) rhs: Vec<P>,
    pub(super) constant: T,
}

impl<T: Scalar, P: ControlPoint<T>> NormalEquations<T, P> {
    /// The knot vector of the fit.
    #[must_use]
    pub fn knots(&self) -> &KnotVector<T> {
        &self.knots
    }

    /// The number of control points `n` (the size of `G`).
    #[must_use]
    pub fn len(&self) -> usize {
        self.rhs.len()
    }

    /// Whether there are no unknowns (never, for a valid knot vector).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.rhs.is_empty()
    }

    /// The half-bandwidth of `G` (the degree).
    #[must_use]
    pub fn bandwidth(&self) -> usize {
        self.matrix.bandwidth()
    }

    /// The entry $G_{ij}$ (zero outside the band).
    ///
    /// # Panics
    /// If `i` or `j` is not below [`Self::len`].
    #[must_use]
    pub fn gram(&self, i: usize, j: usize) -> T {
        let n = self.len();
        assert!(
            i < n && j < n,
            "index ({i}, {j}) outside a {n} × {n} matrix"
        );
        let (i, j) = if j <= i { (i, j) } else { (j, i) };
        if i - j > self.bandwidth() {
            T::zero()
        } else {
            self.matrix.lower(i, j)
        }
    }

    /// The right-hand side $r = A^T W^2 Q$.
    #[must_use]
    pub fn rhs(&self) -> &[P] {
        &self.rhs
    }

    /// The constant $\tfrac12 \sum_k w_k^2 \lVert Q_k \rVert^2$.
    #[must_use]
    pub fn constant(&self) -> T {
        self.constant
    }

    /// The objective $\tfrac12 c^T G c - r^T c + \text{constant}$ at the control points
    /// `control` (not negative up to rounding).
    ///
    /// # Panics
    /// If `control` does not have [`Self::len`] points.
    #[must_use]
    pub fn objective(&self, control: &[P]) -> T {
        assert_eq!(control.len(), self.len(), "one control point per unknown");
        let half: T = cast(0.5);
        let mut quadratic = T::zero();
        let mut linear = T::zero();
        let bw = self.bandwidth();
        for i in 0..self.len() {
            quadratic += control[i].dot(&control[i]) * self.matrix.lower(i, i) * half;
            for j in i.saturating_sub(bw)..i {
                quadratic += control[i].dot(&control[j]) * self.matrix.lower(i, j);
            }
            linear += self.rhs[i].dot(&control[i]);
        }
        quadratic - linear + self.constant
    }

    /// The unconstrained minimiser (the least-squares control points).
    ///
    /// # Errors
    /// [`ErrorKind::SingularSystem`] when the data do not determine every control point.
    pub fn solve(&self) -> Result<Vec<P>> {
        let mut matrix = self.matrix.clone();
        matrix.factor(&|i| format!("control point {i}"))?;
        let mut x = self.rhs.clone();
        matrix.solve(&mut x);
        Ok(x)
    }
}

/// A least-squares fit of a tensor-product B-spline function to values on a grid:
/// minimises $\tfrac12 \sum_{a,b} (s(\bar u_a, \bar v_b) - z_{ab})^2$ over the `n_u × n_v`
/// coefficients. Its normal equations ([`GridLeastSquares::normal_equations`]) have the Gram
/// matrix $G_u \otimes G_v$ of the two directions, each assembled by [`LeastSquares`] (the
/// one assembly of the crate).
///
/// ```
/// use spline_core::KnotVector;
/// use spline_fit::GridLeastSquares;
/// let (ku, kv) = (KnotVector::bezier(1, 0.0, 1.0)?, KnotVector::bezier(2, 0.0, 1.0)?);
/// let us = [0.0, 0.3, 0.7, 1.0];
/// let vs = [0.0, 0.5, 1.0];
/// // z = u v², exactly in the space.
/// let values: Vec<f64> = us.iter().flat_map(|u| vs.iter().map(move |v| u * v * v)).collect();
/// let normal = GridLeastSquares::new(&us, &vs, &values, ku, kv).normal_equations()?;
/// let x = normal.solve()?;
/// assert!((x[5] - 1.0).abs() < 1e-14 && x[..5].iter().all(|c: &f64| c.abs() < 1e-14));
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct GridLeastSquares<'a, T> {
    us: &'a [T],
    vs: &'a [T],
    values: &'a [T],
    knots_u: KnotVector<T>,
    knots_v: KnotVector<T>,
}

impl<'a, T: Scalar> GridLeastSquares<'a, T> {
    /// The problem for `values[a · vs.len() + b]` at `(us[a], vs[b])` (parameters
    /// non-decreasing, inside the domains).
    #[must_use]
    pub fn new(
        us: &'a [T],
        vs: &'a [T],
        values: &'a [T],
        knots_u: KnotVector<T>,
        knots_v: KnotVector<T>,
    ) -> Self {
        Self {
            us,
            vs,
            values,
            knots_u,
            knots_v,
        }
    }

    /// The normal equations $(G_u \otimes G_v)\\, x = r$ with
    /// $r = \operatorname{vec}(A_u^T Z A_v)$, assembled but not solved.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are `us.len() · vs.len() > 0` values; the
    /// errors of [`LeastSquares::normal_equations`] in each direction (named in the message).
    pub fn normal_equations(&self) -> Result<GridNormalEquations<T>> {
        let (mu, mv) = (self.us.len(), self.vs.len());
        if mu == 0 || mv == 0 || self.values.len() != mu * mv {
            return Err(Error::invalid_length(
                format!("a grid of {mu} × {mv} parameters needs as many values (at least one)"),
                mu * mv,
                self.values.len(),
            ));
        }
        // A_uᵀ Z, one grid column at a time (m_v assemblies in u).
        let in_u = |b: usize| {
            let column: Vec<T> = (0..mu).map(|a| self.values[a * mv + b]).collect();
            LeastSquares::new(&column, self.us, self.knots_u.clone())
                .normal_equations()
                .map_err(|e| e.context("u"))
        };
        let gram_u = in_u(0)?;
        let mut az = vec![gram_u.rhs().to_vec()];
        for b in 1..mv {
            az.push(in_u(b)?.rhs().to_vec());
        }
        // (A_uᵀ Z) A_v, one row at a time (n_u assemblies in v).
        let in_v = |i: usize| {
            let row: Vec<T> = az.iter().map(|column| column[i]).collect();
            LeastSquares::new(&row, self.vs, self.knots_v.clone())
                .normal_equations()
                .map_err(|e| e.context("v"))
        };
        let gram_v = in_v(0)?;
        let mut rhs = Vec::with_capacity(gram_u.rhs().len() * gram_v.rhs().len());
        rhs.extend_from_slice(gram_v.rhs());
        for i in 1..self.knots_u.num_basis() {
            rhs.extend_from_slice(in_v(i)?.rhs());
        }
        let half: T = cast(0.5);
        let constant = self.values.iter().fold(T::zero(), |s, &z| s + z * z) * half;
        Ok(GridNormalEquations {
            u: gram_u,
            v: gram_v,
            rhs,
            constant,
        })
    }
}

/// The normal equations of a [`GridLeastSquares`] fit: the objective is
/// $f_0(x) = \tfrac12 x^T (G_u \otimes G_v) x - r^T x + \text{constant}$ over the row-major
/// coefficients `x[i · n_v + j]`.
#[derive(Clone, Debug)]
pub struct GridNormalEquations<T> {
    u: NormalEquations<T, T>,
    v: NormalEquations<T, T>,
    rhs: Vec<T>,
    constant: T,
}

impl<T: Scalar> GridNormalEquations<T> {
    /// The Gram matrix $G_u$ of the `u` direction (its right-hand side is not used).
    #[must_use]
    pub fn gram_u(&self) -> &NormalEquations<T, T> {
        &self.u
    }

    /// The Gram matrix $G_v$ of the `v` direction.
    #[must_use]
    pub fn gram_v(&self) -> &NormalEquations<T, T> {
        &self.v
    }

    /// The right-hand side $r$, row-major (`n_u · n_v` entries).
    #[must_use]
    pub fn rhs(&self) -> &[T] {
        &self.rhs
    }

    /// The constant $\tfrac12 \sum z_{ab}^2$.
    #[must_use]
    pub fn constant(&self) -> T {
        self.constant
    }

    /// The unconstrained minimiser $X = G_u^{-1} R\\, G_v^{-1}$ (row-major), by two banded
    /// Cholesky solves.
    ///
    /// # Errors
    /// [`ErrorKind::SchoenbergWhitney`] when the parameters of a direction do not determine
    /// every coefficient (a basis function without a parameter in its support).
    pub fn solve(&self) -> Result<Vec<T>> {
        let factor = |normal: &NormalEquations<T, T>, what: &str| {
            let mut m = normal.matrix.clone();
            m.factor(&|i| format!("coefficient {i}")).map_err(|e| {
                Error::new(
                    ErrorKind::SchoenbergWhitney,
                    format!(
                        "the {what} parameters do not determine every coefficient (a basis function has no sample in its support): {}",
                        e.message()
                    ),
                )
            })?;
            Ok::<_, Error>(m)
        };
        let gu = factor(&self.u, "u")?;
        let gv = factor(&self.v, "v")?;
        let (nu, nv) = (self.u.len(), self.v.len());
        let mut x = self.rhs.clone();
        for row in x.chunks_exact_mut(nv) {
            gv.solve(row);
        }
        let mut column = vec![T::zero(); nu];
        for j in 0..nv {
            for (i, c) in column.iter_mut().enumerate() {
                *c = x[i * nv + j];
            }
            gu.solve(&mut column);
            for (i, c) in column.iter().enumerate() {
                x[i * nv + j] = *c;
            }
        }
        Ok(x)
    }
}
