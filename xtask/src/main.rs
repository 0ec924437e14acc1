//! Project automation: `cargo xtask <task>`.
//!
//! - `ci`: exactly what CI runs (`.ci/run`): format check, clippy with warnings denied,
//!   documentation with warnings denied, tests.
//! - `test`: the whole test suite (the README's test command; see `test_all`); `test python`:
//!   only the Python package's suite.
//! - `help` (`--help`, `-h`): the list of tasks.
//! - `docs`: regenerate the SVG pictures in `docs/` (and `docs/studio.png`, a screenshot of
//!   `spline studio` taken by its browser test).
//! - `bench airfoils [--jobs J]`: the whole UIUC database (fetched once from the
//!   `aerosandbox` wheel into `target/airfoils/`) smoothed by the release tool, 20 control
//!   points and one curvature maximum: the distribution of deviations and times.
//! - `bench fit`, `bench eval`, `bench smoothing`: criterion benchmarks of fitting, of curve
//!   evaluation and of smoothing splines against scipy in the same run (a Python virtual
//!   environment with scipy is created under `target/`).
//! - `bench python`: 10⁶-point evaluation through the Python package against the Rust batch
//!   and scipy's `BSpline.__call__`, in the same run.
//! - `dask [--all | --limit N] [--workers W]`: the UIUC database smoothed with Dask through
//!   the Python package (`python/examples/dask_smooth.py`), compared with the tool's batch
//!   summary.
//! - `bench peers [--readme]`: ours against curvo and truck-geometry in one criterion
//!   binary (evaluation, derivatives, insertion, refinement, elevation, surfaces, NURBS,
//!   the `parallel` feature at 1 and 2 threads) and scipy's evaluation in the same run;
//!   `--readme` rewrites the performance table of the README.
//! - `bench surfaces`: criterion benchmarks of closest points on surfaces against
//!   truck-geometry and of scattered least squares against scipy, in the same run.
//! - `fuzz [--cases N | --seconds S] [--seed S] [--target T] [--coverage]`: structured mutation
//!   fuzzing of the readers and of every operation, in process; with `--coverage`, the same
//!   oracles under libFuzzer on nightly (see `fuzz/README.md`).
//! - `campaign [--cases N] [--seed S] [--jobs J] [--timeout S] [--memory-mb M]`: a mutation
//!   campaign of the release binary over every subcommand (subprocesses, memory limit,
//!   timeout), printing a table of panics, aborts, slow runs, non-finite outputs and
//!   multi-line errors.
//! - `reproduce`: the seeds' published numbers next to ours (thesis Table 6.1 and §5.1, seed
//!   000 Tables 1 and 2).
//! - `demo`: the main job — fit an airfoil shipped in `data/airfoils/`, print the result and
//!   write `docs/airfoil.svg`.

mod bench;
mod bench_airfoils;
mod bench_eval;
mod bench_fit;
mod bench_peers;
mod bench_python;
mod bench_smoothing;
mod bench_surfaces;
mod campaign;
mod dask;
mod demo;
mod docs_constructions;
mod docs_curve_tools;
mod docs_curves;
mod docs_output;
mod docs_ridges;
mod docs_shape_functions;
mod docs_studio;
mod docs_surface_features;
mod docs_surfaces;
mod fuzz;
mod fuzz_coverage;
mod fuzz_oracles;
mod mutate;
mod reproduce;
mod test_all;
mod test_browser;
mod test_occt;
mod test_python;

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the repository")
        .to_path_buf()
}

