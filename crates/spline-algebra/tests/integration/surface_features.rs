//! Curvature numerators of surfaces and their zero sets (parabolic lines), against closed
//! forms (the torus), the pointwise curvatures of spline-geom and dense sampling.

#![allow(clippy::needless_range_loop)]

use nalgebra::Vector3;
use spline_algebra::{curvature_numerators, parabolic_lines, zero_set};
use spline_core::KnotVector;
use spline_geom::{NurbsSurface, Surface};

/// Deterministic uniform numbers in [0, 1).
fn rng(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A bicubic surface over [0, 1]² with two interior knots each way: a random height
/// field over a slightly sheared grid, random weights when `rational`.
fn random_surface(seed: u64, rational: bool) -> NurbsSurface<f64, 3> {
    let mut next = rng(seed);
    let knots = KnotVector::new(3, vec![0.0, 0.0, 0.0, 0.0, 0.4, 0.7, 1.0, 1.0, 1.0, 1.0]).unwrap();
    let n = knots.num_basis();
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..n {
        for j in 0..n {
            points.push(Vector3::new(
                i as f64 + 0.3 * j as f64 + 0.2 * next(),
                j as f64 + 0.2 * next(),
                2.0 * next() - 1.0,
            ));
            weights.push(if rational { 0.5 + 1.5 * next() } else { 1.0 });
        }
    }
    NurbsSurface::new(knots.clone(), knots, points, weights).unwrap()
}

/// The torus's parabolic lines are exactly its top and bottom circles: two closed curves on
/// parameter lines, every point at height ±r above the centre plane and at distance R from
/// the axis; nothing else, whatever the centre, axis and radii.
#[test]
fn torus_parabolic_lines_are_its_top_and_bottom_circles() {
    for (center, axis, major, minor) in [
        (Vector3::zeros(), Vector3::z(), 2.0, 1.0),
        (
            Vector3::new(1.0, -2.0, 0.5),
            Vector3::new(1.0, 2.0, 2.0),
            5.0,
            0.3,
        ),
        (
            Vector3::new(-3e3, 1e3, 7.0),
            Vector3::new(0.0, 1.0, 0.0),
            0.02,
            0.015,
        ),
    ] {
        let torus = NurbsSurface::torus(center, axis, major, minor).unwrap();
        let lines = parabolic_lines(&torus, 8).unwrap();
        assert_eq!(lines.curves.len(), 2, "{lines:?}");
        assert!(lines.regions.is_empty() && lines.singular.is_empty());
        let a = axis.normalize();
        let mut heights = Vec::new();
        for curve in &lines.curves {
            // A parameter line spanning the whole revolution.
            let fixed = (0..2).find(|&k| curve.iter().all(|p| p[k] == curve[0][k]));
            assert!(fixed.is_some(), "not a parameter line: {curve:?}");
            let k = 1 - fixed.unwrap();
            let (lo, hi) = curve
                .iter()
                .fold((1.0f64, 0.0f64), |(lo, hi), p| (lo.min(p[k]), hi.max(p[k])));
            assert!(lo == 0.0 && hi == 1.0, "{lo} {hi}");
            let h = a.dot(&(torus.eval(curve[0][0], curve[0][1]).unwrap() - center));
            heights.push(h);
            for p in curve {
                let x = torus.eval(p[0], p[1]).unwrap() - center;
                let along = a.dot(&x);
                let radial = (x - a * along).norm();
                assert!(
                    (along.abs() - minor).abs() < 1e-12 * major.max(1.0),
                    "{along}"
                );
                assert!((radial - major).abs() < 1e-12 * major.max(1.0), "{radial}");
            }
        }
        assert!(
            heights[0] * heights[1] < 0.0,
            "one top, one bottom: {heights:?}"
        );
    }
}

/// The signs of the numerators are the signs of K and H computed pointwise by spline-geom
/// (fundamental forms from the derivatives), on random polynomial and rational bicubics.
#[test]
fn numerator_signs_are_the_curvature_signs() {
    for (seed, rational) in [(1, false), (2, true), (3, true)] {
        let s = random_surface(seed, rational);
        let n = curvature_numerators(&s).unwrap();
        let mut next = rng(seed + 100);
        let mut checked = [0, 0];
        for _ in 0..400 {
            let (u, v) = (next(), next());
            let lp = s.local_properties(u, v).unwrap();
            let (k, h) = (n.gaussian.eval(u, v).unwrap(), n.mean.eval(u, v).unwrap());
            // Skip points too close to a zero to have a well-defined sign.
            if lp.gaussian_curvature.abs() > 1e-6 {
                assert_eq!(
                    k.signum(),
                    lp.gaussian_curvature.signum(),
                    "K at ({u}, {v})"
                );
                checked[0] += 1;
            }
            if lp.mean_curvature.abs() > 1e-6 {
                assert_eq!(h.signum(), lp.mean_curvature.signum(), "H at ({u}, {v})");
                checked[1] += 1;
            }
        }
        assert!(checked[0] > 300 && checked[1] > 300, "{checked:?}");
    }
}

/// Along the lines `v = c` and `u = c` for each of `lines_at`, `m` samples each: the sign
/// changes of the pointwise K are exactly the crossings of the reported parabolic lines
/// with the line, each within `tolerance` (a sample step plus a chord's sagitta). Returns
/// how many sign changes were checked.
fn crossings_match_sampling(
    s: &NurbsSurface<f64, 3>,
    lines: &spline_algebra::ZeroSet,
    lines_at: &[f64],
    m: usize,
    tolerance: f64,
) -> usize {
    let mut total = 0;
    for axis in 0..2 {
        for &c in lines_at {
            let at = |t: f64| if axis == 0 { (t, c) } else { (c, t) };
            let k: Vec<f64> = (0..=m)
                .map(|j| {
                    let (u, v) = at(j as f64 / m as f64);
                    s.local_properties(u, v).unwrap().gaussian_curvature
                })
                .collect();
            let sampled: Vec<f64> = (1..=m)
                .filter(|&j| k[j - 1] * k[j] < 0.0)
                .map(|j| (j as f64 - 0.5) / m as f64)
                .collect();
            // Crossings of the polylines with the line (the other coordinate = c).
            let o = 1 - axis;
            let mut found: Vec<f64> = Vec::new();
            for curve in &lines.curves {
                for w in curve.windows(2) {
                    let (a, b) = (w[0][o] - c, w[1][o] - c);
                    if a * b < 0.0 || (a == 0.0 && b != 0.0) {
                        let t = a / (a - b);
                        found.push(w[0][axis] + t * (w[1][axis] - w[0][axis]));
                    }
                }
            }
            found.sort_by(f64::total_cmp);
            assert_eq!(
                found.len(),
                sampled.len(),
                "axis {axis} c {c}: {found:?} vs {sampled:?}"
            );
            for (f, e) in found.iter().zip(&sampled) {
                assert!((f - e).abs() < tolerance, "axis {axis} c {c}: {f} vs {e}");
            }
            total += sampled.len();
        }
    }
    total
}

/// Dense sampling: along many lines `v = c` (and `u = c`), the sign changes of the
/// pointwise K are exactly where the reported parabolic lines cross the line — every sign
/// change found, none invented.
#[test]
fn parabolic_lines_match_dense_sampling() {
    let mut total = 0;
    for (seed, rational) in [(11, false), (12, true), (13, false), (14, true)] {
        let s = random_surface(seed, rational);
        let lines = parabolic_lines(&s, 16).unwrap();
        assert!(lines.regions.is_empty());
        total += crossings_match_sampling(
            &s,
            &lines,
            &[0.1234, 0.3321, 0.5077, 0.6941, 0.8813],
            4000,
            5e-3,
        );
    }
    assert!(total > 20, "the check is not vacuous: {total}");
}

/// The zero set of closed-form functions: a circle `(u − ½)² + (v − ½)² = ¼²` is one closed
/// curve; `(u − ½)(v − ½)` is the two lines `u = ½` and `v = ½` (the subdivision meets the
/// crossing exactly: every quarter has one sign and zero edges).
#[test]
fn zero_sets_of_closed_forms() {
    // Bernstein coefficients of (u − a)² on [0, 1]: a², a² − a, (1 − a)².
    let k = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).unwrap();
    let sq = |a: f64| [a * a, a * a - a, (1.0 - a) * (1.0 - a)];
    let (su, sv) = (sq(0.5), sq(0.5));
    let coefficients: Vec<f64> = (0..3)
        .flat_map(|i| (0..3).map(move |j| su[i] + sv[j] - 0.0625))
        .collect();
    let f = Surface::new(k.clone(), k.clone(), coefficients).unwrap();
    let zs = zero_set(&f, 32).unwrap();
    assert_eq!(zs.curves.len(), 1, "{zs:?}");
    let curve = &zs.curves[0];
    assert_eq!(curve.first(), curve.last(), "closed");
    for p in curve {
        assert!(((p[0] - 0.5).hypot(p[1] - 0.5) - 0.25).abs() < 1e-12);
    }
    let k1 = KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0]).unwrap();
    let saddle = Surface::new(k1.clone(), k1, vec![0.25, -0.25, -0.25, 0.25]).unwrap();
    let zs = zero_set(&saddle, 4).unwrap();
    assert_eq!(zs.curves.len(), 2, "{zs:?}");
    for (k, curve) in zs.curves.iter().enumerate() {
        let fixed = if curve[0][0] == 0.5 && curve[1][0] == 0.5 {
            0
        } else {
            1
        };
        assert!(curve.iter().all(|p| p[fixed] == 0.5), "{k}: {curve:?}");
        let span: Vec<f64> = curve.iter().map(|p| p[1 - fixed]).collect();
        assert_eq!(
            (
                span[0].min(span[span.len() - 1]),
                span[0].max(span[span.len() - 1])
            ),
            (0.0, 1.0)
        );
    }
    let e = zero_set(&f, 0).unwrap_err();
    assert_eq!(e.kind(), spline_core::ErrorKind::InvalidArgument);
    assert_eq!(
        (e.value(), e.interval()),
        (Some(0.0), Some((1.0, 10_000.0)))
    );
}

