//! Models given as text, compiled at run time and solved by the runtime: the one library
//! entry point every front end calls.
//!
//! # The boundary
//!
//! `model!` compiles a model into Rust at build time; this crate takes the same text at run
//! time. The front end (`model-dsl`) reads it, the equation compiler (`model-algebra`) derives
//! its programs, and the compiler's interpreter runs them inside the runtime's integrators and
//! switched driver (`model-runtime`), so a model file behaves as the model `model!` would emit
//! from it, step for step. Everything a front end needs that is not presentation lives here:
//! loading ([`ModelFile`]), values by name ([`SolveRequest::params`], [`evaluate`]), events,
//! the solve itself ([`solve`]) and its typed result ([`Solution`]) or typed failure
//! ([`SolveFailure`]). A front end keeps only its own concerns: `eulerdisk model solve` parses
//! flags, writes CSV files and prints sentences; a Python package converts keyword arguments
//! and builds arrays. Neither matches on message text: the errors are enums whose variants say
//! which input was wrong and where in the list it was given.
//!
//! # The API
//!
//! * **Loading**: [`ModelFile::read`], [`ModelFile::from_text`] give a [`ModelFile`] (smooth,
//!   with its charts, or switched); [`ModelFile::model`] chooses a [`ModelRef`]
//!   ([`LoadError`]); a front end that keeps only the compiled models picks one with
//!   [`select_chart`].
//! * **Solving**: [`solve`] with a [`SolveRequest`] ([`EventRequest`], [`Named`] values, a
//!   [`WorkBound`]) gives a [`Solution`] ([`SolvedEvent`], [`EventKind`], [`Stop`],
//!   [`AccumulationPoint`]) or a [`SolveFailure`] ([`RequestError`], [`UnknownEvent`],
//!   [`RunFailure`] with the solution until the failure and a [`WorkHint`], [`WorkExceeded`],
//!   [`ValueError`]); [`solve_with`] also stops on an interrupt ([`Control`]);
//!   [`solve_stepped`] bounds the step sizes and keeps each step's dense output
//!   ([`Stepping`], [`DenseStep`]).
//! * **One point**: [`evaluate`] gives the derivatives and outputs by name, [`PointValues`]
//!   ([`NamedValues`], [`PointError`]); the values in the model's order, [`params`],
//!   [`initial_state`], [`resolve`].
//! * **For a switched model**: its runtime [`mode_graph`].
//!
//! An interpreted model runs in exactly its own states, of any number: the runtime's
//! integrators and drivers are written once over a state size known at compile time
//! (`model!`'s models, `model_runtime::Const`) or at run time (a file's, `model_runtime::Dyn`),
//! so the interpreter needs no padding and the request's tolerance is the model's own.
//!
//! ```
//! use model_interpreted::{solve, EventKind, EventRequest, ModelFile, SolveRequest, Stop};
//! use model_runtime::Direction;
//!
//! let file = ModelFile::from_text(
//!     "oscillator.dsl",
//!     "mod oscillator {
//!         params { w = 3 }
//!         states { x, v }
//!         equations { der(x) = v; der(v) = -w^2 * x; }
//!         outputs { energy = v^2 / 2 + w^2 * x^2 / 2; }
//!     }",
//! )
//! .unwrap();
//! let mut request = SolveRequest::new(2.0);
//! request.state = vec![("x".to_string(), 1.0)];
//! request.events = vec![EventRequest {
//!     name: "x".to_string(),
//!     direction: Direction::Down,
//!     stop: true,
//! }];
//! let solution = solve(file.model(None).unwrap(), &request).unwrap();
//! // x = cos(3 t) first crosses zero downwards at t = pi / 6.
//! let first = &solution.events[0];
//! assert_eq!(first.kind, EventKind::Crossing);
//! assert!((first.t() - std::f64::consts::PI / 6.0).abs() < 1e-8);
//! assert!(matches!(&solution.stop, Stop::Event { name, .. } if name == "x"));
//! let energy = solution.column("energy").unwrap();
//! assert!(energy.iter().all(|e| (e - 4.5).abs() < 1e-6));
//! ```
#![warn(missing_docs)]

mod cache;
mod engine;
mod error;
mod file;
mod interpreted;
mod load;
mod recording;
mod request;
mod smooth;
mod solution;
mod switched;
mod tables;
mod trajectory;
mod values;

pub use cache::ModelCache;
pub use engine::{set_evaluator, Evaluator};
pub use error::{
    LoadError, PointError, RequestError, RunFailure, SolveFailure, UnknownEvent, ValueError,
    WorkHint,
};
pub use file::ModelFile;
pub use load::{select_chart, CacheUse, Loaded, ModelRef};
pub use model_runtime::{WorkBound, WorkExceeded};
pub use request::{Control, EventRequest, SolveRequest, Stepping, Watched, MAX_SAMPLES};
pub use solution::{
    AccumulationPoint, DenseStep, EventKind, Solution, SolvedEvent, Stop, Trajectory, DENSE_NODES,
};
pub use switched::mode_graph;
pub use values::{evaluate, initial_state, params, resolve, Named, NamedValues, PointValues};

/// Solves `model` as `request` says: the values and events resolved by name, the integration
/// by the runtime with the model's programs run by the interpreter, the outputs evaluated at
/// every recorded point. An unusable request is a [`SolveFailure::Request`] found before any
/// integration; a failed run says why in the model's terms.
pub fn solve(model: ModelRef<'_>, request: &SolveRequest) -> Result<Solution, SolveFailure> {
    let never = std::sync::atomic::AtomicBool::new(false);
    solve_with(model, request, &Control { interrupt: &never })
}

/// [`solve`], stopped at its next step once `control`'s interrupt is set: the solution then
/// holds the rows and events computed, its stop [`Stop::Interrupted`].
pub fn solve_with(
    model: ModelRef<'_>,
    request: &SolveRequest,
    control: &Control<'_>,
) -> Result<Solution, SolveFailure> {
    solve_stepped(model, request, control, &Stepping::default())
}

/// [`solve_with`], its steps shaped by `stepping`: a first and a largest step size, and the
/// dense output of every step kept in the solution.
pub fn solve_stepped(
    model: ModelRef<'_>,
    request: &SolveRequest,
    control: &Control<'_>,
    stepping: &Stepping,
) -> Result<Solution, SolveFailure> {
    let resolved = request::Resolved::new(model, request)?;
    let how = (control, stepping);
    match model {
        ModelRef::Smooth(model) => smooth::solve_smooth(model, resolved, request, how),
        ModelRef::Switched(model) => switched::solve_switched(model, resolved, request, how),
    }
}
