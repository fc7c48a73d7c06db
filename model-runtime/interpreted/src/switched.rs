//! A switched model (one with `mode` and `when`) solved by the runtime's switched driver, the
//! modes' programs run by the interpreter, exactly as for the model `model!` compiles from the
//! same text.
//!
//! Each mode runs in the model's own states, as a smooth model does (see `interpreted`), with
//! the request's tolerance. The trajectory's rows are `t`, the states, the discrete values in
//! force and the outputs of the mode in force (reading those values); each located event is
//! an event of the solution under its name (an impact, a stick, a stop) with the state before
//! and, for a reset, after it, and an accumulation of an event's resets an
//! [`EventKind::Accumulation`] at the extrapolated accumulation point, with the state its rule
//! sets. A run that stops at an accumulation reports it at that one time: its event row, the
//! solution's [`Solution::stop_time`] and every message (the driver itself ends at the last
//! firing, within the rule's tail before it, which is the trajectory's last row).

use crate::engine::{Engine, Runner};
use crate::error::{RunFailure, SolveFailure};
use crate::interpreted::{failure_at, tolerance, Interpreted, Labels};
use crate::recording::{Grid, Recording, SharedValues};
use crate::request::{Control, Resolved, SolveRequest, Stepping};
use crate::smooth::{columns, explicit};
use crate::solution::{AccumulationPoint, EventKind, Solution, Stop};
use crate::tables::{Ended, Tables};
use model_algebra::{CompiledModel, Inputs};
use model_dsl::{Action, CompiledSwitched, Crossing};
use model_runtime::{
    name_modes, AccumulationAction, AccumulationRule, Direction, Dyn, EvalError, EventAction,
    EventDecl, EventId, Fired, Firing, HybridError, HybridOptions, HybridSolver, InputError,
    ModeDecl, ModeGraph, ModeId, Observed, Observer, Rhs, Sample, StepView, Stepper, StopReason,
    Switched, SwitchedModel, SwitchedNote, SwitchedStop, TransitionKind, TransitionRecord,
    WithStepper,
};
use std::cell::RefCell;
use std::ops::ControlFlow;
use std::rc::Rc;

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
    /// The discrete values as they are now, shared with the recording (written at each
    /// reset, read at each recorded point).
    discrete: SharedValues,
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
        let discrete = values[model.n_params()..].to_vec();
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
            discrete: Rc::new(RefCell::new(discrete)),
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
                self.discrete.borrow_mut()[slot - n] = value;
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

/// One transition as the recording saw it: the event, what it did, the state on both sides
/// (with the discrete values, by snapshot) and the modes.
struct Met {
    event: EventId,
    fired: Fired,
    t: f64,
    from: usize,
    to: usize,
    y: Vec<f64>,
    y_after: Vec<f64>,
    before: usize,
    after: usize,
}

/// The recording of a switched run, and its transitions.
struct SwitchedRecording<'r> {
    recording: Recording<'r>,
    met: Vec<Met>,
    /// The discrete values in force since the last transition (a snapshot's index).
    known: usize,
}

impl Observer<Dyn, ModeId, EventId, SwitchedNote> for SwitchedRecording<'_> {
    fn wants_dense(&self) -> bool {
        self.recording.wants_dense()
    }

    fn on_step(&mut self, step: &StepView<'_, Dyn, ModeId>) -> Observed {
        self.recording.step(step.mode.index(), step)
    }

    fn on_sample(&mut self, sample: &Sample<'_, Dyn, ModeId>) -> Observed {
        self.recording.sample(sample.mode.index(), sample)
    }

    fn proceed(&mut self) -> ControlFlow<()> {
        self.recording.proceed()
    }

    fn on_transition(
        &mut self,
        record: TransitionRecord<Dyn, ModeId, EventId, SwitchedNote>,
    ) -> Observed {
        let Firing { event, fired, t } = Firing::of(record.note, record.hit.t);
        let from = record.from.index();
        let to = match record.kind {
            TransitionKind::Switch { to } => to.index(),
            TransitionKind::Continue | TransitionKind::Pass => from,
        };
        // Discrete values change only in a transition's reset, applied before this call.
        let before = self.known;
        let after = self.recording.values_now();
        self.known = after;
        self.met.push(Met {
            event,
            fired,
            t,
            from,
            to,
            y: record.hit.y,
            y_after: record.y_after,
            before,
            after,
        });
        Ok(())
    }
}

