//! Tensor-product surfaces: interpolation of grids by two passes (seed 004 §7), least
//! squares from grids and from scattered points.
//!
//! Results are [`spline_geom::Surface`]s (two knot vectors and a row-major control net,
//! `i` along `u`) with the parameters of the data and the deviation.

// Index loops mirror the formulas (basis index ↔ control-point index).
#![allow(clippy::needless_range_loop)]

use crate::interpolate::interpolate_with_knots;
use crate::lsq::{LeastSquares, scattered_normal_equations};
use crate::params::{KnotChoice, Parametrization, check_given, knots_for, parametrize};
use crate::params::{check_degree, check_non_negative};
use crate::report::Deviation;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, from_count};
use spline_geom::Surface;

/// A fitted tensor-product surface $S(u, v) = \sum_i \sum_j N_i(u) N_j(v) P_{ij}$ with the
/// parameters of the data and its deviation from them.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceFit<T, P> {
    /// The surface: knots in `u` (index `i`) and `v` (index `j`), the control net row-major
    /// ($P_{ij}$ is `control_points()[i * n_v + j]`, the exchange format's
    /// `control_points[i][j]`).
    pub surface: Surface<T, P>,
    /// Grid fits: the `u` parameter of each grid row. Scattered fits: the `u` parameter of
    /// each point.
    pub params_u: Vec<T>,
    /// Grid fits: the `v` parameter of each grid column. Scattered fits: the `v` parameter of
    /// each point.
    pub params_v: Vec<T>,
    /// Distances of the data from the surface (grid points in row-major order).
    pub deviation: Deviation<T>,
}

fn check_grid<T: Scalar, P: ControlPoint<T>>(grid: &[P], rows: usize, cols: usize) -> Result<()> {
    if rows * cols != grid.len() || rows < 2 || cols < 2 {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "a grid of {rows} × {cols} points (at least 2 × 2) needs {} points, got {}",
                rows * cols,
                grid.len()
            ),
        ));
    }
    if let Some(k) = grid.iter().position(|p| !p.all_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("grid point ({}, {}) is not finite", k / cols, k % cols),
        ));
    }
    Ok(())
}

/// Checks the degrees and the grid of a grid fit, then `enough` (the numbers of points and
/// control points agree with the degrees); `shortfall` describes the problem otherwise.
fn checked_grid_params<T: Scalar, P: ControlPoint<T>>(
    grid: &[P],
    (rows, cols): (usize, usize),
    (degree_u, degree_v): (usize, usize),
    (param_u, param_v): (&Parametrization<T>, &Parametrization<T>),
    shortfall: Option<String>,
) -> Result<(Vec<T>, Vec<T>)> {
    check_degree(degree_u)?;
    check_degree(degree_v)?;
    check_grid(grid, rows, cols)?;
    if let Some(message) = shortfall {
        return Err(Error::new(ErrorKind::TooFewPoints, message));
    }
    surface_grid_params(grid, rows, cols, param_u, param_v)
}

/// Parameters of a grid $Q_{kl}$ (`rows × cols`, row-major, `k` along `u`) by The NURBS
/// Book A9.3: the `u` parameters average those of the columns $Q_{\cdot l}$, the `v`
/// parameters those of the rows, skipping degenerate lines (all points equal, as at a
/// pole). Given parameters are checked and returned.
///
/// # Errors
/// [`ErrorKind::InvalidLength`] for a malformed grid or wrong number of given parameters;
/// [`ErrorKind::NonFinite`]; [`ErrorKind::DegenerateGeometry`] when every line of a
/// direction is degenerate or when a line has coincident consecutive points under chordal
/// or centripetal parameters.
pub fn surface_grid_params<T: Scalar, P: ControlPoint<T>>(
    grid: &[P],
    rows: usize,
    cols: usize,
    param_u: &Parametrization<T>,
    param_v: &Parametrization<T>,
) -> Result<(Vec<T>, Vec<T>)> {
    check_grid(grid, rows, cols)?;
    let averaged = |count: usize,
                    lines: usize,
                    line: &dyn Fn(usize) -> Vec<P>,
                    kind: &Parametrization<T>|
     -> Result<Vec<T>> {
        if let Parametrization::Given(u) = kind {
            check_given(u, count)?;
            return Ok(u.clone());
        }
        let mut sum = vec![T::zero(); count];
        let mut used = 0usize;
        for l in 0..lines {
            let pts = line(l);
            if pts.windows(2).all(|w| w[0] == w[1]) {
                continue;
            }
            let params = parametrize(&pts, kind)?;
            for (s, u) in sum.iter_mut().zip(params) {
                *s += u;
            }
            used += 1;
        }
        if used == 0 {
            return Err(Error::new(
                ErrorKind::DegenerateGeometry,
                "every grid line of one direction is a single point",
            ));
        }
        let inv = T::one() / from_count::<T>(used);
        let mut out: Vec<T> = sum.into_iter().map(|s| s * inv).collect();
        out[0] = T::zero();
        out[count - 1] = T::one();
        Ok(out)
    };
    let column = |l: usize| (0..rows).map(|k| grid[k * cols + l]).collect::<Vec<P>>();
    let row = |k: usize| grid[k * cols..(k + 1) * cols].to_vec();
    let u = averaged(rows, cols, &column, param_u)?;
    let v = averaged(cols, rows, &row, param_v)?;
    Ok((u, v))
}

