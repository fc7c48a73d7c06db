//! A switched model (one with `mode` and `when`) solved by the runtime's switched driver, the
//! modes' programs run by the interpreter, exactly as for the model `model!` compiles from the
//! same text.
//!
//! Each mode runs in the model's own states, as a smooth model does (see `interpreted`), with
//! the request's tolerance. The trajectory's rows are `t`, the states
//! and the outputs of the mode in force; each located event is an event of the solution under
//! its name (an impact, a stick, a stop), and an accumulation of an event's resets an
//! [`EventKind::Accumulation`] at the extrapolated accumulation point, with the state its rule
//! sets.

use crate::engine::{Engine, Runner};
use crate::error::{RunFailure, SolveFailure};
use crate::interpreted::{failure_at, row, tolerance, Interpreted, Labels};
use crate::request::{Resolved, SolveRequest};
use crate::smooth::columns;
use crate::solution::{AccumulationPoint, EventKind, Solution, SolvedEvent, Stop};
use model_algebra::{CompiledModel, Inputs};
use model_dsl::{Action, CompiledSwitched, Crossing};
use model_runtime::{
    run_switched, AccumulationAction, Direction, Dop853, Dopri5, Dyn, EvalError, EventAction,
    EventDecl, Fired, HybridError, HybridOptions, Method, ModeDecl, ModeGraph, Rhs, Rk4, Rodas4,
    SwitchedFailure, SwitchedModel, SwitchedRun,
};

/// The runtime's mode graph of a compiled switched model.
pub fn mode_graph(model: &CompiledSwitched) -> Result<ModeGraph, SolveFailure> {
    let modes = (model.modes.iter())
        .map(|mode| ModeDecl {
            name: mode.model.name.clone(),
            events: (mode.events.iter())
                .map(|event| EventDecl {
                    name: event.name.clone(),
                    direction: match event.crossing {
                        Crossing::Up => Direction::Up,
                        Crossing::Down => Direction::Down,
                        Crossing::Both => Direction::Both,
                    },
                    action: match &event.action {
                        Action::Record => EventAction::Record,
                        Action::Stop => EventAction::Stop,
                        Action::Jump(jump) => EventAction::Reset {
                            to: jump.to,
                            reset: !jump.states.is_empty(),
                        },
                    },
                    on_accumulation: event.accumulation.as_ref().map(|jump| AccumulationAction {
                        to: jump.to,
                        reset: !jump.states.is_empty(),
                    }),
                })
                .collect(),
        })
        .collect();
    ModeGraph::new(modes).map_err(|error| SolveFailure::Graph(error.to_string()))
}

/// A switched model run by the interpreter, in its own number of states.
struct InterpretedSwitched<'a> {
    model: &'a CompiledSwitched,
    /// The parameters, then the discrete values as they are now (the model's parameters,
    /// the discrete values' defaults the initial ones: what every mode's model reads).
    values: Vec<f64>,
    /// Each mode's names, in mode order.
    labels: Vec<Labels>,
    /// Each mode's programs, in mode order.
    engines: Vec<Engine>,
    /// Each mode's guards, in mode order.
    guards: Vec<Runner>,
    graph: ModeGraph,
}

impl<'a> InterpretedSwitched<'a> {
    fn new(model: &'a CompiledSwitched, params: &[f64], t0: f64) -> Result<Self, SolveFailure> {
        let values = params.to_vec();
        let (mut engines, mut guards) = (Vec::new(), Vec::new());
        for mode in &model.modes {
            let m = &mode.model;
            let at_t0 = |e| failure_at(m, t0, e);
            engines.push(Engine::new(m, values.len()).map_err(at_t0)?);
            let guard = Runner::outputs(&mode.guards, m, values.len(), mode.events.len());
            guards.push(guard.map_err(at_t0)?);
        }
        Ok(InterpretedSwitched {
            model,
            labels: (model.modes.iter())
                .map(|mode| Labels::of(&mode.model))
                .collect(),
            values,
            engines,
            guards,
            graph: mode_graph(model)?,
        })
    }

