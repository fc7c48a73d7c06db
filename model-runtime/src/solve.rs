//! One call from a model to a trajectory, in the spirit of scipy's `solve_ivp`: the model (with
//! its parameters), the initial state, the time span and a few options in; times, states,
//! outputs, located events, statistics and the reason it stopped out ([`Trajectory`]).
//!
//! It is built on the hybrid driver with a single mode ([`crate::HybridSolver`]): the events are its
//! guards, located exactly on the dense output with the semantics documented at
//! [`crate::GuardSpec`]; a terminal event stops the run, any other restarts the integrator at the
//! event state. Nothing about stepping or event location is re-implemented here.

use crate::control::StepOptions;
use crate::dim::{Dim, Matrix, Vector};
use crate::dop853::Dop853;
use crate::dopri5::Dopri5;
use crate::error::EvalError;
use crate::events::{Direction, EventHit, GuardSpec, InteriorChecks};
use crate::hybrid::run::HybridSolver;
use crate::hybrid::{HybridError, HybridOptions, HybridSystem, StopReason, Transition};
use crate::model::{System, SystemOutputs};
use crate::observer::{Observed, Observer, StepView};
use crate::rk4::Rk4;
use crate::rodas4::Rodas4;
use crate::solution::{LocatedEvent, SolveFailure, Termination, Trajectory};
use crate::stepper::Stepper;
use crate::tolerance::Tolerance;

/// The integration method.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Method {
    /// Dormand–Prince 5(4), dense order 4: the general-purpose default.
    #[default]
    Dopri5,
    /// Dormand–Prince 8(5,3), dense order 7: for tight tolerances.
    Dop853,
    /// Rosenbrock 4(3), uses the model's Jacobian: for stiff models.
    Rodas4,
    /// Classical Runge–Kutta with this fixed step (no error control).
    Rk4 {
        /// The step size.
        h: f64,
    },
}

/// A computation that runs with a stepper of whichever [`Method`] is chosen: the stepper's
/// type is fixed inside [`Method::with_stepper`], so one generic body serves every method
/// (and every state size) with no dispatch per step.
pub trait WithStepper<D: Dim> {
    /// What the computation gives.
    type Output;
    /// Runs it with `stepper`.
    fn run<S: Stepper<D>>(self, stepper: S) -> Self::Output;
}

impl Method {
    /// Runs `task` with a fresh stepper of this method for states of size `dim`.
    pub fn with_stepper<D: Dim, T: WithStepper<D>>(self, dim: D, task: T) -> T::Output {
        match self {
            Method::Dopri5 => task.run(Dopri5::new_in(dim)),
            Method::Dop853 => task.run(Dop853::new_in(dim)),
            Method::Rodas4 => task.run(Rodas4::new_in(dim)),
            Method::Rk4 { h } => task.run(Rk4::new_in(dim, h)),
        }
    }
}

/// Where the trajectory is recorded.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Output {
    /// At the start and at the end of every accepted step (as `solve_ivp` without `t_eval`).
    #[default]
    Steps,
    /// At these times, interpolated on each step's dense output (of the method's order); they
    /// must be finite, inside the time span and in the run's order (non-decreasing, or
    /// non-increasing for a span that runs backward, `t_end < t0`).
    Times(Vec<f64>),
}

/// The function of an event: `g(t, y, dy)`, whose zero crossings are the event. It reads the
/// state and its derivative as slices, so one event type serves models of every [`Dim`].
pub type EventFunction = Box<dyn Fn(f64, &[f64], &[f64]) -> f64>;

/// An event: a named scalar function of `(t, y, dy)` whose zero crossings are located exactly.
///
/// A non-terminal event restarts the integrator at the event state (a clean restart, as after
/// any transition). Two events crossing at the very same time are reported once, for the one
/// listed first ([`crate::GuardSpec`]: the segment ends at the earliest event).
pub struct Event {
    name: String,
    function: EventFunction,
    direction: Direction,
    terminal: bool,
}

impl Event {
    /// An event firing on crossings of `function` through zero in either direction, not
    /// terminal.
    pub fn new(
        name: impl Into<String>,
        function: impl Fn(f64, &[f64], &[f64]) -> f64 + 'static,
    ) -> Self {
        Event {
            name: name.into(),
            function: Box::new(function),
            direction: Direction::Both,
            terminal: false,
        }
    }

