//! Common zeros of two bivariate splines (Bernstein subdivision, then Newton's method), and
//! the umbilics of a surface as the common zeros of its umbilic numerators.

use crate::bezier_patch::Patch;
use crate::surface_numerators::{CurvatureNumerators, curvature_numerators};
use crate::zero_set::bezier_patches;
use spline_core::{Error, ErrorKind, KnotVector, Result};
use spline_geom::{NurbsSurface, Surface};

/// Largest number of boxes examined before the zeros are declared not isolated.
const BOX_BUDGET: usize = 200_000;
/// Boxes are halved down to this fraction of their patch in each direction.
const RESOLUTION: f64 = 1e-7;
/// Where one function vanishes identically, more boxes than this at the resolution on one
/// patch mean a curve of zeros of the other.
const LONE_CANDIDATES: usize = 64;

/// The common zeros of two bivariate functions ([`common_zeros`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CommonZeros {
    /// The isolated common zeros `[u, v]`, refined by Newton's method.
    pub points: Vec<[f64; 2]>,
    /// Whether common zeros that are not isolated were met (both functions vanishing on a
    /// patch, or one of them vanishing on a piece where the other has zeros, or more boxes
    /// than the budget): `points` is then incomplete.
    pub not_isolated: bool,
    /// Filled by [`umbilics`] only: umbilics on singular parameter lines (a boundary line of
    /// the domain that the surface collapses to a pole), one `[u, v]` per pole (the middle
    /// of the line), not in `points`. Empty when `not_isolated`.
    pub poles: Vec<[f64; 2]>,
}

/// The isolated common zeros of `a(u, v)` and `b(u, v)` on the same domain: per Bézier patch
/// (both converted to per-patch Bernstein form on the union of their breaks), factors
/// `(u − u₀)` that make both vanish on a whole patch edge are divided out exactly (such a
/// line of common zeros would otherwise stall the subdivision along the edge); then
/// boxes are discarded where either function's coefficients have one strict sign and the
/// others halved (de Casteljau at the midpoint) down to `10⁻⁷` of the patch; the
/// centres of the remaining boxes start Newton's method on the divided functions, and the
/// results are merged.
///
/// ```
/// use spline_core::KnotVector;
/// use spline_geom::Surface;
/// // a = u − 0.3, b = v − 0.6 on [0, 1]²: one common zero.
/// let k = KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0])?;
/// let a = Surface::new(k.clone(), k.clone(), vec![-0.3, -0.3, 0.7, 0.7])?;
/// let b = Surface::new(k.clone(), k, vec![-0.6, 0.4, -0.6, 0.4])?;
/// let z = spline_algebra::common_zeros(&a, &b)?;
/// assert_eq!(z.points.len(), 1);
/// assert!((z.points[0][0] - 0.3).abs() < 1e-14 && (z.points[0][1] - 0.6).abs() < 1e-14);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::SpaceMismatch`] if the domains differ; [`ErrorKind::NonFinite`] for a
/// coefficient that is not finite.
pub fn common_zeros(a: &Surface<f64, f64>, b: &Surface<f64, f64>) -> Result<CommonZeros> {
    if a.domain() != b.domain() {
        return Err(Error::new(
            ErrorKind::SpaceMismatch,
            "common zeros need two functions on the same domain",
        ));
    }
    for (name, f) in [("first", a), ("second", b)] {
        if let Some(i) = f.control_points().iter().position(|c| !c.is_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!("coefficient {i} of the {name} function is not finite"),
            ));
        }
    }
    let merged = |x: Vec<f64>, y: Vec<f64>| {
        let mut m: Vec<f64> = x.into_iter().chain(y).collect();
        m.sort_by(f64::total_cmp);
        m.dedup();
        m
    };
    let bu = merged(a.knots_u().domain_breaks(), b.knots_u().domain_breaks());
    let bv = merged(a.knots_v().domain_breaks(), b.knots_v().domain_breaks());
    let pa = bezier_patches(a, &bu, &bv)?;
    let pb = bezier_patches(b, &bu, &bv)?;
    let mut search = Search {
        budget: BOX_BUDGET,
        candidates: Vec::new(),
        not_isolated: false,
        overflow: false,
    };
    let mut points: Vec<[f64; 2]> = Vec::new();
    for (fa, fb) in pa.into_iter().zip(pb) {
        let (fa, fb) = divide_common_edges(fa, fb)?;
        search.candidates.clear();
        search.overflow = false;
        search.boxes(&Patch::of(&fa), &Patch::of(&fb));
        if search.overflow {
            continue;
        }
        let ((u0, u1), (v0, v1)) = fa.domain();
        for c in std::mem::take(&mut search.candidates) {
            let p = newton(&fa, &fb, c)?.unwrap_or(c);
            if p[0] < u0 || p[0] > u1 || p[1] < v0 || p[1] > v1 {
                continue;
            }
            let tol = 10.0 * RESOLUTION * (u1 - u0).max(v1 - v0);
            if !points
                .iter()
                .any(|q| (q[0] - p[0]).abs() <= tol && (q[1] - p[1]).abs() <= tol)
            {
                points.push(p);
            }
        }
    }
    points.sort_by(|x, y| x[0].total_cmp(&y[0]).then(x[1].total_cmp(&y[1])));
    Ok(CommonZeros {
        points,
        not_isolated: search.not_isolated,
        poles: Vec::new(),
    })
}

