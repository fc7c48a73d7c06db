//! `eulerdisk model ...`: the dispatch of the model subcommands, with their exit codes.
//!
//! `show` and `eval` take a disk model's name or a DSL file; `solve` takes a file. A mistake
//! in the file, an unknown name in `--state`/`--set`, a malformed `--event` or a state where
//! the model is singular is an input error (exit 2), and so is an unusable setting of `solve`
//! (an empty time span, a sampling step or tolerance that is not positive, too many states);
//! a failed integration or an unwritable output is a failure (exit 1), and a run that a
//! `:stop` event ended before `--t-end` exits with 3, as a scene stopped by its physics does.

use crate::args::{backend, print_json, print_out, EXIT_FAILED, EXIT_INPUT, EXIT_STOPPED};
use crate::cli::{ModelCommand, ModelEvalArgs, ModelPointArgs, ModelSolveArgs};
use crate::eval::{evaluate_model, parse_model_state, parse_params};
use crate::model_file::{
    evaluate, initial_state, load, load_any, params, select, state, Loaded, ModelFileError,
};
use crate::model_show::{Format, ModelName};
use crate::model_solve::{solve, EventSpec, FileTrajectory, SolveSettings};
use crate::model_switched::solve_switched;
use clap::ValueEnum;
use model_algebra::CompiledModel;
use model_dsl::TextModel;
use model_runtime::Termination;
use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

/// Runs one model subcommand.
pub fn run(command: &ModelCommand) -> ExitCode {
    match command {
        ModelCommand::Show { model, format } => show(model, *format),
        ModelCommand::Eval(args) => eval(args),
        ModelCommand::Solve(args) => solve_file(args),
    }
}

fn input_error(error: impl std::fmt::Display) -> ExitCode {
    eprintln!("error: {error}");
    ExitCode::from(EXIT_INPUT)
}

fn show(model: &str, format: Format) -> ExitCode {
    if let Ok(name) = ModelName::from_str(model, true) {
        return match crate::model_show::show(name, format) {
            Ok(text) => match print_out(&text) {
                Ok(()) => ExitCode::SUCCESS,
                Err(code) => code,
            },
            Err(err) => {
                eprintln!("error: {err}");
                ExitCode::from(EXIT_FAILED)
            }
        };
    }
    let path = Path::new(model);
    if !path.exists() {
        return input_error(format_args!(
            "`{model}` is neither a model of the disk (rolling, sliding, sliding-cartesian) nor a DSL file"
        ));
    }
    match crate::model_file::show(path, format) {
        Ok(text) => match print_out(&text) {
            Ok(()) => ExitCode::SUCCESS,
            Err(code) => code,
        },
        Err(err) => input_error(err),
    }
}

/// The selected model of the file, with its parameters and state.
struct Point {
    models: Vec<TextModel>,
    params: Vec<f64>,
    state: Vec<f64>,
}

impl Point {
    fn read(args: &ModelPointArgs) -> Result<Self, ModelFileError> {
        let models = load(Path::new(&args.model))?;
        let model = select(&models, args.chart.as_deref())?;
        let params = params(model, &args.set)?;
        let state = state(model, &args.state)?;
        Ok(Point {
            models,
            params,
            state,
        })
    }

    fn model(&self, args: &ModelPointArgs) -> Result<&CompiledModel, ModelFileError> {
        select(&self.models, args.chart.as_deref())
    }
}

fn eval(args: &ModelEvalArgs) -> ExitCode {
    if let Ok(name) = ModelName::from_str(&args.point.model, true) {
        return eval_disk(name, args);
    }
    if args.reference {
        return input_error(format_args!(
            "--reference: `{}` is not a model of the disk (rolling, sliding); a file has no hand-written reference",
            args.point.model
        ));
    }
    let result = Point::read(&args.point).and_then(|point| {
        let model = point.model(&args.point)?;
        evaluate(model, args.t, &point.state, &point.params)
    });
    match result {
        Ok(evaluation) => print_json(&evaluation),
        Err(err) => input_error(err),
    }
}

/// `model eval rolling|sliding|sliding-cartesian`: the compiled disk model (or with
/// `--reference` the hand-written one) at the state, the parameters the paper's unless set.
fn eval_disk(name: ModelName, args: &ModelEvalArgs) -> ExitCode {
    if let Some(chart) = &args.point.chart {
        return input_error(format_args!(
            "--chart {chart}: the disk's charts are models of their own here (`sliding-cartesian`)"
        ));
    }
    let point = &args.point;
    let result = parse_params("--set", &point.set).and_then(|params| {
        let y = parse_model_state(name, &point.state)?;
        evaluate_model(backend(args.reference), name, &params, args.t, &y)
    });
    match result {
        Ok(evaluation) => print_json(&evaluation),
        Err(err) => input_error(err),
    }
}