    /// Fires only on crossings in `direction`.
    pub fn direction(mut self, direction: Direction) -> Self {
        self.direction = direction;
        self
    }

    /// Stops the run at the first crossing.
    pub fn terminal(mut self) -> Self {
        self.terminal = true;
        self
    }

    /// The event's name.
    pub fn name(&self) -> &str {
        &self.name
    }
}

impl std::fmt::Debug for Event {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Event")
            .field("name", &self.name)
            .field("direction", &self.direction)
            .field("terminal", &self.terminal)
            .finish_non_exhaustive()
    }
}

/// An initial-value problem and how to solve it; [`Problem::solve`] runs it.
///
/// ```
/// use model_runtime::{Event, Method, Output, Problem, Termination};
/// use model_runtime::{Direction, EvalError, Model, ModelInfo, WithOutputs};
///
/// /// A ball thrown upwards: y = (height, velocity); output: its energy per unit mass.
/// struct Ball;
/// static INFO: ModelInfo = ModelInfo::of("ball", &["h", "v"], &[], &["energy"]);
/// impl Model<2> for Ball {
///     fn info(&self) -> &'static ModelInfo { &INFO }
///     fn rhs(&self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) -> Result<(), EvalError> {
///         *dy = [y[1], -9.81];
///         Ok(())
///     }
/// }
/// impl WithOutputs<2, 1> for Ball {
///     fn outputs(&self, _t: f64, y: &[f64; 2], _dy: &[f64; 2], out: &mut [f64; 1])
///         -> Result<(), EvalError> {
///         out[0] = y[1] * y[1] / 2.0 + 9.81 * y[0];
///         Ok(())
///     }
/// }
///
/// let sol = Problem::new(&Ball, [0.0, 10.0], (0.0, 5.0))
///     .method(Method::Dop853)
///     .tolerances(1e-10, 1e-12)
///     .output(Output::Times((0..=30).map(|k| 0.1 * k as f64).collect()))
///     .event(Event::new("apex", |_t, y, _dy| y[1]))
///     .event(Event::new("ground", |_t, y, _dy| y[0]).direction(Direction::Down).terminal())
///     .solve()
///     .unwrap();
/// // The apex (v = 0) and the landing (h = 0, at 2 v0 / g) are located exactly.
/// assert!((sol.events[0].t - 10.0 / 9.81).abs() < 1e-12);
/// assert_eq!(sol.stop, Termination::Event { name: "ground".into() });
/// assert!((sol.events[1].t - 20.0 / 9.81).abs() < 1e-12);
/// assert!(sol.events[1].y[0].abs() < 1e-12); // the exact state at the landing
/// assert_eq!(sol.t.len(), 21); // the requested times before the landing: 0, 0.1, ..., 2
/// assert!(sol.column("energy").unwrap().iter().all(|e| (e - 50.0).abs() < 1e-9));
/// ```
#[derive(Debug)]
pub struct Problem<'m, M, D: Dim> {
    model: &'m M,
    y0: Vector<D>,
    span: (f64, f64),
    method: Method,
    tolerance: Tolerance<D>,
    output: Output,
    events: Vec<Event>,
    step: StepOptions,
    guard_checks: InteriorChecks,
}

impl<'m, M: System<D>, D: Dim> Problem<'m, M, D> {
    /// `model` (with its parameters) from `y0` over `span = (t0, t_end)`, with [`Method::Dopri5`]
    /// at `rtol = 1e-6`, `atol = 1e-9`, recording every step.
    pub fn new(model: &'m M, y0: Vector<D>, span: (f64, f64)) -> Self {
        Problem {
            model,
            y0,
            span,
            method: Method::default(),
            tolerance: Tolerance::scalar_in(model.dim(), 1e-6, 1e-9),
            output: Output::default(),
            events: Vec::new(),
            step: StepOptions::default(),
            guard_checks: InteriorChecks::default(),
        }
    }

