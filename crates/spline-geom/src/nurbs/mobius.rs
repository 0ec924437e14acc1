//! The rational linear (Möbius) reparametrization of a NURBS curve: the same points along
//! the same domain at other parameters, with other end weights.

use super::curve::NurbsCurve;
use crate::homogeneous::Homogeneous;
use spline_core::{Error, ErrorKind, KnotVector, Result, Scalar, to_f64};

impl<T: Scalar, const D: usize> NurbsCurve<T, D> {
    /// The curve reparametrized by the rational linear map of its domain $[a, b]$ onto itself
    /// with `factor` $c > 0$: in the normalised parameter $x = (u - a)/(b - a)$,
    ///
    /// $$ C'(s) = C(\varphi(s)), \qquad \varphi(s) = \frac{s}{c\,(1 - s) + s}, $$
    ///
    /// the same points in the same order (Lee and Lucian, *Möbius reparametrizations of
    /// rational B-splines*, CAGD 8, 1991). The knots move to $\varphi^{-1}(u_j) = c\,u_j /
    /// (1 - u_j + c\,u_j)$ and each weight is multiplied by
    /// $\prod_{j=i+1}^{i+p} \bigl(c\,(1 - s_j) + s_j\bigr)$ over the new knots $s_j$ (the
    /// minimal support of a B-spline is kept, so each basis function becomes a multiple of
    /// one new basis function). Of a clamped curve, the first weight is multiplied by $c^p$
    /// and the last is kept: the ratio of the end weights is free, which is what rational
    /// constructions need to make corner weights agree. `factor = 1` is the identity.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use spline_geom::NurbsCurve2;
    /// let arc = NurbsCurve2::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
    ///     vec![Vector2::new(1.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(0.0, 1.0)],
    ///     vec![1.0, 0.5f64.sqrt(), 1.0])?;
    /// let moved = arc.mobius_reparametrized(2.0)?;
    /// assert!((moved.weights()[0] - 4.0).abs() < 1e-15);
    /// let phi = |s: f64| s / (2.0 * (1.0 - s) + s);
    /// for s in [0.1, 0.5, 0.9] {
    ///     assert!((moved.eval(s)? - arc.eval(phi(s))?).norm() < 1e-15);
    /// }
    /// # Ok::<(), spline_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`ErrorKind::InvalidArgument`] unless `factor` is positive and finite;
    /// [`ErrorKind::InvalidWeight`] when a weight overflows or underflows (a factor far from
    /// 1 on a curve of high degree).
    pub fn mobius_reparametrized(&self, factor: T) -> Result<Self> {
        if !(factor > T::zero() && factor.is_finite()) {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "the factor of a Möbius reparametrization must be positive and finite, got {}",
                    to_f64(factor)
                ),
            )
            .with_value(to_f64(factor))
            .with_interval(0.0, f64::INFINITY));
        }
        let curve = self.clamped();
        let p = curve.degree();
        let (a, b) = curve.domain();
        let width = b - a;
        let one = T::one();
        let normalised: Vec<T> = curve
            .knots()
            .knots()
            .iter()
            .map(|&u| ((u - a) / width).max(T::zero()).min(one))
            .collect();
        let moved: Vec<T> = normalised
            .iter()
            .map(|&x| {
                if x <= T::zero() || x >= one {
                    x
                } else {
                    factor * x / (one - x + factor * x)
                }
            })
            .collect();
        let denominator = |s: T| factor * (one - s) + s;
        let points: Vec<Homogeneous<T, D>> = curve
            .homogeneous()
            .control_points()
            .iter()
            .enumerate()
            .map(|(i, h)| {
                let scale = (i + 1..=i + p).fold(one, |acc, j| acc * denominator(moved[j]));
                Homogeneous::new(h.point * scale, h.weight * scale)
            })
            .collect();
        let knots = KnotVector::new(
            p,
            moved
                .iter()
                .map(|&s| if s >= one { b } else { a + width * s })
                .collect(),
        )?;
        Self::checked(crate::bspline::BSpline::new(knots, points)?)
    }
}
