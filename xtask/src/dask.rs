//! `cargo xtask dask [--all | --limit N] [--workers W]`: the UIUC database smoothed with
//! Dask through the Python package (`python/examples/dask_smooth.py`: a `dask.bag` over the
//! files on a `LocalCluster` of `W` = 2 workers) and by the tool's batch mode
//! (`spline smooth DIR --out`), 20 control points and one curvature maximum; the two
//! `summary.jsonl` must agree file by file.
//!
//! By default the first 200 files (in name order) are smoothed, a couple of minutes on two
//! cores; `--all` smooths the whole database (about 2,200 files).

use crate::bench::target_dir;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// Files smoothed without `--all`.
const DEFAULT_LIMIT: usize = 200;
/// Relative difference allowed between the two deviations of a file (the same library code
/// compiled twice: they agree to the last digits).
const TOLERANCE: f64 = 1e-9;

/// The value following `flag`, if any.
fn option<'a>(args: &'a [String], flag: &str) -> Option<&'a str> {
    args.windows(2)
        .find(|w| w[0] == flag)
        .map(|w| w[1].as_str())
}

/// The first `limit` `.dat` files of `dir` copied into `<target>/dask/subset`.
fn subset(dir: &Path, out: &Path, limit: usize) -> Result<PathBuf, String> {
    let subset = out.join("subset");
    let _ = std::fs::remove_dir_all(&subset);
    std::fs::create_dir_all(&subset).map_err(|e| format!("{}: {e}", subset.display()))?;
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dat")))
        .collect();
    files.sort();
    for file in files.iter().take(limit) {
        let name = file.file_name().ok_or("a file without a name")?;
        std::fs::copy(file, subset.join(name)).map_err(|e| format!("{}: {e}", file.display()))?;
    }
    Ok(subset)
}

/// The lines of a `summary.jsonl` by name.
fn summary(path: &Path) -> Result<BTreeMap<String, Value>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    text.lines()
        .map(|line| {
            let v: Value =
                serde_json::from_str(line).map_err(|e| format!("{}: {e}", path.display()))?;
            let name = v["name"]
                .as_str()
                .ok_or("a line without a name")?
                .to_owned();
            Ok((name, v))
        })
        .collect()
}

/// Compares the summaries; returns the largest relative difference of the deviations.
fn compare(batch: &BTreeMap<String, Value>, dask: &BTreeMap<String, Value>) -> Result<f64, String> {
    if batch.len() != dask.len() || batch.keys().ne(dask.keys()) {
        return Err(format!(
            "the summaries list different files ({} in the batch, {} with Dask)",
            batch.len(),
            dask.len()
        ));
    }
    let mut worst = 0.0_f64;
    for (name, a) in batch {
        let b = &dask[name];
        if a["error"].is_null() != b["error"].is_null() {
            return Err(format!(
                "{name}: batch error {} vs Dask error {}",
                a["error"], b["error"]
            ));
        }
        if !a["error"].is_null() {
            continue;
        }
        for key in ["control_points", "extrema"] {
            if a[key] != b[key] {
                return Err(format!(
                    "{name}: {key} {} (batch) vs {} (Dask)",
                    a[key], b[key]
                ));
            }
        }
        for key in ["max_deviation", "max_deviation_to_data"] {
            let (x, y) = (a[key].as_f64(), b[key].as_f64());
            let (Some(x), Some(y)) = (x, y) else {
                return Err(format!("{name}: {key} missing"));
            };
            let relative = (x - y).abs() / x.abs().max(1e-300);
            worst = worst.max(relative);
            if relative > TOLERANCE {
                return Err(format!("{name}: {key} {x} (batch) vs {y} (Dask)"));
            }
        }
    }
    Ok(worst)
}

/// Runs both and compares; see the module documentation.
pub(crate) fn run(root: &Path, args: &[String]) -> Result<(), String> {
    let target = target_dir(root);
    let workers = option(args, "--workers").unwrap_or("2").to_owned();
    let limit = match option(args, "--limit") {
        Some(n) => n
            .parse()
            .map_err(|_| format!("--limit: not a count: {n}"))?,
        None if args.iter().any(|a| a == "--all") => usize::MAX,
        None => DEFAULT_LIMIT,
    };
    let database = crate::bench_airfoils::database(&target)?;
    let out = target.join("dask");
    let dir = subset(&database, &out, limit)?;
    let python = crate::test_python::prepare(root, crate::test_python::Build::Release)?;
    eprintln!("dask: building the release tool");
    let status = Command::new(env!("CARGO"))
        .args(["build", "--release", "--quiet", "-p", "spline-cli"])
        .current_dir(root)
        .status()
        .map_err(|e| format!("cannot run cargo build: {e}"))?;
    if !status.success() {
        return Err(format!(
            "cargo build --release -p spline-cli failed ({status})"
        ));
    }
    let batch_dir = out.join("batch");
    let _ = std::fs::remove_dir_all(&batch_dir);
    eprintln!(
        "dask: spline smooth {} --out {}",
        dir.display(),
        batch_dir.display()
    );
    let started = Instant::now();
    // Exit status 2 means some files failed: the summary says which, and Dask must agree.
    Command::new(target.join("release").join("spline"))
        .arg("smooth")
        .arg(&dir)
        .args(["--control-points", "20", "--jobs", &workers, "--out"])
        .arg(&batch_dir)
        .status()
        .map_err(|e| format!("cannot run the tool: {e}"))?;
    let batch_wall = started.elapsed().as_secs_f64();
    let dask_summary = out.join("dask_summary.jsonl");
    eprintln!("dask: python/examples/dask_smooth.py on {workers} workers");
    let started = Instant::now();
    let status = Command::new(&python)
        .arg(root.join("python/examples/dask_smooth.py"))
        .arg(&dir)
        .arg("--out")
        .arg(&dask_summary)
        .args(["--workers", &workers, "--control-points", "20"])
        .status()
        .map_err(|e| format!("cannot run the Dask example: {e}"))?;
    if !status.success() {
        return Err(format!("the Dask example failed ({status})"));
    }
    let dask_wall = started.elapsed().as_secs_f64();
    let batch = summary(&batch_dir.join("summary.jsonl"))?;
    let dask = summary(&dask_summary)?;
    let worst = compare(&batch, &dask)?;
    let failed = batch.values().filter(|v| !v["error"].is_null()).count();
    println!(
        "dask: {} files ({} smoothed, {failed} failed in both), the same in both summaries: \
         largest relative difference of a deviation {worst:.1e}; batch {batch_wall:.1} s, \
         Dask on {workers} workers {dask_wall:.1} s",
        batch.len(),
        batch.len() - failed
    );
    Ok(())
}