/// The umbilics of the ellipsoid `x²/b² + y²/a² + z²/c² = 1` (a > b > c, the largest axis
/// along y so that the umbilics are off the seam) sit at the closed form
/// `y = ±a √((a² − b²)/(a² − c²))`, `z = ±c √((b² − c²)/(a² − c²))`, `x = 0`; and the
/// principal curvatures computed pointwise agree there.
#[test]
fn ellipsoid_umbilics_sit_at_the_closed_form() {
    use spline_algebra::umbilics;
    for (a, b, c) in [(2.0f64, 1.5, 1.0), (3.0, 1.2, 0.5), (1.1, 1.05, 1.0)] {
        let sphere = NurbsSurface::sphere(Vector3::zeros(), 1.0).unwrap();
        let e = sphere.map_control_points(|p| Vector3::new(b * p.x, a * p.y, c * p.z));
        let found = umbilics(&e).unwrap();
        assert!(!found.not_isolated);
        assert_eq!(found.points.len(), 4, "{a} {b} {c}: {found:?}");
        let y = a * ((a * a - b * b) / (a * a - c * c)).sqrt();
        let z = c * ((b * b - c * c) / (a * a - c * c)).sqrt();
        let mut signs = Vec::new();
        for p in &found.points {
            let x = e.eval(p[0], p[1]).unwrap();
            assert!(x.x.abs() < 1e-9, "{x}");
            assert!(
                (x.y.abs() - y).abs() < 1e-9 && (x.z.abs() - z).abs() < 1e-9,
                "{x} vs {y} {z}"
            );
            signs.push((x.y.signum() as i32, x.z.signum() as i32));
            let lp = e.local_properties(p[0], p[1]).unwrap();
            assert!((lp.max_curvature - lp.min_curvature).abs() < 1e-6, "{lp:?}");
        }
        signs.sort_unstable();
        assert_eq!(signs, vec![(-1, -1), (-1, 1), (1, -1), (1, 1)]);
    }
    // A sphere: every point is umbilic; none reported, flagged as not isolated.
    let sphere = NurbsSurface::sphere(Vector3::new(1.0, 2.0, 3.0), 2.0).unwrap();
    let found = umbilics(&sphere).unwrap();
    assert!(found.points.is_empty() && found.not_isolated, "{found:?}");
    // A torus has none.
    let torus = NurbsSurface::torus(Vector3::zeros(), Vector3::z(), 2.0, 1.0).unwrap();
    let found = umbilics(&torus).unwrap();
    assert!(found.points.is_empty() && !found.not_isolated, "{found:?}");
}

