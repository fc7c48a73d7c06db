//! One call from a switched model to what a person asks of it: every event by name, with its
//! time and the state there, the samples, and how the run ended — the switched counterpart of
//! [`crate::Problem`].
//!
//! Each transition the driver applies becomes an [`EventRecord`]: an event that fired (with
//! the state just before it and the state the run continues from), or an accumulation of an
//! event's resets, reported at its extrapolated accumulation point `t_inf` (where, say, a ball
//! comes to rest) rather than at the firing that revealed it.

use crate::accumulation::AccumulationRule;
use crate::dim::{Dim, Vector};
use crate::hybrid::run::HybridSolver;
use crate::hybrid::{HybridError, HybridOptions, StopReason};
use crate::observer::{Observed, Observer, Sample, StepView, TransitionRecord};
use crate::stats::Stats;
use crate::stepper::Stepper;
use crate::switched::graph::{EventId, ModeGraph, ModeId};
use crate::switched::outcome::{SwitchedNote, SwitchedStop};
use crate::switched::{Switched, SwitchedModel};
use crate::tolerance::Tolerance;

/// What happened at an event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fired {
    /// A record-only event passed; nothing changed.
    Recorded,
    /// The event applied its reset and the run went on (in its target mode).
    Reset,
    /// The event's resets accumulated; its accumulation reset applied, the run went on in the
    /// accumulation's mode.
    Accumulated,
    /// A terminal event ended the run.
    Stopped,
    /// The event's resets accumulated with no rule for it: the run ended.
    AccumulatedStop,
}

/// An event a transition reports: which, what it did, and its one time (the crossing's, or
/// for an accumulation the extrapolated point).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Firing {
    /// The event.
    pub event: EventId,
    /// What it did.
    pub fired: Fired,
    /// When.
    pub t: f64,
}

impl Firing {
    /// The event of a transition with `note`, whose guard was hit at `hit_t`.
    pub fn of(note: SwitchedNote, hit_t: f64) -> Self {
        let (event, fired, t) = match note {
            SwitchedNote::Recorded(event) => (event, Fired::Recorded, hit_t),
            SwitchedNote::Reset(event) => (event, Fired::Reset, hit_t),
            SwitchedNote::Accumulated {
                event,
                accumulation,
            } => (event, Fired::Accumulated, accumulation.t_inf),
        };
        Firing { event, fired, t }
    }
}

/// One event of a run, by name.
#[derive(Clone, Debug, PartialEq)]
pub struct EventRecord<D: Dim> {
    /// The event's name (as declared in its mode).
    pub event: String,
    /// The mode it fired in.
    pub mode: String,
    /// What it did.
    pub fired: Fired,
    /// When: the located crossing, or for an accumulation its extrapolated point `t_inf`.
    pub t: f64,
    /// The state at the event, before any reset.
    pub y: Vector<D>,
    /// The state the run went on from (equal to `y` for a record or a stop).
    pub y_after: Vector<D>,
}

/// The outcome of [`run_switched`].
#[derive(Clone, Debug)]
pub struct SwitchedRun<D: Dim> {
    /// Every event, in time order.
    pub events: Vec<EventRecord<D>>,
    /// `(t, mode name, state)` at every sample (`options.sample_rate`), or at every step end
    /// (and the start) when no rate is set.
    pub samples: Vec<(f64, String, Vector<D>)>,
    /// Final time: where the run ended, the time of the terminal event's record (for an
    /// accumulation without a rule, its accumulation point).
    pub t: f64,
    /// Final state.
    pub y: Vector<D>,
    /// Final mode's name.
    pub mode: String,
    /// The terminal event, if one ended the run (`None`: the end time).
    pub stopped_by: Option<String>,
    /// Work done.
    pub stats: Stats,
}

impl<D: Dim> SwitchedRun<D> {
    /// The times of the events named `event` that did `fired`.
    pub fn times(&self, event: &str, fired: Fired) -> Vec<f64> {
        (self.events.iter())
            .filter(|e| e.event == event && e.fired == fired)
            .map(|e| e.t)
            .collect()
    }
}

/// A run that failed: why (with its modes named), and the work it did until then.
#[derive(Clone, Debug, PartialEq)]
pub struct SwitchedFailure<D: Dim> {
    /// What went wrong (boxed: a failure is rare, and the run's result stays small).
    pub error: Box<HybridError<String>>,
    /// The events met before the failure, in time order.
    pub events: Vec<EventRecord<D>>,
    /// The steps accepted before the failure.
    pub steps: u64,
}

impl<D: Dim> std::fmt::Display for SwitchedFailure<D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} (after {} steps and {} events)",
            self.error,
            self.steps,
            self.events.len()
        )
    }
}

impl<D: Dim> std::error::Error for SwitchedFailure<D> {}

