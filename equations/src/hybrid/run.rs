//! One simulation from start to stop: checking the inputs, deciding the initial mode, driving
//! the disk's system, and turning the driver's raw phase states into disk samples for the
//! caller. The system is either engine of the disk ([`DiskEngine`]): the hand-written one
//! ([`simulate`]) or the DSL's mode graph ([`simulate_graph`]); the stages below serve both,
//! so that the observer cannot tell them apart but by their round-off.
//!
//! A run goes in four stages, each one function: `begin` decides where the driver starts (or
//! that the run ends before a step); `drive` (module `drive`) integrates in the configured time
//! variable, with the `Adaptor` turning the driver's phases into disk output and failing, as
//! the driver's observer, where the models cannot evaluate that output; `Adaptor::close` hands
//! out what the run's end owes the observer; `conclude` turns the driver's outcome into the
//! disk's, converting each error once.

use super::drive::{drive, Drive, Driven, Failed, Start};
use super::extrema::Scanner;
use super::graph::{DiskPhase, Engine, GraphSystem};
use super::models::{DiskModels, GeneratedModels};
use super::switching::disk;
use super::system::{DiskNote, DiskSystem, Entry, Halt, Halted, Ledger, Phase};
use super::trailing::{StepRing, Trailing};
use super::{
    DiskObserver, DiskSample, RunOutcome, SimError, SimFailure, StopReason, TransitionRecord,
    Trigger,
};
use crate::config::{AllowedModes, DiskConfig};
use crate::modes::{ContactForce, Mode, PhysicalState, Slip, DIM};
use crate::params::DiskParams;
use crate::start::InitialState;
use model_runtime::{
    Const, EvalError, HybridOutcome, HybridSystem, Model, Observed, Observer, ObserverError,
    Sample, Stats, StepView, TimeScale,
};
use model_runtime::{WorkExceeded, WorkMeter};

/// Runs the hybrid disk from `initial` until `config.t_end` or a stop, streaming samples and
/// mode decisions to `observer`.
///
/// The settings and the start are checked first ([`DiskConfig::issues`],
/// [`InitialState::issues`]): every broken rule comes back in [`SimError::Invalid`]; a failure
/// comes back with the work done until then ([`SimFailure`]). A sliding
/// start whose slip exceeds the stick threshold starts sliding with that slip; otherwise the
/// state is put on the rolling constraints and starts rolling if static friction can hold it,
/// or sliding from zero slip in the consistent direction if it cannot (reported as a
/// transition with [`Trigger::InitialFriction`], not counted in [`RunOutcome::transitions`]).
/// A decision for a mode `config.allowed` does not list ends the run there with
/// [`StopReason::ModeNotAllowed`].
pub fn simulate<R: Model<DIM>, S: Model<DIM>, O: DiskObserver + ?Sized>(
    models: &DiskModels<R, S>,
    config: &DiskConfig,
    initial: &InitialState,
    observer: &mut O,
) -> Result<RunOutcome, SimFailure> {
    validate(models, config, initial)?;
    let mut system = DiskSystem::new(models, config);
    let mut gate = Gate {
        allowed: config.allowed,
        forbidden: None,
    };
    let entry = match begin(&mut system, models, config, initial, &mut gate, observer)? {
        Begun::Running(entry) => entry,
        Begun::Stopped(outcome) => return Ok(*outcome),
    };
    let run = Run {
        models,
        config,
        initial,
    };
    run_on(
        &mut system,
        &PHASES,
        entry.phase,
        entry,
        run,
        gate,
        observer,
    )
}

/// A set of the disk's models, run with an observer behind a trait object.
///
/// [`simulate`] is generic in the models and in the observer, so a crate that calls it with
/// three observers compiles the engine (integrators, guards, extrema) three times for each set
/// of models. Through `&dyn DiskRunner` the observer is a trait object (`O = dyn
/// DiskObserver`): the engine is compiled once per set of models, whatever observes it, and a
/// front end holds any of the sets as one type. The hot path, the models' evaluations, is not
/// behind an object; a caller that wants the observer's calls inlined too (a benchmark with
/// `()`) calls [`simulate`] with its own type.
pub trait DiskRunner {
    /// The disk's parameters the models were built for.
    fn params(&self) -> &DiskParams;

