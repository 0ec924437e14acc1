//! Inflections and curvature extrema of planar curves of every kind: polynomial curves
//! through the invariants `h4` and `g = h1 h2 − 3 h3 h4` ([`PlanarInvariants`]), rational
//! curves through their homogeneous analogues, each a B-spline function whose sign changes
//! are found by root isolation.

use crate::curves::{Differentiated, Form, Invariant, PlanarInvariants};
use crate::numerator::Tracked;
use crate::roots::{sign_change_params, zeros};
use nalgebra::{SVector, Vector2};
use spline_core::{Error, ErrorKind, Result, Scalar, cast, to_f64};
use spline_geom::{BSpline, Bezier, Homogeneous, NurbsCurve, PeriodicBSpline, PlanarCurve};

/// The inflections and curvature extrema of a planar curve.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarFeatures<T> {
    /// Parameters where the signed curvature changes sign.
    pub inflections: Vec<T>,
    /// Parameters where the signed curvature has a local extremum.
    pub curvature_extrema: Vec<T>,
    /// The curvature, when it is constant (a circle, a straight line: the numerator of
    /// `κ′` vanishes identically); there are then no extrema.
    pub constant_curvature: Option<T>,
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

/// The default accuracy of curve features relative to the width of the domain: the
/// front ends (tool, studio, Python) locate features to this fraction of `b − a`
/// ([`default_feature_accuracy`]).
pub const RELATIVE_FEATURE_ACCURACY: f64 = 1e-12;

/// The default absolute accuracy of the features of a curve on the domain `(a, b)`:
/// [`RELATIVE_FEATURE_ACCURACY`] of its width (of 1 where the width is not positive, so that
/// the accuracy is always valid).
///
/// ```
/// let accuracy = spline_algebra::default_feature_accuracy((2.0f64, 6.0));
/// assert_eq!(accuracy, 4e-12);
/// ```
pub fn default_feature_accuracy<T: Scalar>((a, b): (T, T)) -> T {
    let width = b - a;
    if width > T::zero() {
        cast::<T>(RELATIVE_FEATURE_ACCURACY) * width
    } else {
        cast::<T>(RELATIVE_FEATURE_ACCURACY)
    }
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
/// domain are not reported (the sign is known on one side only), except at the seam of a
/// closed curve (its end meets its start with the same unit tangent): there the signs
/// before the end and after the start decide, and the feature is reported at the start.
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
/// [`ErrorKind::InvalidArgument`] for degree below 2; [`ErrorKind::InvalidTolerance`] for
/// an accuracy that is not positive and finite;
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
pub(crate) fn leg_scale<T: Scalar>(points: &[Vector2<T>]) -> T {
    let legs = points
        .windows(2)
        .fold(0.0f64, |m, w| m.max(to_f64((w[1] - w[0]).amax())));
    cast(spline_core::power_of_two_scale(legs))
}

/// [`ErrorKind::DegenerateGeometry`] if the squared speed (or its rational analogue) has a
/// zero.
pub(crate) fn check_regular<T: Scalar>(squared_speed: &BSpline<T, T>, accuracy: T) -> Result<()> {
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
        let constant = g.control_points().iter().all(|c| *c == T::zero());
        let mut features = PlanarFeatures {
            inflections: sign_change_params(&h4, accuracy)?,
            curvature_extrema: sign_change_params(&g, accuracy)?,
            constant_curvature: constant.then(|| middle_curvature(self)).transpose()?,
        };
        if !constant {
            add_seam_features(self, &h4, &g, &mut features)?;
        }
        Ok(features)
    }
}

