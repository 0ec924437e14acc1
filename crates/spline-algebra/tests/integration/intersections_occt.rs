//! Curve–curve intersections that the Open CASCADE geometry suite (`tests/occt/geometry.py`)
//! found wrong, each with its answer computed independently: collinear segments overlapping
//! in part (one touching point was reported), an overlap across a sharp C0 corner (broken in
//! two, a piece left out), a crossing with a rational degree-1 curve (missed), a crossing
//! beside an overlap (dropped), and parameters one rounding step past the end of a domain
//! (the command failed). The reproducers' control points and knots are copied here.

use nalgebra::Vector2;
use spline_algebra::{
    CurveIntersections, CurveOverlap, intersect_curves, intersect_curves_relative,
};
use spline_geom::{BSpline, NurbsCurve};

type Curve = BSpline<f64, Vector2<f64>>;
type Rational = NurbsCurve<f64, 2>;

fn v2(p: [f64; 2]) -> Vector2<f64> {
    Vector2::new(p[0], p[1])
}

fn curve(degree: usize, knots: &[f64], points: &[[f64; 2]]) -> Curve {
    BSpline::from_knots(
        degree,
        knots.to_vec(),
        points.iter().copied().map(v2).collect(),
    )
    .unwrap()
}

fn rational(degree: usize, knots: &[f64], points: &[[f64; 2]], weights: &[f64]) -> Rational {
    let points = points.iter().copied().map(v2).collect();
    NurbsCurve::from_knots(degree, knots.to_vec(), points, weights.to_vec()).unwrap()
}

