//! Intersections against closed forms and dense sampling (none missed): curve–surface
//! points (tangential touches flagged), surface–surface curves traced to a tolerance.

// Grid indices become coordinates: small integer counts, exact as f64.
#![allow(clippy::cast_lossless)]

use nalgebra::Vector3;
use spline_core::KnotVector;
use spline_fit::{SurfaceProjector, Tolerances, intersect_curve_surface, intersect_surfaces};
use spline_geom::{BSpline, ErrorKind, NurbsSurface, ParamSurface, Surface};

type V3 = Vector3<f64>;

fn lcg(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A wavy bicubic surface over `[0, 4] × [0, 4]` with heights in `[−amp, amp]`.
fn wavy(rand: &mut impl FnMut() -> f64, amp: f64) -> Surface<f64, V3> {
    let k = KnotVector::clamped(3, 0.0, 1.0, &[0.3, 0.6]).unwrap();
    let n = k.num_basis();
    let pts = (0..n * n)
        .map(|i| {
            V3::new(
                (i / n) as f64 * 4.0 / (n - 1) as f64,
                (i % n) as f64 * 4.0 / (n - 1) as f64,
                amp * (2.0 * rand() - 1.0),
            )
        })
        .collect();
    Surface::new(k.clone(), k, pts).unwrap()
}

/// A random spatial curve crossing the box of [`wavy`] several times.
fn wiggle(rand: &mut impl FnMut() -> f64) -> BSpline<f64, V3> {
    let pts: Vec<V3> = (0..9)
        .map(|i| {
            V3::new(
                0.2 + 3.6 * rand(),
                0.2 + 3.6 * rand(),
                if i % 2 == 0 { 1.5 } else { -1.5 } * rand(),
            )
        })
        .collect();
    BSpline::new(KnotVector::clamped_uniform(3, 9, 0.0, 1.0).unwrap(), pts).unwrap()
}

/// Signed distance of `x` from the graph-like surface: height above the closest point
/// along the normal there.
fn signed<S: ParamSurface<f64, Point = V3>>(
    p: &SurfaceProjector<'_, f64, S>,
    x: V3,
) -> (f64, bool) {
    let hit = p.closest(x).unwrap();
    let ((a, b), (c, d)) = p.surface().domain();
    let interior = hit.u > a && hit.u < b && hit.v > c && hit.v < d;
    let props = p.surface().derivatives_into_normal(hit.u, hit.v);
    ((x - hit.point).dot(&props), interior)
}

trait Normal {
    fn derivatives_into_normal(&self, u: f64, v: f64) -> V3;
}
impl<S: ParamSurface<f64, Point = V3>> Normal for S {
    fn derivatives_into_normal(&self, u: f64, v: f64) -> V3 {
        let mut d = [V3::zeros(); 4];
        self.derivatives_into(u, v, 1, &mut d).unwrap();
        d[2].cross(&d[1]).normalize()
    }
}

/// Random curves against random surfaces: every sign change of the signed distance along a
/// dense sampling of the curve (with the foot point inside the domain) has an intersection
/// within its interval, and every reported point is on both.
#[test]
fn curve_surface_against_dense_sampling() {
    let mut rand = lcg(42);
    let mut total = 0;
    for case in 0..8 {
        let s = wavy(&mut rand, 1.0);
        let c = wiggle(&mut rand);
        let hits = intersect_curve_surface(&c, &s, &Tolerances::default()).unwrap();
        for h in &hits {
            assert!((c.eval(h.t).unwrap() - s.eval(h.u, h.v).unwrap()).norm() < 1e-8);
            assert!(
                !h.tangential,
                "case {case}: a transversal crossing flagged tangential"
            );
        }
        let projector = SurfaceProjector::new(&s).unwrap();
        let n: u32 = 2000;
        let samples: Vec<(f64, f64, bool)> = (0..=n)
            .map(|k| {
                let t = f64::from(k) / f64::from(n);
                let (d, interior) = signed(&projector, c.eval(t).unwrap());
                (t, d, interior)
            })
            .collect();
        for w in samples.windows(2) {
            let ((t0, d0, i0), (t1, d1, i1)) = (w[0], w[1]);
            if i0 && i1 && d0 * d1 < 0.0 && d0.abs() < 0.1 && d1.abs() < 0.1 {
                total += 1;
                assert!(
                    hits.iter().any(|h| h.t >= t0 - 1e-9 && h.t <= t1 + 1e-9),
                    "case {case}: a crossing in [{t0}, {t1}] was missed ({} found)",
                    hits.len()
                );
            }
        }
    }
    assert!(total > 20, "only {total} crossings sampled");
}

/// Lines and a sphere: two points, one tangential touch, none.
#[test]
fn lines_and_a_sphere() {
    let sphere = NurbsSurface::sphere(V3::new(0.0, 0.0, 0.0), 1.0).unwrap();
    let line = |a: V3, b: V3| BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0], vec![a, b]).unwrap();
    let hits = intersect_curve_surface(
        &line(V3::new(-2.0, 0.3, 0.2), V3::new(2.0, 0.3, 0.2)),
        &sphere,
        &Tolerances::default(),
    )
    .unwrap();
    assert_eq!(hits.len(), 2);
    let x = (1.0f64 - 0.09 - 0.04).sqrt();
    assert!((hits[0].point - V3::new(-x, 0.3, 0.2)).norm() < 1e-12);
    assert!((hits[1].point - V3::new(x, 0.3, 0.2)).norm() < 1e-12);
    let touch = intersect_curve_surface(
        &line(V3::new(-2.0, 0.0, 1.0), V3::new(2.0, 0.0, 1.0)),
        &sphere,
        &Tolerances::default(),
    )
    .unwrap();
    assert_eq!(touch.len(), 1, "{touch:?}");
    assert!(touch[0].tangential);
    // A touch is located to about the square root of the distance tolerance.
    assert!((touch[0].point - V3::new(0.0, 0.0, 1.0)).norm() < 1e-6);
    let miss = intersect_curve_surface(
        &line(V3::new(-2.0, 0.0, 1.1), V3::new(2.0, 0.0, 1.1)),
        &sphere,
        &Tolerances::default(),
    )
    .unwrap();
    assert!(miss.is_empty());
    let bad = Tolerances {
        angle: -1.0,
        ..Tolerances::default()
    };
    let e = intersect_curve_surface(&line(V3::zeros(), V3::new(1.0, 0.0, 0.0)), &sphere, &bad)
        .unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidTolerance);
}