/// A closed curve: the features of one period `[a, a + T)`, found exactly on its wrapped
/// container (whose two ends are the closing point): those inside the period as on any
/// B-spline, and at `a` an inflection or a curvature extremum where the numerator changes
/// sign across the closing point (judged by its one-sided values, or its slope where it
/// vanishes there). A closing point that is a corner (a knot of multiplicity `p`) has none.
impl<T: Scalar> CurveFeatures<T> for PeriodicBSpline<T, Vector2<T>> {
    fn features(&self, accuracy: T) -> Result<PlanarFeatures<T>> {
        self.wrapped().features(accuracy)
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
        check_feature_degree(self.degree(), (8, 6), "curvature-extremum")?;
        // Exact power-of-two scalings: of the points (the features do not depend on the
        // size of the curve) and of the weights (the curve does not depend on their scale).
        // And a translation to the middle of the control points: the numerators combine
        // the coordinates themselves, whose rounding would otherwise grow with the distance
        // from the origin.
        let frame = Normalisation::of(self.control_points(), self.weights());
        let (det, g) = rational_planar(self, &frame, false, accuracy)?;
        let constant = g.is_zero();
        let (det, g) = (det.value, g.value);
        let mut features = PlanarFeatures {
            inflections: sign_change_params(&det, accuracy)?,
            curvature_extrema: sign_change_params(&g, accuracy)?,
            constant_curvature: constant.then(|| middle_curvature(self)).transpose()?,
        };
        if !constant {
            add_seam_features(self, &det, &g, &mut features)?;
        }
        Ok(features)
    }
}

/// The numerators of the curvature and of its derivative of a rational planar curve, each a
/// B-spline function of the parameter, with their Jacobians with respect to the weighted
/// control points: the variables are $[w_0 x_0, w_0 y_0, w_0, w_1 x_1, \dots]$.
///
/// For `C = (X, Y) / W` with homogeneous container `P = (X, Y, W)`: the inflection numerator
/// is $D = \det(P, P', P'') = W^3\, C' \wedge C''$, the curvature-extremum numerator
/// $G = (D' W + 3 D W')\, N \cdot N - 3 D W\, N \cdot N'$ with $N = W^2 C'$ and
/// $N' = (X''W - XW'', Y''W - YW'')$, so that $\kappa = D W^3 / |N|^3$ and
/// $\kappa' = W^2 G / |N|^5$ (both denominators positive). Degrees `3p − 3` and `8p − 6`.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::NurbsCurve;
/// let w = std::f64::consts::FRAC_1_SQRT_2;
/// let arc = NurbsCurve::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(2.0, 0.0), Vector2::new(2.0, 1.0), Vector2::new(0.0, 1.0)],
///     vec![1.0, w, 1.0])?;
/// let n = spline_algebra::rational_planar_numerators(&arc)?;
/// assert_eq!(n.curvature_extremum.jacobian.ncols(), 9); // three weighted points (wx, wy, w)
/// // A quarter of an ellipse: D > 0 (no inflection), G < 0 (curvature decreasing).
/// assert!(n.inflection.value.eval(0.5)? > 0.0 && n.curvature_extremum.value.eval(0.5)? < 0.0);
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] for degree below 2; [`ErrorKind::DegreeTooHigh`] if
/// `8p − 6` exceeds [`spline_core::MAX_DEGREE`].
pub fn rational_planar_numerators<T: Scalar>(
    curve: &NurbsCurve<T, 2>,
) -> Result<RationalNumerators<T>> {
    check_feature_degree(curve.degree(), (8, 6), "curvature-extremum")?;
    let (det, g) = rational_planar(curve, &Normalisation::identity(), true, T::zero())?;
    Ok(RationalNumerators {
        inflection: det.differentiated(),
        curvature_extremum: g.differentiated(),
    })
}

