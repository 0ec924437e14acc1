//! The least-squares problem's types: the request ([`LeastSquares`]), its solver choice
//! ([`LsqMethod`]) and the data rows the assembly kernels take; the methods are in `mod.rs`
//! and the kernels in the sibling modules.

use spline_core::KnotVector;

/// The data rows of a curve fit as the assembly kernels take them: the knots, the data's
/// parameters and points, and their weights (`None`: all ones).
#[derive(Clone, Copy)]
pub(crate) struct Rows<'a, T, P> {
    pub(crate) knots: &'a KnotVector<T>,
    pub(crate) params: &'a [T],
    pub(crate) points: &'a [P],
    pub(crate) weights: Option<&'a [T]>,
}

/// How the least-squares problem is solved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LsqMethod {
    /// Banded normal equations $A^T W^2 A\\, c = A^T W^2 Q$ solved by banded Cholesky: the
    /// fastest, `O(m p² + n p²)`, accurate for the well-conditioned B-spline bases.
    #[default]
    NormalEquations,
    /// Givens QR of the banded design matrix, one data row at a time (as FITPACK): about
    /// twice the work, without squaring the condition number.
    Qr,
}

impl LsqMethod {
    /// The names every front end spells (the tool's `--method`); scipy's `"norm-eq"` is
    /// read as `"normal"`.
    pub const NAMES: [&'static str; 2] = ["normal", "qr"];

    /// The method called `name` (one of [`Self::NAMES`], or scipy's `"norm-eq"`).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`](spline_core::ErrorKind::InvalidArgument) naming the
    /// choices for any other text.
    ///
    /// ```
    /// use spline_fit::LsqMethod;
    /// assert_eq!(LsqMethod::from_name("norm-eq")?, LsqMethod::NormalEquations);
    /// assert_eq!(LsqMethod::from_name("qr")?, LsqMethod::Qr);
    /// assert!(LsqMethod::from_name("svd").is_err());
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    pub fn from_name(name: &str) -> spline_core::Result<Self> {
        match name.trim() {
            "normal" | "norm-eq" => Ok(Self::NormalEquations),
            "qr" => Ok(Self::Qr),
            other => Err(crate::params::unknown_name(
                "least-squares method",
                other,
                &Self::NAMES,
            )),
        }
    }
}

/// A least-squares fit of a B-spline to data (seed 000 (10)–(13), seed 003 TD3, The NURBS
/// Book §9.4.1): minimises
///
/// $$ \sum_k w_k^2 \lVert C(\bar u_k) - Q_k \rVert^2 + \lambda \int \lVert C''(u) \rVert^2 du $$
///
/// over the control points that are not fixed. Weights multiply the residuals, as in scipy's
/// `make_lsq_spline` (weight `w` on a point counts like `w²` copies of it). Built with
/// [`LeastSquares::new`], configured with the builder methods, run by
/// [`LeastSquares::solve`].
///
/// ```
/// use nalgebra::Vector2;
/// use spline_core::KnotVector;
/// use spline_fit::LeastSquares;
/// // 50 points on a parabola, a quadratic Bézier reproduces it exactly.
/// let params: Vec<f64> = (0..50).map(|k| k as f64 / 49.0).collect();
/// let points: Vec<Vector2<f64>> = params.iter().map(|&t| Vector2::new(t, t * t)).collect();
/// let knots = KnotVector::bezier(2, 0.0, 1.0)?;
/// let fit = LeastSquares::new(&points, &params, knots).pin_ends().solve()?;
/// assert!(fit.deviation.max < 1e-13);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct LeastSquares<'a, T, P> {
    pub(super) points: &'a [P],
    pub(super) params: &'a [T],
    pub(super) knots: KnotVector<T>,
    pub(super) weights: Option<&'a [T]>,
    pub(super) fixed_points: Vec<(usize, P)>,
    pub(super) fixed_coords: Vec<(usize, usize, T)>,
    pub(super) pin_ends: bool,
    pub(super) smoothing: T,
    pub(super) method: LsqMethod,
    pub(super) check_sw: bool,
}
