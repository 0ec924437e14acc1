//! Approximation of a map of two parameters within a tolerance by adaptive knot refinement
//! in both directions: the surface counterpart of [`crate::AdaptiveApproximation`] (offset
//! surfaces use it).

use crate::adaptive::FirstScale;
use crate::lsq::LeastSquares;
use crate::params::check_degree;
use spline_core::{
    ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, from_count, to_f64,
};
use spline_geom::Surface;

/// The most patches [`AdaptiveSurfaceApproximation`] allows by default.
pub const MAX_ADAPTIVE_PATCHES: usize = 40_000;

/// Approximation of a map $f : [a, b] \times [c, d] \to \mathbb{R}^D$ by a clamped
/// tensor-product B-spline of degrees `(p, q)` within a tolerance: least squares on a grid
/// of `2 (p + 1) × 2 (q + 1)` samples per patch (exactly, as two passes of curve least
/// squares: the data have the product structure of the basis), the ends of every line
/// pinned so that the corners are interpolated, the deviation measured on a grid of
/// `4 (p + 1) × 4 (q + 1)` other points per patch, and every knot span in `u` or `v` that
/// holds a patch whose deviation exceeds **half** the tolerance split in two; until every
/// patch meets it. The tolerance is absolute (in the units of the map's values); the
/// computation is scale-invariant (the values are divided by a power of four near their
/// size first, as in [`crate::AdaptiveApproximation`]).
///
/// ```
/// use nalgebra::Vector3;
/// use spline_fit::AdaptiveSurfaceApproximation;
/// use spline_geom::ParamSurface;
/// let f = |u: f64, v: f64| Vector3::new(u, v, (2.0 * u).sin() * v.cos());
/// let fit = AdaptiveSurfaceApproximation::new((3, 3), 1e-7).fit(((0.0, 2.0), (0.0, 1.0)), |us, vs| {
///     Ok(us.iter().flat_map(|&u| vs.iter().map(move |&v| f(u, v))).collect())
/// })?;
/// assert!(fit.max_error <= 1e-7);
/// assert!((fit.surface.eval(1.3, 0.7)? - f(1.3, 0.7)).norm() <= 1e-7);
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct AdaptiveSurfaceApproximation<T> {
    degrees: (usize, usize),
    tolerance: T,
    breaks: (Vec<T>, Vec<T>),
    max_patches: usize,
}

/// The result of [`AdaptiveSurfaceApproximation::fit`].
#[derive(Clone, Debug)]
pub struct AdaptiveSurfaceFit<T, P> {
    /// The approximating surface on the domain.
    pub surface: Surface<T, P>,
    /// The largest deviation $\lVert S(u, v) - f(u, v) \rVert$ at the check points.
    pub max_error: T,
    /// How many refinement passes were needed.
    pub passes: usize,
}

impl<T: Scalar> AdaptiveSurfaceApproximation<T> {
    /// Degrees `(p, q)` and the tolerance on $\lVert S(u, v) - f(u, v) \rVert$.
    #[must_use]
    pub fn new(degrees: (usize, usize), tolerance: T) -> Self {
        Self {
            degrees,
            tolerance,
            breaks: (Vec::new(), Vec::new()),
            max_patches: MAX_ADAPTIVE_PATCHES,
        }
    }

    /// Initial interior knots in `u` and in `v`, e.g. the breaks of the map: a value given
    /// `k` times is a knot of multiplicity `k` (at most the degree), for a map that is only
    /// $C^{p-k}$ there; the knots added by refinement are simple.
    #[must_use]
    pub fn breaks(mut self, u: &[T], v: &[T]) -> Self {
        self.breaks = (u.to_vec(), v.to_vec());
        self
    }

    /// The most patches allowed (default [`MAX_ADAPTIVE_PATCHES`]).
    #[must_use]
    pub fn max_patches(mut self, patches: usize) -> Self {
        self.max_patches = patches;
        self
    }

