//! The browser suite of `cargo xtask test`: `spline studio` in headless Chromium.
//!
//! The test (`crates/spline-studio/tests/integration/browser.rs`) is `#[ignore]`d so that a plain
//! `cargo test --workspace` needs no browser; this suite installs Debian's `chromium` and
//! `chromium-driver` with apt-get when `/usr/bin/chromedriver` is missing (CI runs as root;
//! `apt-get update` first), then runs it with `--ignored`. Its screenshots go to
//! `target/studio/`. `cargo xtask docs` runs the same test to redraw `docs/studio.png`.

use std::path::Path;
use std::process::Command;

/// Where chromedriver is expected (Debian's `chromium-driver`).
pub(crate) const CHROMEDRIVER: &str = "/usr/bin/chromedriver";

fn run(program: &str, args: &[&str]) -> Result<(), String> {
    let status = Command::new(program)
        .args(args)
        .env("DEBIAN_FRONTEND", "noninteractive")
        .status()
        .map_err(|e| format!("cannot run {program}: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("{program} {} failed ({status})", args.join(" ")))
    }
}

/// Installs `chromium` and `chromium-driver` unless chromedriver is already there.
pub(crate) fn ensure_chromium() -> Result<(), String> {
    if Path::new(CHROMEDRIVER).exists() && Path::new("/usr/bin/chromium").exists() {
        return Ok(());
    }
    println!("xtask: installing chromium and chromium-driver (apt-get) for the browser test");
    run("apt-get", &["update", "-qq"])?;
    run(
        "apt-get",
        &["install", "-y", "-qq", "chromium", "chromium-driver"],
    )
}

/// Runs the browser test, with `screenshot` (a path) copied from its last picture if given.
pub(crate) fn run_browser_test(root: &Path, screenshot: Option<&Path>) -> Result<(), String> {
    ensure_chromium()?;
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut command = Command::new(cargo);
    command
        .args([
            "test",
            "-p",
            "spline-studio",
            "--test",
            "integration",
            "--",
            "browser::",
            "--ignored",
            "--nocapture",
        ])
        .current_dir(root);
    if let Some(file) = screenshot {
        command.env("STUDIO_SCREENSHOT", file);
    }
    let status = command
        .status()
        .map_err(|e| format!("browser test: cannot run cargo: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!(
            "browser test (spline studio in Chromium) failed ({status})"
        ))
    }
}
