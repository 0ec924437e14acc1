//! `cargo xtask bench fit`: the fitting benchmarks of `spline-fit` against scipy.
//!
//! 1. Creates a Python virtual environment in `<target>/bench-venv` (once) and installs
//!    scipy into it with pip.
//! 2. Runs `xtask/bench/fit_scipy.py`: `make_interp_spline` on 10⁴, 10⁵, 10⁶ planar points
//!    (cubic) and `make_lsq_spline` on 10⁵ points with 200 coefficients (QR and normal
//!    equations), printing medians and residuals as JSON.
//! 3. Runs `cargo bench -p spline-fit --bench fit` (criterion, the same workloads) and reads
//!    the medians from `<target>/criterion/fit/*/*/new/estimates.json`, the residuals from
//!    the `fit-residual` lines the benchmark prints.
//! 4. Prints a table of medians, speed-ups and residuals, and whether the targets are met
//!    (interpolation ≥ 2× scipy at 10⁵ points; least squares at least as fast as scipy's
//!    normal equations and ≥ 5× its default QR, with residuals as small).
//!
//! `<target>` is `$CARGO_TARGET_DIR` or `<repo>/target`. `OpenBLAS` core-type overrides
//! (`OPENBLAS_CORETYPE`, `OPENBLAS_L2_SIZE`) are removed from the environment of the Python
//! run only, so that numpy uses the kernels it would pick by itself.

use crate::bench::{self, seconds};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

/// Runs the comparison and prints the table.
///
/// # Errors
/// A message when Python, pip, the scipy script or `cargo bench` fail, or when their output
/// cannot be read.
pub(crate) fn run(repo_root: &Path) -> Result<(), String> {
    let target = bench::target_dir(repo_root);
    let python = bench::ensure_venv(&target)?;
    eprintln!("bench fit: timing scipy (a minute or two)…");
    let scipy = bench::run_python_json(&python, &repo_root.join("xtask/bench/fit_scipy.py"))?;
    eprintln!("bench fit: running cargo bench -p spline-fit --bench fit…");
    let residuals = bench::run_criterion(repo_root, "fit", &["fit-residual"])?;
    print_table(&scipy, &rust_medians(&target)?, &residuals)
}

/// The criterion medians of the fitting benchmark, by workload.
///
/// # Errors
/// A message when a median cannot be read.
pub(crate) fn rust_medians(target: &Path) -> Result<BTreeMap<String, f64>, String> {
    let mut rust = BTreeMap::new();
    for id in RUST_IDS {
        rust.insert(
            id.to_string(),
            bench::criterion_median(target, &format!("fit/{id}"))?,
        );
    }
    Ok(rust)
}

const RUST_IDS: [&str; 5] = [
    "interp/10000",
    "interp/100000",
    "interp/1000000",
    "lsq_normal/100000",
    "lsq_qr/100000",
];

/// One compared workload: medians, speed-up scipy / ours, residuals, and the target.
pub(crate) struct FitRow {
    pub(crate) label: &'static str,
    pub(crate) scipy: f64,
    pub(crate) rust: f64,
    pub(crate) scipy_residual: f64,
    pub(crate) rust_residual: f64,
    /// The speed-up asked for (0 where there is none).
    pub(crate) target: f64,
}

impl FitRow {
    pub(crate) fn ratio(&self) -> f64 {
        self.scipy / self.rust
    }

    /// The residual "as small" as scipy's: within a relative 1e-9 (least squares) or 1e-9
    /// absolute (interpolation).
    pub(crate) fn as_small(&self) -> bool {
        self.rust_residual <= self.scipy_residual * (1.0 + 1e-9) + 1e-9
    }

    pub(crate) fn met(&self) -> bool {
        self.ratio() >= self.target && self.as_small()
    }
}

/// The compared workloads from scipy's JSON and the criterion medians and residuals.
///
/// # Errors
/// A message when a result is missing.
pub(crate) fn fit_rows(
    scipy: &Value,
    rust: &BTreeMap<String, f64>,
    residuals: &BTreeMap<String, f64>,
) -> Result<Vec<FitRow>, String> {
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
    // (label, scipy id, rust id, target speed-up)
    let rows: [(&str, &str, &str, f64); 6] = [
        ("interp 10^4", "interp/10000", "interp/10000", 0.0),
        ("interp 10^5", "interp/100000", "interp/100000", 2.0),
        ("interp 10^6", "interp/1000000", "interp/1000000", 0.0),
        (
            "lsq 10^5 normal vs scipy qr",
            "lsq_qr/100000",
            "lsq_normal/100000",
            5.0,
        ),
        (
            "lsq 10^5 normal vs scipy norm-eq",
            "lsq_norm_eq/100000",
            "lsq_normal/100000",
            1.0,
        ),
        (
            "lsq 10^5 qr vs scipy qr",
            "lsq_qr/100000",
            "lsq_qr/100000",
            0.0,
        ),
    ];
    rows.into_iter()
        .map(|(label, sid, rid, target)| {
            Ok(FitRow {
                label,
                scipy: field(sid, "median_s")?,
                rust: *rust
                    .get(rid)
                    .ok_or_else(|| format!("no criterion median for {rid}"))?,
                scipy_residual: field(sid, "residual")?,
                rust_residual: residuals
                    .get(&format!("fit-residual {rid}"))
                    .copied()
                    .unwrap_or(f64::NAN),
                target,
            })
        })
        .collect()
}

fn print_table(
    scipy: &Value,
    rust: &BTreeMap<String, f64>,
    residuals: &BTreeMap<String, f64>,
) -> Result<(), String> {
    let version = scipy.get("scipy").and_then(Value::as_str).unwrap_or("?");
    let numpy = scipy.get("numpy").and_then(Value::as_str).unwrap_or("?");
    println!();
    println!("spline-fit vs scipy {version} (numpy {numpy}): medians, speed-up = scipy / rust");
    println!(
        "{:<34} {:>12} {:>12} {:>9} {:>18} {:>18}  target",
        "workload", "scipy", "rust", "speed-up", "scipy resid.", "rust resid."
    );
    let mut all_met = true;
    for row in fit_rows(scipy, rust, residuals)? {
        let verdict = if row.target > 0.0 {
            all_met &= row.met();
            format!(
                "≥ {}×: {}",
                row.target,
                if row.met() { "met" } else { "MISSED" }
            )
        } else {
            String::new()
        };
        println!(
            "{:<34} {:>12} {:>12} {:>8.2}× {:>18.10e} {:>18.10e}  {verdict}",
            row.label,
            seconds(row.scipy),
            seconds(row.rust),
            row.ratio(),
            row.scipy_residual,
            row.rust_residual
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