fn wedge(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The one overlap, with no isolated point beside it.
fn only_overlap(found: &CurveIntersections<f64>) -> CurveOverlap<f64> {
    assert!(found.points.is_empty(), "{found:?}");
    assert_eq!(found.overlaps.len(), 1, "{found:?}");
    found.overlaps[0]
}

/// A straight segment of a degree-1 curve: its interval, its ends and their weights.
struct Leg {
    interval: (f64, f64),
    ends: (Vector2<f64>, Vector2<f64>),
    weights: (f64, f64),
}

impl Leg {
    /// The parameter where the leg passes through `x` (on its line), if within the leg:
    /// the fraction `λ` of the chord inverted through the weights,
    /// `λ = μ w₁ / ((1 − μ) w₀ + μ w₁)`.
    fn parameter(&self, x: Vector2<f64>) -> Option<f64> {
        let d = self.ends.1 - self.ends.0;
        let lambda = (x - self.ends.0).dot(&d) / d.norm_squared();
        if !(-1e-12..=1.0 + 1e-12).contains(&lambda) {
            return None;
        }
        let (w0, w1) = self.weights;
        let mu = lambda * w0 / (lambda * w0 + (1.0 - lambda) * w1);
        Some(self.interval.0 + (self.interval.1 - self.interval.0) * mu)
    }
}

/// The legs of a degree-1 curve with simple interior knots (weights 1 if none given).
fn legs(knots: &[f64], points: &[[f64; 2]], weights: Option<&[f64]>) -> Vec<Leg> {
    let w = |i: usize| weights.map_or(1.0, |w| w[i]);
    (0..points.len() - 1)
        .map(|i| Leg {
            interval: (knots[i + 1], knots[i + 2]),
            ends: (v2(points[i]), v2(points[i + 1])),
            weights: (w(i), w(i + 1)),
        })
        .collect()
}

/// A quadratic Bézier piece: its interval and control points.
type Quadratic = ((f64, f64), [Vector2<f64>; 3]);

/// The Bézier pieces of a quadratic with knots `[k0, k0, k0, k1, k2, k2, k2]` (blossoms: the
/// middle point at `k1` divides `P1 P2` in the ratio of the knot spans).
fn quadratic_pieces(k: [f64; 3], p: &[[f64; 2]; 4]) -> [Quadratic; 2] {
    let [p0, p1, p2, p3] = p.map(v2);
    let m = p1 + (p2 - p1) * ((k[1] - k[0]) / (k[2] - k[0]));
    [((k[0], k[1]), [p0, p1, m]), ((k[1], k[2]), [m, p2, p3])]
}

/// The crossings `(u, v)` of quadratic Bézier pieces with straight legs, in closed form:
/// `n · (A(τ) − L₀) = 0` is a quadratic in `τ`.
fn quadratic_crossings(pieces: &[Quadratic], legs: &[Leg]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for ((u0, u1), q) in pieces {
        for leg in legs {
            let d = leg.ends.1 - leg.ends.0;
            let n = Vector2::new(-d.y, d.x);
            let c0 = n.dot(&(q[0] - leg.ends.0));
            let c1 = 2.0 * n.dot(&(q[1] - q[0]));
            let c2 = n.dot(&(q[0] - 2.0 * q[1] + q[2]));
            let disc = c1 * c1 - 4.0 * c2 * c0;
            if disc < 0.0 {
                continue;
            }
            // The stable pair of roots.
            let big = -0.5 * (c1 + c1.signum() * disc.sqrt());
            for tau in [big / c2, c0 / big] {
                if !(0.0..=1.0).contains(&tau) {
                    continue;
                }
                let x = q[0] * (1.0 - tau) * (1.0 - tau)
                    + q[1] * (2.0 * tau * (1.0 - tau))
                    + q[2] * (tau * tau);
                if let Some(v) = leg.parameter(x) {
                    out.push((u0 + (u1 - u0) * tau, v));
                }
            }
        }
    }
    out.sort_by(|x, y| x.0.total_cmp(&y.0));
    out
}

/// Every found point is one of `expected` (and the reverse), to `within` in both parameters.
fn same_points(found: &CurveIntersections<f64>, expected: &[(f64, f64)], within: f64) {
    assert!(found.overlaps.is_empty(), "{found:?}");
    assert_eq!(
        found.points.len(),
        expected.len(),
        "{found:?} against {expected:?}"
    );
    for (p, (u, v)) in found.points.iter().zip(expected) {
        assert!(
            (p.u - u).abs() <= within && (p.v - v).abs() <= within && !p.tangential,
            "{p:?} against ({u}, {v})"
        );
    }
}

/// `[[0,0],[1,0]]` against `[[0.5,0],[1.5,0]]` gave one touching point at u = 0.5: the
/// overlap is u ∈ [0.5, 1], v ∈ [0, 0.5] (v = u − 1/2). Also collinear segments of degrees
/// 1 to 3 (control points on the line, equally spaced: A(u) = P₀ + u (P₁ − P₀)) against a
/// segment B(v) = P₀ + (s + v (t − s)) (P₁ − P₀), s < 1 < t, either way round: the overlap is
/// u ∈ [s, 1], v ∈ [0, (1 − s) / (t − s)] (reversed: v from 1 to 1 − (1 − s) / (t − s)).
#[test]
fn collinear_segments_overlapping_in_part() {
    let knots = [0.0, 0.0, 1.0, 1.0];
    let a = curve(1, &knots, &[[0.0, 0.0], [1.0, 0.0]]);
    let b = curve(1, &knots, &[[0.5, 0.0], [1.5, 0.0]]);
    let o = only_overlap(&intersect_curves_relative(&a, &b, 1e-9).unwrap());
    assert_eq!((o.u, o.v, o.reversed), ((0.5, 1.0), (0.0, 0.5), false));

    // The ends of o329.json of the geometry suite, s its constructed start.
    let (p0, p1) = (
        Vector2::new(13.13652785823029, 14.71264333123128),
        Vector2::new(11.434176616305496, 26.568849389590937),
    );
    let at = |f: f64| p0 + (p1 - p0) * f;
    for degree in 1..=3 {
        for (s, t) in [(0.48686577534014897, 1.6), (0.1, 1.9), (0.9, 1.05)] {
            let line: Vec<Vector2<f64>> =
                (0..=degree).map(|i| at(i as f64 / degree as f64)).collect();
            let mut knots = vec![0.0; degree + 1];
            knots.extend(vec![1.0; degree + 1]);
            let a = BSpline::from_knots(degree, knots, line).unwrap();
            let end = (1.0 - s) / (t - s);
            for reversed in [false, true] {
                let ends = if reversed {
                    [at(t), at(s)]
                } else {
                    [at(s), at(t)]
                };
                let b = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0], ends.to_vec()).unwrap();
                let found = intersect_curves_relative(&a, &b, 1e-9).unwrap();
                let o = only_overlap(&found);
                let v = if reversed {
                    (1.0, 1.0 - end)
                } else {
                    (0.0, end)
                };
                let close = |x: (f64, f64), y: (f64, f64)| {
                    (x.0 - y.0).abs() < 1e-12 && (x.1 - y.1).abs() < 1e-12
                };
                assert!(
                    close(o.u, (s, 1.0)) && close(o.v, v) && o.reversed == reversed,
                    "degree {degree}, s {s}, t {t}, reversed {reversed}: {o:?}"
                );
            }
        }
    }
}

