//! `cargo xtask fuzz [--cases N | --seconds S] [--seed S] [--target exchange|points|operations]`:
//! structured mutation fuzzing of the library, in process, on the stable toolchain
//! (`--coverage [--seconds S]`: the same oracles under libFuzzer on nightly, see
//! [`crate::fuzz_coverage`]).
//!
//! Three targets, each drawing inputs from a seeded generator ([`crate::mutate::Rng`]):
//! - `exchange`: the JSON exchange-format reader (records of curves, NURBS curves and
//!   surfaces, then validation into containers) on mutated files of `fuzz/corpus/exchange/`;
//! - `points`: the point-file and airfoil `.dat` reader (`parse_points`) on mutated files of
//!   `fuzz/corpus/points/` and `data/airfoils/`;
//! - `operations`: every operation on arbitrary valid objects (random degrees, knots with
//!   multiplicities, points at scales from 1e-150 to 1e150, weights) with arbitrary counts:
//!   evaluation and derivatives of any order, insertion, refinement, removal, elevation,
//!   splitting, Bézier extraction, derivative curves, curvature and features, products,
//!   constructions, meshes, interpolation, least squares, parameter correction, natural
//!   splines.
//!
//! Each case runs under `catch_unwind`: a panic is a failure, and so is an `Ok` result holding
//! non-finite numbers. Failing inputs are written to `fuzz/crashes/` and become regression
//! tests. A short deterministic pass of the same generators runs in `cargo test`
//! (`tests::deterministic_pass`).

use crate::fuzz_oracles::{CURRENT, exchange, operations, points};
use crate::mutate::{Rng, mutate_text, mutate_value};
use serde_json::Value;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The fuzz targets.
pub(crate) const TARGETS: &[&str] = &["exchange", "points", "operations"];

/// A failing case: the target, the seed of the case, the message, and the input.
#[derive(Debug)]
pub(crate) struct Failure {
    pub(crate) target: &'static str,
    pub(crate) case_seed: u64,
    pub(crate) message: String,
    pub(crate) input: String,
}

/// The seed inputs of a target.
pub(crate) fn corpus(root: &Path, target: &str) -> Vec<String> {
    let mut dirs: Vec<PathBuf> = vec![root.join("fuzz/corpus").join(target)];
    if target == "points" {
        dirs.push(root.join("data/airfoils"));
    }
    let mut files: Vec<PathBuf> = dirs
        .iter()
        .filter_map(|d| std::fs::read_dir(d).ok())
        .flat_map(|entries| entries.filter_map(|e| e.ok().map(|e| e.path())))
        .filter(|p| p.is_file() && p.extension().is_some_and(|e| e != "md"))
        .collect();
    files.sort();
    files
        .iter()
        .filter_map(|p| std::fs::read_to_string(p).ok())
        .collect()
}

/// Runs one case of `target` from `case_seed`; `Err` describes a failure.
pub(crate) fn run_case(
    target: &str,
    case_seed: u64,
    corpus: &[String],
) -> Result<(), (String, String)> {
    let mut rng = Rng::new(case_seed);
    let input = match target {
        "exchange" | "points" => {
            let seed = if corpus.is_empty() {
                String::new()
            } else {
                rng.pick(corpus).clone()
            };
            mutated_input(&mut rng, &seed)
        }
        _ => String::new(),
    };
    CURRENT.with(|current| current.borrow_mut().clear());
    let outcome = catch_unwind(AssertUnwindSafe(|| match target {
        "exchange" => exchange(&input),
        "points" => points(&input),
        _ => operations(&mut rng),
    }));
    match outcome {
        Ok(Ok(())) => Ok(()),
        Ok(Err(message)) => Err((message, input)),
        Err(payload) => {
            let message = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| (*s).to_string()))
                .unwrap_or_else(|| "panic".into());
            let doing = CURRENT.with(|current| current.borrow().clone());
            Err((format!("panicked: {message} ({doing})"), input))
        }
    }
}

fn mutated_input(rng: &mut Rng, seed: &str) -> String {
    let mut text = seed.to_string();
    for _ in 0..1 + rng.below(3) {
        text = match serde_json::from_str::<Value>(&text) {
            Ok(mut value) if rng.chance(0.8) => {
                mutate_value(rng, &mut value);
                value.to_string()
            }
            _ => mutate_text(rng, &text),
        };
    }
    text
}

/// Runs `cases` cases (or until `deadline`) of each target; returns the failures.
pub(crate) fn pass(
    root: &Path,
    targets: &[&'static str],
    seed: u64,
    cases: usize,
    deadline: Option<Instant>,
) -> (usize, Vec<Failure>) {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut failures = Vec::new();
    let mut total = 0;
    for &target in targets {
        let corpus = corpus(root, target);
        for k in 0..cases {
            if deadline.is_some_and(|d| Instant::now() > d) {
                break;
            }
            let case_seed = seed
                .wrapping_mul(0x100_0000_01B3)
                .wrapping_add(k as u64)
                .wrapping_add(target.len() as u64 * 0x9E37);
            total += 1;
            if let Err((message, input)) = run_case(target, case_seed, &corpus) {
                failures.push(Failure {
                    target,
                    case_seed,
                    message,
                    input,
                });
            }
        }
    }
    std::panic::set_hook(previous);
    (total, failures)
}

/// Runs one input file of a libFuzzer run through the stable harness, printing what the
/// case did and its time.
fn replay_file(target: &str, path: &Path) -> Result<(), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let started = Instant::now();
    let outcome = match target {
        "exchange" => exchange(&text),
        "points" => points(&text),
        _ => operations(&mut Rng::from_bytes(&bytes)),
    };
    let doing = CURRENT.with(|current| current.borrow().clone());
    println!(
        "{target} {}: {outcome:?} in {:.3} s ({doing})",
        path.display(),
        started.elapsed().as_secs_f64()
    );
    outcome
}

