//! `eulerdisk model solve FILE.dsl`: a model read from a file, integrated by the runtime's
//! `Problem` API with its programs run by the compiler's interpreter, into a CSV.
//!
//! The runtime's models have a state dimension fixed at compile time; a file's model has its
//! own. Rather than instantiating the integrators once per dimension, the interpreted model is
//! embedded in [`MAX_STATES`] components: the components past the model's states have zero
//! derivatives and stay zero. The error norm is a root mean square over all components, so
//! each component's tolerances are scaled by `sqrt(n / MAX_STATES)`, which makes the norm, and
//! with it every step-size decision, exactly that of the model's `n` states alone.
//!
//! Events (`--event NAME[:up|:down][:stop]`) are zero crossings of one of the model's states
//! or outputs. A threshold other than zero is an output of the file (`hit = theta - 0.1`), so
//! the command needs no expression language of its own; an output needs the derivatives,
//! which the runtime hands every event function, and is evaluated by the interpreter there.

use crate::model_file::{describe, ModelFileError};
use model_algebra::{CompiledModel, EvalFailure, Inputs, Ops};
use model_runtime::{
    Direction, EvalError, Event, LocatedEvent, Method, Model, ModelInfo, OpCounts, Output, Problem,
    SolveError, SolveFailure, Stats, Termination, Tolerance, WithOutputs,
};
use std::io::Write;
use std::sync::Arc;

/// The most states a model file may have for `model solve`.
pub const MAX_STATES: usize = 32;

/// How to integrate.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveSettings {
    /// Start time.
    pub t0: f64,
    /// End time.
    pub t_end: f64,
    /// The integration method.
    pub method: Method,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Record every `dt` from `t0` (and at `t_end`); `None`: at every accepted step.
    pub dt: Option<f64>,
    /// The events to locate, in the order given (the first wins a tie).
    pub events: Vec<EventSpec>,
}

/// What an event watches: one of the model's states or outputs, by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Watched {
    /// The state at this index of `CompiledModel::states`.
    State(usize),
    /// The output at this index of `CompiledModel::outputs`.
    Output(usize),
}

/// One `--event NAME[:up|:down][:stop]`, resolved against a model.
#[derive(Clone, Debug, PartialEq)]
pub struct EventSpec {
    /// The state's or output's name (the event's name).
    pub name: String,
    /// What crosses zero.
    pub watched: Watched,
    /// Which crossings fire (both by default).
    pub direction: Direction,
    /// Whether the run ends at the first one.
    pub stop: bool,
}

/// The form of `--event`, said in every error about it.
const EVENT_FORM: &str = "expected NAME[:up|:down][:stop]";

impl EventSpec {
    /// Reads `NAME[:up|:down][:stop]` for `model`; an empty spec, an unknown word, a word
    /// given twice or a name that is neither a state nor an output of the model is an
    /// [`ModelFileError::Assignment`] naming the flag, the spec and the problem.
    pub fn parse(text: &str, model: &CompiledModel) -> Result<Self, ModelFileError> {
        let problem = |problem: String| ModelFileError::Assignment {
            flag: "--event",
            text: text.to_string(),
            problem,
        };
        let mut words = text.split(':').map(str::trim);
        let name = words.next().unwrap_or_default();
        if name.is_empty() {
            return Err(problem(format!("the name is empty; {EVENT_FORM}")));
        }
        let watched = watched(model, name).ok_or_else(|| {
            problem(format!(
                "the model has no state or output `{name}`; the states are {}; the outputs are {}",
                quoted(&model.states),
                quoted(&model.outputs)
            ))
        })?;
        let (mut direction, mut stop) = (None, false);
        for word in words {
            let twice = match word {
                "up" => direction.replace(Direction::Up).is_some(),
                "down" => direction.replace(Direction::Down).is_some(),
                "stop" => std::mem::replace(&mut stop, true),
                _ => {
                    return Err(problem(format!(
                        "`{word}` is neither a direction (`up`, `down`) nor `stop`; {EVENT_FORM}"
                    )))
                }
            };
            if twice {
                return Err(problem(format!(
                    "`{word}` comes after another direction or twice; {EVENT_FORM}"
                )));
            }
        }
        Ok(EventSpec {
            name: name.to_string(),
            watched,
            direction: direction.unwrap_or(Direction::Both),
            stop,
        })
    }