/// A wavy surface cut by the plane z = c: the traced curves lie on both surfaces, their
/// chords within the tolerance of the level set, and every sign change of z − c on a dense
/// grid of the surface lies near a traced curve.
#[test]
fn surface_plane_against_dense_sampling() {
    let mut rand = lcg(9);
    for case in 0..4 {
        let s = wavy(&mut rand, 1.0);
        let c = 0.3 * (rand() - 0.5);
        let plane = Surface::bezier(vec![
            vec![V3::new(-1.0, -1.0, c), V3::new(-1.0, 5.0, c)],
            vec![V3::new(5.0, -1.0, c), V3::new(5.0, 5.0, c)],
        ])
        .unwrap();
        let tol = 1e-4;
        let curves = intersect_surfaces(
            &s,
            &plane,
            &Tolerances {
                trace: Some(tol),
                ..Tolerances::default()
            },
        )
        .unwrap();
        assert!(!curves.is_empty());
        for curve in &curves {
            for (k, p) in curve.points.iter().enumerate() {
                assert!(
                    (p.z - c).abs() < 1e-8,
                    "case {case}: off the plane by {}",
                    p.z - c
                );
                let (u, v) = curve.uv_a[k];
                assert!((s.eval(u, v).unwrap() - p).norm() < 1e-8);
            }
            // Chord midpoints: within the tolerance of the surface (the level set is where
            // the chord meets the plane).
            for (k, w) in curve.points.windows(2).enumerate() {
                let mid = (w[0] + w[1]) * 0.5;
                let (u0, v0) = curve.uv_a[k];
                let (u1, v1) = curve.uv_a[k + 1];
                let local =
                    spline_fit::closest_local(&s, mid, ((u0 + u1) * 0.5, (v0 + v1) * 0.5)).unwrap();
                assert!(
                    local.distance < 2.0 * tol,
                    "chord {k} strays by {}",
                    local.distance
                );
            }
        }
        // Dense sampling of z − c on a 150 × 150 grid of the surface.
        let n = 150;
        let g: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
        let grid = s.eval_grid(&g, &g).unwrap();
        let mut crossings = 0;
        for i in 0..=n {
            for j in 0..=n {
                let p = grid[i * (n + 1) + j];
                for q in [
                    (i < n).then(|| grid[(i + 1) * (n + 1) + j]),
                    (j < n).then(|| grid[i * (n + 1) + j + 1]),
                ]
                .into_iter()
                .flatten()
                {
                    if (p.z - c) * (q.z - c) < 0.0 {
                        crossings += 1;
                        let x = p + (q - p) * ((c - p.z) / (q.z - p.z));
                        let near = curves.iter().any(|cv| {
                            cv.points.windows(2).any(|w| {
                                segment_distance(&x, &w[0], &w[1]) < (q - p).norm() + 2.0 * tol
                            })
                        });
                        assert!(
                            near,
                            "case {case}: a crossing at {x:?} is far from every traced curve"
                        );
                    }
                }
            }
        }
        assert!(crossings > 50);
    }
}

fn segment_distance(x: &V3, a: &V3, b: &V3) -> f64 {
    let ab = b - a;
    let t = if ab.norm_squared() > 0.0 {
        ((x - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (x - (a + ab * t)).norm()
}

/// Two cylinders of radii 1 and 0.6 with perpendicular axes through the origin: two closed
/// loops, every point at distance 1 from the x axis and 0.6 from the y axis.
#[test]
fn two_cylinders() {
    use spline_geom::{Axis, CircleConstruction, Frame, NurbsCurve};
    let cylinder = |r: f64, axis: V3, len: f64| {
        let frame = Frame::with_normal(-axis * len, axis).unwrap();
        let circle = NurbsCurve::circle(&frame, r, CircleConstruction::Square).unwrap();
        NurbsSurface::extrusion(&circle, axis * 2.0 * len).unwrap()
    };
    let a = cylinder(1.0, V3::new(1.0, 0.0, 0.0), 2.0);
    let b = cylinder(0.6, V3::new(0.0, 1.0, 0.0), 2.0);
    let curves = intersect_surfaces(&a, &b, &Tolerances::default()).unwrap();
    assert_eq!(curves.len(), 2, "{} curves", curves.len());
    for c in &curves {
        assert!(c.closed);
        for p in &c.points {
            assert!(((p.y * p.y + p.z * p.z).sqrt() - 1.0).abs() < 1e-8);
            assert!(((p.x * p.x + p.z * p.z).sqrt() - 0.6).abs() < 1e-8);
        }
    }
    let _ = Axis::new(V3::zeros(), V3::new(0.0, 0.0, 1.0));
}
