//! Adaptive arc length (the quadrature behind [`crate::ParamCurve::arc_length`]).

use spline_core::{Error, ErrorKind, Result, Scalar, cast, gauss_legendre, to_f64};

/// The default relative accuracy of [`crate::ParamCurve::arc_length`] (and of
/// [`crate::ArcLengthTable`]): lengths to about nine digits at every scale.
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
/// is smooth inside each), by adaptive Gauss–Legendre quadrature to the **relative**
/// `accuracy`: every piece (and every half a piece is bisected into) is accepted when two
/// estimates agree to `accuracy` times its own length, so the sum is accurate to `accuracy`
/// times the total at any scale of the coordinates and whatever the number of pieces (an
/// absolute accuracy shared among 10⁵ pieces asked each for 1e-15 and took minutes).
///
/// # Errors
/// [`ErrorKind::NoConvergence`] if a piece cannot reach the accuracy.
pub(crate) fn adaptive_length<T: Scalar>(
    breaks: &[T],
    accuracy: T,
    speed: impl Fn(T) -> T,
) -> Result<T> {
    let rule = Quadrature::<T>::new(8);
    let mut total = T::zero();
    for w in breaks.windows(2) {
        let whole = rule.integrate(w[0], w[1], &speed);
        // The piece's share: `accuracy` times its length, split between halves on bisection.
        let budget = whole.abs() * accuracy;
        total += adaptive(&rule, (w[0], w[1]), whole, &speed, budget, 0)?;
    }
    Ok(total)
}

/// The integral over `[a, b]` given the rule's estimate `whole` there (the halves'
/// estimates are passed down on bisection, not computed again), to the absolute `budget`
/// (each half gets half of it: the errors of the accepted intervals add up to at most the
/// piece's budget; no interval is asked for less than the rounding of its own value).
fn adaptive<T: Scalar>(
    rule: &Quadrature<T>,
    (a, b): (T, T),
    whole: T,
    f: &impl Fn(T) -> T,
    budget: T,
    depth: usize,
) -> Result<T> {
    let mid = (a + b) * cast(0.5);
    let left = rule.integrate(a, mid, f);
    let right = rule.integrate(mid, b, f);
    let halves = left + right;
    // The halves estimate is far more accurate than `whole`; their difference bounds its error.
    let tol = budget.max(halves.abs() * cast(8.0 * f64::EPSILON));
    if (halves - whole).abs() <= tol {
        return Ok(halves);
    }
    if depth >= 48 {
        return Err(Error::new(
            ErrorKind::NoConvergence,
            format!(
                "arc length did not reach the accuracy {:.1e} near u = {}",
                to_f64(budget),
                to_f64(mid)
            ),
        ));
    }
    let half = budget * cast(0.5);
    Ok(adaptive(rule, (a, mid), left, f, half, depth + 1)?
        + adaptive(rule, (mid, b), right, f, half, depth + 1)?)
}
