//! `cargo xtask campaign [--cases N] [--seed S] [--jobs J] [--timeout SECONDS] [--memory-mb M]`:
//! a mutation campaign of the release `spline` binary over every subcommand (240 cases each by
//! default; the first ones in `templates.rs`, those added since in `newer.rs`).
//!
//! Valid command lines on small curves and surfaces made with the tool itself are mutated
//! (extreme counts and numbers, mutated JSON arguments, mutated and rescaled input files,
//! dropped or repeated options) and run as subprocesses under a memory limit (`ulimit -v`)
//! and a timeout. Each run is classified: a panic, an abort (killed by a signal), a run over
//! the timeout, non-finite numbers in the output (standard output or the written file), an
//! error that is not one line, or an unexpected exit status. The table counts them per
//! subcommand; failing command lines are written to `target/campaign/failures.txt`.

use crate::mutate::{Rng, mutate_arg, mutate_text, mutate_value};
use newer::{NEWER_SUBCOMMANDS, make_newer_seed_files, newer_templates};
use serde_json::Value;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use templates::{SUBCOMMANDS, SeedWriter, make_seed_files, templates};

mod newer;
mod templates;

/// Every subcommand of the campaign, first and newer, in the order of the cases.
fn subcommands() -> impl Iterator<Item = &'static str> {
    SUBCOMMANDS.iter().chain(NEWER_SUBCOMMANDS).copied()
}

/// The valid command lines of subcommand `sub`.
fn command_lines(sub: &str) -> Vec<Vec<&'static str>> {
    let first = templates(sub);
    if first.is_empty() {
        newer_templates(sub)
    } else {
        first
    }
}

/// The options of a campaign.
struct Options {
    cases: usize,
    seed: u64,
    jobs: usize,
    timeout: Duration,
    memory_mb: u64,
}

fn parse_options(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        cases: 8640,
        seed: 2026,
        jobs: 2,
        timeout: Duration::from_secs(20),
        memory_mb: 4096,
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| -> Result<u64, String> {
            it.next()
                .and_then(|v| v.parse().ok())
                .ok_or_else(|| format!("{name} needs a non-negative integer"))
        };
        match a.as_str() {
            "--cases" => o.cases = usize::try_from(value("--cases")?).map_err(|e| e.to_string())?,
            "--seed" => o.seed = value("--seed")?,
            "--jobs" => o.jobs = usize::try_from(value("--jobs")?).map_err(|e| e.to_string())?,
            "--timeout" => o.timeout = Duration::from_secs(value("--timeout")?),
            "--memory-mb" => o.memory_mb = value("--memory-mb")?,
            other => return Err(format!("campaign: unknown option {other}")),
        }
    }
    Ok(o)
}

/// A case's index, outcome, duration and detail (the error message or the first output).
type CaseResult = (usize, Outcome, Duration, String);

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Outcome {
    Ok,
    CleanError,
    Panic,
    Abort,
    Timeout,
    NonFinite,
    MultiLine,
    OtherStatus,
}

/// One case: its subcommand, its arguments, and the output file it writes (if any).
struct Case {
    sub: &'static str,
    args: Vec<String>,
    output: Option<String>,
}

/// Builds case `k`: a template of subcommand `k mod count` (the number of subcommands),
/// mutated one to three times.
fn build_case(k: usize, seed: u64, dir: &Path) -> Result<Case, String> {
    let count = SUBCOMMANDS.len() + NEWER_SUBCOMMANDS.len();
    let sub = subcommands().nth(k % count).expect("a subcommand");
    let mut rng = Rng::new(seed.wrapping_mul(1_000_003).wrapping_add(k as u64));
    let templates = command_lines(sub);
    let template = rng.pick(&templates).clone();
    let mut args: Vec<String> = template.iter().map(|s| (*s).to_string()).collect();
    let mut output = None;
    for a in &mut args {
        if let Some(ext) = a.strip_prefix("OUT") {
            *a = format!("out_{k}{ext}");
            output = Some(a.clone());
        }
    }
    // The first case of each template runs unmutated (the tool must succeed on it).
    let mutations = if k < count * 2 {
        0
    } else {
        *rng.pick(&[1, 1, 1, 1, 1, 1, 2, 2, 2, 3])
    };
    for _ in 0..mutations {
        mutate_case(&mut rng, &mut args, k, dir)?;
    }
    Ok(Case { sub, args, output })
}

