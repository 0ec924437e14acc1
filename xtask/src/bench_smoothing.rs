//! `cargo xtask bench smoothing`: the smoothing splines of `spline-fit` against scipy on
//! 10⁵ data, in the same run.
//!
//! 1. Runs `xtask/bench/smoothing_scipy.py` in `<target>/bench-venv` (created with scipy on
//!    first use): `make_smoothing_spline` with a given λ and with λ by GCV, `splrep(s=…)`
//!    (FITPACK) and `make_splrep(s=…)` (scipy's replica of FITPACK, the algorithm spline-fit
//!    follows), printing medians and checks (λ, residuals) as JSON.
//! 2. Runs `cargo bench -p spline-fit --bench smoothing` and reads criterion's medians and
//!    the `smoothing-check` lines.
//! 3. Prints medians, speed-ups (scipy / rust) and whether the results agree and the
//!    target is met: at least as fast as scipy on every workload.

use crate::bench::{self, seconds};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

const N: usize = 100_000;

/// Runs the comparison and prints the table.
///
/// # Errors
/// A message when Python, the scipy script or `cargo bench` fail, or their output cannot be
/// read.
pub(crate) fn run(repo_root: &Path) -> Result<(), String> {
    let target = bench::target_dir(repo_root);
    let python = bench::ensure_venv(&target)?;
    eprintln!("bench smoothing: timing scipy (GCV in scipy takes a minute or two)…");
    let scipy = bench::run_python_json(&python, &repo_root.join("xtask/bench/smoothing_scipy.py"))?;
    eprintln!("bench smoothing: running cargo bench -p spline-fit --bench smoothing…");
    let checks = bench::run_criterion(repo_root, "smoothing", &["smoothing-check"])?;
    let mut rust = BTreeMap::new();
    for id in ["lambda", "gcv", "residual"] {
        let id = format!("{id}/{N}");
        rust.insert(
            id.clone(),
            // criterion writes the function id `lambda/N` as `lambda_N`.
            bench::criterion_median(&target, &format!("smoothing/{}", id.replace('/', "_")))?,
        );
    }
    print_table(&scipy, &rust, &checks)
}

fn print_table(
    scipy: &Value,
    rust: &BTreeMap<String, f64>,
    checks: &BTreeMap<String, f64>,
) -> Result<(), String> {
    let results = scipy
        .get("results")
        .ok_or("scipy output has no \"results\"")?;
    let field = |id: &str, key: &str| -> Result<f64, String> {
        results
            .get(id)
            .and_then(|r| r.get(key))
            .and_then(Value::as_f64)
            .ok_or_else(|| format!("scipy output lacks {id}.{key}"))
    };
    let version = scipy.get("scipy").and_then(Value::as_str).unwrap_or("?");
    let numpy = scipy.get("numpy").and_then(Value::as_str).unwrap_or("?");
    // (label, scipy id, rust id, relative tolerance of the check)
    let rows = [
        (
            "make_smoothing_spline, λ = 1",
            format!("lambda/{N}"),
            format!("lambda/{N}"),
            1e-9,
        ),
        (
            "make_smoothing_spline, λ by GCV",
            format!("gcv/{N}"),
            format!("gcv/{N}"),
            1e-5,
        ),
        (
            "splrep(s = N/200), FITPACK",
            format!("splrep/{N}"),
            format!("residual/{N}"),
            1e-3,
        ),
        (
            "make_splrep(s = N/200)",
            format!("make_splrep/{N}"),
            format!("residual/{N}"),
            1e-9,
        ),
    ];
    println!();
    println!(
        "spline-fit vs scipy {version} (numpy {numpy}), N = {N}: medians, speed-up = scipy / rust"
    );
    println!(
        "{:<34} {:>11} {:>11} {:>9} {:>20} {:>20}  target",
        "workload", "scipy", "rust", "speed-up", "scipy check", "rust check"
    );
    let mut all_met = true;
    for (label, sid, rid, tol) in rows {
        let s = field(&sid, "median_s")?;
        let r = *rust
            .get(&rid)
            .ok_or_else(|| format!("no criterion median for {rid}"))?;
        let sc = field(&sid, "check")?;
        let rc = checks
            .get(&format!("smoothing-check {rid}"))
            .copied()
            .unwrap_or(f64::NAN);
        let agree = (rc - sc).abs() <= tol * sc.abs();
        let ratio = s / r;
        let met = ratio >= 1.0 && agree;
        all_met &= met;
        println!(
            "{label:<34} {:>11} {:>11} {:>8.2}× {sc:>20.12e} {rc:>20.12e}  ≥ 1×, check to {tol:e}: {}",
            seconds(s),
            seconds(r),
            ratio,
            if met { "met" } else { "MISSED" }
        );
    }
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