/// o389.json: a cubic with a sharp C0 corner at u = 1 (the tangent turns by 153°) against
/// itself gave [0, 1.00000003] and [1.0159, 2], the piece between left out: one overlap,
/// the whole curve. A piece across the corner against the whole curve: the piece's interval.
#[test]
fn an_overlap_across_a_sharp_corner_is_one() {
    let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0];
    let points = [
        [0.0, 0.0],
        [1.0, 1.0],
        [2.0, 1.0],
        [3.0, 0.0],
        [2.0, 3.0],
        [4.0, 3.0],
        [5.0, 2.0],
    ];
    let c = curve(3, &knots, &points);
    let o = only_overlap(&intersect_curves_relative(&c, &c, 1e-9).unwrap());
    assert_eq!((o.u, o.v, o.reversed), ((0.0, 2.0), (0.0, 2.0), false));
    let piece: Curve = c.split(0.5).unwrap().1.split(1.5).unwrap().0;
    let o = only_overlap(&intersect_curves_relative(&c, &piece, 1e-9).unwrap());
    for (x, y) in [(o.u.0, 0.5), (o.u.1, 1.5), (o.v.0, 0.5), (o.v.1, 1.5)] {
        assert!((x - y).abs() < 1e-12, "{o:?}");
    }
}

/// o327.json / o328.json: a rational quadratic with a C0 corner at u = 0.6368…, and Open
/// CASCADE's piece of it on [c, d] (`Segment`), reversed (`Reverse`: B(v) = A(c + d − v)) with
/// a knot added: one reversed overlap u ∈ [c, d], v from d to c (its ends within the
/// touching distance, 1e-9 of the size, of the constructed ones), no point.
#[test]
fn a_reversed_rational_piece_across_a_corner() {
    let a = rational(
        2,
        &[
            0.2535974891980294,
            0.2535974891980294,
            0.2535974891980294,
            0.6368469901930828,
            0.6368469901930828,
            1.092147568188673,
            1.7930215731746801,
            1.7930215731746801,
            1.7930215731746801,
        ],
        &[
            [21.169399757452712, 17.243089284969308],
            [22.779614569942293, 49.26270986135419],
            [15.540254299873371, 57.76930829791455],
            [50.567732562647116, 48.832506921002064],
            [25.243077805863145, 20.943338160776236],
            [24.2004153164448, 20.893967280767832],
        ],
        &[
            2.2726558616311148,
            0.9717523270132273,
            2.448511002986055,
            1.172806329742384,
            0.3466556000243757,
            1.821309132482225,
        ],
    );
    let b = rational(
        2,
        &[
            0.37187581996155805,
            0.37187581996155805,
            0.37187581996155805,
            0.667699101969305,
            0.667699101969305,
            0.7864636473997444,
            0.9326702722008298,
            0.9326702722008298,
            0.9326702722008298,
        ],
        &[
            [40.51572387705565, 49.73639168361201],
            [32.01996078520773, 53.56472746841846],
            [15.540254299873371, 57.769308297914556],
            [16.635258408084372, 56.482625512773076],
            [19.866321727419816, 42.1349954607647],
            [20.797460430103037, 30.34932018707917],
        ],
        &[
            1.1919780238980175,
            1.6196450591452844,
            2.448511002986055,
            1.9908807323477271,
            1.5649948749994764,
            1.7342485258789602,
        ],
    );
    let (c, d) = (0.37187581996155805, 0.9326702722008298);
    // The construction: B(v) = A(c + d − v).
    for v in [0.4, 0.6, 0.66, 0.7, 0.9] {
        assert!((b.eval(v).unwrap() - a.eval(c + d - v).unwrap()).norm() < 1e-12);
    }
    let o = only_overlap(&intersect_curves_relative(&a, &b, 1e-9).unwrap());
    assert!(o.reversed, "{o:?}");
    let touch = 2.0 * 1e-9 * 40.0;
    let on_a = |u: f64| a.eval(u).unwrap();
    for (x, y) in [(on_a(o.u.0), on_a(c)), (on_a(o.u.1), on_a(d))] {
        assert!((x - y).norm() <= touch, "{o:?}");
    }
    for (x, y) in [
        (b.eval(o.v.0).unwrap(), on_a(c)),
        (b.eval(o.v.1).unwrap(), on_a(d)),
    ] {
        assert!((x - y).norm() <= touch, "{o:?}");
    }
}

