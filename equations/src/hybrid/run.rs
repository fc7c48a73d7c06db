//! One simulation from start to stop: checking the inputs, deciding the initial mode, choosing
//! the integrator, and turning the driver's raw phase states into disk samples for the caller.

use super::extrema::Scanner;
use super::models::DiskModels;
use super::system::{DiskNote, DiskSystem, Entry, Halt, Halted, Phase};
use super::trailing::{StepRing, Trailing};
use super::{
    DiskObserver, DiskSample, RunOutcome, SimError, SimFailure, StopReason, TransitionRecord,
    Trigger,
};
use crate::config::{AllowedModes, DiskConfig};
use crate::modes::{ContactForce, Mode, PhysicalState, Slip, SlipChart, DIM};
use crate::settings::{Integrator, TimeVariable};
use crate::start::InitialState;
use crate::work::WorkMeter;
use model_runtime::ChatterLimit as DriverChatter;
use model_runtime::Const;
use model_runtime::{
    Clocked, Dop853, Dopri5, EvalError, HybridError, HybridOptions, HybridSolver, InputError,
    LimitingComponent, Model, Observer, PhysicalTime, Regularised, Rk4, Rodas4, Sample,
    StepOptions, StepView, Stepper, Tolerance,
};

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
pub fn simulate<R: Model<DIM>, S: Model<DIM>, O: DiskObserver>(
    models: &DiskModels<R, S>,
    config: &DiskConfig,
    initial: &InitialState,
    observer: &mut O,
) -> Result<RunOutcome, SimFailure> {
    validate(models, config, initial)?;
    match config.integrator {
        Integrator::Dopri5 => run_with(
            Dopri5::new(),
            Dopri5::new(),
            models,
            config,
            initial,
            observer,
        ),
        Integrator::Dop853 => run_with(
            Dop853::new(),
            Dop853::new(),
            models,
            config,
            initial,
            observer,
        ),
        Integrator::Rodas4 => run_with(
            Rodas4::new(),
            Rodas4::new(),
            models,
            config,
            initial,
            observer,
        ),
        Integrator::Rk4 { h } => {
            run_with(Rk4::new(h), Rk4::new(h), models, config, initial, observer)
        }
    }
}

/// The clocked state's dimension in [`TimeVariable::Regularised`] runs.
const CLOCKED: usize = DIM + 1;

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

