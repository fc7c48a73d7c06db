//! The work bound: a run may take only so many steps per simulated second.
//!
//! Why: a valid scene can need steps so short that it would run for hours without ever
//! failing. A disk of radius 1e-12 m started near θ = π takes about 2e8 steps per simulated
//! second (its time scale `sqrt(a/g)` is 3e-7 s): no step size falls below the solver's
//! floor, no tolerance is broken, the one-second run just never ends. The bound turns that
//! into a failure within seconds of work that names itself, the key that raises it and how
//! short the steps had become. The paper's 100 s scene takes about 3e3 steps per simulated
//! second (at most 4150 in any one of its seconds), so the default leaves it a margin of 240.

use model_runtime::Readable;
use std::fmt;

/// The limit on the steps of a run per simulated second, in the scene as
/// `solver.max_steps_per_s` ([`WorkBound::KEY`]).
///
/// By simulated time `t` a run that started at `t0` may have taken
/// `steps_per_s × (t − t0 + ALLOWANCE_S)` accepted steps: the rate over the whole run so far,
/// plus an allowance for the short steps of a start (the first step-size guess, an initial
/// transient). A run over it fails with [`crate::SimError::WorkBound`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkBound {
    /// Accepted steps allowed per simulated second (finite and > 0).
    pub steps_per_s: f64,
}

impl WorkBound {
    /// The scene key of the limit.
    pub const KEY: &'static str = "solver.max_steps_per_s";
    /// The default limit: 1e6 steps per simulated second.
    pub const DEFAULT: WorkBound = WorkBound { steps_per_s: 1e6 };
    /// The simulated time whose steps every run is granted on top of the rate (s): 1e5
    /// steps at the default rate, a few seconds of work.
    pub const ALLOWANCE_S: f64 = 0.1;

    /// The steps allowed once `elapsed` seconds have been simulated.
    pub fn budget(self, elapsed: f64) -> f64 {
        self.steps_per_s * (elapsed.max(0.0) + Self::ALLOWANCE_S)
    }
}

impl Default for WorkBound {
    fn default() -> Self {
        WorkBound::DEFAULT
    }
}

/// Where and how a run went over its [`WorkBound`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkExceeded {
    /// The bound that was reached.
    pub bound: WorkBound,
    /// Simulated time when it was reached (s).
    pub t: f64,
    /// Simulated time since the start (s).
    pub elapsed: f64,
    /// Accepted steps until then.
    pub steps: u64,
    /// The length of the last step (s of simulated time).
    pub h_last: f64,
}

impl fmt::Display for WorkExceeded {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the work bound was reached at t = {} s: {} steps in {} s of simulated time, more \
             than `{}` = {} steps per simulated second allow (with an allowance of {} s); \
             the last step was {} s long: raise `{}` to go on",
            Readable(self.t),
            self.steps,
            Readable(self.elapsed),
            WorkBound::KEY,
            Readable(self.bound.steps_per_s),
            WorkBound::ALLOWANCE_S,
            Readable(self.h_last),
            WorkBound::KEY,
        )
    }
}

impl std::error::Error for WorkExceeded {}

/// Counts a run's accepted steps against its [`WorkBound`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct WorkMeter {
    bound: WorkBound,
    t0: f64,
    steps: u64,
    t: f64,
    h_last: f64,
}

impl WorkMeter {
    /// A meter for a run starting at `t0`.
    pub(crate) fn new(bound: WorkBound, t0: f64) -> Self {
        WorkMeter {
            bound,
            t0,
            steps: 0,
            t: t0,
            h_last: 0.0,
        }
    }

    /// An accepted step from `t0` to `t1` (physical time).
    pub(crate) fn step(&mut self, t0: f64, t1: f64) {
        self.steps += 1;
        self.t = t1;
        self.h_last = t1 - t0;
    }

    /// The excess, once the steps so far are over the bound.
    pub(crate) fn exceeded(&self) -> Option<WorkExceeded> {
        let elapsed = self.t - self.t0;
        // `!(<=)`: a NaN time is over the bound too, not a way around it.
        let within = self.steps as f64 <= self.bound.budget(elapsed);
        (!within).then_some(WorkExceeded {
            bound: self.bound,
            t: self.t,
            elapsed,
            steps: self.steps,
            h_last: self.h_last,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_budget_grows_with_simulated_time_after_an_allowance() {
        let bound = WorkBound {
            steps_per_s: 1000.0,
        };
        assert_eq!(bound.budget(0.0), 100.0);
        assert_eq!(bound.budget(-1.0), 100.0);
        assert_eq!(bound.budget(1.0), 1100.0);
    }

    #[test]
    fn the_meter_fails_at_the_first_step_over_the_budget() {
        let bound = WorkBound {
            steps_per_s: 1000.0,
        };
        let mut meter = WorkMeter::new(bound, 2.0);
        // 100 steps of 1e-6 s are within the allowance; the 101st is not.
        for k in 0..100 {
            meter.step(2.0 + k as f64 * 1e-6, 2.0 + (k + 1) as f64 * 1e-6);
            assert_eq!(meter.exceeded(), None, "step {k}");
        }
        meter.step(2.0001, 2.000101);
        let over = meter.exceeded().unwrap();
        assert_eq!(over.steps, 101);
        assert!((over.elapsed - 1.01e-4).abs() < 1e-12, "{}", over.elapsed);
        assert!((over.h_last - 1e-6).abs() < 1e-12, "{}", over.h_last);
        let message = over.to_string();
        assert!(message.contains("work bound"), "{message}");
        assert!(message.contains("solver.max_steps_per_s"), "{message}");
    }

    #[test]
    fn steps_at_the_bound_s_rate_never_exceed_it() {
        let bound = WorkBound { steps_per_s: 10.0 };
        let mut meter = WorkMeter::new(bound, 0.0);
        for k in 0..10_000 {
            meter.step(k as f64 * 0.1, (k + 1) as f64 * 0.1);
            assert_eq!(meter.exceeded(), None, "step {k}");
        }
    }
}