    /// [`simulate`] with these models.
    fn simulate(
        &self,
        config: &DiskConfig,
        initial: &InitialState,
        observer: &mut dyn DiskObserver,
    ) -> Result<RunOutcome, SimFailure>;
}

impl<R: Model<DIM>, S: Model<DIM>> DiskRunner for DiskModels<R, S> {
    fn params(&self) -> &DiskParams {
        &self.params
    }

    fn simulate(
        &self,
        config: &DiskConfig,
        initial: &InitialState,
        observer: &mut dyn DiskObserver,
    ) -> Result<RunOutcome, SimFailure> {
        simulate(self, config, initial, observer)
    }
}

/// Runs the disk's mode graph (module `switching`) from `initial` until `config.t_end` or a
/// stop, streaming to `observer` what [`simulate`] streams: the same samples, steps, extrema,
/// trailing steps and decision records, the same gate of allowed modes and work bound, the
/// same outcome (the decisions counted as the hand-written run counts them, its largest
/// constraint drift). `models` evaluate the output (forces, energy) as in [`simulate`]; the
/// start is decided as there.
///
/// The graph models the disk in still air, in the Cartesian slip chart, with DOP853 or DP5
/// and no projection after steps: other settings are refused by key in
/// [`SimError::Invalid`] ([`Engine::for_run`] says which engine a run can use).
///
/// Not generic: its one set of models is this crate's, so the graph's engine is compiled
/// here, once, with the observer behind the object (a handful of calls a step), and no crate
/// that runs it compiles it again.
pub fn simulate_graph(
    models: &GeneratedModels,
    config: &DiskConfig,
    initial: &InitialState,
    observer: &mut dyn DiskObserver,
) -> Result<RunOutcome, SimFailure> {
    validate(models, config, initial)?;
    let refused = Engine::graph_refusals(&models.params, config, models.chart);
    if !refused.is_empty() {
        return Err(SimError::Invalid { issues: refused }.into());
    }
    // The start is decided by the hand-written rules (it is no event of the graph).
    let mut decider = DiskSystem::new(models, config);
    let mut gate = Gate {
        allowed: config.allowed,
        forbidden: None,
    };
    let entry = match begin(&mut decider, models, config, initial, &mut gate, observer)? {
        Begun::Running(entry) => entry,
        Begun::Stopped(outcome) => return Ok(*outcome),
    };
    let mut model = disk::Model::for_run(&models.params, config);
    let first = match entry.phase {
        Phase::Rolling => disk::mode::rolling,
        Phase::Sliding => disk::mode::sliding,
        Phase::Bridge => model.hold(&decider.bridge),
    };
    let mut system = GraphSystem::new(model, config).map_err(|e| SimError::Solve {
        mode: entry.phase.mode(),
        error: e.into(),
    })?;
    let modes = system.modes();
    let run = Run {
        models,
        config,
        initial,
    };
    run_on(
        &mut system,
        &modes,
        modes[first],
        entry,
        run,
        gate,
        observer,
    )
}

/// A system of the disk that a run drives: the hand-written one or the mode graph. It keeps
/// the run's [`Ledger`]; [`run_on`] asks the rest of it (its modes seen as phases, the disk's
/// stops and notes).
pub(crate) trait DiskEngine {
    /// The decisions and the drift so far.
    fn ledger(&self) -> &Ledger;
}

impl<R: Model<DIM>, S: Model<DIM>> DiskEngine for DiskSystem<'_, R, S> {
    fn ledger(&self) -> &Ledger {
        &self.ledger
    }
}

impl DiskEngine for GraphSystem {
    fn ledger(&self) -> &Ledger {
        &self.ledger
    }
}

/// The modes of an engine.
type ModeOf<H> = <H as HybridSystem<Const<DIM>>>::Mode;

/// What a run is of: the models that evaluate its output, its settings and its start.
struct Run<'a, R, S> {
    models: &'a DiskModels<R, S>,
    config: &'a DiskConfig,
    initial: &'a InitialState,
}

