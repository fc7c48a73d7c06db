//! Runtime for models emitted by `model-macros`: integrators, exact event location and a
//! generic hybrid (mode-switching) driver.
//!
//! * Methods, all behind one [`Stepper`] trait and allocation-free: [`Dopri5`] (5(4), dense
//!   order 4), [`Dop853`] (8(5,3), dense order 7), [`Rodas4`] (stiff, uses the model's
//!   Jacobian, dense order 3) and fixed-step [`Rk4`] (cubic Hermite dense output).
//! * [`Problem`]: one call from a model to a [`Trajectory`] (times, states, outputs, located
//!   events, statistics, stop reason), as `solve_ivp` does; see [`solve`].
//! * [`Integrator`]: the shared adaptive loop (PI control, Hairer's initial step, typed
//!   collapse detection); [`integrate`] for a plain run.
//! * [`Tolerance`]: one mixed relative/absolute error norm for every method; components that
//!   form a vector can be scaled by the vector's length (frame-independent), and the component
//!   that limits each step can be counted ([`Stats::limiting`]).
//! * [`hybrid`]: modes, guards with exact crossing location ([`events`] documents the guard
//!   semantics), transition maps, chattering detection, projection, streaming [`observer`]s.
//!
//! ```
//! use model_runtime::{integrate, Dop853, EvalError, Model, ModelInfo, OpCounts, StepOptions, Tolerance};
//!
//! /// y' = -y.
//! struct Decay;
//! const ZERO: OpCounts = OpCounts { add: 0, mul: 0, div: 0, sqrt: 0, trig: 0, transcendental: 0 };
//! static INFO: ModelInfo = ModelInfo {
//!     name: "decay", state_names: &["y"], param_names: &[], output_names: &[],
//!     rhs_ops: ZERO, jacobian_ops: ZERO, outputs_ops: ZERO, pivots: &[], numeric_blocks: &[],
//! };
//! impl Model<1> for Decay {
//!     fn info(&self) -> &'static ModelInfo { &INFO }
//!     fn rhs(&self, _t: f64, y: &[f64; 1], dy: &mut [f64; 1]) -> Result<(), EvalError> {
//!         dy[0] = -y[0];
//!         Ok(())
//!     }
//! }
//!
//! let sol = integrate(&Decay, Dop853::new(), Tolerance::scalar(1e-12, 1e-12),
//!                     StepOptions::default(), 0.0, &[1.0], 2.0).unwrap();
//! assert!((sol.y[0] - (-2.0f64).exp()).abs() < 1e-11);
//! assert!(sol.stats.steps < 40);
//! ```
#![warn(missing_docs)]
// Numerical kernels index several arrays with one loop variable, as the formulas do.
#![allow(clippy::needless_range_loop)]

pub mod control;
pub mod dop853;
pub mod dopri5;
pub mod error;
pub mod events;
pub mod hybrid;
pub mod integrator;
pub mod linalg;
mod lu;
pub mod model;
pub mod observer;
pub mod rk4;
pub mod rodas4;
pub mod root;
pub mod solution;
pub mod solve;
pub mod stats;
pub mod stepper;
mod tableau;
pub mod tolerance;

pub use control::{StepControl, StepOptions};
pub use dop853::Dop853;
pub use dopri5::Dopri5;
pub use error::{parse_word, GroupProblem, InputError, ParseSettingError, SolveError};
pub use events::{Crossed, Direction, EventHit, GuardInputs, GuardSpec, InteriorChecks};
pub use hybrid::{
    ChatterLimit, HybridError, HybridOptions, HybridOutcome, HybridSolver, HybridSystem,
    StopReason, Transition,
};
pub use integrator::{integrate, DenseStep, Integrator, Solution};
pub use model::{EvalError, Evaluation, Model, ModelInfo, OpCounts, WithOutputs};
pub use observer::{
    Interpolant, Observer, Recorder, Sample, StepView, TransitionKind, TransitionRecord,
};
pub use rk4::Rk4;
pub use rodas4::Rodas4;
pub use solution::{LocatedEvent, SolveFailure, Termination, Trajectory};
pub use solve::{Event, Method, Output, Problem};
pub use stats::{ComponentCounts, Stats};
pub use stepper::{Components, StepEnd, StepStart, Stepper};
pub use tolerance::{ComponentGroup, ErrorEstimate, LimitingComponent, Tolerance, VectorGroups};