fn mutate_case(rng: &mut Rng, args: &mut Vec<String>, k: usize, dir: &Path) -> Result<(), String> {
    let files: Vec<usize> = (1..args.len())
        .filter(|&i| {
            let a = &args[i];
            (a.ends_with(".json") || a.ends_with(".dat") || a.ends_with(".txt"))
                && !a.starts_with("out_")
                && dir.join(a).exists()
        })
        .collect();
    let values: Vec<usize> = (2..args.len())
        .filter(|&i| {
            args[i - 1].starts_with("--")
                && !args[i].starts_with("--")
                && !args[i].starts_with("out_")
        })
        .collect();
    match rng.below(20) {
        0..=9 if !values.is_empty() => {
            let i = *rng.pick(&values);
            args[i] = mutate_arg(rng, &args[i]);
        }
        10..=18 if !files.is_empty() => {
            let i = *rng.pick(&files);
            let text = std::fs::read_to_string(dir.join(&args[i])).unwrap_or_default();
            let mutated = match serde_json::from_str::<Value>(&text) {
                // Valid objects at extreme scales reach the numerics, not only the reader.
                Ok(mut value) if rng.chance(0.4) => {
                    let factor =
                        *rng.pick(&[1e150, 1e-150, 1e80, 1e-100, 1e300, 1e-300, 1e154, 1e-200]);
                    crate::mutate::scale_numbers(&mut value, factor);
                    value.to_string()
                }
                Ok(mut value) if rng.chance(0.8) => {
                    mutate_value(rng, &mut value);
                    value.to_string()
                }
                _ => mutate_text(rng, &text),
            };
            let name = format!("case_{k}_{i}.json");
            std::fs::write(dir.join(&name), mutated).map_err(|e| e.to_string())?;
            args[i] = name;
        }
        19 if args.len() > 2 && rng.chance(0.5) => {
            // Drop an argument (an option and its value, or a positional).
            let i = 1 + rng.below(args.len() - 1);
            if args[i].starts_with("--") && i + 1 < args.len() && !args[i + 1].starts_with("--") {
                args.drain(i..=i + 1);
            } else {
                args.remove(i);
            }
        }
        19 if !values.is_empty() && rng.chance(0.5) => {
            // Repeat an option.
            let i = *rng.pick(&values);
            let (name, value) = (args[i - 1].clone(), args[i].clone());
            args.push(name);
            args.push(value);
        }
        _ => {
            let extra = rng.pick(&[
                "--derivatives",
                "--times",
                "--direction",
                "--bogus",
                "-",
                "--segments-u",
                "--order",
            ]);
            args.push((*extra).to_string());
            args.push(rng.pick(crate::mutate::EXTREME_TEXT).to_string());
        }
    }
    Ok(())
}

