//! The Open CASCADE suite of `cargo xtask test` (`cargo xtask test occt` alone), two scripts
//! (see `tests/occt/README.md`):
//!
//! 1. `tests/occt/check.py`, the CAD exchange: writes random B-spline and NURBS curves and
//!    surfaces to STEP and IGES with the tool and reads them with Open CASCADE 8, and the
//!    other way round, then whole B-rep solids and malformed files;
//! 2. `tests/occt/geometry.py`, the geometry: evaluation, knot insertion, degree elevation,
//!    knot removal, closest points, intersections, offsets, arc length and the constructions
//!    of `spline make` on random cases, each against Open CASCADE's own operation.
//!
//! Open CASCADE comes from the Python package index (`cadquery-ocp-novtk`, OCCT 8 with
//! Python bindings), installed into the test virtual environment `target/python-venv` on
//! first use; the tool is the debug binary that `cargo test --workspace` builds.

use crate::bench::{ensure_venv_with, target_dir};
use std::path::Path;
use std::process::Command;

/// Builds the tool, then runs both checks; fails with the table of the first that disagrees.
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
    for (script, work, what) in [
        ("check.py", "occt", "CAD exchange"),
        ("geometry.py", "occt-geometry", "geometry"),
    ] {
        let status = Command::new(&python)
            .arg(root.join("tests/occt").join(script))
            .arg(&binary)
            .arg(target.join(work))
            .env("PYTHONDONTWRITEBYTECODE", "1")
            .status()
            .map_err(|e| format!("occt: cannot run {}: {e}", python.display()))?;
        if !status.success() {
            return Err(format!(
                "the Open CASCADE check of the {what} (tests/occt/{script}) failed ({status})"
            ));
        }
    }
    Ok(())
}
