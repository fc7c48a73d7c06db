//! Streaming output: a run hands every accepted step, dense sample, event and transition to an
//! observer as it happens, so a long run never holds its trajectory in memory.

use crate::dense::Interpolant;
use crate::dim::{Const, Dim, Vector};
use crate::error::EvalError;
use crate::events::EventHit;
use std::ops::ControlFlow;

/// Why an observer could not take a run's output: the model failed where the observer
/// evaluated it (a force at a sample, say). The run ends there with
/// [`crate::HybridError::Observer`], carrying this time and error; the work done until then
/// is in [`crate::HybridSolver::stats`].
#[derive(Clone, Debug, PartialEq)]
pub struct ObserverError {
    /// Where the observer evaluated the model, in its own time variable (physical time for an
    /// observer behind [`crate::PhysicalTime`]).
    pub t: f64,
    /// The model's error.
    pub source: EvalError,
}

/// What an observer's hook returns: `Err` ends the run ([`ObserverError`]).
pub type Observed = Result<(), ObserverError>;

/// One accepted step as an observer sees it. If an event cut the step short, `t1`/`y1` are the
/// event time and state (the part of the step after the event is discarded); a step cut to
/// nothing (an event at its very start) is not reported.
pub struct StepView<'a, D: Dim, Md> {
    /// The mode the step was taken in.
    pub mode: Md,
    /// Start time.
    pub t0: f64,
    /// End time.
    pub t1: f64,
    /// State at the start.
    pub y0: &'a Vector<D>,
    /// State at the end.
    pub y1: &'a Vector<D>,
    /// Derivative at the start.
    pub f0: &'a Vector<D>,
    /// The step's interpolant: present when [`Observer::wants_dense`] returns true.
    pub dense: Option<&'a dyn Interpolant<D>>,
}

/// A state sampled at a requested time from the dense output.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<'a, D: Dim, Md> {
    /// Sample time (`t0 + k / rate`).
    pub t: f64,
    /// The mode in force at `t` (at an event time: the mode before the transition).
    pub mode: Md,
    /// The interpolated state.
    pub y: &'a Vector<D>,
}

/// What happened at a transition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TransitionKind<Md> {
    /// The mode changed.
    Switch {
        /// The new mode.
        to: Md,
    },
    /// The same mode restarted (after a state reset).
    Continue,
    /// Nothing changed: the event was only reported ([`crate::Transition::Pass`]); the mode,
    /// the state (`y_after` is the event state) and the integrator's step go on as they were.
    Pass,
}

/// A transition as it was applied (or an event that passed): which event triggered it, the state on both sides, and what
/// the system noted about it ([`crate::HybridSystem::Note`]).
#[derive(Clone, Debug, PartialEq)]
pub struct TransitionRecord<D: Dim, Md, G, Nt = ()> {
    /// The event that triggered it.
    pub hit: EventHit<D, G>,
    /// The mode before.
    pub from: Md,
    /// What happened.
    pub kind: TransitionKind<Md>,
    /// The state the next segment starts from (after the transition map and projection).
    pub y_after: Vector<D>,
    /// The transition map's note, moved here from its [`crate::Transition`].
    pub note: Nt,
}

impl<const N: usize, Md: Copy, G: Copy, Nt: Copy> Copy for TransitionRecord<Const<N>, Md, G, Nt> {}

/// Receives a run's output as it is produced. Every method has an empty default. `Nt` is the
/// system's [`crate::HybridSystem::Note`].
///
/// A hook that cannot take what it is handed (the model failed where the observer evaluated
/// it) returns an [`ObserverError`]: the run ends there with [`crate::HybridError::Observer`],
/// so a failure travels the way every other failure does, with the run's work counted to that
/// point. Stopping for any other reason (an interrupt, a closed output) is
/// [`Observer::proceed`]'s, and ends the run as a stop, not a failure.
pub trait Observer<D: Dim, Md, G, Nt = ()> {
    /// Whether [`StepView::dense`] should be provided (building it may cost extra evaluations,
    /// e.g. three per step for DOP853).
    fn wants_dense(&self) -> bool {
        false
    }
    /// An accepted step.
    fn on_step(&mut self, _step: &StepView<'_, D, Md>) -> Observed {
        Ok(())
    }
    /// Whether the sample due at `t` is wanted (default: every one). Asked before the state
    /// is interpolated, so an observer that needs the grid only in places (a coarse grid for
    /// a file and a fine one in a window, say) pays nothing for the samples it declines.
    fn wants_sample(&self, _t: f64) -> bool {
        true
    }
    /// After [`Observer::wants_sample`] declined the sample due at `t`: a time at or before
    /// the next sample it may want (default `t`: ask about each). The driver skips the grid's
    /// samples before it without asking about each, so an observer that wants a coarse grid
    /// and a fine one in a window is not asked about every point of the fine grid. A bound
    /// too early costs questions; one too late loses samples.
    fn next_wanted_sample(&self, t: f64) -> f64 {
        t
    }
    /// A dense sample at a requested time.
    fn on_sample(&mut self, _sample: &Sample<'_, D, Md>) -> Observed {
        Ok(())
    }
    /// Asked after every accepted step and every transition: [`ControlFlow::Break`] ends the
    /// run there, with everything delivered so far (an interrupt, a time budget, a state the
    /// caller forbids). The default never stops.
    fn proceed(&mut self) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    /// A transition, handed over by value (the event that caused it and the system's note are
    /// in the record). Called before the next segment starts.
    fn on_transition(&mut self, _record: TransitionRecord<D, Md, G, Nt>) -> Observed {
        Ok(())
    }
}