    /// The runtime's event: the state read from `y`, or the output evaluated at `(t, y, dy)`
    /// by the interpreter (NaN where it cannot be, which the runtime reports naming the
    /// event).
    fn event(&self, shared: &Arc<Shared>) -> Event<MAX_STATES> {
        let event = match self.watched {
            Watched::State(k) => Event::new(&self.name, move |_t, y, _dy| y[k]),
            Watched::Output(j) => {
                let shared = Arc::clone(shared);
                Event::new(&self.name, move |t, y, dy| {
                    let n = shared.model.states.len();
                    (shared
                        .model
                        .outputs_at(t, &y[..n], &dy[..n], &shared.params))
                    .map_or(f64::NAN, |outputs| outputs[j])
                })
            }
        };
        let event = event.direction(self.direction);
        if self.stop {
            event.terminal()
        } else {
            event
        }
    }
}

/// The state or output called `name`.
fn watched(model: &CompiledModel, name: &str) -> Option<Watched> {
    let position = |names: &[String]| names.iter().position(|n| n == name);
    (position(&model.states).map(Watched::State))
        .or_else(|| position(&model.outputs).map(Watched::Output))
}

/// `` `a`, `b` `` (or `none`).
fn quoted(names: &[String]) -> String {
    if names.is_empty() {
        return "none".to_string();
    }
    let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    quoted.join(", ")
}

/// The model and its parameters, owned, for the event functions (which must be `'static`).
struct Shared {
    model: CompiledModel,
    params: Vec<f64>,
}

/// A located event: its name, time, and the states and outputs there.
#[derive(Clone, Debug, PartialEq)]
pub struct FileEvent {
    /// The event's name (the state or output that crossed zero).
    pub name: String,
    /// `t`, the states and the outputs at the event, as a trajectory row.
    pub row: Vec<f64>,
}

impl FileEvent {
    /// The event time.
    pub fn t(&self) -> f64 {
        self.row[0]
    }
}

/// A trajectory of a file's model: a table of `t`, the states and the outputs.
#[derive(Clone, Debug)]
pub struct FileTrajectory {
    /// Column names: `t`, the states, the outputs.
    pub header: Vec<String>,
    /// One row per recorded time; after a terminal event the last row is the event's.
    pub rows: Vec<Vec<f64>>,
    /// The located events, in time order.
    pub events: Vec<FileEvent>,
    /// Why the run ended.
    pub stop: Termination,
    /// The work done.
    pub stats: Stats,
    /// What the run said beside its rows and events (an accumulation and where the run went
    /// on), one sentence each, for the terminal.
    pub notes: Vec<String>,
}

impl FileTrajectory {
    /// Writes the table as CSV, numbers in Rust's shortest round-trip form.
    pub fn write_csv(&self, mut out: impl Write) -> std::io::Result<()> {
        writeln!(out, "{}", self.header.join(","))?;
        for row in &self.rows {
            write_row(&mut out, None, row)?;
        }
        Ok(())
    }

    /// Writes the located events as CSV: `event,t`, the states and the outputs.
    pub fn write_events_csv(&self, mut out: impl Write) -> std::io::Result<()> {
        writeln!(out, "event,{}", self.header.join(","))?;
        for event in &self.events {
            write_row(&mut out, Some(&event.name), &event.row)?;
        }
        Ok(())
    }
}

/// One CSV line: the label (if any), then the numbers in Rust's shortest round-trip form.
fn write_row(out: &mut impl Write, label: Option<&str>, row: &[f64]) -> std::io::Result<()> {
    let numbers = row.iter().map(f64::to_string);
    let cells: Vec<String> = label
        .map(str::to_string)
        .into_iter()
        .chain(numbers)
        .collect();
    writeln!(out, "{}", cells.join(","))
}

