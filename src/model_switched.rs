//! `eulerdisk model solve FILE.dsl` for a switched model (one with `mode` and `when`): the
//! modes' programs run by the compiler's interpreter, the events located and applied by the
//! runtime's switched driver, exactly as for the model `model!` compiles from the same text.
//!
//! Each mode is embedded in [`MAX_STATES`] components as `model solve` embeds a smooth model
//! (see `model_solve`), with the same tolerance scaling, so the error norm and every step-size
//! decision are those of the model's own states. The events and what they do come from the
//! file: the trajectory's rows are `t`, the states and the outputs of the mode in force; each
//! located event is a row of the events table under its name (an impact, a stick, a stop), and
//! an accumulation of an event's resets under `NAME accumulates`, at the extrapolated
//! accumulation point, with the state its rule sets.

use crate::model_file::ModelFileError;
use crate::model_solve::{row, sample_times, FileEvent, FileTrajectory, Interpreted, SolveSettings, MAX_STATES};
use model_algebra::Inputs;
use model_dsl::{Action, CompiledSwitched, Crossing};
use model_runtime::{
    AccumulationAction, AccumulationRule, Direction, Dop853, Dopri5, EvalError, EventAction,
    EventDecl, HybridError, HybridOptions, HybridSolver, Method, Model, ModeDecl, ModeGraph,
    ModeId, Observer, Rk4, Rodas4, Sample, StepView, Stepper, StopReason, Switched, SwitchedModel,
    SwitchedNote, SwitchedStop, Termination, Tolerance, TransitionRecord,
};
use model_runtime::{EventId, SolveError, TransitionKind};
use std::ops::ControlFlow;

/// The runtime's mode graph of a compiled switched model.
pub fn mode_graph(model: &CompiledSwitched) -> Result<ModeGraph, ModelFileError> {
    let modes = model
        .modes
        .iter()
        .map(|mode| ModeDecl {
            name: mode.model.name.clone(),
            events: mode
                .events
                .iter()
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
    ModeGraph::new(modes).map_err(|error| ModelFileError::Eval(error.to_string()))
}

/// A switched model run by the interpreter, in [`MAX_STATES`] components.
struct InterpretedSwitched<'a> {
    model: &'a CompiledSwitched,
    params: &'a [f64],
    modes: Vec<Interpreted<'a>>,
    graph: ModeGraph,
}

impl<'a> InterpretedSwitched<'a> {
    fn new(model: &'a CompiledSwitched, params: &'a [f64]) -> Result<Self, ModelFileError> {
        Ok(InterpretedSwitched {
            model,
            params,
            modes: (model.modes.iter())
                .map(|mode| Interpreted::new(&mode.model, params))
                .collect(),
            graph: mode_graph(model)?,
        })
    }

    fn n(&self) -> usize {
        self.model.states().len()
    }

    fn inputs<'b>(&'b self, t: f64, y: &'b [f64], dy: &'b [f64]) -> Inputs<'b> {
        let n = self.n();
        Inputs {
            t,
            states: &y[..n],
            params: self.params,
            ders: &dy[..n],
        }
    }
}

impl SwitchedModel<MAX_STATES> for InterpretedSwitched<'_> {
    fn graph(&self) -> &ModeGraph {
        &self.graph
    }

    fn rhs(
        &self,
        mode: usize,
        t: f64,
        y: &[f64; MAX_STATES],
        dy: &mut [f64; MAX_STATES],
    ) -> Result<(), EvalError> {
        self.modes[mode].rhs(t, y, dy)
    }

    fn jacobian(
        &self,
        mode: usize,
        t: f64,
        y: &[f64; MAX_STATES],
        jac: &mut [[f64; MAX_STATES]; MAX_STATES],
    ) -> Result<(), EvalError> {
        self.modes[mode].jacobian(t, y, jac)
    }

    fn event_values(
        &self,
        mode: usize,
        t: f64,
        y: &[f64; MAX_STATES],
        dy: &[f64; MAX_STATES],
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        let guards = &self.model.modes[mode].guards;
        let stores = (guards.eval(&self.inputs(t, y, dy))).map_err(|e| self.modes[mode].error(e))?;
        values.copy_from_slice(&stores.outputs(values.len()));
        Ok(())
    }

    fn reset(
        &self,
        mode: usize,
        event: usize,
        accumulation: bool,
        t: f64,
        y: &[f64; MAX_STATES],
        dy: &[f64; MAX_STATES],
        out: &mut [f64; MAX_STATES],
    ) -> Result<(), EvalError> {
        let event = &self.model.modes[mode].events[event];
        let jump = match (&event.action, &event.accumulation, accumulation) {
            (_, Some(jump), true) => jump,
            (Action::Jump(jump), _, false) => jump,
            _ => return Ok(()),
        };
        let stores = (jump.program.eval(&self.inputs(t, y, dy)))
            .map_err(|e| self.modes[mode].error(e))?;
        for (&state, value) in jump.states.iter().zip(stores.outputs(jump.states.len())) {
            out[state] = value;
        }
        Ok(())
    }
}

