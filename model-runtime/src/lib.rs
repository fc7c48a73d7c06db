//! Runtime for models emitted by `model-macros`: integrators, exact event location and a
//! generic hybrid (mode-switching) driver.
//!
//! * Models of any size, one code path: every item below is generic over a [`Dim`], the
//!   number of states known at compile time ([`Const<N>`](Const), states in `[f64; N]`: what
//!   `model!` emits, monomorphised to fixed-size arrays) or only at run time ([`Dyn`], states in
//!   `Vec<f64>`: a model read from a file), as nalgebra's `Const`/`Dyn` do for matrices.
//! * Methods, all behind one [`Stepper`] trait and allocation-free (for [`Const`] sizes): [`Dopri5`] (5(4), dense
//!   order 4), [`Dop853`] (8(5,3), dense order 7), [`Rodas4`] (stiff, uses the model's
//!   Jacobian, dense order 3) and fixed-step [`Rk4`] (cubic Hermite dense output).
//! * [`Problem`]: one call from a model to a [`Trajectory`] (times, states, outputs, located
//!   events, statistics, stop reason), as `solve_ivp` does, backward in time too (a span
//!   `(t0, t_end)` with `t_end < t0`: the exact forward run in `−t`, [`HybridSolver::run`]).
//! * [`Integrator`]: the shared adaptive loop (PI control, Hairer's initial step, typed
//!   collapse detection); [`integrate`] for a plain run.
//! * [`Tolerance`]: one mixed relative/absolute error norm for every method; components that
//!   form a vector can be scaled by the vector's length (frame-independent), and the component
//!   that limits each step can be counted ([`Stats::limiting`]).
//! * Hybrid systems ([`HybridSystem`], run by [`HybridSolver`]): modes, guards with exact
//!   crossing location (semantics at [`GuardSpec`]), transition maps with a typed note for the
//!   observer, events that only pass (reported, no restart), chattering detection,
//!   projection, streaming [`Observer`]s.
//!
//! # The API by theme
//!
//! Every public item is re-exported here, once, under one name; the modules are private, so a
//! path such as `model_runtime::Tolerance` is the only one there is. There is no
//! sub-namespace: even regularised time, a layer over the hybrid driver, has names of its own
//! that read well at the root, and a caller's imports then never depend on how the crate is
//! split into files.
//!
//! * **Sizes**: [`Dim`] with [`Const`] and [`Dyn`]; a state [`Vector`], a Jacobian [`Matrix`],
//!   their storage [`Array`] of [`Element`]s.
//! * **The model contract** (what `model-macros` emits, what hand-written models implement):
//!   [`Model`], [`WithOutputs`], [`Evaluation`], [`ModelInfo`], [`OpCounts`], [`EvalError`]; the
//!   same of any size, what the drivers run ([`Model`]s are ones), [`System`] and
//!   [`SystemOutputs`];
//!   for emitted code only, [`solve_block`] and [`check_finite`]; the default Jacobian, [`finite_difference_jacobian`].
//! * **Methods**: the [`Stepper`] trait ([`StepStart`], [`StepEnd`], [`Components`], the
//!   right-hand side it steps, [`Rhs`]) and its implementations [`Dopri5`], [`Dop853`],
//!   [`Rodas4`], [`Rk4`].
//! * **Error control and step control**: [`Tolerance`], [`VectorGroups`], [`ComponentGroup`],
//!   [`LimitingComponent`], [`ErrorEstimate`]; [`StepOptions`], [`StepControl`].
//! * **One model, one call**: [`Problem`] with [`Method`], [`Output`], [`Event`]
//!   ([`EventFunction`]) gives a [`Trajectory`] ([`LocatedEvent`], [`Termination`],
//!   [`SolveFailure`]); [`integrate`] gives a [`Solution`]; [`Integrator`] and [`DenseStep`] are
//!   the loop underneath; [`WithStepper`] runs one generic body with the stepper a [`Method`]
//!   names.
//! * **Guards and events**: [`GuardSpec`], [`Direction`], [`Crossed`], [`EventHit`],
//!   [`GuardInputs`], [`InteriorChecks`]; the bracketing root finder [`find_crossing`]
//!   ([`Crossing`], [`converged_width`]).
//! * **Hybrid systems**: [`HybridSystem`], [`Transition`] ([`TransitionOf`]), [`HybridSolver`],
//!   [`HybridOptions`], [`ChatterLimit`], [`HybridOutcome`], [`HybridResult`], [`StopReason`],
//!   [`HybridError`].
//! * **Switched models given by tables** (what `model!` and the model interpreter produce for
//!   modes and events): [`SwitchedModel`] with its [`ModeGraph`] ([`ModeDecl`], [`EventDecl`],
//!   [`EventAction`], [`AccumulationAction`], [`ModeId`], [`EventId`], [`GraphError`]), run as
//!   the hybrid system [`Switched`] ([`SwitchedStop`], [`SwitchedNote`]); accumulation (Zeno)
//!   detection, [`AccumulationDetector`] with its [`AccumulationRule`] and [`Accumulation`];
//!   one call from such a model to its named events and samples, [`run_switched`]
//!   ([`SwitchedRun`], [`EventRecord`], [`Fired`], [`Firing`], [`SwitchedFailure`], [`name_modes`]).
//! * **Regularised time** (a hybrid system integrated in `τ` with `dt = s dτ`):
//!   [`TimeScale`], [`Regularised`] (which also reads a run's outcome and failure back in
//!   physical terms), [`ClockGuard`], [`Clocked`], and the observer adaptor [`PhysicalTime`].
//! * **Streaming output**: [`Observer`], [`StepView`], [`Sample`], [`Interpolant`],
//!   [`TransitionRecord`], [`TransitionKind`], [`Recorder`]; an observer's failure, which
//!   ends the run like any other ([`Observed`], [`ObserverError`]); a step's interpolant kept after
//!   the step, [`StoredInterpolant`], from each method's [`DenseOutput`] ([`Dopri5Dense`],
//!   [`Dop853Dense`], [`Rodas4Dense`], [`Rk4Dense`]).
//! * **Work and failures**: [`Stats`], [`ComponentCounts`]; the bound on steps per simulated
//!   second, [`WorkBound`] ([`WorkMeter`], [`WorkExceeded`]); [`SolveError`], [`InputError`],
//!   [`GroupProblem`]; reading settings spelled as words, [`parse_word`] and
//!   [`ParseSettingError`].
//!
//! ```
//! use model_runtime::{integrate, Dop853, EvalError, Model, ModelInfo, StepOptions, Tolerance};
//!
//! /// y' = -y.
//! struct Decay;
//! static INFO: ModelInfo = ModelInfo::of("decay", &["y"], &[], &[]);
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

