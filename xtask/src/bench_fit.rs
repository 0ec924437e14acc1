//! `cargo xtask bench fit`: the fitting benchmarks of `spline-fit` against scipy.
//!
//! 1. Creates a Python virtual environment in `<target>/bench-venv` (once) and installs
//!    scipy into it with pip.
//! 2. Runs `xtask/bench/fit_scipy.py`: `make_interp_spline` on 10⁴, 10⁵, 10⁶ planar points
//!    (cubic) and `make_lsq_spline` on 10⁵ points with 200 coefficients (QR and normal
//!    equations), printing medians and residuals as JSON.
//! 3. Runs `cargo bench -p spline-fit --bench fit` (criterion, the same workloads) and reads
//!    the medians from `<target>/criterion/fit/*/*/new/estimates.json`, the residuals from
//!    the `fit-residual` lines the benchmark prints.
//! 4. Prints a table of medians, speed-ups and residuals, and whether the targets are met
//!    (interpolation ≥ 2× scipy at 10⁵ points; least squares at least as fast as scipy's
//!    normal equations and ≥ 5× its default QR, with residuals as small).
//!
//! `<target>` is `$CARGO_TARGET_DIR` or `<repo>/target`. `OpenBLAS` core-type overrides
//! (`OPENBLAS_CORETYPE`, `OPENBLAS_L2_SIZE`) are removed from the environment of the Python
//! run only, so that numpy uses the kernels it would pick by itself.

