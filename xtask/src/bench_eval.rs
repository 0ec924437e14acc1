//! `cargo xtask bench eval`: curve evaluation against scipy's `BSpline.__call__` in the same
//! run — a cubic planar curve with 100 control points at 10⁶ random parameters, in random
//! order and sorted (`benches/curves.rs` and `xtask/bench/eval_scipy.py`).

use crate::bench::{self, seconds};
use serde_json::Value;
use std::path::Path;
use std::process::{Command, Stdio};

const POINTS: f64 = 1e6;
const GROUP: &str = "cubic_100_ctrl_1e6_params";

/// Runs both sides and prints medians per point and the speed-ups.
pub(crate) fn run(repo_root: &Path) -> Result<(), String> {
    let target = bench::target_dir(repo_root);
    let python = bench::ensure_venv(&target)?;
    eprintln!("bench eval: timing scipy…");
    let scipy = bench::run_python_json(&python, &repo_root.join("xtask/bench/eval_scipy.py"))?;
    eprintln!("bench eval: running cargo bench --bench curves…");
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let status = Command::new(cargo)
        .args(["bench", "--bench", "curves"])
        .current_dir(repo_root)
        .stdout(Stdio::inherit())
        .status()
        .map_err(|e| format!("cannot run cargo bench: {e}"))?;
    if !status.success() {
        return Err(format!("cargo bench --bench curves failed ({status})"));
    }
    let field = |id: &str| -> Result<f64, String> {
        scipy
            .pointer(&format!("/results/{id}/median_s"))
            .and_then(Value::as_f64)
            .ok_or_else(|| format!("scipy output lacks {id}"))
    };
    println!();
    println!(
        "curve evaluation vs scipy {} (numpy {}): medians per point, speed-up = scipy / rust",
        scipy.get("scipy").and_then(Value::as_str).unwrap_or("?"),
        scipy.get("numpy").and_then(Value::as_str).unwrap_or("?")
    );
    println!(
        "{:<44} {:>12} {:>12} {:>9}",
        "workload", "scipy", "rust", "speed-up"
    );
    let rows = [
        (
            "one call per point, random order",
            "random_order",
            "one_at_a_time",
        ),
        (
            "batch, random order",
            "random_order",
            "batched_random_order",
        ),
        ("batch, sorted", "sorted", "batched_sorted"),
    ];
    for (label, scipy_id, rust_id) in rows {
        let s = field(scipy_id)? / POINTS;
        let r = bench::criterion_median(&target, &format!("{GROUP}/{rust_id}"))? / POINTS;
        println!(
            "{label:<44} {:>12} {:>12} {:>8.1}×",
            seconds(s),
            seconds(r),
            s / r
        );
    }
    Ok(())
}