fn run_with<St, Sc, R, S, O>(
    stepper: St,
    clocked_stepper: Sc,
    models: &DiskModels<R, S>,
    config: &DiskConfig,
    initial: &InitialState,
    observer: &mut O,
) -> Result<RunOutcome, SimFailure>
where
    St: Stepper<Const<DIM>>,
    Sc: Stepper<Const<CLOCKED>>,
    R: Model<DIM>,
    S: Model<DIM>,
    O: DiskObserver,
{
    let mut system = DiskSystem::new(models, config);
    let (start, decision) = initial_phase(&mut system, models, config, initial)?;
    let mut gate = Gate {
        allowed: config.allowed,
        forbidden: None,
    };
    gate.admit(initial.t, start.phase.mode());
    if let Some(record) = decision {
        gate.forward(&record, observer);
    }
    let Entry {
        phase,
        y: y0,
        bridge,
    } = start;
    let first = sample_at(models, bridge, initial.t, phase, &y0).map_err(|source| {
        SimError::Transition {
            mode: phase.mode(),
            t: initial.t,
            source,
        }
    })?;
    if let Some((t, mode)) = gate.forbidden {
        return Ok(stopped_at_start(
            StopReason::ModeNotAllowed { t, mode },
            first,
        ));
    }
    if first.force.normal <= 0.0 || first.force.normal.is_nan() {
        // The floor would have to pull: the disk leaves it at once.
        let stop = StopReason::ContactLost {
            t: initial.t,
            mode: phase.mode(),
        };
        return Ok(stopped_at_start(stop, first));
    }
    let options = hybrid_options(config);
    let input_error = |e: InputError| SimError::Solve {
        mode: phase.mode(),
        error: e.into(),
    };
    let tolerance = config.tolerance(models.chart).map_err(input_error)?;
    let ring = observer_ring(observer, (initial.t, config.sample_rate));
    let mut adaptor = Adaptor {
        models,
        bridge,
        user: observer,
        gate: &mut gate,
        failure: None,
        scanner: Scanner::default(),
        work: WorkMeter::new(config.work, initial.t),
        ring,
        last: None,
    };
    let (ended, work) = match config.time {
        TimeVariable::Physical => {
            let mut solver = HybridSolver::new(stepper, tolerance, options).map_err(input_error)?;
            let result = solver
                .run(
                    &mut system,
                    phase,
                    initial.t,
                    &y0,
                    config.t_end,
                    &mut adaptor,
                )
                .map(|out| Ended {
                    t: out.t,
                    y: out.y,
                    phase: out.mode,
                    stop: out.stop,
                    stats: out.stats,
                });
            (result, solver.stats())
        }
        TimeVariable::Regularised => {
            let mut clocked =
                Regularised::<_, DIM, CLOCKED>::new(&mut system, &PHASES, initial.t, config.t_end);
            // The clock is held to the states' tolerances (in seconds): the same cost per
            // step and, on the paper's scene, the same phase accuracy as a run in physical
            // time. A clock held 1000 times tighter makes the transition times 400 times more
            // accurate for 1.4 times the work (BENCHMARKS.md §3).
            let tolerance = clocked.tolerance(&tolerance, (config.rtol, config.atol));
            // The driver samples in its own variable; the clocked observer samples in t.
            let options = HybridOptions {
                sample_rate: None,
                ..options
            };
            let mut solver =
                HybridSolver::new(clocked_stepper, tolerance, options).map_err(input_error)?;
            let mut physical =
                PhysicalTime::<_, DIM, CLOCKED>::new(&mut adaptor, initial.t, config.sample_rate);
            let z0 = Regularised::<DiskSystem<R, S>, DIM, CLOCKED>::start(&y0);
            let result = solver.run(&mut clocked, phase, initial.t, &z0, f64::MAX, &mut physical);
            let at = clocked.latest_time();
            let result = result
                .map(|out| Ended {
                    t: match out.stop {
                        model_runtime::StopReason::User(Clocked::EndTime) => config.t_end,
                        _ => clocked.time_of(&out.y),
                    },
                    y: Regularised::<DiskSystem<R, S>, DIM, CLOCKED>::state_of(&out.y),
                    phase: out.mode,
                    stop: match out.stop {
                        model_runtime::StopReason::EndTime
                        | model_runtime::StopReason::User(Clocked::EndTime) => {
                            model_runtime::StopReason::EndTime
                        }
                        model_runtime::StopReason::User(Clocked::Inner(halted)) => {
                            model_runtime::StopReason::User(halted)
                        }
                        model_runtime::StopReason::Observer => model_runtime::StopReason::Observer,
                    },
                    stats: out.stats,
                })
                .map_err(|e| in_physical_time(e, at));
            (result, solver.stats())
        }
    };
    // Every failure from here on has the work done with it, and the last state reached.
    let last = (adaptor.last.as_ref())
        .and_then(|l| sample_at(models, l.bridge, l.t, l.phase, &l.y).ok())
        .map(Box::new);
    let failed = |error: SimError| SimFailure {
        error,
        stats: Box::new(work),
        last: last.clone(),
    };
    adaptor.end_segment();
    if let Some(ring) = &adaptor.ring {
        let sample = |t, phase, bridge, y: &[f64; DIM]| sample_at(models, bridge, t, phase, y);
        adaptor.user.on_trailing(&Trailing {
            ring,
            sample_at: &sample,
        });
    }
    let failure = adaptor.failure.take();
    let over_budget = adaptor.work.exceeded();
    if let Ok(Ended {
        stop:
            model_runtime::StopReason::User(Halted {
                decision: Some(record),
                ..
            }),
        ..
    }) = &ended
    {
        // The decision just before a stop: no segment followed it to carry it. A stop on a
        // bridge is sampled in the direction just decided, where the run found it must stop.
        adaptor.gate.forward(record, adaptor.user);
        if let Some(direction) = record.slip_direction {
            adaptor.bridge = Some(Slip {
                speed: 0.0,
                direction,
            });
        }
    }
    let bridge = adaptor.bridge;
    let out = ended.map_err(|e| failed(SimError::from_driver(e, Phase::mode)))?;
    if let Some((t, phase, source)) = failure {
        return Err(failed(SimError::Transition {
            mode: phase.mode(),
            t,
            source,
        }));
    }
    if let Some(over) = over_budget {
        return Err(failed(SimError::WorkBound(over)));
    }
    let stop = match out.stop {
        model_runtime::StopReason::EndTime => StopReason::EndTime,
        model_runtime::StopReason::Observer => match gate.forbidden {
            Some((t, mode)) => StopReason::ModeNotAllowed { t, mode },
            None => StopReason::Requested { t: out.t },
        },
        model_runtime::StopReason::User(Halted { halt, .. }) => match halt {
            Halt::Stop(reason) => reason,
            Halt::Onset { t, source } => return Err(failed(SimError::Onset { t, source })),
        },
    };
    let last = sample_at(models, bridge, out.t, out.phase, &out.y).map_err(|source| {
        failed(SimError::Transition {
            mode: out.phase.mode(),
            t: out.t,
            source,
        })
    })?;
    Ok(RunOutcome {
        stop,
        last,
        transitions: system.transitions,
        stats: out.stats,
        max_drift: system.max_drift(),
    })
}

/// The driver's options for a run under `config` (the hand-written and the switched disk
/// alike).
pub(super) fn hybrid_options(config: &DiskConfig) -> HybridOptions {
    HybridOptions {
        step: StepOptions {
            max_steps: config.max_steps,
            control: config.step_control,
            ..StepOptions::default()
        },
        // A backstop only: the disk counts its own decisions (each may take three driver
        // transitions through bridges) and stops with a named reason first.
        chatter: DriverChatter {
            max_transitions: 3 * config.chatter.max_transitions + 3,
            window: config.chatter.window,
        },
        sample_rate: config.sample_rate,
        guard_checks: config.guard_checks,
    }
}

