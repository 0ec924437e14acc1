//! Allocation counting for tests that check that an iteration allocates nothing: the test
//! binary installs `stats_alloc`'s instrumented allocator as its global allocator (a counting
//! allocator needs `unsafe impl GlobalAlloc`, which the workspace forbids: the crate holds
//! it) and measures with [`allocations`].

use stats_alloc::{Region, StatsAlloc};
use std::alloc::System;
use std::sync::Mutex;

/// One measurement at a time in a test binary (the counters are global): tests that count
/// hold this lock.
pub static SERIAL: Mutex<()> = Mutex::new(());

/// The allocations made while `f` runs, counted by `global` (the test binary's global
/// allocator): the least of three runs (the test harness's own threads may allocate
/// meanwhile; a deterministic computation allocates the same every time), and `f`'s last
/// result.
pub fn allocations<R>(global: &'static StatsAlloc<System>, f: impl Fn() -> R) -> (usize, R) {
    let mut least = usize::MAX;
    let mut out = None;
    for _ in 0..3 {
        let region = Region::new(global);
        let result = f();
        least = least.min(region.change().allocations);
        out = Some(result);
    }
    (least, out.expect("ran three times"))
}
