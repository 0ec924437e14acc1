//! Least-squares approximation by B-spline curves and functions.

mod assemble;
mod normal;
#[cfg(feature = "parallel")]
mod parallel;
mod scattered;
mod types;

#[cfg(feature = "parallel")]
pub use assemble::PARALLEL_MIN_POINTS;
pub(crate) use assemble::penalty_rows;
pub use normal::{GridLeastSquares, GridNormalEquations, NormalEquations};
#[cfg(feature = "parallel")]
pub(crate) use parallel::chunk_len;
pub(crate) use scattered::scattered_normal_equations;
pub(crate) use types::Rows;
pub use types::{LeastSquares, LsqMethod};

use crate::params::{
    KnotChoice, Parametrization, check_control_count, check_points, check_weights, knots_for,
    parametrize,
};
use crate::params::{check_degree, check_non_negative};
use crate::report::CurveFit;
use assemble::Sink;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, check_params};
use spline_geom::BSpline;

impl<'a, T: Scalar, P: ControlPoint<T>> LeastSquares<'a, T, P> {
    /// The problem for the data `points` at `params` (non-decreasing, inside the domain of
    /// `knots`).
    #[must_use]
    pub fn new(points: &'a [P], params: &'a [T], knots: KnotVector<T>) -> Self {
        Self {
            points,
            params,
            knots,
            weights: None,
            fixed_points: Vec::new(),
            fixed_coords: Vec::new(),
            pin_ends: false,
            smoothing: T::zero(),
            method: LsqMethod::NormalEquations,
            check_sw: true,
        }
    }

    /// Positive weights, one per point (residual `k` is multiplied by `w_k`).
    #[must_use]
    pub fn weights(mut self, weights: &'a [T]) -> Self {
        self.weights = Some(weights);
        self
    }

    /// Pins the ends: the first and last control points are the first and last data points,
    /// so a clamped curve whose end parameters are the domain ends passes through them.
    #[must_use]
    pub fn pin_ends(mut self) -> Self {
        self.pin_ends = true;
        self
    }

    /// Fixes control point `index` to `value`.
    #[must_use]
    pub fn fix_point(mut self, index: usize, value: P) -> Self {
        self.fixed_points.push((index, value));
        self
    }

    /// Fixes coordinate `coord` of control point `index` to `value`, leaving its other
    /// coordinates free (seed 000 §3.3: `x_0 = x_1 = y_0 = y_n = 0`, `x_n = 1`).
    #[must_use]
    pub fn fix_coordinate(mut self, index: usize, coord: usize, value: T) -> Self {
        self.fixed_coords.push((index, coord, value));
        self
    }

    /// Adds the smoothing term $\lambda \int \lVert C'' \rVert^2$ (zero for degrees below 2),
    /// integrated exactly by Gauss–Legendre quadrature on each knot span. With `λ > 0` the
    /// Schoenberg–Whitney conditions are no longer needed.
    #[must_use]
    pub fn smoothing(mut self, lambda: T) -> Self {
        self.smoothing = lambda;
        self
    }

    /// The solution method (default: normal equations).
    #[must_use]
    pub fn method(mut self, method: LsqMethod) -> Self {
        self.method = method;
        self
    }

