//! The Open CASCADE suite of `cargo xtask test` (`cargo xtask test occt` alone):
//! `tests/occt/check.py` writes random B-spline and NURBS curves and surfaces to STEP and IGES
//! with the tool and reads them with Open CASCADE 8, and the other way round, then whole
//! B-rep solids and malformed files (see `tests/occt/README.md`).
//!
//! Open CASCADE comes from the Python package index (`cadquery-ocp-novtk`, OCCT 8 with
//! Python bindings), installed into the test virtual environment `target/python-venv` on
//! first use; the tool is the debug binary that `cargo test --workspace` builds.

use crate::bench::{ensure_venv_with, target_dir};
use std::path::Path;
use std::process::Command;

/// Builds the tool, then runs the check; fails with its table on any disagreement.
pub(crate) fn run_suite(root: &Path) -> Result<(), String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo)
        // The tool as `cargo test --workspace` builds it for its integration tests (with the
        // features a test build unifies): after that step of `cargo xtask test`, nothing is
        // compiled again; alone, this builds the tests too.
        .args(["test", "--workspace", "--no-run"])
        .current_dir(root)
        .status()
        .map_err(|e| format!("occt: cannot run cargo: {e}"))?;
    if !status.success() {
        return Err(format!("occt: cargo build failed ({status})"));
    }
    let target = target_dir(root);
    let python = ensure_venv_with(
        &target,
        "python-venv",
        "import numpy, OCP.STEPControl, OCP.IGESControl",
        &["numpy", "cadquery-ocp-novtk"],
    )?;
    let binary = target.join("debug").join("spline");
    let status = Command::new(&python)
        .arg(root.join("tests/occt/check.py"))
        .arg(&binary)
        .arg(target.join("occt"))
        .env("PYTHONDONTWRITEBYTECODE", "1")
        .status()
        .map_err(|e| format!("occt: cannot run {}: {e}", python.display()))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!(
            "the Open CASCADE check (tests/occt/check.py) failed ({status})"
        ))
    }
}
