//! Closest points on surfaces against brute force (a dense grid of the domain), closed
//! forms (sphere, torus, plane) and the first-order conditions of a minimum, including
//! targets whose closest point lies on the boundary of the domain.

// Grid indices become coordinates: small integer counts, exact as f64.
#![allow(clippy::cast_lossless)]

use nalgebra::Vector3;
use proptest::prelude::*;
use spline_core::KnotVector;
use spline_fit::{SurfaceProjector, closest_local, closest_point_on_surface};
use spline_geom::{ErrorKind, NurbsSurface, ParamSurface, Surface};

type V3 = Vector3<f64>;

/// The smallest distance over a `n × n` grid of the domain, where, and the largest distance
/// between neighbouring grid points (a bound of how much the grid can miss the minimum by).
fn brute<S: ParamSurface<f64, Point = V3>>(s: &S, q: V3, n: usize) -> (f64, (f64, f64), f64) {
    let ((a, b), (c, d)) = s.domain();
    let us: Vec<f64> = (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect();
    let vs: Vec<f64> = (0..=n).map(|j| c + (d - c) * j as f64 / n as f64).collect();
    let grid = s.eval_grid(&us, &vs).unwrap();
    let mut best = (f64::INFINITY, (a, c));
    let mut cell: f64 = 0.0;
    for i in 0..=n {
        for j in 0..=n {
            let p = grid[i * (n + 1) + j];
            let dist = (p - q).norm();
            if dist < best.0 {
                best = (dist, (us[i], vs[j]));
            }
            if i < n {
                cell = cell.max((grid[(i + 1) * (n + 1) + j] - p).norm());
            }
            if j < n {
                cell = cell.max((grid[i * (n + 1) + j + 1] - p).norm());
            }
        }
    }
    (best.0, best.1, cell)
}

/// The first-order conditions of a minimum of ‖S − Q‖² on the domain at `(u, v)`: the
/// gradient `(r·S_u, r·S_v)` vanishes in each free direction, and points out of the domain
/// in each direction held at a bound.
fn assert_stationary<S: ParamSurface<f64, Point = V3>>(
    s: &S,
    q: V3,
    u: f64,
    v: f64,
    kinks: &(Vec<f64>, Vec<f64>),
) {
    let d = s.derivatives_into_vec(u, v);
    let r = d[0] - q;
    let ((a, b), (c, e)) = s.domain();
    for (x, lo, hi, g, t, kinks) in [
        (u, a, b, r.dot(&d[1]), d[1], &kinks.0),
        (v, c, e, r.dot(&d[2]), d[2], &kinks.1),
    ] {
        // Along a knot line where the surface is only C⁰ (a kink) the minimum need not be
        // a stationary point.
        if kinks.iter().any(|k| (x - k).abs() < 1e-6) {
            continue;
        }
        let scale = r.norm() * t.norm() + 1e-300;
        let tol = 1e-7 * scale + 1e-12;
        if x <= lo {
            assert!(
                g >= -tol,
                "at the lower bound the gradient {g} points inward"
            );
        } else if x >= hi {
            assert!(
                g <= tol,
                "at the upper bound the gradient {g} points inward"
            );
        } else {
            assert!(
                g.abs() <= tol,
                "gradient {g} at an interior point (scale {scale})"
            );
        }
    }
}

trait Partials {
    fn derivatives_into_vec(&self, u: f64, v: f64) -> [V3; 3];
}

impl<S: ParamSurface<f64, Point = V3>> Partials for S {
    fn derivatives_into_vec(&self, u: f64, v: f64) -> [V3; 3] {
        let mut d = [V3::zeros(); 4];
        self.derivatives_into(u, v, 1, &mut d).unwrap();
        [d[0], d[2], d[1]]
    }
}

/// The interior knots of `s` where it is only C⁰ (multiplicity ≥ degree).
fn kinks(s: &Surface<f64, V3>) -> (Vec<f64>, Vec<f64>) {
    let of = |k: &KnotVector<f64>| {
        k.interior_breakpoints()
            .into_iter()
            .filter(|&(_, m)| m >= k.degree())
            .map(|(x, _)| x)
            .collect()
    };
    (of(s.knots_u()), of(s.knots_v()))
}

fn knots(p: usize, interior: &[f64]) -> KnotVector<f64> {
    KnotVector::clamped(p, 0.0, 1.0, interior).unwrap()
}

/// A random surface: degrees 1–3, up to three interior knots each way, control points in
/// `[−1, 1]³` on a wavy grid (so that it folds and has several local minima of distance).
fn surface_strategy() -> impl Strategy<Value = Surface<f64, V3>> {
    (
        1usize..=3,
        1usize..=3,
        proptest::collection::vec(0.05f64..0.95, 0..=3),
        proptest::collection::vec(0.05f64..0.95, 0..=3),
    )
        .prop_flat_map(|(p, q, mut iu, mut iv)| {
            iu.sort_by(f64::total_cmp);
            iv.sort_by(f64::total_cmp);
            let (ku, kv) = (knots(p, &iu), knots(q, &iv));
            let n = ku.num_basis() * kv.num_basis();
            proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), n).prop_map(
                move |c| {
                    let nv = kv.num_basis();
                    let pts = c
                        .iter()
                        .enumerate()
                        .map(|(k, &(x, y, z))| {
                            let (i, j) = ((k / nv) as f64, (k % nv) as f64);
                            V3::new(i + 0.4 * x, j + 0.4 * y, z)
                        })
                        .collect();
                    Surface::new(ku.clone(), kv.clone(), pts).unwrap()
                },
            )
        })
}

