//! Scattered fitting of a sampled analytic surface with noise: the fit reaches the stated
//! deviation from the true surface; deviations both ways; meshes; errors.

// Grid indices become coordinates: small integer counts, exact as f64.
#![allow(clippy::cast_lossless)]

use nalgebra::Vector3;
use spline_fit::{ScatteredOptions, fit_scattered};
use spline_geom::{ErrorKind, Surface};

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

/// The analytic surface: a rotated, tilted graph of `sin x cos y` over `[0, 2] × [0, 2]`.
fn truth(x: f64, y: f64) -> V3 {
    let z = 0.3 * (1.5 * x).sin() * (1.2 * y).cos();
    let (c, s) = (0.6f64.cos(), 0.6f64.sin());
    V3::new(c * x - s * z, y, s * x + c * z)
}

/// Gaussian noise by Box–Muller.
fn gauss(rand: &mut impl FnMut() -> f64) -> f64 {
    let (a, b) = (rand().max(1e-300), rand());
    (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
}

/// 3000 random samples with noise σ = 1e-3 (normal to nothing in particular, in all three
/// coordinates): the fit is within 3σ of the true surface everywhere inside, and its
/// data → surface RMS is about σ√3 (all three coordinates carry noise, the normal
/// component about σ).
#[test]
fn noisy_samples_of_an_analytic_surface() {
    let mut rand = lcg(2024);
    let sigma = 1e-3;
    let points: Vec<V3> = (0..3000)
        .map(|_| {
            let (x, y) = (2.0 * rand(), 2.0 * rand());
            truth(x, y) + V3::new(gauss(&mut rand), gauss(&mut rand), gauss(&mut rand)) * sigma
        })
        .collect();
    let options = ScatteredOptions {
        control_points: (10, 10),
        smoothing: 1e-9,
        corrections: 5,
        ..ScatteredOptions::default()
    };
    let fit = fit_scattered::<f64, Surface<f64, V3>>(&points, None, None, &options).unwrap();
    // The true surface against the fit, on a grid inside the data (closest points on the
    // fit: independent of the fit's parametrisation).
    let projector = spline_fit::SurfaceProjector::new(&fit.surface).unwrap();
    let mut worst: f64 = 0.0;
    for i in 1..20 {
        for j in 1..20 {
            let x = truth(2.0 * i as f64 / 20.0, 2.0 * j as f64 / 20.0);
            worst = worst.max(projector.closest(x).unwrap().distance);
        }
    }
    assert!(
        worst < 3.0 * sigma,
        "the fit is {worst} from the true surface"
    );
    assert!(
        fit.to_surface.rms > 0.5 * sigma && fit.to_surface.rms < 1.5 * sigma,
        "rms {}",
        fit.to_surface.rms
    );
    assert!(
        fit.to_surface.max < 6.0 * sigma,
        "max {}",
        fit.to_surface.max
    );
    // Surface → data includes the spacing of the random samples (about 0.04 apart).
    assert!(fit.to_data < 0.1, "surface → data {}", fit.to_data);
    assert!(fit.corrections >= 1);
}

/// A triangle mesh of the graph of `0.3 sin 1.5x cos 1.2y` over a square: the fit is within
/// 2e-4 of every vertex, the surface → mesh distance measured to the triangles. The
/// least-squares plane of the vertices is tilted against the square, so the projected data
/// do not fill the rectangle of the domain: the surface extends beyond the data at the
/// corners (by 0.058 here, 3 % of the size), and surface → data measures that extension.
#[test]
fn triangle_mesh() {
    let n = 30;
    let graph = |x: f64, y: f64| V3::new(x, y, 0.3 * (1.5 * x).sin() * (1.2 * y).cos());
    let points: Vec<V3> = (0..=n)
        .flat_map(|i| {
            (0..=n).map(move |j| graph(2.0 * i as f64 / n as f64, 2.0 * j as f64 / n as f64))
        })
        .collect();
    let mut triangles = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let k = i * (n + 1) + j;
            triangles.push([k, k + n + 1, k + 1]);
            triangles.push([k + 1, k + n + 1, k + n + 2]);
        }
    }
    let options = ScatteredOptions {
        control_points: (12, 12),
        ..ScatteredOptions::default()
    };
    let fit =
        fit_scattered::<f64, Surface<f64, V3>>(&points, Some(&triangles), None, &options).unwrap();
    assert!(
        fit.to_surface.max < 2e-4,
        "data → surface {}",
        fit.to_surface.max
    );
    assert!(
        fit.to_data > 0.03 && fit.to_data < 0.07,
        "surface → mesh {}",
        fit.to_data
    );
    // A base surface for the parameters: the fit of the mesh itself.
    let again = fit_scattered(&points, Some(&triangles), Some(&fit.surface), &options).unwrap();
    assert!(again.to_surface.max < 2e-4);
}

#[test]
fn errors() {
    let points: Vec<V3> = (0..50)
        .map(|k| V3::new(k as f64, (k * k % 7) as f64, 0.0))
        .collect();
    let none: Option<&Surface<f64, V3>> = None;
    let opts = |nu, nv| ScatteredOptions {
        control_points: (nu, nv),
        ..ScatteredOptions::default()
    };
    assert_eq!(
        fit_scattered(&points, None, none, &opts(10, 10))
            .unwrap_err()
            .kind(),
        ErrorKind::TooFewPoints
    );
    assert_eq!(
        fit_scattered(&points, None, none, &opts(2, 5))
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        fit_scattered(&points, None, none, &opts(usize::MAX, 5))
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    let many = ScatteredOptions {
        corrections: usize::MAX,
        ..opts(4, 4)
    };
    assert_eq!(
        fit_scattered(&points, None, none, &many)
            .unwrap_err()
            .kind(),
        ErrorKind::InvalidArgument
    );
    assert_eq!(
        fit_scattered(&points, Some(&[[0, 1, 50]]), none, &opts(4, 4))
            .unwrap_err()
            .kind(),
        ErrorKind::IndexOutOfRange
    );
    let line: Vec<V3> = (0..50).map(|k| V3::new(k as f64, 0.0, 0.0)).collect();
    assert_eq!(
        fit_scattered(&line, None, none, &opts(4, 4))
            .unwrap_err()
            .kind(),
        ErrorKind::DegenerateGeometry
    );
    let mut bad = points.clone();
    bad[3].y = f64::NAN;
    assert_eq!(
        fit_scattered(&bad, None, none, &opts(4, 4))
            .unwrap_err()
            .kind(),
        ErrorKind::NonFinite
    );
}
