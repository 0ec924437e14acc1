//! Surfaces through curves: skinning (lofting) through sections, Gordon surfaces through a
//! network of curves (The NURBS Book §10.3, §10.5).

use crate::interpolate::interpolate_with_knots;
use crate::params::{Parametrization, check_degree};
use crate::project::closest_point;
use crate::surface::surface_grid_params;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, to_f64};
use spline_geom::{BSpline, Surface, boolean_sum, compatible_curves};

/// A surface skinned through section curves, with the parameter of each section.
#[derive(Clone, Debug, PartialEq)]
pub struct Skinned<T, P> {
    /// The surface: `u` runs along the sections, `v` across them; $S(u, v_k)$ is section
    /// `k`.
    pub surface: Surface<T, P>,
    /// The parameters $v_k$ of the sections.
    pub params: Vec<T>,
}

/// The surface through the section curves $C_0, …, C_{K-1}$ (skinning, lofting; The NURBS
/// Book §10.3): the sections are made compatible ([`compatible_curves`]: the highest
/// degree, the domain of the first, merged knots), then each column of their control
/// points $P_{i,0}, …, P_{i,K-1}$ is interpolated in `v` at the parameters $v_k$ on
/// averaging knots of degree `min(degree_v, K − 1)`. The surface reproduces every section
/// exactly: $S(u, v_k) = C_k(u)$.
///
/// Parameters: given (strictly increasing), or by default the chord lengths between
/// consecutive sections averaged over the columns of control points, on `[0, 1]`. Any
/// control-point type works: sections with [`spline_geom::Homogeneous`] points skin NURBS
/// curves (the weights are interpolated with the points).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::skin;
/// use spline_geom::BSpline;
/// let section = |z: f64, r: f64| BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector3::new(-r, 0.0, z), Vector3::new(0.0, r, z), Vector3::new(r, 0.0, z)]);
/// let sections = [section(0.0, 1.0)?, section(1.0, 2.0)?, section(3.0, 1.5)?];
/// let skinned = skin(&sections, 2, None)?;
/// for (c, &v) in sections.iter().zip(&skinned.params) {
///     assert!((skinned.surface.eval(0.3, v)? - c.eval(0.3)?).norm() < 1e-14);
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] with fewer than two sections; [`ErrorKind::DegreeTooHigh`];
/// [`ErrorKind::InvalidLength`], [`ErrorKind::UnsortedKnots`] or [`ErrorKind::NonFinite`]
/// for given parameters that are not one strictly increasing finite value per section;
/// [`ErrorKind::DegenerateGeometry`] when all sections coincide (no chord lengths).
pub fn skin<T: Scalar, P: ControlPoint<T>>(
    sections: &[BSpline<T, P>],
    degree_v: usize,
    params: Option<&[T]>,
) -> Result<Skinned<T, P>> {
    if sections.len() < 2 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "skinning needs at least two sections, got {}",
                sections.len()
            ),
        ));
    }
    check_degree(degree_v)?;
    if degree_v == 0 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "skinning needs a degree of at least 1 across the sections",
        )
        .with_value(0.0)
        .with_interval(1.0, f64::INFINITY));
    }
    let same = compatible_curves(sections)?;
    let v = section_params(&same, params)?;
    let kv = KnotVector::averaging(degree_v.min(sections.len() - 1), &v)?;
    let surface = skin_on(&same, &v, &kv)?;
    Ok(Skinned { surface, params: v })
}

/// The parameters of compatible sections: given (checked), or averaged chord lengths.
fn section_params<T: Scalar, P: ControlPoint<T>>(
    same: &[BSpline<T, P>],
    given: Option<&[T]>,
) -> Result<Vec<T>> {
    let k = same.len();
    let n = same[0].len();
    if let Some(v) = given {
        if v.len() != k {
            return Err(Error::invalid_length("section parameters", k, v.len()));
        }
        if let Some(j) = v.iter().position(|x| !x.is_finite()) {
            return Err(Error::non_finite(format_args!("section parameter {j}")));
        }
        if let Some(j) = v.windows(2).position(|w| !(w[0] < w[1])) {
            return Err(Error::new(
                ErrorKind::UnsortedKnots,
                format!(
                    "section parameters must increase strictly: {} then {}",
                    to_f64(v[j]),
                    to_f64(v[j + 1])
                ),
            ));
        }
        return Ok(v.to_vec());
    }
    let grid: Vec<P> = (0..n)
        .flat_map(|i| same.iter().map(move |c| c.control_points()[i]))
        .collect();
    let (_, v) = surface_grid_params(
        &grid,
        n,
        k,
        &Parametrization::Uniform,
        &Parametrization::Chordal,
    )
    .map_err(|e| e.context("section parameters"))?;
    Ok(v)
}

/// The net through compatible sections at the parameters `v` on the knots `kv`.
fn skin_on<T: Scalar, P: ControlPoint<T>>(
    same: &[BSpline<T, P>],
    v: &[T],
    kv: &KnotVector<T>,
) -> Result<Surface<T, P>> {
    let n = same[0].len();
    let nv = kv.num_basis();
    let mut net = vec![P::origin(); n * nv];
    for i in 0..n {
        let column: Vec<P> = same.iter().map(|c| c.control_points()[i]).collect();
        let line = interpolate_with_knots(kv, v, &column)
            .map_err(|e| e.context(format_args!("control point {i} of the sections")))?;
        net[i * nv..(i + 1) * nv].copy_from_slice(line.control_points());
    }
    Ok(Surface::new_unchecked(
        same[0].knots().clone(),
        kv.clone(),
        net,
    ))
}

