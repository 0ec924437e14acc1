//! `cargo xtask bench python`: 10⁶-point evaluation through the Python package against the
//! Rust batch (criterion, `benches/curves.rs`) and scipy's `BSpline.__call__`, in the same
//! run (`xtask/bench/eval_python.py`). The package should be within 1.5× of the Rust batch
//! and at least 3× faster than scipy. Then the scipy drop-in's rows (`python/bench/scipy_rows.py`):
//! evaluation with extrapolation, `make_interp_spline`, `make_lsq_spline`,
//! `make_smoothing_spline` and `make_splrep` through the package and through scipy on the
//! same data (results compared before timing), medians and the ratio.

use crate::bench::{self, seconds};
use serde_json::Value;
use std::path::Path;
use std::process::{Command, Stdio};

const POINTS: f64 = 1e6;
const GROUP: &str = "cubic_100_ctrl_1e6_params";

/// Builds and installs the package, times both Python sides, runs the criterion batch
/// benchmarks and prints medians per point and the ratios.
pub(crate) fn run(root: &Path) -> Result<(), String> {
    let target = bench::target_dir(root);
    let python = crate::test_python::prepare(root, crate::test_python::Build::Release)?;
    eprintln!("bench python: timing the package and scipy…");
    let py = bench::run_python_json(&python, &root.join("xtask/bench/eval_python.py"))?;
    eprintln!("bench python: running cargo bench --bench curves -- batched…");
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let status = Command::new(cargo)
        .args(["bench", "--bench", "curves", "--", "batched_"])
        .current_dir(root)
        .stdout(Stdio::inherit())
        .status()
        .map_err(|e| format!("cannot run cargo bench: {e}"))?;
    if !status.success() {
        return Err(format!("cargo bench --bench curves failed ({status})"));
    }
    let field = |id: &str| -> Result<f64, String> {
        py.pointer(&format!("/results/{id}/median_s"))
            .and_then(Value::as_f64)
            .ok_or_else(|| format!("eval_python.py output lacks {id}"))
    };
    println!();
    println!(
        "10⁶-point evaluation, cubic planar curve with 100 control points: medians per point \
         (scipy {}, numpy {})",
        py.get("scipy").and_then(Value::as_str).unwrap_or("?"),
        py.get("numpy").and_then(Value::as_str).unwrap_or("?")
    );
    println!(
        "{:<14} {:>11} {:>11} {:>11} {:>15} {:>15}",
        "order", "rust batch", "python", "scipy", "python / rust", "scipy / python"
    );
    let mut ok = true;
    for (order, id, rust_id) in [
        ("random", "random_order", "batched_random_order"),
        ("sorted", "sorted", "batched_sorted"),
    ] {
        let ours = field(&format!("spline_{id}"))? / POINTS;
        let scipy = field(&format!("scipy_{id}"))? / POINTS;
        let rust = bench::criterion_median(&target, &format!("{GROUP}/{rust_id}"))? / POINTS;
        let (slow, fast) = (ours / rust, scipy / ours);
        ok &= slow <= 1.5 && fast >= 3.0;
        println!(
            "{order:<14} {:>11} {:>11} {:>11} {:>14.2}× {:>14.1}×",
            seconds(rust),
            seconds(ours),
            seconds(scipy),
            slow,
            fast
        );
    }
    println!(
        "targets: python within 1.5× of the Rust batch, at least 3× faster than scipy: {}",
        if ok { "met" } else { "NOT met" }
    );
    scipy_rows(root, &python)
}

/// The scipy drop-in's rows: the same calls through the package and scipy, medians.
fn scipy_rows(root: &Path, python: &Path) -> Result<(), String> {
    eprintln!("bench python: the scipy drop-in's rows…");
    let rows = bench::run_python_json(python, &root.join("python/bench/scipy_rows.py"))?;
    let rows = rows
        .get("rows")
        .and_then(Value::as_array)
        .ok_or("scipy_rows.py output lacks rows")?;
    println!();
    println!("scipy's B-spline API through the package and through scipy: medians per call");
    println!(
        "{:<36} {:>11} {:>11} {:>15}",
        "call", "spline", "scipy", "scipy / spline"
    );
    for row in rows {
        let name = row.get("name").and_then(Value::as_str).unwrap_or("?");
        let time = |key: &str| {
            row.get(key)
                .and_then(Value::as_f64)
                .ok_or_else(|| format!("scipy_rows.py row {name} lacks {key}"))
        };
        let (ours, scipy) = (time("spline_s")?, time("scipy_s")?);
        println!(
            "{name:<36} {:>11} {:>11} {:>14.1}×",
            seconds(ours),
            seconds(scipy),
            scipy / ours
        );
    }
    Ok(())
}
