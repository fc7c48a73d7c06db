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
//!   and `N_r > 0`, otherwise sliding restarts with a new consistent `α0` ([`SlipSign::Physical`])
//!   or goes on through zero with `α` fixed and a signed slip speed ([`SlipSign::Paper`], polar
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
//! use equations::hybrid::{simulate, DiskConfig, DiskRecorder, GeneratedModels, InitialState};
//! use equations::modes::{Mode, SlipChart};
//! use equations::DiskParams;
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

pub mod embedded;
pub mod models;
pub mod onset;
mod run;
mod system;

pub use embedded::{EmbedError, Embedded, Embedding, Variant};
pub use models::{
    DiskModels, GeneratedModels, PruneError, Pruned, PrunedModels, ReferenceModels, SlidingModel,
    PROBE_SLIP_SPEED, PRUNED_STATES,
};
pub use onset::{consistent_slip_direction, OnsetError, SlipAcceleration, SlipOnset};
pub use run::simulate;
pub use system::DiskGuard;

use crate::modes::{ConstraintResiduals, ContactForce, Mode, PhysicalState, SlipChart, DIM};
use crate::ParamError;
/// Where a step's interior is searched for guard crossings (re-exported from the runtime).
pub use model_runtime::InteriorChecks;
/// Whether a run counts the component that limits each step (re-exported from the runtime).
pub use model_runtime::LimitingComponent;
/// The gains of the step-size controller (re-exported from the runtime).
pub use model_runtime::StepControl;
use model_runtime::{parse_word, EvalError, ParseSettingError, SolveError, Stats};
use std::f64::consts::FRAC_PI_2;
use std::ops::{ControlFlow, Range};

/// Which integrator runs every segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum IntegratorChoice {
    /// Dormand–Prince 5(4) with its 4th-order dense output (the paper's `ode45`).
    Dopri5,
    /// Dormand–Prince 8(5,3) with its 7th-order dense output.
    Dop853,
    /// Rodas4, linearly implicit (stiff stretches); Jacobians by finite differences.
    Rodas4,
    /// Classical RK4 with a fixed step (s), for quick previews; no error control.
    Rk4 {
        /// Step size (s).
        h: f64,
    },
}

/// How the slip speed is read when it reaches zero and static friction cannot hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlipSign {
    /// `v_C ≥ 0` (docs/physics.md §7.4): sliding restarts from zero slip in a new consistent
    /// direction, so friction always opposes the slip.
    Physical,
    /// The paper's signed slip speed: `v_C` passes through zero with `α` held fixed, after which
    /// friction points along the slip. Needs the polar chart.
    Paper,
}

/// How the integration error of the disk's state is measured.
///
/// A relative tolerance applied per component depends on the frame a vector is written in.
/// `Ω` is written in the precessing frame, which turns at `ψ̇ ≈ 1e3–1e4 rad/s` late in the
/// run; there `Ω_z` is ~70 times smaller than `|Ω|`, so with [`ErrorNorm::Components`] its
/// own scale `atol + rtol |Ω_z|` is the tightest: it limits 59% of the paper run's steps.
/// [`ErrorNorm::Vectors`] scales each component of a vector by the vector's length
/// (`model_runtime::Tolerance` gives the exact rule), which no choice of frame changes.
///
/// Fewer steps are not the same as less work for the same answer. On the paper's 100 s run at
/// `rtol = 1e-8` the vector norm takes 13% fewer steps (685 k) and misses more sliding
/// restarts (85 of 568, against 47), its final θ 100× farther from the reference's (9e-4 rad
/// against 9e-6); in the work-precision sweep (paper scene, 1 s and 10 s)
/// its final-state error at equal cost lies between a quarter of and five times that of the
/// per-component norm, and on pure rolling the two lie on one line. So the per-component norm
/// stays the default.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ErrorNorm {
    /// Every component by its own magnitude (the paper's `ode45` norm).
    #[default]
    Components,
    /// `(Ω_x, Ω_y, Ω_z)` as one vector, and state slots 3 and 4 as one: the centre's
    /// horizontal velocity `(V_X, V_Y)` in rolling, the slip `(u_X, u_Y)` in the Cartesian
    /// sliding chart. The polar chart's `(v_C, α)` is a speed and an angle, not a Cartesian
    /// vector, so there those two stay per component. The rest (position, `V_Z`, angles) stays
    /// per component too: a run has one norm for all its modes, and slot 5 (`V_Z`) cannot
    /// join slots 3 and 4 in rolling without joining the slip in sliding.
    Vectors,
}