/// With the `parallel` feature and at least [`crate::PARALLEL_MIN_POINTS`] pairs: whether
/// every pair lies in the domains, checked in chunks on every core; `false` otherwise (and
/// when a check fails), so that the sequential check runs and names the first bad pair.
#[allow(unused_variables)]
fn params_inside_on_every_core<T: Scalar>(
    params: &[(T, T)],
    knots_u: &KnotVector<T>,
    knots_v: &KnotVector<T>,
) -> bool {
    #[cfg(feature = "parallel")]
    if params.len() >= crate::PARALLEL_MIN_POINTS {
        use rayon::prelude::*;
        let ((a, b), (c, d)) = (knots_u.domain(), knots_v.domain());
        let chunk = crate::lsq::chunk_len(params.len());
        // The comparisons fail for NaN too.
        return params.par_chunks(chunk).all(|pairs| {
            pairs
                .iter()
                .all(|&(u, v)| u >= a && u <= b && v >= c && v <= d)
        });
    }
    false
}

fn grid_deviation<T: Scalar, P: ControlPoint<T>>(
    surface: &Surface<T, P>,
    grid: &[P],
    u: &[T],
    v: &[T],
) -> Result<Deviation<T>> {
    // The grid kernel (iso-curves along v, then one combination per point), not one
    // evaluation per point.
    let mut evaluated = vec![P::origin(); grid.len()];
    surface.eval_grid_into(u, v, &mut evaluated)?;
    let d = evaluated
        .iter()
        .zip(grid)
        .map(|(s, g)| (*s - *g).length())
        .collect();
    Ok(Deviation::from_distances(d))
}

/// The surface of degrees `(p, q)` through the grid $Q_{kl}$ (`rows × cols` points,
/// row-major, `k` along `u`), by the two passes of seed 004 §7: curves $R_l$ through each
/// column along `u`, then curves through the rows of their control points along `v`.
/// Knots average the parameters (seed 004 (7.6)) in each direction; parameters by
/// [`surface_grid_params`]. Each pass solves banded systems in `O(n p²)` per line.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::{Parametrization, interpolate_surface};
/// let grid: Vec<Vector3<f64>> = (0..4)
///     .flat_map(|k| (0..5).map(move |l| {
///         let (x, y) = (k as f64, l as f64);
///         Vector3::new(x, y, (x * 0.5).sin() * (y * 0.4).cos())
///     }))
///     .collect();
/// let fit = interpolate_surface(&grid, 4, 5, 3, 3, &Parametrization::Chordal, &Parametrization::Chordal)?;
/// assert!(fit.deviation.max < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] unless `rows > p` and `cols > q`; the errors of
/// [`surface_grid_params`] and [`crate::interpolate_with_knots`].
pub fn interpolate_surface<T: Scalar, P: ControlPoint<T>>(
    grid: &[P],
    rows: usize,
    cols: usize,
    degree_u: usize,
    degree_v: usize,
    param_u: &Parametrization<T>,
    param_v: &Parametrization<T>,
) -> Result<SurfaceFit<T, P>> {
    let (u, v) = checked_grid_params(
        grid,
        (rows, cols),
        (degree_u, degree_v),
        (param_u, param_v),
        (rows <= degree_u || cols <= degree_v).then(|| {
            format!(
                "a surface of degrees ({degree_u}, {degree_v}) needs at least {} × {} points, got {rows} × {cols}",
                degree_u + 1,
                degree_v + 1
            )
        }),
    )?;
    let ku = KnotVector::averaging(degree_u, &u)?;
    let kv = KnotVector::averaging(degree_v, &v)?;
    two_passes(grid, rows, cols, &u, &v, &ku, &kv, &|k, params, pts| {
        Ok(interpolate_with_knots(k, params, pts)?.into_parts().1)
    })
}