    pub(crate) fn points_ref(&self) -> &'a [P] {
        self.points
    }

    pub(crate) fn params_ref(&self) -> &'a [T] {
        self.params
    }

    pub(crate) fn knots_ref(&self) -> &KnotVector<T> {
        &self.knots
    }

    pub(crate) fn weights_ref(&self) -> Option<&'a [T]> {
        self.weights
    }

    /// The same problem with other parameters.
    pub(crate) fn with_params<'b>(&self, params: &'b [T]) -> LeastSquares<'b, T, P>
    where
        'a: 'b,
    {
        LeastSquares {
            points: self.points,
            params,
            knots: self.knots.clone(),
            weights: self.weights,
            fixed_points: self.fixed_points.clone(),
            fixed_coords: self.fixed_coords.clone(),
            pin_ends: self.pin_ends,
            smoothing: self.smoothing,
            method: self.method,
            check_sw: self.check_sw,
        }
    }

    /// Computes the fit.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidLength`] if points, parameters and weights differ in number;
    /// [`ErrorKind::TooFewPoints`] without points; [`ErrorKind::NonFinite`];
    /// [`ErrorKind::UnsortedKnots`] for decreasing parameters; [`ErrorKind::OutOfDomain`];
    /// [`ErrorKind::InvalidWeight`] for weights that are not positive and finite;
    /// [`ErrorKind::InvalidArgument`] for a negative smoothing weight or pinned ends on an
    /// unclamped knot vector; [`ErrorKind::IndexOutOfRange`] for a fixed index or coordinate
    /// out of range, [`ErrorKind::NonFinite`] for a fixed value that is not finite (the
    /// control point as [`Error::index`]);
    /// [`ErrorKind::SchoenbergWhitney`] when the data leave a free basis function without a
    /// parameter of its own (the message names it and an empty knot span);
    /// [`ErrorKind::SingularSystem`] for numerically singular systems.
    pub fn solve(&self) -> Result<CurveFit<T, P>> {
        let control = self.control_points()?;
        let curve = BSpline::new(self.knots.clone(), control)?;
        CurveFit::new(curve, self.params.to_vec(), self.points)
    }

    /// Computes only the control points (no deviation report): the fast path.
    ///
    /// # Errors
    /// As [`LeastSquares::solve`].
    pub fn control_points(&self) -> Result<Vec<P>> {
        self.validate()?;
        let n = self.knots.num_basis();
        // Fixed values per control point and coordinate.
        let mut fixed: Vec<Option<Vec<Option<T>>>> = vec![None; n];
        let mut set = |i: usize, c: usize, v: T| {
            fixed[i].get_or_insert_with(|| vec![None; P::DIM])[c] = Some(v);
        };
        if self.pin_ends {
            let (first, last) = (self.points[0], self.points[self.points.len() - 1]);
            for c in 0..P::DIM {
                set(0, c, first.coord(c));
                set(n - 1, c, last.coord(c));
            }
        }
        for &(i, v) in &self.fixed_points {
            for c in 0..P::DIM {
                set(i, c, v.coord(c));
            }
        }
        for &(i, c, v) in &self.fixed_coords {
            set(i, c, v);
        }
        if fixed.iter().all(Option::is_none) {
            let free = vec![true; n];
            return self.solve_group(&free, &vec![P::origin(); n]);
        }
        // Group the coordinates by their set of fixed control points.
        let mut groups: Vec<(Vec<bool>, Vec<usize>)> = Vec::new();
        for c in 0..P::DIM {
            let free: Vec<bool> = fixed
                .iter()
                .map(|f| f.as_ref().is_none_or(|f| f[c].is_none()))
                .collect();
            match groups.iter_mut().find(|(g, _)| *g == free) {
                Some((_, coords)) => coords.push(c),
                None => groups.push((free, vec![c])),
            }
        }
        let values: Vec<P> = fixed
            .iter()
            .map(|f| P::from_coords(|c| f.as_ref().and_then(|f| f[c]).unwrap_or_else(T::zero)))
            .collect();
        let mut out = vec![P::origin(); n];
        for (free, coords) in &groups {
            let solution = self.solve_group(free, &values)?;
            for (i, (o, s)) in out.iter_mut().zip(&solution).enumerate() {
                let source = if free[i] { s } else { &values[i] };
                for &c in coords {
                    o.set_coord(c, source.coord(c));
                }
            }
        }
        Ok(out)
    }

    fn validate(&self) -> Result<()> {
        self.validate_with(self.params)
    }

    /// With the `parallel` feature and at least [`PARALLEL_MIN_POINTS`] points: whether
    /// every point is finite and the parameters are non-decreasing inside the domain, checked
    /// in chunks on every core. `false` otherwise (and when a check fails), so that the
    /// sequential checks run and name the first bad entry.
    #[allow(clippy::unused_self, unused_variables)]
    fn data_valid_on_every_core(&self, params: &[T]) -> bool {
        #[cfg(feature = "parallel")]
        if params.len() >= PARALLEL_MIN_POINTS {
            return parallel::data_valid(&self.knots, params, self.points);
        }
        false
    }

    /// [`LeastSquares::validate`] with other parameters.
    fn validate_with(&self, params: &[T]) -> Result<()> {
        let m = self.points.len();
        if params.len() != m {
            return Err(Error::new(
                ErrorKind::InvalidLength,
                format!("{} parameters for {m} points", params.len()),
            ));
        }
        if !self.data_valid_on_every_core(params) {
            // Sequentially (also when a parallel check failed): the error names the first
            // bad entry.
            check_points(self.points, 1, "least squares")?;
            check_params(params)?;
            for (j, &u) in params.iter().enumerate() {
                self.knots
                    .check_param(u)
                    .map_err(|e| e.context(format_args!("parameter {j}")))?;
            }
        }
        if let Some(w) = self.weights {
            check_weights(w, m)?;
        }
        check_non_negative(self.smoothing, "the smoothing weight")?;
        let n = self.knots.num_basis();
        for &(i, v) in &self.fixed_points {
            if i >= n || !v.all_finite() {
                return Err(Error::new(
                    if i >= n {
                        ErrorKind::IndexOutOfRange
                    } else {
                        ErrorKind::NonFinite
                    },
                    format!(
                        "cannot fix control point {i} of {n} (index out of range or value not finite)"
                    ),
                )
                .with_index(i));
            }
        }
        for &(i, c, v) in &self.fixed_coords {
            if i >= n || c >= P::DIM || !v.is_finite() {
                return Err(Error::new(
                    if i >= n || c >= P::DIM {
                        ErrorKind::IndexOutOfRange
                    } else {
                        ErrorKind::NonFinite
                    },
                    format!(
                        "cannot fix coordinate {c} of control point {i} ({n} control points of dimension {}; value must be finite)",
                        P::DIM
                    ),
                )
                .with_index(i));
            }
        }
        if self.pin_ends {
            let (a, b) = self.knots.domain();
            if !(self.knots.is_clamped() && params[0] == a && params[m - 1] == b) {
                return Err(Error::new(
                    ErrorKind::InvalidArgument,
                    "pinned ends need a clamped knot vector and the first and last parameters at the ends of its domain",
                ));
            }
        }
        Ok(())
    }

    /// The normal equations $A^T W^2 A\\, c = A^T W^2 Q$ of the problem (with the smoothing
    /// term), assembled but not solved: the quadratic objective
    /// $f_0(c) = \tfrac12 \sum_k w_k^2 \lVert C(\bar u_k) - Q_k \rVert^2 + \tfrac\lambda2 \int \lVert C'' \rVert^2$
    /// for methods that minimise it under other constraints (the selective eraser).
    ///
    /// # Errors
    /// As [`LeastSquares::solve`], except the Schoenberg–Whitney and singular-system errors
    /// (nothing is factored: [`NormalEquations::solve`] reports them);
    /// [`ErrorKind::InvalidArgument`] if control points or coordinates are fixed or the ends
    /// pinned (the normal equations are those of the free problem).
    pub fn normal_equations(&self) -> Result<NormalEquations<T, P>> {
        self.validate()?;
        if self.pin_ends || !self.fixed_points.is_empty() || !self.fixed_coords.is_empty() {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "normal equations are available for problems without fixed control points",
            ));
        }
        let n = self.knots.num_basis();
        let free = vec![true; n];
        let values = vec![P::origin(); n];
        // Assembled, not solved: the Schoenberg–Whitney conditions are the solver's concern.
        let plain = Self {
            method: LsqMethod::NormalEquations,
            check_sw: false,
            ..self.clone()
        };
        let (matrix, rhs) = match plain.assemble_group(&free, &values)? {
            (Sink::Normal(matrix, rhs), _) => (matrix, rhs),
            (Sink::Qr(_), _) => unreachable!("normal equations requested"),
        };
        let half: T = cast(0.5);
        let constant = weighted_square_sum(self.points, self.weights) * half;
        Ok(NormalEquations {
            knots: self.knots.clone(),
            matrix,
            rhs,
            constant,
        })
    }

    /// Solves for the control points flagged in `free`, the others taking `values`.
    fn solve_group(&self, free: &[bool], values: &[P]) -> Result<Vec<P>> {
        let n = self.knots.num_basis();
        if !free.iter().any(|&f| f) {
            return Ok(values.to_vec());
        }
        let (sink, column) = self.assemble_group(free, values)?;
        let names: Vec<usize> = (0..n).filter(|&i| free[i]).collect();
        let what = |c: usize| format!("control point {}", names[c]);
        let solution = match sink {
            Sink::Normal(mut matrix, mut rhs) => {
                matrix.factor(&what)?;
                matrix.solve(&mut rhs);
                rhs
            }
            Sink::Qr(qr) => qr.solve(&what)?,
        };
        Ok((0..n)
            .map(|i| {
                if free[i] {
                    solution[column[i]]
                } else {
                    values[i]
                }
            })
            .collect())
    }
}

