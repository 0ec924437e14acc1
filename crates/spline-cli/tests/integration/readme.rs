//! Every command-line example of the README runs as written: the `sh` block of the section
//! "The `spline` tool" is run by bash from the repository root, with `spline` standing for
//! the binary under test (the block's own build line and definition are skipped), and each
//! command must succeed and print something or write its file.

use std::path::Path;
use std::process::Command;

/// The lines of the README's tool examples.
fn examples(readme: &str) -> Vec<String> {
    let section = readme
        .split("## The `spline` tool")
        .nth(1)
        .expect("the README has a section on the tool");
    let block = section
        .split("```sh\n")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .expect("the section has an sh block");
    block
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .filter(|l| !l.starts_with("cargo build") && !l.starts_with("spline()"))
        .map(str::to_owned)
        .collect()
}

#[test]
fn every_cli_example_of_the_readme_runs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README.md");
    let lines = examples(&readme);
    assert!(lines.len() >= 15, "{lines:?}");
    assert!(
        lines.iter().any(|l| l.contains("make circle")),
        "a NURBS example"
    );
    let binary = env!("CARGO_BIN_EXE_spline");
    for line in &lines {
        let script = format!("set -euo pipefail\nspline() {{ '{binary}' \"$@\"; }}\n{line}\n");
        let out = Command::new("bash")
            .arg("-c")
            .arg(&script)
            .current_dir(&root)
            .output()
            .expect("bash runs");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{line}: {stderr}");
        let written = line
            .split_whitespace()
            .skip_while(|w| *w != "-o")
            .nth(1)
            .map(|file| root.join(file));
        match written {
            Some(file) => assert!(
                std::fs::metadata(&file).is_ok_and(|m| m.len() > 0),
                "{line}: {} not written",
                file.display()
            ),
            None => assert!(!out.stdout.is_empty(), "{line}: no output"),
        }
    }
}