/// The observer that ignores everything.
impl<D: Dim, Md, G, Nt> Observer<D, Md, G, Nt> for () {}

/// An observer that keeps samples and transitions in memory: convenient for tests and short
/// runs, not for long ones.
#[derive(Clone, Debug, Default)]
pub struct Recorder<D: Dim, Md, G, Nt = ()> {
    /// Samples `(t, mode, y)`.
    pub samples: Vec<(f64, Md, Vector<D>)>,
    /// Transitions in order.
    pub transitions: Vec<TransitionRecord<D, Md, G, Nt>>,
    /// Number of accepted steps seen.
    pub steps: u64,
}

impl<D: Dim, Md, G, Nt> Recorder<D, Md, G, Nt> {
    /// An empty recorder.
    pub fn new() -> Self {
        Recorder {
            samples: Vec::new(),
            transitions: Vec::new(),
            steps: 0,
        }
    }
}

impl<D: Dim, Md: Copy, G, Nt> Observer<D, Md, G, Nt> for Recorder<D, Md, G, Nt> {
    fn on_step(&mut self, _step: &StepView<'_, D, Md>) -> Observed {
        self.steps += 1;
        Ok(())
    }
    fn on_sample(&mut self, s: &Sample<'_, D, Md>) -> Observed {
        self.samples.push((s.t, s.mode, s.y.clone()));
        Ok(())
    }
    fn on_transition(&mut self, r: TransitionRecord<D, Md, G, Nt>) -> Observed {
        self.transitions.push(r);
        Ok(())
    }
}

/// The first index `k ≥ next` of the sample grid `t_first + k / rate` whose time is at or
/// after `from` (`u64::MAX` when none is: `from` infinite or past the grid's reach): where a
/// driver resumes after [`Observer::next_wanted_sample`] said `from`. The grid's times are
/// computed as the drivers compute them, so no sample at or after `from` is skipped.
pub(crate) fn first_sample_from(t_first: f64, rate: f64, next: u64, from: f64) -> u64 {
    let time = |k: u64| t_first + k as f64 / rate;
    // A NaN bound skips nothing; one past the grid's reach skips everything.
    if from.is_nan() || from <= time(next) {
        return next;
    }
    let guess = ((from - t_first) * rate).floor();
    if guess >= 1e15 {
        return u64::MAX;
    }
    let mut k = (guess as u64).max(next);
    while k > next && time(k - 1) >= from {
        k -= 1;
    }
    while time(k) < from {
        k += 1;
    }
    k
}

#[cfg(test)]
mod tests {
    use super::first_sample_from;

    #[test]
    fn the_first_sample_from_a_time_is_the_first_at_or_after_it() {
        // Grids whose times round (a rate of 3 and of 20 kHz, a start off zero), bounds on
        // grid points, between them and an ulp either side of one.
        for (t_first, rate) in [(0.0, 3.0), (0.1, 20_000.0), (-2.5, 7.0)] {
            let time = |k: u64| t_first + k as f64 / rate;
            for next in [0u64, 5, 40] {
                for j in 0..200u64 {
                    let on = time(j);
                    for from in [on, on.next_down(), on.next_up(), on + 0.37 / rate] {
                        let k = first_sample_from(t_first, rate, next, from);
                        assert!(k >= next);
                        assert!(time(k) >= from || k == next, "{from}: {k}");
                        assert!(
                            k == next || time(k - 1) < from,
                            "{from}: {k} is not the first"
                        );
                    }
                }
            }
        }
        assert_eq!(first_sample_from(0.0, 10.0, 3, f64::INFINITY), u64::MAX);
        assert_eq!(first_sample_from(0.0, 10.0, 3, f64::NAN), 3);
    }
}
