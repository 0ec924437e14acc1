//! The tight box against dense sampling and the control points' box.

use proptest::prelude::*;
use spline_algebra::tight_box;
use spline_core::ErrorKind;
use spline_geom::{ParamCurve, hull_box};
use spline_testing::strategies::planar_curve;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    // Knots on the grid of eighths: no piece so short and fast that a dip of its coordinate
    // falls between samples (the box would be right and the sampling wrong).
    #[test]
    fn the_tight_box_is_the_sampled_box(c in planar_curve(1, 5, true)) {
        let b = tight_box(&c, 1e-13).unwrap();
        let hull = hull_box(&c);
        let params = c.sample_params(4000usize.div_ceil(c.breaks().len() - 1).max(50));
        let points = c.eval_many(&params).unwrap();
        // The extreme of coordinate k (sign s): every local extreme of the samples refined
        // by sampling the two intervals beside it 2000 times more finely.
        let extreme = |k: usize, s: f64| {
            let v: Vec<f64> = points.iter().map(|p| s * p[k]).collect();
            let mut best = f64::NEG_INFINITY;
            for i in 0..v.len() {
                let left = if i > 0 { v[i - 1] } else { f64::NEG_INFINITY };
                let right = if i + 1 < v.len() { v[i + 1] } else { f64::NEG_INFINITY };
                if v[i] < left || v[i] < right {
                    continue;
                }
                let (u0, u1) = (params[i.saturating_sub(1)], params[(i + 1).min(params.len() - 1)]);
                let fine: Vec<f64> = (0..=2000).map(|j| u0 + (u1 - u0) * f64::from(j) / 2000.0).collect();
                let m = c.eval_many(&fine).unwrap().iter().map(|p| s * p[k]).fold(v[i], f64::max);
                best = best.max(m);
            }
            s * best
        };
        for k in 0..2 {
            let (lo, hi) = (extreme(k, -1.0), extreme(k, 1.0));
            // Contains every sample; attained (to the sampling's resolution).
            prop_assert!(b.min[k] <= lo + 1e-12 && b.max[k] >= hi - 1e-12, "{:?} vs [{}, {}]", b, lo, hi);
            prop_assert!(lo - b.min[k] < 1e-6 && b.max[k] - hi < 1e-6, "{:?} vs [{}, {}]", b, lo, hi);
            prop_assert!(b.min[k] >= hull.min[k] - 1e-12 && b.max[k] <= hull.max[k] + 1e-12);
        }
    }
}

#[test]
fn bad_accuracy_is_an_error() {
    let c = spline_geom::BSpline::from_knots(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![
            nalgebra::Vector2::new(0.0, 0.0),
            nalgebra::Vector2::new(1.0, 2.0),
        ],
    )
    .unwrap();
    assert_eq!(
        tight_box(&c, 0.0).unwrap_err().kind(),
        ErrorKind::InvalidTolerance
    );
    let b = tight_box(&c, 1e-12).unwrap();
    assert_eq!(
        (b.min, b.max),
        (
            nalgebra::Vector2::new(0.0, 0.0),
            nalgebra::Vector2::new(1.0, 2.0)
        )
    );
}
