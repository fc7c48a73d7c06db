//! The simulation on a worker thread, its records (the library's, `equations::record`)
//! streamed to the caller.
//!
//! The simulation runs on a worker thread and streams what it observes through a bounded
//! channel, in batches; the caller's thread writes and collects meanwhile (on a second core,
//! the files cost the simulation nothing). The worker asks only for the samples of the
//! [`SamplePlan`], and it stops by itself, through its observer, when the caller raises the
//! stop flag (Ctrl-C); a mode the scene forbids ends the run by itself
//! ([`equations::StopReason::ModeNotAllowed`]).

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::thread::Scope;

use equations::record::{FrictionLaw, Sample, Stop};
use equations::{
    simulate_graph, DiskConfig, DiskObserver, DiskRunner, DiskSample, Engine, Extremum,
    GeneratedModels, InitialState, SimFailure, Trailing, TransitionRecord,
};

use super::model::{with_models, ModelChoice, ModelsTask};
use super::plan::{SamplePlan, WINDOW};
use crate::scene::Scene;
use equations::record::forget_frozen;

/// What the worker sends.
#[derive(Debug)]
pub enum Message {
    /// Samples of the plan, in order.
    Samples(Vec<Sample>),
    /// A mode decision.
    Event(TransitionRecord),
    /// Located extrema, in order.
    Extrema(Vec<Extremum>),
    /// The finely sampled last second of a run that stopped before its plan's last window
    /// (sampled, once the run had ended, from its kept steps).
    LastSecond(Vec<Sample>),
    /// The run ended (boxed: an outcome holds a whole sample).
    Done(Box<Result<Outcome, Failure>>),
}

/// A simulation that failed: why, and the work it did until then.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// The error, in words.
    pub message: String,
    /// Accepted steps until the failure.
    pub steps: u64,
    /// Right-hand-side evaluations until the failure.
    pub rhs_evals: u64,
    /// When it failed (s), if the error says.
    pub t: Option<f64>,
    /// The disk at the end of the last accepted step, if a step was accepted (boxed: a
    /// failure is rare, the record large).
    pub last: Option<Box<Sample>>,
}

impl Failure {
    /// A failure before the simulation started (its models could not be built): no work.
    fn before_start(message: String) -> Self {
        Failure {
            message,
            steps: 0,
            rhs_evals: 0,
            t: None,
            last: None,
        }
    }
}

/// The end of a run: why, the work, and the exact final state.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// Why it ended.
    pub stop: Stop,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations.
    pub rhs_evals: u64,
    /// Largest constraint drift (SI units).
    pub constraint_drift_max: f64,
    /// The exact final state.
    pub last: Sample,
}

/// The outcome of the simulation's run `o`; `config` is the run's.
fn outcome(o: &equations::RunOutcome, config: &DiskConfig, law: FrictionLaw) -> Outcome {
    Outcome {
        stop: Stop::of(o, config.allowed),
        steps: o.stats.steps,
        rhs_evals: o.stats.rhs_evals,
        constraint_drift_max: o.max_drift.max_abs(),
        last: Sample::of(&o.last, law),
    }
}

/// Samples per message: the channel's cost spread over many samples.
const BATCH: usize = 256;

/// Where the simulation's stream goes: a channel to another thread, or straight into a
/// collector on this one.
pub trait Outlet {
    /// Delivers `m`; false once the receiver is gone (the run then stops).
    fn deliver(&mut self, m: Message) -> bool;
}

impl Outlet for SyncSender<Message> {
    fn deliver(&mut self, m: Message) -> bool {
        self.send(m).is_ok()
    }
}

struct ChannelObserver<'a, O> {
    tx: O,
    open: bool,
    plan: SamplePlan,
    batch: Vec<Sample>,
    /// Extrema not yet sent (they go with the next batch of samples).
    extrema: Vec<Extremum>,
    /// Flush the batch once the simulation passes this time, so progress keeps moving even
    /// where samples are sparse.
    flush_at: f64,
    flush_every: f64,
    /// States the models do not integrate: blanked in every sample.
    frozen: Vec<&'static str>,
    /// The friction law, which gives ν where the forces do not.
    law: FrictionLaw,
    stop: &'a AtomicBool,
    /// Whether this observer stopped the run (the caller's stop flag or a closed channel).
    interrupted: bool,
}

impl<O: Outlet> ChannelObserver<'_, O> {
    /// The named record of the simulation's sample, frozen states blanked.
    fn record(&self, sample: &DiskSample) -> Sample {
        let mut s = Sample::of(sample, self.law);
        if !self.frozen.is_empty() {
            forget_frozen(&mut s, &self.frozen);
        }
        s
    }

    fn send(&mut self, m: Message) {
        if self.open && !self.tx.deliver(m) {
            self.open = false;
        }
    }

    fn flush(&mut self) {
        if !self.extrema.is_empty() {
            let extrema = std::mem::take(&mut self.extrema);
            self.send(Message::Extrema(extrema));
        }
        if !self.batch.is_empty() {
            let batch = std::mem::replace(&mut self.batch, Vec::with_capacity(BATCH));
            self.send(Message::Samples(batch));
        }
    }
}