    /// Mode `mode`'s model reading the values now.
    fn mode(&self, mode: usize) -> Interpreted<'_> {
        Interpreted::new(
            &self.model.modes[mode].model,
            &self.values,
            &self.labels[mode],
            &self.engines[mode],
        )
    }

    fn inputs<'b>(&'b self, t: f64, y: &'b [f64], dy: &'b [f64]) -> Inputs<'b> {
        Inputs {
            t,
            states: y,
            params: &self.values,
            ders: dy,
        }
    }
}

impl SwitchedModel<Dyn> for InterpretedSwitched<'_> {
    fn graph(&self) -> &ModeGraph {
        &self.graph
    }

    fn rhs(&self, mode: usize, t: f64, y: &Vec<f64>, dy: &mut Vec<f64>) -> Result<(), EvalError> {
        self.mode(mode).rhs(t, y, dy)
    }

    fn jacobian(
        &self,
        mode: usize,
        t: f64,
        y: &Vec<f64>,
        jac: &mut Vec<Vec<f64>>,
    ) -> Result<(), EvalError> {
        self.mode(mode).jacobian(t, y, jac)
    }

    fn event_values(
        &self,
        mode: usize,
        t: f64,
        y: &Vec<f64>,
        dy: &Vec<f64>,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        (self.guards[mode].run(&self.inputs(t, y, dy), values))
            .map_err(|e| self.mode(mode).error(e))
    }

    fn reset(
        &mut self,
        mode: usize,
        event: usize,
        accumulation: bool,
        t: f64,
        y: &Vec<f64>,
        dy: &Vec<f64>,
        out: &mut Vec<f64>,
    ) -> Result<(), EvalError> {
        let event = &self.model.modes[mode].events[event];
        let jump = match (&event.action, &event.accumulation, accumulation) {
            (_, Some(jump), true) => jump,
            (Action::Jump(jump), _, false) => jump,
            _ => return Ok(()),
        };
        let stores =
            (jump.program.eval(&self.inputs(t, y, dy))).map_err(|e| self.mode(mode).error(e))?;
        let n = self.model.states().len();
        let params = self.model.n_params();
        for (&slot, value) in jump.states.iter().zip(stores.outputs(jump.states.len())) {
            if slot < n {
                out[slot] = value;
            } else {
                // A discrete value: after the parameters in what the modes read.
                self.values[params + slot - n] = value;
            }
        }
        Ok(())
    }

    fn first_step(&self, mode: usize, t: f64, y: &Vec<f64>) -> Option<f64> {
        let step = self.model.modes[mode].first_step.as_ref()?;
        let mut dy = vec![0.0; y.len()];
        self.rhs(mode, t, y, &mut dy).ok()?;
        let stores = step.program.eval(&self.inputs(t, y, &dy)).ok()?;
        let h = stores.outputs(1)[0];
        (h.is_finite() && h > 0.0).then_some(h)
    }
}