/// The Hessians of the numerators of [`rational_planar_numerators`] with respect to the
/// weighted control points `x`: `[inflection, curvature_extremum]`, row `k` of each the
/// symmetric matrix $\partial^2 c_k / \partial x \partial x$. The Jacobian computation is
/// run on dual numbers ([`num_dual::Dual64`]) with the seed on one variable at a time: the
/// dual parts of its exact Jacobian are the Hessian's columns (forward mode over the product
/// rule), `3n` runs for `n` control points.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::NurbsCurve;
/// let w = std::f64::consts::FRAC_1_SQRT_2;
/// let arc = NurbsCurve::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(2.0, 0.0), Vector2::new(2.0, 1.0), Vector2::new(0.0, 1.0)],
///     vec![1.0, w, 1.0])?;
/// let [d, g] = spline_algebra::rational_planar_hessians(&arc)?;
/// assert_eq!((d.left_dim(), g.left_dim()), (9, 9));
/// # Ok::<(), spline_core::Error>(())
/// ```
///
/// # Errors
/// As [`rational_planar_numerators`].
pub fn rational_planar_hessians(
    curve: &NurbsCurve<f64, 2>,
) -> Result<[crate::SparseBilinear<f64>; 2]> {
    numerator_hessians(curve, |dual| {
        let n = rational_planar_numerators(dual)?;
        Ok([n.inflection, n.curvature_extremum])
    })
}

/// The Hessians of two numerators with respect to the weighted control points of `curve`
/// (`D + 1` variables a point: `w P` then `w`): `numerators` — a function computing the
/// numerators with their exact Jacobians — runs on dual numbers seeded on one variable at a
/// time, and the dual parts of its Jacobians are the Hessians' columns.
pub(crate) fn numerator_hessians<const D: usize>(
    curve: &NurbsCurve<f64, D>,
    numerators: impl Fn(
        &NurbsCurve<num_dual::Dual64, D>,
    ) -> Result<[Differentiated<num_dual::Dual64>; 2]>,
) -> Result<[crate::SparseBilinear<f64>; 2]> {
    use num_dual::Dual64;
    let h = curve.homogeneous();
    let stride = D + 1;
    let nx = stride * h.control_points().len();
    let knots: Vec<Dual64> = h.knots().knots().iter().map(|&k| Dual64::from(k)).collect();
    let mut rows: [Vec<Vec<(usize, usize, f64)>>; 2] = [Vec::new(), Vec::new()];
    for j in 0..nx {
        let seeded = h
            .control_points()
            .iter()
            .enumerate()
            .map(|(i, q)| {
                let d =
                    |k: usize, v: f64| Dual64::new(v, if stride * i + k == j { 1.0 } else { 0.0 });
                Homogeneous::new(SVector::from_fn(|k, _| d(k, q.point[k])), d(D, q.weight))
            })
            .collect();
        let dual =
            NurbsCurve::from_homogeneous(BSpline::from_knots(h.degree(), knots.clone(), seeded)?)?;
        for (target, numerator) in rows.iter_mut().zip(numerators(&dual)?) {
            target.resize_with(numerator.jacobian.nrows(), Vec::new);
            for (r, c, v) in numerator.jacobian.triplet_iter() {
                if v.eps != 0.0 {
                    target[r].push((c, j, v.eps));
                }
            }
        }
    }
    let [first, second] = rows;
    Ok([
        crate::SparseBilinear::from_rows(nx, nx, first)?,
        crate::SparseBilinear::from_rows(nx, nx, second)?,
    ])
}

/// The feature numerators of a curve with Jacobians ([`rational_planar_numerators`]).
#[derive(Clone, Debug)]
pub struct RationalNumerators<T> {
    /// The numerator whose sign is the sign of the curvature (planar curves).
    pub inflection: Differentiated<T>,
    /// The numerator whose sign is the sign of the derivative of the curvature.
    pub curvature_extremum: Differentiated<T>,
}