/// The ring of latest steps `observer` asks for, if any, on the run's sample `grid` (origin,
/// rate).
fn observer_ring<O: DiskObserver>(observer: &O, grid: (f64, Option<f64>)) -> Option<StepRing> {
    observer
        .keeps_trailing()
        .map(|span| StepRing::new(span, grid))
}

/// A run that ends where it starts, at `first`, before any step.
fn stopped_at_start(stop: StopReason, first: DiskSample) -> RunOutcome {
    RunOutcome {
        stop,
        last: first,
        transitions: 0,
        stats: Default::default(),
        max_drift: Default::default(),
    }
}

/// Where the driver left a run, in physical time and the disk's own state.
struct Ended {
    t: f64,
    y: [f64; DIM],
    phase: Phase,
    stop: model_runtime::StopReason<Halted>,
    stats: model_runtime::Stats,
}

/// A failure of a regularised run dated in physical time (`t`, the latest the clocked system
/// saw) instead of the integration variable.
pub(super) fn in_physical_time<Md>(e: HybridError<Md>, t: f64) -> HybridError<Md> {
    match e {
        HybridError::Solve { mode, error } => HybridError::Solve {
            mode,
            error: error.at_time(t),
        },
        HybridError::Transition { mode, source, .. } => HybridError::Transition { mode, t, source },
        HybridError::Chattering {
            transitions,
            window,
            modes,
            ..
        } => HybridError::Chattering {
            t,
            transitions,
            window,
            modes,
        },
    }
}

impl DiskConfig {
    /// The error norm of a run sliding in `chart`: the tolerances, the vector groups of
    /// [`DiskConfig::error_norm`], and whether the limiting component is counted.
    pub fn tolerance(&self, chart: SlipChart) -> Result<Tolerance<Const<DIM>>, InputError> {
        let tol = self
            .error_norm
            .groups(chart)
            .iter()
            .try_fold(Tolerance::scalar(self.rtol, self.atol), |tol, g| {
                tol.with_group(g.clone())
            })?;
        Ok(match self.limiting_component {
            LimitingComponent::Untracked => tol,
            LimitingComponent::Tracked => tol.tracking_limiting(),
        })
    }
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
        // direction decided, where `run_with` sees N <= 0 in the first sample and stops at once.
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
    fn forward<O: DiskObserver>(&mut self, record: &TransitionRecord, observer: &mut O) {
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
struct Adaptor<'a, R, S, O> {
    models: &'a DiskModels<R, S>,
    /// The slip the current bridge started from (from the note of the transition into it).
    bridge: Option<Slip>,
    user: &'a mut O,
    gate: &'a mut Gate,
    /// The first model failure while sampling (reported after the run).
    failure: Option<(f64, Phase, EvalError)>,
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

impl<R: Model<DIM>, S: Model<DIM>, O: DiskObserver> Adaptor<'_, R, S, O> {
    /// Ends the scanned segment (a transition or the end of the run).
    fn end_segment(&mut self) {
        if self.user.wants_extrema() {
            let user = &mut *self.user;
            self.scanner.end_segment(&mut |e| user.on_extremum(&e));
        }
    }
}

impl<R: Model<DIM>, S: Model<DIM>, O: DiskObserver>
    Observer<Const<DIM>, Phase, super::DiskGuard, DiskNote> for Adaptor<'_, R, S, O>
{
    fn wants_sample(&self, t: f64) -> bool {
        self.user.wants_sample(t)
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

    fn on_sample(&mut self, s: &Sample<'_, Const<DIM>, Phase>) {
        match sample_at(self.models, self.bridge, s.t, s.mode, s.y) {
            Ok(sample) => self.user.on_sample(&sample),
            Err(e) => {
                if self.failure.is_none() {
                    self.failure = Some((s.t, s.mode, e));
                }
            }
        }
    }

    fn on_step(&mut self, step: &StepView<'_, Const<DIM>, Phase>) {
        self.work.step(step.t0, step.t1);
        if let (Some(ring), Some(dense)) = (&mut self.ring, step.dense) {
            ring.push(dense, (step.t0, step.t1), step.mode, self.bridge);
        }
        self.last = Some(StepEnd {
            t: step.t1,
            phase: step.mode,
            bridge: self.bridge,
            y: *step.y1,
        });
        if self.user.wants_extrema() {
            let user = &mut *self.user;
            self.scanner
                .step(self.models, step.mode, step, &mut |e| user.on_extremum(&e));
        }
        if !self.user.wants_steps() {
            return;
        }
        match sample_at(self.models, self.bridge, step.t1, step.mode, step.y1) {
            Ok(sample) => self.user.on_step(&sample),
            Err(e) => {
                if self.failure.is_none() {
                    self.failure = Some((step.t1, step.mode, e));
                }
            }
        }
    }

    fn on_transition(
        &mut self,
        record: model_runtime::TransitionRecord<Const<DIM>, Phase, super::DiskGuard, DiskNote>,
    ) {
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
    }
}
