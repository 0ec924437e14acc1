//! Ridges of parametric surfaces and umbilics at poles, against closed forms (the triaxial
//! ellipsoid's principal sections, the spheroid's poles, the torus, surfaces of revolution
//! through `revolution_features`) and dense sampling of the ridge condition computed
//! independently from `NurbsSurface::derivatives`.

use nalgebra::Vector3;
use proptest::prelude::*;
use spline_algebra::{revolution_features, surface_ridges, umbilics};
use spline_core::KnotVector;
use spline_geom::{Axis, BSpline, NurbsCurve, NurbsSurface};

fn ellipsoid(a: f64, b: f64, c: f64) -> NurbsSurface<f64, 3> {
    NurbsSurface::sphere(Vector3::zeros(), 1.0)
        .unwrap()
        .map_control_points(|p| Vector3::new(a * p.x, b * p.y, c * p.z))
}

#[test]
fn the_ellipsoid_ridges_are_its_principal_sections() {
    let e = ellipsoid(1.5, 2.0, 1.0);
    let r = surface_ridges(&e, 16).unwrap();
    assert!(r.red_constant.is_empty() && r.blue_constant.is_empty());
    assert_eq!(r.umbilics.len(), 4);
    // Every traced point on a coordinate plane; red on z = 0 or x = 0, blue on y = 0 or x = 0
    // (x = 0 holds the umbilics, where its colour changes).
    let mut worst = 0.0f64;
    let mut on = |lines: &[Vec<[f64; 2]>], planes: [usize; 2]| -> Vec<Vector3<f64>> {
        let mut points = Vec::new();
        for p in lines.iter().flatten() {
            let x = e.eval(p[0], p[1]).unwrap();
            let d = x[planes[0]].abs().min(x[planes[1]].abs());
            worst = worst.max(d);
            points.push(x);
        }
        points
    };
    let red_count = on(&r.red, [2, 0]).len();
    let blue_count = on(&r.blue, [1, 0]).len();
    println!(
        "ellipsoid: {red_count} red, {blue_count} blue points, worst distance to its planes {worst:.2e}"
    );
    assert!(worst < 2e-6, "a ridge point is {worst} off its planes");
    // Every principal section covered (points every 1/200 of a turn).
    // Within 0.01 of a chord of a traced polyline (the chords are at most a sixteenth of a
    // patch: their sagitta is below 0.003).
    let chords = |lines: &[Vec<[f64; 2]>]| -> Vec<(Vector3<f64>, Vector3<f64>)> {
        lines
            .iter()
            .flat_map(|l| {
                l.windows(2).map(|w| {
                    (
                        e.eval(w[0][0], w[0][1]).unwrap(),
                        e.eval(w[1][0], w[1][1]).unwrap(),
                    )
                })
            })
            .collect()
    };
    let (red, blue) = (chords(&r.red), chords(&r.blue));
    let covered = |target: Vector3<f64>, segments: &[(Vector3<f64>, Vector3<f64>)]| {
        segments.iter().any(|(a, b)| {
            let d = b - a;
            let t = if d.norm_squared() > 0.0 {
                ((target - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (a + d * t - target).norm() < 0.01
        })
    };
    let mut gaps = 0;
    for k in 0..200 {
        let t = std::f64::consts::TAU * f64::from(k) / 200.0;
        let (c, s) = (t.cos(), t.sin());
        // z = 0: red; y = 0: blue; x = 0: red near the poles, blue near y = ±2.
        let equator = Vector3::new(1.5 * c, 2.0 * s, 0.0);
        let xz = Vector3::new(1.5 * c, 0.0, s);
        let yz = Vector3::new(0.0, 2.0 * c, s);
        gaps += usize::from(!covered(equator, &red));
        gaps += usize::from(!covered(xz, &blue));
        let mut both = red.clone();
        both.extend(&blue);
        gaps += usize::from(!covered(yz, &both));
    }
    assert_eq!(
        gaps, 0,
        "principal-section points without a traced ridge point nearby"
    );
}

#[test]
fn umbilics_at_poles() {
    let spheroid = ellipsoid(1.5, 1.5, 1.0);
    let u = umbilics(&spheroid).unwrap();
    assert!(u.points.is_empty() && !u.not_isolated);
    assert_eq!(u.poles.len(), 2);
    for p in &u.poles {
        let x = spheroid.eval(p[0], p[1]).unwrap();
        assert!((x.z.abs() - 1.0).abs() < 1e-14 && x.x.abs() < 1e-14 && x.y.abs() < 1e-14);
    }
    // The triaxial ellipsoid: four, none at its poles.
    let u = umbilics(&ellipsoid(1.5, 2.0, 1.0)).unwrap();
    assert_eq!((u.points.len(), u.poles.len()), (4, 0));
    // A spheroid that is almost one: 1e-6 apart is not umbilic at the poles.
    let u = umbilics(&ellipsoid(1.5, 1.5 * (1.0 + 1e-6), 1.0)).unwrap();
    assert_eq!(u.poles.len(), 0);
    // The sphere: umbilic everywhere.
    let u = umbilics(&NurbsSurface::sphere(Vector3::zeros(), 2.0).unwrap()).unwrap();
    assert!(u.not_isolated && u.poles.is_empty());
}

#[test]
fn the_torus_has_constant_curvature_along_both_families() {
    let torus = NurbsSurface::torus(Vector3::zeros(), Vector3::z(), 2.0, 1.0).unwrap();
    let r = surface_ridges(&torus, 8).unwrap();
    assert!(r.red.is_empty() && r.blue.is_empty());
    assert_eq!(r.red_constant.len(), 16);
    assert_eq!(r.blue_constant.len(), 16);
    // A sphere: umbilic everywhere, no ridge defined.
    let r = surface_ridges(&NurbsSurface::sphere(Vector3::zeros(), 1.0).unwrap(), 8).unwrap();
    assert!(r.red.is_empty() && r.blue.is_empty());
    assert_eq!((r.red_constant.len(), r.blue_constant.len()), (8, 8));
    // Bad input.
    let torus = NurbsSurface::torus(Vector3::zeros(), Vector3::z(), 2.0, 1.0).unwrap();
    assert!(surface_ridges(&torus, 0).is_err() && surface_ridges(&torus, 10_001).is_err());
}

/// The surface of revolution of `f(z)` about the z axis, with the profile parameter `z`.
fn revolved(f: &BSpline<f64, f64>) -> NurbsSurface<f64, 3> {
    let knots = f.knots().clone();
    let p = knots.degree();
    let points: Vec<Vector3<f64>> = f
        .control_points()
        .iter()
        .enumerate()
        .map(|(i, &r)| {
            let z = (1..=p).map(|k| knots.knots()[i + k]).sum::<f64>() / p as f64;
            Vector3::new(r, 0.0, z)
        })
        .collect();
    let n = points.len();
    let profile = NurbsCurve::new(knots, points, vec![1.0; n]).unwrap();
    NurbsSurface::revolution(
        &profile,
        &Axis::new(Vector3::zeros(), Vector3::z()).unwrap(),
        std::f64::consts::TAU,
    )
    .unwrap()
}

#[test]
fn ridge_circles_of_a_surface_of_revolution() {
    // f(z) = 1 + 1.5z² + 0.2z³ on [−½, ½] (Bézier form): the meridian curvature stays
    // above the parallel one (no circle of umbilics, where the colours would swap); one
    // ridge circle near z = 0.
    let knots = KnotVector::new(3, vec![-0.5, -0.5, -0.5, -0.5, 0.5, 0.5, 0.5, 0.5]).unwrap();
    let f = BSpline::new(knots, vec![1.35, 0.9, 0.85, 1.4]).unwrap();
    let expected = revolution_features(&f, 1e-13).unwrap().ridges;
    assert_eq!(expected.len(), 1);
    let s = revolved(&f);
    let r = surface_ridges(&s, 8).unwrap();
    // The parallels are lines of curvature along which their curvature is constant (reported
    // as constant regions); the ridges of the meridians' curvature are the circles (of either
    // colour: the colours swap where the two curvatures cross, on circles of umbilics).
    assert!(!r.red_constant.is_empty() || !r.blue_constant.is_empty());
    let mut lines = r.red.clone();
    lines.extend(r.blue.iter().cloned());
    let mut worst = 0.0f64;
    for p in lines.iter().flatten() {
        let d = expected
            .iter()
            .map(|c| (c.z - p[0]).abs())
            .fold(f64::INFINITY, f64::min);
        worst = worst.max(d);
    }
    println!(
        "revolution: {} lines, worst |u − z| {worst:.2e}",
        lines.len()
    );
    assert!(worst < 1e-9);
    for c in &expected {
        assert!(
            lines.iter().flatten().any(|p| (p[0] - c.z).abs() < 1e-9),
            "circle z = {} missed",
            c.z
        );
    }
}

/// The ridge condition of both colours at `(u, v)`, written out from the surface's own
/// derivatives (independently of the numerators the library uses): the principal curvatures
/// `κ` of `(II, I)`, a principal direction `t` (a null vector of `II − κI`), and the
/// derivative of `κ` along `t` by first-order perturbation of the generalised eigenvalue,
/// `∂κ = tᵀ(∂II − κ ∂I)t / tᵀIt`. Returns per colour (red = smaller κ, blue = larger):
/// `(t, D_t κ, |∇κ| |t|)`, `None` near an umbilic.
type Sampled = [([f64; 2], f64, f64); 2];

fn sampled_condition(s: &NurbsSurface<f64, 3>, u: f64, v: f64) -> Option<Sampled> {
    let d = s.derivatives(u, v, 3).unwrap();
    let (su, sv, suu, suv, svv) = (d[1][0], d[0][1], d[2][0], d[1][1], d[0][2]);
    let (suuu, suuv, suvv, svvv) = (d[3][0], d[2][1], d[1][2], d[0][3]);
    let m = su.cross(&sv);
    let mu = suu.cross(&sv) + su.cross(&suv);
    let mv = suv.cross(&sv) + su.cross(&svv);
    let len = m.norm();
    let n = m / len;
    let nu = (mu - n * n.dot(&mu)) / len;
    let nv = (mv - n * n.dot(&mv)) / len;
    let first = [[su.dot(&su), su.dot(&sv)], [su.dot(&sv), sv.dot(&sv)]];
    let first_u = [
        [2.0 * suu.dot(&su), suu.dot(&sv) + su.dot(&suv)],
        [suu.dot(&sv) + su.dot(&suv), 2.0 * suv.dot(&sv)],
    ];
    let first_v = [
        [2.0 * suv.dot(&su), suv.dot(&sv) + su.dot(&svv)],
        [suv.dot(&sv) + su.dot(&svv), 2.0 * svv.dot(&sv)],
    ];
    let second = [[suu.dot(&n), suv.dot(&n)], [suv.dot(&n), svv.dot(&n)]];
    let second_u = [
        [suuu.dot(&n) + suu.dot(&nu), suuv.dot(&n) + suv.dot(&nu)],
        [suuv.dot(&n) + suv.dot(&nu), suvv.dot(&n) + svv.dot(&nu)],
    ];
    let second_v = [
        [suuv.dot(&n) + suu.dot(&nv), suvv.dot(&n) + suv.dot(&nv)],
        [suvv.dot(&n) + suv.dot(&nv), svvv.dot(&n) + svv.dot(&nv)],
    ];
    let (e, f, g) = (first[0][0], first[0][1], first[1][1]);
    let (l, mm, nn) = (second[0][0], second[0][1], second[1][1]);
    let a = e * g - f * f;
    let b = e * nn - 2.0 * f * mm + g * l;
    let c = l * nn - mm * mm;
    let disc = b * b - 4.0 * a * c;
    if disc <= 1e-4 * b * b.max(1e-300) || disc <= 1e-12 * a * a {
        return None;
    }
    let form = |q: [[f64; 2]; 2], t: [f64; 2]| {
        t[0] * (q[0][0] * t[0] + q[0][1] * t[1]) + t[1] * (q[1][0] * t[0] + q[1][1] * t[1])
    };
    let mut out = [([0.0; 2], 0.0, 0.0); 2];
    for (k, sign) in [(0, -1.0), (1, 1.0)] {
        let kappa = (b + sign * disc.sqrt()) / (2.0 * a);
        let r1 = [l - kappa * e, mm - kappa * f];
        let r2 = [mm - kappa * f, nn - kappa * g];
        let r = if r1[0].hypot(r1[1]) >= r2[0].hypot(r2[1]) {
            r1
        } else {
            r2
        };
        let t = [r[1], -r[0]];
        let metric = form(first, t);
        // ∂κ/∂u and ∂κ/∂v; the ridge condition is D_t κ = t_u κ_u + t_v κ_v = 0.
        let grad = [
            (form(second_u, t) - kappa * form(first_u, t)) / metric,
            (form(second_v, t) - kappa * form(first_v, t)) / metric,
        ];
        out[k] = (
            t,
            grad[0] * t[0] + grad[1] * t[1],
            grad[0].hypot(grad[1]) * t[0].hypot(t[1]),
        );
    }
    Some(out)
}

/// A meridian whose third derivative jumps at its knots: the ridge circles there (sign
/// changes of `R` by a jump, which `revolution_features` reports) are found along the patch
/// boundaries.
#[test]
fn ridge_circles_at_knots() {
    let knots = KnotVector::new(
        3,
        vec![-1.0, -1.0, -1.0, -1.0, -0.3, 0.4, 1.0, 1.0, 1.0, 1.0],
    )
    .unwrap();
    let f = BSpline::new(knots, vec![2.0, 2.02, 1.99, 2.015, 1.995, 2.01]).unwrap();
    let expected = revolution_features(&f, 1e-13).unwrap().ridges;
    assert_eq!(
        expected.iter().map(|c| c.z).collect::<Vec<_>>(),
        vec![-0.3, 0.4]
    );
    let s = revolved(&f);
    let r = surface_ridges(&s, 8).unwrap();
    let mut lines = r.red.clone();
    lines.extend(r.blue.iter().cloned());
    for c in &expected {
        let on: Vec<&[f64; 2]> = lines
            .iter()
            .flatten()
            .filter(|p| (p[0] - c.z).abs() < 1e-12)
            .collect();
        // The whole circle: v covers [0, 1].
        let (lo, hi) = on
            .iter()
            .fold((1.0f64, 0.0f64), |(a, b), p| (a.min(p[1]), b.max(p[1])));
        assert!(
            lo == 0.0 && hi == 1.0,
            "circle z = {} covers v in [{lo}, {hi}]",
            c.z
        );
    }
    assert!(
        lines
            .iter()
            .flatten()
            .all(|p| expected.iter().any(|c| (p[0] - c.z).abs() < 1e-12))
    );
}

/// A bicubic Bézier patch over `[0, 1]²`: heights `z` over a slightly perturbed grid, both
/// offset by fixed irregular amounts (shrinking towards zero must not reach the
/// non-generic planar boundaries where the ridge condition only touches zero).
fn bicubic(z: &[f64], xy: &[f64]) -> NurbsSurface<f64, 3> {
    let k = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]).unwrap();
    let irregular = |i: usize| ((i * 7 + 3) % 11) as f64 / 11.0 - 0.5;
    let points = (0..16)
        .map(|i| {
            Vector3::new(
                (i / 4) as f64 / 3.0 + xy[2 * i] + 0.02 * irregular(2 * i),
                (i % 4) as f64 / 3.0 + xy[2 * i + 1] + 0.02 * irregular(2 * i + 1),
                z[i] + 0.2 * irregular(i + 5),
            )
        })
        .collect();
    NurbsSurface::new(k.clone(), k, points, vec![1.0; 16]).unwrap()
}

/// Sign changes of the sampled ridge condition of each colour on the edges of an
/// `n × n` grid (the direction at the second end oriented like the first), with the points
/// where the condition was not decided (near umbilics, or the direction turning fast).
fn sampled_ridges(s: &NurbsSurface<f64, 3>, n: usize) -> ([Vec<[f64; 2]>; 2], Vec<[f64; 2]>) {
    let h = 1.0 / n as f64;
    let grid: Vec<Vec<Option<Sampled>>> = (0..=n)
        .map(|i| {
            (0..=n)
                .map(|j| sampled_condition(s, i as f64 * h, j as f64 * h))
                .collect()
        })
        .collect();
    let mut changes = [Vec::new(), Vec::new()];
    let mut undecided = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            for (di, dj) in [(1, 0), (0, 1)] {
                let (i2, j2) = (i + di, j + dj);
                if i2 > n || j2 > n {
                    continue;
                }
                let mid = [
                    (i as f64 + 0.5 * di as f64) * h,
                    (j as f64 + 0.5 * dj as f64) * h,
                ];
                let (Some(a), Some(b)) = (grid[i][j], grid[i2][j2]) else {
                    undecided.push(mid);
                    continue;
                };
                for k in 0..2 {
                    let (ta, ga, _) = a[k];
                    let (tb, mut gb, _) = b[k];
                    let dot = ta[0] * tb[0] + ta[1] * tb[1];
                    let cos = dot / (ta[0].hypot(ta[1]) * tb[0].hypot(tb[1]));
                    if cos.abs() < 0.9 {
                        undecided.push(mid);
                        continue;
                    }
                    if dot < 0.0 {
                        gb = -gb;
                    }
                    if (ga > 0.0) != (gb > 0.0) {
                        changes[k].push(mid);
                    }
                }
            }
        }
    }
    (changes, undecided)
}

