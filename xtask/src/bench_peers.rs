//! `cargo xtask bench peers [--readme]`: ours against curvo 0.3 and truck-geometry 0.5
//! (bench-only dev-dependencies of spline-geom) and scipy, in one run.
//!
//! 1. Times scipy's `BSpline.__call__` with `xtask/bench/eval_scipy.py` (the venv of
//!    `bench eval`; the same cubic, 10⁶ parameters, random order and sorted), and scipy's
//!    fitting with `xtask/bench/fit_scipy.py` (the workloads of `bench fit`).
//! 2. Runs `cargo bench -p spline-geom --features parallel --bench peers`: every workload
//!    with every library in one binary, one criterion group per workload, after the
//!    benchmark has checked that the libraries' results agree (`peers-check` lines, at most
//!    1e-12 apart, or it stops before timing); then spline-fit's `peers_fit` (interpolation
//!    against curvo, checked the same way) and `fit` (the scipy workloads, with residuals);
//!    then `xtask/bench/downstream` (a crate outside the workspace, thin LTO, built in
//!    `target/downstream`): one-point surface evaluation timed from a user's crate.
//! 3. Prints the table of medians (per point where the workload is a batch of points), the
//!    ratio best peer / ours and whether the target holds, the limits on this CPU
//!    (the batch's arithmetic alone, memory traffic alone) and the `parallel` rows with the
//!    CPU time of all threads (`peers-cpu` lines); with `--readme`, writes the same table
//!    between the `bench-peers` markers of `README.md`.
//!
//! Wall-clock medians on a shared machine grow with its load; the ratios, measured in one
//! binary minutes apart, much less. Rerun to see the spread.

use crate::bench::{self, seconds};
use crate::bench_fit::{self, FitRow};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

const START: &str = "<!-- bench-peers:start -->";
const END: &str = "<!-- bench-peers:end -->";

/// One line of the table: criterion ids (`group/function`) and the count a median is
/// divided by (points per iteration; 1 for whole operations).
struct Row {
    label: &'static str,
    per: f64,
    ours: &'static str,
    curvo: &'static [&'static str],
    truck: &'static [&'static str],
    target: Option<f64>,
}