    /// Fits `f`, a map evaluated on a grid `us × vs` (both increasing) that returns the
    /// values row-major (`[a · vs.len() + b]` $= f(u_a, v_b)$), on the domain
    /// `((a, b), (c, d))`.
    ///
    /// # Errors
    /// [`ErrorKind::InvalidTolerance`] unless the tolerance is positive and finite;
    /// [`ErrorKind::DegreeTooHigh`]; [`ErrorKind::EmptyDomain`] unless `a < b` and `c < d`
    /// (finite); [`ErrorKind::OutOfDomain`] for breaks outside the domain;
    /// [`ErrorKind::InvalidLength`] if `f` returns a grid of the wrong size;
    /// [`ErrorKind::ToleranceExceeded`] when more than the allowed patches would be needed
    /// (the message gives the best deviation reached); the errors of `f`.
    pub fn fit<P: ControlPoint<T>>(
        &self,
        domain: ((T, T), (T, T)),
        f: impl Fn(&[T], &[T]) -> Result<Vec<P>>,
    ) -> Result<AdaptiveSurfaceFit<T, P>> {
        check_degree(self.degrees.0)?;
        check_degree(self.degrees.1)?;
        if !(self.tolerance > T::zero() && self.tolerance.is_finite()) {
            return Err(Error::invalid_tolerance(
                "approximation tolerance",
                "positive and finite",
                to_f64(self.tolerance),
            ));
        }
        let mut breaks_u = initial_breaks(domain.0, &self.breaks.0, "u")?;
        let mut breaks_v = initial_breaks(domain.1, &self.breaks.1, "v")?;
        let repeats = (&self.breaks.0[..], &self.breaks.1[..]);
        let degrees = (self.degrees.0.max(1), self.degrees.1.max(1));
        // The values divided by a power of four near the size of the first samples (exact).
        let scale = FirstScale::new();
        let scaled = |us: &[T], vs: &[T]| -> Result<Vec<P>> {
            let mut points = f(us, vs)?;
            if points.len() != us.len() * vs.len() {
                return Err(Error::new(
                    ErrorKind::InvalidLength,
                    format!(
                        "the map returned {} values for a grid of {} × {} parameters",
                        points.len(),
                        us.len(),
                        vs.len()
                    ),
                ));
            }
            scale.divide(&mut points);
            Ok(points)
        };
        let mut passes = 0;
        loop {
            let (mut surface, errors) = fit_on(degrees, (&breaks_u, &breaks_v), repeats, &scaled)?;
            let s = scale.get();
            let target = self.tolerance * cast(0.5) / s;
            let spans_v = breaks_v.len() - 1;
            let worst = errors.iter().fold(T::zero(), |m, &e| m.max(e)) * s;
            let mut bad_u = vec![false; breaks_u.len() - 1];
            let mut bad_v = vec![false; spans_v];
            for (k, &e) in errors.iter().enumerate() {
                if e > target {
                    bad_u[k / spans_v] = true;
                    bad_v[k % spans_v] = true;
                }
            }
            if !bad_u.contains(&true) {
                for q in surface.control_points_mut() {
                    *q = *q * s;
                }
                return Ok(AdaptiveSurfaceFit {
                    surface,
                    max_error: worst,
                    passes,
                });
            }
            let refined_u = split(&breaks_u, &bad_u);
            let refined_v = split(&breaks_v, &bad_v);
            let patches = (refined_u.len() - 1).saturating_mul(refined_v.len() - 1);
            if patches > self.max_patches {
                return Err(Error::new(
                    ErrorKind::ToleranceExceeded,
                    format!(
                        "the approximation needs more than {} patches: the best deviation reached is {:.3e} (tolerance {:.3e})",
                        self.max_patches,
                        to_f64(worst),
                        to_f64(self.tolerance)
                    ),
                ));
            }
            if refined_u.len() == breaks_u.len() && refined_v.len() == breaks_v.len() {
                return Err(Error::new(
                    ErrorKind::ToleranceExceeded,
                    format!(
                        "the approximation cannot be refined further (patches at rounding size): best deviation {:.3e}",
                        to_f64(worst)
                    ),
                ));
            }
            breaks_u = refined_u;
            breaks_v = refined_v;
            passes += 1;
        }
    }
}

/// The domain ends and the interior breaks, sorted and without repeats.
fn initial_breaks<T: Scalar>((a, b): (T, T), interior: &[T], name: &str) -> Result<Vec<T>> {
    if !(a.is_finite() && b.is_finite() && a < b) {
        return Err(Error::new(
            ErrorKind::EmptyDomain,
            format!(
                "cannot approximate on [{}, {}] in {name}",
                to_f64(a),
                to_f64(b)
            ),
        ));
    }
    for &u in interior {
        if !(u > a && u < b) {
            return Err(Error::out_of_domain(to_f64(u), (to_f64(a), to_f64(b)))
                .context(format_args!("interior break in {name}")));
        }
    }
    let mut breaks: Vec<T> = interior.to_vec();
    breaks.push(a);
    breaks.push(b);
    breaks.sort_by(|x, y| x.partial_cmp(y).unwrap_or(std::cmp::Ordering::Equal));
    breaks.dedup();
    Ok(breaks)
}

