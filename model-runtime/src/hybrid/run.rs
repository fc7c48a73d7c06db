//! The hybrid driver: [`HybridSolver`] and one run of it, the loop that steps, looks for guard
//! crossings, hands output to the observer and applies transitions. Split from the system's
//! contract (the parent module) so that the contract reads alone.
//!
//! A step's events are handled in time order: an event that passes ([`Transition::Pass`])
//! leaves the step as it is and the search of the step resumes where it found the event (see
//! "Passes" at [`crate::GuardSpec`]); the first event that does anything else cuts the step
//! there and ends the segment.

use super::backward::{error_in_t, outcome_in_t, InCallersTime, Reversed};
use super::chatter::RecentTransitions;
use super::{
    HybridError, HybridOptions, HybridOutcome, HybridResult, HybridSystem, StopReason, Transition,
};
use crate::dense::Interpolant;
use crate::dim::{Dim, Matrix, Vector};
use crate::error::{at, EvalError, InputError, SolveError};
use crate::events::{EventHit, Found, GuardInputs, GuardTracker, Probe, Quiet};
use crate::integrator::Integrator;
use crate::observer::{
    first_sample_from, Observer, ObserverError, Sample, StepView, TransitionKind, TransitionRecord,
};
use crate::stats::Stats;
use crate::stepper::{eval, Rhs, Stepper};
use crate::tolerance::Tolerance;

/// The outcome of a run of `H` in states of size `D`.
type Outcome<D, H> = HybridOutcome<D, <H as HybridSystem<D>>::Mode, <H as HybridSystem<D>>::Stop>;
use std::fmt::Debug;

/// Runs hybrid systems with one stepper and one set of options.
#[derive(Clone, Debug)]
pub struct HybridSolver<S, D: Dim> {
    integrator: Integrator<S, D>,
    options: HybridOptions,
}

impl<S: Stepper<D>, D: Dim> HybridSolver<S, D> {
    /// A solver; the options are checked here.
    pub fn new(stepper: S, tol: Tolerance<D>, options: HybridOptions) -> Result<Self, InputError> {
        if let Some(rate) = options.sample_rate {
            if !rate.is_finite() || rate <= 0.0 {
                return Err(InputError::SampleRate { rate });
            }
        }
        let c = options.chatter;
        if c.max_transitions == 0 || c.window.is_nan() || c.window <= 0.0 {
            return Err(InputError::ChatterLimit {
                max_transitions: c.max_transitions,
                window: c.window,
            });
        }
        Ok(HybridSolver {
            integrator: Integrator::new(stepper, tol, options.step)?,
            options,
        })
    }

    /// The work of the latest [`HybridSolver::run`]: also of one that failed, which reports
    /// its work through this (its error says only what went wrong).
    pub fn stats(&self) -> Stats {
        *self.integrator.stats()
    }

    /// Integrates `sys` from `(t0, y0)` in `mode` until `t_end` or until the transition map
    /// stops, streaming output to `observer`.
    ///
    /// A `t_end` before `t0` runs backward in time: the forward run of the system in
    /// `τ = −t`, which is exact (the same floating-point numbers a method stepping with
    /// `h < 0` computes), everything handed to the system and the observer, and the outcome
    /// or failure, in `t` (see the module `backward` for what holds, and for the meaning of a
    /// guard's direction there: along the run, as SciPy's `solve_ivp` has it).
    pub fn run<H, O>(
        &mut self,
        sys: &mut H,
        mode: H::Mode,
        t0: f64,
        y0: &Vector<D>,
        t_end: f64,
        observer: &mut O,
    ) -> HybridResult<D, H>
    where
        H: HybridSystem<D>,
        O: Observer<D, H::Mode, H::Guard, H::Note>,
    {
        let input = |e: InputError| HybridError::Solve {
            mode,
            error: e.into(),
        };
        if !(t0.is_finite() && t_end.is_finite()) {
            return Err(input(InputError::TimeSpan { t0, t_end }));
        }
        if t_end < t0 {
            let dim = self.integrator.dim();
            let mut reversed = Reversed::new(sys, dim);
            let mut in_t = InCallersTime::new(observer, dim);
            return (self.forward(&mut reversed, mode, -t0, y0, -t_end, &mut in_t))
                .map(outcome_in_t)
                .map_err(error_in_t);
        }
        self.forward(sys, mode, t0, y0, t_end, observer)
    }

