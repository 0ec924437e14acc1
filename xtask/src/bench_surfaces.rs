//! `cargo xtask bench surfaces`: closest points on surfaces against truck-geometry and
//! scattered least squares against scipy, in one run.
//!
//! 1. Creates (once) the Python virtual environment with scipy in `<target>/bench-venv`.
//! 2. Runs `xtask/bench/surfaces_scipy.py`: `LSQBivariateSpline` on 10⁴ and 10⁵ scattered
//!    heights with 20 × 20 coefficients, printing medians and residuals as JSON.
//! 3. Runs `cargo bench -p spline-fit --bench surfaces` (criterion): closest points with
//!    ours and truck-geometry's `SearchNearestParameter` (a bench-only dev-dependency), the
//!    same least squares, and the whole scattered-fitting pipeline; reads the medians from
//!    `<target>/criterion/surface_*/*/new/estimates.json` and the `closest-check`,
//!    `fit-residual` and `fit-deviation` lines the benchmark prints.
//! 4. Prints a table of medians, per-query times and speed-ups, and whether the issue's
//!    targets hold: a few microseconds per closest-point query after setup (≤ 5 µs), no
//!    query where truck finds a closer point than ours, least squares as small as scipy's.
//!    Timings are wall-clock medians: on a loaded machine they grow, the ratios much less.

use crate::bench::{self, seconds};
use serde_json::Value;
use std::path::Path;

/// Queries per closest-point benchmark iteration (`crates/spline-fit/benches/surfaces.rs`).
const QUERIES: f64 = 1000.0;

/// Runs the comparison and prints the table.
///
/// # Errors
/// A message when Python, pip, the scipy script or `cargo bench` fail, or when their output
/// cannot be read.
pub(crate) fn run(repo_root: &Path) -> Result<(), String> {
    let target = bench::target_dir(repo_root);
    let python = bench::ensure_venv(&target)?;
    eprintln!("bench surfaces: timing scipy…");
    let scipy = bench::run_python_json(&python, &repo_root.join("xtask/bench/surfaces_scipy.py"))?;
    eprintln!("bench surfaces: running cargo bench -p spline-fit --bench surfaces…");
    let lines = bench::run_criterion(repo_root, "surfaces", &["closest-check", "fit-residual"])?;
    let median = |id: &str| bench::criterion_median(&target, id);
    let scipy_field = |id: &str, key: &str| -> Result<f64, String> {
        scipy
            .pointer(&format!("/results/{}/{key}", id.replace('/', "~1")))
            .and_then(Value::as_f64)
            .ok_or_else(|| format!("scipy output lacks {id}.{key}"))
    };
    let count = |key: &str| -> Result<f64, String> {
        lines
            .get(&format!("closest-check {key}"))
            .copied()
            .ok_or_else(|| format!("the benchmark printed no closest-check {key}"))
    };

    println!();
    println!("closest points, 1000 queries on a bicubic with 10 × 10 control points (medians):");
    println!(
        "{:<40} {:>12} {:>12} {:>10}",
        "workload", "per query", "truck", "speed-up"
    );
    let setup = median("surface_closest/setup")?;
    println!(
        "{:<40} {:>12}",
        "setup (box hierarchy, once)",
        seconds(setup)
    );
    let mut all_met = true;
    for (label, ours, theirs) in [
        (
            "global (ours: boxes; truck: presearch)",
            "surface_closest/ours_global",
            "surface_closest/truck_global",
        ),
        (
            "local Newton from a hint",
            "surface_closest/ours_local",
            "surface_closest/truck_local",
        ),
    ] {
        let (o, t) = (median(ours)? / QUERIES, median(theirs)? / QUERIES);
        println!(
            "{label:<40} {:>12} {:>12} {:>9.1}×",
            seconds(o),
            seconds(t),
            t / o
        );
        if ours.ends_with("global") {
            let met = o <= 5e-6;
            all_met &= met;
            println!(
                "  target ≤ 5 µs per global query: {}",
                if met { "met" } else { "MISSED" }
            );
        }
    }
    let (farther, truck_farther, none, outside, boundary) = (
        count("ours_farther")?,
        count("truck_farther")?,
        count("truck_none")?,
        count("truck_outside")?,
        count("boundary_answers")?,
    );
    println!(
        "agreement (1e-9): ours farther {farther}; truck farther {truck_farther} (of which no answer {none}, outside the domain {outside}); our answers on the boundary {boundary}"
    );
    all_met &= farther == 0.0;

    let version = scipy.get("scipy").and_then(Value::as_str).unwrap_or("?");
    println!();
    println!(
        "least squares of scattered heights, bicubic 20 × 20 (scipy {version} LSQBivariateSpline):"
    );
    println!(
        "{:<22} {:>12} {:>12} {:>9} {:>18} {:>18}",
        "workload", "scipy", "rust", "speed-up", "scipy resid.", "rust resid."
    );
    for id in ["lsq/10000", "lsq/100000"] {
        let (s, r) = (
            scipy_field(id, "median_s")?,
            median(&format!("surface_fit/{id}"))?,
        );
        let sres = scipy_field(id, "residual")?;
        let rres = lines
            .get(&format!("fit-residual {id}"))
            .copied()
            .unwrap_or(f64::NAN);
        all_met &= rres <= sres * (1.0 + 1e-9);
        println!(
            "{id:<22} {:>12} {:>12} {:>8.2}× {sres:>18.10e} {rres:>18.10e}",
            seconds(s),
            seconds(r),
            s / r
        );
    }
    let pipeline = median("surface_fit/scattered/10000")?;
    println!(
        "fit_scattered, 10^4 noisy points in 3-D, 12 × 12, corrections: {} (no peer)",
        seconds(pipeline)
    );
    println!(
        "{}",
        if all_met {
            "all targets met"
        } else {
            "some targets missed"
        }
    );
    Ok(())
}
