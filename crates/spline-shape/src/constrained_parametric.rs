//! Convexity of a parametric patch under the interior-point method (thesis ch. 7, as §5.6
//! does for functions): the heights `z(u, v)` of the patch
//! $S(u, v) = (X(u, v), Y(u, v), z(u, v))$ over a fixed planar parametrisation `(X, Y)`
//! (any tensor-product net, not a grid of `x` and `y`) are fitted to samples so that the
//! Gaussian curvature is nowhere negative and the patch turns its convex side one way.
//!
//! With `(X, Y)` fixed, $S_u \times S_v$ and the second derivatives are affine in the height
//! coefficients and their planar parts cancel in $L = S_{uu} \cdot (S_u \times S_v)$ (and
//! `M`, `N`): the second fundamental form is *linear* in the heights, so the numerator
//! $LN - M^2$ of `K` ([`spline_algebra::curvature_numerators`], per-patch Bernstein form) is
//! a homogeneous quadratic form of them, each coefficient $\tfrac12 z^T H_k z$ with a
//! constant Hessian $H_k$. The Hessians are read off the numerators' Jacobians
//! ([`spline_algebra::curvature_numerators_with_jacobians`]) at the unit height vectors
//! ($\nabla (\tfrac12 z^T H_k z) = H_k z$). The constraints are: every Bernstein coefficient
//! of $LN - M^2$ non-negative (`K ≥ 0` by the convex-hull property), and every coefficient
//! of `L` with the chosen sign (linear); the problem is the same [`ApproximationProblem`]
//! as the convexity of functions.

use crate::barrier::BarrierOptions;
use crate::constrained::{grid_pairs, sampled_grid};
use crate::constrained_surface::ConstrainedSurfaceFit;
use crate::problem::{ApproximationProblem, LeastSquaresObjective, Sign, normalized_rows, vstack};
use crate::problem::{check_convexity_degrees, check_grid, normalized_forms};
use nalgebra::{DMatrix, Vector2, Vector3};
use nalgebra_sparse::CsrMatrix;
use spline_algebra::{SparseBilinear, curvature_numerators_with_jacobians};
use spline_core::{Error, ErrorKind, Result};
use spline_geom::{NurbsSurface, Surface};

/// The fitted patch `(X, Y, z)` of [`ParametricConvexity::fit_grid`]: its objective is
/// `½ Σ (z − h)²` at the samples.
pub type ParametricConvexFit = ConstrainedSurfaceFit<Vector3<f64>>;

/// Heights over a planar parametrisation with `K ≥ 0` and the sign of `L` (see the module
/// documentation).
///
/// ```
/// use nalgebra::{Vector2, Vector3};
/// use spline_core::KnotVector;
/// use spline_geom::Surface;
/// use spline_shape::{ParametricConvexity, Sign};
/// // A sheared, bent parametrisation of the plane: X = u + 0.3 v², Y = v + 0.2 u.
/// let k = KnotVector::clamped(3, 0.0, 1.0, &[0.5])?;
/// let g = k.greville();
/// let base: Vec<Vector2<f64>> = g.iter()
///     .flat_map(|&u| g.iter().map(move |&v| (u, v)))
///     .map(|(u, v)| Vector2::new(u + 0.3 * v * v, v + 0.2 * u))
///     .collect();
/// // Exact: the Greville abscissae reproduce degree-1 terms, and v² is a quadratic.
/// let base = Surface::new(k.clone(), k, base)?;
/// let convex = ParametricConvexity::new(base, Sign::NonNegative)?;
/// // A bowl with ripples: the ripples make K negative in places.
/// let fit = convex.fit_function((12, 12), |x, y| x * x + y * y + 0.05 * (9.0 * x).sin())?;
/// assert!(fit.objective >= fit.unconstrained_objective);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct ParametricConvexity {
    base: Surface<f64, Vector2<f64>>,
    sign: Sign,
    /// Settings of the interior-point method.
    pub options: BarrierOptions,
}