/// Spelled `components` or `vectors`, as in scene files and command lines.
impl std::fmt::Display for ErrorNorm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            ErrorNorm::Components => "components",
            ErrorNorm::Vectors => "vectors",
        })
    }
}

impl std::str::FromStr for ErrorNorm {
    type Err = ParseSettingError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        parse_word(
            s,
            &[ErrorNorm::Components, ErrorNorm::Vectors],
            "error norm",
            "components or vectors",
        )
    }
}

impl ErrorNorm {
    /// The groups of state components scaled as one vector in a run sliding in `chart`
    /// (the same in every mode of the run; see [`ErrorNorm::Vectors`]).
    pub fn groups(self, chart: SlipChart) -> &'static [Range<usize>] {
        use crate::modes::layout::{OMEGA_X, OMEGA_Z, U_X, U_Y};
        const OMEGA: Range<usize> = OMEGA_X..OMEGA_Z + 1;
        const CARTESIAN: &[Range<usize>] = &[U_X..U_Y + 1, OMEGA];
        const POLAR: &[Range<usize>] = &[OMEGA];
        match (self, chart) {
            (ErrorNorm::Components, _) => &[],
            (ErrorNorm::Vectors, SlipChart::Cartesian) => CARTESIAN,
            (ErrorNorm::Vectors, SlipChart::Polar) => POLAR,
        }
    }
}

/// In which time variable the disk is integrated.
///
/// Most of the steps of a rattling run are spent where the right-hand side is not smooth:
/// the friction direction `u/|u|` of a slip about to stick or just started, and the bounce at
/// the nutation minima where `θ` nearly vanishes and `ψ̇ ∝ 1/sin θ`. [`TimeVariable::Regularised`]
/// integrates in `τ` with `dt = s dτ` (`model_runtime::Regularised`), where
/// `s = S_θ S_u`, `S_θ = θ̃/(θ̃ + θ_c)` with `θ̃ = min(θ, π − θ)` and `θ_c` =
/// [`TimeVariable::THETA_SCALE`], and, while sliding, `S_u = |u|/(|u| + u_c)` with `u_c` =
/// [`TimeVariable::SLIP_SCALE`] (1 while rolling and on a bridge). The scaled field
/// `s f` is smooth through `u → 0` (the `1/|u|` of the friction direction is cancelled), so
/// the steps in `τ` stay long where the steps in `t` must shrink. Events, samples and the end
/// time stay in physical time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TimeVariable {
    /// Physical time `t`.
    #[default]
    Physical,
    /// The regularised time `τ` described above.
    Regularised,
}

impl TimeVariable {
    /// `θ_c` (rad): below it the inclination slows the clock.
    pub const THETA_SCALE: f64 = 0.1;
    /// `u_c` (m/s): below it the slip speed slows the clock. On the paper's scene 1e-3 takes
    /// the fewest steps (1e-2: +4%, 1e-4: +4%, 1e-5: +17%); `θ_c` between 0.01 and 1 changes
    /// them by 2% (BENCHMARKS.md §3).
    pub const SLIP_SCALE: f64 = 1e-3;
}

/// Spelled `physical` or `regularised`, as in scene files and command lines.
impl std::fmt::Display for TimeVariable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            TimeVariable::Physical => "physical",
            TimeVariable::Regularised => "regularised",
        })
    }
}

