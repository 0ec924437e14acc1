//! Shared pieces of the `cargo xtask bench` comparisons: a Python virtual environment with
//! scipy, running a timing script, reading criterion's medians.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// `$CARGO_TARGET_DIR` or `<repo>/target`.
pub(crate) fn target_dir(repo_root: &Path) -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) => {
            let dir = PathBuf::from(dir);
            if dir.is_absolute() {
                dir
            } else {
                repo_root.join(dir)
            }
        }
        None => repo_root.join("target"),
    }
}

fn venv_python(venv: &Path) -> PathBuf {
    if cfg!(windows) {
        venv.join("Scripts").join("python.exe")
    } else {
        venv.join("bin").join("python")
    }
}

fn status_of(command: &mut Command, what: &str) -> Result<(), String> {
    let status = command
        .status()
        .map_err(|e| format!("cannot run {what}: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("{what} failed ({status})"))
    }
}

/// The Python of `<target>/bench-venv`, created and given scipy on first use.
pub(crate) fn ensure_venv(target: &Path) -> Result<PathBuf, String> {
    ensure_venv_with(target, "bench-venv", "import scipy, numpy", &["scipy"])
}

/// The Python of the virtual environment `<target>/<name>`, created on first use; `packages`
/// are installed with pip whenever the Python statement `check` fails in it.
pub(crate) fn ensure_venv_with(
    target: &Path,
    name: &str,
    check: &str,
    packages: &[&str],
) -> Result<PathBuf, String> {
    let venv = target.join(name);
    let python = venv_python(&venv);
    if !python.exists() {
        std::fs::create_dir_all(target)
            .map_err(|e| format!("cannot create {}: {e}", target.display()))?;
        eprintln!(
            "creating a Python virtual environment in {}",
            venv.display()
        );
        let base = if cfg!(windows) { "python" } else { "python3" };
        status_of(
            Command::new(base).arg("-m").arg("venv").arg(&venv),
            &format!("{base} -m venv"),
        )?;
    }
    let ready = Command::new(&python)
        .args(["-c", check])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !ready {
        eprintln!("installing {} with pip", packages.join(", "));
        status_of(
            Command::new(&python)
                // No wheel cache: on a CI machine the cache is written once and never read
                // again, and the Open CASCADE wheel alone is hundreds of megabytes.
                .args(["-m", "pip", "install", "--quiet", "--no-cache-dir"])
                .args(packages),
            &format!("pip install {}", packages.join(" ")),
        )?;
    }
    Ok(python)
}

/// Runs a Python script and parses the one JSON document it prints. `OpenBLAS` core-type
/// overrides are removed from its environment so that numpy picks its kernels itself.
pub(crate) fn run_python_json(python: &Path, script: &Path) -> Result<Value, String> {
    let out = Command::new(python)
        .arg(script)
        .env_remove("OPENBLAS_CORETYPE")
        .env_remove("OPENBLAS_L2_SIZE")
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run {}: {e}", script.display()))?;
    if !out.status.success() {
        return Err(format!("{} failed ({})", script.display(), out.status));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    serde_json::from_str(text.trim())
        .map_err(|e| format!("output of {}: {e}: {text}", script.display()))
}

/// The median (seconds) criterion stored for benchmark `id` (`group/function`).
pub(crate) fn criterion_median(target: &Path, id: &str) -> Result<f64, String> {
    let path = target
        .join("criterion")
        .join(id.replace('/', std::path::MAIN_SEPARATOR_STR))
        .join("new")
        .join("estimates.json");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let json: Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    json.pointer("/median/point_estimate")
        .and_then(Value::as_f64)
        .map(|ns| ns * 1e-9)
        .ok_or_else(|| format!("{}: no median.point_estimate", path.display()))
}

/// Runs `cargo bench -p spline-fit --bench BENCH`, echoing its output, and returns the
/// numbers of the lines `TAG KEY VALUE` it printed for the given tags, keyed `"TAG KEY"`
/// (the benchmarks print such lines to report the residuals and checks of what they timed).
///
/// # Errors
/// A message when cargo cannot run, the benchmark fails, or a tagged line's value is not a
/// number.
pub(crate) fn run_criterion(
    repo_root: &Path,
    bench: &str,
    tags: &[&str],
) -> Result<std::collections::BTreeMap<String, f64>, String> {
    run_criterion_args(repo_root, &["-p", "spline-fit", "--bench", bench], tags)
}

/// [`run_criterion`] for `cargo bench ARGS` (another package, features).
///
/// # Errors
/// As [`run_criterion`].
pub(crate) fn run_criterion_args(
    repo_root: &Path,
    args: &[&str],
    tags: &[&str],
) -> Result<std::collections::BTreeMap<String, f64>, String> {
    run_criterion_in(repo_root, args, tags, None)
}

/// [`run_criterion_args`] with the build in `target_dir` (`CARGO_TARGET_DIR`) when given: a
/// crate outside the workspace.
///
/// # Errors
/// As [`run_criterion`].
pub(crate) fn run_criterion_in(
    repo_root: &Path,
    args: &[&str],
    tags: &[&str],
    target_dir: Option<&Path>,
) -> Result<std::collections::BTreeMap<String, f64>, String> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut command = Command::new(cargo);
    if let Some(dir) = target_dir {
        command.env("CARGO_TARGET_DIR", dir);
    }
    let out = command
        .arg("bench")
        .args(args)
        .current_dir(repo_root)
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run cargo bench: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    print!("{text}");
    if !out.status.success() {
        return Err(format!(
            "cargo bench {} failed ({})",
            args.join(" "),
            out.status
        ));
    }
    let mut found = std::collections::BTreeMap::new();
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if let [tag, key, value] = words[..]
            && tags.contains(&tag)
        {
            let v: f64 = value
                .parse()
                .map_err(|e| format!("bad line {line:?}: {e}"))?;
            found.insert(format!("{tag} {key}"), v);
        }
    }
    Ok(found)
}

/// A duration for tables.
pub(crate) fn seconds(s: f64) -> String {
    if s >= 1.0 {
        format!("{s:.3} s")
    } else if s >= 1e-3 {
        format!("{:.3} ms", s * 1e3)
    } else if s >= 1e-6 {
        format!("{:.1} µs", s * 1e6)
    } else {
        format!("{:.1} ns", s * 1e9)
    }
}
