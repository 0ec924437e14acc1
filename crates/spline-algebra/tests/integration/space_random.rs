//! Curvature extrema of random space cubics and NURBS against dense sampling of `κ` (issue
//! 25, item 4: 2 of 12 random space cubics disagreed with sampling, the reproducer
//! `space_cubic_extrema.json` among them). The curves are drawn as the reproducer was:
//! control points in `[−1.5, 1.5]³`, interior knots anywhere in `(0, 1)`, so that spans of
//! very different lengths and numerators of very different sizes occur.

use nalgebra::Vector3;
use spline_algebra::SpaceCurveFeatures;
use spline_geom::NurbsCurve;

/// A small xorshift generator: the cases are the same on every run.
struct Draw(u64);

impl Draw {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A random cubic with `n` control points; rational with weights in `[0.3, 3]` if asked.
fn random_cubic(draw: &mut Draw, n: usize, rational: bool) -> NurbsCurve<f64, 3> {
    let mut interior: Vec<f64> = (0..n - 4).map(|_| draw.next()).collect();
    interior.sort_by(f64::total_cmp);
    let mut knots = vec![0.0; 4];
    knots.extend(interior);
    knots.extend([1.0; 4]);
    let points: Vec<Vector3<f64>> = (0..n)
        .map(|_| {
            Vector3::new(
                3.0 * draw.next() - 1.5,
                3.0 * draw.next() - 1.5,
                3.0 * draw.next() - 1.5,
            )
        })
        .collect();
    let weights: Vec<f64> = (0..n)
        .map(|_| {
            if rational {
                0.3 + 2.7 * draw.next()
            } else {
                1.0
            }
        })
        .collect();
    NurbsCurve::from_knots(3, knots, points, weights).unwrap()
}

/// The interior turning points of `κ` sampled at `m + 1` equally spaced parameters: where
/// consecutive differences change sign (where `κ′` jumps across zero at a knot too).
fn sampled_extrema(curve: &NurbsCurve<f64, 3>, m: usize) -> Vec<f64> {
    let kappa: Vec<f64> = (0..=m)
        .map(|j| curve.curvature_magnitude(j as f64 / m as f64).unwrap())
        .collect();
    (1..m)
        .filter(|&j| (kappa[j] - kappa[j - 1]) * (kappa[j + 1] - kappa[j]) < 0.0)
        .map(|j| j as f64 / m as f64)
        .collect()
}

/// Every case: the reported extrema and the sampled turning points are as many and pair up
/// within a few grid steps. Cases whose extrema are closer than the grid can resolve, or
/// that touch the ends of the domain, would make sampling unreliable: none of the seeded
/// cases is such, and the check says so if one ever is.
fn check(rational: bool, seed: u64, cases: usize) {
    let mut draw = Draw(seed);
    let m = 100_000;
    let mut total = 0;
    for case in 0..cases {
        let n = 5 + (case % 5);
        let curve = random_cubic(&mut draw, n, rational);
        let found = curve.space_features(1e-12).unwrap().curvature_extrema;
        let sampled = sampled_extrema(&curve, m);
        assert_eq!(
            found.len(),
            sampled.len(),
            "case {case} (rational {rational}): found {found:?}, sampled {sampled:?}; {curve:?}"
        );
        for (f, s) in found.iter().zip(&sampled) {
            assert!(
                (f - s).abs() <= 2.0 / m as f64,
                "case {case} (rational {rational}): found {f}, sampled {s}"
            );
        }
        total += found.len();
    }
    // The check is not vacuous: the random curves have many extrema between them.
    assert!(total >= 2 * cases, "{total} extrema in {cases} cases");
}

#[test]
fn random_space_cubics_agree_with_dense_sampling() {
    check(false, 0x2545_f491_4f6c_dd1d, 40);
}

#[test]
fn random_rational_space_cubics_agree_with_dense_sampling() {
    check(true, 0x9e37_79b9_7f4a_7c15, 40);
}
