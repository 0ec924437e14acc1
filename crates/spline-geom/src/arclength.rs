//! Adaptive arc length.

use crate::bspline::BSpline;
use spline_core::{ControlPoint, Error, ErrorKind, Result, Scalar, cast, gauss_legendre, to_f64};

/// The default absolute accuracy of [`BSpline::arc_length`].
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

impl<T: Scalar, P: ControlPoint<T>> BSpline<T, P> {
    /// The arc length of the whole curve to the absolute `accuracy`.
    ///
    /// # Errors
    /// As [`BSpline::arc_length_between`].
    pub fn arc_length(&self, accuracy: T) -> Result<T> {
        let (a, b) = self.domain();
        self.arc_length_between(a, b, accuracy)
    }

    /// The arc length between parameters `a ≤ b` to the absolute `accuracy`:
    /// $\int_a^b \lVert C'(u) \rVert\,du$ by adaptive Gauss–Legendre quadrature on each knot
    /// span (the speed is smooth inside a span), bisecting where two estimates differ.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use spline_geom::BSpline;
    /// // The parabola y = x², 0 ≤ x ≤ 1: length √5/2 + asinh(2)/4.
    /// let c = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    ///     vec![Vector2::new(0.0, 0.0), Vector2::new(0.5, 0.0), Vector2::new(1.0, 1.0)])?;
    /// let exact = 5f64.sqrt() / 2.0 + 2f64.asinh() / 4.0;
    /// assert!((c.arc_length(1e-12)? - exact).abs() < 1e-12);
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::NonFinite`]/[`ErrorKind::OutOfDomain`] for the bounds;
    /// [`ErrorKind::InvalidArgument`] if `a > b` or the accuracy is not positive;
    /// [`ErrorKind::NoConvergence`] if the requested accuracy cannot be reached (it is far
    /// below rounding of the result).
    pub fn arc_length_between(&self, a: T, b: T, accuracy: T) -> Result<T> {
        self.knots().check_param(a)?;
        self.knots().check_param(b)?;
        if a > b {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "arc length from {} to {}: bounds in decreasing order",
                    to_f64(a),
                    to_f64(b)
                ),
            ));
        }
        if !(accuracy > T::zero()) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!("accuracy must be positive, got {}", to_f64(accuracy)),
            ));
        }
        let rule = Quadrature::<T>::new(8);
        let speed = |u: T| {
            let span = self.knots().span_in_domain(u);
            let mut d = [P::origin(); 2];
            self.derivatives_in_span(span, u, &mut d);
            d[1].length()
        };
        let breaks = self.knots().breaks_between(a, b);
        let pieces = breaks.len().saturating_sub(1).max(1);
        let tol_piece = accuracy / spline_core::from_count::<T>(pieces);
        let mut total = T::zero();
        for w in breaks.windows(2) {
            total += adaptive(&rule, w[0], w[1], &speed, tol_piece, 0)?;
        }
        Ok(total)
    }
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
