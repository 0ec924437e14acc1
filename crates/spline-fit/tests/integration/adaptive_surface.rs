//! `AdaptiveSurfaceApproximation` against its map: the tolerance met on a dense grid, the
//! same fit scaled at 1e-200 and 1e200, a kink kept by a repeated break, clean errors.

use nalgebra::Vector3;
use spline_core::ErrorKind;
use spline_fit::AdaptiveSurfaceApproximation;

type Map = fn(f64, f64) -> Vector3<f64>;

fn on_grid(
    f: Map,
    scale: f64,
) -> impl Fn(&[f64], &[f64]) -> spline_core::Result<Vec<Vector3<f64>>> {
    move |us, vs| {
        Ok(us
            .iter()
            .flat_map(|&u| vs.iter().map(move |&v| f(u, v) * scale))
            .collect())
    }
}

fn wave(u: f64, v: f64) -> Vector3<f64> {
    Vector3::new(u, v, (3.0 * u).sin() * (2.0 * v).cos() + 0.1 * u * v)
}

fn dense_error(surface: &spline_geom::Surface<f64, Vector3<f64>>, f: Map, scale: f64) -> f64 {
    let mut worst = 0.0f64;
    for i in 0..=60 {
        for j in 0..=60 {
            let (u, v) = (2.0 * f64::from(i) / 60.0, f64::from(j) / 60.0);
            worst = worst.max(((surface.eval(u, v).unwrap() - f(u, v) * scale) / scale).norm());
        }
    }
    worst
}

#[test]
fn meets_the_tolerance_at_every_scale() {
    let domain = ((0.0, 2.0), (0.0, 1.0));
    let base = AdaptiveSurfaceApproximation::new((3, 3), 1e-7)
        .fit(domain, on_grid(wave, 1.0))
        .unwrap();
    assert!(base.max_error <= 1e-7);
    assert!(base.passes > 0, "the map needs refinement");
    assert!(dense_error(&base.surface, wave, 1.0) <= 1e-7);
    for scale in [1e-200, 1e200] {
        let fit = AdaptiveSurfaceApproximation::new((3, 3), 1e-7 * scale)
            .fit(domain, on_grid(wave, scale))
            .unwrap();
        assert_eq!(
            fit.surface.knots_u(),
            base.surface.knots_u(),
            "scale {scale:e}"
        );
        assert_eq!(
            fit.surface.knots_v(),
            base.surface.knots_v(),
            "scale {scale:e}"
        );
        assert!(
            dense_error(&fit.surface, wave, scale) <= 1e-7,
            "scale {scale:e}"
        );
    }
}

#[test]
fn a_repeated_break_keeps_a_kink() {
    // |u − 1| is only C⁰ at u = 1: with a break of multiplicity 3 there, no refinement.
    let kink: Map = |u, v| Vector3::new(u, v, (u - 1.0).abs() * (1.0 + v));
    let fit = AdaptiveSurfaceApproximation::new((3, 2), 1e-10)
        .breaks(&[1.0, 1.0, 1.0], &[])
        .fit(((0.0, 2.0), (0.0, 1.0)), on_grid(kink, 1.0))
        .unwrap();
    assert_eq!(fit.passes, 0);
    assert!(dense_error(&fit.surface, kink, 1.0) <= 1e-10);
    assert_eq!(
        fit.surface
            .knots_u()
            .knots()
            .iter()
            .filter(|&&k| k == 1.0)
            .count(),
        3
    );
}

#[test]
fn bad_settings_and_maps_are_refused() {
    let domain = ((0.0, 2.0), (0.0, 1.0));
    let err = |e: spline_core::Error| e.kind();
    for tolerance in [0.0, -1.0, f64::NAN] {
        let e = AdaptiveSurfaceApproximation::new((3, 3), tolerance)
            .fit(domain, on_grid(wave, 1.0))
            .unwrap_err();
        assert_eq!(err(e), ErrorKind::InvalidTolerance);
    }
    let e = AdaptiveSurfaceApproximation::new((3, 3), 1e-6)
        .fit(((0.0, 2.0), (1.0, 1.0)), on_grid(wave, 1.0))
        .unwrap_err();
    assert_eq!(err(e), ErrorKind::EmptyDomain);
    let e = AdaptiveSurfaceApproximation::new((3, 3), 1e-6)
        .breaks(&[3.0], &[])
        .fit(domain, on_grid(wave, 1.0))
        .unwrap_err();
    assert_eq!(err(e), ErrorKind::OutOfDomain);
    let e = AdaptiveSurfaceApproximation::new((3, 3), 1e-6)
        .fit(domain, |_: &[f64], _: &[f64]| Ok(vec![Vector3::zeros(); 3]))
        .unwrap_err();
    assert_eq!(err(e), ErrorKind::InvalidLength);
    // A map no spline reaches: a jump inside the first span, within a small budget.
    let jump: Map = |u, v| Vector3::new(u, v, if u < 0.3 { 0.0 } else { 1.0 });
    let e = AdaptiveSurfaceApproximation::new((3, 3), 1e-6)
        .max_patches(400)
        .fit(domain, on_grid(jump, 1.0))
        .unwrap_err();
    assert_eq!(err(e), ErrorKind::ToleranceExceeded);
}