const ROWS: &[Row] = &[
    Row {
        label: "cubic, 100 cp, 10⁶ random params, one call per point (`BSpline::evaluator`)",
        per: 1e6,
        ours: "peers_eval_point/ours_evaluator",
        curvo: &["peers_eval_point/curvo", "peers_eval_point/curvo_evaluator"],
        truck: &["peers_eval_point/truck"],
        target: Some(3.0),
    },
    Row {
        label: "same, `BSpline::eval` (the triangular scheme's values, bit for bit)",
        per: 1e6,
        ours: "peers_eval_point/ours",
        curvo: &["peers_eval_point/curvo", "peers_eval_point/curvo_evaluator"],
        truck: &["peers_eval_point/truck"],
        target: Some(3.0),
    },
    Row {
        label: "same, batch (curvo: its evaluator, one call per point)",
        per: 1e6,
        ours: "peers_eval_batch/ours",
        curvo: &["peers_eval_point/curvo_evaluator"],
        truck: &[],
        target: Some(5.0),
    },
    Row {
        label: "same, sorted batch",
        per: 1e6,
        ours: "peers_eval_batch/ours_sorted",
        curvo: &["peers_eval_batch/curvo_evaluator_sorted"],
        truck: &[],
        target: None,
    },
    Row {
        label: "C′ and C″, 10⁵ random params (`derivatives_into`)",
        per: 1e5,
        ours: "peers_derivs/ours",
        curvo: &["peers_derivs/curvo"],
        truck: &["peers_derivs/truck"],
        target: Some(4.0),
    },
    Row {
        label: "same, through the evaluator",
        per: 1e5,
        ours: "peers_derivs/ours_evaluator",
        curvo: &["peers_derivs/curvo"],
        truck: &["peers_derivs/truck"],
        target: Some(4.0),
    },
    Row {
        label: "insert 1,000 knots one at a time",
        per: 1.0,
        ours: "peers_insert/ours",
        curvo: &["peers_insert/curvo"],
        truck: &["peers_insert/truck"],
        target: Some(1.5),
    },
    Row {
        label: "refine with 1,000 knots",
        per: 1.0,
        ours: "peers_refine/ours",
        curvo: &["peers_refine/curvo"],
        truck: &[],
        target: Some(1.5),
    },
    Row {
        label: "elevate +1 (curvo panics)",
        per: 1.0,
        ours: "peers_elevate1/ours",
        curvo: &[],
        truck: &["peers_elevate1/truck"],
        target: Some(10.0),
    },
    Row {
        label: "elevate +3 (curvo panics)",
        per: 1.0,
        ours: "peers_elevate3/ours",
        curvo: &[],
        truck: &["peers_elevate3/truck"],
        target: Some(10.0),
    },
    Row {
        label: "bicubic 50×50, 500² random points, one call per point",
        per: 250_000.0,
        ours: "peers_surface_point/ours",
        curvo: &["peers_surface_point/curvo_evaluator"],
        truck: &["peers_surface_point/truck"],
        target: Some(2.0),
    },
    Row {
        label: "same, through `Surface::evaluator` (per-patch Taylor form, built once)",
        per: 250_000.0,
        ours: "peers_surface_point/ours_evaluator",
        curvo: &["peers_surface_point/curvo_evaluator"],
        truck: &["peers_surface_point/truck"],
        target: Some(2.0),
    },
    Row {
        label: "same, 500² grid call",
        per: 250_000.0,
        ours: "peers_surface_grid/ours",
        curvo: &["peers_surface_grid/curvo"],
        truck: &[],
        target: Some(5.0),
    },
    Row {
        label: "S_u and S_v, 10⁵ random points",
        per: 1e5,
        ours: "peers_surface_derivs/ours",
        curvo: &["peers_surface_derivs/curvo_evaluator"],
        truck: &["peers_surface_derivs/truck"],
        target: None,
    },
    Row {
        label: "same, through `Surface::evaluator`",
        per: 1e5,
        ours: "peers_surface_derivs/ours_evaluator",
        curvo: &["peers_surface_derivs/curvo_evaluator"],
        truck: &["peers_surface_derivs/truck"],
        target: None,
    },
    Row {
        label: "NURBS circle, 10⁶ params, one call per point (`eval`)",
        per: 1e6,
        ours: "peers_nurbs/ours",
        curvo: &["peers_nurbs/curvo", "peers_nurbs/curvo_evaluator"],
        truck: &["peers_nurbs/truck"],
        target: Some(3.0),
    },
    Row {
        label: "same, through the evaluator",
        per: 1e6,
        ours: "peers_nurbs/ours_evaluator",
        curvo: &["peers_nurbs/curvo", "peers_nurbs/curvo_evaluator"],
        truck: &["peers_nurbs/truck"],
        target: Some(3.0),
    },
    Row {
        label: "same, batch (`eval_many_into`)",
        per: 1e6,
        ours: "peers_nurbs/ours_batch",
        curvo: &["peers_nurbs/curvo", "peers_nurbs/curvo_evaluator"],
        truck: &["peers_nurbs/truck"],
        target: Some(3.0),
    },
    Row {
        label: "NURBS sphere, 10⁵ random points",
        per: 1e5,
        ours: "peers_nurbs_surface/ours",
        curvo: &["peers_nurbs_surface/curvo_evaluator"],
        truck: &["peers_nurbs_surface/truck"],
        target: None,
    },
    Row {
        label: "same, through `NurbsSurface::evaluator`",
        per: 1e5,
        ours: "peers_nurbs_surface/ours_evaluator",
        curvo: &["peers_nurbs_surface/curvo_evaluator"],
        truck: &["peers_nurbs_surface/truck"],
        target: None,
    },
];

/// Rows timed from `xtask/bench/downstream`, a crate outside the workspace that depends on
/// the library as a user's crate does (thin LTO; built in `target/downstream`).
const DOWNSTREAM_ROWS: &[Row] = &[
    Row {
        label: "from a separate crate (thin LTO): bicubic 50×50, 1000² random points, `Surface::eval`",
        per: 1e6,
        ours: "downstream_surface_point/ours",
        curvo: &["downstream_surface_point/curvo_evaluator"],
        truck: &[],
        target: Some(2.0),
    },
    Row {
        label: "same, from a separate crate, through `Surface::evaluator`",
        per: 1e6,
        ours: "downstream_surface_point/ours_evaluator",
        curvo: &["downstream_surface_point/curvo_evaluator"],
        truck: &[],
        target: Some(2.0),
    },
];

/// The manifest of the downstream crate, relative to the repository.
const DOWNSTREAM: &str = "xtask/bench/downstream/Cargo.toml";

/// The fastest of the given benchmarks, per unit.
fn best(target: &Path, ids: &[&str], per: f64) -> Result<Option<f64>, String> {
    let mut found: Option<f64> = None;
    for id in ids {
        let t = bench::criterion_median(target, id)? / per;
        found = Some(found.map_or(t, |f| f.min(t)));
    }
    Ok(found)
}

fn cell(t: Option<f64>) -> String {
    t.map_or_else(|| "—".to_string(), seconds)
}

