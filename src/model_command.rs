//! `eulerdisk model ...`: the dispatch of the model subcommands, with their exit codes.
//!
//! `show` and `eval` take a disk model's name or a DSL file; `solve` takes a file. A mistake
//! in the file, an unknown name in `--state`/`--set`, a malformed `--event` or a state where
//! the model is singular is an input error (exit 2), and so is an unusable setting of `solve`
//! (an empty time span, a sampling step or tolerance that is not positive);
//! a failed integration, a run over its work bound (`--max-steps-per-s`, as `run`'s) or an
//! unwritable output is a failure (exit 1), a run that a `:stop` event or an accumulation
//! without a rule ended before `--t-end` exits with 3, as a scene stopped by its physics
//! does, and one interrupted by Ctrl-C with 130. A run that failed or was interrupted still
//! writes what it computed, complete files whose last event row says why it stopped.

use crate::args::{
    backend, interrupt_on_ctrl_c, print_json, print_out, EXIT_FAILED, EXIT_INPUT, EXIT_INTERRUPTED,
    EXIT_STOPPED,
};
use crate::cli::{ModelCommand, ModelEvalArgs, ModelPointArgs, ModelSolveArgs};
use eulerdisk::{
    evaluate_model, model_event_spec as event_spec, model_named as named,
    model_value_error as value_error, parse_model_state, parse_params, read_model_file,
    show_disk_model, show_model_file, solution_events as events, solution_trajectory as trajectory,
    write_table_at, ModelArguments as Arguments, ModelFileError, ModelFormat as Format, ModelName,
    Table, TableFormat,
};
use model_interpreted::{
    evaluate, initial_state, params, solve_with, Control, ModelFile, ModelRef, PointValues,
    Solution, SolveFailure, SolveRequest, Stop,
};
use std::io::Write;
use std::path::Path;
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;

/// Runs one model subcommand.
pub fn run(command: &ModelCommand) -> ExitCode {
    match command {
        ModelCommand::Show {
            model,
            format,
            no_cache,
        } => show(model, (*format).into(), *no_cache),
        ModelCommand::Eval(args) => eval(args),
        ModelCommand::Solve(args) => solve_file(args),
    }
}

fn input_error(error: impl std::fmt::Display) -> ExitCode {
    eprintln!("error: {error}");
    ExitCode::from(EXIT_INPUT)
}

