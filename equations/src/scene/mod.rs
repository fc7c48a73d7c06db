//! A scene: which disk, which start, which modes, which solver, for how long. The tables as a
//! scene file writes them ([`SceneSettings`], read straight from TOML by any serde
//! deserialiser), and their resolution into what a run takes ([`DiskScene`]).
//!
//! Resolving checks every rule at once and reports each broken one with the key it is about
//! ([`Issue`]), so one attempt shows all the mistakes of a scene. The rules on the solver and
//! the run are [`DiskConfig::issues`], the same that [`crate::simulate`] applies to a
//! configuration built in code; the initial state is completed from the contact constraints
//! by `initial.rs`.

mod initial;

pub use initial::InitialTable;

use crate::config::{AllowedModes, DiskConfig};
use crate::issue::{Checks, Issue, Rule};
use crate::modes::Mode;
use crate::params::DiskParams;
use crate::settings::{RunTable, SolverTable};
use crate::start::InitialState;
use serde::{Deserialize, Serialize};

/// The most samples a scene's run may record (a program keeps them, for figures, say).
pub const MAX_RECORDED_SAMPLES: f64 = 5e6;

/// A whole scene, as written. Every table rejects keys it does not know, so a misspelt key
/// is an error, not a silently ignored line.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SceneSettings {
    /// The disk's body and gravity.
    pub disk: DiskTable,
    /// Friction coefficients.
    pub friction: FrictionTable,
    /// Air resistance (default: still air without drag).
    #[serde(default)]
    pub air: AirTable,
    /// The initial state by the paper's names.
    pub initial: InitialTable,
    /// Which modes the simulation may enter (default: both).
    #[serde(default)]
    pub modes: ModesTable,
    /// Integrator and tolerances (defaults: [`SolverTable::default`]).
    #[serde(default)]
    pub solver: SolverTable,
    /// Duration, sampling, slip rule.
    pub run: RunTable,
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

/// `[air]`: the paper's linear air model (docs/physics.md).
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

/// `[modes]`: the modes the simulation may enter.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ModesTable {
    /// Allowed modes, `rolling` and/or `sliding` (default: both, also in a `[modes]` table
    /// that does not name them).
    #[serde(default = "all_modes")]
    pub allowed: Vec<Mode>,
}

/// Both modes: what `modes.allowed` is when not given.
fn all_modes() -> Vec<Mode> {
    AllowedModes::ALL.modes()
}

impl Default for ModesTable {
    fn default() -> Self {
        ModesTable {
            allowed: all_modes(),
        }
    }
}

/// A scene whose every rule holds, in the form a run takes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiskScene {
    /// The disk's parameters.
    pub params: DiskParams,
    /// The run's settings (samples at the scene's `run.sample_rate`).
    pub config: DiskConfig,
    /// The completed initial state.
    pub initial: InitialState,
}

impl SceneSettings {
    /// The disk's parameters as written (unchecked).
    pub fn params(&self) -> DiskParams {
        DiskParams {
            m: self.disk.m,
            a: self.disk.a,
            g: self.disk.g,
            mu_d: self.friction.mu_d,
            mu_st: self.friction.mu_st,
            mu_a: self.air.mu_a,
            w_z: self.air.w_z,
        }
    }

    /// Checks every rule and completes the initial state; on success the scene in the form a
    /// run takes, else every issue found.
    pub fn resolve(&self) -> Result<DiskScene, Vec<Issue>> {
        let mut c = Checks::default();
        let params = self.params();
        c.issues.extend(params.issues());
        let a_ok = !c.issues.iter().any(|i| i.key == "disk.a");
        let mut config = DiskConfig::new(&self.solver, &self.run);
        config.allowed = AllowedModes::of(&self.modes.allowed);
        // The recorded samples are bounded below the delivered ones: checked here, by the
        // scene's own rule.
        let unsampled = DiskConfig {
            sample_rate: None,
            ..config
        };
        c.issues.extend(unsampled.issues(0.0, config.chart()));
        self.check_recorded_samples(&mut c);
        self.check_modes(&mut c);
        let initial = if a_ok {
            self.initial.complete(&params, &mut c)
        } else {
            None
        };
        if let Some(start) = initial.filter(|s| s.mode == Mode::Sliding) {
            if !config.allowed.sliding {
                c.push(
                    "initial.v_C",
                    Rule::ModeNotAllowed {
                        mode: Mode::Sliding.name(),
                        because: format!(
                            "the contact particle slips at {:e} m/s",
                            start.state.slip.speed
                        ),
                    },
                );
            }
        }
        match initial {
            Some(initial) if c.issues.is_empty() => Ok(DiskScene {
                params,
                config,
                initial,
            }),
            _ => Err(c.issues),
        }
    }

    fn check_recorded_samples(&self, c: &mut Checks) {
        let run = &self.run;
        if !c.positive("run.sample_rate", run.sample_rate) {
            return;
        }
        if !(run.t_end.is_finite() && run.t_end > 0.0) {
            // `run.t_end` has its own issue.
            return;
        }
        // May overflow to infinity, which is over the limit too.
        let samples = run.t_end * run.sample_rate;
        if samples > MAX_RECORDED_SAMPLES {
            // Blame the key that left its usual value: a raised rate, else the duration.
            let key = if run.sample_rate > RunTable::DEFAULT_SAMPLE_RATE {
                "run.sample_rate"
            } else {
                "run.t_end"
            };
            c.push(
                key,
                Rule::TooManySamples {
                    samples,
                    limit: MAX_RECORDED_SAMPLES,
                    t_end: run.t_end,
                    sample_rate: run.sample_rate,
                },
            );
        }
    }

    fn check_modes(&self, c: &mut Checks) {
        let allowed = &self.modes.allowed;
        if allowed.is_empty() {
            c.push("modes.allowed", Rule::Empty);
        }
        for (i, mode) in allowed.iter().enumerate() {
            if allowed[..i].contains(mode) {
                c.push(
                    "modes.allowed",
                    Rule::Duplicate {
                        name: mode.to_string(),
                    },
                );
            }
        }
    }
}
