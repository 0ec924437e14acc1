//! `cargo xtask test`: the whole test suite, the README's test command and the last step of
//! `.ci/run`.
//!
//! Every suite runs in turn and the first failure stops the run with its name:
//! 1. `cargo test --workspace`: unit, integration, property and doc tests of every crate.
//! 2. The browser test of `spline studio` in headless Chromium (`test_browser`), which
//!    installs `chromium` and `chromium-driver` with apt-get when they are missing.
//! 3. The Python package (`python/`): built as a wheel and installed into a virtual
//!    environment under `target/`, then its pytest suite (`test_python`), scipy's own
//!    `test_bsplines.py` with the package in scipy's place among them.
//! 4. Open CASCADE's second opinion on the STEP and IGES files and on the geometry
//!    operations (`test_occt`).
//!
//! Suites that need more than the Rust toolchain (a Python virtual environment, a browser)
//! install what they need under `target/` or through the system's package manager first, so
//! that the command works on a fresh machine.

use std::path::Path;
use std::process::Command;

/// Runs `cargo ARGS` in the repository and fails with the suite's name if it fails.
fn cargo(root: &Path, suite: &str, args: &[&str]) -> Result<(), String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo)
        .args(args)
        .current_dir(root)
        .status()
        .map_err(|e| format!("{suite}: cannot run cargo: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("{suite} failed ({status})"))
    }
}

/// Runs every suite; see the module documentation.
pub(crate) fn run(root: &Path) -> Result<(), String> {
    cargo(root, "cargo test --workspace", &["test", "--workspace"])?;
    crate::test_browser::run_browser_test(root, None)?;
    crate::test_python::run_suite(root)?;
    crate::test_occt::run_suite(root)?;
    println!("xtask test: every suite passed");
    Ok(())
}