/// Random surfaces: every reported umbilic has equal principal curvatures (pointwise), and
/// on a dense grid no point with nearly equal principal curvatures is far from a reported
/// one.
#[test]
fn umbilics_of_random_surfaces_match_sampling() {
    use spline_algebra::umbilics;
    let (mut total, mut sampled) = (0, 0);
    for (seed, rational) in [(21, false), (22, true), (23, false)] {
        let s = random_surface(seed, rational);
        let found = umbilics(&s).unwrap();
        for p in &found.points {
            let lp = s.local_properties(p[0], p[1]).unwrap();
            let scale = lp.max_curvature.abs().max(lp.min_curvature.abs()).max(1e-3);
            assert!(
                (lp.max_curvature - lp.min_curvature).abs() < 1e-7 * scale,
                "{p:?} {lp:?}"
            );
        }
        // Dense sampling of the umbilic defect (k1 − k2)² / (k1² + k2²): its local minima
        // below 1e-4 on a 200 × 200 grid must lie near reported umbilics.
        let m = 200;
        let defect = |u: f64, v: f64| {
            let lp = s.local_properties(u, v).unwrap();
            let d = lp.max_curvature - lp.min_curvature;
            d * d / (lp.max_curvature.powi(2) + lp.min_curvature.powi(2))
        };
        let grid: Vec<Vec<f64>> = (0..=m)
            .map(|i| {
                (0..=m)
                    .map(|j| defect(i as f64 / m as f64, j as f64 / m as f64))
                    .collect()
            })
            .collect();
        for i in 1..m {
            for j in 1..m {
                let d = grid[i][j];
                let is_min = (i - 1..=i + 1).all(|k| (j - 1..=j + 1).all(|l| grid[k][l] >= d));
                if is_min && d < 1e-4 {
                    let (u, v) = (i as f64 / m as f64, j as f64 / m as f64);
                    sampled += 1;
                    assert!(
                        found
                            .points
                            .iter()
                            .any(|p| (p[0] - u).abs() < 0.02 && (p[1] - v).abs() < 0.02),
                        "seed {seed}: a sampled near-umbilic at ({u}, {v}) (defect {d}) is not reported: {found:?}"
                    );
                }
            }
        }
        total += found.points.len();
    }
    assert!(
        total > 0 && sampled > 0,
        "the check is not vacuous: {total} {sampled}"
    );
    eprintln!("umbilics: {total} reported, {sampled} sampled near-umbilics");
}