    /// [`HybridSolver::run`] for `t_end >= t0`.
    fn forward<H, O>(
        &mut self,
        sys: &mut H,
        mode: H::Mode,
        t0: f64,
        y0: &Vector<D>,
        t_end: f64,
        observer: &mut O,
    ) -> HybridResult<D, H>
    where
        H: HybridSystem<D>,
        O: Observer<D, H::Mode, H::Guard, H::Note>,
    {
        self.integrator.reset_counters();
        let dim = self.integrator.dim();
        let mut run = Run {
            it: &mut self.integrator,
            opts: self.options,
            tracker: GuardTracker::default(),
            values: Vec::new(),
            end_values: Vec::new(),
            inputs: GuardInputs::all(dim),
            recent: RecentTransitions::new(self.options.chatter),
            next_sample: 0,
            t_first: t0,
            mode,
            transitions: 0,
            passes: 0,
        };
        run.go(sys, t0, y0, t_end, observer)
    }
}

/// The system in one mode, as the stepper sees it.
pub(super) struct InMode<'a, H, Md> {
    sys: &'a H,
    mode: Md,
}

impl<D: Dim, H: HybridSystem<D>> Rhs<D> for InMode<'_, H, H::Mode> {
    #[inline]
    fn rhs(&self, t: f64, y: &Vector<D>, dy: &mut Vector<D>) -> Result<(), EvalError> {
        self.sys.rhs(self.mode, t, y, dy)
    }
    #[inline]
    fn jacobian(&self, t: f64, y: &Vector<D>, jac: &mut Matrix<D>) -> Result<(), EvalError> {
        self.sys.jacobian(self.mode, t, y, jac)
    }
}

/// Which search of a step's guards: from its start, or on after an event that passed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Search {
    Step,
    Resume,
}

/// The state of one run.
pub(super) struct Run<'a, S, D: Dim, Md> {
    pub(super) it: &'a mut Integrator<S, D>,
    pub(super) opts: HybridOptions,
    pub(super) tracker: GuardTracker,
    /// Guard values at one point: a segment start, an event.
    pub(super) values: Vec<f64>,
    /// Guard values at the end of the last accepted step.
    pub(super) end_values: Vec<f64>,
    /// What the current mode's guards read (see [`HybridSystem::guard_inputs`]).
    pub(super) inputs: GuardInputs<D>,
    pub(super) recent: RecentTransitions<Md>,
    pub(super) next_sample: u64,
    pub(super) t_first: f64,
    pub(super) mode: Md,
    pub(super) transitions: u64,
    pub(super) passes: u64,
}

