//! Euler's disk: the paper's rolling and sliding models, an independent reference, and the
//! paper's mode rules.
//!
//! The same physics is written three times, on purpose: as the paper's boxes in the equation
//! DSL ([`models`], compiled to explicit Rust), as vector Newton–Euler solved numerically
//! ([`reference`](mod@reference), the oracle), and as the closed forms a reader can check by hand
//! ([`formulas`]). The tests hold each to the others at random and extreme states. All of
//! them take their parameters from one validated [`DiskParams`].
//!
//! The crate also owns the scene's domain: the settings a scene file writes
//! ([`SceneSettings`], with the one set of defaults in [`SolverTable::default`]), their one
//! validation ([`Issue`], keyed by the scene's names), the completion of the initial state
//! ([`InitialState`]), and the run ([`simulate`]) that takes what they resolve to
//! ([`DiskScene`]).
//!
//! What a run leaves behind, named for front ends, is here too ([`record`]): samples in the
//! one named state layout ([`layout`], [`STATE_NAMES`]), the quantities a file may record with
//! their units, and the kinds of mode decisions and stops with the words the files write. A
//! front end (the command line, the Python package) formats these and holds no physics of
//! its own.
//!
//! # Example
//!
//! ```
//! use equations::{simulate, DiskRecorder, GeneratedModels, SceneSettings};
//!
//! let text = r#"
//!     disk = { m = 0.4387, a = 0.03755, g = 9.81 }
//!     friction = { mu_d = 0.15, mu_st = 0.2 }
//!     initial = { theta = 0.5707963267948966, Omega_x = 1.0 }
//!     run = { t_end = 0.1 }
//! "#;
//! let settings: SceneSettings = toml::from_str(text).unwrap();
//! let scene = settings.resolve().unwrap();
//! assert_eq!(scene.config.integrator.name(), "dop853");
//! let models = GeneratedModels::generated(scene.params, scene.config.chart()).unwrap();
//! let mut record = DiskRecorder::default();
//! let out = simulate(&models, &scene.config, &scene.initial, &mut record).unwrap();
//! assert_eq!(out.stop.name(), "end time");
//! ```
#![warn(missing_docs)]

mod config;
pub mod formulas;
mod hybrid;
mod issue;
pub mod models;
mod modes;
pub mod paper;
mod params;
pub mod record;
pub mod reference;
mod scene;
mod settings;
mod start;
mod work;

pub use config::{AllowedModes, DiskConfig, ATOL_MAX, MAX_DELIVERED_SAMPLES, RTOL_MAX, RTOL_MIN};
pub use hybrid::{
    consistent_slip_direction, disk, simulate, simulate_graph, simulate_switched, AirModel,
    DiskGuard, DiskModels, DiskObserver, DiskRecorder, DiskRunner, DiskSample, EmbedError,
    Embedded, Embedding, Engine, Extremum, ExtremumKind, GeneratedModels, OnsetError, PruneError,
    Pruned, PrunedModels, ReferenceModels, RunOutcome, SimError, SimFailure, SlidingModel,
    SlipAcceleration, SlipOnset, StopReason, SwitchedDiskRun, SwitchedEvent, Trailing,
    TransitionRecord, Trigger, Variant, Watched, ENGINE, GRAPH_ENGINE, PROBE_SLIP_SPEED,
    PRUNED_STATES,
};
pub use issue::{Issue, Number, Rule};
/// Where a step's interior is searched for guard crossings (re-exported from the runtime).
pub use model_runtime::InteriorChecks;
/// Whether a run counts the component that limits each step (re-exported from the runtime).
pub use model_runtime::LimitingComponent;
/// The gains of the step-size controller (re-exported from the runtime).
pub use model_runtime::StepControl;
pub use modes::{
    layout, no_slip_velocity, ConstraintResiduals, ContactForce, Mode, PhysicalState, Slip,
    SlipChart, DIM,
};
pub use params::{DiskParams, ParamError};
pub use scene::{
    AirTable, DiskScene, DiskTable, FrictionTable, InitialTable, ModesTable, SceneSettings,
    MAX_RECORDED_SAMPLES,
};
pub use settings::{
    spelled, ChatterLimit, ErrorNorm, Integrator, RunTable, SlipSign, SolverTable, TimeVariable,
};
pub use start::{InitialState, CONSTRAINT_TOL, STATE_NAMES};
pub use work::{WorkBound, WorkExceeded, WORK_BOUND_KEY};
