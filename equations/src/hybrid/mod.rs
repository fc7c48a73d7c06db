//! The hybrid disk: rolling and sliding joined by the paper's transition rules (docs/physics.md
//! §7), run on the generic hybrid driver of `model-runtime`.
//!
//! # Why the transitions look the way they do
//!
//! * **Onset of sliding.** When rolling would need `T ≥ μ_st N` the disk starts to slide from
//!   `v_C = 0` in the *consistent* direction `α0` (docs/physics.md §7.1, [`onset`]). The Cartesian
//!   chart cannot represent the direction of a zero slip, so the first `2δ / v̇_C` seconds (δ = the
//!   stick threshold, ~1e-9 s of motion) are bridged by an exact linear segment along the
//!   derivative at `(u = 0, α0)`: the slip leaves the origin along `e_s(α0)` and the sliding model
//!   takes over at `|u| = 2δ`. The bridge is a mode of its own whose right-hand side is that
//!   constant derivative and whose only guard is the time it ends, so the generic driver integrates
//!   and times it exactly; its error is `O(s²)` in the step `s ≈ 5e-10 s`, far below any tolerance.
//! * **End of sliding.** `|u|` touches zero without changing sign, and the sliding field is
//!   discontinuous there, so the guard is `|u| − δ` (downward; in the polar chart, where `v_C`
//!   is signed and smooth through zero, `±v_C − δ` with the sign the slip had when the segment
//!   started); at that crossing a second
//!   bridge follows the derivative for the remaining `s = −u·u̇/|u̇|²` to the exact zero of the
//!   slip. There the rolling equations decide (docs/physics.md §7.2): rolling if `T_r < μ_st N_r`
//!   and `N_r > 0`, otherwise sliding restarts with a new consistent `α0` ([`SlipSign::Physical`](crate::SlipSign::Physical))
//!   or goes on through zero with `α` fixed and a signed slip speed ([`SlipSign::Paper`](crate::SlipSign::Paper), polar
//!   chart only).
//! * **Stops.** Contact lost (`N` falls through zero, either mode), the inclination reaching the
//!   configured floor, chattering (too many transitions in a short window), or the end time.
//!
//! Constraint drift (`Z − a sin θ`, `V_Z − a Ω_y cos θ`, and the no-slip velocity in rolling) is
//! measured after every step and removed at every switch (optionally after every step).
//!
//! # Accuracy of the decisions
//!
//! Transitions into rolling and their times converge with the tolerances (the paper's scene:
//! the first 20 agree between DP5 and DOP853 at `rtol = 1e-11` to a few ps). *Restarts* of
//! sliding (the slip reaches zero where static friction cannot hold) need the slip resolved
//! well below δ: with `atol = 1e-10` most of them pass numerically as near misses of zero (the
//! slip turns through the origin instead), which changes little else; `atol ≤ 1e-12` resolves
//! them.
//!
//! # Example
//!
//! ```
//! use equations::{
//!     simulate, DiskConfig, DiskParams, DiskRecorder, GeneratedModels, InitialState, Mode,
//!     SlipChart,
//! };
//!
//! let params = DiskParams::paper();
//! let models = GeneratedModels::generated(params, SlipChart::Cartesian).unwrap();
//! let config = DiskConfig { t_end: 0.1, ..DiskConfig::paper() };
//! let mut record = DiskRecorder::default();
//! let out = simulate(&models, &config, &InitialState::paper(&params), &mut record).unwrap();
//! // The paper's disk slides from the start and first sticks at t ≈ 0.0722 s.
//! assert_eq!(record.transitions[0].to, Mode::Sliding);
//! assert_eq!(record.transitions[1].to, Mode::Rolling);
//! assert!((record.transitions[1].t - 0.0722).abs() < 1e-4);
//! assert_eq!(out.stop.name(), "end time");
//! ```

mod drive;
pub mod embedded;
pub mod extrema;
mod graph;
pub mod models;
pub mod onset;
mod run;
pub mod switching;
pub use switching::disk;
mod switching_run;
mod system;
pub mod trailing;

