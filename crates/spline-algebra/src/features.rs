//! Inflections and curvature extrema of planar curves of every kind: polynomial curves
//! through the invariants `h4` and `g = h1 h2 − 3 h3 h4` ([`PlanarInvariants`]), rational
//! curves through their homogeneous analogues, each a B-spline function whose sign changes
//! are found by root isolation.

use crate::curves::{Form, Invariant, PlanarInvariants};
use crate::product::{linear_combination, product};
use crate::roots::{sign_change_params, zeros};
use nalgebra::Vector2;
use spline_core::{Error, ErrorKind, Result, Scalar, cast, to_f64};
use spline_geom::{BSpline, Bezier, NurbsCurve};

/// The inflections and curvature extrema of a planar curve.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarFeatures<T> {
    /// Parameters where the signed curvature changes sign.
    pub inflections: Vec<T>,
    /// Parameters where the signed curvature has a local extremum.
    pub curvature_extrema: Vec<T>,
}

/// A planar curve whose inflections and curvature extrema can be located exactly: every
/// kind of planar curve (B-spline, Bézier, NURBS).
pub trait CurveFeatures<T: Scalar> {
    /// The inflections and curvature extrema, located to `accuracy` (absolute, in
    /// parameter units); see [`planar_features`].
    ///
    /// # Errors
    /// As [`planar_features`].
    fn features(&self, accuracy: T) -> Result<PlanarFeatures<T>>;
}

/// The inflections and curvature extrema of a regular planar curve of any kind
/// ([`CurveFeatures`]) of degree at least 2, located to `accuracy` (absolute, in parameter
/// units) by [`crate::zeros`]:
///
/// - inflections are the zeros of $c' \wedge c''$ where it changes sign (a double zero, as
///   at the flat point of `(u, u⁴)`, is not an inflection);
/// - curvature extrema are the zeros of the numerator of $\kappa'$ where it changes sign
///   (`g = h1 h2 − 3 h3 h4` for polynomial curves, `κ' = g / h_1^{5/2}`), and the knots where
///   it jumps across zero: a cubic with simple knots is only `C²`, its `κ′` is discontinuous
///   at the knots, and a jump of `κ′` from one sign to the other is a (corner) extremum of
///   `κ` ([`crate::sign_change_params`]).
///
/// Where the function vanishes on a whole piece (a straight segment, a circular arc) and
/// changes sign across it, the middle of the piece is reported. Zeros at the ends of the
/// domain are not reported (the sign is known on one side only).
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::BSpline;
/// // The graph (u, u³ − u) on [−1, 1] as a cubic Bézier curve: one inflection, at u = 0.
/// let curve = BSpline::from_knots(3, vec![-1.0f64, -1., -1., -1., 1., 1., 1., 1.], vec![
///     Vector2::new(-1.0, 0.0), Vector2::new(-1.0 / 3.0, 4.0 / 3.0),
///     Vector2::new(1.0 / 3.0, -4.0 / 3.0), Vector2::new(1.0, 0.0)])?;
/// let features = spline_algebra::planar_features(&curve, 1e-12)?;
/// assert_eq!(features.inflections.len(), 1);
/// assert!(features.inflections[0].abs() < 1e-12);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for degree below 2 or a bad accuracy;
/// [`ErrorKind::DegreeTooHigh`] when the numerator of `κ'` is above
/// [`spline_core::MAX_DEGREE`] (`4p − 6` for polynomial curves, `8p − 6` for rational ones);
/// [`ErrorKind::DegenerateGeometry`] if the velocity vanishes somewhere (the curve is not
/// regular, curvature is undefined there).
pub fn planar_features<T: Scalar, C: CurveFeatures<T> + ?Sized>(
    curve: &C,
    accuracy: T,
) -> Result<PlanarFeatures<T>> {
    curve.features(accuracy)
}

/// The inflections of a planar curve ([`planar_features`]).
///
/// # Errors
/// As [`planar_features`].
pub fn inflections<T: Scalar, C: CurveFeatures<T> + ?Sized>(
    curve: &C,
    accuracy: T,
) -> Result<Vec<T>> {
    Ok(curve.features(accuracy)?.inflections)
}

/// The curvature extrema of a planar curve ([`planar_features`]).
///
/// # Errors
/// As [`planar_features`].
pub fn curvature_extrema<T: Scalar, C: CurveFeatures<T> + ?Sized>(
    curve: &C,
    accuracy: T,
) -> Result<Vec<T>> {
    Ok(curve.features(accuracy)?.curvature_extrema)
}