fn near(p: &[f64; 2], points: &[[f64; 2]], tol: f64) -> bool {
    points
        .iter()
        .any(|q| (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Every sign change of the sampled ridge condition (64 × 64 grid) has a traced ridge
    /// point of its colour within 2 sample steps, and every traced point a sampled sign
    /// change of its colour (away from where the sampling cannot decide: near umbilics).
    #[test]
    fn ridges_match_dense_sampling(
        z in proptest::collection::vec(-0.4f64..0.4, 16),
        xy in proptest::collection::vec(-0.05f64..0.05, 32),
    ) {
        let s = bicubic(&z, &xy);
        let n = 64;
        let step = 1.0 / n as f64;
        let (changes, undecided) = sampled_ridges(&s, n);
        let r = surface_ridges(&s, 64).unwrap();
        for (k, traced) in [&r.red, &r.blue].into_iter().enumerate() {
            let points: Vec<[f64; 2]> = traced.iter().flatten().copied().collect();
            for c in &changes[k] {
                if near(c, &undecided, 3.0 * step) || near(c, &r.umbilics, 3.0 * step) {
                    continue;
                }
                prop_assert!(near(c, &points, 2.0 * step), "colour {k}: sampled sign change at {c:?} not traced");
            }
            for p in &points {
                if near(p, &undecided, 3.0 * step) || near(p, &r.umbilics, 3.0 * step) {
                    continue;
                }
                prop_assert!(near(p, &changes[k], 2.0 * step), "colour {k}: traced point {p:?} without a sampled sign change");
            }
        }
    }
}

/// A biquartic surface over `[0, 1]²` with `n × n` control points on uniform simple knots
/// (so `(n − 4)²` patches, marched on several threads; C³, so no ridge lies along a patch
/// boundary by a jump of the third derivatives): random heights over a sheared grid.
fn random_net(n: usize, seed: u64) -> NurbsSurface<f64, 3> {
    let mut state = seed;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let spans = n - 4;
    let knots: Vec<f64> = (0..n + 5)
        .map(|i| (i.saturating_sub(4)).min(spans) as f64 / spans as f64)
        .collect();
    let k = KnotVector::new(4, knots).unwrap();
    let points = (0..n * n)
        .map(|i| {
            let (a, b) = ((i / n) as f64, (i % n) as f64);
            Vector3::new(a + 0.2 * b, b + 0.1 * next(), 0.6 * next())
        })
        .collect();
    NurbsSurface::new(k.clone(), k, points, vec![1.0; n * n]).unwrap()
}

/// On surfaces of 16 and 25 patches (the marching split between threads, pieces chained
/// across patches) the
/// traced ridges and the sign changes of the independently sampled ridge condition agree
/// both ways within two sample steps, and every traced line is a chain of short steps
/// (pieces joined end to end, not across the domain).
#[test]
fn ridges_of_many_patches_match_dense_sampling() {
    for (n, seed) in [(8, 11u64), (9, 23)] {
        let s = random_net(n, seed);
        let samples = 128;
        let step = 1.0 / samples as f64;
        let (changes, undecided) = sampled_ridges(&s, samples);
        let r = surface_ridges(&s, 32).unwrap();
        let mut traced_points = 0;
        for (k, traced) in [&r.red, &r.blue].into_iter().enumerate() {
            for line in traced {
                for w in line.windows(2) {
                    let gap = (w[1][0] - w[0][0]).abs().max((w[1][1] - w[0][1]).abs());
                    assert!(gap <= 1.0 / (n - 4) as f64, "colour {k}: a jump of {gap}");
                }
            }
            let points: Vec<[f64; 2]> = traced.iter().flatten().copied().collect();
            traced_points += points.len();
            let skip =
                |c: &[f64; 2]| near(c, &undecided, 3.0 * step) || near(c, &r.umbilics, 3.0 * step);
            for c in changes[k].iter().filter(|c| !skip(c)) {
                assert!(
                    near(c, &points, 2.0 * step),
                    "n {n}, colour {k}: sampled sign change at {c:?} not traced"
                );
            }
            for p in points.iter().filter(|p| !skip(p)) {
                assert!(
                    near(p, &changes[k], 2.0 * step),
                    "n {n}, colour {k}: traced point {p:?} without a sampled sign change"
                );
            }
        }
        assert!(traced_points > 100, "n {n}: {traced_points} points");
    }
}
