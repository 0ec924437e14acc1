//! Running the `spline` binary in tests.

#![allow(dead_code, unreachable_pub)]

use serde_json::Value;
#[allow(unused_imports)] // each test file uses some of them
pub use spline_testing::reference::{assert_close_json, assert_same_curve, cases, flatten};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The result of one run of the tool.
pub struct Run {
    pub status: i32,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    /// The standard output as JSON, asserting success.
    pub fn json(&self) -> Value {
        assert_eq!(self.status, 0, "stderr: {}", self.stderr);
        serde_json::from_str(&self.stdout)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {}", self.stdout))
    }

    /// Asserts the contract for invalid input: exit status 2, one line on stderr, no panic,
    /// nothing on stdout. Returns the message.
    pub fn assert_clean_error(&self) -> String {
        assert_eq!(
            self.status, 2,
            "expected exit status 2; stdout: {} stderr: {}",
            self.stdout, self.stderr
        );
        assert!(self.stdout.is_empty(), "stdout not empty: {}", self.stdout);
        let lines: Vec<&str> = self.stderr.lines().collect();
        assert_eq!(
            lines.len(),
            1,
            "stderr should be one line: {:?}",
            self.stderr
        );
        assert!(!self.stderr.contains("panicked"), "{}", self.stderr);
        assert!(lines[0].starts_with("spline: "), "{}", lines[0]);
        lines[0].to_owned()
    }
}

/// Runs `spline` with arguments.
pub fn spline(args: &[&str]) -> Run {
    let output: Output = Command::new(env!("CARGO_BIN_EXE_spline"))
        .args(args)
        .output()
        .expect("run spline");
    Run {
        status: output.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

static COUNTER: AtomicUsize = AtomicUsize::new(0);

/// Writes `contents` to a fresh temporary file and returns its path.
pub fn temp_file(name: &str, contents: &str) -> String {
    let dir = std::env::temp_dir().join(format!("spline-cli-tests-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let path = dir.join(format!("{n}-{name}"));
    std::fs::write(&path, contents).expect("write temp file");
    path.to_string_lossy().into_owned()
}

/// The path of a file of issue 25's reproducers (`tests/data/reproducers/`).
pub fn reproducer(name: &str) -> String {
    format!(
        "{}/tests/data/reproducers/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// A JSON number of the tool's output.
///
/// # Panics
/// If `v` is not a number.
pub fn num(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}
