//! Knots that follow the shape: more where the curvature is high.

use crate::interpolate::check_degree;
use crate::params::check_control_count;
use spline_core::{ControlPoint, Error, ErrorKind, KnotVector, Result, Scalar, cast, from_count};
use spline_geom::BSpline;

/// Samples per knot span of `curve` when integrating the knot density.
const SAMPLES_PER_SPAN: usize = 32;

/// A clamped knot vector of degree `degree` for `num_control` control points on the domain
/// of `curve`, whose interior knots equidistribute the density
///
/// $$ \rho(u) = \lVert C'(u) \rVert \,\bigl(\kappa(u) L + c\bigr)^{\beta} $$
///
/// along a preliminary fit `C` (`κ` its curvature, `L` its length, `β = exponent`,
/// `c = floor`): with `β = 0` the knots are uniform in arc length; with `β = ½` their
/// spacing in arc length goes like $\kappa^{-1/2}$, the classic rule for approximating a
/// curve whose curvature varies by orders of magnitude (the nose of an airfoil). The floor
/// keeps knots on the flat parts. Each interior knot is the parameter where the cumulative
/// density reaches `j / (n − p)` of the total (integrated by the trapezoidal rule on a dense
/// grid of every knot span).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_fit::curvature_knots;
/// use spline_geom::BSpline;
/// // A quarter of an ellipse: sharper at (2, 0) than at (0, 1).
/// let arc: Vec<Vector2<f64>> = (0..=40)
///     .map(|k| {
///         let t = k as f64 / 40.0 * std::f64::consts::FRAC_PI_2;
///         Vector2::new(2.0 * t.cos(), 0.5 * t.sin())
///     })
///     .collect();
/// let fit = spline_fit::interpolate(&arc, 3, &Default::default())?;
/// let knots = curvature_knots(&fit.curve, 3, 12, 0.5, 0.5)?;
/// assert_eq!(knots.num_basis(), 12);
/// let k = knots.knots();
/// assert!(k[4] - k[3] < k[11] - k[10]); // denser where the ellipse is sharper
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::TooFewPoints`] unless `degree < num_control`; [`ErrorKind::InvalidArgument`]
/// for a negative or non-finite exponent or floor, or a preliminary curve of degree below 2
/// (no curvature); [`ErrorKind::DegenerateGeometry`] when the curve has zero length.
pub fn curvature_knots<T: Scalar, P: ControlPoint<T>>(
    curve: &BSpline<T, P>,
    degree: usize,
    num_control: usize,
    exponent: T,
    floor: T,
) -> Result<KnotVector<T>> {
    curvature_knots_with(curve, degree, num_control, exponent, floor, &[])
}

/// [`curvature_knots`] with prescribed interior knots: each `(u, m)` of `fixed` is a knot of
/// multiplicity `m`, and the other interior knots equidistribute the density on each piece
/// between them, the number of knot spans of a piece in proportion to its share of the
/// density (at least one each).
///
/// # Errors
/// As [`curvature_knots`]; [`ErrorKind::InvalidArgument`] when a prescribed knot is not
/// strictly inside the domain, two coincide, a multiplicity is 0 or above the degree, or the
/// prescribed knots leave too few control points for one span per piece.
pub fn curvature_knots_with<T: Scalar, P: ControlPoint<T>>(
    curve: &BSpline<T, P>,
    degree: usize,
    num_control: usize,
    exponent: T,
    floor: T,
    fixed: &[(T, usize)],
) -> Result<KnotVector<T>> {
    check_degree(degree)?;
    check_control_count(degree, num_control, num_control)?;
    let (a, b) = curve.domain();
    let mut fixed: Vec<(T, usize)> = fixed.to_vec();
    fixed.sort_by(|x, y| x.0.partial_cmp(&y.0).unwrap_or(std::cmp::Ordering::Equal));
    for (i, &(u, m)) in fixed.iter().enumerate() {
        if !(u > a && u < b) || m == 0 || m > degree {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "prescribed knot {i} ({}, multiplicity {m}) must lie inside the domain with multiplicity 1 to {degree}",
                    spline_core::to_f64(u)
                ),
            )
            .with_index(i)
            .with_value(spline_core::to_f64(u))
            .with_interval(spline_core::to_f64(a), spline_core::to_f64(b)));
        }
        if i > 0 && !(u > fixed[i - 1].0) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                "two prescribed knots coincide",
            ));
        }
    }
    let used: usize = fixed.iter().map(|f| f.1).sum();
    // Interior knots in all: n − p − 1; the free ones are distinct.
    let interior_total = num_control - degree - 1;
    if used > interior_total {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "{num_control} control points of degree {degree} leave no room for the prescribed knots"
            ),
        ));
    }
    let free = interior_total - used;
    if !(exponent >= T::zero() && exponent.is_finite() && floor >= T::zero() && floor.is_finite()) {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "the exponent and the floor of the knot density must be finite and not negative",
        ));
    }
    if curve.degree() < 2 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            "knots that follow the curvature need a preliminary curve of degree 2 or more",
        )
        .with_value(from_count(curve.degree()))
        .with_interval(2.0, f64::INFINITY));
    }
    let breaks = curve.knots().domain_breaks();
    let steps: T = from_count(SAMPLES_PER_SPAN);
    let mut grid = Vec::with_capacity((breaks.len() - 1) * SAMPLES_PER_SPAN + 1);
    for w in breaks.windows(2) {
        let h = (w[1] - w[0]) / steps;
        for k in 0..SAMPLES_PER_SPAN {
            grid.push(w[0] + h * from_count::<T>(k));
        }
    }
    grid.push(breaks[breaks.len() - 1]);
    let mut speed = Vec::with_capacity(grid.len());
    let mut kappa = Vec::with_capacity(grid.len());
    let mut ders = [P::origin(); 3];
    for &u in &grid {
        curve.derivatives_into(u, &mut ders)?;
        let (d1, d2) = (ders[1], ders[2]);
        let s2 = d1.length_squared();
        let s = s2.sqrt();
        // |C′ × C″| in any dimension: √(|C′|²|C″|² − (C′·C″)²).
        let cross2 = (s2 * d2.length_squared() - d1.dot(&d2).powi(2)).max(T::zero());
        speed.push(s);
        kappa.push(if s > T::zero() {
            cross2.sqrt() / (s2 * s)
        } else {
            T::zero()
        });
    }
    let half: T = cast(0.5);
    let length = grid
        .windows(2)
        .zip(speed.windows(2))
        .fold(T::zero(), |acc, (u, s)| {
            acc + (s[0] + s[1]) * half * (u[1] - u[0])
        });
    if !(length > T::zero()) || !length.is_finite() {
        return Err(Error::new(
            ErrorKind::DegenerateGeometry,
            "the preliminary curve has no length: its curvature cannot place knots",
        ));
    }
    let density: Vec<T> = speed
        .iter()
        .zip(&kappa)
        .map(|(&s, &k)| s * (k * length + floor).powf(exponent))
        .collect();
    let mut cumulative = Vec::with_capacity(grid.len());
    cumulative.push(T::zero());
    for i in 1..grid.len() {
        let last = cumulative[i - 1];
        cumulative.push(last + (density[i] + density[i - 1]) * half * (grid[i] - grid[i - 1]));
    }
    let total = cumulative[grid.len() - 1];
    if !(total > T::zero()) || !total.is_finite() {
        return Err(Error::new(
            ErrorKind::DegenerateGeometry,
            "the knot density of the preliminary curve vanishes",
        ));
    }
    // The cumulative density at a parameter (linear between grid points).
    let at = |u: T| -> T {
        let i = grid.partition_point(|&g| g <= u).clamp(1, grid.len() - 1);
        let (g0, g1) = (grid[i - 1], grid[i]);
        let t = if g1 > g0 {
            (u - g0) / (g1 - g0)
        } else {
            T::zero()
        };
        cumulative[i - 1] + (cumulative[i] - cumulative[i - 1]) * t.max(T::zero()).min(T::one())
    };
    // The parameter where the cumulative density reaches `target`.
    let inverse = |target: T| -> T {
        let i = cumulative
            .partition_point(|&c| c < target)
            .clamp(1, grid.len() - 1);
        let (c0, c1) = (cumulative[i - 1], cumulative[i]);
        let t = if c1 > c0 {
            (target - c0) / (c1 - c0)
        } else {
            T::zero()
        };
        grid[i - 1] + (grid[i] - grid[i - 1]) * t
    };
    // Pieces between prescribed knots; spans shared by largest remainders, one at least.
    let mut bounds = vec![a];
    bounds.extend(fixed.iter().map(|f| f.0));
    bounds.push(b);
    let pieces = bounds.len() - 1;
    let spans = free + pieces; // distinct free knots + one span per piece
    let masses: Vec<T> = bounds.windows(2).map(|w| at(w[1]) - at(w[0])).collect();
    let mut share: Vec<usize> = vec![1; pieces];
    let mut left = spans - pieces;
    let exact: Vec<T> = masses
        .iter()
        .map(|&m| m / total * from_count::<T>(spans))
        .collect();
    // Give each piece what its share asks beyond its first span, then the remainders.
    for (s, &e) in share.iter_mut().zip(&exact) {
        let extra = spline_core::to_f64(e - T::one()).floor().max(0.0);
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let extra = (extra as usize).min(left);
        *s += extra;
        left -= extra;
    }
    while left > 0 {
        let (best, _) = exact
            .iter()
            .zip(&share)
            .enumerate()
            .map(|(i, (&e, &s))| (i, e - from_count::<T>(s)))
            .fold((0, None::<T>), |(bi, bv), (i, v)| match bv {
                Some(b) if !(v > b) => (bi, Some(b)),
                _ => (i, Some(v)),
            });
        share[best] += 1;
        left -= 1;
    }
    let mut interior = Vec::with_capacity(interior_total);
    for (j, w) in bounds.windows(2).enumerate() {
        let (c0, c1) = (at(w[0]), at(w[1]));
        let s = share[j];
        for k in 1..s {
            let u = inverse(c0 + (c1 - c0) * from_count::<T>(k) / from_count::<T>(s));
            interior.push(u.max(w[0]).min(w[1]));
        }
        if j < fixed.len() {
            interior.extend(std::iter::repeat_n(fixed[j].0, fixed[j].1));
        }
    }
    KnotVector::clamped(degree, a, b, &interior)
}