/// A target near the surface, far from it, or beyond one of its edges (whose closest point
/// is then usually on the boundary).
fn target_strategy() -> impl Strategy<Value = (u8, f64, f64, f64, V3)> {
    (
        0u8..3,
        0.0f64..=1.0,
        0.0f64..=1.0,
        0.1f64..2.0,
        (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0),
    )
        .prop_map(|(kind, u, v, r, (x, y, z))| (kind, u, v, r, V3::new(x, y, z)))
}

fn target_for(s: &Surface<f64, V3>, (kind, u, v, r, dir): (u8, f64, f64, f64, V3)) -> V3 {
    let p = s.eval(u, v).unwrap();
    match kind {
        0 => p + dir * r * 0.5,
        1 => p + dir * r * 5.0,
        _ => {
            // Beyond the edge u = 0 (or u = 1), out along the surface.
            let edge = if u < 0.5 { 0.0 } else { 1.0 };
            let d = s.derivatives(edge, v, 1).unwrap();
            let out = if edge == 0.0 { -d[1][0] } else { d[1][0] };
            s.eval(edge, v).unwrap() + out.normalize() * r + dir * 0.1
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Never farther than the best of a 200 × 200 grid (the global minimum is found), and
    /// stationary there.
    #[test]
    fn agrees_with_brute_force(s in surface_strategy(), targets in proptest::collection::vec(target_strategy(), 3)) {
        let projector = SurfaceProjector::new(&s).unwrap();
        for t in targets {
            let q = target_for(&s, t);
            let hit = projector.closest(q).unwrap();
            let (d_grid, _, cell) = brute(&s, q, 200);
            prop_assert!(hit.distance <= d_grid + 1e-12, "projection {} worse than the grid {}", hit.distance, d_grid);
            prop_assert!(hit.distance >= d_grid - cell, "below the grid by more than a cell");
            prop_assert!(((s.eval(hit.u, hit.v).unwrap() - q).norm() - hit.distance).abs() < 1e-12);
            assert_stationary(&s, q, hit.u, hit.v, &kinks(&s));
        }
    }
}

/// Targets beyond the edges: the closest points lie on the boundary of the domain and agree
/// with brute force there.
#[test]
fn boundary_closest_points() {
    let s = Surface::from_knots(
        (2, 3),
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        (0..4)
            .map(|i| {
                (0..4)
                    .map(|j| V3::new(i as f64, j as f64, ((i * j) as f64 * 0.7).sin()))
                    .collect()
            })
            .collect(),
    )
    .unwrap();
    let projector = SurfaceProjector::new(&s).unwrap();
    let mut on_boundary = 0;
    for k in 0..40 {
        let t = k as f64 / 39.0;
        for q in [
            V3::new(-1.0 - t, 3.0 * t, 0.3),
            V3::new(4.0 + t, 3.0 * t, -0.2),
            V3::new(3.0 * t, -0.5 - t, 0.5),
            V3::new(3.0 * t, 3.5 + t, 0.0),
            V3::new(-1.0, -1.0, 2.0 * t - 1.0),
        ] {
            let hit = projector.closest(q).unwrap();
            let (d_grid, _, _) = brute(&s, q, 300);
            assert!(
                hit.distance <= d_grid + 1e-12,
                "{q:?}: {} vs grid {d_grid}",
                hit.distance
            );
            assert_stationary(&s, q, hit.u, hit.v, &kinks(&s));
            if hit.u == 0.0 || hit.u == 1.0 || hit.v == 0.0 || hit.v == 1.0 {
                on_boundary += 1;
            }
        }
    }
    assert!(
        on_boundary >= 150,
        "only {on_boundary} of 200 on the boundary"
    );
}

/// Closed forms on NURBS surfaces: the sphere (radial projection), the torus (the nearest
/// point of the nearest tube circle).
#[test]
fn sphere_and_torus() {
    let center = V3::new(1.0, -2.0, 0.5);
    let sphere = NurbsSurface::sphere(center, 2.0).unwrap();
    let projector = SurfaceProjector::new(&sphere).unwrap();
    let torus = NurbsSurface::torus(center, V3::new(0.0, 0.0, 1.0), 3.0, 1.0).unwrap();
    let tp = SurfaceProjector::new(&torus).unwrap();
    for k in 0..200 {
        let a = k as f64 * 0.731;
        let b = (k as f64 * 0.377).sin() * 1.5;
        let r = 0.3 + (k % 7) as f64;
        let dir = V3::new(a.cos() * b.cos(), a.sin() * b.cos(), b.sin());
        let q = center + dir * r;
        let hit = projector.closest(q).unwrap();
        assert!(
            (hit.distance - (r - 2.0).abs()).abs() < 1e-11,
            "sphere: {} vs {}",
            hit.distance,
            (r - 2.0).abs()
        );
        assert!((hit.point - (center + dir * 2.0)).norm() < 1e-9);
        // Torus: the tube circle's nearest point, then the tube.
        let rel = q - center;
        let radial = V3::new(rel.x, rel.y, 0.0);
        if radial.norm() < 1e-3 {
            continue;
        }
        let ring = center + radial.normalize() * 3.0;
        let exact = ((q - ring).norm() - 1.0).abs();
        let hit = tp.closest(q).unwrap();
        assert!(
            (hit.distance - exact).abs() < 1e-10,
            "torus at {q:?}: {} vs {exact}",
            hit.distance
        );
    }
}

/// Random NURBS surfaces (random weights) against brute force.
#[test]
fn rational_against_brute_force() {
    let mut seed = 7u64;
    let mut rand = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..12 {
        let (nu, nv) = (5, 4);
        let pts: Vec<V3> = (0..nu * nv)
            .map(|k| {
                V3::new(
                    (k / nv) as f64 + 0.3 * rand(),
                    (k % nv) as f64 + 0.3 * rand(),
                    2.0 * rand() - 1.0,
                )
            })
            .collect();
        let weights: Vec<f64> = (0..nu * nv).map(|_| 0.2 + 3.0 * rand()).collect();
        let s = NurbsSurface::new(knots(2, &[0.3, 0.6]), knots(3, &[]), pts, weights).unwrap();
        let projector = SurfaceProjector::new(&s).unwrap();
        for _ in 0..8 {
            let q = V3::new(6.0 * rand() - 1.0, 5.0 * rand() - 1.0, 4.0 * rand() - 2.0);
            let hit = projector.closest(q).unwrap();
            let (d_grid, _, _) = brute(&s, q, 200);
            assert!(
                hit.distance <= d_grid + 1e-12,
                "{} vs grid {d_grid}",
                hit.distance
            );
            assert_stationary(&s, q, hit.u, hit.v, &(vec![], vec![]));
        }
    }
}

#[test]
fn one_shot_local_and_errors() {
    let plane = Surface::bezier(vec![
        vec![V3::new(0.0, 0.0, 0.0), V3::new(0.0, 2.0, 0.0)],
        vec![V3::new(2.0, 0.0, 0.0), V3::new(2.0, 2.0, 0.0)],
    ])
    .unwrap();
    let hit = closest_point_on_surface(&plane, V3::new(0.5, 1.5, 3.0)).unwrap();
    assert!((hit.u - 0.25).abs() < 1e-15 && (hit.v - 0.75).abs() < 1e-15);
    assert!((hit.distance - 3.0).abs() < 1e-15);
    let local = closest_local(&plane, V3::new(5.0, -1.0, 1.0), (0.5, 0.5)).unwrap();
    assert_eq!((local.u, local.v), (1.0, 0.0));
    let e = closest_point_on_surface(&plane, V3::new(f64::NAN, 0.0, 0.0)).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NonFinite);
    let e = closest_local(&plane, V3::new(0.0, 0.0, 0.0), (1.5, 0.0)).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::OutOfDomain);
    let projector = SurfaceProjector::new(&plane).unwrap();
    let e = projector
        .closest_many(&[V3::new(0.0, 0.0, 0.0), V3::new(0.0, f64::INFINITY, 0.0)])
        .unwrap_err();
    assert!(e.to_string().contains("point 1"), "{e}");
}
