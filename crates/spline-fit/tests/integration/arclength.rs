//! Adaptive approximation within a tolerance and reparametrisation by arc length, checked by
//! dense sampling against the maps, closed forms (the circle) and the speed of the result.

use nalgebra::Vector2;
use proptest::prelude::*;
use spline_core::ErrorKind;
use spline_fit::{AdaptiveApproximation, reparametrize_by_arc_length};
use spline_geom::{BSpline, NurbsCurve, ParamCurve};
use spline_testing::strategies::linspace;
use spline_testing::strategies::planar_curve;

/// The test's own arc length: 5-point Gauss–Legendre on a fine grid inside every piece
/// (error far below 1e-12 for these curves), inverted by Newton's method on one grid cell.
struct Reference<'a> {
    curve: &'a BSpline<f64, Vector2<f64>>,
    us: Vec<f64>,
    ss: Vec<f64>,
}

impl<'a> Reference<'a> {
    fn new(curve: &'a BSpline<f64, Vector2<f64>>) -> Self {
        let spans = curve.breaks().len() - 1;
        let us = curve.sample_params(2000usize.div_ceil(spans).max(32));
        let mut ss = vec![0.0];
        for w in us.windows(2) {
            let last = ss[ss.len() - 1];
            ss.push(last + Self::gauss(curve, w[0], w[1]));
        }
        Self { curve, us, ss }
    }

    fn gauss(curve: &BSpline<f64, Vector2<f64>>, a: f64, b: f64) -> f64 {
        let x = [
            0.0,
            0.538_469_310_105_683_1,
            -0.538_469_310_105_683_1,
            0.906_179_845_938_664,
            -0.906_179_845_938_664,
        ];
        let w = [
            0.568_888_888_888_888_9,
            0.478_628_670_499_366_5,
            0.478_628_670_499_366_5,
            0.236_926_885_056_189_1,
            0.236_926_885_056_189_1,
        ];
        let (m, h) = ((a + b) / 2.0, (b - a) / 2.0);
        (0..5)
            .map(|i| w[i] * curve.speed(m + h * x[i]).unwrap())
            .sum::<f64>()
            * h
    }

    fn total(&self) -> f64 {
        self.ss[self.ss.len() - 1]
    }

    fn param_at(&self, s: f64) -> f64 {
        let i = self
            .ss
            .partition_point(|&x| x <= s)
            .clamp(1, self.ss.len() - 1)
            - 1;
        let (u0, s0) = (self.us[i], self.ss[i]);
        let mut u = u0 + (self.us[i + 1] - u0) * ((s - s0) / (self.ss[i + 1] - s0)).clamp(0.0, 1.0);
        for _ in 0..8 {
            let f = s0 + Self::gauss(self.curve, u0, u) - s;
            u = (u - f / self.curve.speed(u).unwrap()).clamp(u0, self.us[i + 1]);
        }
        u
    }
}

#[test]
fn functions_within_the_tolerance() {
    for tol in [1e-3, 1e-6, 1e-10] {
        let f = |t: f64| Ok(Vector2::new(t.sin() * 3.0, (2.0 * t).cos()));
        let fit = AdaptiveApproximation::new(3, tol)
            .fit((0.0, 5.0), f)
            .unwrap();
        let worst = linspace(0.0, 5.0, 20_000)
            .into_iter()
            .map(|t| (fit.curve.eval(t).unwrap() - f(t).unwrap()).norm())
            .fold(0.0, f64::max);
        assert!(worst <= tol, "{worst:e} > {tol:e}");
        assert!(fit.max_error <= tol);
    }
}

#[test]
fn corners_keep_kinks() {
    // |t − 0.3| is piecewise linear: with a corner there a cubic fits it at once.
    let fit = AdaptiveApproximation::new(3, 1e-12)
        .corners(&[0.3])
        .fit((0.0, 1.0), |t: f64| Ok((t - 0.3).abs()))
        .unwrap();
    assert_eq!(fit.passes, 0);
    assert_eq!(fit.curve.knots().multiplicity(0.3), 3);
    // Without the corner the kink needs many refinements and still fails a small budget.
    let e = AdaptiveApproximation::new(3, 1e-12)
        .max_pieces(40)
        .fit((0.0, 1.0), |t: f64| Ok((t - 0.3).abs()))
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::ToleranceExceeded);
    assert!(e.message().contains("best deviation"), "{}", e.message());
}

#[test]
fn bad_input_is_an_error() {
    let f = |t: f64| Ok(t);
    let e = AdaptiveApproximation::new(3, 0.0)
        .fit((0.0, 1.0), f)
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidTolerance);
    let e = AdaptiveApproximation::new(3, 1e-3)
        .fit((1.0, 1.0), f)
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::EmptyDomain);
    let e = AdaptiveApproximation::new(3, 1e-3)
        .breaks(&[2.0])
        .fit((0.0, 1.0), f)
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::OutOfDomain);
    let e = AdaptiveApproximation::new(99, 1e-3)
        .fit((0.0, 1.0), f)
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::DegreeTooHigh);
    let e = AdaptiveApproximation::new(3, 1e-3)
        .fit((0.0, 1.0), |_| {
            Err::<f64, _>(spline_core::Error::non_finite("f"))
        })
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
}