/// Collects the rows (at samples or at step ends) and the transitions of a switched run.
struct Collector {
    every_step: bool,
    points: Vec<(f64, usize, [f64; MAX_STATES])>,
    transitions: Vec<TransitionRecord<MAX_STATES, ModeId, EventId, SwitchedNote>>,
    steps: u64,
}

impl Observer<MAX_STATES, ModeId, EventId, SwitchedNote> for Collector {
    fn on_step(&mut self, step: &StepView<'_, MAX_STATES, ModeId>) {
        self.steps += 1;
        if self.every_step {
            if self.points.last().is_none_or(|(t, ..)| *t < step.t0) {
                self.points.push((step.t0, step.mode.index(), *step.y0));
            }
            self.points.push((step.t1, step.mode.index(), *step.y1));
        }
    }

    fn on_sample(&mut self, sample: &Sample<'_, MAX_STATES, ModeId>) {
        self.points.push((sample.t, sample.mode.index(), *sample.y));
    }

    fn on_transition(&mut self, record: TransitionRecord<MAX_STATES, ModeId, EventId, SwitchedNote>) {
        self.transitions.push(record);
    }

    fn proceed(&mut self) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
}

/// Integrates a switched model from `y0` in its first mode; `settings.events` must be empty
/// (a switched model declares its events in the file).
pub fn solve_switched(
    model: &CompiledSwitched,
    params: &[f64],
    y0: &[f64],
    settings: &SolveSettings,
) -> Result<FileTrajectory, ModelFileError> {
    let n = model.states().len();
    if n > MAX_STATES {
        return Err(ModelFileError::Eval(format!(
            "`{}` has {n} states; `model solve` integrates at most {MAX_STATES} (compile the model with `model!` instead)",
            model.name
        )));
    }
    if let Some(dt) = settings.dt {
        sample_times(settings.t0, settings.t_end, dt)?;
    }
    let interpreted = InterpretedSwitched::new(model, params)?;
    let mut start = [0.0; MAX_STATES];
    start[..n].copy_from_slice(y0);
    let scale = (n as f64 / MAX_STATES as f64).sqrt();
    let tolerance = Tolerance::per_component(
        [settings.rtol * scale; MAX_STATES],
        [settings.atol * scale; MAX_STATES],
    );
    let options = HybridOptions {
        sample_rate: settings.dt.map(|dt| 1.0 / dt),
        ..HybridOptions::default()
    };
    let mut collector = Collector {
        every_step: settings.dt.is_none(),
        points: Vec::new(),
        transitions: Vec::new(),
        steps: 0,
    };
    let outcome = match settings.method {
        Method::Dopri5 => run(Dopri5::new(), &interpreted, tolerance, options, start, settings, &mut collector),
        Method::Dop853 => run(Dop853::new(), &interpreted, tolerance, options, start, settings, &mut collector),
        Method::Rodas4 => run(Rodas4::new(), &interpreted, tolerance, options, start, settings, &mut collector),
        Method::Rk4 { h } => run(Rk4::new(h), &interpreted, tolerance, options, start, settings, &mut collector),
    };
    let graph = &interpreted.graph;
    let (t_end, mode_end, y_end, stop, stats) = match outcome {
        Ok(outcome) => (outcome.t, outcome.mode, outcome.y, outcome.stop, outcome.stats),
        Err(error) => {
            return Err(ModelFileError::Eval(format!(
                "{} (after {} steps and {} transitions)",
                describe_error(graph, &error),
                collector.steps,
                collector.transitions.len()
            )))
        }
    };
    let mode_model = |mode: usize| &model.modes[mode].model;
    let mut rows = Vec::with_capacity(collector.points.len() + 1);
    for (t, mode, y) in &collector.points {
        rows.push(row(mode_model(*mode), params, *t, &y[..n])?);
    }
    if rows.last().is_none_or(|r| r[0] < t_end) {
        rows.push(row(mode_model(mode_end.index()), params, t_end, &y_end[..n])?);
    }
    let mut events = Vec::new();
    for record in &collector.transitions {
        let (name, t, y, mode) = match record.note {
            SwitchedNote::Accumulated { event, accumulation } => (
                format!("{} accumulates", graph.event(event).name),
                accumulation.t_inf,
                record.y_after,
                match record.kind {
                    TransitionKind::Switch { to } => to.index(),
                    _ => record.from.index(),
                },
            ),
            SwitchedNote::Reset(event) | SwitchedNote::Recorded(event) => (
                graph.event(event).name.clone(),
                record.hit.t,
                record.hit.y,
                record.from.index(),
            ),
        };
        events.push(FileEvent {
            name,
            row: row(mode_model(mode), params, t, &y[..n])?,
        });
    }
    let stop = match stop {
        StopReason::EndTime | StopReason::Observer => Termination::EndTime,
        StopReason::User(SwitchedStop::Event { mode, event, t }) => {
            let name = graph.mode(mode).events[event].name.clone();
            events.push(FileEvent {
                name: name.clone(),
                row: row(mode_model(mode.index()), params, t, &y_end[..n])?,
            });
            Termination::Event { name }
        }
        StopReason::User(SwitchedStop::Accumulation { mode, event, t_inf }) => {
            let name = format!("{} accumulates", graph.mode(mode).events[event].name);
            events.push(FileEvent {
                name: name.clone(),
                row: row(mode_model(mode.index()), params, t_inf, &y_end[..n])?,
            });
            Termination::Event { name }
        }
    };
    let mut header = vec!["t".to_string()];
    header.extend(model.states().iter().cloned());
    header.extend(mode_model(0).outputs.iter().cloned());
    Ok(FileTrajectory {
        header,
        rows,
        events,
        stop,
        stats,
    })
}