impl std::str::FromStr for TimeVariable {
    type Err = ParseSettingError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        parse_word(
            s,
            &[TimeVariable::Physical, TimeVariable::Regularised],
            "time variable",
            "physical or regularised",
        )
    }
}

/// Transitions allowed in a short window before the run is stopped as chattering.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChatterLimit {
    /// Mode decisions (rolling ↔ sliding, sliding restarts) allowed within one window.
    pub max_transitions: usize,
    /// The window's width (s).
    pub window: f64,
}

/// Where a run starts: a time and a state in rolling variables
/// `(X, Y, Z, V_X, V_Y, V_Z, ψ, θ, φ, Ω_x, Ω_y, Ω_z)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InitialState {
    /// Start time (s).
    pub t: f64,
    /// The state; `V_X, V_Y` may include a slip of the contact particle.
    pub y: [f64; DIM],
}

impl InitialState {
    /// The paper's start (docs/physics.md §11): centre above the origin at rest, `ψ = φ = 0`,
    /// `θ0 = π/2 − 1`, `Ω = (1, 0, 0)` rad/s, on the rolling constraints.
    pub fn paper(params: &crate::DiskParams) -> Self {
        let theta0 = std::f64::consts::FRAC_PI_2 - 1.0;
        let mut y = [0.0; DIM];
        y[crate::modes::layout::Z] = params.a * theta0.sin();
        y[crate::modes::layout::THETA] = theta0;
        y[crate::modes::layout::OMEGA_X] = 1.0;
        InitialState { t: 0.0, y }
    }
}

/// Everything a run needs besides the models and the initial state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiskConfig {
    /// The integrator.
    pub integrator: IntegratorChoice,
    /// Relative tolerance (every component).
    pub rtol: f64,
    /// Absolute tolerance (every component, in its own unit).
    pub atol: f64,
    /// Whether the error of a vector is measured against its own components or its length.
    pub error_norm: ErrorNorm,
    /// How the step size follows the error estimates (adaptive methods).
    pub step_control: StepControl,
    /// Whether the run counts, for every accepted step, the state component with the largest
    /// scaled error (the one that limited the step) in `RunOutcome::stats.limiting`.
    /// A diagnostic: tracking costs a search over the components per step.
    pub limiting_component: LimitingComponent,
    /// End time (s).
    pub t_end: f64,
    /// Reading of the slip speed's sign.
    pub slip_sign: SlipSign,
    /// Slip speed δ (m/s) at which the end of sliding is detected; the remaining approach to
    /// zero is bridged exactly, so δ does not move the events (tested: 1e-9 and 1e-10 give the
    /// same times to < 1e-9 s). Must lie well above the integration error of the slip (a few
    /// `atol`) and far below the slip speeds of interest; sliding starts at `2δ`.
    pub stick_threshold: f64,
    /// The run stops when the disk comes this close to lying flat (rad): when θ falls to it,
    /// or, for a disk leaning past upright, when π − θ does. Positive: both models are singular
    /// at sin θ = 0, and the event's state must still be one they can evaluate.
    pub min_inclination: f64,
    /// Project onto the contact constraints after every accepted step (always at switches).
    pub project_each_step: bool,
    /// Samples per second delivered to the observer; `None` for none.
    pub sample_rate: Option<f64>,
    /// Interior points of each step where the guards are checked too. A friction ratio can
    /// rise through `μ_st` and fall back within one step near a peak of `N`; checked at the
    /// step ends only, the paper run finds 6085 transitions; with 4 exact interior checks
    /// 6585; screening 64 interior points on the dense output (no model evaluation unless an
    /// estimate shows a crossing, and only 2 estimates in a step whose guards stay clear of
    /// zero) finds 7435, and 128 or 256 points find the same (7438, 7437) — the default, at
    /// about 15% more time than no checks (BENCHMARKS.md, "Guard checks").
    pub guard_checks: InteriorChecks,
    /// Chattering detection.
    pub chatter: ChatterLimit,
    /// Budget of step attempts for the whole run.
    pub max_steps: u64,
    /// The time variable the integrator steps in (adaptive integrators only).
    pub time: TimeVariable,
}