#![allow(unreachable_pub)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// Runs the comparison and prints the table.
///
/// # Errors
/// A message when Python, pip, the scipy script or `cargo bench` fail, or when their output
/// cannot be read.
pub fn run(repo_root: &Path) -> Result<(), String> {
    let target = target_dir(repo_root);
    let python = ensure_venv(&target)?;
    eprintln!("bench fit: timing scipy (a minute or two)…");
    let scipy = run_scipy(&python, repo_root)?;
    eprintln!("bench fit: running cargo bench -p spline-fit --bench fit…");
    let residuals = run_criterion(repo_root)?;
    let mut rust = BTreeMap::new();
    for id in RUST_IDS {
        let path = target
            .join("criterion")
            .join("fit")
            .join(id.replace('/', std::path::MAIN_SEPARATOR_STR))
            .join("new")
            .join("estimates.json");
        let text = std::fs::read_to_string(&path)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let json = Json::parse(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let ns = json
            .get("median")
            .and_then(|m| m.get("point_estimate"))
            .and_then(Json::as_f64)
            .ok_or_else(|| format!("{}: no median.point_estimate", path.display()))?;
        rust.insert(id.to_string(), ns * 1e-9);
    }
    print_table(&scipy, &rust, &residuals)
}

const RUST_IDS: [&str; 5] = [
    "interp/10000",
    "interp/100000",
    "interp/1000000",
    "lsq_normal/100000",
    "lsq_qr/100000",
];

fn target_dir(repo_root: &Path) -> PathBuf {
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

/// The venv's interpreter, with scipy installed.
fn ensure_venv(target: &Path) -> Result<PathBuf, String> {
    let venv = target.join("bench-venv");
    let python = venv_python(&venv);
    if !python.exists() {
        std::fs::create_dir_all(target)
            .map_err(|e| format!("cannot create {}: {e}", target.display()))?;
        eprintln!(
            "bench fit: creating a Python virtual environment in {}",
            venv.display()
        );
        let base = if cfg!(windows) { "python" } else { "python3" };
        status_of(
            Command::new(base).arg("-m").arg("venv").arg(&venv),
            &format!("{base} -m venv"),
        )?;
    }
    let has_scipy = Command::new(&python)
        .args(["-c", "import scipy, numpy"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !has_scipy {
        eprintln!("bench fit: installing scipy with pip");
        status_of(
            Command::new(&python).args(["-m", "pip", "install", "--quiet", "scipy"]),
            "pip install scipy",
        )?;
    }
    Ok(python)
}

fn run_scipy(python: &Path, repo_root: &Path) -> Result<Json, String> {
    let script = repo_root.join("xtask").join("bench").join("fit_scipy.py");
    let out = Command::new(python)
        .arg(&script)
        .env_remove("OPENBLAS_CORETYPE")
        .env_remove("OPENBLAS_L2_SIZE")
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run {}: {e}", script.display()))?;
    if !out.status.success() {
        return Err(format!("{} failed ({})", script.display(), out.status));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    Json::parse(text.trim()).map_err(|e| format!("scipy output: {e}: {text}"))
}

/// Runs criterion; returns the residuals it printed.
fn run_criterion(repo_root: &Path) -> Result<BTreeMap<String, f64>, String> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let out = Command::new(cargo)
        .args(["bench", "-p", "spline-fit", "--bench", "fit"])
        .current_dir(repo_root)
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run cargo bench: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    print!("{text}");
    if !out.status.success() {
        return Err(format!("cargo bench -p spline-fit failed ({})", out.status));
    }
    let mut residuals = BTreeMap::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        if let (Some("fit-residual"), Some(id), Some(value)) =
            (words.next(), words.next(), words.next())
        {
            let v: f64 = value
                .parse()
                .map_err(|e| format!("bad residual line {line:?}: {e}"))?;
            residuals.insert(id.to_string(), v);
        }
    }
    Ok(residuals)
}

fn seconds(s: f64) -> String {
    if s >= 1.0 {
        format!("{s:.3} s")
    } else if s >= 1e-3 {
        format!("{:.3} ms", s * 1e3)
    } else {
        format!("{:.1} µs", s * 1e6)
    }
}

fn print_table(
    scipy: &Json,
    rust: &BTreeMap<String, f64>,
    residuals: &BTreeMap<String, f64>,
) -> Result<(), String> {
    let results = scipy
        .get("results")
        .ok_or("scipy output has no \"results\"")?;
    let field = |id: &str, key: &str| -> Result<f64, String> {
        results
            .get(id)
            .and_then(|r| r.get(key))
            .and_then(Json::as_f64)
            .ok_or_else(|| format!("scipy output lacks {id}.{key}"))
    };
    let version = scipy.get("scipy").and_then(Json::as_str).unwrap_or("?");
    let numpy = scipy.get("numpy").and_then(Json::as_str).unwrap_or("?");
    // (label, scipy id, rust id, target speed-up)
    let rows: [(&str, &str, &str, f64); 6] = [
        ("interp 10^4", "interp/10000", "interp/10000", 0.0),
        ("interp 10^5", "interp/100000", "interp/100000", 2.0),
        ("interp 10^6", "interp/1000000", "interp/1000000", 0.0),
        (
            "lsq 10^5 normal vs scipy qr",
            "lsq_qr/100000",
            "lsq_normal/100000",
            5.0,
        ),
        (
            "lsq 10^5 normal vs scipy norm-eq",
            "lsq_norm_eq/100000",
            "lsq_normal/100000",
            1.0,
        ),
        (
            "lsq 10^5 qr vs scipy qr",
            "lsq_qr/100000",
            "lsq_qr/100000",
            0.0,
        ),
    ];
    println!();
    println!("spline-fit vs scipy {version} (numpy {numpy}): medians, speed-up = scipy / rust");
    println!(
        "{:<34} {:>12} {:>12} {:>9} {:>18} {:>18}  target",
        "workload", "scipy", "rust", "speed-up", "scipy resid.", "rust resid."
    );
    let mut all_met = true;
    for (label, sid, rid, target) in rows {
        let s = field(sid, "median_s")?;
        let r = *rust
            .get(rid)
            .ok_or_else(|| format!("no criterion median for {rid}"))?;
        let sres = field(sid, "residual")?;
        let rres = residuals.get(rid).copied().unwrap_or(f64::NAN);
        let ratio = s / r;
        // "As small": within a relative 1e-9 (least squares) or 1e-9 absolute (interpolation).
        let small = rres <= sres * (1.0 + 1e-9) + 1e-9;
        let verdict = if target > 0.0 {
            let met = ratio >= target && small;
            all_met &= met;
            format!("≥ {target}×: {}", if met { "met" } else { "MISSED" })
        } else {
            String::new()
        };
        println!(
            "{label:<34} {:>12} {:>12} {:>8.2}× {sres:>18.10e} {rres:>18.10e}  {verdict}",
            seconds(s),
            seconds(r),
            ratio
        );
    }
    println!(
        "{}",
        if all_met {
            "all targets met"
        } else {
            "some targets missed"
        }
    );
    Ok(())
}

/// A minimal JSON value, enough for scipy's output and criterion's estimates.
#[derive(Clone, Debug, PartialEq)]
enum Json {
    Null,
    Bool(bool),
    Number(f64),
    String(String),
    Array(Vec<Json>),
    Object(Vec<(String, Json)>),
}

impl Json {
    fn parse(text: &str) -> Result<Self, String> {
        let bytes = text.as_bytes();
        let mut pos = 0;
        let value = parse_value(bytes, &mut pos)?;
        skip_ws(bytes, &mut pos);
        if pos != bytes.len() {
            return Err(format!("trailing characters at byte {pos}"));
        }
        Ok(value)
    }

    fn get(&self, key: &str) -> Option<&Self> {
        match self {
            Self::Object(items) => items.iter().find(|(k, _)| k == key).map(|(_, v)| v),
            _ => None,
        }
    }

    fn as_f64(&self) -> Option<f64> {
        match self {
            Self::Number(x) => Some(*x),
            _ => None,
        }
    }

    fn as_str(&self) -> Option<&str> {
        match self {
            Self::String(s) => Some(s),
            _ => None,
        }
    }
}

fn skip_ws(b: &[u8], pos: &mut usize) {
    while *pos < b.len() && b[*pos].is_ascii_whitespace() {
        *pos += 1;
    }
}

fn expect(b: &[u8], pos: &mut usize, word: &str) -> Result<(), String> {
    if b[*pos..].starts_with(word.as_bytes()) {
        *pos += word.len();
        Ok(())
    } else {
        Err(format!("expected {word} at byte {pos}"))
    }
}

fn parse_value(b: &[u8], pos: &mut usize) -> Result<Json, String> {
    skip_ws(b, pos);
    let Some(&c) = b.get(*pos) else {
        return Err("unexpected end of JSON".into());
    };
    match c {
        b'n' => expect(b, pos, "null").map(|()| Json::Null),
        b't' => expect(b, pos, "true").map(|()| Json::Bool(true)),
        b'f' => expect(b, pos, "false").map(|()| Json::Bool(false)),
        b'N' => expect(b, pos, "NaN").map(|()| Json::Number(f64::NAN)),
        b'I' => expect(b, pos, "Infinity").map(|()| Json::Number(f64::INFINITY)),
        b'"' => parse_string(b, pos).map(Json::String),
        b'[' => {
            *pos += 1;
            let mut items = Vec::new();
            skip_ws(b, pos);
            if b.get(*pos) == Some(&b']') {
                *pos += 1;
                return Ok(Json::Array(items));
            }
            loop {
                items.push(parse_value(b, pos)?);
                skip_ws(b, pos);
                match b.get(*pos) {
                    Some(b',') => *pos += 1,
                    Some(b']') => {
                        *pos += 1;
                        return Ok(Json::Array(items));
                    }
                    _ => return Err(format!("expected , or ] at byte {pos}")),
                }
            }
        }
        b'{' => {
            *pos += 1;
            let mut items = Vec::new();
            skip_ws(b, pos);
            if b.get(*pos) == Some(&b'}') {
                *pos += 1;
                return Ok(Json::Object(items));
            }
            loop {
                skip_ws(b, pos);
                let key = parse_string(b, pos)?;
                skip_ws(b, pos);
                expect(b, pos, ":")?;
                let value = parse_value(b, pos)?;
                items.push((key, value));
                skip_ws(b, pos);
                match b.get(*pos) {
                    Some(b',') => *pos += 1,
                    Some(b'}') => {
                        *pos += 1;
                        return Ok(Json::Object(items));
                    }
                    _ => return Err(format!("expected , or }} at byte {pos}")),
                }
            }
        }
        _ => {
            let start = *pos;
            while *pos < b.len()
                && matches!(b[*pos], b'-' | b'+' | b'.' | b'e' | b'E' | b'0'..=b'9')
            {
                *pos += 1;
            }
            std::str::from_utf8(&b[start..*pos])
                .ok()
                .and_then(|s| s.parse().ok())
                .map(Json::Number)
                .ok_or_else(|| format!("bad number at byte {start}"))
        }
    }
}

fn parse_string(b: &[u8], pos: &mut usize) -> Result<String, String> {
    if b.get(*pos) != Some(&b'"') {
        return Err(format!("expected a string at byte {pos}"));
    }
    *pos += 1;
    let mut out = Vec::new();
    while let Some(&c) = b.get(*pos) {
        *pos += 1;
        match c {
            b'"' => return String::from_utf8(out).map_err(|e| e.to_string()),
            b'\\' => {
                let Some(&e) = b.get(*pos) else { break };
                *pos += 1;
                match e {
                    b'n' => out.push(b'\n'),
                    b't' => out.push(b'\t'),
                    b'r' => out.push(b'\r'),
                    b'b' => out.push(8),
                    b'f' => out.push(12),
                    b'u' => {
                        let hex = b
                            .get(*pos..*pos + 4)
                            .and_then(|h| std::str::from_utf8(h).ok())
                            .and_then(|h| u32::from_str_radix(h, 16).ok())
                            .ok_or("bad \\u escape")?;
                        *pos += 4;
                        let ch = char::from_u32(hex).unwrap_or('\u{fffd}');
                        let mut buf = [0; 4];
                        out.extend_from_slice(ch.encode_utf8(&mut buf).as_bytes());
                    }
                    other => out.push(other),
                }
            }
            other => out.push(other),
        }
    }
    Err("unterminated string".into())
}

#[cfg(test)]
mod tests {
    use super::Json;

    #[test]
    fn parses_criterion_and_scipy_shapes() {
        let j = Json::parse(
            r#"{"median": {"point_estimate": 1.5e6, "x": [1, -2.5, true, null]}, "s": "a\"b"}"#,
        )
        .unwrap();
        assert_eq!(
            j.get("median")
                .and_then(|m| m.get("point_estimate"))
                .and_then(Json::as_f64),
            Some(1.5e6)
        );
        assert_eq!(j.get("s").and_then(Json::as_str), Some("a\"b"));
        assert!(Json::parse("{\"a\": }").is_err());
    }
}