/// A power of two near the largest coordinate step between consecutive points: dividing by
/// it is exact, and the invariants (products of up to eight coordinates of derivatives) of
/// the scaled points neither overflow nor underflow.
fn leg_scale<T: Scalar>(points: &[Vector2<T>]) -> T {
    let legs = points
        .windows(2)
        .fold(0.0f64, |m, w| m.max(to_f64((w[1] - w[0]).amax())));
    cast(spline_core::power_of_two_scale(legs))
}

/// [`ErrorKind::DegenerateGeometry`] if the squared speed (or its rational analogue) has a
/// zero.
fn check_regular<T: Scalar>(squared_speed: &BSpline<T, T>, accuracy: T) -> Result<()> {
    match zeros(squared_speed, accuracy)?.first() {
        Some(z) => Err(Error::new(
            ErrorKind::DegenerateGeometry,
            format!(
                "the curve is not regular: its velocity vanishes at u = {}",
                to_f64(z.at())
            ),
        )),
        None => Ok(()),
    }
}

impl<T: Scalar> CurveFeatures<T> for BSpline<T, Vector2<T>> {
    fn features(&self, accuracy: T) -> Result<PlanarFeatures<T>> {
        let algebra = PlanarInvariants::new(self.knots())?;
        // The features do not change when the curve is scaled.
        let scale = leg_scale(self.control_points());
        let points: Vec<Vector2<T>> = self.control_points().iter().map(|p| p / scale).collect();
        let h1 = algebra.invariant_value(Invariant::H1, &points, Form::Bernstein)?;
        check_regular(&h1, accuracy)?;
        let h4 = algebra.invariant_value(Invariant::H4, &points, Form::Bernstein)?;
        let g = algebra.g_value(&points, Form::Bernstein)?;
        Ok(PlanarFeatures {
            inflections: sign_change_params(&h4, accuracy)?,
            curvature_extrema: sign_change_params(&g, accuracy)?,
        })
    }
}

impl<T: Scalar> CurveFeatures<T> for Bezier<T, Vector2<T>> {
    fn features(&self, accuracy: T) -> Result<PlanarFeatures<T>> {
        self.to_bspline()?.features(accuracy)
    }
}

/// For a rational curve `C = (X, Y) / W` with homogeneous container `P = (X, Y, W)`:
/// $C' \wedge C'' = D / W^3$ with $D = \det(P, P', P'')$ and $C' = N / W^2$ with
/// $N = (X'W - XW', Y'W - YW')$, so $\kappa = D W^3 / |N|^3$ and
/// $\kappa' = W^2 G / |N|^5$ with
/// $G = (D' W + 3 D W')\\, N \cdot N - 3 D W\\, N \cdot N'$, $N' = (X''W - XW'', Y''W - YW'')$.
/// Inflections are the sign changes of `D`, curvature extrema those of `G` (for `W ≡ 1`,
/// `D = h4` and `G = g`).
impl<T: Scalar> CurveFeatures<T> for NurbsCurve<T, 2> {
    fn features(&self, accuracy: T) -> Result<PlanarFeatures<T>> {
        if self.is_polynomial() {
            if let Some(polynomial) = self.to_bspline() {
                return polynomial.features(accuracy);
            }
        }
        let p = self.degree();
        if p < 2 {
            return Err(Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "curvature features need degree 2 or more, got {p} (a polyline has zero curvature wherever it is defined)"
                ),
            ));
        }
        if 8 * p - 6 > spline_core::MAX_DEGREE {
            return Err(Error::new(
                ErrorKind::DegreeTooHigh,
                format!(
                    "the curvature-extremum numerator of a rational curve of degree {p} has degree {}, above the supported maximum",
                    8 * p - 6
                ),
            ));
        }
        // Exact power-of-two scalings: of the points (the features do not depend on the
        // size of the curve) and of the weights (the curve does not depend on their scale).
        let scale = leg_scale(self.control_points());
        let largest = self.weights().iter().fold(0.0f64, |m, &w| m.max(to_f64(w)));
        let wscale: T = cast(spline_core::power_of_two_scale(largest));
        // And a translation to the middle of the control points: the numerators combine
        // the coordinates themselves, whose rounding would otherwise grow with the distance
        // from the origin.
        let (lo, hi) = self.control_points().iter().fold(
            (self.control_points()[0], self.control_points()[0]),
            |(lo, hi), p| (lo.inf(p), hi.sup(p)),
        );
        let half: T = cast(0.5);
        let middle = (lo + hi) * half;
        let h = self.homogeneous();
        let coordinate =
            |f: &dyn Fn(&spline_geom::Homogeneous<T, 2>) -> T| h.map_control_points(|q| f(q));
        let x = Tracked::leaf(coordinate(&|q| {
            (q.point.x - q.weight * middle.x) / scale / wscale
        }));
        let y = Tracked::leaf(coordinate(&|q| {
            (q.point.y - q.weight * middle.y) / scale / wscale
        }));
        let w = Tracked::leaf(coordinate(&|q| q.weight / wscale));
        let (x1, y1, w1) = (x.derivative(1)?, y.derivative(1)?, w.derivative(1)?);
        let (x2, y2, w2) = (x.derivative(2)?, y.derivative(2)?, w.derivative(2)?);
        let (one, three): (T, T) = (T::one(), cast(3.0));
        // a · b − c · e
        let cross = |a: &Tracked<T>, b: &Tracked<T>, c: &Tracked<T>, e: &Tracked<T>| {
            Tracked::combination(one, &a.times(b)?, -one, &c.times(e)?)
        };
        // N, N' and D = X (Y'W'' − W'Y'') − Y (X'W'' − W'X'') + W (X'Y'' − Y'X'').
        let nx = cross(&x1, &w, &x, &w1)?;
        let ny = cross(&y1, &w, &y, &w1)?;
        let nx1 = cross(&x2, &w, &x, &w2)?;
        let ny1 = cross(&y2, &w, &y, &w2)?;
        let det = Tracked::combination(
            one,
            &Tracked::combination(
                one,
                &x.times(&cross(&y1, &w2, &w1, &y2)?)?,
                -one,
                &y.times(&cross(&x1, &w2, &w1, &x2)?)?,
            )?,
            one,
            &w.times(&cross(&x1, &y2, &y1, &x2)?)?,
        )?
        .cleaned();
        let nn = Tracked::combination(one, &nx.times(&nx)?, one, &ny.times(&ny)?)?;
        check_regular(&nn.value, accuracy)?;
        let nn1 = Tracked::combination(one, &nx.times(&nx1)?, one, &ny.times(&ny1)?)?;
        let lead =
            Tracked::combination(one, &det.derivative(1)?.times(&w)?, three, &det.times(&w1)?)?;
        let g = Tracked::combination(one, &lead.times(&nn)?, -three, &det.times(&w)?.times(&nn1)?)?
            .cleaned();
        let (det, g) = (det.value, g.value);
        Ok(PlanarFeatures {
            inflections: sign_change_params(&det, accuracy)?,
            curvature_extrema: sign_change_params(&g, accuracy)?,
        })
    }
}