impl DiskConfig {
    /// The paper's settings: DP5 (its `ode45`) in physical time at `rtol = 1e-8`,
    /// `atol = 1e-10` over 100 s, physical slip. [`DiskConfig::default`] is what this
    /// project recommends for the same scene.
    pub fn paper() -> Self {
        DiskConfig {
            integrator: IntegratorChoice::Dopri5,
            rtol: 1e-8,
            atol: 1e-10,
            error_norm: ErrorNorm::Components,
            step_control: StepControl::PiGustafsson,
            limiting_component: LimitingComponent::Untracked,
            t_end: 100.0,
            slip_sign: SlipSign::Physical,
            stick_threshold: 1e-9,
            min_inclination: 1e-9,
            project_each_step: false,
            sample_rate: None,
            guard_checks: InteriorChecks::Screened(64),
            chatter: ChatterLimit {
                max_transitions: 50,
                window: 1e-6,
            },
            max_steps: 500_000_000,
            time: TimeVariable::Physical,
        }
    }
}

impl Default for DiskConfig {
    /// The recommended settings, the scenes' defaults: the paper's tolerances, DOP853 in
    /// [`TimeVariable::Regularised`] time. On the paper's 100 s scene it takes 2.7 times fewer
    /// steps than [`DiskConfig::paper`] for 4% fewer model evaluations, finds every one of
    /// the 7483 transitions a run at `rtol = 1e-13` finds (DP5 in physical time: 7436), and
    /// places the first 100 of them as accurately (BENCHMARKS.md §3).
    fn default() -> Self {
        DiskConfig {
            integrator: IntegratorChoice::Dop853,
            time: TimeVariable::Regularised,
            ..DiskConfig::paper()
        }
    }
}

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
    /// guess for `α0` (under [`SlipSign::Paper`] restarts: the held direction).
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
    /// The observer asked to stop ([`DiskObserver::proceed`]): an interrupt, a time budget,
    /// a mode the caller forbids.
    Requested {
        /// Time (s).
        t: f64,
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
    /// Whether the sample due at `t` on the grid of [`DiskConfig::sample_rate`] is wanted
    /// (default: all). A declined sample costs neither an interpolation nor a model
    /// evaluation.
    fn wants_sample(&self, _t: f64) -> bool {
        true
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
    /// Asked after every step and every mode decision: [`ControlFlow::Break`] ends the run
    /// there with [`StopReason::Requested`] and the outcome of the work done so far.
    fn proceed(&mut self) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
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
    /// A setting is out of range.
    #[error("invalid setting `{name}` = {value}: {reason}")]
    Config {
        /// The setting.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What is wrong.
        reason: &'static str,
    },
    /// The initial state is not finite or not on the floor.
    #[error("invalid initial state: component {component} = {value}")]
    InitialState {
        /// Index in the rolling layout.
        component: usize,
        /// Its value.
        value: f64,
    },
    /// The paper's signed slip needs the polar chart.
    #[error("the paper's signed slip speed needs the polar slip chart")]
    SignedSlipNeedsPolarChart,
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
    /// The driver's own chattering backstop fired (the disk's limit should fire first).
    #[error("chattering at t = {t}: {transitions} driver transitions in the window")]
    DriverChattering {
        /// Time (s).
        t: f64,
        /// Driver transitions counted.
        transitions: usize,
    },
    /// Sliding had to start but no consistent slip direction exists.
    #[error("at t = {t}: {source}")]
    Onset {
        /// Time (s).
        t: f64,
        /// Why.
        source: OnsetError,
    },
}