    /// The integration method.
    pub fn method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }

    /// The same relative and absolute tolerance for every state.
    pub fn tolerances(mut self, rtol: f64, atol: f64) -> Self {
        self.tolerance = Tolerance::scalar_in(self.model.dim(), rtol, atol);
        self
    }

    /// Full control of the error norm (per-state tolerances, vector groups).
    pub fn tolerance(mut self, tolerance: Tolerance<D>) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// Where the trajectory is recorded.
    pub fn output(mut self, output: Output) -> Self {
        self.output = output;
        self
    }

    /// Adds an event (events listed first win ties).
    pub fn event(mut self, event: Event) -> Self {
        self.events.push(event);
        self
    }

    /// The budget of step attempts (accepted and rejected).
    pub fn max_steps(mut self, max_steps: u64) -> Self {
        self.step.max_steps = max_steps;
        self
    }

    /// Step-size limits, initial step, step budget and control, all at once.
    pub fn step_options(mut self, step: StepOptions) -> Self {
        self.step = step;
        self
    }

    /// Interior points of each step where the events are also checked (a sign change and back
    /// within one step is otherwise invisible).
    pub fn event_checks(mut self, checks: InteriorChecks) -> Self {
        self.guard_checks = checks;
        self
    }

    /// Integrates and records the trajectory.
    pub fn solve<const K: usize>(self) -> Result<Trajectory<D, K>, SolveFailure>
    where
        M: SystemOutputs<D, K>,
    {
        let (method, dim) = (self.method, self.model.dim());
        method.with_stepper(dim, Solving::<_, _, K>(self))
    }

    fn solve_with<S: Stepper<D>, const K: usize>(
        self,
        stepper: S,
    ) -> Result<Trajectory<D, K>, SolveFailure>
    where
        M: SystemOutputs<D, K>,
    {
        let info = self.model.info().clone();
        let names: Vec<String> = self.events.iter().map(|e| e.name.clone()).collect();
        let fail = |error: HybridError<()>| {
            SolveFailure::from_hybrid(error, Box::new(info.clone()), &names)
        };
        let (t0, t_end) = self.span;
        if let Output::Times(times) = &self.output {
            check_times(times, t0, t_end)?;
        }
        let options = HybridOptions {
            step: self.step,
            guard_checks: self.guard_checks,
            ..HybridOptions::default()
        };
        let mut solver = HybridSolver::new(stepper, self.tolerance, options).map_err(|e| {
            fail(HybridError::Solve {
                mode: (),
                error: e.into(),
            })
        })?;
        let mut system = Single {
            model: self.model,
            guards: self
                .events
                .iter()
                .enumerate()
                .map(|(index, e)| GuardSpec {
                    id: index,
                    direction: e.direction,
                })
                .collect(),
            events: &self.events,
            located: Vec::new(),
        };
        let mut record = Record::new(&self.output, (t0, t_end), &self.y0);
        let outcome = solver
            .run(&mut system, (), t0, &self.y0, t_end, &mut record)
            .map_err(fail)?;
        let stop = match outcome.stop {
            StopReason::EndTime => Termination::EndTime,
            StopReason::User(index) => Termination::Event {
                name: self.events[index].name.clone(),
            },
            StopReason::Observer => unreachable!("the trajectory's recorder never stops a run"),
        };
        Trajectory::build(
            self.model,
            record.t,
            record.y,
            system.located,
            outcome.stats,
            stop,
        )
    }
}

/// Output times must be finite, inside the span and in the run's order.
fn check_times(times: &[f64], t0: f64, t_end: f64) -> Result<(), SolveFailure> {
    let backward = t_end < t0;
    let mut previous = t0;
    for (index, &t) in times.iter().enumerate() {
        // At or after the previous one, at or before the end, in the run's direction.
        if !(t.is_finite() && reached(t, previous, backward) && reached(t_end, t, backward)) {
            return Err(SolveFailure::OutputTime {
                index,
                t,
                t0,
                t_end,
            });
        }
        previous = t;
    }
    Ok(())
}

/// Whether a run that has reached `now` has reached `t` (is at or past it in its direction).
fn reached(now: f64, t: f64, backward: bool) -> bool {
    if backward {
        t >= now
    } else {
        t <= now
    }
}