impl<O: Outlet> DiskObserver for ChannelObserver<'_, O> {
    fn wants_sample(&self, t: f64) -> bool {
        self.plan.wants(t)
    }

    fn next_wanted_sample(&self, t: f64) -> f64 {
        self.plan.next_wanted(t)
    }

    fn on_sample(&mut self, sample: &DiskSample) {
        let s = self.record(sample);
        self.batch.push(s);
        if self.batch.len() >= BATCH || s.t >= self.flush_at {
            self.flush_at = s.t + self.flush_every;
            self.flush();
        }
    }

    fn wants_extrema(&self) -> bool {
        true
    }

    fn on_extremum(&mut self, extremum: &Extremum) {
        self.extrema.push(*extremum);
    }

    fn on_transition(&mut self, record: &TransitionRecord) {
        self.flush();
        self.send(Message::Event(*record));
    }

    fn keeps_trailing(&self) -> Option<f64> {
        Some(WINDOW)
    }

    /// A run that ended before its plan's last window gets the last second before its end
    /// from the steps it kept (an interrupted run does not: it was not meant to end there).
    fn on_trailing(&mut self, trailing: &Trailing<'_>) {
        let Some((_, end)) = trailing.span() else {
            return;
        };
        if self.interrupted || self.plan.covers_last_second(end) {
            return;
        }
        let last = self.plan.last_second_before(end);
        let samples = (trailing.grid(end - WINDOW))
            .filter(|&t| last.wants(t))
            .map_while(|t| trailing.sample(t)?.ok())
            .map(|s| self.record(&s))
            .collect();
        self.flush();
        self.send(Message::LastSecond(samples));
    }

    fn proceed(&mut self) -> ControlFlow<()> {
        // A closed channel: the caller has given up on this run (a write error).
        if !self.open || self.stop.load(Ordering::Relaxed) {
            self.interrupted = true;
            return ControlFlow::Break(());
        }
        ControlFlow::Continue(())
    }
}

/// The worker's task: simulate and stream what is observed.
struct Streamed<'a, 'b, O> {
    config: &'a DiskConfig,
    initial: &'a InitialState,
    observer: &'a mut ChannelObserver<'b, O>,
}

impl<O: Outlet> ModelsTask for Streamed<'_, '_, O> {
    type Output = Result<Outcome, Failure>;

    fn run(self, models: &dyn DiskRunner) -> Self::Output {
        let result = models.simulate(self.config, self.initial, self.observer);
        self.concluded(result, FrictionLaw::of(models.params()))
    }
}

impl<O: Outlet> Streamed<'_, '_, O> {
    /// The run on the DSL's mode graph, with the full generated `models`.
    fn on_graph(self, models: &GeneratedModels) -> Result<Outcome, Failure> {
        let result = simulate_graph(models, self.config, self.initial, self.observer);
        self.concluded(result, FrictionLaw::of(&models.params))
    }

    /// The simulation's `result` as the worker reports it.
    fn concluded(
        self,
        result: Result<equations::RunOutcome, SimFailure>,
        law: FrictionLaw,
    ) -> Result<Outcome, Failure> {
        result
            .map(|o| outcome(&o, self.config, law))
            .map_err(|failure| Failure {
                message: failure.to_string(),
                steps: failure.stats.steps,
                rhs_evals: failure.stats.rhs_evals,
                t: failure.error.time(),
                last: failure.last.map(|s| Box::new(self.observer.record(&s))),
            })
    }
}

/// Runs the simulation of `scene` with the models of `choice` on this thread, delivering the
/// samples `plan` keeps and the mode decisions to `outlet`; raising `stop` ends it at its next
/// step.
pub fn simulate_into<O: Outlet>(
    scene: &Scene,
    choice: &ModelChoice,
    plan: SamplePlan,
    stop: &AtomicBool,
    outlet: O,
) -> Result<Outcome, Failure> {
    let config = DiskConfig {
        sample_rate: Some(plan.fine_rate()),
        ..scene.config
    };
    let flush_every = scene.config.t_end / 200.0;
    let mut observer = ChannelObserver {
        tx: outlet,
        open: true,
        plan,
        batch: Vec::with_capacity(BATCH),
        extrema: Vec::new(),
        flush_at: flush_every,
        flush_every,
        frozen: choice.frozen.clone(),
        law: FrictionLaw::of(&scene.params),
        stop,
        interrupted: false,
    };
    let task = Streamed {
        config: &config,
        initial: &scene.initial,
        observer: &mut observer,
    };
    let result = match choice.engine {
        Engine::ModeGraph => GeneratedModels::generated(scene.params, scene.config.chart())
            .map(|models| task.on_graph(&models))
            .map_err(|e| e.to_string()),
        Engine::HandWritten => with_models(choice.model, scene.params, scene.config.chart(), task)
            .map_err(|e| e.to_string()),
    }
    .unwrap_or_else(|e| Err(Failure::before_start(e)));
    observer.flush();
    result.map(|mut o| {
        if observer.interrupted {
            o.stop = o.stop.by_the_user();
        }
        o
    })
}

/// Starts [`simulate_into`] on a worker thread of `scope`, streaming through a bounded
/// channel whose receiving end is returned; the last message is [`Message::Done`].
pub fn start<'scope>(
    scope: &'scope Scope<'scope, '_>,
    scene: &'scope Scene,
    choice: &'scope ModelChoice,
    plan: SamplePlan,
    stop: &'scope AtomicBool,
) -> Receiver<Message> {
    let (tx, rx) = sync_channel(64);
    scope.spawn(move || {
        let result = simulate_into(scene, choice, plan, stop, tx.clone());
        let _ = tx.send(Message::Done(Box::new(result)));
    });
    rx
}