/// The breaks with the spans marked `bad` halved (where the midpoint is representable).
fn split<T: Scalar>(breaks: &[T], bad: &[bool]) -> Vec<T> {
    let mut refined = Vec::with_capacity(breaks.len() * 2);
    for k in 0..breaks.len() - 1 {
        refined.push(breaks[k]);
        if bad[k] {
            let mid = (breaks[k] + breaks[k + 1]) * cast(0.5);
            if mid > breaks[k] && mid < breaks[k + 1] {
                refined.push(mid);
            }
        }
    }
    refined.push(breaks[breaks.len() - 1]);
    refined
}

/// `per` samples per span (the span's start and `per − 1` interior points) and the end;
/// with `half`, the midpoints of those steps instead (the check points).
fn samples<T: Scalar>(breaks: &[T], per: usize, half: bool) -> Vec<T> {
    let mut params = Vec::with_capacity((breaks.len() - 1) * per + 1);
    for w in breaks.windows(2) {
        for j in 0..per {
            let t = if half {
                from_count::<T>(2 * j + 1) / from_count::<T>(2 * per)
            } else {
                from_count::<T>(j) / from_count::<T>(per)
            };
            params.push(w[0] + (w[1] - w[0]) * t);
        }
    }
    if !half {
        params.push(breaks[breaks.len() - 1]);
    }
    params
}

/// The least-squares surface on the knots with these breaks, and the deviation per patch
/// (row-major: `[a · spans_v + b]`).
fn fit_on<T: Scalar, P: ControlPoint<T>>(
    (p, q): (usize, usize),
    (breaks_u, breaks_v): (&[T], &[T]),
    (repeats_u, repeats_v): (&[T], &[T]),
    f: &impl Fn(&[T], &[T]) -> Result<Vec<P>>,
) -> Result<(Surface<T, P>, Vec<T>)> {
    let knots = |degree: usize, breaks: &[T], repeats: &[T]| {
        let mut interior = Vec::with_capacity(breaks.len());
        for &b in &breaks[1..breaks.len() - 1] {
            let times = repeats.iter().filter(|&&r| r == b).count().clamp(1, degree);
            interior.extend(std::iter::repeat_n(b, times));
        }
        KnotVector::clamped(degree, breaks[0], breaks[breaks.len() - 1], &interior)
    };
    let (ku, kv) = (
        knots(p, breaks_u, repeats_u)?,
        knots(q, breaks_v, repeats_v)?,
    );
    let us = samples(breaks_u, 2 * (p + 1), false);
    let vs = samples(breaks_v, 2 * (q + 1), false);
    let grid = f(&us, &vs)?;
    let (nu, nv) = (ku.num_basis(), kv.num_basis());
    // Along u for every column of samples, then along v for every row of the result.
    let mut along_u = vec![P::origin(); nu * vs.len()];
    let mut column = Vec::with_capacity(us.len());
    for l in 0..vs.len() {
        column.clear();
        column.extend((0..us.len()).map(|k| grid[k * vs.len() + l]));
        let control = LeastSquares::new(&column, &us, ku.clone())
            .pin_ends()
            .control_points()?;
        for (i, c) in control.into_iter().enumerate() {
            along_u[i * vs.len() + l] = c;
        }
    }
    let mut net = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let row = &along_u[i * vs.len()..(i + 1) * vs.len()];
        net.extend(
            LeastSquares::new(row, &vs, kv.clone())
                .pin_ends()
                .control_points()?,
        );
    }
    let surface = Surface::new(ku, kv, net)?;
    let check_u = samples(breaks_u, 4 * (p + 1), true);
    let check_v = samples(breaks_v, 4 * (q + 1), true);
    let exact = f(&check_u, &check_v)?;
    let approximation = surface.eval_grid(&check_u, &check_v)?;
    let spans_v = breaks_v.len() - 1;
    let mut errors = vec![T::zero(); (breaks_u.len() - 1) * spans_v];
    let (per_u, per_v) = (4 * (p + 1), 4 * (q + 1));
    for a in 0..check_u.len() {
        for b in 0..check_v.len() {
            let k = a * check_v.len() + b;
            let e = &mut errors[(a / per_u) * spans_v + b / per_v];
            *e = (*e).max((approximation[k] - exact[k]).length());
        }
    }
    Ok((surface, errors))
}