/// A B-spline function with a bound on the magnitudes that entered each coefficient (sums
/// of absolute values of the terms, through products and linear combinations): where a
/// coefficient is below `1e-10` of its magnitude it is rounding left by cancellation, not
/// a value. A circle's curvature-extremum numerator, a straight segment's curvature
/// numerator cancel that way, and sign changes of the noise would be reported as features.
struct Tracked<T: Scalar> {
    value: BSpline<T, T>,
    magnitude: BSpline<T, T>,
}

impl<T: Scalar> Tracked<T> {
    /// An input (a coordinate or a derivative): its magnitudes are its coefficients' sizes.
    fn leaf(value: BSpline<T, T>) -> Self {
        let magnitude = value.map_control_points(|&c| c.abs());
        Self { value, magnitude }
    }

    fn derivative(&self, order: usize) -> Result<Self> {
        Ok(Self::leaf(self.value.derivative(order)?))
    }

    /// The product; products of non-negative coefficients bound those of the product.
    fn times(&self, other: &Self) -> Result<Self> {
        Ok(Self {
            value: product(&self.value, &other.value)?,
            magnitude: product(&self.magnitude, &other.magnitude)?,
        })
    }

    /// `alpha · a + beta · b`, with magnitude `|alpha| |a| + |beta| |b|`.
    fn combination(alpha: T, a: &Self, beta: T, b: &Self) -> Result<Self> {
        Ok(Self {
            value: linear_combination(alpha, &a.value, beta, &b.value)?,
            magnitude: linear_combination(alpha.abs(), &a.magnitude, beta.abs(), &b.magnitude)?,
        })
    }

    /// The coefficients that are rounding of cancelled terms set to zero (and the
    /// magnitudes of what remains restarted from the values).
    fn cleaned(self) -> Self {
        let threshold: T = cast(1e-10);
        let points = self
            .value
            .control_points()
            .iter()
            .zip(self.magnitude.control_points())
            .map(|(&v, &m)| {
                if v.abs() <= threshold * m {
                    T::zero()
                } else {
                    v
                }
            })
            .collect();
        Self::leaf(BSpline::new_unchecked(self.value.knots().clone(), points))
    }
}
