//! `cargo xtask fuzz --coverage [--target T] [--seconds S]`: coverage-guided fuzzing with
//! libFuzzer on the nightly toolchain.
//!
//! The targets of `fuzz/` (a crate of its own, outside the workspace, so that stable builds
//! never see it) run the same oracles as the stable mutation fuzzer
//! ([`crate::fuzz_oracles`]): `exchange` and `points` read the bytes libFuzzer hands in as a
//! file, `operations` draws every decision of a case from them ([`crate::mutate::Rng::from_bytes`]).
//! The build instruments the code for coverage the way cargo-fuzz does (sanitizer coverage
//! with comparison tracing, debug assertions and overflow checks on: an arithmetic overflow
//! is a crash too). Each target runs for its share of the time, from the seed files in
//! `fuzz/corpus/<target>/` (and `data/airfoils/` for `points`) plus the corpus it grew on
//! earlier runs (`target/fuzz/corpus/<target>/`); a crash is written to `fuzz/crashes/`.

use std::path::Path;
use std::process::Command;

/// The instrumentation cargo-fuzz uses for libFuzzer without a sanitizer.
const COVERAGE_FLAGS: &str = "-Cpasses=sancov-module \
    -Cllvm-args=-sanitizer-coverage-level=4 \
    -Cllvm-args=-sanitizer-coverage-inline-8bit-counters \
    -Cllvm-args=-sanitizer-coverage-pc-table \
    -Cllvm-args=-sanitizer-coverage-trace-compares \
    --cfg fuzzing -Cdebug-assertions -Coverflow-checks";

/// A `cargo +nightly` command with the environment of the calling cargo removed (it names
/// the stable toolchain and this workspace's settings).
fn nightly_cargo(root: &Path) -> Command {
    let mut command = Command::new("cargo");
    command.arg("+nightly").current_dir(root.join("fuzz"));
    for variable in [
        "RUSTUP_TOOLCHAIN",
        "RUSTC",
        "RUSTDOC",
        "RUSTC_WRAPPER",
        "RUSTFLAGS",
        "CARGO_ENCODED_RUSTFLAGS",
        "CARGO",
        "CARGO_MANIFEST_DIR",
    ] {
        command.env_remove(variable);
    }
    command
}

/// The host's target triple, from `rustc -vV`.
fn host_triple() -> Result<String, String> {
    let output = Command::new("rustc")
        .arg("-vV")
        .output()
        .map_err(|e| format!("rustc -vV: {e}"))?;
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .find_map(|line| line.strip_prefix("host: "))
        .map(str::to_string)
        .ok_or_else(|| "rustc -vV names no host".into())
}

/// Builds the instrumented targets and fuzzes each for `seconds / targets.len()` seconds.
///
/// # Errors
/// A message when nightly is missing, the build fails, or a target crashes (with where the
/// crashing input was written).
pub(crate) fn run(root: &Path, targets: &[&str], seconds: u64) -> Result<(), String> {
    let nightly = nightly_cargo(root).arg("--version").output();
    if !nightly.is_ok_and(|o| o.status.success()) {
        return Err("coverage-guided fuzzing needs the nightly toolchain \
             (`rustup toolchain install nightly`); `cargo xtask fuzz` without --coverage \
             runs the stable mutation fuzzer"
            .into());
    }
    let host = host_triple()?;
    let target_dir = root.join("target/fuzz");
    // An explicit --target keeps the instrumentation off build scripts and proc macros.
    let status = nightly_cargo(root)
        .args(["build", "--release", "--bins", "--target", &host])
        .env("CARGO_TARGET_DIR", &target_dir)
        .env("RUSTFLAGS", COVERAGE_FLAGS)
        .status()
        .map_err(|e| format!("cargo +nightly build: {e}"))?;
    if !status.success() {
        return Err("building the fuzz targets failed".into());
    }
    let crashes = root.join("fuzz/crashes");
    std::fs::create_dir_all(&crashes).map_err(|e| format!("{}: {e}", crashes.display()))?;
    let share = (seconds / targets.len().max(1) as u64).max(1);
    let mut failed = Vec::new();
    for &target in targets {
        let corpus = target_dir.join("corpus").join(target);
        std::fs::create_dir_all(&corpus).map_err(|e| format!("{}: {e}", corpus.display()))?;
        let mut command = Command::new(target_dir.join(&host).join("release").join(target));
        command
            .arg(format!("-max_total_time={share}"))
            .arg("-timeout=20")
            .arg("-rss_limit_mb=4096")
            .arg("-max_len=65536")
            .arg("-print_final_stats=1")
            .arg(format!("-artifact_prefix={}/{target}-", crashes.display()))
            .arg(&corpus)
            .arg(root.join("fuzz/corpus").join(target));
        if target == "points" {
            command.arg(root.join("data/airfoils"));
        }
        println!("fuzz --coverage: {target} for {share} s");
        let status = command
            .status()
            .map_err(|e| format!("running the {target} fuzz target: {e}"))?;
        if !status.success() {
            failed.push(target);
        }
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "{} crashed (inputs in {}; replay one with target/fuzz/<host>/release/<target> <file>)",
            failed.join(", "),
            crashes.display()
        ))
    }
}