/// Fits the control points of one grid line on the given knots.
type LineSolver<'a, T, P> = &'a (dyn Fn(&KnotVector<T>, &[T], &[P]) -> Result<Vec<P>> + Sync);

/// `line(0), …, line(count − 1)`, the first error in that order. With the `parallel`
/// feature, for grids of at least [`crate::PARALLEL_MIN_POINTS`] points, the lines are
/// solved on every core: they are independent, so the results are the same bit for bit.
fn each_line<P: Send>(
    count: usize,
    grid_points: usize,
    line: &(dyn Fn(usize) -> Result<Vec<P>> + Sync),
) -> Result<Vec<Vec<P>>> {
    #[cfg(feature = "parallel")]
    if grid_points >= crate::PARALLEL_MIN_POINTS && rayon::current_num_threads() > 1 {
        use rayon::prelude::*;
        let lines: Vec<Result<Vec<P>>> = (0..count).into_par_iter().map(line).collect();
        return lines.into_iter().collect();
    }
    let _ = grid_points;
    (0..count).map(line).collect()
}

#[allow(clippy::too_many_arguments)]
fn two_passes<T: Scalar, P: ControlPoint<T>>(
    grid: &[P],
    rows: usize,
    cols: usize,
    u: &[T],
    v: &[T],
    ku: &KnotVector<T>,
    kv: &KnotVector<T>,
    solve: LineSolver<'_, T, P>,
) -> Result<SurfaceFit<T, P>> {
    let (nu, nv) = (ku.num_basis(), kv.num_basis());
    // Pass 1: along u for every column l: R[i][l].
    let mut r = vec![P::origin(); nu * cols];
    let columns = each_line(cols, grid.len(), &|l| {
        let column: Vec<P> = (0..rows).map(|k| grid[k * cols + l]).collect();
        solve(ku, u, &column).map_err(|e| e.context(format_args!("grid column {l}")))
    })?;
    for (l, ctrl) in columns.into_iter().enumerate() {
        for (i, c) in ctrl.into_iter().enumerate() {
            r[i * cols + l] = c;
        }
    }
    // Pass 2: along v for every row i of R.
    let mut net = vec![P::origin(); nu * nv];
    let control_rows = each_line(nu, grid.len(), &|i| {
        solve(kv, v, &r[i * cols..(i + 1) * cols])
            .map_err(|e| e.context(format_args!("control row {i}")))
    })?;
    for (i, ctrl) in control_rows.into_iter().enumerate() {
        net[i * nv..(i + 1) * nv].copy_from_slice(&ctrl);
    }
    let surface = Surface::new_unchecked(ku.clone(), kv.clone(), net);
    let deviation = grid_deviation(&surface, grid, u, v)?;
    Ok(SurfaceFit {
        surface,
        params_u: u.to_vec(),
        params_v: v.to_vec(),
        deviation,
    })
}