/// The model as a hybrid system with one mode whose guards are the events.
struct Single<'a, M, D: Dim> {
    model: &'a M,
    guards: Vec<GuardSpec<usize>>,
    events: &'a [Event],
    located: Vec<LocatedEvent<D>>,
}

impl<M: System<D>, D: Dim> HybridSystem<D> for Single<'_, M, D> {
    type Mode = ();
    type Guard = usize;
    type Stop = usize;
    type Note = ();

    fn rhs(&self, _: (), t: f64, y: &Vector<D>, dy: &mut Vector<D>) -> Result<(), EvalError> {
        self.model.rhs(t, y, dy)
    }

    fn jacobian(&self, _: (), t: f64, y: &Vector<D>, jac: &mut Matrix<D>) -> Result<(), EvalError> {
        self.model.jacobian(t, y, jac)
    }

    fn guards(&self, _: ()) -> &[GuardSpec<usize>] {
        &self.guards
    }

    fn guard_values(
        &self,
        _: (),
        t: f64,
        y: &Vector<D>,
        dy: &Vector<D>,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        for (value, event) in values.iter_mut().zip(self.events) {
            *value = (event.function)(t, y.as_ref(), dy.as_ref());
        }
        Ok(())
    }

    fn on_event(
        &mut self,
        _: (),
        hit: &EventHit<D, usize>,
    ) -> Result<Transition<D, (), usize>, EvalError> {
        let event = &self.events[hit.guard];
        self.located.push(LocatedEvent {
            name: event.name.clone(),
            index: hit.guard,
            t: hit.t,
            y: hit.y.clone(),
            der: hit.dy.clone(),
            crossed: hit.direction,
        });
        Ok(if event.terminal {
            Transition::Stop(hit.guard)
        } else {
            Transition::Continue {
                y: hit.y.clone(),
                note: (),
            }
        })
    }
}

/// Collects the recorded points as the run streams its steps.
struct Record<'o, D: Dim> {
    output: &'o Output,
    /// Whether the run goes backward in time.
    backward: bool,
    /// The next requested time not yet recorded ([`Output::Times`]).
    next: usize,
    t: Vec<f64>,
    y: Vec<Vector<D>>,
}

impl<'o, D: Dim> Record<'o, D> {
    fn new(output: &'o Output, (t0, t_end): (f64, f64), y0: &Vector<D>) -> Self {
        let backward = t_end < t0;
        let mut record = Record {
            output,
            backward,
            next: 0,
            t: Vec::new(),
            y: Vec::new(),
        };
        match output {
            Output::Steps => record.push(t0, y0.clone()),
            Output::Times(times) => {
                while record.next < times.len() && reached(t0, times[record.next], backward) {
                    record.next += 1;
                    record.push(t0, y0.clone());
                }
            }
        }
        record
    }

    fn push(&mut self, t: f64, y: Vector<D>) {
        self.t.push(t);
        self.y.push(y);
    }
}

/// A [`Problem`] waiting for its stepper, with the size of its outputs.
struct Solving<'m, M, D: Dim, const K: usize>(Problem<'m, M, D>);

impl<M: SystemOutputs<D, K>, D: Dim, const K: usize> WithStepper<D> for Solving<'_, M, D, K> {
    type Output = Result<Trajectory<D, K>, SolveFailure>;
    fn run<S: Stepper<D>>(self, stepper: S) -> Self::Output {
        self.0.solve_with(stepper)
    }
}

impl<D: Dim> Observer<D, (), usize> for Record<'_, D> {
    fn wants_dense(&self) -> bool {
        matches!(self.output, Output::Times(_))
    }

    fn on_step(&mut self, step: &StepView<'_, D, ()>) -> Observed {
        match self.output {
            Output::Steps => self.push(step.t1, step.y1.clone()),
            Output::Times(times) => {
                while self.next < times.len() && reached(step.t1, times[self.next], self.backward) {
                    let t = times[self.next];
                    let mut y = step.y1.clone();
                    if t != step.t1 {
                        // Always present: `wants_dense` asks the driver for it in this case.
                        if let Some(dense) = step.dense {
                            dense.at(t, &mut y);
                        }
                    }
                    self.push(t, y);
                    self.next += 1;
                }
            }
        }
        Ok(())
    }
}
