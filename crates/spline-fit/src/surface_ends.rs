//! Surface interpolation of a grid with first partial derivatives imposed along the
//! boundary (The NURBS Book §9.2.5, by two passes of curve interpolation with end
//! derivatives).

use crate::interpolate::{InterpolationOptions, interpolate};
use crate::params::{KnotChoice, Parametrization};
use crate::report::Deviation;
use crate::surface::{SurfaceFit, surface_grid_params};
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar};
use spline_geom::Surface;

/// First partial derivatives imposed on the boundary of an interpolating surface
/// ([`interpolate_surface_with_derivatives`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceEnds<P> {
    /// $\partial S/\partial u$ at $(u_0, v_l)$ and at $(u_{m}, v_l)$, one per grid column.
    pub du: Option<(Vec<P>, Vec<P>)>,
    /// $\partial S/\partial v$ at $(u_k, v_0)$ and at $(u_k, v_{n})$, one per grid row.
    pub dv: Option<(Vec<P>, Vec<P>)>,
    /// The twists $\partial^2 S/\partial u \partial v$ at the corners `(u_0, v_0)`,
    /// `(u_m, v_0)`, `(u_0, v_n)`, `(u_m, v_n)`: needed when both `du` and `dv` are given.
    pub twists: Option<[P; 4]>,
}

impl<P> Default for SurfaceEnds<P> {
    fn default() -> Self {
        Self {
            du: None,
            dv: None,
            twists: None,
        }
    }
}

