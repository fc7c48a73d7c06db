//! The solver and run settings as a scene writes them: the integrator and its tolerances,
//! the time variable, the end time, the sampling and the slip rule, with the one set of
//! defaults every scene without a `[solver]` table gets.
//!
//! The words a scene uses (`dop853`, `screened:64`, `regularised`) are the types' own
//! spellings, read and printed by one rule ([`spelled`]), so a scene file, a `--set` and a
//! `summary.json` spell every setting alike.

use crate::modes::SlipChart;
use crate::work::WorkBound;
use model_runtime::{parse_word, ParseSettingError};
use model_runtime::{InteriorChecks, StepControl};
use serde::{Deserialize, Serialize};
use std::ops::Range;

/// Which integrator runs every segment; spelled `dopri5`, `dop853`, `rodas4` in scene files
/// (RK4 is for programs only).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Integrator {
    /// Dormand–Prince 5(4) with its 4th-order dense output (the paper's `ode45`).
    Dopri5,
    /// Dormand–Prince 8(5,3) with its 7th-order dense output.
    Dop853,
    /// Rodas4, linearly implicit (stiff stretches); Jacobians by finite differences.
    Rodas4,
    /// Classical RK4 with a fixed step (s), for quick previews; no error control.
    #[serde(skip)]
    Rk4 {
        /// Step size (s).
        h: f64,
    },
}

/// How the slip speed is read when it reaches zero and static friction cannot hold; spelled
/// `physical` or `paper` in scene files.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SlipSign {
    /// `v_C ≥ 0` (docs/physics.md §7.4): sliding restarts from zero slip in a new consistent
    /// direction, so friction always opposes the slip.
    #[default]
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

impl Integrator {
    /// The name as written in scenes (`rk4` for the fixed-step method).
    pub fn name(self) -> &'static str {
        match self {
            Integrator::Dopri5 => "dopri5",
            Integrator::Dop853 => "dop853",
            Integrator::Rodas4 => "rodas4",
            Integrator::Rk4 { .. } => "rk4",
        }
    }
}

impl std::fmt::Display for Integrator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Integrator::Rk4 { h } => write!(f, "rk4 (h = {h} s)"),
            other => f.write_str(other.name()),
        }
    }
}

impl SlipSign {
    /// The slip chart a run under this rule slides in: the paper's signed slip exists only in
    /// the polar chart; otherwise the Cartesian chart, smooth through near misses of zero.
    pub fn chart(self) -> SlipChart {
        match self {
            SlipSign::Physical => SlipChart::Cartesian,
            SlipSign::Paper => SlipChart::Polar,
        }
    }
}

/// `[solver]`: the integrator and its tolerances. [`SolverTable::default`] holds the
/// project's recommended settings, the defaults of every scene (BENCHMARKS.md §3): DOP853 in
/// regularised time at the paper's `rtol = 1e-8`, `atol = 1e-10`, per-component error norm,
/// the PI controller of Gustafsson, and guards screened at 64 interior points per step. On the
/// paper's 100 s scene these take 2.7 times fewer steps than the paper's own settings
/// ([`crate::DiskConfig::paper`]) for 4% fewer model evaluations, find every one of the 7483
/// transitions a run at `rtol = 1e-13` finds (DP5 in physical time: 7436), and place the first
/// 100 of them as accurately.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct SolverTable {
    /// The integrator (`dop853`).
    pub integrator: Integrator,
    /// Relative tolerance (`1e-8`).
    pub rtol: f64,
    /// Absolute tolerance (`1e-10`).
    pub atol: f64,
    /// Where inside each step the guards are looked at: `none`, `exact:N` or `screened:N`
    /// (`screened:64`).
    #[serde(with = "spelled")]
    pub guard_checks: InteriorChecks,
    /// How the error of a vector is measured: `components` or `vectors` (`components`).
    #[serde(with = "spelled")]
    pub error_norm: ErrorNorm,
    /// The step-size controller: `pi-gustafsson`, `pi-hairer` or `integral`
    /// (`pi-gustafsson`).
    #[serde(with = "spelled")]
    pub step_control: StepControl,
    /// The variable the integrator steps in: `physical` or `regularised` (`regularised`).
    #[serde(with = "spelled")]
    pub time: TimeVariable,
    /// The work bound: accepted steps allowed per simulated second (`1e6`,
    /// [`WorkBound::DEFAULT`]); a run over it fails instead of running for hours.
    pub max_steps_per_s: f64,
}

impl Default for SolverTable {
    fn default() -> Self {
        SolverTable {
            integrator: Integrator::Dop853,
            rtol: 1e-8,
            atol: 1e-10,
            guard_checks: InteriorChecks::Screened(64),
            error_norm: ErrorNorm::Components,
            step_control: StepControl::PiGustafsson,
            time: TimeVariable::Regularised,
            max_steps_per_s: WorkBound::DEFAULT.steps_per_s,
        }
    }
}

/// `[run]`: duration, sampling and the slip rule.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RunTable {
    /// Simulated time (s), required.
    pub t_end: f64,
    /// Samples per second of the recorded trajectory ([`RunTable::DEFAULT_SAMPLE_RATE`]).
    #[serde(default = "RunTable::default_sample_rate")]
    pub sample_rate: f64,
    /// The slip-sign rule (`physical`).
    #[serde(default)]
    pub slip_sign: SlipSign,
}

impl RunTable {
    /// The default of `run.sample_rate` (samples per second).
    pub const DEFAULT_SAMPLE_RATE: f64 = 1000.0;

    fn default_sample_rate() -> f64 {
        Self::DEFAULT_SAMPLE_RATE
    }

    /// A run of `t_end` seconds with the default sampling and slip rule.
    pub fn lasting(t_end: f64) -> Self {
        RunTable {
            t_end,
            sample_rate: Self::DEFAULT_SAMPLE_RATE,
            slip_sign: SlipSign::default(),
        }
    }
}

/// Reads and writes a setting as the word its type parses and prints (`screened:64`,
/// `vectors`, `pi-hairer`): one rule for all of them, and a bad word is rejected with the
/// type's own message, which lists the valid spellings. Use as `#[serde(with = "spelled")]`.
pub mod spelled {
    use serde::{Deserialize, Deserializer, Serializer};
    use std::fmt::Display;
    use std::str::FromStr;

    /// Parses the word with the type's `FromStr`.
    pub fn deserialize<'de, D, T>(d: D) -> Result<T, D::Error>
    where
        D: Deserializer<'de>,
        T: FromStr,
        T::Err: Display,
    {
        let text = String::deserialize(d)?;
        text.parse().map_err(serde::de::Error::custom)
    }

    /// Writes the word with the type's `Display`.
    pub fn serialize<S: Serializer, T: Display>(value: &T, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(value)
    }
}