/// o391.json / o392.json: a cubic Bézier loop against its second half (the same control
/// points subdivided at 1/2) gave the overlap but dropped the crossing of the loop: the curve
/// passes the origin at u = 1/6 and u = 5/6, so the first half crosses the second at
/// (u, v) = (1/6, 5/6).
#[test]
fn a_crossing_beside_an_overlap() {
    let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let p = [
        [1.25, -1.875],
        [-1.75, 3.875],
        [-1.75, -3.875],
        [1.25, 1.875],
    ];
    let a = curve(3, &knots, &p);
    // The loop closes at the origin (Bernstein form, the test's own).
    let bezier = |t: f64| {
        let s = 1.0 - t;
        v2(p[0]) * (s * s * s)
            + v2(p[1]) * (3.0 * s * s * t)
            + v2(p[2]) * (3.0 * s * t * t)
            + v2(p[3]) * (t * t * t)
    };
    assert!(bezier(1.0 / 6.0).norm() < 1e-15 && bezier(5.0 / 6.0).norm() < 1e-15);
    let half = [0.5, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0];
    let b = curve(
        3,
        &half,
        &[[-1.0, 0.0], [-1.0, -0.5], [-0.25, -1.0], [1.25, 1.875]],
    );
    let found = intersect_curves_relative(&a, &b, 1e-9).unwrap();
    assert_eq!(found.points.len(), 1, "{found:?}");
    let x = found.points[0];
    assert!(
        (x.u - 1.0 / 6.0).abs() < 1e-14 && (x.v - 5.0 / 6.0).abs() < 1e-14 && !x.tangential,
        "{x:?}"
    );
    assert_eq!(found.overlaps.len(), 1, "{found:?}");
    let o = found.overlaps[0];
    // Where the overlap ends because B does: at the foot of B's end.
    assert!((o.u.0 - 0.5).abs() < 1e-12 && o.u.1 == 1.0, "{o:?}");
    assert_eq!((o.v, o.reversed), ((0.5, 1.0), false));
}

/// o383.json / o384.json: a quadratic against a rational degree-1 curve (weights 0.57,
/// 0.36, 2.34) missed the crossing at u = 0.946556835140767, v = 0.4803425982839834 (Open
/// CASCADE's): the start for Newton's method took the chord's fraction for the parameter.
/// The crossings in closed form: each quadratic piece against each leg.
#[test]
fn a_crossing_with_a_rational_line() {
    let p = [[-0.1, -0.3], [-0.8, -0.47], [-0.97, -0.06], [-0.85, -1.11]];
    let a = curve(2, &[0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0], &p);
    let (knots, q, w) = (
        [0.0, 0.0, 0.4, 1.0, 1.0],
        [[-1.13, -0.03], [-1.56, -0.95], [-0.19, -0.85]],
        [0.57, 0.36, 2.34],
    );
    let b = rational(1, &knots, &q, &w);
    let expected = quadratic_crossings(
        &quadratic_pieces([0.0, 0.5, 1.0], &p),
        &legs(&knots, &q, Some(&w)),
    );
    assert_eq!(expected.len(), 1, "{expected:?}");
    let (u, v) = expected[0];
    assert!((u - 0.946556835140767).abs() < 1e-14 && (v - 0.4803425982839834).abs() < 1e-14);
    same_points(
        &intersect_curves_relative(&a, &b, 1e-9).unwrap(),
        &expected,
        1e-14,
    );
}