/// A double zero curve (no sign change: `(u − v)²`) is not separable
/// by subdivision: the box budget stops the work and reports singular points on it.
#[test]
fn double_zero_curves_stop_at_the_budget() {
    let k = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).unwrap();
    // (u − v)² = u² − 2uv + v²: Bernstein coefficients b_ij = [i = j = 1 ? …] from the
    // blossom: u² → (0, 0, 1), uv → (0, ½, 1) ⊗ …, v² → (0, 0, 1).
    let sq = [0.0, 0.0, 1.0];
    let lin = [0.0, 0.5, 1.0];
    let c: Vec<f64> = (0..3)
        .flat_map(|i| (0..3).map(move |j| sq[i] - 2.0 * lin[i] * lin[j] + sq[j]))
        .collect();
    let f = Surface::new(k.clone(), k, c).unwrap();
    assert!((f.eval(0.3, 0.7).unwrap() - 0.16).abs() < 1e-15);
    let zs = zero_set(&f, 4).unwrap();
    assert!(!zs.singular.is_empty());
    for p in &zs.singular {
        assert!((p[0] - p[1]).abs() < 0.01, "{p:?}");
    }
}

/// Bernstein coefficients on [0, 1]² of bidegree (4, 4) of `Σ sign · (α u + β v + γ)⁴`.
fn quartic_ridges(terms: &[(f64, f64, f64, f64)]) -> Surface<f64, f64> {
    let binom = |n: usize, k: usize| -> f64 {
        (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
    };
    let fact = |n: usize| -> f64 { (1..=n).map(|k| k as f64).product() };
    // Power coefficients c[a][b] of u^a v^b.
    let mut c = [[0.0f64; 5]; 5];
    for &(sign, alpha, beta, gamma) in terms {
        for i in 0..=4 {
            for j in 0..=4 - i {
                let k = 4 - i - j;
                c[i][j] += sign * fact(4) / (fact(i) * fact(j) * fact(k))
                    * alpha.powi(i as i32)
                    * beta.powi(j as i32)
                    * gamma.powi(k as i32);
            }
        }
    }
    let coefficients: Vec<f64> = (0..=4)
        .flat_map(|ii| {
            (0..=4).map(move |jj| {
                let mut sum = 0.0;
                for a in 0..=ii {
                    for b in 0..=jj {
                        sum += c[a][b] * binom(ii, a) / binom(4, a) * binom(jj, b) / binom(4, b);
                    }
                }
                sum
            })
        })
        .collect();
    let k = KnotVector::new(4, vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0]).unwrap();
    Surface::new(k.clone(), k, coefficients).unwrap()
}