fn verdict(ratio: f64, target: Option<f64>, missed: &mut Vec<String>, what: &str) -> String {
    match target {
        Some(goal) if ratio >= goal => format!("≥ {goal}×: met"),
        Some(goal) => {
            missed.push(format!("{what} ({ratio:.2}× < {goal}×)"));
            format!("≥ {goal}×: **missed**")
        }
        None => "—".to_string(),
    }
}

/// Runs everything and prints (and with `--readme` writes) the table.
///
/// # Errors
/// A message when Python, scipy, `cargo bench` or reading the results fail, or for an
/// unknown argument.
pub(crate) fn run(repo_root: &Path, args: &[String]) -> Result<(), String> {
    let readme = match args {
        [] => false,
        [flag] if flag == "--readme" => true,
        _ => return Err("usage: cargo xtask bench peers [--readme]".into()),
    };
    let target = bench::target_dir(repo_root);
    let python = bench::ensure_venv(&target)?;
    eprintln!("bench peers: timing scipy…");
    let scipy = bench::run_python_json(&python, &repo_root.join("xtask/bench/eval_scipy.py"))?;
    eprintln!("bench peers: timing scipy's fitting…");
    let scipy_fit = bench::run_python_json(&python, &repo_root.join("xtask/bench/fit_scipy.py"))?;
    eprintln!("bench peers: running cargo bench -p spline-geom --bench peers…");
    let mut lines = bench::run_criterion_args(
        repo_root,
        &[
            "-p",
            "spline-geom",
            "--features",
            "parallel",
            "--bench",
            "peers",
        ],
        &["peers-check", "peers-cpu"],
    )?;
    eprintln!("bench peers: running cargo bench -p spline-fit --bench peers_fit and --bench fit…");
    lines.extend(bench::run_criterion(
        repo_root,
        "peers_fit",
        &["peers-check"],
    )?);
    let residuals = bench::run_criterion(repo_root, "fit", &["fit-residual"])?;
    eprintln!("bench peers: running the downstream crate ({DOWNSTREAM}, thin LTO)…");
    lines.extend(bench::run_criterion_in(
        repo_root,
        &["--manifest-path", DOWNSTREAM, "--bench", "downstream"],
        &["peers-check"],
        Some(&target.join("downstream")),
    )?);
    let fits = bench_fit::fit_rows(&scipy_fit, &bench_fit::rust_medians(&target)?, &residuals)?;
    let table = table(&target, &scipy, &fits, &lines)?;
    println!();
    print!("{table}");
    if readme {
        write_readme(repo_root, &table)?;
        println!("README.md: table rewritten");
    }
    Ok(())
}