/// The edges of a Bézier patch on which it vanishes: `[u = u₀, u = u₁, v = v₀, v = v₁]`.
fn zero_edges(f: &Surface<f64, f64>) -> [bool; 4] {
    let (p, q) = f.degrees();
    let c = f.control_points();
    let nv = q + 1;
    let row = |i: usize| (0..=q).all(|j| c[i * nv + j] == 0.0);
    let col = |j: usize| (0..=p).all(|i| c[i * nv + j] == 0.0);
    [
        p > 0 && row(0),
        p > 0 && row(p),
        q > 0 && col(0),
        q > 0 && col(q),
    ]
}

/// Divides a Bézier patch by the factor vanishing on `edge` ([`zero_edges`]): by
/// `t = (u − u₀)/(u₁ − u₀)` with $B^p_i = \frac{p}{i}\, t\, B^{p-1}_{i-1}$ the quotient's
/// coefficients are $c_{i+1, j}\, p / (i + 1)$, by `1 − t` they are $c_{ij}\, p / (p - i)$;
/// likewise in `v`. Exact up to one rounding per coefficient.
fn divide_edge(f: &Surface<f64, f64>, edge: usize) -> Result<Surface<f64, f64>> {
    let (p, q) = f.degrees();
    let c = f.control_points();
    let nv = q + 1;
    let at = |i: usize, j: usize| c[i * nv + j];
    let ((u0, u1), (v0, v1)) = f.domain();
    let (coefficients, degrees): (Vec<f64>, _) = match edge {
        0 | 1 => (
            (0..p)
                .flat_map(|i| (0..=q).map(move |j| (i, j)))
                .map(|(i, j)| {
                    if edge == 0 {
                        at(i + 1, j) * p as f64 / (i + 1) as f64
                    } else {
                        at(i, j) * p as f64 / (p - i) as f64
                    }
                })
                .collect(),
            (p - 1, q),
        ),
        _ => (
            (0..=p)
                .flat_map(|i| (0..q).map(move |j| (i, j)))
                .map(|(i, j)| {
                    if edge == 2 {
                        at(i, j + 1) * q as f64 / (j + 1) as f64
                    } else {
                        at(i, j) * q as f64 / (q - j) as f64
                    }
                })
                .collect(),
            (p, q - 1),
        ),
    };
    Ok(Surface::new_unchecked(
        KnotVector::bernstein(degrees.0, &[u0, u1])?,
        KnotVector::bernstein(degrees.1, &[v0, v1])?,
        coefficients,
    ))
}