impl<S: Stepper<D>, D: Dim, Md: Copy + PartialEq + Debug> Run<'_, S, D, Md> {
    fn solve_err(&self, error: SolveError) -> HybridError<Md> {
        HybridError::Solve {
            mode: self.mode,
            error,
        }
    }

    /// The run's failure for an observer's (in the mode in force when it was handed output).
    fn observer_err(&self, ObserverError { t, source }: ObserverError) -> HybridError<Md> {
        HybridError::Observer {
            mode: self.mode,
            t,
            source,
        }
    }

    pub(super) fn go<H, O>(
        &mut self,
        sys: &mut H,
        t0: f64,
        y0: &Vector<D>,
        t_end: f64,
        obs: &mut O,
    ) -> Result<HybridOutcome<D, Md, H::Stop>, HybridError<Md>>
    where
        H: HybridSystem<D, Mode = Md>,
        O: Observer<D, Md, H::Guard, H::Note>,
    {
        self.start_segment(sys, t0, y0, Quiet::Start)?;
        self.emit_samples(sys, t0, obs)?;
        loop {
            if self.it.t() >= t_end {
                return Ok(self.outcome(StopReason::EndTime));
            }
            let found = self.advance(sys, t_end).map_err(|e| self.solve_err(e))?;
            if let Some(stop) = self.events(sys, found, obs)? {
                return Ok(stop);
            }
            if obs.proceed().is_break() {
                return Ok(self.outcome(StopReason::Observer));
            }
        }
    }

    /// The events of the last accepted step from the first one `found` on, in time order, and
    /// then the end of the step: the outcome if one of them stops the run.
    fn events<H, O>(
        &mut self,
        sys: &mut H,
        mut found: Option<Found>,
        obs: &mut O,
    ) -> Result<Option<Outcome<D, H>>, HybridError<Md>>
    where
        H: HybridSystem<D, Mode = Md>,
        O: Observer<D, Md, H::Guard, H::Note>,
    {
        while let Some(f) = found {
            let hit = self.event_hit(sys, f)?;
            self.emit_samples(sys, hit.t, obs)?;
            if obs.wants_dense() && hit.t > self.it.t_prev() {
                // Built before the transition map runs: the map may change the right-hand
                // side, and the step's output (cut at the event or not) must not see that.
                let m = InMode {
                    sys: &*sys,
                    mode: self.mode,
                };
                self.it.ensure_dense(&m).map_err(|e| self.solve_err(e))?;
            }
            let from = self.mode;
            let transition =
                sys.on_event(from, &hit)
                    .map_err(|source| HybridError::Transition {
                        mode: from,
                        t: hit.t,
                        source,
                    })?;
            let ends_segment = !matches!(transition, Transition::Pass { .. });
            if ends_segment && hit.t > self.it.t_prev() {
                self.report_step(sys, obs, hit.t, Some(&hit.y))?;
            }
            let next = match transition {
                Transition::Pass { note } => {
                    found = self.pass(sys, hit, note, obs)?;
                    continue;
                }
                Transition::Stop(reason) => {
                    let mut out = self.outcome(StopReason::User(reason));
                    out.t = hit.t;
                    out.y = hit.y;
                    return Ok(Some(out));
                }
                Transition::Switch { to, y, note } => (to, TransitionKind::Switch { to }, y, note),
                Transition::Continue { y, note } => (from, TransitionKind::Continue, y, note),
            };
            self.transition(sys, hit, next, obs)?;
            return Ok(None);
        }
        self.finish_step(sys, obs)?;
        Ok(None)
    }

    /// Reports an event that passed and searches the rest of the step after it.
    fn pass<H, O>(
        &mut self,
        sys: &H,
        hit: EventHit<D, H::Guard>,
        note: H::Note,
        obs: &mut O,
    ) -> Result<Option<Found>, HybridError<Md>>
    where
        H: HybridSystem<D, Mode = Md>,
        O: Observer<D, Md, H::Guard, H::Note>,
    {
        self.passes += 1;
        // `values` holds the exact guard values at the event; at the step's end, the guard's
        // value there is its end value too, so the resumed search sees the same sign.
        let value = self.values[hit.index];
        self.tracker.pass(hit.index, hit.t, value);
        if hit.t >= self.it.t() {
            self.end_values[hit.index] = value;
        }
        obs.on_transition(TransitionRecord {
            y_after: hit.y.clone(),
            hit,
            from: self.mode,
            kind: TransitionKind::Pass,
            note,
        })
        .map_err(|e| self.observer_err(e))?;
        self.search(sys, Search::Resume)
            .map_err(|e| self.solve_err(e))
    }

    /// A step without event: samples, observer, projection.
    fn finish_step<H, O>(&mut self, sys: &H, obs: &mut O) -> Result<(), HybridError<Md>>
    where
        H: HybridSystem<D, Mode = Md>,
        O: Observer<D, Md, H::Guard, H::Note>,
    {
        let t1 = self.it.t();
        self.emit_samples(sys, t1, obs)?;
        self.report_step(sys, obs, t1, None)?;
        let mut y = self.it.y().clone();
        if sys.project(self.mode, t1, &mut y) {
            let m = InMode {
                sys,
                mode: self.mode,
            };
            self.it
                .replace_state(&m, &y)
                .map_err(|e| self.solve_err(e))?;
            self.rebase_guards(sys)?;
        }
        Ok(())
    }

    /// The located crossing as an event: exact time, state from the dense output, derivative
    /// and guard value there.
    fn event_hit<H: HybridSystem<D, Mode = Md>>(
        &mut self,
        sys: &H,
        found: Found,
    ) -> Result<EventHit<D, H::Guard>, HybridError<Md>> {
        let m = InMode {
            sys,
            mode: self.mode,
        };
        let dim = self.it.dim();
        let mut y = dim.zeros();
        let mut dy = dim.zeros();
        self.it
            .interpolate(&m, found.t, &mut y)
            .map_err(|e| self.solve_err(e))?;
        eval(&m, found.t, &y, &mut dy, self.it.stats_mut()).map_err(|e| self.solve_err(e))?;
        self.guards_at(sys, found.t, &y, &dy)?;
        self.it.stats_mut().events += 1;
        Ok(EventHit {
            guard: sys.guards(self.mode)[found.index].id,
            index: found.index,
            t: found.t,
            before: found.before,
            y,
            dy,
            value: self.values[found.index],
            direction: found.direction,
        })
    }

    /// Applies a switch or a restart decided at an event: the next mode, what the observer is
    /// told it is, the state the map returned and its note. A fresh segment starts there.
    fn transition<H, O>(
        &mut self,
        sys: &H,
        hit: EventHit<D, H::Guard>,
        (to, kind, mut y_after, note): (Md, TransitionKind<Md>, Vector<D>, H::Note),
        obs: &mut O,
    ) -> Result<(), HybridError<Md>>
    where
        H: HybridSystem<D, Mode = Md>,
        O: Observer<D, Md, H::Guard, H::Note>,
    {
        let from = self.mode;
        if let Some(component) = y_after.as_ref().iter().position(|v| !v.is_finite()) {
            return Err(self.solve_err(SolveError::TransitionState {
                t: hit.t,
                component,
                value: y_after[component],
            }));
        }
        sys.project(to, hit.t, &mut y_after);
        self.transitions += 1;
        self.recent.record(hit.t, from, to)?;
        self.mode = to;
        let quiet = match kind {
            TransitionKind::Continue | TransitionKind::Pass => Quiet::Guard(hit.index),
            TransitionKind::Switch { .. } => Quiet::None,
        };
        // The observer hears of the transition before the next segment starts, so that a
        // restart that fails there still follows the decision that led to it.
        let t = hit.t;
        obs.on_transition(TransitionRecord {
            hit,
            from,
            kind,
            y_after: y_after.clone(),
            note,
        })
        .map_err(|ObserverError { t, source }| HybridError::Observer {
            mode: from,
            t,
            source,
        })?;
        self.start_segment(sys, t, &y_after, quiet)
    }

    /// One accepted step, then the search for the earliest admitted guard crossing in it.
    fn advance<H: HybridSystem<D, Mode = Md>>(
        &mut self,
        sys: &H,
        t_end: f64,
    ) -> Result<Option<Found>, SolveError> {
        let m = InMode {
            sys,
            mode: self.mode,
        };
        self.it.step(&m, t_end)?;
        let t1 = self.it.t();
        self.it.stats_mut().guard_evals += 1;
        sys.guard_values(
            self.mode,
            t1,
            self.it.y(),
            self.it.f(),
            &mut self.end_values,
        )
        .map_err(at(t1))?;
        check_finite(t1, &self.end_values)?;
        let found = self.search(sys, Search::Step)?;
        match self.tracker.violation() {
            Some(guard) if found.is_none() => Err(SolveError::GuardHolds {
                t: t1,
                guard,
                value: self.end_values[guard],
            }),
            _ => Ok(found),
        }
    }

    /// The search for the earliest admitted guard crossing in the last accepted step.
    fn search<H: HybridSystem<D, Mode = Md>>(
        &mut self,
        sys: &H,
        search: Search,
    ) -> Result<Option<Found>, SolveError> {
        let m = InMode {
            sys,
            mode: self.mode,
        };
        let (t0, t1) = (self.it.t_prev(), self.it.t());
        let dim = self.it.dim();
        let it = &mut *self.it;
        let inputs = &self.inputs;
        let mut y = dim.zeros();
        let mut dy = dim.zeros();
        // Estimates fill only the declared inputs: a guard that reads anything else sees NaN.
        let mut y_est = dim.filled(f64::NAN);
        let mut dy_est = dim.filled(f64::NAN);
        let probe_at = |t: f64, probe: Probe, out: &mut [f64]| {
            let (y, dy) = match probe {
                Probe::Exact => {
                    it.interpolate(&m, t, &mut y)?;
                    eval(&m, t, &y, &mut dy, it.stats_mut())?;
                    it.stats_mut().guard_evals += 1;
                    (&y, &dy)
                }
                Probe::Estimate => {
                    it.interpolate_components(
                        &m,
                        t,
                        &inputs.state,
                        &inputs.rates,
                        &mut y_est,
                        &mut dy_est,
                    )?;
                    it.stats_mut().guard_estimates += 1;
                    (&y_est, &dy_est)
                }
            };
            sys.guard_values(m.mode, t, y, dy, out).map_err(at(t))?;
            match probe {
                Probe::Exact => check_finite(t, out),
                // A non-finite estimate only asks for the exact check.
                Probe::Estimate => Ok(()),
            }
        };
        let (checks, end) = (self.opts.guard_checks, &self.end_values);
        match search {
            Search::Step => self.tracker.scan(t0, t1, end, checks, probe_at),
            Search::Resume => self.tracker.resume(end, probe_at),
        }
    }

    /// Starts a segment in the current mode at `(t, y)`: fresh integrator, guards armed
    /// (`quiet`: the guard whose departure from zero must not fire).
    fn start_segment<H: HybridSystem<D, Mode = Md>>(
        &mut self,
        sys: &H,
        t: f64,
        y: &Vector<D>,
        quiet: Quiet,
    ) -> Result<(), HybridError<Md>> {
        let m = InMode {
            sys,
            mode: self.mode,
        };
        let first_step = sys.first_step(self.mode, t, y);
        self.it
            .restart_with_step(&m, t, y, first_step)
            .map_err(|e| self.solve_err(e))?;
        self.inputs =
            (sys.guard_inputs(self.mode)).unwrap_or_else(|| GuardInputs::all(self.it.dim()));
        let specs = sys.guards(self.mode);
        self.values.clear();
        self.values.resize(specs.len(), 0.0);
        self.end_values.clear();
        self.end_values.resize(specs.len(), 0.0);
        let (y, f) = (self.it.y().clone(), self.it.f().clone());
        self.guards_at(sys, t, &y, &f)?;
        let entry = sys.fires_on_entry();
        self.tracker.start(
            specs.iter().map(|s| s.direction),
            &self.values,
            quiet,
            entry,
        );
        Ok(())
    }

    /// After a projection: the guard values at the new end state become the reference.
    fn rebase_guards<H: HybridSystem<D, Mode = Md>>(
        &mut self,
        sys: &H,
    ) -> Result<(), HybridError<Md>> {
        let (t, y, f) = (self.it.t(), self.it.y().clone(), self.it.f().clone());
        self.guards_at(sys, t, &y, &f)?;
        let specs = sys.guards(self.mode);
        self.tracker.start(
            specs.iter().map(|s| s.direction),
            &self.values,
            Quiet::All,
            false,
        );
        Ok(())
    }

    /// Evaluates all guards of the current mode into `self.values`.
    fn guards_at<H: HybridSystem<D, Mode = Md>>(
        &mut self,
        sys: &H,
        t: f64,
        y: &Vector<D>,
        dy: &Vector<D>,
    ) -> Result<(), HybridError<Md>> {
        self.it.stats_mut().guard_evals += 1;
        let r = sys
            .guard_values(self.mode, t, y, dy, &mut self.values)
            .map_err(at(t))
            .and_then(|()| check_finite(t, &self.values));
        r.map_err(|e| self.solve_err(e))
    }

    /// Delivers the samples due up to and including `t_hi`.
    fn emit_samples<H, O>(&mut self, sys: &H, t_hi: f64, obs: &mut O) -> Result<(), HybridError<Md>>
    where
        H: HybridSystem<D, Mode = Md>,
        O: Observer<D, Md, H::Guard, H::Note>,
    {
        let Some(rate) = self.opts.sample_rate else {
            return Ok(());
        };
        let m = InMode {
            sys,
            mode: self.mode,
        };
        let dim = self.it.dim();
        let mut y = dim.zeros();
        loop {
            let ts = self.t_first + self.next_sample as f64 / rate;
            if ts > t_hi {
                return Ok(());
            }
            self.next_sample += 1;
            if !obs.wants_sample(ts) {
                let from = obs.next_wanted_sample(ts);
                self.next_sample = first_sample_from(self.t_first, rate, self.next_sample, from);
                continue;
            }
            self.it
                .interpolate(&m, ts, &mut y)
                .map_err(|e| self.solve_err(e))?;
            obs.on_sample(&Sample {
                t: ts,
                mode: self.mode,
                y: &y,
            })
            .map_err(|e| self.observer_err(e))?;
        }
    }

    /// Hands the last accepted step (cut at `t1` if an event ended it) to the observer.
    fn report_step<H, O>(
        &mut self,
        sys: &H,
        obs: &mut O,
        t1: f64,
        y1: Option<&Vector<D>>,
    ) -> Result<(), HybridError<Md>>
    where
        H: HybridSystem<D, Mode = Md>,
        O: Observer<D, Md, H::Guard, H::Note>,
    {
        if obs.wants_dense() {
            let m = InMode {
                sys,
                mode: self.mode,
            };
            self.it.ensure_dense(&m).map_err(|e| self.solve_err(e))?;
        }
        let it = &*self.it;
        let dense = it.dense();
        let view = StepView {
            mode: self.mode,
            t0: it.t_prev(),
            t1,
            y0: it.y_prev(),
            y1: y1.unwrap_or(it.y()),
            f0: it.f_prev(),
            dense: if obs.wants_dense() {
                dense.as_ref().map(|d| d as &dyn Interpolant<D>)
            } else {
                None
            },
        };
        obs.on_step(&view).map_err(|e| self.observer_err(e))
    }

    fn outcome<R>(&self, stop: StopReason<R>) -> HybridOutcome<D, Md, R> {
        HybridOutcome {
            t: self.it.t(),
            y: self.it.y().clone(),
            mode: self.mode,
            stop,
            stats: *self.it.stats(),
            transitions: self.transitions,
            passes: self.passes,
        }
    }
}

fn check_finite(t: f64, values: &[f64]) -> Result<(), SolveError> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(guard) => Err(SolveError::GuardNotFinite {
            t,
            guard,
            value: values[guard],
        }),
    }
}