/// The stages after the start, for either engine: `system` driven from `entry` in its mode
/// `first` (through `modes`; the entry's bridge is the slip a starting bridge starts from), its
/// output turned into the disk's for `observer` by the [`Adaptor`], and the outcome concluded.
fn run_on<H, R: Model<DIM>, S: Model<DIM>, O: DiskObserver + ?Sized>(
    system: &mut H,
    modes: &[ModeOf<H>],
    first: ModeOf<H>,
    entry: Entry,
    Run {
        models,
        config,
        initial,
    }: Run<'_, R, S>,
    gate: Gate,
    observer: &mut O,
) -> Result<RunOutcome, SimFailure>
where
    H: DiskEngine + TimeScale<DIM>,
    H: HybridSystem<Const<DIM>, Stop = Halted, Note = DiskNote>,
    ModeOf<H>: DiskPhase,
{
    let start = Start {
        t: initial.t,
        mode: first,
        y: entry.y,
    };
    let bridge = entry.bridge;
    let tolerance = config
        .tolerance(models.chart)
        .map_err(|e| SimError::Solve {
            mode: start.mode.phase().mode(),
            error: e.into(),
        })?;
    let how = Drive {
        config,
        tolerance,
        sample_rate: config.sample_rate,
    };
    let ring = observer_ring(observer, (initial.t, config.sample_rate));
    let mut adaptor = Adaptor {
        models,
        bridge,
        user: observer,
        gate,
        scanner: Scanner::default(),
        work: WorkMeter::new(config.work, initial.t),
        ring,
        last: None,
    };
    let driven = drive(how, system, modes, start, &mut adaptor);
    let closing = adaptor.close(&driven);
    conclude(models, system.ledger(), driven, closing)
}

/// The disk's modes, for the clocked system's guard lists.
const PHASES: [Phase; 3] = [Phase::Rolling, Phase::Sliding, Phase::Bridge];

pub(super) fn validate<R, S>(
    models: &DiskModels<R, S>,
    config: &DiskConfig,
    initial: &InitialState,
) -> Result<(), SimError> {
    models.params.validate()?;
    let mut issues = config.issues(initial.t, models.chart);
    issues.extend(initial.issues());
    if issues.is_empty() {
        Ok(())
    } else {
        Err(SimError::Invalid { issues })
    }
}

/// How a run begins: where the driver starts, or an end before the first step.
enum Begun {
    /// The driver starts here.
    Running(Entry),
    /// The run ended where it started: a mode not allowed, or a floor that would have to pull.
    Stopped(Box<RunOutcome>),
}

/// The first stage: the initial mode decided (and told to the observer and the gate), the
/// start sampled, and the ends before any step.
fn begin<R: Model<DIM>, S: Model<DIM>, O: DiskObserver + ?Sized>(
    system: &mut DiskSystem<'_, R, S>,
    models: &DiskModels<R, S>,
    config: &DiskConfig,
    initial: &InitialState,
    gate: &mut Gate,
    observer: &mut O,
) -> Result<Begun, SimError> {
    let (entry, decision) = initial_phase(system, models, config, initial)?;
    gate.admit(initial.t, entry.phase.mode());
    if let Some(record) = decision {
        gate.forward(&record, observer);
    }
    let t = initial.t;
    let mode = entry.phase.mode();
    let first = sample_at(models, entry.bridge, t, entry.phase, &entry.y)
        .map_err(|source| SimError::Transition { mode, t, source })?;
    let stop = match gate.forbidden {
        Some((t, mode)) => StopReason::ModeNotAllowed { t, mode },
        // The floor would have to pull: the disk leaves it at once.
        None if first.force.normal <= 0.0 || first.force.normal.is_nan() => {
            StopReason::ContactLost { t, mode }
        }
        None => return Ok(Begun::Running(entry)),
    };
    Ok(Begun::Stopped(Box::new(RunOutcome {
        stop,
        last: first,
        transitions: 0,
        stats: Default::default(),
        max_drift: Default::default(),
    })))
}