pub use embedded::{EmbedError, Embedded, Embedding, Variant};
pub use extrema::{Extremum, ExtremumKind, Watched};
pub use graph::{Engine, ENGINE, GRAPH_ENGINE};
pub use models::{
    AirModel, DiskModels, GeneratedModels, PruneError, Pruned, PrunedModels, ReferenceModels,
    SlidingModel, PROBE_SLIP_SPEED, PRUNED_STATES,
};
pub use onset::{consistent_slip_direction, OnsetError, SlipAcceleration, SlipOnset};
pub use run::{simulate, simulate_graph, DiskRunner};
pub use switching_run::{simulate_switched, SwitchedDiskRun, SwitchedEvent};
pub use system::DiskGuard;
pub use trailing::Trailing;

use crate::issue::Issue;
use crate::modes::{ConstraintResiduals, ContactForce, Mode, PhysicalState};
use crate::work::WorkExceeded;
use crate::ParamError;
use model_runtime::EvalError;
use model_runtime::HybridError;
use model_runtime::SolveError;
use model_runtime::Stats;
use std::f64::consts::FRAC_PI_2;
use std::ops::ControlFlow;

/// The quantity whose crossing caused a transition, with its value there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Trigger {
    /// At the start of the run the state needs more friction than `μ_st N` to roll.
    InitialFriction {
        /// `T/N` rolling would need.
        ratio: f64,
    },
    /// While rolling, `T/N` reached `μ_st`.
    FrictionLimit {
        /// `T/N` at the event (equals `μ_st` to round-off).
        ratio: f64,
    },
    /// While sliding, the slip speed reached zero; the rolling equations were evaluated there.
    SlipStopped {
        /// `T_r/N_r` that rolling would need.
        rolling_ratio: f64,
        /// `N_r` rolling would have (N).
        rolling_normal: f64,
    },
}

/// One mode decision, as it happened.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TransitionRecord {
    /// Time (s).
    pub t: f64,
    /// Mode before.
    pub from: Mode,
    /// Mode after (sliding → sliding is a restart from zero slip).
    pub to: Mode,
    /// What fired it.
    pub trigger: Trigger,
    /// When sliding starts: the consistent friction direction `α0` (rad).
    pub slip_direction: Option<f64>,
    /// When sliding starts: the direction `α_r` of the friction rolling needed (rad), the first
    /// guess for `α0` (under [`SlipSign::Paper`](crate::SlipSign::Paper) restarts: the held direction).
    pub rolling_direction: Option<f64>,
    /// Constraint drift just before the switch's projection.
    pub drift: ConstraintResiduals,
}

/// Why a run ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StopReason {
    /// The configured end time was reached.
    EndTime,
    /// `N` fell through zero: the disk would leave the floor (free flight is not modelled).
    ContactLost {
        /// Time (s).
        t: f64,
        /// Mode at that time.
        mode: Mode,
    },
    /// θ (or π − θ) reached the configured floor ("inclination reached 0", or "… pi" for a
    /// disk that fell over past upright onto its other face).
    InclinationReachedFloor {
        /// Time (s).
        t: f64,
        /// θ there (rad).
        theta: f64,
    },
    /// The observer asked to stop ([`DiskObserver::proceed`]): an interrupt, a time budget.
    Requested {
        /// Time (s).
        t: f64,
    },
    /// The disk was about to enter a mode [`crate::DiskConfig::allowed`] does not list (or to
    /// start in one); the run ends at that decision.
    ModeNotAllowed {
        /// Time of the decision (s).
        t: f64,
        /// The mode it would have entered.
        mode: Mode,
    },
    /// Too many transitions within the chattering window.
    Chattering {
        /// Time (s).
        t: f64,
        /// Mode decisions counted in the window.
        transitions: usize,
        /// The window (s).
        window: f64,
    },
}

impl StopReason {
    /// A short human-readable name.
    pub fn name(&self) -> &'static str {
        match self {
            StopReason::EndTime => "end time",
            StopReason::ContactLost { .. } => "contact lost",
            StopReason::InclinationReachedFloor { theta, .. } if *theta > FRAC_PI_2 => {
                "inclination reached pi"
            }
            StopReason::InclinationReachedFloor { .. } => "inclination reached 0",
            StopReason::Chattering { .. } => "chattering",
            StopReason::Requested { .. } => "stopped on request",
            StopReason::ModeNotAllowed { .. } => "mode not allowed",
        }
    }
}