fn run_ci(root: &Path) -> Result<(), String> {
    let status = Command::new("bash")
        .arg(root.join(".ci/run"))
        .current_dir(root)
        .status()
        .map_err(|e| format!("cannot run .ci/run: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!(".ci/run failed ({status})"))
    }
}

fn run_docs(root: &Path) -> Result<(), String> {
    let out = root.join("docs");
    std::fs::create_dir_all(&out).map_err(|e| e.to_string())?;
    docs_curves::render(&out)?;
    docs_curve_tools::render(&out)?;
    docs_surfaces::render(&out)?;
    docs_constructions::render(root, &out)?;
    docs_surface_features::render(&out)?;
    docs_ridges::render(&out)?;
    docs_shape_functions::render(&out)?;
    demo::render(root, &out)?;
    docs_studio::render(root, &out)?;
    println!("pictures written to {}", out.display());
    Ok(())
}

/// The tasks, as `cargo xtask --help` lists them (keep in step with the module docs).
const TASKS: &[(&str, &str)] = &[
    (
        "ci",
        "exactly what CI runs (.ci/run): format check, clippy -D warnings, docs, tests",
    ),
    (
        "test [python | occt]",
        "the whole test suite: cargo test --workspace and the suites that need more than Rust \
         (python: only the Python package's; occt: only the Open CASCADE check of STEP and IGES)",
    ),
    (
        "docs",
        "redraw the SVG pictures in docs/ and the studio's screenshot (docs/studio.png)",
    ),
    (
        "demo",
        "fit and smooth an airfoil from data/airfoils/, print the result, draw it under target/demo/",
    ),
    (
        "reproduce",
        "the seeds' published numbers next to ours (thesis Table 6.1 and §5.1, seed 000 Tables 1–2)",
    ),
    (
        "bench fit",
        "criterion benchmarks of fitting, with scipy in the same run (venv under target/)",
    ),
    (
        "bench eval",
        "criterion benchmarks of curve evaluation, with scipy in the same run",
    ),
    (
        "bench python",
        "10⁶-point evaluation: the Python package vs the Rust batch vs scipy, in the same run",
    ),
    (
        "dask [--all | --limit N] [--workers W]",
        "smooth the UIUC database with Dask via the Python package; compare with the batch summary",
    ),
    (
        "bench surfaces",
        "closest points on surfaces vs truck-geometry, scattered least squares vs scipy",
    ),
    (
        "bench peers [--readme]",
        "evaluation, insertion, elevation, surfaces, NURBS vs curvo and truck (and scipy) in one run; --readme rewrites the README table",
    ),
    (
        "bench smoothing",
        "criterion benchmarks of smoothing splines at 10⁵ data, with scipy in the same run",
    ),
    (
        "bench airfoils [--jobs J]",
        "smooth the whole UIUC database (fetched once into target/airfoils/)",
    ),
    (
        "fuzz [--cases N | --seconds S] [--seed S] [--target T] [--coverage]",
        "structured mutation fuzzing in process; --coverage: libFuzzer on nightly (fuzz/README.md)",
    ),
    (
        "campaign [--cases N] [--seed S] [--jobs J] [--timeout S] [--memory-mb M]",
        "mutation campaign of the release binary over every subcommand",
    ),
    ("help", "this list"),
];

fn help() -> String {
    let mut text = String::from("usage: cargo xtask <task>\n\ntasks:\n");
    for (task, what) in TASKS {
        text.push_str(&format!("  {task}\n      {what}\n"));
    }
    text
}

fn usage() -> String {
    let names: Vec<&str> = TASKS
        .iter()
        .map(|(task, _)| task.split(" [").next().unwrap_or(task))
        .collect();
    format!(
        "usage: cargo xtask <{}> (cargo xtask --help lists what each does)",
        names.join(" | ")
    )
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = repo_root();
    let result = match args.first().map(String::as_str) {
        Some("help" | "--help" | "-h") => {
            print!("{}", help());
            Ok(())
        }
        Some("ci") => run_ci(&root),
        Some("test") if args.get(1).is_some_and(|a| a == "python") => {
            test_python::run_suite(&root)
        }
        Some("test") if args.get(1).is_some_and(|a| a == "occt") => test_occt::run_suite(&root),
        Some("test") => test_all::run(&root),
        Some("docs") => run_docs(&root),
        Some("demo") => demo::run(&root),
        Some("reproduce") => reproduce::run(&root),
        Some("campaign") => campaign::run(&root, &args[1..]),
        Some("fuzz") => fuzz::run(&root, &args[1..]),
        Some("dask") => dask::run(&root, &args[1..]),
        Some("bench") => match args.get(1).map(String::as_str) {
            Some("fit") => bench_fit::run(&root),
            Some("eval") => bench_eval::run(&root),
            Some("surfaces") => bench_surfaces::run(&root),
            Some("smoothing") => bench_smoothing::run(&root),
            Some("python") => bench_python::run(&root),
            Some("airfoils") => bench_airfoils::run_bench(&root, &args[2..]),
            Some("peers") => bench_peers::run(&root, &args[2..]),
            _ => Err(
                "usage: cargo xtask bench fit | eval | peers [--readme] | smoothing | surfaces | python | airfoils [--jobs J]"
                    .into(),
            ),
        },
        _ => Err(usage()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("xtask: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{TASKS, help, usage};

    #[test]
    fn help_lists_every_task() {
        let (help, usage) = (help(), usage());
        for task in [
            "ci",
            "test",
            "docs",
            "demo",
            "reproduce",
            "bench fit",
            "fuzz",
            "campaign",
        ] {
            assert!(help.contains(task) && usage.contains(task), "{task}");
        }
        assert_eq!(help.matches("\n      ").count(), TASKS.len());
    }
}