/// Runs `model` from `(t0, y0)` in its first mode to `t_end` with `stepper`, the tolerances
/// and options given and the [`AccumulationRule`] for the run's span
/// ([`AccumulationRule::for_span`]), forward in time only (a `t_end` before `t0` is an
/// [`crate::InputError::ForwardOnly`]); a failure names the mode and keeps
/// the work done.
pub fn run_switched<D: Dim, M: SwitchedModel<D>, S: Stepper<D>>(
    model: M,
    stepper: S,
    tolerance: Tolerance<D>,
    options: HybridOptions,
    (t0, y0): (f64, Vector<D>),
    t_end: f64,
) -> Result<SwitchedRun<D>, SwitchedFailure<D>> {
    let graph = model.graph().clone();
    let start = graph.first();
    let input = |error: crate::error::InputError| SwitchedFailure {
        error: Box::new(HybridError::Solve {
            mode: graph.mode_name(start).to_string(),
            error: error.into(),
        }),
        events: Vec::new(),
        steps: 0,
    };
    if t_end < t0 {
        return Err(input(crate::error::InputError::ForwardOnly { t0, t_end }));
    }
    let rule = AccumulationRule::for_span(t_end - t0);
    let mut system = Switched::new(model, rule).map_err(input)?;
    let mut solver = HybridSolver::new(stepper, tolerance, options).map_err(input)?;
    let mut collector = Collector {
        graph: &graph,
        every_step: options.sample_rate.is_none(),
        events: Vec::new(),
        samples: Vec::new(),
        steps: 0,
    };
    let outcome = match solver.run(&mut system, start, t0, &y0, t_end, &mut collector) {
        Ok(outcome) => outcome,
        Err(error) => {
            return Err(SwitchedFailure {
                error: Box::new(name_modes(&graph, error)),
                events: collector.events,
                steps: collector.steps,
            })
        }
    };
    let mut events = collector.events;
    let samples = collector.samples;
    // One time per event: a run stopped by an accumulation ends at the accumulation point its
    // event is reported at (the state is the last firing's, within the rule's tail of it).
    let mut t_final = outcome.t;
    let stopped_by = match outcome.stop {
        StopReason::User(stop) => {
            let (fired, t) = match stop {
                SwitchedStop::Event { t, .. } => (Fired::Stopped, t),
                SwitchedStop::Accumulation { t_inf, .. } => {
                    t_final = t_inf;
                    (Fired::AccumulatedStop, t_inf)
                }
            };
            let event = stop.event();
            let name = graph.mode(event.mode).events[event.event].name.clone();
            events.push(EventRecord {
                event: name.clone(),
                mode: graph.mode_name(event.mode).to_string(),
                fired,
                t,
                y: outcome.y.clone(),
                y_after: outcome.y.clone(),
            });
            Some(name)
        }
        StopReason::EndTime | StopReason::Observer => None,
    };
    Ok(SwitchedRun {
        events,
        samples,
        t: t_final,
        y: outcome.y,
        mode: graph.mode_name(outcome.mode).to_string(),
        stopped_by,
        stats: outcome.stats,
    })
}

/// A hybrid error with its modes named.
pub fn name_modes(graph: &ModeGraph, error: HybridError<ModeId>) -> HybridError<String> {
    error.map_mode(|mode| graph.mode_name(mode).to_string())
}

struct Collector<'g, D: Dim> {
    graph: &'g ModeGraph,
    every_step: bool,
    events: Vec<EventRecord<D>>,
    samples: Vec<(f64, String, Vector<D>)>,
    steps: u64,
}

impl<D: Dim> Observer<D, ModeId, EventId, SwitchedNote> for Collector<'_, D> {
    fn on_step(&mut self, step: &StepView<'_, D, ModeId>) -> Observed {
        self.steps += 1;
        if !self.every_step {
            return Ok(());
        }
        let mode = self.graph.mode_name(step.mode);
        if self.samples.last().is_none_or(|(t, ..)| *t < step.t0) {
            self.samples
                .push((step.t0, mode.to_string(), step.y0.clone()));
        }
        self.samples
            .push((step.t1, mode.to_string(), step.y1.clone()));
        Ok(())
    }

    fn on_sample(&mut self, sample: &Sample<'_, D, ModeId>) -> Observed {
        let mode = self.graph.mode_name(sample.mode).to_string();
        self.samples.push((sample.t, mode, sample.y.clone()));
        Ok(())
    }

    fn on_transition(
        &mut self,
        record: TransitionRecord<D, ModeId, EventId, SwitchedNote>,
    ) -> Observed {
        let Firing { event, fired, t } = Firing::of(record.note, record.hit.t);
        self.events.push(EventRecord {
            event: self.graph.mode(event.mode).events[event.event].name.clone(),
            mode: self.graph.mode_name(record.from).to_string(),
            fired,
            t,
            y: record.hit.y,
            y_after: record.y_after,
        });
        Ok(())
    }
}