/// Integrates `model` from `y0` with `params`; the outputs are evaluated at every recorded
/// point. Errors name the state, the pivot or the time, as the runtime does for compiled
/// models.
pub fn solve(
    model: &CompiledModel,
    params: &[f64],
    y0: &[f64],
    settings: &SolveSettings,
) -> Result<FileTrajectory, ModelFileError> {
    let n = model.states.len();
    if n > MAX_STATES {
        return Err(ModelFileError::Setting(format!(
            "`{}` has {n} states; `model solve` integrates at most {MAX_STATES} (compile the model with `model!` instead)",
            model.name
        )));
    }
    let interpreted = Interpreted::new(model, params);
    let mut start = [0.0; MAX_STATES];
    start[..n].copy_from_slice(y0);
    let scale = (n as f64 / MAX_STATES as f64).sqrt();
    let tolerance = Tolerance::per_component(
        [settings.rtol * scale; MAX_STATES],
        [settings.atol * scale; MAX_STATES],
    );
    let output = match settings.dt {
        Some(dt) => Output::Times(sample_times(settings.t0, settings.t_end, dt)?),
        None => Output::Steps,
    };
    let mut problem = Problem::new(&interpreted, start, (settings.t0, settings.t_end))
        .method(settings.method)
        .tolerance(tolerance)
        .output(output);
    if !settings.events.is_empty() {
        let shared = Arc::new(Shared {
            model: model.clone(),
            params: params.to_vec(),
        });
        for spec in &settings.events {
            problem = problem.event(spec.event(&shared));
        }
    }
    let solved = problem.solve::<0>().map_err(|failure| match failure {
        // Unusable settings (a time span, a tolerance) are the caller's input, not a failed run.
        SolveFailure::Solve {
            error: SolveError::InvalidInput(_),
            ..
        }
        | SolveFailure::OutputTime { .. } => ModelFileError::Setting(failure.to_string()),
        failure => ModelFileError::Eval(failure.to_string()),
    })?;
    let mut header = vec!["t".to_string()];
    header.extend(model.states.iter().cloned());
    header.extend(model.outputs.iter().cloned());
    let mut rows = Vec::with_capacity(solved.t.len() + 1);
    for (&t, y) in solved.t.iter().zip(&solved.y) {
        rows.push(row(model, params, t, &y[..n])?);
    }
    let events = (solved.events.iter())
        .map(|event| event_row(model, params, event))
        .collect::<Result<Vec<_>, _>>()?;
    if let (Termination::Event { .. }, Some(last)) = (&solved.stop, events.last()) {
        // The run ended at the event: its state closes the trajectory.
        if rows.last().is_none_or(|row| row[0] < last.t()) {
            rows.push(last.row.clone());
        }
    }
    Ok(FileTrajectory {
        header,
        rows,
        events,
        stop: solved.stop,
        stats: solved.stats,
        notes: Vec::new(),
    })
}

/// `t`, the states and the outputs at `(t, y)`.
pub(crate) fn row(
    model: &CompiledModel,
    params: &[f64],
    t: f64,
    y: &[f64],
) -> Result<Vec<f64>, ModelFileError> {
    let at_t =
        |e: EvalFailure| ModelFileError::Eval(format!("at t = {t}: {}", describe(model, &e)));
    let der = model.derivatives(t, y, params).map_err(at_t)?;
    let outputs = model.outputs_at(t, y, &der, params).map_err(at_t)?;
    let mut row = vec![t];
    row.extend_from_slice(y);
    row.extend(outputs);
    Ok(row)
}

/// A located event as a trajectory row, under its name.
fn event_row(
    model: &CompiledModel,
    params: &[f64],
    event: &LocatedEvent<MAX_STATES>,
) -> Result<FileEvent, ModelFileError> {
    let n = model.states.len();
    Ok(FileEvent {
        name: event.name.clone(),
        row: row(model, params, event.t, &event.y[..n])?,
    })
}

/// `t0, t0 + dt, ...` up to and including `t_end`.
pub(crate) fn sample_times(t0: f64, t_end: f64, dt: f64) -> Result<Vec<f64>, ModelFileError> {
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(ModelFileError::Setting(format!(
            "--dt {dt}: the sampling step must be positive and finite"
        )));
    }
    let count = ((t_end - t0) / dt).floor();
    if !(0.0..1e8).contains(&count) {
        return Err(ModelFileError::Setting(format!(
            "--dt {dt} from {t0} to {t_end}: gives no samples or too many (at most 1e8)"
        )));
    }
    let mut times: Vec<f64> = (0..=count as u64).map(|k| t0 + k as f64 * dt).collect();
    if times.last().is_some_and(|&t| t < t_end) {
        times.push(t_end);
    }
    Ok(times)
}

/// A compiled model run by the interpreter, in [`MAX_STATES`] components.
pub(crate) struct Interpreted<'a> {
    model: &'a CompiledModel,
    params: &'a [f64],
    /// The runtime's names for the model: leaked once per command, as a compiled model's are
    /// `static`.
    info: &'static ModelInfo,
    /// `der(x)` for each state, for `NonFinite` errors.
    der_names: &'static [&'static str],
    /// The pivots and numeric blocks, for `SingularPivot` errors.
    pivots: &'static [&'static str],
}

