//! `eulerdisk model ...`: the dispatch of the model subcommands, with their exit codes.
//!
//! `show` and `eval` take a disk model's name or a DSL file; `solve` takes a file. A mistake
//! in the file, an unknown name in `--state`/`--set`, a malformed `--event` or a state where
//! the model is singular is an input error (exit 2), and so is an unusable setting of `solve`
//! (an empty time span, a sampling step or tolerance that is not positive);
//! a failed integration or an unwritable output is a failure (exit 1), and a run that a
//! `:stop` event ended before `--t-end` exits with 3, as a scene stopped by its physics does.

use crate::args::{backend, print_json, print_out, EXIT_FAILED, EXIT_INPUT, EXIT_STOPPED};
use crate::cli::{ModelCommand, ModelEvalArgs, ModelPointArgs, ModelSolveArgs};
use crate::eval::{evaluate_model, parse_model_state, parse_params};
use crate::model_csv::{write_csv, write_events_csv};
use crate::model_file::{event_spec, named, value_error, Arguments, ModelFileError};
use crate::model_show::{Format, ModelName};
use clap::ValueEnum;
use model_interpreted::{
    evaluate, initial_state, params, solve, ModelRef, PointValues, Solution, SolveRequest, Stop,
};
use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

/// Runs one model subcommand.
pub fn run(command: &ModelCommand) -> ExitCode {
    match command {
        ModelCommand::Show {
            model,
            format,
            no_cache,
        } => show(model, *format, *no_cache),
        ModelCommand::Eval(args) => eval(args),
        ModelCommand::Solve(args) => solve_file(args),
    }
}

fn input_error(error: impl std::fmt::Display) -> ExitCode {
    eprintln!("error: {error}");
    ExitCode::from(EXIT_INPUT)
}

fn show(model: &str, format: Format, no_cache: bool) -> ExitCode {
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
    match crate::model_file::show(path, format, no_cache) {
        Ok(text) => match print_out(&text) {
            Ok(()) => ExitCode::SUCCESS,
            Err(code) => code,
        },
        Err(err) => input_error(err),
    }
}

/// `model eval`: the derivatives and outputs at the point the arguments give.
fn point(args: &ModelEvalArgs) -> Result<PointValues, ModelFileError> {
    let point = &args.point;
    let file = crate::model_file::read(Path::new(&point.model), point.no_cache)?;
    let model = file.smooth(point.chart.as_deref())?;
    let params = params(ModelRef::Smooth(model), &named("--set", &point.set)?)
        .map_err(|e| value_error("--set", &point.set, e))?;
    let state = initial_state(ModelRef::Smooth(model), &named("--state", &point.state)?)
        .map_err(|e| value_error("--state", &point.state, e))?;
    Ok(evaluate(model, args.t, &state, &params)?)
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
    match point(args) {
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

/// The library's request from `model solve`'s arguments.
fn request(args: &ModelSolveArgs) -> Result<SolveRequest, ModelFileError> {
    let point: &ModelPointArgs = &args.point;
    Ok(SolveRequest {
        t0: args.t0,
        t_end: args.t_end,
        method: args.integrator().into(),
        rtol: args.rtol,
        atol: args.atol,
        dt: args.dt,
        times: None,
        params: named("--set", &point.set)?,
        state: named("--state", &point.state)?,
        events: (args.event.iter())
            .map(|text| event_spec(text))
            .collect::<Result<_, _>>()?,
    })
}

/// `model solve`: the file's model solved as the arguments say.
fn solved(args: &ModelSolveArgs) -> Result<Solution, ModelFileError> {
    let file = crate::model_file::read(Path::new(&args.point.model), args.point.no_cache)?;
    let model = file.model(args.point.chart.as_deref())?;
    let arguments = Arguments {
        set: &args.point.set,
        state: &args.point.state,
        event: &args.event,
    };
    solve(model, &request(args)?).map_err(|failure| arguments.solve_error(failure))
}

fn solve_file(args: &ModelSolveArgs) -> ExitCode {
    if args.no_jit {
        model_interpreted::set_evaluator(model_interpreted::Evaluator::Flat);
    }
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
    let solution = match solved(args) {
        Ok(solution) => solution,
        Err(err) if err.is_input() => return input_error(err),
        Err(err) => {
            eprintln!("error: {err}");
            return ExitCode::from(EXIT_FAILED);
        }
    };
    let mut written = write_to(&args.out, |out| write_csv(&solution, out));
    match &args.events {
        Some(path) if written.is_ok() => {
            written = write_to(path, |out| write_events_csv(&solution, out));
        }
        Some(_) => {}
        None => {
            for event in &solution.events {
                eprintln!("event `{}` at t = {}", event.label(), event.t());
            }
        }
    }
    if let Err(err) = written {
        eprintln!("error: {err}");
        return ExitCode::from(EXIT_FAILED);
    }
    for accumulation in &solution.accumulations {
        eprintln!("{accumulation}");
    }
    eprintln!("{}", summary(&solution, args.t0));
    match solution.stop {
        Stop::EndTime => ExitCode::SUCCESS,
        Stop::Event { .. } => ExitCode::from(EXIT_STOPPED),
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
fn summary(solution: &Solution, t0: f64) -> String {
    let stats = &solution.stats;
    format!(
        "`{}`: {} rows, {} events, {} at t = {}, {} steps ({} rejected), {} RHS evaluations",
        solution.model,
        solution.rows.len(),
        solution.events.len(),
        solution.stop,
        solution.t_end().unwrap_or(t0),
        stats.steps,
        stats.rejected,
        stats.rhs_evals
    )
}
