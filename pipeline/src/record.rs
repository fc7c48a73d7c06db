//! What a run leaves behind: the library's records (`equations::record`) gathered, with the
//! work it did and where its time went.
//!
//! The writers, the figures and the summary read only these, so they can be built and tested
//! on synthetic runs. The samples, the mode decisions and the stop are the library's own
//! types; what is added here is the command line's: how the samples were kept, the models
//! chosen, the wall time.

use crate::run::model::ModelChoice;
use equations::record::{Sample, Stop};
use equations::{Extremum, TransitionRecord};

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
    pub events: Vec<TransitionRecord>,
    /// Extrema of θ, N and the slip speed located on the dense output (module
    /// `equations::hybrid::extrema`), in the order found.
    pub extrema: Vec<Extremum>,
    /// Why it ended (`None` while running).
    pub stop: Option<Stop>,
    /// A failed run's last accepted state (the end of its last accepted step); `None` for a
    /// run that ended by itself (its final state ends `samples`) or failed before a step.
    pub last_state: Option<Sample>,
    /// Integrator work.
    pub work: Work,
    /// Largest constraint drift seen (SI units, before projection); `None` when the models
    /// do not integrate every constrained state.
    pub constraint_drift_max: Option<f64>,
    /// The models that ran, and the states they left frozen.
    pub model: ModelChoice,
}