/// Least-squares approximation of points by a curve of degree `p` with `num_control`
/// control points: parameters by `parametrization` (named choices on `[0, 1]`), knots by
/// `knots` (averaging means The NURBS Book (9.68) when there are fewer control points than
/// points), normal equations, ends free.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::{KnotChoice, Parametrization, approximate};
/// let points: Vec<Vector2<f64>> = (0..=40)
///     .map(|k| {
///         let t = k as f64 / 40.0 * std::f64::consts::PI;
///         Vector2::new(t.cos(), t.sin())
///     })
///     .collect();
/// let fit = approximate(&points, 3, 8, &Parametrization::Chordal, &KnotChoice::NurbsBook)?;
/// assert!(fit.deviation.max < 1e-3);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] unless `p < num_control ≤` the number of points; the errors
/// of [`parametrize`], of the knot choice and of [`LeastSquares::solve`].
pub fn approximate<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    degree: usize,
    num_control: usize,
    parametrization: &Parametrization<T>,
    knots: &KnotChoice<T>,
) -> Result<CurveFit<T, P>> {
    check_degree(degree)?;
    check_control_count(degree, num_control, points.len())?;
    let params = parametrize(points, parametrization)?;
    let knot_vector = knots_for(knots, degree, num_control, &params)?;
    LeastSquares::new(points, &params, knot_vector).solve()
}

/// $\sum_k w_k^2 |q_k|^2$ (weights 1 when absent): with the `parallel` feature and at least
/// [`PARALLEL_MIN_POINTS`] points, in chunks on every core summed in chunk order.
fn weighted_square_sum<T: Scalar, P: ControlPoint<T>>(points: &[P], weights: Option<&[T]>) -> T {
    #[cfg(feature = "parallel")]
    if points.len() >= PARALLEL_MIN_POINTS {
        return parallel::weighted_square_sum(points, weights, weighted_square_sum_of);
    }
    weighted_square_sum_of(points, weights)
}

/// [`weighted_square_sum`] in one pass.
pub(crate) fn weighted_square_sum_of<T: Scalar, P: ControlPoint<T>>(
    points: &[P],
    weights: Option<&[T]>,
) -> T {
    points
        .iter()
        .enumerate()
        .map(|(k, q)| {
            let w = weights.map_or_else(T::one, |w| w[k]);
            w * w * q.length_squared()
        })
        .fold(T::zero(), |a, b| a + b)
}