/// The surface of degrees `(p, q)` through the grid $Q_{kl}$ (`rows × cols`, row-major, `k`
/// along `u`) with the partial derivatives of `ends` on the boundary:
/// $S(u_k, v_l) = Q_{kl}$, $S_u(u_0, v_l) = D^u_{0,l}$, $S_u(u_m, v_l) = D^u_{m,l}$,
/// $S_v(u_k, v_0) = D^v_{k,0}$, $S_v(u_k, v_n) = D^v_{k,n}$, and with both, the four corner
/// twists. Each given pair of derivative rows adds two control points in its direction.
///
/// Pass 1 interpolates every column along `u` with its end derivatives, and the `v`
/// derivatives of the first and last rows along `u` with the twists as end derivatives;
/// pass 2 interpolates every row of control points along `v` with the derivative control
/// points as end derivatives. Parameters by [`surface_grid_params`], knots by averaging
/// over the parameters with doubled ends where a derivative is given.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::{Parametrization, SurfaceEnds, interpolate_surface_with_derivatives};
/// // z = x² y on a 4 × 3 grid of [0, 1]², with the exact ∂S/∂u along u = 0 and u = 1.
/// let f = |x: f64, y: f64| Vector3::new(x, y, x * x * y);
/// let (xs, ys) = ([0.0, 0.3, 0.7, 1.0], [0.0, 0.5, 1.0]);
/// let grid: Vec<_> = xs.iter().flat_map(|&x| ys.iter().map(move |&y| f(x, y))).collect();
/// let du = |x: f64| ys.iter().map(|&y| Vector3::new(1.0, 0.0, 2.0 * x * y)).collect::<Vec<_>>();
/// let ends = SurfaceEnds { du: Some((du(0.0), du(1.0))), ..SurfaceEnds::default() };
/// let given = |v: &[f64]| Parametrization::Given(v.to_vec());
/// let fit = interpolate_surface_with_derivatives(&grid, 4, 3, (3, 2), &given(&xs), &given(&ys), &ends)?;
/// let d = fit.surface.derivatives(0.0, 0.5, 1)?;
/// assert!((d[1][0] - Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-13);
/// assert!(fit.deviation.max < 1e-14);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidLength`] for derivative rows of the wrong length;
/// [`ErrorKind::InvalidArgument`] when `du` and `dv` are both given without twists (or
/// twists without both); [`ErrorKind::NonFinite`]; the errors of
/// [`crate::interpolate_surface`] and [`crate::interpolate`].
///
/// # Panics
/// Never: a valid grid has at least one control row.
pub fn interpolate_surface_with_derivatives<T: Scalar, P: ControlPoint<T>>(
    grid: &[P],
    rows: usize,
    cols: usize,
    (degree_u, degree_v): (usize, usize),
    param_u: &Parametrization<T>,
    param_v: &Parametrization<T>,
    ends: &SurfaceEnds<P>,
) -> Result<SurfaceFit<T, P>> {
    let (u, v) = surface_grid_params(grid, rows, cols, param_u, param_v)?;
    for (name, pair, len) in [("du", &ends.du, cols), ("dv", &ends.dv, rows)] {
        if let Some((a, b)) = pair {
            for (which, d) in [("start", a), ("end", b)] {
                if d.len() != len {
                    return Err(Error::invalid_length(
                        format_args!("{name} at the {which}"),
                        len,
                        d.len(),
                    ));
                }
                if let Some(k) = d.iter().position(|p| !p.all_finite()) {
                    return Err(Error::non_finite(format_args!(
                        "{name} at the {which}, entry {k}"
                    )));
                }
            }
        }
    }
    let both = ends.du.is_some() && ends.dv.is_some();
    if both != ends.twists.is_some() {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            if both {
                "with derivatives along both directions the four corner twists are needed"
            } else {
                "corner twists need derivatives along both directions"
            },
        ));
    }
    if let Some(t) = &ends.twists {
        if t.iter().any(|p| !p.all_finite()) {
            return Err(Error::non_finite("a corner twist"));
        }
    }
    let line = |params: &[T], degree: usize, points: &[P], ends: Option<(P, P)>| {
        interpolate(
            points,
            degree,
            &InterpolationOptions {
                parametrization: Parametrization::Given(params.to_vec()),
                knots: KnotChoice::Averaging,
                start_derivative: ends.map(|e| e.0),
                end_derivative: ends.map(|e| e.1),
            },
        )
        .map(|fit| fit.curve)
    };
    // Pass 1: along u, every column with its u derivatives.
    let mut columns = Vec::with_capacity(cols);
    for l in 0..cols {
        let column: Vec<P> = (0..rows).map(|k| grid[k * cols + l]).collect();
        let d = ends.du.as_ref().map(|(a, b)| (a[l], b[l]));
        columns.push(
            line(&u, degree_u, &column, d)
                .map_err(|e| e.context(format_args!("grid column {l}")))?,
        );
    }
    let ku = columns[0].knots().clone();
    let nu = ku.num_basis();
    // The v derivatives along u (the twists at their ends).
    let dv_lines = match &ends.dv {
        Some((a, b)) => {
            let tw = ends.twists.map(|t| ((t[0], t[1]), (t[2], t[3])));
            let start = line(&u, degree_u, a, tw.map(|t| t.0))?;
            let end = line(&u, degree_u, b, tw.map(|t| t.1))?;
            Some((start, end))
        }
        None => None,
    };
    // Pass 2: along v, every row of control points.
    let mut net = Vec::new();
    let mut kv = None;
    for i in 0..nu {
        let row: Vec<P> = columns.iter().map(|c| c.control_points()[i]).collect();
        let d = dv_lines
            .as_ref()
            .map(|(a, b)| (a.control_points()[i], b.control_points()[i]));
        let curve =
            line(&v, degree_v, &row, d).map_err(|e| e.context(format_args!("control row {i}")))?;
        kv.get_or_insert_with(|| curve.knots().clone());
        net.extend_from_slice(curve.control_points());
    }
    let kv = kv.expect("at least one control row");
    let surface = Surface::new_unchecked(ku, kv, net);
    let mut distances = Vec::with_capacity(grid.len());
    for (k, &uk) in u.iter().enumerate() {
        for (l, &vl) in v.iter().enumerate() {
            distances.push((surface.eval(uk, vl)? - grid[k * cols + l]).length());
        }
    }
    Ok(SurfaceFit {
        surface,
        params_u: u,
        params_v: v,
        deviation: Deviation::from_distances(distances),
    })
}