/// Divides both patches by the factors of the edges on which both vanish (a line of
/// common zeros, such as the image of a pole, carries no isolated zero inside the patch).
fn divide_common_edges(
    mut a: Surface<f64, f64>,
    mut b: Surface<f64, f64>,
) -> Result<(Surface<f64, f64>, Surface<f64, f64>)> {
    loop {
        let (za, zb) = (vanishes(&a), vanishes(&b));
        if za && zb {
            return Ok((a, b));
        }
        // A function vanishing on the whole patch vanishes on every edge (and stays as is).
        let ea = if za { [true; 4] } else { zero_edges(&a) };
        let eb = if zb { [true; 4] } else { zero_edges(&b) };
        let Some(edge) = (0..4).find(|&k| ea[k] && eb[k]) else {
            return Ok((a, b));
        };
        if !za {
            a = divide_edge(&a, edge)?;
        }
        if !zb {
            b = divide_edge(&b, edge)?;
        }
    }
}

struct Search {
    budget: usize,
    candidates: Vec<[f64; 2]>,
    not_isolated: bool,
    /// The patch being searched holds a curve of zeros of one function where the other
    /// vanishes identically: its candidates are not isolated points.
    overflow: bool,
}

/// Whether the coefficients have one strict sign (no zero in the closed box).
fn excluded(c: &[f64]) -> bool {
    c.iter().all(|&x| x > 0.0) || c.iter().all(|&x| x < 0.0)
}

fn all_zero(c: &[f64]) -> bool {
    c.iter().all(|&x| x == 0.0)
}

fn vanishes(f: &Surface<f64, f64>) -> bool {
    all_zero(f.control_points())
}

impl Search {
    /// Subdivides the patch pair over its whole domain.
    fn boxes(&mut self, a: &Patch, b: &Patch) {
        self.split(a, b, [a.u.1 - a.u.0, a.v.1 - a.v.0]);
    }

    /// Halves the boxes by de Casteljau's scheme on their Bernstein coefficients (the
    /// midpoint insertion of `Surface::split`, without its knot vectors).
    fn split(&mut self, a: &Patch, b: &Patch, size: [f64; 2]) {
        if excluded(&a.c) || excluded(&b.c) {
            return;
        }
        let (za, zb) = (all_zero(&a.c), all_zero(&b.c));
        if za && zb {
            // A region of common zeros.
            self.not_isolated = true;
            return;
        }
        // Where one function vanishes on the whole box the common zeros are the other's:
        // isolated only if few boxes reach the resolution (else a curve of them).
        if (za || zb) && self.candidates.len() > LONE_CANDIDATES {
            self.not_isolated = true;
            self.overflow = true;
            return;
        }
        if self.budget == 0 {
            self.not_isolated = true;
            return;
        }
        self.budget -= 1;
        let ((u0, u1), (v0, v1)) = (a.u, a.v);
        let (wu, wv) = ((u1 - u0) / size[0], (v1 - v0) / size[1]);
        if wu <= RESOLUTION && wv <= RESOLUTION {
            self.candidates.push([0.5 * (u0 + u1), 0.5 * (v0 + v1)]);
            return;
        }
        let along_u = wu >= wv;
        let (a0, a1) = a.halves(along_u);
        let (b0, b1) = b.halves(along_u);
        self.split(&a0, &b0, size);
        self.split(&a1, &b1, size);
    }
}

/// Newton's method for `a = b = 0` from `start`, staying in the patch; `None` if it does
/// not converge.
fn newton(
    a: &Surface<f64, f64>,
    b: &Surface<f64, f64>,
    start: [f64; 2],
) -> Result<Option<[f64; 2]>> {
    let ((u0, u1), (v0, v1)) = a.domain();
    let [mut u, mut v] = start;
    for _ in 0..30 {
        let da = a.derivatives(u, v, 1)?;
        let db = b.derivatives(u, v, 1)?;
        let (f, g) = (da[0][0], db[0][0]);
        let det = da[1][0] * db[0][1] - da[0][1] * db[1][0];
        if det == 0.0 || !det.is_finite() {
            return Ok(None);
        }
        let du = (f * db[0][1] - g * da[0][1]) / det;
        let dv = (g * da[1][0] - f * db[1][0]) / det;
        u = (u - du).clamp(u0, u1);
        v = (v - dv).clamp(v0, v1);
        if du.abs() <= 1e-15 * (u1 - u0).max(1.0) && dv.abs() <= 1e-15 * (v1 - v0).max(1.0) {
            return Ok(Some([u, v]));
        }
    }
    // Close enough when the last step was tiny relative to the box resolution.
    Ok(Some([u, v]).filter(|p| {
        (p[0] - start[0]).abs() <= 10.0 * RESOLUTION * (u1 - u0)
            && (p[1] - start[1]).abs() <= 10.0 * RESOLUTION * (v1 - v0)
    }))
}