/// `s = (u + v − 1)⁴ − (u − v − 0.2)⁴`: Hessian eigenvalues `12(u + v − 1)² · 2 ≥ 0` along
/// `(1, 1)` and `−12(u − v − 0.2)² · 2 ≤ 0` along `(1, −1)`, each extremal along its own
/// direction on one line: the blue ridge (larger eigenvalue) is `u + v = 1`, the red ridge
/// `u − v = 0.2`; nothing else.
#[test]
fn ridges_of_a_closed_form() {
    use spline_algebra::ridges;
    let s = quartic_ridges(&[(1.0, 1.0, 1.0, -1.0), (-1.0, 1.0, -1.0, -0.2)]);
    let f = |u: f64, v: f64| (u + v - 1.0).powi(4) - (u - v - 0.2).powi(4);
    assert!((s.eval(0.3, 0.8).unwrap() - f(0.3, 0.8)).abs() < 1e-13);
    let r = ridges(&s, 16).unwrap();
    assert!(!r.blue.is_empty() && !r.red.is_empty(), "{r:?}");
    let blue: usize = r.blue.iter().map(Vec::len).sum();
    let red: usize = r.red.iter().map(Vec::len).sum();
    assert!(blue >= 10 && red >= 10, "{blue} {red}");
    for p in r.blue.iter().flatten() {
        assert!((p[0] + p[1] - 1.0).abs() < 1e-7, "blue {p:?}");
    }
    for p in r.red.iter().flatten() {
        assert!((p[0] - p[1] - 0.2).abs() < 1e-7, "red {p:?}");
    }
}

/// A clamped uniform cubic knot vector for `n` coefficients over [0, 1].
fn uniform_cubic(n: usize) -> KnotVector<f64> {
    let spans = n - 3;
    let mut knots = vec![0.0; 4];
    knots.extend((1..spans).map(|i| i as f64 / spans as f64));
    knots.extend([1.0; 4]);
    KnotVector::new(3, knots).unwrap()
}