/// A tolerance below the rounding of the values is refused after the first fit instead of
/// refining to the limit of pieces (the fuzzing campaign's `arclength --reparametrize
/// --tolerance 1e-19` ran over 20 s), at every scale; one just above it is still met.
#[test]
fn tolerances_below_the_rounding_are_refused_at_once() {
    for scale in [1e-300, 1.0, 1e6, 1e300] {
        let f = |t: f64| Ok(scale * t.sin());
        for tolerance in [1e-19 * scale, 5e-324] {
            let e = AdaptiveApproximation::new(3, tolerance)
                .fit((0.0, 3.0), f)
                .unwrap_err();
            assert_eq!(e.kind(), ErrorKind::InvalidTolerance, "{scale:e}: {e}");
            assert!(e.message().contains("units in the last place"), "{e}");
        }
        let fit = AdaptiveApproximation::new(3, 1e-10 * scale)
            .fit((0.0, 3.0), f)
            .unwrap();
        assert!(fit.max_error <= 1e-10 * scale);
    }
    // A curve of size 4 reparametrised by arc length within 1e-19 (absolute).
    let curve = spline_geom::BSpline::from_knots(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        vec![
            nalgebra::Vector2::new(0.0, 0.0),
            nalgebra::Vector2::new(1.0, 2.0),
            nalgebra::Vector2::new(3.0, 2.0),
            nalgebra::Vector2::new(4.0, 0.0),
        ],
    )
    .unwrap();
    let e = spline_fit::reparametrize_by_arc_length(&curve, 3, 1e-19).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidTolerance, "{e}");
}

#[test]
fn the_circle_by_arc_length() {
    let circle = NurbsCurve::from_knots(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0],
        vec![
            Vector2::new(1.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(-1.0, 1.0),
            Vector2::new(-1.0, 0.0),
            Vector2::new(-1.0, -1.0),
            Vector2::new(0.0, -1.0),
            Vector2::new(1.0, -1.0),
            Vector2::new(1.0, 0.0),
        ],
        vec![
            1.0,
            0.5f64.sqrt(),
            1.0,
            0.5f64.sqrt(),
            1.0,
            0.5f64.sqrt(),
            1.0,
            0.5f64.sqrt(),
            1.0,
        ],
    )
    .unwrap();
    for tol in [1e-4, 1e-8] {
        let fit = reparametrize_by_arc_length(&circle, 3, tol).unwrap();
        let (a, b) = fit.curve.domain();
        assert_eq!(a, 0.0);
        assert!((b - std::f64::consts::TAU).abs() < 1e-10, "length {b}");
        for s in linspace(0.0, b, 5000) {
            let e = (fit.curve.eval(s).unwrap() - Vector2::new(s.cos(), s.sin())).norm();
            assert!(e <= tol, "s = {s}: {e:e}");
        }
    }
    assert_eq!(
        reparametrize_by_arc_length(&circle, 3, -1.0)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidTolerance
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]

    #[test]
    fn random_curves_by_arc_length(curve in planar_curve(2, 4, true), k in 0usize..2) {
        let tol = [1e-3, 1e-6][k];
        let reference = Reference::new(&curve);
        let length = reference.total();
        // Curves with (nearly) stationary points have no arc-length parametrisation of
        // bounded speed variation; keep regular ones.
        let (a, b) = curve.domain();
        let min_speed = linspace(a, b, 400).into_iter().map(|u| curve.speed(u).unwrap()).fold(f64::INFINITY, f64::min);
        prop_assume!(length > 1e-3 && min_speed > 1e-2 * length);
        let fit = reparametrize_by_arc_length(&curve, 3, tol).unwrap();
        let (s0, s1) = fit.curve.domain();
        // The table's lengths are accurate to a thousandth of the tolerance.
        prop_assert!(s0 == 0.0 && (s1 - length).abs() < 1e-3 * tol + 1e-12, "{} vs {}", s1, length);
        for s in linspace(0.0, s1, 300) {
            let u = reference.param_at(s.min(length));
            let e = (fit.curve.eval(s).unwrap() - curve.eval(u).unwrap()).norm();
            prop_assert!(e <= tol, "s = {}: {:e}", s, e);
        }
        // Unit speed, to the accuracy of the positions (a derivative of an approximation).
        let speeds: Vec<f64> = linspace(0.0, s1, 300).into_iter().map(|s| fit.curve.speed(s).unwrap()).collect();
        let worst = speeds.iter().map(|v| (v - 1.0).abs()).fold(0.0, f64::max);
        prop_assert!(worst < 100.0 * tol.sqrt(), "speed off by {}", worst);
    }
}
