//! libFuzzer target `operations`: see `xtask/src/fuzz_oracles.rs` (`cargo xtask fuzz --coverage`).
#![no_main]

#[allow(dead_code)]
#[path = "../../xtask/src/mutate.rs"]
mod mutate;

#[allow(dead_code)]
#[path = "../../xtask/src/fuzz_oracles.rs"]
mod fuzz_oracles;

/// An oracle's `Err` (a non-finite number in an `Ok` result, …) is a crash.
fn check(outcome: Result<(), String>) {
    if let Err(message) = outcome {
        panic!("{message}");
    }
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let mut rng = mutate::Rng::from_bytes(data);
    check(fuzz_oracles::operations(&mut rng));
});