fn leak(text: String) -> &'static str {
    Box::leak(text.into_boxed_str())
}

fn leak_all(texts: impl Iterator<Item = String>) -> &'static [&'static str] {
    Box::leak(texts.map(leak).collect::<Vec<_>>().into_boxed_slice())
}

fn op_counts(ops: Ops) -> OpCounts {
    OpCounts {
        add: ops.add,
        mul: ops.mul,
        div: ops.div,
        sqrt: ops.sqrt,
        trig: ops.trig,
        transcendental: ops.transcendental,
    }
}

impl<'a> Interpreted<'a> {
    pub(crate) fn new(model: &'a CompiledModel, params: &'a [f64]) -> Self {
        let n = model.states.len();
        let padding = (n..MAX_STATES).map(|k| format!("(unused {k})"));
        let pivots = leak_all(model.pivots.iter().chain(&model.numeric_blocks).cloned());
        let info = Box::leak(Box::new(ModelInfo {
            name: leak(model.name.clone()),
            state_names: leak_all(model.states.iter().cloned().chain(padding)),
            param_names: leak_all(model.params.iter().map(|(name, _)| name.clone())),
            output_names: &[],
            rhs_ops: op_counts(model.rhs.ops()),
            jacobian_ops: op_counts(model.jacobian.ops()),
            outputs_ops: op_counts(model.outputs_program.ops()),
            pivots,
            numeric_blocks: &[],
        }));
        Interpreted {
            model,
            params,
            info,
            der_names: leak_all(model.states.iter().map(|s| format!("der({s})"))),
            pivots,
        }
    }

    pub(crate) fn error(&self, failure: EvalFailure) -> EvalError {
        match failure {
            EvalFailure::SingularPivot { text, value } => EvalError::SingularPivot {
                model: self.info.name,
                pivot: (self.pivots.iter().find(|p| **p == text).copied())
                    .unwrap_or_else(|| leak(text)),
                value,
            },
            EvalFailure::BadOperand(operand) => EvalError::NonFinite {
                model: self.info.name,
                quantity: leak(format!("{operand:?} (a compiler bug)")),
                value: f64::NAN,
            },
        }
    }
}

impl Model<MAX_STATES> for Interpreted<'_> {
    fn info(&self) -> &'static ModelInfo {
        self.info
    }

    fn rhs(
        &self,
        t: f64,
        y: &[f64; MAX_STATES],
        dy: &mut [f64; MAX_STATES],
    ) -> Result<(), EvalError> {
        let n = self.model.states.len();
        let der = (self.model.derivatives(t, &y[..n], self.params)).map_err(|e| self.error(e))?;
        if let Some(k) = der.iter().position(|v| !v.is_finite()) {
            return Err(EvalError::NonFinite {
                model: self.info.name,
                quantity: self.der_names[k],
                value: der[k],
            });
        }
        dy[..n].copy_from_slice(&der);
        dy[n..].fill(0.0);
        Ok(())
    }

    fn jacobian(
        &self,
        t: f64,
        y: &[f64; MAX_STATES],
        jac: &mut [[f64; MAX_STATES]; MAX_STATES],
    ) -> Result<(), EvalError> {
        let n = self.model.states.len();
        let inputs = Inputs {
            t,
            states: &y[..n],
            params: self.params,
            ders: &[],
        };
        let stores = self
            .model
            .jacobian
            .eval(&inputs)
            .map_err(|e| self.error(e))?;
        *jac = [[0.0; MAX_STATES]; MAX_STATES];
        for (row, values) in jac.iter_mut().zip(stores.jacobian(n)) {
            row[..n].copy_from_slice(&values);
        }
        Ok(())
    }
}

