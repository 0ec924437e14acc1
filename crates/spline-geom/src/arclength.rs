//! Adaptive arc length (the quadrature behind [`crate::ParamCurve::arc_length`]).

use spline_core::{Error, ErrorKind, Result, Scalar, cast, gauss_legendre, to_f64};

/// The default absolute accuracy of [`crate::ParamCurve::arc_length`].
pub const DEFAULT_ACCURACY: f64 = 1e-9;

struct Quadrature<T> {
    nodes: Vec<T>,
    weights: Vec<T>,
}

impl<T: Scalar> Quadrature<T> {
    fn new(n: usize) -> Self {
        let (nodes, weights) = gauss_legendre::<T>(n).into_iter().unzip();
        Self { nodes, weights }
    }

    fn integrate(&self, a: T, b: T, f: &impl Fn(T) -> T) -> T {
        let half = (b - a) * cast(0.5);
        let mid = (a + b) * cast(0.5);
        self.nodes
            .iter()
            .zip(&self.weights)
            .fold(T::zero(), |s, (&x, &w)| s + w * f(mid + half * x))
            * half
    }
}

/// $\int \lVert C'(u) \rVert\\,du$ over the pieces between consecutive `breaks` (the speed
/// is smooth inside each), by adaptive Gauss–Legendre quadrature to the absolute `accuracy`
/// shared among the pieces.
///
/// # Errors
/// [`ErrorKind::NoConvergence`] if a piece cannot reach its share of the accuracy.
pub(crate) fn adaptive_length<T: Scalar>(
    breaks: &[T],
    accuracy: T,
    speed: impl Fn(T) -> T,
) -> Result<T> {
    let rule = Quadrature::<T>::new(8);
    let pieces = breaks.len().saturating_sub(1).max(1);
    let tol_piece = accuracy / spline_core::from_count::<T>(pieces);
    let mut total = T::zero();
    for w in breaks.windows(2) {
        total += adaptive(&rule, w[0], w[1], &speed, tol_piece, 0)?;
    }
    Ok(total)
}

fn adaptive<T: Scalar>(
    rule: &Quadrature<T>,
    a: T,
    b: T,
    f: &impl Fn(T) -> T,
    tol: T,
    depth: usize,
) -> Result<T> {
    let whole = rule.integrate(a, b, f);
    let mid = (a + b) * cast(0.5);
    let left = rule.integrate(a, mid, f);
    let right = rule.integrate(mid, b, f);
    let halves = left + right;
    // The halves estimate is far more accurate than `whole`; their difference bounds its error.
    let rounding = halves.abs() * cast(8.0 * f64::EPSILON);
    if (halves - whole).abs() <= tol.max(rounding) {
        return Ok(halves);
    }
    if depth >= 48 {
        return Err(Error::new(
            ErrorKind::NoConvergence,
            format!(
                "arc length did not reach the accuracy {:.1e} near u = {}",
                to_f64(tol),
                to_f64(mid)
            ),
        ));
    }
    let half_tol = tol * cast(0.5);
    Ok(adaptive(rule, a, mid, f, half_tol, depth + 1)?
        + adaptive(rule, mid, b, f, half_tol, depth + 1)?)
}