fn show(model: &str, format: Format, no_cache: bool) -> ExitCode {
    if let Some(name) = ModelName::from_name(model) {
        return match show_disk_model(name, format) {
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
    match show_model_file(path, format, no_cache) {
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
    let file = read_model_file(Path::new(&point.model), point.no_cache)?;
    let model = file.smooth(point.chart.as_deref())?;
    let params = params(ModelRef::Smooth(model), &named("--set", &point.set)?)
        .map_err(|e| value_error("--set", &point.set, e))?;
    let state = initial_state(ModelRef::Smooth(model), &named("--state", &point.state)?)
        .map_err(|e| value_error("--state", &point.state, e))?;
    Ok(evaluate(model, args.t, &state, &params)?)
}

fn eval(args: &ModelEvalArgs) -> ExitCode {
    if let Some(name) = ModelName::from_name(&args.point.model) {
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
        max_steps_per_s: args.max_steps_per_s,
    })
}

/// `model solve`: the file's model solved as the arguments say, until `interrupt` is set.
fn solved(args: &ModelSolveArgs, interrupt: &AtomicBool) -> Result<Solution, ModelFileError> {
    let file = read_model_file(Path::new(&args.point.model), args.point.no_cache)?;
    if let ModelFile::Switched(model) = &file {
        for warning in &model.warnings {
            eprintln!("{warning}");
        }
    }
    let model = file.model(args.point.chart.as_deref())?;
    let arguments = Arguments {
        set: &args.point.set,
        state: &args.point.state,
        event: &args.event,
    };
    let control = Control { interrupt };
    solve_with(model, &request(args)?, &control).map_err(|failure| arguments.solve_error(failure))
}

/// The flag that raises the work bound, as the failure names it.
const WORK_BOUND_FLAG: &str = "--max-steps-per-s";

fn solve_file(args: &ModelSolveArgs) -> ExitCode {
    if args.no_jit {
        model_interpreted::set_evaluator(model_interpreted::Evaluator::Flat);
    }
    if args.method.is_some() {
        eprintln!("note: `--method` is deprecated: write `--integrator`");
    }
    if ModelName::from_name(&args.point.model).is_some() && !Path::new(&args.point.model).exists() {
        return input_error(format_args!(
            "`model solve` takes a DSL file; to simulate the disk's `{}` model, run a scene (`eulerdisk run`, `[modes] allowed`)",
            args.point.model
        ));
    }
    let format = TableFormat::from(args.format);
    if format == TableFormat::Parquet {
        let to_stdout =
            args.out.as_os_str() == "-" || args.events.as_deref() == Some(Path::new("-"));
        if to_stdout {
            return input_error(
                "-f parquet: Parquet is written to files only: give `--out FILE` (and `--events FILE`)",
            );
        }
    }
    let interrupt = interrupt_on_ctrl_c("writing what is complete");
    // A failed run keeps what it computed: its files are written, then the failure said.
    let (solution, failure) = match solved(args, &interrupt) {
        Ok(solution) => (solution, None),
        Err(ModelFileError::Failed(SolveFailure::Run(mut failure)))
            if failure.partial.is_some() =>
        {
            let partial = failure.partial.take().map(|partial| *partial);
            let message = failure.describe(WORK_BOUND_FLAG);
            match partial {
                Some(partial) => (partial, Some(message)),
                None => return ExitCode::from(EXIT_FAILED),
            }
        }
        Err(err) if err.is_input() => return input_error(err),
        Err(err) => {
            eprintln!("error: {err}");
            return ExitCode::from(EXIT_FAILED);
        }
    };
    let mut written = write_to(&args.out, format, &trajectory(&solution));
    match &args.events {
        Some(path) if written.is_ok() => {
            written = write_to(path, format, &events(&solution, failure.as_deref()));
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
    for warning in &solution.warnings {
        eprintln!("warning: {warning}");
    }
    for accumulation in &solution.accumulations {
        eprintln!("{accumulation}");
    }
    eprintln!("{}", summary(&solution, args.t0));
    if let Some(message) = failure {
        eprintln!("error: {message}");
        return ExitCode::from(EXIT_FAILED);
    }
    match solution.stop {
        Stop::EndTime => ExitCode::SUCCESS,
        Stop::Event { .. } => ExitCode::from(EXIT_STOPPED),
        Stop::Interrupted => ExitCode::from(EXIT_INTERRUPTED),
        Stop::Failed { .. } => ExitCode::from(EXIT_FAILED),
    }
}

/// Writes `table` in `format` to the file `path` (`-`: standard output, as CSV), a file
/// atomically (complete or not there); an error names the path.
fn write_to(path: &Path, format: TableFormat, table: &Table) -> Result<(), String> {
    if path.as_os_str() == "-" {
        let mut lock = std::io::stdout().lock();
        return (table.write_csv(&mut lock).and_then(|()| lock.flush()))
            .map_err(|err| format!("cannot write to standard output: {err}"));
    }
    write_table_at(table, path, format).map_err(|err| err.to_string())
}

/// One line on the run: rows, events, why and when it ended (a run stopped by an event, at
/// the event's time), the work done.
fn summary(solution: &Solution, t0: f64) -> String {
    let stats = &solution.stats;
    format!(
        "`{}`: {} rows, {} events, {} at t = {}, {} steps ({} rejected), {} RHS evaluations",
        solution.model,
        solution.len(),
        solution.events.len(),
        solution.stop,
        solution.stop_time().unwrap_or(t0),
        stats.steps,
        stats.rejected,
        stats.rhs_evals
    )
}
