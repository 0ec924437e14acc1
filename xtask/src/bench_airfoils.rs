//! `cargo xtask bench airfoils`: the whole UIUC airfoil database smoothed by the release
//! `spline smooth` (20 control points, one curvature maximum), with the distribution of
//! deviations and times.
//!
//! The database comes from the `aerosandbox` wheel on the Python package index (MIT; it holds
//! the UIUC coordinate files under `aerosandbox/geometry/airfoil/airfoil_database/`): the
//! wheel is downloaded once with `pip download` into `target/airfoils/` and unpacked with
//! Python's `zipfile` (no network after the first run).

use crate::bench::target_dir;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// The version of the wheel that holds the database.
const WHEEL: &str = "aerosandbox==4.2.10";

fn run(command: &mut Command, what: &str) -> Result<(), String> {
    let status = command
        .status()
        .map_err(|e| format!("cannot run {what}: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("{what} failed ({status})"))
    }
}

/// The directory of `.dat` files, fetched and unpacked on first use.
pub(crate) fn database(target: &Path) -> Result<PathBuf, String> {
    let root = target.join("airfoils");
    let dir = root.join("uiuc");
    let count = std::fs::read_dir(&dir).map_or(0, Iterator::count);
    if count > 1000 {
        return Ok(dir);
    }
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let python = if cfg!(windows) { "python" } else { "python3" };
    eprintln!(
        "bench airfoils: downloading the {WHEEL} wheel (the UIUC database) into {}",
        root.display()
    );
    run(
        Command::new(python)
            .args(["-m", "pip", "download", "--no-deps", "--quiet", "-d"])
            .arg(&root)
            .arg(WHEEL),
        "pip download",
    )?;
    let script = r#"
import glob, os, sys, zipfile
root, out = sys.argv[1], sys.argv[2]
wheel = sorted(glob.glob(os.path.join(root, "aerosandbox-*.whl")))[-1]
prefix = "aerosandbox/geometry/airfoil/airfoil_database/"
with zipfile.ZipFile(wheel) as z:
    for name in z.namelist():
        if name.startswith(prefix) and name.endswith(".dat"):
            with open(os.path.join(out, os.path.basename(name)), "wb") as f:
                f.write(z.read(name))
"#;
    run(
        Command::new(python)
            .arg("-c")
            .arg(script)
            .arg(&root)
            .arg(&dir),
        "unpacking the wheel",
    )?;
    Ok(dir)
}

fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let i = ((sorted.len() - 1) as f64 * q).round() as usize;
    sorted[i]
}

/// Runs the benchmark and prints the distribution.
pub(crate) fn run_bench(repo: &Path, args: &[String]) -> Result<(), String> {
    let target = target_dir(repo);
    let dir = database(&target)?;
    let jobs = args
        .windows(2)
        .find(|w| w[0] == "--jobs")
        .map_or_else(|| "2".to_owned(), |w| w[1].clone());
    eprintln!("bench airfoils: building the release tool");
    run(
        Command::new(env!("CARGO"))
            .args(["build", "--release", "--quiet", "-p", "spline-cli"])
            .current_dir(repo),
        "cargo build --release",
    )?;
    let tool = target.join("release").join("spline");
    let out = target.join("airfoils").join("out");
    let _ = std::fs::remove_dir_all(&out);
    let started = Instant::now();
    // Exit status 2 means some inputs failed: the summary says which.
    let status = Command::new(&tool)
        .arg("smooth")
        .arg(&dir)
        .args(["--control-points", "20", "--jobs", &jobs, "--out"])
        .arg(&out)
        .status()
        .map_err(|e| format!("cannot run {}: {e}", tool.display()))?;
    let wall = started.elapsed().as_secs_f64();
    let summary = std::fs::read_to_string(out.join("summary.jsonl"))
        .map_err(|e| format!("no summary ({status}): {e}"))?;
    let rows: Vec<Value> = summary
        .lines()
        .filter_map(|l| serde_json::from_str(l).ok())
        .collect();
    let ok: Vec<&Value> = rows.iter().filter(|r| r["error"].is_null()).collect();
    let mut to_curve: Vec<f64> = ok
        .iter()
        .filter_map(|r| r["max_deviation"].as_f64())
        .map(|d| d * 1e3)
        .collect();
    let mut to_data: Vec<f64> = ok
        .iter()
        .filter_map(|r| r["max_deviation_to_data"].as_f64())
        .map(|d| d * 1e3)
        .collect();
    let mut seconds: Vec<f64> = rows.iter().filter_map(|r| r["seconds"].as_f64()).collect();
    for v in [&mut to_curve, &mut to_data, &mut seconds] {
        v.sort_by(f64::total_cmp);
    }
    println!("## UIUC database: 20 control points, one curvature maximum ({jobs} jobs)\n");
    println!(
        "smoothed {} of {} airfoils ({:.1} %) in {wall:.0} s wall ({:.3} s per airfoil)",
        ok.len(),
        rows.len(),
        100.0 * ok.len() as f64 / rows.len().max(1) as f64,
        wall / rows.len().max(1) as f64
    );
    println!("\n| mm (chord 1 m) | median | p90 | p99 | max |");
    println!("|---|---|---|---|---|");
    for (what, v) in [
        ("data → curve", &to_curve),
        ("curve → data polyline", &to_data),
    ] {
        println!(
            "| {what} | {:.2} | {:.2} | {:.2} | {:.2} |",
            quantile(v, 0.5),
            quantile(v, 0.9),
            quantile(v, 0.99),
            quantile(v, 1.0)
        );
    }
    println!(
        "| seconds per airfoil (one job) | {:.3} | {:.3} | {:.3} | {:.3} |",
        quantile(&seconds, 0.5),
        quantile(&seconds, 0.9),
        quantile(&seconds, 0.99),
        quantile(&seconds, 1.0)
    );
    let failures: Vec<String> = rows
        .iter()
        .filter(|r| !r["error"].is_null())
        .map(|r| {
            format!(
                "{}: {}",
                r["name"].as_str().unwrap_or("?"),
                r["error"].as_str().unwrap_or("?")
            )
        })
        .collect();
    if !failures.is_empty() {
        println!("\nnot smoothed ({}):", failures.len());
        for f in &failures {
            println!("- {f}");
        }
    }
    println!("\nper-airfoil results: {}", out.display());
    Ok(())
}