/// o385.json / o386.json: `intersect` failed with "parameter 0.6752854320379084 is outside
/// the domain [-0.640724881610729, 0.6752854320379083]": a sample `x₀ + (x₁ − x₀) k / n` one
/// rounding step past the end knot. The crossings of the quadratic with the line in closed
/// form.
#[test]
fn parameters_stay_in_the_domain() {
    let k = [-0.640724881610729, -0.1496352764229789, 0.6752854320379083];
    let p = [
        [364.0, -1116.0],
        [171.0, -1976.0],
        [43.0, -1519.0],
        [-996.0, -614.0],
    ];
    let a = curve(2, &[k[0], k[0], k[0], k[1], k[2], k[2], k[2]], &p);
    let q = [[-160.0, -1587.0], [397.0, -1529.0]];
    let b = curve(1, &[0.0, 0.0, 1.0, 1.0], &q);
    let expected = quadratic_crossings(
        &quadratic_pieces(k, &p),
        &legs(&[0.0, 0.0, 1.0, 1.0], &q, None),
    );
    assert_eq!(expected.len(), 2, "{expected:?}");
    for (x, y) in [(&a, &b), (&b, &a)] {
        let _ = intersect_curves_relative(x, y, 1e-9).unwrap();
    }
    same_points(
        &intersect_curves_relative(&a, &b, 1e-9).unwrap(),
        &expected,
        1e-13,
    );
}

/// o331.json / o332.json, the same failure at the end knot 0.9878629627966431 of a cubic
/// with a C0 knot, against a rational polyline: its eight crossings, found by the test's
/// own sign changes of `n · (B(τ) − L₀)` on every leg and every Bézier piece of the cubic.
#[test]
fn parameters_stay_in_the_domain_rational_polyline() {
    let (ka, pa, wa) = (
        [
            -0.17253531285493223,
            -0.17253531285493223,
            0.12729532810709981,
            0.6172025912484651,
            1.3438958312909537,
            1.8655490922779494,
            1.8655490922779494,
        ],
        [
            [-0.44734551007775203, -0.16033405754211827],
            [0.03791285209832086, 0.5627694388981664],
            [0.08794762281411735, 0.39112741500808695],
            [0.4588336211269063, 0.41536256182314785],
            [-0.6505662542577647, 0.2842271187316932],
        ],
        [
            2.691557496907351,
            0.7703961560295005,
            0.5385732621902198,
            1.7052502474477302,
            0.921488958886995,
        ],
    );
    let a = rational(1, &ka, &pa, &wa);
    let (k0, k1, k2) = (
        -0.47696477118569147,
        0.21649628466486326,
        0.9878629627966431,
    );
    let pb = [
        [-0.6076623840028778, 0.5784983935843961],
        [0.2253759570376201, -0.3227838731287033],
        [0.807591227187165, 0.6586794494542275],
        [-0.4694892992877179, 0.5508690922307992],
        [0.16113152547715628, 0.24386759357753862],
        [0.5293397365841507, 0.15341228398031032],
        [-0.04552314635620666, -0.6503928834110507],
    ];
    let b = curve(3, &[k0, k0, k0, k0, k1, k1, k1, k2, k2, k2, k2], &pb);
    let mut expected = Vec::new();
    for leg in legs(&ka, &pa, Some(&wa)) {
        let d = leg.ends.1 - leg.ends.0;
        for (lo, hi, q) in [(k0, k1, &pb[0..4]), (k1, k2, &pb[3..7])] {
            let at = |t: f64| {
                let s = 1.0 - t;
                v2(q[0]) * (s * s * s)
                    + v2(q[1]) * (3.0 * s * s * t)
                    + v2(q[2]) * (3.0 * s * t * t)
                    + v2(q[3]) * (t * t * t)
            };
            let g = |t: f64| wedge(d, at(t) - leg.ends.0);
            let n = 4000;
            for i in 0..n {
                let (mut x, mut y) = (f64::from(i) / f64::from(n), f64::from(i + 1) / f64::from(n));
                if g(x) * g(y) > 0.0 || g(y) == 0.0 {
                    continue;
                }
                for _ in 0..100 {
                    let m = 0.5 * (x + y);
                    if g(x) * g(m) <= 0.0 { y = m } else { x = m }
                }
                if let Some(u) = leg.parameter(at(x)) {
                    expected.push((u, lo + (hi - lo) * x));
                }
            }
        }
    }
    expected.sort_by(|x, y| x.0.total_cmp(&y.0));
    assert_eq!(expected.len(), 8, "{expected:?}");
    let found = intersect_curves_relative(&a, &b, 1e-9).unwrap();
    same_points(&found, &expected, 1e-12);
    let ((da0, da1), (db0, db1)) = (a.domain(), b.domain());
    for p in &found.points {
        assert!(
            (da0..=da1).contains(&p.u) && (db0..=db1).contains(&p.v),
            "{p:?}"
        );
    }
    // The other way round: no failure either.
    let _ = intersect_curves(&b, &a, 1e-9 * 1.5).unwrap();
}
