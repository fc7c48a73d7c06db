//! One simulation from start to stop: checking the inputs, deciding the initial mode, choosing
//! the integrator, and turning the driver's raw phase states into disk samples for the caller.

use super::models::DiskModels;
use super::system::{DiskNote, DiskSystem, Entry, Halt, Halted, Phase};
use super::{
    DiskConfig, DiskObserver, DiskSample, InitialState, IntegratorChoice, RunOutcome, SimError,
    SlipSign, StopReason, TimeVariable, TransitionRecord, Trigger,
};
use crate::modes::layout::THETA;
use crate::modes::{ContactForce, Mode, PhysicalState, Slip, SlipChart, DIM};
use model_runtime::ChatterLimit as DriverChatter;
use model_runtime::{
    Clocked, Dop853, Dopri5, EvalError, HybridError, HybridOptions, HybridSolver, InputError,
    LimitingComponent, Model, Observer, PhysicalTime, Regularised, Rk4, Rodas4, Sample,
    StepOptions, StepView, Stepper, Tolerance,
};

/// Runs the hybrid disk from `initial` until `config.t_end` or a stop, streaming samples and
/// mode decisions to `observer`.
///
/// The initial state is given in rolling variables. If its contact particle slips (faster
/// than the stick threshold) the run starts sliding with that slip; otherwise the state is put
/// on the rolling constraints and starts rolling if static friction can hold it, or sliding
/// from zero slip in the consistent direction if it cannot (reported as a transition with
/// [`Trigger::InitialFriction`], not counted in [`RunOutcome::transitions`]).
pub fn simulate<R: Model<DIM>, S: Model<DIM>, O: DiskObserver>(
    models: &DiskModels<R, S>,
    config: &DiskConfig,
    initial: &InitialState,
    observer: &mut O,
) -> Result<RunOutcome, SimError> {
    validate(models, config, initial)?;
    match config.integrator {
        IntegratorChoice::Dopri5 => run_with(
            Dopri5::new(),
            Dopri5::new(),
            models,
            config,
            initial,
            observer,
        ),
        IntegratorChoice::Dop853 => run_with(
            Dop853::new(),
            Dop853::new(),
            models,
            config,
            initial,
            observer,
        ),
        IntegratorChoice::Rodas4 => run_with(
            Rodas4::new(),
            Rodas4::new(),
            models,
            config,
            initial,
            observer,
        ),
        IntegratorChoice::Rk4 { h } => {
            run_with(Rk4::new(h), Rk4::new(h), models, config, initial, observer)
        }
    }
}

/// The clocked state's dimension in [`TimeVariable::Regularised`] runs.
const CLOCKED: usize = DIM + 1;

/// The disk's modes, for the clocked system's guard lists.
const PHASES: [Phase; 3] = [Phase::Rolling, Phase::Sliding, Phase::Bridge];

/// The most samples a run may deliver (about a day of a fast observer's time).
const MAX_SAMPLES: f64 = 1e9;

fn config_error(name: &'static str, value: f64, reason: &'static str) -> SimError {
    SimError::Config {
        name,
        value,
        reason,
    }
}

fn validate<R, S>(
    models: &DiskModels<R, S>,
    config: &DiskConfig,
    initial: &InitialState,
) -> Result<(), SimError> {
    models.params.validate()?;
    let positive = [
        ("rtol", config.rtol),
        ("atol", config.atol),
        ("stick_threshold", config.stick_threshold),
        ("chatter.window", config.chatter.window),
    ];
    for (name, value) in positive {
        if !(value.is_finite() && value > 0.0) {
            return Err(config_error(name, value, "must be finite and > 0"));
        }
    }
    if let IntegratorChoice::Rk4 { h } = config.integrator {
        if !(h.is_finite() && h > 0.0) {
            return Err(config_error("integrator.h", h, "must be finite and > 0"));
        }
        if config.time == TimeVariable::Regularised {
            return Err(config_error(
                "integrator.h",
                h,
                "a fixed step cannot follow a regularised time: choose an adaptive integrator",
            ));
        }
    }
    if let Some(rate) = config.sample_rate {
        if !(rate.is_finite() && rate > 0.0) {
            return Err(config_error("sample_rate", rate, "must be finite and > 0"));
        }
    }
    if !(config.min_inclination > 0.0 && config.min_inclination < std::f64::consts::FRAC_PI_2) {
        return Err(config_error(
            "min_inclination",
            config.min_inclination,
            "must lie in (0, pi/2): the models are singular at sin(theta) = 0",
        ));
    }
    if config.chatter.max_transitions == 0 {
        return Err(config_error("chatter.max_transitions", 0.0, "must be >= 1"));
    }
    if !(config.t_end.is_finite() && config.t_end >= initial.t && initial.t.is_finite()) {
        return Err(config_error(
            "t_end",
            config.t_end,
            "must be finite and not before the initial time",
        ));
    }
    if config.stick_threshold < config.atol {
        // The slip's own error is about atol: a lower threshold is crossed by noise or,
        // more often, never (the run then slides past every stick, silently wrong).
        return Err(config_error(
            "stick_threshold",
            config.stick_threshold,
            "must be at least atol: a slip below the integration error cannot be seen to stop",
        ));
    }
    if let Some(rate) = config.sample_rate {
        // Finite is not enough: 1e300 samples per second would never finish.
        if rate * (config.t_end - initial.t) > MAX_SAMPLES {
            return Err(config_error(
                "sample_rate",
                rate,
                "gives more than 1e9 samples over the run",
            ));
        }
    }
    if config.slip_sign == SlipSign::Paper && models.chart != SlipChart::Polar {
        return Err(SimError::SignedSlipNeedsPolarChart);
    }
    if let Some(i) = initial.y.iter().position(|v| !v.is_finite()) {
        return Err(SimError::InitialState {
            component: i,
            value: initial.y[i],
        });
    }
    let theta = initial.y[THETA];
    if !(theta > 0.0 && theta < std::f64::consts::PI) {
        return Err(SimError::InitialState {
            component: THETA,
            value: theta,
        });
    }
    Ok(())
}

