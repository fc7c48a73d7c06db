//! What a run leaves behind, in the CLI's own named types.
//!
//! The writers, the figures and the summary read only these, so they can be built and tested
//! on synthetic runs, and the simulation's own types reach them through one conversion
//! (`run::convert`).

use crate::run::model::ModelChoice;
use crate::sample::Sample;
use equations::{Extremum, Mode};

/// The quantity whose crossing caused a mode decision.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TriggerKind {
    /// At the start, rolling would need more friction than `mu_st N`.
    InitialFriction,
    /// While rolling, `T/N` reached `mu_st`.
    FrictionLimit,
    /// While sliding, the slip speed reached zero.
    SlipStopped,
}

impl TriggerKind {
    /// The trigger's name in `events.csv`.
    pub fn name(self) -> &'static str {
        match self {
            TriggerKind::InitialFriction => "initial_friction",
            TriggerKind::FrictionLimit => "friction_limit",
            TriggerKind::SlipStopped => "slip_stopped",
        }
    }

    /// What `EventRow::value` holds for this trigger.
    pub fn value_meaning(self) -> &'static str {
        match self {
            TriggerKind::InitialFriction | TriggerKind::FrictionLimit => "T/N",
            TriggerKind::SlipStopped => "T_r/N_r rolling would need",
        }
    }
}

/// One mode decision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventRow {
    /// Time (s).
    pub t: f64,
    /// Mode before.
    pub from: Mode,
    /// Mode after (sliding -> sliding: a restart from zero slip).
    pub to: Mode,
    /// What fired it.
    pub trigger: TriggerKind,
    /// The triggering quantity's value (a friction ratio, see [`TriggerKind::value_meaning`]).
    pub value: f64,
    /// When sliding starts: the friction direction α0 (rad).
    pub slip_direction: Option<f64>,
}

/// Why a run ended.
#[derive(Clone, Debug, PartialEq)]
pub struct StopRecord {
    /// Time (s).
    pub t: f64,
    /// The mode in force.
    pub mode: Mode,
    /// Short name (`end_time`, `contact_lost`, `inclination_reached_0`, `chattering`,
    /// `interrupted`, `error`).
    pub reason: String,
    /// Details (numbers, the error's message), may be empty.
    pub detail: String,
}

/// Integrator work.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Work {
    /// Accepted steps; `None` when the simulation was abandoned before it reported them.
    pub steps: Option<u64>,
    /// Right-hand-side evaluations; `None` as for `steps`.
    pub rhs_evals: Option<u64>,
    /// Wall-clock time (s).
    pub wall_s: f64,
}

/// Where the wall time of a run went (s, from its start).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Timings {
    /// The simulation, with the trajectory streamed to its file meanwhile.
    pub simulation_s: f64,
    /// A second pass over the last second of a run that stopped early (0 otherwise).
    pub replay_s: f64,
    /// Committing the trajectory and writing the events.
    pub outputs_s: f64,
    /// The summary's analysis.
    pub analysis_s: f64,
    /// The figures.
    pub figures_s: f64,
    /// Everything, up to the summary.
    pub total_s: f64,
}

/// How many samples a run kept, by where they went.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct SampleCounts {
    /// Rows of `trajectory.csv`.
    pub trajectory: usize,
    /// Fine samples of the first second (figures).
    pub first_second: usize,
    /// Fine samples of the last second (figures).
    pub last_second: usize,
}

/// Everything a run produced.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunData {
    /// Samples at the scene's rate.
    pub samples: Vec<Sample>,
    /// Finely sampled first second (for the figures).
    pub first_second: Vec<Sample>,
    /// Finely sampled last second (for the figures).
    pub last_second: Vec<Sample>,
    /// Mode decisions in order.
    pub events: Vec<EventRow>,
    /// Extrema of θ, N and the slip speed located on the dense output (module
    /// `equations::hybrid::extrema`), in the order found.
    pub extrema: Vec<Extremum>,
    /// Why it ended (`None` while running).
    pub stop: Option<StopRecord>,
    /// Integrator work.
    pub work: Work,
    /// Largest constraint drift seen (SI units, before projection); `None` when the models
    /// do not integrate every constrained state.
    pub constraint_drift_max: Option<f64>,
    /// The models that ran, and the states they left frozen.
    pub model: ModelChoice,
}