/// The last stage: the driver's outcome as the disk's, or its failure with the work done and
/// the last state reached.
fn conclude<R: Model<DIM>, S: Model<DIM>, Md: DiskPhase>(
    models: &DiskModels<R, S>,
    ledger: &Ledger,
    driven: Driven<Md, Halted>,
    closing: Closing,
) -> Result<RunOutcome, SimFailure> {
    let out = match driven {
        Ok(out) => out,
        Err(Failed { error, stats }) => {
            let error = SimError::from_driver(error, |m: Md| m.phase().mode());
            return Err(closing.failure(error, stats));
        }
    };
    if let Some(over) = closing.over_budget {
        return Err(closing.failure(SimError::WorkBound(over), Box::new(out.stats)));
    }
    let stop = match out.stop {
        model_runtime::StopReason::EndTime => StopReason::EndTime,
        model_runtime::StopReason::Observer => match closing.forbidden {
            Some((t, mode)) => StopReason::ModeNotAllowed { t, mode },
            None => StopReason::Requested { t: out.t },
        },
        model_runtime::StopReason::User(Halted { halt, .. }) => match halt {
            Halt::Stop(reason) => reason,
            Halt::Onset { t, source } => {
                return Err(closing.failure(SimError::Onset { t, source }, Box::new(out.stats)))
            }
        },
    };
    let mode = out.mode.phase().mode();
    let last =
        sample_at(models, closing.bridge, out.t, out.mode.phase(), &out.y).map_err(|source| {
            let error = SimError::Transition {
                mode,
                t: out.t,
                source,
            };
            closing.failure(error, Box::new(out.stats))
        })?;
    Ok(RunOutcome {
        stop,
        last,
        transitions: ledger.transitions,
        stats: out.stats,
        max_drift: ledger.max_drift(),
    })
}

/// The ring of latest steps `observer` asks for, if any, on the run's sample `grid` (origin,
/// rate).
fn observer_ring<O: DiskObserver + ?Sized>(
    observer: &O,
    grid: (f64, Option<f64>),
) -> Option<StepRing> {
    observer
        .keeps_trailing()
        .map(|span| StepRing::new(span, grid))
}

/// Where the driver starts (see [`simulate`]), and the initial mode decision if one was made.
pub(super) fn initial_phase<R: Model<DIM>, S: Model<DIM>>(
    system: &mut DiskSystem<'_, R, S>,
    models: &DiskModels<R, S>,
    config: &DiskConfig,
    initial: &InitialState,
) -> Result<(Entry, Option<TransitionRecord>), SimError> {
    let t = initial.t;
    let given = initial.state;
    let mut state = given;
    if initial.mode == Mode::Sliding && given.slip.speed.abs() > config.stick_threshold {
        state.project(&models.params, Mode::Sliding);
        let y = state.sliding_vector(models.chart, given.slip);
        return Ok((undecided(Phase::Sliding, y), None));
    }
    state.project(&models.params, Mode::Rolling);
    let eval_error = |source| SimError::Transition {
        mode: Mode::Rolling,
        t,
        source,
    };
    let force = system.rolling_force(t, &state).map_err(eval_error)?;
    if force.admits_rolling(models.params.mu_st) {
        return Ok((undecided(Phase::Rolling, state.rolling_vector()), None));
    }
    let drift = given.residuals(&models.params, Mode::Rolling);
    let trigger = Trigger::InitialFriction {
        ratio: force.ratio(),
    };
    let start = system
        .begin_sliding(
            t,
            state,
            force.direction(),
            Mode::Rolling,
            trigger,
            drift,
            false,
        )
        .map_err(eval_error)?;
    let decision = start.decision;
    match start.next {
        Ok(entry) => Ok((entry, decision)),
        Err(Halt::Onset { t, source }) => Err(SimError::Onset { t, source }),
        // Sliding would need the floor to pull: start on the bridge at zero slip in the
        // direction decided, where `begin` sees N <= 0 in the first sample and stops at once.
        Err(Halt::Stop(_)) => {
            let direction = decision
                .and_then(|d| d.slip_direction)
                .unwrap_or(force.direction());
            let zero = Slip {
                speed: 0.0,
                direction,
            };
            let y = state.sliding_vector(models.chart, zero);
            let entry = Entry {
                phase: Phase::Bridge,
                y,
                bridge: Some(zero),
            };
            Ok((entry, decision))
        }
    }
}

/// A start in `phase` at `y` that no decision led to (and no bridge).
fn undecided(phase: Phase, y: [f64; DIM]) -> Entry {
    Entry {
        phase,
        y,
        bridge: None,
    }
}

/// The allowed modes of a run, and the first decision for one that is not.
struct Gate {
    allowed: AllowedModes,
    /// Time and mode of the first decision for a mode not allowed.
    forbidden: Option<(f64, Mode)>,
}

