//! The work bound: a run may take only so many accepted steps per simulated second.
//!
//! Why: a valid model can need steps so short that a run never ends and never fails. A stiff
//! decay under an explicit method takes steps of 1e-19 s, a chattering `if` steps across its
//! switch forever, a disk of radius 1e-12 m started near θ = π takes about 2e8 steps per
//! simulated second: no step size falls below the solver's floor and no tolerance is broken,
//! the run just does not end, and whatever records its steps grows without bound. The bound
//! turns that into a failure within seconds of work that names itself, the setting that
//! raises it and how short the steps had become. Every front end uses this one bound (a
//! scene's `solver.max_steps_per_s`, `model solve --max-steps-per-s`, Python's
//! `max_steps_per_s=`), so the default, the allowance and the sentence are the same
//! everywhere; only the setting's spelling differs.

use crate::Readable;

/// Accepted steps allowed per simulated second: by simulated time `t` a run that started at
/// `t0` may have taken `steps_per_s × (|t − t0| + ALLOWANCE_S)` steps, the rate over the whole
/// run so far plus an allowance for the short steps of a start (the first step-size guess, an
/// initial transient).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkBound {
    /// Accepted steps allowed per simulated second (finite and > 0).
    pub steps_per_s: f64,
}

impl WorkBound {
    /// The default limit: 1e6 steps per simulated second.
    pub const DEFAULT: WorkBound = WorkBound { steps_per_s: 1e6 };
    /// The simulated time whose steps every run is granted on top of the rate (s): 1e5
    /// steps at the default rate, a few seconds of work.
    pub const ALLOWANCE_S: f64 = 0.1;

    /// The steps allowed once `elapsed` seconds have been simulated (either way in time).
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
    /// (`solver.max_steps_per_s`, `--max-steps-per-s`) and the unit of its time (`" s"` for a
    /// model in seconds, `""` for one whose time has no unit).
    pub fn describe(&self, setting: &str, unit: &str) -> String {
        format!(
            "the work bound was reached at t = {}{unit}: {} steps in {}{unit} of simulated \
             time, more than `{setting}` = {} steps per simulated second allow (with an \
             allowance of {}{unit}); the last step was {}{unit} long: raise `{setting}` to go on",
            Readable(self.t),
            self.steps,
            Readable(self.elapsed),
            Readable(self.bound.steps_per_s),
            WorkBound::ALLOWANCE_S,
            Readable(self.h_last),
        )
    }
}

/// Counts a run's accepted steps against its [`WorkBound`].
#[derive(Clone, Copy, Debug)]
pub struct WorkMeter {
    bound: WorkBound,
    t0: f64,
    steps: u64,
    t: f64,
    h_last: f64,
}

impl WorkMeter {
    /// A meter for a run starting at `t0`.
    pub fn new(bound: WorkBound, t0: f64) -> Self {
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
    pub fn step(&mut self, t0: f64, t1: f64) -> Option<WorkExceeded> {
        self.steps += 1;
        self.t = t1;
        // A length: a run backward in time has steps of negative `t1 - t0`.
        self.h_last = (t1 - t0).abs();
        self.exceeded()
    }

    /// The excess, once the steps so far are over the bound.
    pub fn exceeded(&self) -> Option<WorkExceeded> {
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
        assert_eq!(bound.budget(1.0), 1100.0);
        // A run backwards in time is granted the same.
        assert_eq!(bound.budget(-1.0), 1100.0);
    }

    #[test]
    fn the_meter_fails_at_the_first_step_over_the_budget() {
        let bound = WorkBound {
            steps_per_s: 1000.0,
        };
        let mut meter = WorkMeter::new(bound, 2.0);
        // 100 steps of 1e-6 s are within the allowance; the 101st is not.
        for k in 0..100 {
            let over = meter.step(2.0 + k as f64 * 1e-6, 2.0 + (k + 1) as f64 * 1e-6);
            assert_eq!(over, None, "step {k}");
        }
        let over = meter
            .step(2.0001, 2.000101)
            .expect("the 101st step is over");
        assert_eq!(meter.exceeded(), Some(over));
        assert_eq!(over.steps, 101);
        assert!((over.elapsed - 1.01e-4).abs() < 1e-12, "{}", over.elapsed);
        assert!((over.h_last - 1e-6).abs() < 1e-12, "{}", over.h_last);
        let message = over.describe("--max-steps-per-s", " s");
        assert!(message.contains("work bound"), "{message}");
        assert!(message.contains("raise `--max-steps-per-s`"), "{message}");
        assert!(message.contains("at t = 2.000101 s"), "{message}");
    }

    #[test]
    fn a_nan_time_is_over_the_bound() {
        let mut meter = WorkMeter::new(WorkBound::DEFAULT, 0.0);
        assert!(meter.step(0.0, f64::NAN).is_some());
    }
}