impl WithOutputs<MAX_STATES, 0> for Interpreted<'_> {
    fn outputs(
        &self,
        _t: f64,
        _y: &[f64; MAX_STATES],
        _dy: &[f64; MAX_STATES],
        _out: &mut [f64; 0],
    ) -> Result<(), EvalError> {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use equations::models::rolling;
    use equations::DiskParams;
    use equations::InitialState;
    use model_dsl::Source;

    /// The rolling disk from its own source file, interpreted and embedded, against the same
    /// model compiled by `model!`: the same steps (the scaled tolerances make the error norm
    /// the model's own) and the same trajectory.
    #[test]
    fn the_embedded_interpreted_model_steps_like_the_compiled_one() {
        let file = include_str!("../equations/src/models/box1_rolling.rs");
        let models = Source::rust("box1_rolling.rs", file).compile().unwrap();
        let interpreted = &models[0].compiled;
        let p = DiskParams::paper();
        let y0 = InitialState::paper(&p).state.y;
        let params = p.to_array();
        for method in [Method::Dopri5, Method::Dop853, Method::Rodas4] {
            let settings = SolveSettings {
                t0: 0.0,
                t_end: 0.3,
                method,
                rtol: 1e-9,
                atol: 1e-11,
                dt: None,
                events: Vec::new(),
            };
            let file = solve(interpreted, &params, &y0, &settings).unwrap();
            let model = rolling::Model::new(params);
            let compiled = Problem::new(&model, y0, (0.0, 0.3))
                .method(method)
                .tolerances(1e-9, 1e-11)
                .solve::<{ rolling::N_OUTPUTS }>()
                .unwrap();
            assert_eq!(file.stats.steps, compiled.stats.steps, "{method:?}");
            assert_eq!(file.stats.rejected, compiled.stats.rejected, "{method:?}");
            let last = file.rows.last().unwrap();
            let want = compiled.last().unwrap();
            for (k, (got, want)) in last[1..=12].iter().zip(want).enumerate() {
                assert!(
                    (got - want).abs() <= 1e-9 * want.abs().max(1.0),
                    "{method:?} {}: {got} vs {want}",
                    rolling::STATE_NAMES[k]
                );
            }
            assert_eq!(file.header.len(), 1 + 12 + rolling::N_OUTPUTS);
        }
    }

    fn oscillator() -> CompiledModel {
        let text = "mod oscillator {
            params { w = 3 }
            states { x, v }
            equations { der(x) = v; der(v) = -w^2 * x; }
            outputs { speed = v; position = x; }
        }";
        let models = Source::new("oscillator.dsl", text).compile().unwrap();
        models[0].compiled.clone()
    }

    #[test]
    fn an_event_spec_names_a_state_or_an_output_a_direction_and_a_stop() {
        let model = oscillator();
        let spec = |text| EventSpec::parse(text, &model).unwrap();
        let x = spec("x");
        assert_eq!(x.watched, Watched::State(0));
        assert_eq!((x.direction, x.stop), (Direction::Both, false));
        let position = spec("position:down:stop");
        assert_eq!(position.watched, Watched::Output(1));
        assert_eq!((position.direction, position.stop), (Direction::Down, true));
        let v = spec(" v : stop : up ");
        assert_eq!((v.name.as_str(), v.watched), ("v", Watched::State(1)));
        assert_eq!((v.direction, v.stop), (Direction::Up, true));
        for bad in ["", "w", "x:", "x:left", "x:down:up", "speed:stop:stop"] {
            let err = EventSpec::parse(bad, &model).unwrap_err();
            assert!(
                matches!(&err, ModelFileError::Assignment { flag: "--event", text, .. } if text == bad),
                "{bad:?}: {err}"
            );
        }
    }

    /// An output equal to a state crosses zero where the state does: the output's event,
    /// evaluated by the interpreter from `(t, y, dy)`, is located at the same times (to the
    /// root finder's few ulps), and both at the analytic zeros of `cos(3 t)`.
    #[test]
    fn an_event_on_an_output_is_located_where_the_equal_state_crosses() {
        let model = oscillator();
        let settings = |event: &str| SolveSettings {
            t0: 0.0,
            t_end: 4.0,
            method: Method::Dop853,
            rtol: 1e-12,
            atol: 1e-14,
            dt: None,
            events: vec![EventSpec::parse(event, &model).unwrap()],
        };
        let times = |event: &str| -> Vec<f64> {
            let solved = solve(&model, &[3.0], &[1.0, 0.0], &settings(event)).unwrap();
            assert!(solved.events.iter().all(|e| e.name == event));
            solved.events.iter().map(FileEvent::t).collect()
        };
        let (state, output) = (times("x"), times("position"));
        assert_eq!(state.len(), 4, "{state:?}");
        assert_eq!(state.len(), output.len());
        for (k, (a, b)) in state.iter().zip(&output).enumerate() {
            let want = (k as f64 + 0.5) * std::f64::consts::PI / 3.0;
            assert!((a - b).abs() < 1e-13, "{a} vs {b}");
            assert!((a - want).abs() < 1e-9, "{a} vs {want}");
        }
    }
}