/// Least-squares surface of degrees `(p, q)` with `num_u × num_v` control points for a grid
/// of `rows × cols` points: with the product structure of the data the least-squares
/// problem separates, and two passes of curve least squares (along `u`, then along `v`)
/// give its exact solution. Knots by The NURBS Book (9.68) on the averaged parameters.
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] unless `p < num_u ≤ rows` and `q < num_v ≤ cols`; the errors
/// of [`surface_grid_params`] and [`LeastSquares::solve`].
#[allow(clippy::too_many_arguments)]
pub fn approximate_surface_grid<T: Scalar, P: ControlPoint<T>>(
    grid: &[P],
    rows: usize,
    cols: usize,
    degree_u: usize,
    degree_v: usize,
    num_u: usize,
    num_v: usize,
    param_u: &Parametrization<T>,
    param_v: &Parametrization<T>,
) -> Result<SurfaceFit<T, P>> {
    let enough = num_u > degree_u && num_v > degree_v && num_u <= rows && num_v <= cols;
    let (u, v) = checked_grid_params(
        grid,
        (rows, cols),
        (degree_u, degree_v),
        (param_u, param_v),
        (!enough).then(|| {
            format!(
                "{num_u} × {num_v} control points of degrees ({degree_u}, {degree_v}) need {} ≤ num_u ≤ {rows} and {} ≤ num_v ≤ {cols}",
                degree_u + 1,
                degree_v + 1
            )
        }),
    )?;
    let ku = knots_for(&KnotChoice::NurbsBook, degree_u, num_u, &u)?;
    let kv = knots_for(&KnotChoice::NurbsBook, degree_v, num_v, &v)?;
    two_passes(grid, rows, cols, &u, &v, &ku, &kv, &|k, params, pts| {
        LeastSquares::new(pts, params, k.clone()).control_points()
    })
}

/// Least-squares surface on the knots `knots_u × knots_v` for scattered points $Q_k$ with
/// parameters $(u_k, v_k)$: minimises
///
/// $$ \sum_k \lVert S(u_k, v_k) - Q_k \rVert^2
///    + \lambda \iint \lVert S_{uu} \rVert^2 + 2 \lVert S_{uv} \rVert^2 + \lVert S_{vv} \rVert^2 $$
///
/// by banded normal equations in the row-major unknowns (half-bandwidth `p n_v + q`,
/// assembled in `lsq/scattered.rs`) and banded Cholesky; the thin-plate term (exact Gauss–Legendre quadrature on each cell) lets
/// the data leave cells empty when `λ > 0`.
///
/// # Errors
/// [`ErrorKind::InvalidLength`] if parameters and points differ in number;
/// [`ErrorKind::NonFinite`]; [`ErrorKind::OutOfDomain`]; [`ErrorKind::InvalidArgument`] for a
/// negative `λ`; [`ErrorKind::SingularSystem`] naming a control point the data do not
/// determine (add data there or smoothing).
pub fn approximate_surface_scattered<T: Scalar, P: ControlPoint<T>>(
    params: &[(T, T)],
    points: &[P],
    knots_u: &KnotVector<T>,
    knots_v: &KnotVector<T>,
    smoothing: T,
) -> Result<SurfaceFit<T, P>> {
    if params.len() != points.len() || points.is_empty() {
        return Err(Error::new(
            ErrorKind::InvalidLength,
            format!(
                "{} parameter pairs for {} points (need one per point, at least one)",
                params.len(),
                points.len()
            ),
        ));
    }
    if let Some(k) = points.iter().position(|p| !p.all_finite()) {
        return Err(Error::new(
            ErrorKind::NonFinite,
            format!("data point {k} is not finite"),
        ));
    }
    check_non_negative(smoothing, "the smoothing weight")?;
    if !params_inside_on_every_core(params, knots_u, knots_v) {
        // Sequentially (also when a parallel check failed): the error names the first bad
        // pair.
        for (k, &(u, v)) in params.iter().enumerate() {
            knots_u
                .check_param(u)
                .and_then(|()| knots_v.check_param(v))
                .map_err(|e| e.context(format_args!("point {k}")))?;
        }
    }
    let nv = knots_v.num_basis();
    let (mut matrix, mut rhs) =
        scattered_normal_equations(knots_u, knots_v, params, points, smoothing);
    matrix.factor(&|k| format!("control point ({}, {})", k / nv, k % nv))?;
    matrix.solve(&mut rhs);
    let surface = Surface::new_unchecked(knots_u.clone(), knots_v.clone(), rhs);
    let distances = params
        .iter()
        .zip(points)
        .map(|(&(u, v), q)| Ok((surface.eval(u, v)? - *q).length()))
        .collect::<Result<Vec<T>>>()?;
    Ok(SurfaceFit {
        surface,
        params_u: params.iter().map(|&(u, _)| u).collect(),
        params_v: params.iter().map(|&(_, v)| v).collect(),
        deviation: Deviation::from_distances(distances),
    })
}
