//! A curve lying in a surface over an interval (issue 25, item 1): the interval, maximal,
//! and the isolated crossing elsewhere; checked by closest points on the surface inside the
//! interval and just outside it.

use nalgebra::Vector3;
use spline_fit::{Tolerances, closest_point_on_surface, intersect_curve_surface_with_overlaps};
use spline_geom::{BSpline, Surface};

#[test]
fn a_polyline_in_a_plane_then_across_it() {
    let plane = Surface::bezier(vec![
        vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 1.0, 0.0)],
        vec![Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 1.0, 0.0)],
    ])
    .unwrap();
    // In z = 0 from x = −0.5 to 0.5 (on the plane for t in [0.5, 1]), up to z = 1, then
    // down across the plane at t = 2.5, x = 0.85.
    let curve = BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0],
        vec![
            Vector3::new(-0.5, 0.5, 0.0),
            Vector3::new(0.5, 0.5, 0.0),
            Vector3::new(0.8, 0.5, 1.0),
            Vector3::new(0.9, 0.5, -1.0),
        ],
    )
    .unwrap();
    let found =
        intersect_curve_surface_with_overlaps(&curve, &plane, &Tolerances::default()).unwrap();
    assert_eq!(found.overlaps.len(), 1, "{found:?}");
    let (t0, t1): (f64, f64) = found.overlaps[0].t;
    assert!(
        (t0 - 0.5).abs() < 1e-8 && (t1 - 1.0).abs() < 1e-8,
        "{found:?}"
    );
    assert_eq!(found.points.len(), 1, "{found:?}");
    let p: spline_fit::CurveSurfaceHit<f64> = found.points[0];
    assert!((p.t - 2.5).abs() < 1e-12 && (p.point - Vector3::new(0.85, 0.5, 0.0)).norm() < 1e-12);
    // Independently: inside on the plane within the distance tolerance (1e-9 of the
    // diagonal of the objects' common box, √(1.5² + 1² + 2²) = 2.69), just outside not.
    let distance = |t: f64| {
        closest_point_on_surface(&plane, curve.eval(t).unwrap())
            .unwrap()
            .distance
    };
    for k in 0..=20 {
        let t = t0 + (t1 - t0) * f64::from(k) / 20.0;
        assert!(distance(t) <= 2.7e-9, "{t}");
    }
    assert!(distance(t0 - 1e-3) > 1e-6 && distance(t1 + 1e-3) > 1e-6);
}