/// Integrates a switched model from its first mode. The rows are those of the mode in force;
/// the events are every event the run met, an accumulation at its extrapolated point, and a
/// terminal event last.
pub(crate) fn solve_switched(
    model: &CompiledSwitched,
    resolved: Resolved,
    request: &SolveRequest,
) -> Result<Solution, SolveFailure> {
    let n = model.states().len();
    let params = &resolved.params;
    let mut interpreted = InterpretedSwitched::new(model, params, request.t0)?;
    let tolerance = tolerance(n, request.rtol, request.atol);
    let options = HybridOptions {
        sample_rate: request.dt.map(|dt| 1.0 / dt),
        ..HybridOptions::default()
    };
    let start = (request.t0, resolved.y0);
    let t_end = request.t_end;
    let run = match request.method {
        Method::Dopri5 => run_switched(
            &mut interpreted,
            Dopri5::new_in(Dyn(n)),
            tolerance,
            options,
            start,
            t_end,
        ),
        Method::Dop853 => run_switched(
            &mut interpreted,
            Dop853::new_in(Dyn(n)),
            tolerance,
            options,
            start,
            t_end,
        ),
        Method::Rodas4 => run_switched(
            &mut interpreted,
            Rodas4::new_in(Dyn(n)),
            tolerance,
            options,
            start,
            t_end,
        ),
        Method::Rk4 { h } => run_switched(
            &mut interpreted,
            Rk4::new_in(Dyn(n), h),
            tolerance,
            options,
            start,
            t_end,
        ),
    }
    .map_err(run_failure)?;
    let index = |name: &str| model.mode(name).unwrap_or(0);
    // Outputs read no discrete value (the compiler refuses it): the values at the end serve.
    let values = &interpreted.values;
    let at = |mode: &str, t: f64, y: &[f64]| {
        let k = index(mode);
        row(&model.modes[k].model, &interpreted.engines[k], values, t, y)
    };
    let mut rows = Vec::with_capacity(run.samples.len() + 1);
    for (t, mode, y) in &run.samples {
        rows.push(at(mode, *t, y)?);
    }
    if rows.last().is_none_or(|r| r[0] < run.t) {
        rows.push(at(&run.mode, run.t, &run.y)?);
    }
    let mut events = Vec::with_capacity(run.events.len());
    let mut accumulations = Vec::new();
    for (k, event) in run.events.iter().enumerate() {
        let solved = match event.fired {
            Fired::Accumulated | Fired::AccumulatedStop => {
                let continued_in =
                    (event.fired == Fired::Accumulated).then(|| mode_after(&run, k).to_string());
                accumulations.push(AccumulationPoint {
                    event: event.event.clone(),
                    t: event.t,
                    continued_in,
                });
                SolvedEvent {
                    name: event.event.clone(),
                    kind: EventKind::Accumulation,
                    row: at(mode_after(&run, k), event.t, &event.y_after)?,
                }
            }
            _ => SolvedEvent {
                name: event.event.clone(),
                kind: EventKind::Crossing,
                row: at(&event.mode, event.t, &event.y)?,
            },
        };
        events.push(solved);
    }
    let stop = match &run.stopped_by {
        None => Stop::EndTime,
        Some(name) => Stop::Event {
            name: name.clone(),
            kind: match run.events.last().map(|e| e.fired) {
                Some(Fired::AccumulatedStop) => EventKind::Accumulation,
                _ => EventKind::Crossing,
            },
        },
    };
    let first: &CompiledModel = &model.modes[0].model;
    Ok(Solution {
        model: model.name.clone(),
        columns: columns(model.slot_names().iter().chain(&first.outputs)),
        states: n,
        rows,
        events,
        stop,
        stats: run.stats,
        accumulations,
    })
}

/// The mode the run continued in after its `k`-th event (its own, for an event that ended
/// the run).
fn mode_after(run: &SwitchedRun<Dyn>, k: usize) -> &str {
    let event = &run.events[k];
    match run.events.get(k + 1) {
        Some(next) => next.mode.as_str(),
        None if event.fired == Fired::Accumulated => run.mode.as_str(),
        None => event.mode.as_str(),
    }
}

/// A failed run in the model's words (modes by name, what resolves a chatter), with the work
/// done until then.
fn run_failure(failure: SwitchedFailure<Dyn>) -> SolveFailure {
    let message = match &*failure.error {
        HybridError::Chattering {
            t,
            transitions,
            window,
            modes,
        } => {
            let names: Vec<String> = modes.iter().map(|m| format!("`{m}`")).collect();
            format!(
                "chattering at t = {t}: {transitions} transitions within {window:e} between modes {} \
                 (an event whose firings shrink steadily is resolved by `when EVENT accumulates -> MODE`)",
                names.join(", ")
            )
        }
        other => other.to_string(),
    };
    SolveFailure::Run(RunFailure {
        message,
        steps: Some(failure.steps),
        events: failure.events.len(),
    })
}