/// A Gordon surface through a network of curves, with the parameters of the crossings.
#[derive(Clone, Debug, PartialEq)]
pub struct Gordon<T, P> {
    /// The surface: $S(u, v_l)$ is u-curve `l`, $S(u_k, v)$ is v-curve `k`.
    pub surface: Surface<T, P>,
    /// The parameters $u_k$ of the v-curves.
    pub params_u: Vec<T>,
    /// The parameters $v_l$ of the u-curves.
    pub params_v: Vec<T>,
    /// The largest distance between a u-curve and a v-curve at their crossing (how far the
    /// network is from intersecting exactly).
    pub crossing_gap: T,
}

/// The Gordon surface (The NURBS Book §10.5) through a network: `u_curves[l]` runs along
/// `u` and is crossed by every `v_curves[k]`, which runs along `v`.
///
/// $$ S = L_u + L_v - T, $$
///
/// the skin of the u-curves across `v` ([`skin`]), the skin of the v-curves across `u`,
/// minus the surface interpolating the crossing points ([`boolean_sum`]: all three on the
/// same knots in each direction, made compatible), so `S` reproduces every curve of the
/// network.
///
/// The crossings are found from the first curves: $u_k$ is the parameter on `u_curves[0]`
/// of its point closest to the start of `v_curves[k]`, and $v_l$ that on `v_curves[0]` of
/// the point closest to the start of `u_curves[l]` (so the first curve of each family is a
/// boundary, where the other family starts). Every crossing must then agree within
/// `tolerance`: $\lVert C^u_l(u_k) - C^v_k(v_l) \rVert \le$ `tolerance`.
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] with fewer than two curves in a family;
/// [`ErrorKind::DegenerateGeometry`] when the curves do not cross within the tolerance
/// (the message names the pair and the gap), or two crossings have the same parameter;
/// [`ErrorKind::InvalidTolerance`]; the errors of [`skin`].
pub fn gordon<T: Scalar, P: ControlPoint<T>>(
    u_curves: &[BSpline<T, P>],
    v_curves: &[BSpline<T, P>],
    (degree_u, degree_v): (usize, usize),
    tolerance: T,
) -> Result<Gordon<T, P>> {
    if u_curves.len() < 2 || v_curves.len() < 2 {
        return Err(Error::new(
            ErrorKind::TooFewPoints,
            format!(
                "a Gordon surface needs at least two curves in each family, got {} and {}",
                u_curves.len(),
                v_curves.len()
            ),
        ));
    }
    if !(tolerance >= T::zero() && tolerance.is_finite()) {
        return Err(Error::invalid_tolerance(
            "the crossing tolerance",
            "finite and non-negative",
            to_f64(tolerance),
        ));
    }
    check_degree(degree_u)?;
    check_degree(degree_v)?;
    if degree_u == 0 || degree_v == 0 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "a Gordon surface needs degrees of at least 1",
        )
        .with_value(0.0)
        .with_interval(1.0, f64::INFINITY));
    }
    let us = compatible_curves(u_curves)?;
    let vs = compatible_curves(v_curves)?;
    let start = |c: &BSpline<T, P>| c.control_points()[0];
    let crossing = |family: &[BSpline<T, P>], others: &[BSpline<T, P>]| -> Result<Vec<T>> {
        let mut params = Vec::with_capacity(others.len());
        for c in others {
            params.push(closest_point(&family[0], start(c))?.param);
        }
        if let Some(j) = params.windows(2).position(|w| !(w[0] < w[1])) {
            return Err(Error::new(
                ErrorKind::DegenerateGeometry,
                format!(
                    "curves {j} and {} of the network start at parameters {} and {} of the first curve of the other family: they must cross it in increasing order",
                    j + 1,
                    to_f64(params[j]),
                    to_f64(params[j + 1])
                ),
            ));
        }
        Ok(params)
    };
    let uk = crossing(&us, &vs)?;
    let vl = crossing(&vs, &us)?;
    // The crossing points, checked from both families.
    let (m, n) = (uk.len(), vl.len());
    let mut grid = Vec::with_capacity(m * n);
    let mut gap = T::zero();
    for (k, &u) in uk.iter().enumerate() {
        for (l, &v) in vl.iter().enumerate() {
            let a = us[l].eval(u)?;
            let b = vs[k].eval(v)?;
            let d = (a - b).length();
            if !(d <= tolerance) {
                return Err(Error::new(
                    ErrorKind::DegenerateGeometry,
                    format!(
                        "u-curve {l} and v-curve {k} do not cross: gap {} at u = {}, v = {} (tolerance {})",
                        to_f64(d),
                        to_f64(u),
                        to_f64(v),
                        to_f64(tolerance)
                    ),
                )
                .with_value(to_f64(d)));
            }
            gap = gap.max(d);
            grid.push(a);
        }
    }
    let ku = KnotVector::averaging(degree_u.min(m - 1), &uk)?;
    let kv = KnotVector::averaging(degree_v.min(n - 1), &vl)?;
    let lu = skin_on(&us, &vl, &kv)?;
    let lv = skin_on(&vs, &uk, &ku)?.transposed();
    // The tensor-product interpolant of the crossings, row by row then column by column.
    let rows: Vec<BSpline<T, P>> = (0..m)
        .map(|k| interpolate_with_knots(&kv, &vl, &grid[k * n..(k + 1) * n]))
        .collect::<Result<_>>()?;
    let tensor = skin_on(&rows, &uk, &ku)?.transposed();
    Ok(Gordon {
        surface: boolean_sum(lu, lv, tensor)?,
        params_u: uk,
        params_v: vl,
        crossing_gap: gap,
    })
}