/// Runs one case under the memory limit and the timeout.
fn run_case(binary: &Path, dir: &Path, case: &Case, o: &Options) -> (Outcome, Duration, String) {
    let started = Instant::now();
    let tag =
        format!("{:?}", std::thread::current().id()).replace(|c: char| !c.is_alphanumeric(), "");
    let stdout_path = dir.join(format!("stdout_{tag}"));
    let stderr_path = dir.join(format!("stderr_{tag}"));
    let spawn = || -> std::io::Result<std::process::Child> {
        Command::new("bash")
            .arg("-c")
            .arg(format!(
                "ulimit -v {}; exec \"$0\" \"$@\"",
                o.memory_mb * 1024
            ))
            .arg(binary)
            .args(&case.args)
            .current_dir(dir)
            .stdin(Stdio::null())
            .stdout(std::fs::File::create(&stdout_path)?)
            .stderr(std::fs::File::create(&stderr_path)?)
            .env("RUST_BACKTRACE", "0")
            .spawn()
    };
    let mut child = match spawn() {
        Ok(c) => c,
        Err(e) => {
            return (
                Outcome::OtherStatus,
                Duration::ZERO,
                format!("cannot run: {e}"),
            );
        }
    };
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) if started.elapsed() > o.timeout => {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(2)),
            Err(_) => break None,
        }
    };
    let elapsed = started.elapsed();
    let stdout = std::fs::read(&stdout_path).unwrap_or_default();
    let stderr =
        String::from_utf8_lossy(&std::fs::read(&stderr_path).unwrap_or_default()).into_owned();
    let Some(status) = status else {
        return (Outcome::Timeout, elapsed, stderr);
    };
    if stderr.contains("panicked") {
        return (Outcome::Panic, elapsed, stderr);
    }
    if let Some(signal) = status.signal() {
        return (
            Outcome::Abort,
            elapsed,
            format!("signal {signal}: {stderr}"),
        );
    }
    match status.code() {
        Some(0) => {
            let mut texts = vec![String::from_utf8_lossy(&stdout).into_owned()];
            if let Some(out) = &case.output {
                if let Ok(bytes) = std::fs::read(dir.join(out)) {
                    texts.push(String::from_utf8_lossy(&bytes).into_owned());
                }
                let _ = std::fs::remove_file(dir.join(out));
            }
            if texts.iter().any(|t| has_non_finite(t)) {
                (
                    Outcome::NonFinite,
                    elapsed,
                    texts.concat().chars().take(300).collect(),
                )
            } else {
                (Outcome::Ok, elapsed, String::new())
            }
        }
        Some(2) => {
            if stderr.lines().count() == 1 && stdout.is_empty() {
                (Outcome::CleanError, elapsed, stderr)
            } else {
                (Outcome::MultiLine, elapsed, stderr)
            }
        }
        other => (
            Outcome::OtherStatus,
            elapsed,
            format!("status {other:?}: {stderr}"),
        ),
    }
}

/// Whether a text holds a non-finite number: `NaN`, `inf` or a JSON `null`.
fn has_non_finite(text: &str) -> bool {
    let words = text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'));
    words.into_iter().any(|w| {
        let w = w.to_ascii_lowercase();
        w == "nan" || w == "inf" || w == "infinity" || w == "null"
    })
}

pub(crate) fn run(root: &Path, args: &[String]) -> Result<(), String> {
    let o = parse_options(args)?;
    let status = Command::new(env!("CARGO"))
        .args(["build", "--release", "--quiet", "-p", "spline-cli"])
        .current_dir(root)
        .status()
        .map_err(|e| format!("cannot build the tool: {e}"))?;
    if !status.success() {
        return Err("cannot build the tool".into());
    }
    let binary = root.join("target/release/spline");
    let dir = root.join("target/campaign");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let seeds = SeedWriter {
        binary: &binary,
        dir: &dir,
    };
    make_seed_files(&seeds, root)?;
    make_newer_seed_files(&seeds)?;
    let cases: Vec<Case> = (0..o.cases)
        .map(|k| build_case(k, o.seed, &dir))
        .collect::<Result<_, _>>()?;
    let cases = Arc::new(cases);
    let next = Arc::new(Mutex::new(0usize));
    let results: Arc<Mutex<Vec<CaseResult>>> = Arc::new(Mutex::new(Vec::new()));
    let started = Instant::now();
    std::thread::scope(|scope| {
        for _ in 0..o.jobs.max(1) {
            let (cases, next, results) =
                (Arc::clone(&cases), Arc::clone(&next), Arc::clone(&results));
            let (binary, dir, o) = (&binary, &dir, &o);
            scope.spawn(move || {
                loop {
                    let k = {
                        let mut n = next.lock().expect("lock");
                        let k = *n;
                        *n += 1;
                        k
                    };
                    if k >= cases.len() {
                        break;
                    }
                    let (outcome, time, detail) = run_case(binary, dir, &cases[k], o);
                    results
                        .lock()
                        .expect("lock")
                        .push((k, outcome, time, detail));
                }
            });
        }
    });
    let mut results = Arc::try_unwrap(results)
        .map_err(|_| "results still shared")?
        .into_inner()
        .map_err(|e| e.to_string())?;
    results.sort_by_key(|r| r.0);
    report(&cases, &results, &o, started.elapsed(), &dir)
}

