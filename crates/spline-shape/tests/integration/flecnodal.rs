//! Control of the flecnodal circles of a surface of revolution through its meridian: the
//! result is checked by sampling `F = 3f′f″ + ff‴` and `f″` from the meridian's own
//! derivatives (de Boor, not the product algebra that builds the constraints).

use spline_core::ErrorKind;
use spline_geom::BSpline;
use spline_shape::{FlecnodalCircles, Sign, control_flecnodal_circles};

/// A neck `f = 1 + z²/2` on [−1, 1] with a ripple of amplitude `ripple`, interpolated.
fn rippled_neck(ripple: f64) -> BSpline<f64, f64> {
    let z: Vec<f64> = (0..=40).map(|k| -1.0 + f64::from(k) / 20.0).collect();
    let r: Vec<f64> = z
        .iter()
        .map(|&z| 1.0 + 0.5 * z * z + ripple * (12.0 * z).sin())
        .collect();
    spline_fit::interpolate_function(&z, &r, 3).unwrap()
}

/// The heights in `(a, b)` where the sampled `F` changes sign, and the smallest sampled `f″`.
fn sampled(f: &BSpline<f64, f64>, (a, b): (f64, f64)) -> (Vec<f64>, f64) {
    let count = 20_000;
    let mut changes = Vec::new();
    let mut least_second = f64::INFINITY;
    let mut previous: Option<(f64, f64)> = None;
    for k in 0..=count {
        let z = a + (b - a) * f64::from(k) / f64::from(count);
        let d = f.derivatives(z, 3).unwrap();
        least_second = least_second.min(d[2]);
        let flecnodal = 3.0 * d[1] * d[2] + d[0] * d[3];
        if let Some((z0, f0)) = previous
            && f0 * flecnodal < 0.0
        {
            changes.push(0.5 * (z0 + z));
        }
        if flecnodal != 0.0 {
            previous = Some((z, flecnodal));
        }
    }
    (changes, least_second)
}

#[test]
fn a_rippled_neck_keeps_one_flecnodal_circle_where_asked() {
    let meridian = rippled_neck(0.004);
    let (before, _) = sampled(&meridian, (-1.0, 1.0));
    assert!(
        before.len() >= 5,
        "the ripple adds flecnodal circles: {before:?}"
    );
    let circles = FlecnodalCircles {
        interval: (-1.0, 1.0),
        first: Sign::NonPositive,
        allowed: vec![(-0.3, 0.3)],
    };
    let controlled = control_flecnodal_circles(&meridian, &circles, 200, 0).unwrap();
    let (after, least_second) = sampled(&controlled.meridian, (-1.0, 1.0));
    assert_eq!(after.len(), 1, "{after:?}");
    assert!(after[0].abs() < 0.3, "{after:?}");
    assert!(
        least_second > 0.0,
        "the interval stays hyperbolic: f'' = {least_second}"
    );
    // spline-algebra's feature circles agree.
    let features = spline_algebra::revolution_features(&controlled.meridian, 1e-10).unwrap();
    assert_eq!(features.flecnodal.len(), 1);
    assert!((features.flecnodal[0] - after[0]).abs() < 1e-3);
    assert!(
        controlled.max_deviation < 0.02,
        "{}",
        controlled.max_deviation
    );
    eprintln!(
        "flecnodal circles {} → 1 at z = {:.4}; deviation {:.2e}",
        before.len(),
        features.flecnodal[0],
        controlled.max_deviation
    );
}

#[test]
fn flecnodal_circles_can_be_removed_from_part_of_the_meridian() {
    // Only z ∈ [0.2, 1] is controlled: no flecnodal circle there, F > 0.
    let meridian = rippled_neck(0.003);
    let circles = FlecnodalCircles {
        interval: (0.2, 1.0),
        first: Sign::NonNegative,
        allowed: vec![],
    };
    let (before, _) = sampled(&meridian, (0.2, 1.0));
    assert!(!before.is_empty());
    let controlled = control_flecnodal_circles(&meridian, &circles, 200, 1).unwrap();
    let (after, least_second) = sampled(&controlled.meridian, (0.2, 1.0));
    assert!(after.is_empty(), "{after:?}");
    assert!(least_second > 0.0);
    assert!(
        controlled.max_deviation < 0.02,
        "{}",
        controlled.max_deviation
    );
    assert!(controlled.fit.objective >= controlled.fit.unconstrained_objective);
}

#[test]
fn bad_requests_are_errors() {
    let meridian = rippled_neck(0.004);
    let request = |interval, allowed| FlecnodalCircles {
        interval,
        first: Sign::NonPositive,
        allowed,
    };
    for circles in [
        request((-2.0, 1.0), vec![]),
        request((0.5, 0.2), vec![]),
        request((-1.0, 1.0), vec![(0.3, 0.1)]),
        request((-1.0, 1.0), vec![(-0.5, 0.0), (-0.1, 0.2)]),
        request((0.0, 1.0), vec![(-0.5, 0.2)]),
    ] {
        let e = control_flecnodal_circles(&meridian, &circles, 100, 0).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidArgument, "{circles:?}: {e}");
    }
    let quadratic =
        spline_fit::interpolate_function(&[0.0, 0.5, 1.0], &[1.0, 1.1, 1.3], 2).unwrap();
    let circles = request((0.0, 1.0), vec![]);
    let e = control_flecnodal_circles(&quadratic, &circles, 100, 0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    // Issue 26: what failed, in fields a program can read.
    assert_eq!(
        (e.value(), e.interval()),
        (Some(2.0), Some((3.0, f64::INFINITY)))
    );
    let e =
        control_flecnodal_circles(&meridian, &request((-2.0, 1.0), vec![]), 100, 0).unwrap_err();
    assert_eq!(e.interval(), Some((-1.0, 1.0)), "{e}");
    let allowed = vec![(-0.5, 0.0), (-0.1, 0.2)];
    let e =
        control_flecnodal_circles(&meridian, &request((-1.0, 1.0), allowed), 100, 0).unwrap_err();
    assert_eq!(
        (e.index(), e.interval()),
        (Some(1), Some((-1.0, 1.0))),
        "{e}"
    );
    let e = control_flecnodal_circles(&meridian, &request((-1.0, 1.0), vec![]), 1, 0).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::TooFewPoints);
    let e =
        control_flecnodal_circles(&meridian, &request((-1.0, 1.0), vec![]), 100, 9).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
}
