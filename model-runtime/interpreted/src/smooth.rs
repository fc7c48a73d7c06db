//! A smooth model solved by the runtime's hybrid driver as a system of one mode whose guards
//! are the requested events, its programs run by the interpreter.
//!
//! Events are zero crossings of one of the model's states or outputs. A threshold other than
//! zero is an output of the file (`hit = theta - 0.1`), so a front end needs no expression
//! language of its own; an output needs the derivatives, which the runtime hands every guard,
//! and is evaluated by the interpreter there. The driver is the one `model_runtime::Problem`
//! runs (the same steps, the same event location), observed by this crate's [`Recording`]
//! so that a failed, bounded or interrupted run keeps what it computed.

use crate::engine::Engine;
use crate::error::{settings, SolveFailure};
use crate::interpreted::{failure_at, tolerance, Interpreted, Labels};
use crate::recording::{Grid, Recording};
use crate::request::{Control, Resolved, SolveRequest, Stepping, Watched};
use crate::solution::{EventKind, Solution, SolvedEvent, Stop};
use crate::tables::{Ended, Tables};
use model_algebra::CompiledModel;
use model_runtime::{
    Dyn, EvalError, EventHit, GuardSpec, HybridOptions, HybridSolver, HybridSystem, Matrix, Method,
    Observed, Observer, Rhs, SolveError, StepView, Stepper, StopReason, System, Transition,
    WithStepper,
};
use std::cell::RefCell;
use std::ops::ControlFlow;

/// The model with its events as the guards of one mode, and the events located (each by
/// its index in the request, with its time and state).
struct WithEvents<'a> {
    interpreted: Interpreted<'a>,
    resolved: &'a Resolved<'a>,
    guards: Vec<GuardSpec<usize>>,
    located: Vec<(usize, f64, Vec<f64>)>,
    /// The outputs, evaluated into where an event watches one.
    outputs: RefCell<Vec<f64>>,
}

impl HybridSystem<Dyn> for WithEvents<'_> {
    type Mode = ();
    type Guard = usize;
    type Stop = usize;
    type Note = ();

    fn rhs(&self, _: (), t: f64, y: &Vec<f64>, dy: &mut Vec<f64>) -> Result<(), EvalError> {
        self.interpreted.rhs(t, y, dy)
    }

    fn jacobian(
        &self,
        _: (),
        t: f64,
        y: &Vec<f64>,
        jac: &mut Matrix<Dyn>,
    ) -> Result<(), EvalError> {
        self.interpreted.jacobian(t, y, jac)
    }

    fn guards(&self, _: ()) -> &[GuardSpec<usize>] {
        &self.guards
    }

    /// A state read from `y`, an output evaluated at `(t, y, dy)` by the interpreter.
    fn guard_values(
        &self,
        _: (),
        t: f64,
        y: &Vec<f64>,
        dy: &Vec<f64>,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        let mut outputs = self.outputs.borrow_mut();
        let mut evaluated = false;
        for (value, event) in values.iter_mut().zip(&self.resolved.events) {
            *value = match event.watched {
                Watched::State(k) => y[k],
                Watched::Output(j) => {
                    if !evaluated {
                        let engine = self.interpreted.engine();
                        let params = &self.resolved.params;
                        let at = engine.outputs(t, y, dy, params, &mut outputs);
                        at.map_err(|e| self.interpreted.error(e))?;
                        evaluated = true;
                    }
                    outputs[j]
                }
            };
        }
        Ok(())
    }

    fn on_event(
        &mut self,
        _: (),
        hit: &EventHit<Dyn, usize>,
    ) -> Result<Transition<Dyn, (), usize>, EvalError> {
        self.located.push((hit.guard, hit.t, hit.y.clone()));
        Ok(if self.resolved.events[hit.guard].request.stop {
            Transition::Stop(hit.guard)
        } else {
            Transition::Continue {
                y: hit.y.clone(),
                note: (),
            }
        })
    }
}

impl Observer<Dyn, (), usize> for Recording<'_> {
    fn wants_dense(&self) -> bool {
        Recording::wants_dense(self)
    }

    fn on_step(&mut self, step: &StepView<'_, Dyn, ()>) -> Observed {
        self.step(0, step)
    }

    fn proceed(&mut self) -> ControlFlow<()> {
        Recording::proceed(self)
    }
}

/// The run, waiting for the method's stepper.
struct Run<'a, 'b> {
    model: &'a CompiledModel,
    resolved: &'a Resolved<'a>,
    request: &'a SolveRequest,
    control: &'b Control<'b>,
    stepping: &'b Stepping,
}