/// The umbilics of a surface (where both principal curvatures agree): the isolated common
/// zeros ([`common_zeros`]) of its umbilic numerators ([`crate::CurvatureNumerators`]),
/// except where the parametrisation is singular (`S_u × S_v = 0`, as at a sphere's poles:
/// the numerators vanish there identically along the net's line, and those factors are
/// divided out). Umbilics at poles (a boundary line of the domain collapsed to one point,
/// as on the axis of a spheroid) are decided from the second-order behaviour of the surface
/// there and listed in [`CommonZeros::poles`]. A sphere (every point umbilic) gives no points
/// and `not_isolated`.
///
/// ```
/// use nalgebra::Vector3;
/// use spline_geom::NurbsSurface;
/// // An ellipsoid with semi-axes 2 (y), 1.5 (x), 1 (z): four umbilics, in the plane x = 0.
/// let sphere = NurbsSurface::sphere(Vector3::zeros(), 1.0)?;
/// let ellipsoid = sphere.map_control_points(|p| Vector3::new(1.5 * p.x, 2.0 * p.y, p.z));
/// let found = spline_algebra::umbilics(&ellipsoid)?;
/// assert_eq!(found.points.len(), 4);
/// assert!(found.poles.is_empty()); // its poles (z = ±1) are not umbilics
/// // The spheroid with semi-axes 1.5, 1.5, 1: its umbilics are its two poles.
/// let spheroid = sphere.map_control_points(|p| Vector3::new(1.5 * p.x, 1.5 * p.y, p.z));
/// let found = spline_algebra::umbilics(&spheroid)?;
/// assert!(found.points.is_empty() && !found.not_isolated);
/// assert_eq!(found.poles.len(), 2);
/// for p in &found.points {
///     assert!(ellipsoid.eval(p[0], p[1])?.x.abs() < 1e-9);
/// }
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`crate::curvature_numerators`].
pub fn umbilics(surface: &NurbsSurface<f64, 3>) -> Result<CommonZeros> {
    umbilics_from(surface, &curvature_numerators(surface)?)
}

/// [`umbilics`] from the surface's curvature numerators, already computed.
pub(crate) fn umbilics_from(
    surface: &NurbsSurface<f64, 3>,
    n: &CurvatureNumerators<f64>,
) -> Result<CommonZeros> {
    let [a, b] = &n.umbilic;
    let mut zeros = common_zeros(a, b)?;
    let scale = n
        .area
        .control_points()
        .iter()
        .fold(0.0f64, |m, &x| m.max(x.abs()));
    let mut regular = Vec::new();
    for p in zeros.points {
        if n.area.eval(p[0], p[1])? > 1e-12 * scale {
            regular.push(p);
        }
    }
    // The same point of the surface found from two patches (a seam, a patch edge).
    let mut points: Vec<[f64; 2]> = Vec::new();
    let mut seen: Vec<nalgebra::Vector3<f64>> = Vec::new();
    let size = surface
        .control_points()
        .iter()
        .fold(0.0f64, |m, x| m.max(x.amax()));
    for p in regular {
        let x = surface.eval(p[0], p[1])?;
        if !seen
            .iter()
            .any(|y| (x - y).amax() <= 1e-7 * size.max(1e-300))
        {
            seen.push(x);
            points.push(p);
        }
    }
    zeros.points = points;
    if !zeros.not_isolated {
        zeros.poles = crate::pole_umbilics::pole_umbilics(surface)?;
    }
    Ok(zeros)
}
