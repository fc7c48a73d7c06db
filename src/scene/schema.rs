//! The scene file as written: every table and key a scene may contain, nothing else.
//!
//! `deny_unknown_fields` on every table turns a misspelt key into an error instead of a
//! silently ignored line; the loader reports the path of the key (`friction.mu`). Values are
//! kept as written here; the rules between them live in `validate.rs`.

use equations::hybrid::{
    DiskConfig, ErrorNorm, IntegratorChoice, InteriorChecks, StepControl, TimeVariable,
};
use serde::{Deserialize, Serialize};

/// A whole scene file.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// One line saying what the scene shows.
    #[serde(default)]
    pub description: Option<String>,
    /// The disk's body and gravity.
    pub disk: DiskTable,
    /// Friction coefficients.
    pub friction: FrictionTable,
    /// Air resistance (optional: still air without drag).
    #[serde(default)]
    pub air: AirTable,
    /// The initial state by the paper's names.
    pub initial: InitialTable,
    /// Which modes the simulation may enter.
    #[serde(default)]
    pub modes: ModesTable,
    /// Integrator and tolerances.
    #[serde(default)]
    pub solver: SolverTable,
    /// Duration, sampling, slip rule.
    pub run: RunTable,
    /// What goes into `trajectory.csv`.
    #[serde(default)]
    pub output: OutputTable,
}

/// `[disk]`: mass, radius, gravity.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct DiskTable {
    /// Mass (kg).
    pub m: f64,
    /// Radius (m).
    pub a: f64,
    /// Gravitational acceleration (m/s²).
    pub g: f64,
}

/// `[friction]`: dynamic and static coefficients.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FrictionTable {
    /// Dynamic (sliding) coefficient.
    pub mu_d: f64,
    /// Static coefficient (rolling holds while `T/N < mu_st`).
    pub mu_st: f64,
}

/// `[air]`: the paper's linear air model (eq. 11).
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AirTable {
    /// Air coefficient (N·s/m³), 0 for no drag.
    #[serde(default)]
    pub mu_a: f64,
    /// Normal air velocity (m/s), 0 for still air.
    #[serde(default)]
    pub w_z: f64,
}

/// `[initial]`: the state by the paper's names; omitted entries follow from the constraints
/// (`Z`, `V_Z`, and the horizontal velocity of a rolling start) or are 0.
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
pub struct InitialTable {
    /// Centre position X (m).
    pub X: Option<f64>,
    /// Centre position Y (m).
    pub Y: Option<f64>,
    /// Centre height (m); must equal `a sin(theta)`.
    pub Z: Option<f64>,
    /// Centre velocity X (m/s).
    pub V_X: Option<f64>,
    /// Centre velocity Y (m/s).
    pub V_Y: Option<f64>,
    /// Centre velocity Z (m/s); must equal `a Omega_y cos(theta)`.
    pub V_Z: Option<f64>,
    /// Precession angle (rad).
    pub psi: Option<f64>,
    /// Inclination (rad), required, in (0, π).
    pub theta: Option<f64>,
    /// Spin angle (rad).
    pub phi: Option<f64>,
    /// Angular velocity, `e_x` component (rad/s).
    pub Omega_x: Option<f64>,
    /// Angular velocity, `e_y` component (rad/s).
    pub Omega_y: Option<f64>,
    /// Angular velocity, `e_z` component (rad/s).
    pub Omega_z: Option<f64>,
    /// Slip speed of the contact particle (m/s), instead of `V_X`, `V_Y`.
    pub v_C: Option<f64>,
    /// Direction of the friction force (rad), with `v_C`.
    pub alpha: Option<f64>,
}

/// A mode of contact.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[serde(rename_all = "lowercase")]
pub enum ModeName {
    /// The contact particle is at rest.
    Rolling,
    /// The contact particle slips; friction is `mu_d N` against the slip.
    Sliding,
}

impl ModeName {
    /// The name as written in scenes and output files.
    pub fn as_str(self) -> &'static str {
        match self {
            ModeName::Rolling => "rolling",
            ModeName::Sliding => "sliding",
        }
    }
}

impl std::fmt::Display for ModeName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// `[modes]`: the modes the simulation may enter.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ModesTable {
    /// Allowed modes (default: both).
    pub allowed: Vec<ModeName>,
}

impl Default for ModesTable {
    fn default() -> Self {
        ModesTable {
            allowed: vec![ModeName::Rolling, ModeName::Sliding],
        }
    }
}

/// The integrators a scene may name.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorName {
    /// Dormand–Prince 5(4).
    Dopri5,
    /// Dormand–Prince 8(5,3).
    Dop853,
    /// Rodas4, linearly implicit (uses the generated symbolic Jacobians): for stiff stretches.
    Rodas4,
}

impl IntegratorName {
    /// The name as written in scenes.
    pub fn as_str(self) -> &'static str {
        match self {
            IntegratorName::Dopri5 => "dopri5",
            IntegratorName::Dop853 => "dop853",
            IntegratorName::Rodas4 => "rodas4",
        }
    }
}

