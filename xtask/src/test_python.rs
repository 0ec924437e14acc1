//! The Python package's suite (`python/tests`, pytest), a step of `cargo xtask test`.
//!
//! A virtual environment `target/python-venv` gets numpy, scipy, pytest, maturin and
//! dask (first run only); the package is built as an abi3 wheel by maturin in the workspace's
//! target directory and installed into it, then pytest runs the suite — including
//! `tests/test_scipy_suite.py`, scipy's own `test_bsplines.py` run against the package, which
//! fails when its passes fall below the bar stored there.

use crate::bench::{ensure_venv_with, target_dir};
use std::path::{Path, PathBuf};
use std::process::Command;

/// What the suite, the benchmark and the Dask example need.
const PACKAGES: &[&str] = &[
    "numpy",
    "scipy",
    "pytest",
    "maturin>=1.9,<2",
    "dask[bag]",
    "distributed",
];

/// Runs a command and fails with `what` if it fails.
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

/// How the wheel is compiled.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Build {
    /// The release profile: what the benchmarks and the Dask example time.
    Release,
    /// The dev profile (`opt-level` 1, dependencies 2), whose compiled crates are those
    /// `cargo test --workspace` built just before in the same run: the test suite then
    /// compiles only the binding itself, not a second, optimised copy of the whole library
    /// (the largest single cost of a cold `cargo xtask test`).
    Test,
}

/// The virtual environment with the package built from this tree installed: its Python.
pub(crate) fn prepare(root: &Path, build: Build) -> Result<PathBuf, String> {
    let target = target_dir(root);
    let python = ensure_venv_with(
        &target,
        "python-venv",
        "import numpy, scipy, pytest, maturin, dask.bag, distributed",
        PACKAGES,
    )?;
    let wheels = target.join("wheels");
    let _ = std::fs::remove_dir_all(&wheels);
    let profile = if build == Build::Release {
        "--release"
    } else {
        "--profile=dev"
    };
    eprintln!("python: building the wheel (maturin, {profile})");
    run(
        Command::new(&python)
            .args([
                "-m",
                "maturin",
                "build",
                profile,
                "--quiet",
                "--interpreter",
            ])
            .arg(&python)
            .arg("--out")
            .arg(&wheels)
            .current_dir(root.join("python")),
        "maturin build",
    )?;
    let wheel = std::fs::read_dir(&wheels)
        .map_err(|e| format!("cannot read {}: {e}", wheels.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .find(|p| p.extension().is_some_and(|x| x == "whl"))
        .ok_or_else(|| format!("maturin left no wheel in {}", wheels.display()))?;
    run(
        Command::new(&python)
            .args([
                "-m",
                "pip",
                "install",
                "--quiet",
                "--force-reinstall",
                "--no-deps",
                "--no-cache-dir",
            ])
            .arg(&wheel),
        "pip install (the wheel)",
    )?;
    Ok(python)
}

/// Builds and installs the package, then runs pytest on `python/tests`.
pub(crate) fn run_suite(root: &Path) -> Result<(), String> {
    let python = prepare(root, Build::Test)?;
    run(
        Command::new(&python)
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider", "tests"])
            .env("PYTHONDONTWRITEBYTECODE", "1")
            .current_dir(root.join("python")),
        "pytest python/tests",
    )
}