mod accumulation;
mod control;
mod dense;
mod dim;
mod dop853;
mod dopri5;
mod error;
mod events;
mod finite;
mod hybrid;
mod integrator;
mod jacobian;
mod linalg;
mod lu;
mod model;
mod name;
mod observer;
mod readable;
mod rk4;
mod rodas4;
mod root;
mod solution;
mod solve;
mod stats;
mod stepper;
mod switched;
mod switched_run;
mod tableau;
mod tolerance;
mod work;

pub use accumulation::{Accumulation, AccumulationDetector, AccumulationRule};
pub use control::{StepControl, StepOptions};
pub use dense::{DenseOutput, Interpolant, StoredInterpolant};
pub use dim::{Array, Const, Dim, Dyn, Element, Matrix, Vector};
pub use dop853::{Dop853, Dop853Dense};
pub use dopri5::{Dopri5, Dopri5Dense};
pub use error::{parse_word, EvalError, GroupProblem, InputError, ParseSettingError, SolveError};
pub use events::{Crossed, Direction, EventHit, GuardInputs, GuardSpec, InteriorChecks};
pub use finite::check_finite;
pub use hybrid::physical_time::PhysicalTime;
pub use hybrid::regularised::{ClockGuard, Clocked, Regularised, TimeScale};
pub use hybrid::run::HybridSolver;
pub use hybrid::{
    ChatterLimit, HybridError, HybridOptions, HybridOutcome, HybridResult, HybridSystem,
    StopReason, Transition, TransitionOf,
};
pub use integrator::{integrate, DenseStep, Integrator, Solution};
pub use jacobian::finite_difference_jacobian;
pub use linalg::solve_block;
pub use model::{Evaluation, Model, ModelInfo, OpCounts, System, SystemOutputs, WithOutputs};
pub use name::{Name, Names};
pub use observer::{
    Observed, Observer, ObserverError, Recorder, Sample, StepView, TransitionKind, TransitionRecord,
};
pub use readable::Readable;
pub use rk4::{Rk4, Rk4Dense};
pub use rodas4::{Rodas4, Rodas4Dense};
pub use root::{converged_width, find_crossing, Crossing};
pub use solution::{LocatedEvent, SolveFailure, Termination, Trajectory};
pub use solve::{Event, EventFunction, Method, Output, Problem, WithStepper};
pub use stats::{ComponentCounts, Stats};
pub use stepper::{Components, Rhs, StepEnd, StepStart, Stepper};
pub use switched::graph::{
    AccumulationAction, EventAction, EventDecl, EventId, GraphError, ModeDecl, ModeGraph, ModeId,
};
pub use switched::outcome::{SwitchedNote, SwitchedStop};
pub use switched::{Switched, SwitchedModel};
pub use switched_run::{
    name_modes, run_switched, EventRecord, Fired, Firing, SwitchedFailure, SwitchedRun,
};
pub use tolerance::{ComponentGroup, ErrorEstimate, LimitingComponent, Tolerance, VectorGroups};
pub use work::{WorkBound, WorkExceeded, WorkMeter};