type Outcome = Result<
    model_runtime::HybridOutcome<MAX_STATES, ModeId, SwitchedStop>,
    HybridError<ModeId>,
>;

fn run<S: Stepper<MAX_STATES>>(
    stepper: S,
    model: &InterpretedSwitched<'_>,
    tolerance: Tolerance<MAX_STATES>,
    options: HybridOptions,
    start: [f64; MAX_STATES],
    settings: &SolveSettings,
    collector: &mut Collector,
) -> Outcome {
    let mut system = match Switched::new(model, AccumulationRule::default()) {
        Ok(system) => system,
        Err(error) => {
            return Err(HybridError::Solve {
                mode: first_mode(model),
                error: SolveError::InvalidInput(error),
            })
        }
    };
    let mut solver = match HybridSolver::new(stepper, tolerance, options) {
        Ok(solver) => solver,
        Err(error) => {
            return Err(HybridError::Solve {
                mode: first_mode(model),
                error: SolveError::InvalidInput(error),
            })
        }
    };
    solver.run(&mut system, first_mode(model), settings.t0, &start, settings.t_end, collector)
}

fn first_mode(model: &InterpretedSwitched<'_>) -> ModeId {
    model.graph.id(0).expect("a switched model has a mode")
}

/// A failed run in the model's words: modes and events by name.
fn describe_error(graph: &ModeGraph, error: &HybridError<ModeId>) -> String {
    match error {
        HybridError::Solve { mode, error } => {
            format!("in mode `{}`: {error}", graph.mode_name(*mode))
        }
        HybridError::Transition { mode, t, source } => format!(
            "at an event of mode `{}` at t = {t}: {source}",
            graph.mode_name(*mode)
        ),
        HybridError::Chattering {
            t,
            transitions,
            window,
            modes,
        } => {
            let names: Vec<String> = modes.iter().map(|m| format!("`{}`", graph.mode_name(*m))).collect();
            format!(
                "chattering at t = {t}: {transitions} transitions within {window:e} between modes {} \
                 (no accumulation rule resolved it: intervals that shrink steadily end in `when EVENT accumulates -> MODE`)",
                names.join(", ")
            )
        }
    }
}