/// `[solver]`: integrator and tolerances.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SolverTable {
    /// The integrator (default `dop853`, from `DiskConfig::default`).
    #[serde(default = "default_integrator")]
    pub integrator: IntegratorName,
    /// Relative tolerance (default the paper's 1e-8).
    #[serde(default = "default_rtol")]
    pub rtol: f64,
    /// Absolute tolerance (default the paper's 1e-10).
    #[serde(default = "default_atol")]
    pub atol: f64,
    /// Where inside each step the guards are looked at: `none`, `exact:N` or `screened:N`
    /// (default `screened:64`, BENCHMARKS.md §3).
    #[serde(default = "default_guard_checks")]
    pub guard_checks: Spelled<InteriorChecks>,
    /// How the error of a vector is measured: `components` (default) or `vectors` (each
    /// component against the length of its vector, BENCHMARKS.md §3).
    #[serde(default = "default_error_norm")]
    pub error_norm: Spelled<ErrorNorm>,
    /// The step-size controller: `pi-gustafsson` (default), `pi-hairer` or `integral`.
    #[serde(default = "default_step_control")]
    pub step_control: Spelled<StepControl>,
    /// The variable the integrator steps in: `physical` time or `regularised` (slowed near
    /// zero slip and near lying flat, so steps stay long there; BENCHMARKS.md §3).
    #[serde(default = "default_time")]
    pub time: Spelled<TimeVariable>,
}

/// A `[solver]` setting written as a word that its type parses and prints (`screened:64`,
/// `vectors`, `pi-hairer`): one reading and writing rule for all of them, and a bad word is
/// rejected with the type's own message, which lists the valid spellings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Spelled<T>(pub T);

impl<'de, T> Deserialize<'de> for Spelled<T>
where
    T: std::str::FromStr,
    T::Err: std::fmt::Display,
{
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = String::deserialize(d)?;
        text.parse().map(Spelled).map_err(serde::de::Error::custom)
    }
}

impl<T: std::fmt::Display> Serialize for Spelled<T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(&self.0)
    }
}

fn default_guard_checks() -> Spelled<InteriorChecks> {
    Spelled(DiskConfig::default().guard_checks)
}
fn default_error_norm() -> Spelled<ErrorNorm> {
    Spelled(DiskConfig::default().error_norm)
}
fn default_step_control() -> Spelled<StepControl> {
    Spelled(DiskConfig::default().step_control)
}
fn default_time() -> Spelled<TimeVariable> {
    Spelled(DiskConfig::default().time)
}
fn default_integrator() -> IntegratorName {
    match DiskConfig::default().integrator {
        IntegratorChoice::Dopri5 => IntegratorName::Dopri5,
        IntegratorChoice::Rodas4 => IntegratorName::Rodas4,
        IntegratorChoice::Dop853 | IntegratorChoice::Rk4 { .. } => IntegratorName::Dop853,
    }
}
fn default_rtol() -> f64 {
    DiskConfig::default().rtol
}
fn default_atol() -> f64 {
    DiskConfig::default().atol
}

impl Default for SolverTable {
    fn default() -> Self {
        SolverTable {
            integrator: default_integrator(),
            rtol: default_rtol(),
            atol: default_atol(),
            guard_checks: default_guard_checks(),
            error_norm: default_error_norm(),
            step_control: default_step_control(),
            time: default_time(),
        }
    }
}

/// Which reading of the slip speed's sign to use (docs/physics.md §7.4).
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SlipSignRule {
    /// `v_C >= 0`: a zero of the slip speed is always a mode decision.
    Physical,
    /// The paper's signed slip speed: `v_C` may pass through zero while sliding continues.
    Paper,
}

/// `[run]`: duration, sampling and the slip rule.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RunTable {
    /// Simulated time (s).
    pub t_end: f64,
    /// Samples per second in `trajectory.csv` (default 1000).
    #[serde(default = "default_sample_rate")]
    pub sample_rate: f64,
    /// The slip-sign rule (default `physical`).
    #[serde(default = "default_slip_sign")]
    pub slip_sign: SlipSignRule,
}

/// The default of `run.sample_rate` (samples per second).
pub(crate) fn default_sample_rate() -> f64 {
    1000.0
}
fn default_slip_sign() -> SlipSignRule {
    SlipSignRule::Physical
}

/// `[output]`: the quantities written to `trajectory.csv`. They also decide the models that
/// run: when none of them (nor the figures) needs a state the pruned variants drop (`X`, `Y`,
/// `Z`, `phi`, hence `energy`, `residual_Z`) and the air is still, the pruned 8-state models
/// run (`crate::run::model`).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct OutputTable {
    /// Quantity names (see `eulerdisk quantities`); default all.
    pub quantities: Vec<String>,
}

impl Default for OutputTable {
    fn default() -> Self {
        OutputTable {
            quantities: crate::quantity::Quantity::ALL
                .iter()
                .map(|q| q.name().to_string())
                .collect(),
        }
    }
}