/// [`ErrorKind::InvalidArgument`] below degree 2, [`ErrorKind::DegreeTooHigh`] if the
/// numerator of degree `factor · p − offset` is above [`spline_core::MAX_DEGREE`].
pub(crate) fn check_feature_degree(
    p: usize,
    (factor, offset): (usize, usize),
    what: &str,
) -> Result<()> {
    if p < 2 {
        return Err(Error::new(
            ErrorKind::InvalidArgument,
            format!(
                "curvature features need degree 2 or more, got {p} (a polyline has zero curvature wherever it is defined)"
            ),
        )
        .with_value(p as f64)
        .with_interval(2.0, f64::INFINITY));
    }
    let degree = factor * p - offset;
    if degree > spline_core::MAX_DEGREE {
        return Err(Error::new(
            ErrorKind::DegreeTooHigh,
            format!(
                "the {what} numerator of a curve of degree {p} has degree {degree}, above the supported maximum"
            ),
        ));
    }
    Ok(())
}

/// The signed curvature in the middle of the domain (of a curve whose curvature is constant).
/// The features at the seam of a closed curve: where the curve ends where it starts with
/// the same unit tangent (a closed contour, an ellipse made of rational arcs), the sign of
/// `κ` (`inflection`'s numerator) and of `κ′` (`extremum`'s numerator) just before the end
/// and just after the start decide an inflection or an extremum at the start `a`, which the
/// open-interval analysis cannot see (the sign is known on one side only there).
fn add_seam_features<T: Scalar, C: PlanarCurve<T>>(
    curve: &C,
    inflection: &BSpline<T, T>,
    extremum: &BSpline<T, T>,
    features: &mut PlanarFeatures<T>,
) -> Result<()> {
    let (a, b) = curve.domain();
    let size = curve
        .control_polygon()
        .iter()
        .fold(T::zero(), |m, p| m.max(p.amax()));
    let closes = (curve.eval(a)? - curve.eval(b)?).amax() <= size * cast::<T>(1e-12);
    if !closes {
        return Ok(());
    }
    let turn = (curve.unit_tangent(a)? - curve.unit_tangent(b)?).norm();
    if !(turn <= cast::<T>(1e-9)) {
        return Ok(());
    }
    // Signs one-sidedly: the value at `a` is the right limit, at `b` the left limit; where
    // the numerator vanishes at the seam (an ellipse's vertex), its slope gives the sign
    // next to it.
    let crosses = |f: &BSpline<T, T>| -> Result<bool> {
        let zero = f
            .control_points()
            .iter()
            .fold(T::zero(), |m, c| m.max(c.abs()))
            * cast::<T>(1e-12);
        let side = |u: T, inward: T| -> Result<T> {
            let d = f.derivatives(u, 1)?;
            Ok(if d[0].abs() > zero {
                d[0]
            } else {
                d[1] * inward
            })
        };
        let (before, after) = (side(b, -T::one())?, side(a, T::one())?);
        Ok(before * after < T::zero())
    };
    if crosses(inflection)? && features.inflections.first() != Some(&a) {
        features.inflections.insert(0, a);
    }
    if crosses(extremum)? && features.curvature_extrema.first() != Some(&a) {
        features.curvature_extrema.insert(0, a);
    }
    Ok(())
}

fn middle_curvature<T: Scalar, C: PlanarCurve<T>>(curve: &C) -> Result<T> {
    let (a, b) = curve.domain();
    curve.signed_curvature((a + b) * cast::<T>(0.5))
}

/// An exact change of coordinates of homogeneous points: `(X − W m) / (s · ws)` for the
/// coordinates, `W / ws` for the weight, with `s` and `ws` powers of two.
pub(crate) struct Normalisation<T, const D: usize> {
    pub(crate) middle: SVector<T, D>,
    pub(crate) scale: T,
    pub(crate) wscale: T,
}

impl<T: Scalar, const D: usize> Normalisation<T, D> {
    pub(crate) fn identity() -> Self {
        Self {
            middle: SVector::zeros(),
            scale: T::one(),
            wscale: T::one(),
        }
    }

