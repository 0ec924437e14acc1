//! The cusps of offsets against dense sampling of κ d − 1 (the test's own curvature from
//! the derivatives) on random cubic and quartic curves, and bad input.

use nalgebra::Vector2;
use proptest::prelude::*;
use spline_algebra::offset_cusps;
use spline_core::ErrorKind;
use spline_geom::{BSpline, ParamCurve};
use spline_testing::strategies::planar_curve;

fn kappa(c: &BSpline<f64, Vector2<f64>>, u: f64) -> f64 {
    let d = c.derivatives(u, 2).unwrap();
    (d[1].x * d[2].y - d[1].y * d[2].x) / d[1].norm().powi(3)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn cusps_agree_with_dense_sampling(c in planar_curve(2, 4, true), t in 0.2f64..1.0, side in prop::bool::ANY) {
        let (a, b) = c.domain();
        let us: Vec<f64> = (0..=4000).map(|i| a + (b - a) * f64::from(i) / 4000.0).collect();
        let speeds: Vec<f64> = us.iter().map(|&u| c.derivatives(u, 1).unwrap()[1].norm()).collect();
        let mean = speeds.iter().sum::<f64>() / speeds.len() as f64;
        prop_assume!(speeds.iter().all(|&s| s > 1e-2 * mean));
        // A distance that some curvature reaches: the smallest radius seen over t.
        let kmax = us.iter().map(|&u| kappa(&c, u).abs()).fold(0.0, f64::max);
        let d = if side { 1.0 } else { -1.0 } / (t * kmax);
        let cusps = offset_cusps(&c, d, 1e-12).unwrap();
        for cusp in &cusps {
            let phi = kappa(&c, cusp.u) * d - 1.0;
            prop_assert!(phi.abs() < 1e-6, "{:?}: κ d − 1 = {:e}", cusp, phi);
            let dd = c.derivatives(cusp.u, 1).unwrap();
            let exact = dd[0] + Vector2::new(-dd[1].y, dd[1].x) * (d / dd[1].norm());
            prop_assert!((cusp.point - exact).norm() < 1e-12);
        }
        // Every sign change of κ d − 1 on the grid (away from breaks, where κ may jump) is
        // a reported cusp that changes sign.
        let breaks = c.breaks();
        let mut seen = 0;
        for w in us.windows(2) {
            let (p, q) = (kappa(&c, w[0]) * d - 1.0, kappa(&c, w[1]) * d - 1.0);
            let near_break = breaks.iter().any(|&k| k >= w[0] - 1e-9 && k <= w[1] + 1e-9);
            if p * q < 0.0 && !near_break {
                prop_assert!(
                    cusps.iter().any(|x| x.u >= w[0] - 1e-9 && x.u <= w[1] + 1e-9 && x.sign_change),
                    "missed the sign change in [{}, {}]: {:?}", w[0], w[1], cusps
                );
                seen += 1;
            }
        }
        prop_assert!(seen <= cusps.len());
    }
}

#[test]
fn bad_input_and_lines() {
    let line = BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0)],
    )
    .unwrap();
    assert!(offset_cusps(&line, 1.0, 1e-12).unwrap().is_empty());
    assert_eq!(
        offset_cusps(&line, f64::NAN, 1e-12).unwrap_err().kind(),
        ErrorKind::NonFinite
    );
    assert_eq!(
        offset_cusps(&line, 1.0, 0.0).unwrap_err().kind(),
        ErrorKind::InvalidTolerance
    );
}