pub(crate) fn run(root: &Path, args: &[String]) -> Result<(), String> {
    let mut cases = usize::MAX;
    let mut seconds = None;
    let mut seed = 1u64;
    let mut targets: Vec<&'static str> = TARGETS.to_vec();
    let mut coverage = false;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| {
            it.next()
                .ok_or_else(|| format!("{name} needs a value"))
                .cloned()
        };
        match a.as_str() {
            "--cases" => {
                cases = value("--cases")?
                    .parse()
                    .map_err(|e| format!("--cases: {e}"))?;
            }
            "--seconds" => {
                seconds = Some(
                    value("--seconds")?
                        .parse::<u64>()
                        .map_err(|e| format!("--seconds: {e}"))?,
                );
            }
            "--replay" => {
                // Re-runs one case (seed as printed, 0x…) with the panic message and backtrace
                // shown: `cargo xtask fuzz --target operations --replay 0x…`.
                let text = value("--replay")?;
                let seed = u64::from_str_radix(text.trim_start_matches("0x"), 16)
                    .map_err(|e| format!("--replay: {e}"))?;
                let target = *targets.first().ok_or("--replay needs a --target")?;
                let corpus = corpus(root, target);
                return run_case(target, seed, &corpus)
                    .map_err(|(message, _)| format!("{target} case {seed:#x}: {message}"));
            }
            "--replay-file" => {
                // Re-runs a file written by libFuzzer (`--coverage`): says what the case does
                // and how long it takes.
                let path = PathBuf::from(value("--replay-file")?);
                let target = *targets.first().ok_or("--replay-file needs a --target")?;
                return replay_file(target, &path);
            }
            "--seed" => {
                seed = value("--seed")?
                    .parse()
                    .map_err(|e| format!("--seed: {e}"))?;
            }
            "--target" => {
                let t = value("--target")?;
                let t = TARGETS
                    .iter()
                    .find(|&&x| x == t)
                    .ok_or_else(|| format!("--target: one of {}", TARGETS.join(", ")))?;
                targets = vec![*t];
            }
            "--coverage" => coverage = true,
            other => return Err(format!("fuzz: unknown option {other}")),
        }
    }
    if coverage {
        return crate::fuzz_coverage::run(root, &targets, seconds.unwrap_or(300));
    }
    if cases == usize::MAX && seconds.is_none() {
        cases = 10_000;
    }
    let started = Instant::now();
    let mut total = 0;
    let mut failures = Vec::new();
    // With a time budget, the targets share it and the seed advances round after round.
    let mut round = 0u64;
    loop {
        let per_round = if seconds.is_some() { 1000 } else { cases };
        let deadline = seconds.map(|s| started + Duration::from_secs(s));
        let (n, mut f) = pass(
            root,
            &targets,
            seed.wrapping_add(round),
            per_round,
            deadline,
        );
        total += n;
        failures.append(&mut f);
        round += 1;
        match seconds {
            Some(s) if started.elapsed() < Duration::from_secs(s) && n > 0 => {}
            _ => break,
        }
    }
    println!(
        "fuzz: {total} cases of {} in {:.1} s, {} failures",
        targets.join(", "),
        started.elapsed().as_secs_f64(),
        failures.len()
    );
    if failures.is_empty() {
        return Ok(());
    }
    let dir = root.join("fuzz/crashes");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    for f in &failures {
        let path = dir.join(format!("{}-{:016x}", f.target, f.case_seed));
        std::fs::write(&path, &f.input).map_err(|e| e.to_string())?;
        println!(
            "{} case {:#x}: {} (input in {})",
            f.target,
            f.case_seed,
            f.message,
            path.display()
        );
    }
    Err(format!("{} failing cases", failures.len()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mutate::scale_numbers;
    use nalgebra::Vector2;
    use spline::io::exchange::CurveRecord;

    /// The short deterministic pass that CI runs: the same generators as `cargo xtask fuzz`,
    /// a fixed seed, a few hundred cases per target.
    #[test]
    fn deterministic_pass() {
        let root = crate::repo_root();
        let (total, failures) = pass(&root, TARGETS, 20_261_122, 3000, None);
        assert_eq!(total, 9000);
        assert!(
            failures.is_empty(),
            "{} failures, first: {:?}",
            failures.len(),
            failures.first()
        );
    }

    /// Every seed file of the corpus is read by its target without a failure.
    #[test]
    fn corpus_seeds_pass() {
        let root = crate::repo_root();
        for target in ["exchange", "points"] {
            let corpus = corpus(&root, target);
            assert!(corpus.len() >= 3, "{target} corpus too small");
            for text in &corpus {
                let result = if target == "exchange" {
                    exchange(text)
                } else {
                    points(text)
                };
                assert_eq!(result, Ok(()));
            }
        }
    }

    #[test]
    fn scaling_a_corpus_file_keeps_it_valid() {
        let root = crate::repo_root();
        let text = std::fs::read_to_string(root.join("fuzz/corpus/exchange/cubic.json")).unwrap();
        let mut value: Value = serde_json::from_str(&text).unwrap();
        scale_numbers(&mut value, 1e150);
        let record: CurveRecord = serde_json::from_value(value).unwrap();
        assert!(record.to_bspline::<f64, Vector2<f64>>().is_ok());
    }
}