    /// The middle of the control points' bounding box, a power of two near the largest step
    /// between consecutive points and one near the largest weight.
    pub(crate) fn of(points: &[SVector<T, D>], weights: &[T]) -> Self {
        let legs = points
            .windows(2)
            .fold(0.0f64, |m, w| m.max(to_f64((w[1] - w[0]).amax())));
        let largest = weights.iter().fold(0.0f64, |m, &w| m.max(to_f64(w)));
        let (lo, hi) = points
            .iter()
            .fold((points[0], points[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
        Self {
            middle: (lo + hi) * cast::<T>(0.5),
            scale: cast(spline_core::power_of_two_scale(legs)),
            wscale: cast(spline_core::power_of_two_scale(largest)),
        }
    }

    /// The leaves: coordinate `k < D` and the weight (`k = D`), with Jacobians when asked.
    pub(crate) fn leaves(
        &self,
        h: &BSpline<T, Homogeneous<T, D>>,
        jacobian: bool,
    ) -> Vec<Tracked<T>> {
        let sw = self.scale * self.wscale;
        (0..=D)
            .map(|k| {
                let mut d = vec![T::zero(); D + 1];
                if k < D {
                    d[k] = T::one() / sw;
                    d[D] = -self.middle[k] / sw;
                } else {
                    d[D] = T::one() / self.wscale;
                }
                Tracked::coordinate(
                    h,
                    |q| {
                        if k < D {
                            (q.point[k] - q.weight * self.middle[k]) / sw
                        } else {
                            q.weight / self.wscale
                        }
                    },
                    jacobian.then_some(d.as_slice()),
                )
            })
            .collect()
    }
}

/// `D` and `G` of [`rational_planar_numerators`] in the coordinates of `frame` (without
/// Jacobians: cleaned of rounding); with `accuracy > 0` the curve is first checked to be
/// regular.
fn rational_planar<T: Scalar>(
    curve: &NurbsCurve<T, 2>,
    frame: &Normalisation<T, 2>,
    jacobian: bool,
    accuracy: T,
) -> Result<(Tracked<T>, Tracked<T>)> {
    let [x, y, w]: [Tracked<T>; 3] = frame
        .leaves(curve.homogeneous(), jacobian)
        .try_into()
        .map_err(|_| Error::new(ErrorKind::InvalidArgument, "three coordinates"))?;
    let (x1, y1, w1) = (x.derivative(1)?, y.derivative(1)?, w.derivative(1)?);
    let (x2, y2, w2) = (x.derivative(2)?, y.derivative(2)?, w.derivative(2)?);
    // a · b − c · e
    let cross = |a: &Tracked<T>, b: &Tracked<T>, c: &Tracked<T>, e: &Tracked<T>| {
        a.times(b)?.minus(&c.times(e)?)
    };
    // N, N' and D = X (Y'W'' − W'Y'') − Y (X'W'' − W'X'') + W (X'Y'' − Y'X'').
    let nx = cross(&x1, &w, &x, &w1)?;
    let ny = cross(&y1, &w, &y, &w1)?;
    let nx1 = cross(&x2, &w, &x, &w2)?;
    let ny1 = cross(&y2, &w, &y, &w2)?;
    let det = x
        .times(&cross(&y1, &w2, &w1, &y2)?)?
        .minus(&y.times(&cross(&x1, &w2, &w1, &x2)?)?)?
        .plus(&w.times(&cross(&x1, &y2, &y1, &x2)?)?)?
        .cleaned_if(!jacobian);
    let nn = nx.times(&nx)?.plus(&ny.times(&ny)?)?;
    if accuracy > T::zero() {
        check_regular(&nn.value, accuracy)?;
    }
    let nn1 = nx.times(&nx1)?.plus(&ny.times(&ny1)?)?;
    let three: T = cast(3.0);
    let lead = det
        .derivative(1)?
        .times(&w)?
        .plus(&det.times(&w1)?.scaled(three))?;
    let g = lead
        .times(&nn)?
        .minus(&det.times(&w)?.times(&nn1)?.scaled(three))?
        .cleaned_if(!jacobian);
    Ok((det, g))
}