/// The disk at one instant, with its contact force and invariants.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiskSample {
    /// Time (s).
    pub t: f64,
    /// Mode in force.
    pub mode: Mode,
    /// State in rolling variables, with the slip (in rolling: zero speed, direction `α_r`).
    pub state: PhysicalState,
    /// Contact reaction.
    pub force: ContactForce,
    /// Total energy (J).
    pub energy: f64,
    /// Constraint drift.
    pub residuals: ConstraintResiduals,
}

/// Receives a run's output as it happens.
pub trait DiskObserver {
    /// Whether the sample due at `t` on the grid of [`DiskConfig::sample_rate`](crate::DiskConfig::sample_rate) is wanted
    /// (default: all). A declined sample costs neither an interpolation nor a model
    /// evaluation.
    fn wants_sample(&self, _t: f64) -> bool {
        true
    }
    /// After [`DiskObserver::wants_sample`] declined the sample due at `t`: a time at or
    /// before the next sample it may want (default `t`). The samples due before it are skipped
    /// without asking about each.
    fn next_wanted_sample(&self, t: f64) -> f64 {
        t
    }
    /// A sample at a requested time.
    fn on_sample(&mut self, _sample: &DiskSample) {}
    /// Whether [`DiskObserver::on_step`] should be called (each call costs a model evaluation).
    fn wants_steps(&self) -> bool {
        false
    }
    /// The state at the end of an accepted step (or at the event that cut the step short).
    fn on_step(&mut self, _sample: &DiskSample) {}
    /// A mode decision.
    fn on_transition(&mut self, _record: &TransitionRecord) {}
    /// Whether [`DiskObserver::on_extremum`] should be called: the run then scans every step's
    /// dense output ([`Extremum`]s: a few model evaluations per step). Default: no.
    fn wants_extrema(&self) -> bool {
        false
    }
    /// A located extremum of θ, N or the slip speed, in time order within each quantity.
    fn on_extremum(&mut self, _extremum: &Extremum) {}
    /// Asked after every step and every mode decision: [`ControlFlow::Break`] ends the run
    /// there with [`StopReason::Requested`] and the outcome of the work done so far.
    fn proceed(&mut self) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    /// How many seconds of the latest steps the run keeps for [`DiskObserver::on_trailing`]
    /// (default: none). Keeping them copies each step's interpolant, and has the run build it
    /// as [`DiskObserver::wants_extrema`] does (three model evaluations a step with DOP853).
    fn keeps_trailing(&self) -> Option<f64> {
        None
    }
    /// Once, when the run has ended (stopped or failed after its first step), with the steps
    /// [`DiskObserver::keeps_trailing`] asked for, to sample where the run ended
    /// ([`Trailing`]).
    fn on_trailing(&mut self, _trailing: &Trailing<'_>) {}
}

impl DiskObserver for () {}

/// An observer that keeps everything in memory (tests, short runs).
#[derive(Clone, Debug, Default)]
pub struct DiskRecorder {
    /// Samples in order.
    pub samples: Vec<DiskSample>,
    /// Mode decisions in order.
    pub transitions: Vec<TransitionRecord>,
}

impl DiskObserver for DiskRecorder {
    fn on_sample(&mut self, sample: &DiskSample) {
        self.samples.push(*sample);
    }
    fn on_transition(&mut self, record: &TransitionRecord) {
        self.transitions.push(*record);
    }
}

/// The end of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunOutcome {
    /// Why it ended.
    pub stop: StopReason,
    /// The final state.
    pub last: DiskSample,
    /// Event-driven mode decisions (the initial decision is not counted).
    pub transitions: u64,
    /// Integrator work: steps, rejections, model evaluations (bridges included).
    pub stats: Stats,
    /// Largest constraint drift seen after any step, before projection.
    pub max_drift: ConstraintResiduals,
}