fn solve_file(args: &ModelSolveArgs) -> ExitCode {
    if args.method.is_some() {
        eprintln!("note: `--method` is deprecated: write `--integrator`");
    }
    if ModelName::from_str(&args.point.model, true).is_ok()
        && !Path::new(&args.point.model).exists()
    {
        return input_error(format_args!(
            "`model solve` takes a DSL file; to simulate the disk's `{}` model, run a scene (`eulerdisk run`, `[modes] allowed`)",
            args.point.model
        ));
    }
    let settings = |events| SolveSettings {
        t0: args.t0,
        t_end: args.t_end,
        method: args.integrator().into(),
        rtol: args.rtol,
        atol: args.atol,
        dt: args.dt,
        events,
    };
    let switched = match load_any(Path::new(&args.point.model)) {
        Ok(Loaded::Switched(model)) => Some(model),
        Ok(Loaded::Smooth(_)) => None,
        Err(err) => return input_error(err),
    };
    let (name, solved) = if let Some(model) = switched {
        let input = (|| {
            if let Some(chart) = &args.point.chart {
                return Err(ModelFileError::Eval(format!(
                    "--chart {chart}: a switched model has no charts"
                )));
            }
            if let Some(event) = args.event.first() {
                return Err(ModelFileError::Eval(format!(
                    "--event {event}: a switched model declares its events in the file (`when NAME: GUARD`)"
                )));
            }
            let params = params(&model.modes[0].model, &args.point.set)?;
            let state = initial_state(&model, &args.point.state)?;
            Ok((params, state))
        })();
        let (params, state) = match input {
            Ok(input) => input,
            Err(err) => return input_error(err),
        };
        let solved = solve_switched(&model, &params, &state, &settings(Vec::new()));
        (model.name.clone(), solved)
    } else {
        let point = match Point::read(&args.point) {
            Ok(point) => point,
            Err(err) => return input_error(err),
        };
        let model = match point.model(&args.point) {
            Ok(model) => model,
            Err(err) => return input_error(err),
        };
        let events = match (args.event.iter())
            .map(|text| EventSpec::parse(text, model))
            .collect::<Result<Vec<_>, _>>()
        {
            Ok(events) => events,
            Err(err) => return input_error(err),
        };
        let solved = solve(model, &point.params, &point.state, &settings(events));
        (model.name.clone(), solved)
    };
    let trajectory = match solved {
        Ok(trajectory) => trajectory,
        Err(err @ ModelFileError::Setting(_)) => return input_error(err),
        Err(err) => {
            eprintln!("error: {err}");
            return ExitCode::from(EXIT_FAILED);
        }
    };
    let mut written = write_to(&args.out, |out| trajectory.write_csv(out));
    match &args.events {
        Some(path) if written.is_ok() => {
            written = write_to(path, |out| trajectory.write_events_csv(out));
        }
        Some(_) => {}
        None => {
            for event in &trajectory.events {
                eprintln!("event `{}` at t = {}", event.name, event.t());
            }
        }
    }
    if let Err(err) = written {
        eprintln!("error: {err}");
        return ExitCode::from(EXIT_FAILED);
    }
    for note in &trajectory.notes {
        eprintln!("{note}");
    }
    eprintln!("{}", summary(&name, &trajectory, args.t0));
    match trajectory.stop {
        Termination::EndTime => ExitCode::SUCCESS,
        Termination::Event { .. } => ExitCode::from(EXIT_STOPPED),
    }
}

/// Writes with `write` to the file `path` (`-`: standard output); an error names the path.
fn write_to(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), String> {
    let written = if path.as_os_str() == "-" {
        let mut lock = std::io::stdout().lock();
        write(&mut lock).and_then(|()| lock.flush())
    } else {
        std::fs::File::create(path)
            .map(std::io::BufWriter::new)
            .and_then(|mut file| write(&mut file).and_then(|()| file.flush()))
    };
    written.map_err(|err| format!("cannot write {}: {err}", path.display()))
}

/// One line on the run: rows, events, why and when it ended, the work done.
fn summary(name: &str, trajectory: &FileTrajectory, t0: f64) -> String {
    let stats = &trajectory.stats;
    let stop = match &trajectory.stop {
        Termination::EndTime => "reached the end time".to_string(),
        Termination::Event { name } => format!("stopped by event `{name}`"),
    };
    format!(
        "`{name}`: {} rows, {} events, {stop} at t = {}, {} steps ({} rejected), {} RHS evaluations",
        trajectory.rows.len(),
        trajectory.events.len(),
        trajectory.rows.last().map_or(t0, |row| row[0]),
        stats.steps,
        stats.rejected,
        stats.rhs_evals
    )
}