fn table(
    target: &Path,
    scipy: &Value,
    fits: &[FitRow],
    checks: &BTreeMap<String, f64>,
) -> Result<String, String> {
    let mut missed = Vec::new();
    let mut out = String::from(
        "| workload | ours | curvo | truck | best peer / ours | target |\n|---|---|---|---|---|---|\n",
    );
    let downstream = target.join("downstream");
    let rows = ROWS.iter().map(|row| (row, target)).chain(
        DOWNSTREAM_ROWS
            .iter()
            .map(|row| (row, downstream.as_path())),
    );
    for (row, target) in rows {
        let ours = bench::criterion_median(target, row.ours)? / row.per;
        let curvo = best(target, row.curvo, row.per)?;
        let truck = best(target, row.truck, row.per)?;
        let peer = [curvo, truck]
            .into_iter()
            .flatten()
            .fold(f64::INFINITY, f64::min);
        let ratio = peer / ours;
        out.push_str(&format!(
            "| {} | {} | {} | {} | {ratio:.2}× | {} |\n",
            row.label,
            seconds(ours),
            cell(curvo),
            cell(truck),
            verdict(ratio, row.target, &mut missed, row.label)
        ));
    }
    let version = scipy_version(scipy);
    let scipy_at = |id: &str| -> Result<f64, String> {
        scipy
            .pointer(&format!("/results/{id}/median_s"))
            .and_then(Value::as_f64)
            .map(|s| s / 1e6)
            .ok_or_else(|| format!("scipy output lacks {id}"))
    };
    for (label, ours_id, scipy_id, goal) in [
        (
            "scipy: one call per point (evaluator) vs `__call__`, random",
            "peers_eval_point/ours_evaluator",
            "random_order",
            Some(5.0),
        ),
        (
            "scipy: one call per point (`eval`) vs `__call__`, random",
            "peers_eval_point/ours",
            "random_order",
            None,
        ),
        (
            "scipy: batch vs `__call__`, random",
            "peers_eval_batch/ours",
            "random_order",
            Some(8.0),
        ),
        (
            "scipy: batch vs `__call__`, sorted",
            "peers_eval_batch/ours_sorted",
            "sorted",
            None,
        ),
    ] {
        let ours = bench::criterion_median(target, ours_id)? / 1e6;
        let theirs = scipy_at(scipy_id)?;
        out.push_str(&format!(
            "| {label} (scipy {version}: {}) | {} | | | {:.2}× | {} |\n",
            seconds(theirs),
            seconds(ours),
            theirs / ours,
            verdict(theirs / ours, goal, &mut missed, label)
        ));
    }
    for points in [100, 1000] {
        let ours = bench::criterion_median(target, &format!("peers_interp_{points}/ours"))?;
        let curvo = bench::criterion_median(target, &format!("peers_interp_{points}/curvo"))?;
        out.push_str(&format!(
            "| interpolation, cubic through {points} planar points (chord length, averaged knots) | {} | {} | — | {:.2}× | — |\n",
            seconds(ours),
            seconds(curvo),
            curvo / ours
        ));
    }
    let fit_version = scipy_version(scipy);
    for row in fits.iter().filter(|row| row.target > 0.0) {
        let label = format!(
            "scipy fitting: {} (scipy {fit_version}: {}; residual {:.3e} vs scipy's {:.3e})",
            row.label,
            seconds(row.scipy),
            row.rust_residual,
            row.scipy_residual
        );
        let verdict = if row.met() {
            format!("≥ {}× and residual as small: met", row.target)
        } else {
            missed.push(format!(
                "{} ({:.2}× vs {}×)",
                row.label,
                row.ratio(),
                row.target
            ));
            format!("≥ {}× and residual as small: **missed**", row.target)
        };
        out.push_str(&format!(
            "| {label} | {} | | | {:.2}× | {verdict} |\n",
            seconds(row.rust),
            row.ratio()
        ));
    }
    let median = |id: &str| bench::criterion_median(target, id).map(|t| t / 1e6);
    let batch = median("peers_eval_batch/ours")?;
    let arithmetic = median("peers_eval_batch/limit_arithmetic")?;
    let memory = median("peers_eval_batch/limit_memory")?;
    out.push_str(&format!(
        "| limit on this CPU for the batch: Horner only (span and coefficients known) / \
         parameters in, points out only | {} / {} | | | batch at {:.1}× / {:.1}× these | — |\n",
        seconds(arithmetic),
        seconds(memory),
        batch / arithmetic,
        batch / memory
    ));
    for (label, id) in [("batch of 10⁶", "batch"), ("500² grid", "grid")] {
        let run = |threads: usize| {
            bench::criterion_median(target, &format!("peers_parallel/{id}_{threads}"))
        };
        let (sequential, one, two) = (run(0)?, run(1)?, run(2)?);
        let cpu = |threads: usize| {
            checks
                .get(&format!("peers-cpu parallel/{id}_{threads}/cpu"))
                .copied()
        };
        let cpu = match (cpu(0), cpu(1), cpu(2)) {
            (Some(a), Some(b), Some(c)) => format!(
                " (CPU time of all threads {} / {} / {})",
                seconds(a),
                seconds(b),
                seconds(c)
            ),
            _ => String::new(),
        };
        out.push_str(&format!(
            "| `parallel`, {label}: sequential / 1 / 2 threads | {} / {} / {}{cpu} | | | \
             {:.2}× speed-up at 2 threads, 1 thread at {:.2}× sequential | — |\n",
            seconds(sequential),
            seconds(one),
            seconds(two),
            one / two,
            sequential / one
        ));
    }
    let agreement: Vec<f64> = checks
        .iter()
        .filter(|(key, _)| key.starts_with("peers-check "))
        .map(|(_, &v)| v)
        .collect();
    let worst = agreement.iter().copied().fold(0.0, f64::max);
    out.push_str(&format!(
        "\nLargest difference between the libraries' results before timing: {worst:.1e} ({} checks).\n",
        agreement.len()
    ));
    if missed.is_empty() {
        out.push_str("Every target met in this run.\n");
    } else {
        out.push_str(&format!("Missed in this run: {}.\n", missed.join("; ")));
    }
    Ok(out)
}

fn scipy_version(scipy: &Value) -> &str {
    scipy.get("scipy").and_then(Value::as_str).unwrap_or("?")
}

fn write_readme(repo_root: &Path, table: &str) -> Result<(), String> {
    let path = repo_root.join("README.md");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("README.md: {e}"))?;
    let (Some(start), Some(end)) = (text.find(START), text.find(END)) else {
        return Err(format!("README.md lacks the {START} … {END} markers"));
    };
    let new = format!("{}{START}\n{table}{}", &text[..start], &text[end..]);
    std::fs::write(&path, new).map_err(|e| format!("README.md: {e}"))
}