/// Why a run could not be carried out.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimError {
    /// The parameters are invalid.
    #[error("invalid parameters: {0}")]
    Params(#[from] ParamError),
    /// Settings or the initial state break rules ([`crate::DiskConfig::issues`],
    /// [`crate::InitialState::issues`]), each named by its key.
    #[error("invalid settings:\n  {}", issues.iter().map(|i| i.to_string()).collect::<Vec<_>>().join("\n  "))]
    Invalid {
        /// Every broken rule.
        issues: Vec<Issue>,
    },
    /// Integration failed.
    #[error("integration failed while {mode}: {error}")]
    Solve {
        /// Mode being integrated.
        mode: Mode,
        /// What went wrong.
        error: SolveError,
    },
    /// A model failed at a decision point: the start of the run, a transition, or the final
    /// state.
    #[error("model failed deciding the mode at t = {t} (in {mode}): {source}")]
    Transition {
        /// Mode in force (before the decision).
        mode: Mode,
        /// Time (s).
        t: f64,
        /// The model's error.
        source: EvalError,
    },
    /// A model failed where the run's output is evaluated (a sample, the end of a step): the
    /// run ends there, although its integration had not failed.
    #[error("model failed evaluating the output at t = {t} (in {mode}): {source}")]
    Output {
        /// Mode in force.
        mode: Mode,
        /// Time (s).
        t: f64,
        /// The model's error.
        source: EvalError,
    },
    /// The driver's own chattering backstop fired (the disk's limit should fire first).
    #[error("chattering at t = {t}: {transitions} driver transitions in the window")]
    DriverChattering {
        /// Time (s).
        t: f64,
        /// Driver transitions counted.
        transitions: usize,
    },
    /// The run took more steps per simulated second than its [`crate::WorkBound`] allows:
    /// its step size has collapsed far below what the scene's time scale needs.
    #[error("{}", crate::work::describe(.0))]
    WorkBound(WorkExceeded),
    /// Sliding had to start but no consistent slip direction exists.
    #[error("at t = {t}: {source}")]
    Onset {
        /// Time (s).
        t: f64,
        /// Why.
        source: OnsetError,
    },
}

impl SimError {
    /// The disk's error for the driver's `error`, its modes named by the contact mode
    /// `mode_of` gives (the one conversion of a driver error, for every runner of the disk).
    pub(crate) fn from_driver<Md>(error: HybridError<Md>, mode_of: impl Fn(Md) -> Mode) -> Self {
        match error.map_mode(mode_of) {
            HybridError::Solve { mode, error } => SimError::Solve { mode, error },
            HybridError::Transition { mode, t, source } => SimError::Transition { mode, t, source },
            HybridError::Observer { mode, t, source } => SimError::Output { mode, t, source },
            HybridError::Chattering { t, transitions, .. } => {
                SimError::DriverChattering { t, transitions }
            }
        }
    }

    /// When the run failed (s); `None` for a failure before its start (invalid input).
    pub fn time(&self) -> Option<f64> {
        match self {
            SimError::Params(_) | SimError::Invalid { .. } => None,
            SimError::Solve { error, .. } => error.time(),
            SimError::Transition { t, .. }
            | SimError::Output { t, .. }
            | SimError::DriverChattering { t, .. }
            | SimError::Onset { t, .. } => Some(*t),
            SimError::WorkBound(over) => Some(over.t),
        }
    }
}

/// A run that failed, the work it did until then and where it got: a failure that reports no
/// work would hide what the run cost (and how far it got).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{error}")]
pub struct SimFailure {
    /// What went wrong.
    pub error: SimError,
    /// Integrator work until the failure (zero when the run failed before its first step);
    /// boxed, as the counters are large and a failure is rare.
    pub stats: Box<Stats>,
    /// The disk at the end of the last accepted step (`None` before the first step, or where
    /// the models cannot evaluate it); boxed, as for the work.
    pub last: Option<Box<DiskSample>>,
}

impl From<SimError> for SimFailure {
    /// A failure before any step: no work, no state reached.
    fn from(error: SimError) -> Self {
        SimFailure {
            error,
            stats: Box::default(),
            last: None,
        }
    }
}

impl From<SimFailure> for SimError {
    /// The error alone, for callers that do not count the work.
    fn from(failure: SimFailure) -> Self {
        failure.error
    }
}
