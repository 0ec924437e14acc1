//! The settings of the barrier method, and what ends a centring step early: the watch on
//! Newton steps that crawl, and the caller's stop rule.

use nalgebra::DVector;

/// Settings of [`minimize`].
///
/// [`minimize`]: super::minimize
#[derive(Clone, Debug)]
pub struct BarrierOptions {
    /// Stop when the duality-gap bound `m / t` is below this.
    pub gap_tolerance: f64,
    /// Stop Newton's method when half the squared Newton decrement is below this times
    /// `1 + |barrier value|`.
    pub newton_tolerance: f64,
    /// Factor by which `t` grows between centring steps (μ).
    pub t_growth: f64,
    /// Initial `t`; `None` chooses `t` so that both terms of the first gradient balance.
    pub t_initial: Option<f64>,
    /// Armijo parameter α ∈ (0, ½).
    pub armijo: f64,
    /// Backtracking factor β ∈ (0, 1).
    pub backtracking: f64,
    /// Newton iterations per centring step.
    pub max_newton_iterations: usize,
    /// Centring steps.
    pub max_outer_iterations: usize,
    /// A centring step also ends when [`STALL_STEPS`] accepted Newton steps in a row each
    /// lowered the barrier objective by less than this times `1 + |value|`: the iterate is
    /// crawling along a flat valley (non-convex problems, variables that barely change the
    /// objective), where more steps move the answer by less than the objective's rounding
    /// at this `t`. `0` turns the rule off (the default).
    pub stall_tolerance: f64,
}

/// Accepted Newton steps in a row that must each gain less than
/// [`BarrierOptions::stall_tolerance`] before a centring step ends as crawling.
pub const STALL_STEPS: usize = 4;

/// Counts consecutive accepted Newton steps of negligible gain (see
/// [`BarrierOptions::stall_tolerance`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct StallWatch {
    tolerance: f64,
    small: usize,
}

impl StallWatch {
    pub(super) fn new(options: &BarrierOptions) -> Self {
        Self {
            tolerance: options.stall_tolerance,
            small: 0,
        }
    }

    /// Records an accepted step from the value `before` to `after`; `true` once
    /// [`STALL_STEPS`] steps in a row gained less than the tolerance.
    pub(super) fn crawled(&mut self, before: f64, after: f64) -> bool {
        if before - after < self.tolerance * (1.0 + after.abs()) {
            self.small += 1;
        } else {
            self.small = 0;
        }
        self.small >= STALL_STEPS
    }
}

/// A condition that ends a centring step early.
pub(crate) type StopRule<'a> = &'a dyn Fn(&DVector<f64>) -> bool;

impl Default for BarrierOptions {
    fn default() -> Self {
        Self {
            gap_tolerance: 1e-8,
            newton_tolerance: 1e-10,
            t_growth: 10.0,
            t_initial: None,
            armijo: 0.01,
            backtracking: 0.5,
            max_newton_iterations: 200,
            max_outer_iterations: 60,
            stall_tolerance: 0.0,
        }
    }
}

#[cfg(test)]
mod stall_tests {
    use super::{BarrierOptions, STALL_STEPS, StallWatch};

    /// The watch fires after exactly `STALL_STEPS` negligible gains in a row, a real gain
    /// resets it, and a zero tolerance never fires.
    #[test]
    fn crawling_is_counted_in_a_row() {
        let options = BarrierOptions {
            stall_tolerance: 1e-5,
            ..BarrierOptions::default()
        };
        let mut watch = StallWatch::new(&options);
        // Gains of 1e-6 relative to a value of 1e3: negligible.
        let mut f = 1e3;
        for step in 1..STALL_STEPS {
            assert!(!watch.crawled(f, f - 1e-3), "step {step}");
            f -= 1e-3;
        }
        // A real gain resets the count.
        assert!(!watch.crawled(f, f - 1.0));
        f -= 1.0;
        for _ in 1..STALL_STEPS {
            assert!(!watch.crawled(f, f - 1e-3));
            f -= 1e-3;
        }
        assert!(watch.crawled(f, f - 1e-3));
        let mut off = StallWatch::new(&BarrierOptions::default());
        assert!((0..100).all(|_| !off.crawled(1.0, 1.0)));
    }
}
