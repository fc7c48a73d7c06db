//! The work bound of a solve: a run may take only so many steps per simulated second.
//!
//! Why: a model can need steps so short that a run never ends and never fails (a stiff decay
//! under an explicit method takes steps of 1e-19 s; a chattering `if` steps across its
//! switch forever), and memory grows with every recorded step. The bound turns that into a
//! failure within seconds of work that names itself and how short the steps had become,
//! with what was computed until then kept. It is the same bound as a scene's
//! (`solver.max_steps_per_s` of `eulerdisk run`): the same default, the same allowance for
//! the short steps of a start, the same sentence.

use model_runtime::Readable;
use std::fmt;

/// Accepted steps allowed per simulated second: by time `t` a run that started at `t0` may
/// have taken `steps_per_s × (|t − t0| + ALLOWANCE_S)` steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkBound {
    /// Accepted steps allowed per simulated second (finite and > 0).
    pub steps_per_s: f64,
}

impl WorkBound {
    /// The default limit: 1e6 steps per simulated second, as a scene's.
    pub const DEFAULT: WorkBound = WorkBound { steps_per_s: 1e6 };
    /// The simulated time whose steps every run is granted on top of the rate (s).
    pub const ALLOWANCE_S: f64 = 0.1;

    /// The steps allowed once `elapsed` seconds have been simulated.
    pub fn budget(self, elapsed: f64) -> f64 {
        self.steps_per_s * (elapsed.abs() + Self::ALLOWANCE_S)
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
    /// Simulated time when it was reached.
    pub t: f64,
    /// Simulated time since the start.
    pub elapsed: f64,
    /// Accepted steps until then.
    pub steps: u64,
    /// The length of the last step.
    pub h_last: f64,
}

impl WorkExceeded {
    /// The sentence, naming the setting that raises the bound as the caller spells it
    /// (`--max-steps-per-s`, `max_steps_per_s=`).
    pub fn describe(&self, setting: &str) -> String {
        format!(
            "the work bound was reached at t = {}: {} steps in {} of simulated time, more \
             than `{setting}` = {} steps per simulated second allow (with an allowance of {}); \
             the last step was {} long: raise `{setting}` to go on",
            Readable(self.t),
            self.steps,
            Readable(self.elapsed),
            Readable(self.bound.steps_per_s),
            WorkBound::ALLOWANCE_S,
            Readable(self.h_last),
        )
    }
}

impl fmt::Display for WorkExceeded {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.describe("max_steps_per_s"))
    }
}

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

    /// An accepted step from `t0` to `t1`; the excess, once the steps so far are over the
    /// bound.
    pub(crate) fn step(&mut self, t0: f64, t1: f64) -> Option<WorkExceeded> {
        self.steps += 1;
        self.t = t1;
        self.h_last = t1 - t0;
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
    fn the_meter_fails_once_the_steps_outrun_the_rate() {
        let mut meter = WorkMeter::new(WorkBound { steps_per_s: 10.0 }, 0.0);
        // One step of 0.1 s: within 10 × (0.1 + 0.1) = 2 steps.
        assert!(meter.step(0.0, 0.1).is_none());
        assert!(meter.step(0.1, 0.1 + 1e-9).is_none());
        let over = meter
            .step(0.1 + 1e-9, 0.1 + 2e-9)
            .expect("a third step is over");
        assert_eq!(over.steps, 3);
        let message = over.describe("--max-steps-per-s");
        assert!(message.contains("raise `--max-steps-per-s`"), "{message}");
        // A NaN time is over the bound.
        let mut meter = WorkMeter::new(WorkBound::DEFAULT, 0.0);
        assert!(meter.step(0.0, f64::NAN).is_some());
    }
}