/// The run, waiting for the method's stepper.
struct Run<'a, 'c> {
    model: &'a CompiledSwitched,
    resolved: &'a Resolved<'a>,
    request: &'a SolveRequest,
    control: &'a Control<'c>,
    stepping: &'a Stepping,
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
        let n = model.states().len();
        let mut interpreted = InterpretedSwitched::new(model, &resolved.params, request.t0)?;
        let graph = interpreted.graph.clone();
        let discrete = Rc::clone(&interpreted.discrete);
        let options = HybridOptions {
            sample_rate: request.dt.map(|dt| 1.0 / dt),
            step: stepping.options(),
            ..HybridOptions::default()
        };
        let grid = match request.dt {
            Some(_) => Grid::Rate,
            None => Grid::Steps,
        };
        let bound = (request.t0, request.work_bound());
        let outputs = model.modes[0].model.outputs.len();
        let width = 1 + n + model.discrete.len() + outputs;
        let mut observer = SwitchedRecording {
            recording: Recording::new(grid, discrete, bound, control.interrupt, width)
                .with_dense(stepping.dense),
            met: Vec::new(),
            known: 0,
        };
        let warnings = on_threshold(&interpreted, request.t0, &resolved.y0);
        let start = graph.first();
        let input = |error: InputError| {
            run_failure(
                &graph,
                HybridError::Solve {
                    mode: start,
                    error: error.into(),
                },
            )
        };
        let rule = AccumulationRule::for_span(request.t_end - request.t0);
        let mut system = Switched::new(&mut interpreted, rule).map_err(input)?;
        let tolerance = tolerance(n, request.rtol, request.atol);
        let mut solver = HybridSolver::new(stepper, tolerance, options).map_err(input)?;
        let (t0, t_end) = (request.t0, request.t_end);
        let outcome = solver.run(&mut system, start, t0, &resolved.y0, t_end, &mut observer);
        let SwitchedRecording {
            mut recording, met, ..
        } = observer;
        drop(system);
        let engines = interpreted.engines.iter().collect();
        let tables = tables(model, engines, resolved, request);
        let mut events = Vec::with_capacity(met.len() + 1);
        let mut accumulations = Vec::new();
        for met in &met {
            let name = &graph.mode(met.event.mode).events[met.event.event].name;
            let before = &recording.snapshots[met.before];
            let after = &recording.snapshots[met.after];
            let event = if met.fired == Fired::Accumulated {
                accumulations.push(AccumulationPoint {
                    event: name.clone(),
                    t: met.t,
                    continued_in: tables.modes.get(met.to).cloned(),
                });
                tables.event(
                    name,
                    EventKind::Accumulation,
                    met.to,
                    (met.t, &met.y_after, after),
                )?
            } else {
                let mut event =
                    tables.event(name, EventKind::Crossing, met.from, (met.t, &met.y, before))?;
                if met.fired == Fired::Reset {
                    event.after = Some(tables.row(met.to, met.t, &met.y_after, after)?);
                    event.mode_after = tables.modes.get(met.to).cloned();
                }
                event
            };
            events.push(event);
        }
        let ended = match outcome {
            Ok(outcome) => {
                let mode = outcome.mode.index();
                let now = recording.values_now();
                let values = recording.snapshots[now].clone();
                let stop = match outcome.stop {
                    StopReason::EndTime | StopReason::Observer => Stop::EndTime,
                    StopReason::User(stop) => {
                        let (kind, t) = match stop {
                            SwitchedStop::Event { t, .. } => (EventKind::Crossing, t),
                            SwitchedStop::Accumulation { t_inf, .. } => {
                                (EventKind::Accumulation, t_inf)
                            }
                        };
                        let id = stop.event();
                        let name = graph.mode(id.mode).events[id.event].name.clone();
                        if kind == EventKind::Accumulation {
                            accumulations.push(AccumulationPoint {
                                event: name.clone(),
                                t,
                                continued_in: None,
                            });
                        }
                        events.push(tables.event(&name, kind, mode, (t, &outcome.y, &values))?);
                        Stop::Event { name, kind }
                    }
                };
                recording.close(outcome.t, mode, &outcome.y);
                Ended::Ran {
                    stop,
                    stats: outcome.stats,
                }
            }
            Err(error) => match run_failure(&graph, error) {
                SolveFailure::Run(failure) => Ended::Failed {
                    message: failure.message,
                    stats: solver.stats(),
                },
                other => return Err(other),
            },
        };
        let mut solved = tables.finish(recording, events, accumulations, ended);
        match &mut solved {
            Ok(solution) => solution.warnings = warnings,
            Err(SolveFailure::Run(RunFailure {
                partial: Some(partial),
                ..
            })) => partial.warnings = warnings,
            Err(_) => {}
        }
        solved
    }
}