/// The reproducers' first size (issue 25: "over 60 s", now seconds): a 60 × 60 random
/// bicubic height field over the unit square. Its 57² patches hold hundreds of parabolic
/// lines, umbilics and ridges; along lines `v = c` and `u = c` every sign change of the
/// pointwise K (40,000 samples a line) is a crossing of a reported parabolic line and none
/// is invented, every umbilic has equal principal curvatures, and both colours of ridge
/// are found.
#[test]
fn surface_features_at_the_reproducers_size() {
    let n = 60;
    let knots = uniform_cubic(n);
    let mut next = rng(60);
    let mut points = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (u, v) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
            points.push(Vector3::new(u, v, next()));
        }
    }
    let s = NurbsSurface::new(knots.clone(), knots, points, vec![1.0; n * n]).unwrap();
    let features = spline_algebra::surface_features(&s, 8).unwrap();
    let lines = &features.parabolic_lines;
    assert!(lines.regions.is_empty());
    assert!(lines.curves.len() > 100, "{}", lines.curves.len());
    // A sample step plus the chord's sagitta, on patches 1/57 wide.
    let crossings = crossings_match_sampling(&s, lines, &[0.1234, 0.5077, 0.8813], 40_000, 3e-4);
    assert!(crossings > 100, "the check is not vacuous: {crossings}");
    let umbilics = &features.umbilics.points;
    assert!(umbilics.len() > 100, "{}", umbilics.len());
    for p in umbilics {
        let lp = s.local_properties(p[0], p[1]).unwrap();
        let scale = lp.max_curvature.abs().max(lp.min_curvature.abs()).max(1e-3);
        assert!(
            (lp.max_curvature - lp.min_curvature).abs() < 1e-6 * scale,
            "{p:?} {lp:?}"
        );
    }
    let ridges = &features.ridges;
    assert!(ridges.red.len() > 100 && ridges.blue.len() > 100);
}

/// The reproducers' second size: a 40 × 40 random bicubic function `s(u, v)`. Every vertex
/// of its parabolic lines has a vanishing Hessian determinant, and at every vertex of a
/// ridge (away from the Hessian's umbilics) the derivative of its eigenvalue along its own
/// eigendirection, `Σ s_ijk e_i e_j e_k`, vanishes — computed here from the third
/// derivatives and nalgebra's eigenvectors, not from the ridge polynomials.
#[test]
fn function_ridges_at_the_reproducers_size() {
    use spline_algebra::{hessian_determinant, ridges};
    let n = 40;
    let knots = uniform_cubic(n);
    let mut next = rng(40);
    let values: Vec<f64> = (0..n * n).map(|_| next()).collect();
    let s = Surface::new(knots.clone(), knots, values).unwrap();
    let det = hessian_determinant(&s).unwrap();
    let parabolic = zero_set(&det.value, 8).unwrap();
    assert!(parabolic.curves.len() > 100, "{}", parabolic.curves.len());
    for p in parabolic.curves.iter().flatten() {
        let d = s.derivatives(p[0], p[1], 2).unwrap();
        let (suu, svv, suv) = (d[2][0], d[0][2], d[1][1]);
        // The scale of the determinant's rounding: the Hessian's size, squared.
        let size = (suu.abs() + svv.abs() + suv.abs()).powi(2);
        assert!(
            (suu * svv - suv * suv).abs() <= 1e-8 * size,
            "{p:?}: {suu} {svv} {suv}"
        );
    }
    let found = ridges(&s, 8).unwrap();
    assert!(found.red.len() > 100 && found.blue.len() > 100);
    let mut checked = 0;
    for (larger, lines) in [(false, &found.red), (true, &found.blue)] {
        for p in lines.iter().flatten() {
            let d = s.derivatives(p[0], p[1], 3).unwrap();
            let hessian = nalgebra::Matrix2::new(d[2][0], d[1][1], d[1][1], d[0][2]);
            let eigen = nalgebra::SymmetricEigen::new(hessian);
            let (l0, l1) = (eigen.eigenvalues[0], eigen.eigenvalues[1]);
            if (l0 - l1).abs() < 1e-3 * l0.abs().max(l1.abs()) {
                continue;
            }
            let k = if (l0 > l1) == larger { 0 } else { 1 };
            let e = eigen.eigenvectors.column(k);
            let (a, b) = (e[0], e[1]);
            let third = [d[3][0], d[2][1], d[1][2], d[0][3]];
            let along = third[0] * a.powi(3)
                + 3.0 * third[1] * a * a * b
                + 3.0 * third[2] * a * b * b
                + third[3] * b.powi(3);
            let size = third.iter().map(|t| t.abs()).fold(0.0, f64::max);
            assert!(
                along.abs() <= 1e-5 * size,
                "{p:?} ({larger}): {along} of {size}"
            );
            checked += 1;
        }
    }
    assert!(checked > 1000, "the check is not vacuous: {checked}");
}
