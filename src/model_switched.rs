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
use crate::model_solve::{
    row, sample_times, FileEvent, FileTrajectory, Interpreted, SolveSettings, MAX_STATES,
};
use model_algebra::Inputs;
use model_dsl::{Action, CompiledSwitched, Crossing};
use model_runtime::{
    run_switched, AccumulationAction, Direction, Dop853, Dopri5, EvalError, EventAction, EventDecl,
    Fired, HybridError, HybridOptions, Method, ModeDecl, ModeGraph, Model, Rk4, Rodas4,
    SwitchedModel, SwitchedRun, Termination, Tolerance,
};

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
        let stores =
            (guards.eval(&self.inputs(t, y, dy))).map_err(|e| self.modes[mode].error(e))?;
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
        let stores =
            (jump.program.eval(&self.inputs(t, y, dy))).map_err(|e| self.modes[mode].error(e))?;
        for (&state, value) in jump.states.iter().zip(stores.outputs(jump.states.len())) {
            out[state] = value;
        }
        Ok(())
    }
}

/// Integrates a switched model from `y0` in its first mode; `settings.events` must be empty
/// (a switched model declares its events in the file). The trajectory's rows are those of the
/// mode in force; the events are every event the run met, an accumulation under `NAME
/// accumulates` at its extrapolated point, and a terminal event last.
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
    let start = (settings.t0, start);
    let t_end = settings.t_end;
    let run = match settings.method {
        Method::Dopri5 => run_switched(
            &interpreted,
            Dopri5::new(),
            tolerance,
            options,
            start,
            t_end,
        ),
        Method::Dop853 => run_switched(
            &interpreted,
            Dop853::new(),
            tolerance,
            options,
            start,
            t_end,
        ),
        Method::Rodas4 => run_switched(
            &interpreted,
            Rodas4::new(),
            tolerance,
            options,
            start,
            t_end,
        ),
        Method::Rk4 { h } => {
            run_switched(&interpreted, Rk4::new(h), tolerance, options, start, t_end)
        }
    }
    .map_err(|failure| {
        ModelFileError::Eval(format!(
            "{} (after {} steps and {} events)",
            describe_error(&failure.error),
            failure.steps,
            failure.events.len()
        ))
    })?;
    let mode_model = |name: &str| &model.modes[model.mode(name).unwrap_or(0)].model;
    let mut rows = Vec::with_capacity(run.samples.len() + 1);
    for (t, mode, y) in &run.samples {
        rows.push(row(mode_model(mode), params, *t, &y[..n])?);
    }
    if rows.last().is_none_or(|r| r[0] < run.t) {
        rows.push(row(mode_model(&run.mode), params, run.t, &run.y[..n])?);
    }
    let mut events = Vec::with_capacity(run.events.len());
    let mut notes = Vec::new();
    for (k, event) in run.events.iter().enumerate() {
        let accumulated = matches!(event.fired, Fired::Accumulated | Fired::AccumulatedStop);
        let (name, y, mode) = if accumulated {
            let name = format!("{} accumulates", event.event);
            let continued = match event.fired {
                Fired::Accumulated => format!("the run goes on in `{}`", mode_after(&run, k)),
                _ => format!(
                    "the run stops there (`when {} accumulates -> MODE {{ .. }}` says where it goes on)",
                    event.event
                ),
            };
            notes.push(format!(
                "the firings of `{}` accumulate at t = {}: {continued}",
                event.event, event.t
            ));
            (name, &event.y_after, mode_after(&run, k))
        } else {
            (event.event.clone(), &event.y, event.mode.as_str())
        };
        events.push(FileEvent {
            name,
            row: row(mode_model(mode), params, event.t, &y[..n])?,
        });
    }
    let stop = match &run.stopped_by {
        None => Termination::EndTime,
        Some(name) => Termination::Event {
            name: match run.events.last().map(|e| e.fired) {
                Some(Fired::AccumulatedStop) => format!("{name} accumulates"),
                _ => name.clone(),
            },
        },
    };
    let mut header = vec!["t".to_string()];
    header.extend(model.states().iter().cloned());
    header.extend(model.modes[0].model.outputs.iter().cloned());
    Ok(FileTrajectory {
        header,
        rows,
        events,
        stop,
        stats: run.stats,
        notes,
    })
}

/// The mode the run continued in after its `k`-th event (its own, for an event that ended
/// the run).
fn mode_after(run: &SwitchedRun<MAX_STATES>, k: usize) -> &str {
    let event = &run.events[k];
    match run.events.get(k + 1) {
        Some(next) => next.mode.as_str(),
        None if event.fired == Fired::Accumulated => run.mode.as_str(),
        None => event.mode.as_str(),
    }
}

/// A failed run in the model's words: modes by name, and what resolves a chatter.
fn describe_error(error: &HybridError<String>) -> String {
    match error {
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
    }
}
