//! A smooth model solved by the runtime's `Problem` API, its programs run by the interpreter.
//!
//! Events are zero crossings of one of the model's states or outputs. A threshold other than
//! zero is an output of the file (`hit = theta - 0.1`), so a front end needs no expression
//! language of its own; an output needs the derivatives, which the runtime hands every event
//! function, and is evaluated by the interpreter there.

use crate::engine::Engine;
use crate::error::{RequestError, RunFailure, SolveFailure};
use crate::interpreted::{failure_at, row, tolerance, Interpreted, Labels};
use crate::request::{Resolved, ResolvedEvent, SolveRequest, Watched};
use crate::solution::{EventKind, Solution, SolvedEvent, Stop};
use model_algebra::CompiledModel;
use model_runtime::{Event, Output, Problem, SolveError, Termination};
use std::cell::RefCell;
use std::rc::Rc;

/// The model's engine and its parameters, owned, for the event functions (which must be
/// `'static`).
struct Shared {
    engine: Engine,
    params: Vec<f64>,
    /// The outputs, evaluated into.
    outputs: RefCell<Vec<f64>>,
}

impl ResolvedEvent {
    /// The runtime's event: the state read from `y`, or the output evaluated at `(t, y, dy)`
    /// by the interpreter (NaN where it cannot be, which the runtime reports naming the
    /// event).
    fn event(&self, shared: &Rc<Shared>) -> Event {
        let name = &self.request.name;
        let event = match self.watched {
            Watched::State(k) => Event::new(name, move |_t, y, _dy| y[k]),
            Watched::Output(j) => {
                let shared = Rc::clone(shared);
                Event::new(name, move |t, y, dy| {
                    let mut outputs = shared.outputs.borrow_mut();
                    (shared
                        .engine
                        .outputs(t, y, dy, &shared.params, &mut outputs))
                    .map_or(f64::NAN, |()| outputs[j])
                })
            }
        };
        let event = event.direction(self.request.direction);
        if self.request.stop {
            event.terminal()
        } else {
            event
        }
    }
}

/// Integrates `model` as `request` says; the outputs are evaluated at every recorded point.
pub(crate) fn solve_smooth(
    model: &CompiledModel,
    resolved: Resolved,
    request: &SolveRequest,
) -> Result<Solution, SolveFailure> {
    let n = model.states.len();
    let params = &resolved.params;
    let labels = Labels::of(model);
    let engine =
        |model| Engine::new(model, params.len()).map_err(|e| failure_at(model, request.t0, e));
    let evaluator = engine(model)?;
    let interpreted = Interpreted::new(model, params, &labels, &evaluator);
    let output = match resolved.times {
        Some(times) => Output::Times(times),
        None => Output::Steps,
    };
    let mut problem = Problem::new(&interpreted, resolved.y0, (request.t0, request.t_end))
        .method(request.method)
        .tolerance(tolerance(n, request.rtol, request.atol))
        .output(output);
    if !resolved.events.is_empty() {
        let shared = Rc::new(Shared {
            engine: engine(model)?,
            params: params.clone(),
            outputs: RefCell::new(vec![0.0; model.outputs.len()]),
        });
        for event in &resolved.events {
            problem = problem.event(event.event(&shared));
        }
    }
    let solved = problem.solve::<0>().map_err(|failure| match failure {
        // Unusable settings (a time span, a tolerance) are the caller's input, not a failed run.
        model_runtime::SolveFailure::Solve {
            error: SolveError::InvalidInput(_),
            ..
        }
        | model_runtime::SolveFailure::OutputTime { .. } => {
            SolveFailure::Request(RequestError::Settings(failure.to_string()))
        }
        failure => SolveFailure::Run(RunFailure {
            message: failure.to_string(),
            steps: None,
            events: 0,
        }),
    })?;
    let mut rows = Vec::with_capacity(solved.t.len() + 1);
    for (&t, y) in solved.t.iter().zip(&solved.y) {
        rows.push(row(model, &evaluator, params, t, y)?);
    }
    let events = (solved.events.iter())
        .map(|event| {
            Ok(SolvedEvent {
                name: event.name.clone(),
                kind: EventKind::Crossing,
                row: row(model, &evaluator, params, event.t, &event.y)?,
            })
        })
        .collect::<Result<Vec<_>, SolveFailure>>()?;
    let stop = match solved.stop {
        Termination::EndTime => Stop::EndTime,
        Termination::Event { name } => Stop::Event {
            name,
            kind: EventKind::Crossing,
        },
    };
    if let (Stop::Event { .. }, Some(last)) = (&stop, events.last()) {
        // The run ended at the event: its state closes the trajectory.
        if rows.last().is_none_or(|row| row[0] < last.t()) {
            rows.push(last.row.clone());
        }
    }
    Ok(Solution {
        model: model.name.clone(),
        columns: columns(model.states.iter().chain(&model.outputs)),
        states: n,
        rows,
        events,
        stop,
        stats: solved.stats,
        accumulations: Vec::new(),
    })
}

/// `t`, then `names`.
pub(crate) fn columns<'a>(names: impl Iterator<Item = &'a String>) -> Vec<String> {
    std::iter::once("t".to_string())
        .chain(names.cloned())
        .collect()
}
