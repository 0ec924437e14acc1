//! The Open CASCADE suite of `cargo xtask test` (`cargo xtask test occt` alone):
//! `tests/occt/check.py` writes random B-spline and NURBS curves and surfaces to STEP and IGES
//! with the tool and reads them with Open CASCADE 8, and the other way round, then whole
//! B-rep solids and malformed files; then `tests/occt/geometry.py` checks the tool's geometry
//! (evaluation, knot insertion, elevation and removal, closest points, intersections, offsets,
//! arc length, constructions) against Open CASCADE's on random cases (see
//! `tests/occt/README.md`).
//!
//! Open CASCADE comes from the Python package index (`cadquery-ocp-novtk`, OCCT 8 with
//! Python bindings), installed into the test virtual environment `target/python-venv` on
//! first use; the tool is the debug binary that `cargo test --workspace` builds.

use crate::bench::{ensure_venv_with, target_dir};
use std::path::Path;
use std::process::Command;

/// Builds the tool, then runs both checks; fails with their tables on any disagreement.
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
    // Both run even when the first fails, so that one run shows both tables.
    let mut failed = Vec::new();
    for (script, work) in [("check.py", "occt"), ("geometry.py", "occt-geometry")] {
        let status = Command::new(&python)
            .arg(root.join("tests/occt").join(script))
            .arg(&binary)
            .arg(target.join(work))
            .env("PYTHONDONTWRITEBYTECODE", "1")
            .status()
            .map_err(|e| format!("occt: cannot run {}: {e}", python.display()))?;
        if !status.success() {
            failed.push(format!("tests/occt/{script} ({status})"));
        }
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "the Open CASCADE check failed: {}",
            failed.join(", ")
        ))
    }
}