fn report(
    cases: &[Case],
    results: &[CaseResult],
    o: &Options,
    elapsed: Duration,
    dir: &Path,
) -> Result<(), String> {
    let mut table: BTreeMap<&str, [usize; 9]> = BTreeMap::new();
    let mut failures = String::new();
    let mut messages = String::new();
    let mut slowest = Duration::ZERO;
    for (k, outcome, time, detail) in results {
        let case = &cases[*k];
        let row = table.entry(case.sub).or_default();
        row[0] += 1;
        let column = match outcome {
            Outcome::Ok => 1,
            Outcome::CleanError => 2,
            Outcome::Panic => 3,
            Outcome::Abort => 4,
            Outcome::Timeout => 5,
            Outcome::NonFinite => 6,
            Outcome::MultiLine => 7,
            Outcome::OtherStatus => 8,
        };
        row[column] += 1;
        slowest = slowest.max(*time);
        if column == 2 {
            let _ = writeln!(
                messages,
                "spline {}\n    {}",
                shell_words(&case.args),
                detail.trim()
            );
        }
        if column >= 3 {
            let _ = writeln!(
                failures,
                "{outcome:?} after {:.1} s: spline {}\n    {}",
                time.as_secs_f64(),
                shell_words(&case.args),
                detail.trim().lines().next().unwrap_or("")
            );
        }
    }
    let mut text = String::new();
    let _ = writeln!(
        text,
        "campaign: {} cases, seed {}, timeout {} s, memory limit {} MB, {:.0} s, slowest run {:.2} s",
        cases.len(),
        o.seed,
        o.timeout.as_secs(),
        o.memory_mb,
        elapsed.as_secs_f64(),
        slowest.as_secs_f64()
    );
    let _ = writeln!(
        text,
        "| subcommand | cases | exit 0 | exit 2 | panics | aborts | > {} s | non-finite | multi-line errors | other status |",
        o.timeout.as_secs()
    );
    let _ = writeln!(text, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut total = [0usize; 9];
    for sub in subcommands() {
        let row = table.get(sub).copied().unwrap_or_default();
        for (t, r) in total.iter_mut().zip(row) {
            *t += r;
        }
        let cells: Vec<String> = row.iter().map(ToString::to_string).collect();
        let _ = writeln!(text, "| {sub} | {} |", cells.join(" | "));
    }
    let cells: Vec<String> = total.iter().map(ToString::to_string).collect();
    let _ = writeln!(text, "| **total** | {} |", cells.join(" | "));
    print!("{text}");
    std::fs::write(dir.join("table.md"), &text).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("failures.txt"), &failures).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("errors.txt"), &messages).map_err(|e| e.to_string())?;
    let failed: usize = total[3..].iter().sum();
    if failed == 0 {
        Ok(())
    } else {
        print!("{failures}");
        Err(format!(
            "{failed} failing cases (listed in {})",
            dir.join("failures.txt").display()
        ))
    }
}

fn shell_words(args: &[String]) -> String {
    args.iter()
        .map(|a| {
            if !a.is_empty()
                && a.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "-_.,/:+".contains(c))
            {
                a.clone()
            } else {
                let shown: String = a.chars().take(120).collect();
                format!("'{}'", shown.replace('\'', "'\\''"))
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The campaign's working directory (seed files, mutated files, outputs, the table).
#[allow(dead_code)]
pub(crate) fn workdir(root: &Path) -> PathBuf {
    root.join("target/campaign")
}