fn run_with<St, Sc, R, S, O>(
    stepper: St,
    clocked_stepper: Sc,
    models: &DiskModels<R, S>,
    config: &DiskConfig,
    initial: &InitialState,
    observer: &mut O,
) -> Result<RunOutcome, SimError>
where
    St: Stepper<DIM>,
    Sc: Stepper<CLOCKED>,
    R: Model<DIM>,
    S: Model<DIM>,
    O: DiskObserver,
{
    let mut system = DiskSystem::new(models, config);
    let (start, decision) = initial_phase(&mut system, models, config, initial)?;
    if let Some(record) = decision {
        observer.on_transition(&record);
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
    if first.force.normal <= 0.0 || first.force.normal.is_nan() {
        // The floor would have to pull: the disk leaves it at once.
        return Ok(RunOutcome {
            stop: StopReason::ContactLost {
                t: initial.t,
                mode: phase.mode(),
            },
            last: first,
            transitions: 0,
            stats: Default::default(),
            max_drift: Default::default(),
        });
    }
    let options = HybridOptions {
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
    };
    let input_error = |e: InputError| SimError::Solve {
        mode: phase.mode(),
        error: e.into(),
    };
    let tolerance = config.tolerance(models.chart).map_err(input_error)?;
    let mut adaptor = Adaptor {
        models,
        bridge,
        user: observer,
        failure: None,
    };
    let ended = match config.time {
        TimeVariable::Physical => {
            let mut solver = HybridSolver::new(stepper, tolerance, options).map_err(input_error)?;
            solver
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
                })
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
            result
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
                .map_err(|e| in_physical_time(e, at))
        }
    };
    let failure = adaptor.failure.take();
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
        adaptor.user.on_transition(record);
        if let Some(direction) = record.slip_direction {
            adaptor.bridge = Some(Slip {
                speed: 0.0,
                direction,
            });
        }
    }
    let bridge = adaptor.bridge;
    let out = ended.map_err(|e| match e {
        HybridError::Solve { mode, error } => SimError::Solve {
            mode: mode.mode(),
            error,
        },
        HybridError::Transition { mode, t, source } => SimError::Transition {
            mode: mode.mode(),
            t,
            source,
        },
        HybridError::Chattering { t, transitions, .. } => {
            SimError::DriverChattering { t, transitions }
        }
    })?;
    if let Some((t, phase, source)) = failure {
        return Err(SimError::Transition {
            mode: phase.mode(),
            t,
            source,
        });
    }
    let stop = match out.stop {
        model_runtime::StopReason::EndTime => StopReason::EndTime,
        model_runtime::StopReason::Observer => StopReason::Requested { t: out.t },
        model_runtime::StopReason::User(Halted { halt, .. }) => match halt {
            Halt::Stop(reason) => reason,
            Halt::Onset { t, source } => return Err(SimError::Onset { t, source }),
        },
    };
    let last = sample_at(models, bridge, out.t, out.phase, &out.y).map_err(|source| {
        SimError::Transition {
            mode: out.phase.mode(),
            t: out.t,
            source,
        }
    })?;
    Ok(RunOutcome {
        stop,
        last,
        transitions: system.transitions,
        stats: out.stats,
        max_drift: system.max_drift(),
    })
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
fn in_physical_time(e: HybridError<Phase>, t: f64) -> HybridError<Phase> {
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
    pub fn tolerance(&self, chart: SlipChart) -> Result<Tolerance<DIM>, InputError> {
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
fn initial_phase<R: Model<DIM>, S: Model<DIM>>(
    system: &mut DiskSystem<'_, R, S>,
    models: &DiskModels<R, S>,
    config: &DiskConfig,
    initial: &InitialState,
) -> Result<(Entry, Option<TransitionRecord>), SimError> {
    let t = initial.t;
    let given = PhysicalState::from_rolling(&initial.y, 0.0);
    let slip = given.velocity_slip(&models.params);
    let mut state = given;
    if slip[0].hypot(slip[1]) > config.stick_threshold {
        state.project(&models.params, Mode::Sliding);
        let y = state.sliding_vector(models.chart, Slip::from_vector(slip));
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
    /// The first model failure while sampling (reported after the run).
    failure: Option<(f64, Phase, EvalError)>,
}

impl<R: Model<DIM>, S: Model<DIM>, O: DiskObserver> Observer<DIM, Phase, super::DiskGuard, DiskNote>
    for Adaptor<'_, R, S, O>
{
    fn wants_sample(&self, t: f64) -> bool {
        self.user.wants_sample(t)
    }

    fn proceed(&mut self) -> std::ops::ControlFlow<()> {
        self.user.proceed()
    }

    fn on_sample(&mut self, s: &Sample<'_, DIM, Phase>) {
        match sample_at(self.models, self.bridge, s.t, s.mode, s.y) {
            Ok(sample) => self.user.on_sample(&sample),
            Err(e) => {
                if self.failure.is_none() {
                    self.failure = Some((s.t, s.mode, e));
                }
            }
        }
    }

    fn on_step(&mut self, step: &StepView<'_, DIM, Phase>) {
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
        record: model_runtime::TransitionRecord<DIM, Phase, super::DiskGuard, DiskNote>,
    ) {
        let DiskNote { decision, bridge } = record.note;
        if bridge.is_some() {
            self.bridge = bridge;
        }
        if let Some(decision) = decision {
            self.user.on_transition(&decision);
        }
    }
}