/// The events of the first mode whose guard reads a derivative and is exactly on its
/// threshold at the start: a guard fires when it crosses, and its departure from a
/// threshold it starts on is not a crossing, so such an event may never fire.
fn on_threshold(model: &InterpretedSwitched<'_>, t0: f64, y0: &[f64]) -> Vec<String> {
    let mode = &model.model.modes[0];
    let y = y0.to_vec();
    let mut dy = vec![0.0; y.len()];
    let mut values = vec![0.0; mode.events.len()];
    let evaluated = (model.rhs(0, t0, &y, &mut dy))
        .and_then(|()| model.event_values(0, t0, &y, &dy, &mut values));
    if evaluated.is_err() {
        // The run itself says why the model cannot be evaluated there.
        return Vec::new();
    }
    (mode.events.iter().zip(&values))
        // The guard as the compiler printed it, in the DSL's syntax: `der(` only where the
        // guard reads a derivative.
        .filter(|(event, &value)| value == 0.0 && event.guard.contains("der("))
        .map(|(event, _)| {
            format!(
                "event `{}`: its guard `{}` reads a derivative and is on its threshold (0) at \
                 the start, t = {t0}; leaving a threshold is not crossing it, so the event \
                 fires only once the guard comes back through it: start the run off the \
                 threshold or write the guard on a state",
                event.name, event.guard
            )
        })
        .collect()
}

/// The tables of a switched model: the states' slot names, the discrete values, the outputs
/// (every mode has the same), each mode's model.
fn tables<'a>(
    model: &'a CompiledSwitched,
    engines: Vec<&'a Engine>,
    resolved: &'a Resolved<'a>,
    request: &SolveRequest,
) -> Tables<'a> {
    let first: &CompiledModel = &model.modes[0].model;
    let discrete: Vec<String> = model
        .discrete
        .iter()
        .map(|(name, _)| name.clone())
        .collect();
    let slots = model.slot_names();
    Tables {
        name: model.name.clone(),
        models: model.modes.iter().map(|mode| &mode.model).collect(),
        engines,
        modes: model.modes.iter().map(|m| m.model.name.clone()).collect(),
        params: &resolved.params[..model.n_params()],
        columns: columns(slots.iter().chain(&discrete).chain(&first.outputs)),
        states: slots.len(),
        discrete: discrete.len(),
        explicit: explicit(request.method),
        buffers: Default::default(),
    }
}

/// Integrates a switched model from its first mode. The rows are those of the mode in force,
/// with the discrete values in force; the events are every event the run met, an
/// accumulation at its extrapolated point, and a terminal event last.
pub(crate) fn solve_switched(
    model: &CompiledSwitched,
    resolved: Resolved<'_>,
    request: &SolveRequest,
    (control, stepping): (&Control<'_>, &Stepping),
) -> Result<Solution, SolveFailure> {
    let n = model.states().len();
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

/// A failed run in the model's words (modes by name, what resolves a chatter).
fn run_failure(graph: &ModeGraph, error: HybridError<ModeId>) -> SolveFailure {
    let error = name_modes(graph, error);
    let message = match &error {
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
        steps: None,
        events: 0,
        work: None,
        hint: None,
        partial: None,
    })
}