impl WithStepper<Dyn> for Run<'_, '_> {
    type Output = Result<Solution, SolveFailure>;

    fn run<S: Stepper<Dyn>>(self, stepper: S) -> Self::Output {
        let Run {
            model,
            resolved,
            request,
            control,
            stepping,
        } = self;
        let n = model.states.len();
        let labels = Labels::of(model);
        let engine = Engine::new(model, resolved.params.len())
            .map_err(|e| failure_at(model, request.t0, e))?;
        let mut system = WithEvents {
            interpreted: Interpreted::new(model, &resolved.params, &labels, &engine),
            resolved,
            guards: (resolved.events.iter().enumerate())
                .map(|(index, event)| GuardSpec {
                    id: index,
                    direction: event.request.direction,
                })
                .collect(),
            located: Vec::new(),
            outputs: RefCell::new(vec![0.0; engine.n_outputs()]),
        };
        let grid = match resolved.times {
            Some(times) => Grid::Times { times, next: 0 },
            None => Grid::Steps,
        };
        let bound = (request.t0, request.work_bound());
        let width = 1 + n + model.outputs.len();
        let mut recording =
            Recording::new(grid, Default::default(), bound, control.interrupt, width)
                .with_dense(stepping.dense)
                .with_direction(request.t_end < request.t0);
        recording.start(request.t0, 0, &resolved.y0);
        let options = HybridOptions {
            step: stepping.options(),
            ..HybridOptions::default()
        };
        let tolerance = tolerance(n, request.rtol, request.atol);
        let mut solver = HybridSolver::new(stepper, tolerance, options)
            .map_err(|error| settings(error.to_string()))?;
        let outcome = solver.run(
            &mut system,
            (),
            request.t0,
            &resolved.y0,
            request.t_end,
            &mut recording,
        );
        let tables = Tables {
            name: model.name.clone(),
            models: vec![model],
            engines: vec![&engine],
            modes: Vec::new(),
            params: &resolved.params,
            columns: columns(model.states.iter().chain(&model.outputs)),
            states: n,
            discrete: 0,
            explicit: explicit(request.method),
            buffers: Default::default(),
        };
        let events = (system.located.iter())
            .map(|(guard, t, y)| {
                let name = &resolved.events[*guard].request.name;
                let event = tables.event(name, EventKind::Crossing, 0, (*t, y, &[]))?;
                Ok::<_, SolveFailure>(SolvedEvent {
                    request: Some(*guard),
                    ..event
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let ended = match outcome {
            Ok(outcome) => {
                let stop = match outcome.stop {
                    StopReason::EndTime | StopReason::Observer => Stop::EndTime,
                    StopReason::User(guard) => Stop::Event {
                        name: resolved.events[guard].request.name.clone(),
                        kind: EventKind::Crossing,
                    },
                };
                if let Stop::Event { .. } = stop {
                    // The run ended at the event: its state closes the trajectory.
                    recording.close(outcome.t, 0, &outcome.y);
                }
                Ended::Ran {
                    stop,
                    stats: outcome.stats,
                }
            }
            Err(error) => {
                let names: Vec<String> = (resolved.events.iter())
                    .map(|e| e.request.name.clone())
                    .collect();
                let info = Box::new(system.interpreted.info().clone());
                let failure = model_runtime::SolveFailure::from_hybrid(error, info, &names);
                if let model_runtime::SolveFailure::Solve {
                    error: SolveError::InvalidInput(_),
                    ..
                } = failure
                {
                    // Unusable settings (a time span, a tolerance) are the caller's input.
                    return Err(settings(failure.to_string()));
                }
                Ended::Failed {
                    message: failure.to_string(),
                    stats: solver.stats(),
                }
            }
        };
        tables.finish(recording, events, Vec::new(), ended)
    }
}

/// Whether `method` is explicit (a stiff model makes its steps ever shorter).
pub(crate) fn explicit(method: Method) -> bool {
    !matches!(method, Method::Rodas4)
}

/// `t`, then `names`.
pub(crate) fn columns<'a>(names: impl Iterator<Item = &'a String>) -> Vec<String> {
    std::iter::once("t".to_string())
        .chain(names.cloned())
        .collect()
}

/// Integrates `model` as `request` says; the outputs are evaluated at every recorded point.
pub(crate) fn solve_smooth(
    model: &CompiledModel,
    resolved: Resolved<'_>,
    request: &SolveRequest,
    (control, stepping): (&Control<'_>, &Stepping),
) -> Result<Solution, SolveFailure> {
    let n = model.states.len();
    request.method.with_stepper(
        Dyn(n),
        Run {
            model,
            resolved: &resolved,
            request,
            control,
            stepping,
        },
    )
}