impl Gate {
    /// Notes entering `mode` at `t`.
    fn admit(&mut self, t: f64, mode: Mode) {
        if self.forbidden.is_none() && !self.allowed.allows(mode) {
            self.forbidden = Some((t, mode));
        }
    }

    /// Forwards a mode decision to the caller's observer, noting the mode it enters.
    fn forward<O: DiskObserver + ?Sized>(&mut self, record: &TransitionRecord, observer: &mut O) {
        self.admit(record.t, record.to);
        observer.on_transition(record);
    }
}

/// The disk at `(t, y)` in `phase`, with its contact force (one model evaluation); on a
/// bridge, `bridge` is the slip it started from.
pub(crate) fn sample_at<R: Model<DIM>, S: Model<DIM>>(
    models: &DiskModels<R, S>,
    bridge: Option<Slip>,
    t: f64,
    phase: Phase,
    y: &[f64; DIM],
) -> Result<DiskSample, EvalError> {
    let p = &models.params;
    let mut dy = [0.0; DIM];
    let (state, force) = match phase {
        Phase::Rolling => {
            models.rolling.rhs(t, y, &mut dy)?;
            let force = ContactForce::rolling(p, &PhysicalState::from_rolling(y, 0.0), &dy);
            (PhysicalState::from_rolling(y, force.direction()), force)
        }
        Phase::Sliding => {
            models.sliding.rhs(t, y, &mut dy)?;
            let state = models.sliding_state(y);
            (state, ContactForce::sliding(p, &state, &dy))
        }
        Phase::Bridge => {
            // Within ~1e-9 s of zero slip: the direction is the bridge's, the force the one at
            // zero slip in that direction.
            let mut state = models.sliding_state(y);
            if let Some(slip) = bridge {
                state.slip.direction = slip.direction;
            }
            let (_, dy) = models.probe_onset(t, &state, state.slip.direction)?;
            (state, ContactForce::sliding(p, &state, &dy))
        }
    };
    let mode = phase.mode();
    Ok(DiskSample {
        t,
        mode,
        state,
        force,
        energy: state.energy(p),
        residuals: state.residuals(p, mode),
    })
}

/// Turns the driver's output into disk samples and decisions for the caller.
struct Adaptor<'a, R, S, O: ?Sized> {
    models: &'a DiskModels<R, S>,
    /// The slip the current bridge started from (from the note of the transition into it).
    bridge: Option<Slip>,
    user: &'a mut O,
    gate: Gate,
    /// Locates extrema, when the user asks for them.
    scanner: Scanner,
    /// Counts the steps against the run's work bound.
    work: WorkMeter,
    /// The latest steps, when the user keeps them ([`DiskObserver::keeps_trailing`]).
    ring: Option<StepRing>,
    /// The end of the last accepted step (what a failed run reports of where it got).
    last: Option<StepEnd>,
}

/// The end of an accepted step, with what a sample of it needs.
struct StepEnd {
    t: f64,
    phase: Phase,
    bridge: Option<Slip>,
    y: [f64; DIM],
}

/// What the adaptor knows at a run's end that the driver's outcome does not.
struct Closing {
    /// The slip the bridge in force started from (a stop on a bridge is sampled with it).
    bridge: Option<Slip>,
    /// The first decision for a mode not allowed: why the adaptor stopped the run, if it did.
    forbidden: Option<(f64, Mode)>,
    /// The work bound, if the run went over it (the adaptor stopped the run there).
    over_budget: Option<WorkExceeded>,
    /// The disk at the end of the last accepted step (`None` before the first step, or where
    /// the models cannot evaluate it).
    last: Option<Box<DiskSample>>,
}

impl Closing {
    /// A failure of the run with `stats` of work done, and where it got.
    fn failure(&self, error: SimError, stats: Box<Stats>) -> SimFailure {
        SimFailure {
            error,
            stats,
            last: self.last.clone(),
        }
    }
}