impl ParametricConvexity {
    /// Heights over the planar net `base` with `K ≥ 0` and `L` of sign `sign`
    /// ([`Sign::NonNegative`]: convex towards `+z`).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] below degree 2 in a direction (no curvature to
    /// control) or for more than 400 control points (the dense quadratic forms).
    pub fn new(base: Surface<f64, Vector2<f64>>, sign: Sign) -> Result<Self> {
        let (p, q) = base.degrees();
        check_convexity_degrees(p, q)?;
        let n = base.control_points().len();
        if n > 400 {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "at most 400 control points for the convexity of a parametric patch, got {n}"
                ),
            )
            .with_counts(400, n));
        }
        Ok(Self {
            base,
            sign,
            options: BarrierOptions::default(),
        })
    }

    /// The patch with heights `z` (row-major over the net).
    fn patch(&self, z: &[f64]) -> Result<Surface<f64, Vector3<f64>>> {
        let points = self
            .base
            .control_points()
            .iter()
            .zip(z)
            .map(|(b, &h)| Vector3::new(b.x, b.y, h))
            .collect();
        Surface::new(
            self.base.knots_u().clone(),
            self.base.knots_v().clone(),
            points,
        )
    }

    /// The constraints on the heights: the rows of `L` (times `−sign`, normalised) and the
    /// quadratic forms of $LN - M^2$ (normalised, `< 0` when satisfied).
    ///
    /// # Errors
    /// The errors of the numerator algebra.
    pub fn constraint_forms(&self) -> Result<(CsrMatrix<f64>, SparseBilinear<f64>)> {
        let n = self.base.control_points().len();
        let numerators = |z: &[f64]| -> Result<_> {
            let patch = NurbsSurface::from_surface(&self.patch(z)?);
            curvature_numerators_with_jacobians(&patch)
        };
        // The height columns (4i + 2) of a Jacobian.
        let heights = |j: &CsrMatrix<f64>| -> DMatrix<f64> {
            let dense = DMatrix::from(j);
            DMatrix::from_fn(dense.nrows(), n, |r, c| dense[(r, 4 * c + 2)])
        };
        let zero = vec![0.0; n];
        let (_, at_zero) = numerators(&zero)?;
        let l_rows = heights(&at_zero.second[0]);
        let mut forms: Vec<Vec<(usize, usize, f64)>> = Vec::new();
        for j in 0..n {
            let mut unit = zero.clone();
            unit[j] = 1.0;
            let (_, jac) = numerators(&unit)?;
            let column = heights(&jac.gaussian);
            if forms.is_empty() {
                forms = vec![Vec::new(); column.nrows()];
            }
            for (k, row) in forms.iter_mut().enumerate() {
                for l in 0..n {
                    let v = column[(k, l)];
                    if v != 0.0 {
                        row.push((l, j, v));
                    }
                }
            }
        }
        let quadratic = SparseBilinear::from_rows(n, n, forms)?;
        let linear = CsrMatrix::from(&nalgebra_sparse::CooMatrix::from(&l_rows));
        Ok((
            normalized_rows(&linear, -self.sign.factor()),
            normalized_forms(&quadratic)?,
        ))
    }

    /// Fits the heights `values[a · vs.len() + b]` at `(us[a], vs[b])` under the constraints.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] unless there are `us.len() · vs.len()` values;
    /// [`ErrorKind::NonFinite`]; the errors of the least squares;
    /// [`ErrorKind::NoConvergence`] if no strictly feasible patch is found near the data.
    pub fn fit_grid(&self, us: &[f64], vs: &[f64], values: &[f64]) -> Result<ParametricConvexFit> {
        check_grid(us, vs, values.len(), |j| values[j].is_finite(), "value")?;
        let knots = (self.base.knots_u(), self.base.knots_v());
        let lsq = LeastSquaresObjective::grid(knots, us, vs, values)?;
        let n = self.base.control_points().len();
        let (linear, quadratic) = self.constraint_forms()?;
        let problem = ApproximationProblem::new(lsq, vstack(n, &[linear]), Some(quadratic));
        // A start inside: the paraboloid ± (X² + Y²) fitted at the samples (strictly convex
        // over any planar parametrisation), moved towards the unconstrained fit as far as
        // feasibility allows.
        let bowl = || {
            let heights: Vec<f64> = grid_pairs(us, vs)
                .map(|(u, v)| {
                    self.base
                        .eval(u, v)
                        .map(|p| self.sign.factor() * p.norm_squared())
                })
                .collect::<Result<_>>()?;
            problem.least_squares().solve_for(&heights).map(Some)
        };
        ConstrainedSurfaceFit::solve(&problem, bowl, &self.options, |x| self.patch(x.as_slice()))
    }

    /// Fits `f(X, Y)` sampled on a uniform grid of `counts.0 × counts.1` parameters.
    ///
    /// # Errors
    /// [`ErrorKind::TooFewPoints`] for fewer than two samples in a direction; the errors of
    /// [`ParametricConvexity::fit_grid`].
    pub fn fit_function(
        &self,
        counts: (usize, usize),
        f: impl Fn(f64, f64) -> f64,
    ) -> Result<ParametricConvexFit> {
        let domains = (self.base.knots_u().domain(), self.base.knots_v().domain());
        let (us, vs, values) = sampled_grid(domains, counts, |u, v| {
            self.base.eval(u, v).map(|p| f(p.x, p.y))
        })?;
        self.fit_grid(&us, &vs, &values)
    }
}