impl<R: Model<DIM>, S: Model<DIM>, O: DiskObserver + ?Sized> Adaptor<'_, R, S, O> {
    /// Ends the scanned segment (a transition or the end of the run).
    fn end_segment(&mut self) {
        if self.user.wants_extrema() {
            let user = &mut *self.user;
            self.scanner.end_segment(&mut |e| user.on_extremum(&e));
        }
    }

    /// The disk sample at `(t, y)` in `phase` (with the bridge in force), or the observer's
    /// failure there.
    fn sample(&self, t: f64, phase: Phase, y: &[f64; DIM]) -> Result<DiskSample, ObserverError> {
        sample_at(self.models, self.bridge, t, phase, y)
            .map_err(|source| ObserverError { t, source })
    }

    /// The third stage, once the driver has returned `driven`: the last scanned segment ends,
    /// the kept steps go to the observer, and a decision made at the stop (no segment
    /// followed to carry it) is told; what is left for the outcome comes back.
    fn close<Md>(mut self, driven: &Driven<Md, Halted>) -> Closing {
        let last = (self.last.as_ref())
            .and_then(|l| sample_at(self.models, l.bridge, l.t, l.phase, &l.y).ok())
            .map(Box::new);
        self.end_segment();
        if let Some(ring) = &self.ring {
            let models = self.models;
            let sample = |t, phase, bridge, y: &[f64; DIM]| sample_at(models, bridge, t, phase, y);
            self.user.on_trailing(&Trailing {
                ring,
                sample_at: &sample,
            });
        }
        let over_budget = self.work.exceeded();
        if let Ok(HybridOutcome {
            stop:
                model_runtime::StopReason::User(Halted {
                    decision: Some(record),
                    ..
                }),
            ..
        }) = driven
        {
            // A stop on a bridge is sampled in the direction just decided, where the run
            // found it must stop.
            self.gate.forward(record, self.user);
            if let Some(direction) = record.slip_direction {
                self.bridge = Some(Slip {
                    speed: 0.0,
                    direction,
                });
            }
        }
        Closing {
            bridge: self.bridge,
            forbidden: self.gate.forbidden,
            over_budget,
            last,
        }
    }
}

/// The adaptor observes either engine: their modes are seen as phases, their guards are
/// not read.
impl<R: Model<DIM>, S: Model<DIM>, O: DiskObserver + ?Sized, Md: DiskPhase, G>
    Observer<Const<DIM>, Md, G, DiskNote> for Adaptor<'_, R, S, O>
{
    fn wants_sample(&self, t: f64) -> bool {
        self.user.wants_sample(t)
    }

    fn next_wanted_sample(&self, t: f64) -> f64 {
        self.user.next_wanted_sample(t)
    }

    fn wants_dense(&self) -> bool {
        self.user.wants_extrema() || self.ring.is_some()
    }

    fn proceed(&mut self) -> std::ops::ControlFlow<()> {
        if self.gate.forbidden.is_some() || self.work.exceeded().is_some() {
            return std::ops::ControlFlow::Break(());
        }
        self.user.proceed()
    }

    fn on_sample(&mut self, s: &Sample<'_, Const<DIM>, Md>) -> Observed {
        let sample = self.sample(s.t, s.mode.phase(), s.y)?;
        self.user.on_sample(&sample);
        Ok(())
    }

    fn on_step(&mut self, step: &StepView<'_, Const<DIM>, Md>) -> Observed {
        let phase = step.mode.phase();
        self.work.step(step.t0, step.t1);
        if let (Some(ring), Some(dense)) = (&mut self.ring, step.dense) {
            ring.push(dense, (step.t0, step.t1), phase, self.bridge);
        }
        self.last = Some(StepEnd {
            t: step.t1,
            phase,
            bridge: self.bridge,
            y: *step.y1,
        });
        if self.user.wants_extrema() {
            let user = &mut *self.user;
            self.scanner
                .step(self.models, phase, step, &mut |e| user.on_extremum(&e));
        }
        if self.user.wants_steps() {
            let sample = self.sample(step.t1, phase, step.y1)?;
            self.user.on_step(&sample);
        }
        Ok(())
    }

    fn on_transition(
        &mut self,
        record: model_runtime::TransitionRecord<Const<DIM>, Md, G, DiskNote>,
    ) -> Observed {
        if !matches!(record.kind, model_runtime::TransitionKind::Pass) {
            self.end_segment();
        }
        let DiskNote { decision, bridge } = record.note;
        if bridge.is_some() {
            self.bridge = bridge;
        }
        if let Some(decision) = decision {
            self.gate.forward(&decision, self.user);
        }
        Ok(())
    }
}
