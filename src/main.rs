//! `eulerdisk`: see `eulerdisk --help`. With no arguments it runs the paper's scene.
//!
//! The command line over the library `eulerdisk` (the `pipeline/` package): this program
//! keeps the flags (`cli`, `args`, and the `sound`, `sweep` and `model` subcommands'
//! arguments), the terminal (progress bars, `terminal`), Ctrl-C and the exit codes; the
//! library runs the scenes and writes the files.

mod args;
mod cli;
mod model_command;
mod sound;
mod sweep;
mod terminal;

use std::process::ExitCode;

use args::{
    backend, engine, interrupt_on_ctrl_c, print_json, print_out, progress_style, RunArgs,
    EXIT_FAILED, EXIT_INPUT, EXIT_INTERRUPTED, EXIT_STOPPED,
};
use clap::Parser;
use cli::{Cli, Command, EvalArgs};
use equations::record::StopKind;
use eulerdisk::{
    evaluate, is_json_object, load_scene, parse_params, parse_scene, parse_state, run_scene,
    Ending, Provenance, RunOptions, BUILTIN_SCENES, DEFAULT_SCENE,
};
use model_runtime::Readable;

fn main() -> ExitCode {
    #[cfg(feature = "parquet")]
    eulerdisk_parquet::install();
    let cli = Cli::parse();
    match cli.command {
        None => run(RunArgs {
            scene: DEFAULT_SCENE.to_string(),
            ..RunArgs::default()
        }),
        Some(Command::Run(args)) => run(args),
        Some(Command::Eval(args)) => eval(&args),
        Some(Command::Sound(args)) => sound::command(&args),
        Some(Command::Sweep(args)) => sweep::command(&args),
        Some(Command::Model(command)) => model_command::run(&command),
        Some(Command::Scenes) => {
            for (name, text) in BUILTIN_SCENES {
                let description = parse_scene(name, text, &[])
                    .ok()
                    .and_then(|s| s.file.cli.description)
                    .unwrap_or_default();
                if let Err(code) = print_out(&format!("{name:<20} {description}\n")) {
                    return code;
                }
            }
            ExitCode::SUCCESS
        }
    }
}

fn eval(args: &EvalArgs) -> ExitCode {
    let mode = args.mode.into();
    if args.state.iter().any(|item| is_json_object(item)) {
        eprintln!("note: `--state` as a JSON object is deprecated: write `--state NAME=VALUE` (repeatable)");
    }
    let mut set = args.set.clone();
    if let Some(params) = &args.params {
        eprintln!("note: `--params` is deprecated: write `--set NAME=VALUE` (repeatable)");
        set.push(params.clone());
    }
    let result = parse_params("--set", &set).and_then(|p| {
        let y = parse_state(mode, &args.state)?;
        evaluate(backend(args.reference), mode, &p, &y)
    });
    match result {
        Ok(e) => print_json(&e),
        Err(err) => {
            eprintln!("error: {err}");
            ExitCode::from(EXIT_INPUT)
        }
    }
}

fn run(args: RunArgs) -> ExitCode {
    let loaded = args.overrides().and_then(|o| {
        let scene = load_scene(&args.scene, &o)?;
        Ok((scene, o))
    });
    let (scene, overrides) = match loaded {
        Ok(s) => s,
        Err(err) => {
            eprintln!("error: {err}");
            return ExitCode::from(EXIT_INPUT);
        }
    };
    let interrupt = interrupt_on_ctrl_c("writing what is complete");
    let progress = progress_style(args.quiet);
    let out = args.out_dir("out");
    let opts = RunOptions {
        out_dir: out.clone(),
        progress,
        backend: backend(args.reference),
        engine: engine(args.engine),
        figures: !args.no_figures,
        trajectory: true,
        provenance: Provenance::new(&scene, &args.scene, &overrides),
    };
    if !args.quiet {
        eprintln!(
            "scene `{}`: t_end {} s, {} rtol {} atol {}, output in {}",
            scene.name,
            Readable(scene.file.settings.run.t_end),
            scene.config.integrator.name(),
            Readable(scene.file.settings.solver.rtol),
            Readable(scene.file.settings.solver.atol),
            out.display()
        );
        let choice = eulerdisk::choose(&scene, opts.backend, opts.figures);
        eprintln!("model: {}: {}", choice.model.label(), choice.reason);
    }
    match run_scene(&scene, &opts, &interrupt) {
        Ok(report) => {
            if !args.quiet {
                let said = format!(
                    "{}wrote {} files into {}\n",
                    report.summary.table(),
                    report.files.len(),
                    out.display()
                );
                if let Err(code) = print_out(&said) {
                    return code;
                }
            }
            let s = &report.summary;
            match report.ending {
                Ending::Completed if s.stop_reason != Some(StopKind::EndTime) => {
                    eprintln!(
                        "stopped early at t = {} s of {} s ({}): {}",
                        Readable(s.t_end),
                        Readable(scene.file.settings.run.t_end),
                        stop_word(s.stop_reason),
                        s.stop_detail
                    );
                    ExitCode::from(EXIT_STOPPED)
                }
                Ending::Completed => ExitCode::SUCCESS,
                Ending::Interrupted if !s.figures_not_drawn.is_empty() => {
                    eprintln!(
                        "interrupted while drawing the figures: {} of them not drawn (listed \
                         in summary.json); the run and its data files are complete",
                        s.figures_not_drawn.len()
                    );
                    ExitCode::from(EXIT_INTERRUPTED)
                }
                Ending::Interrupted => {
                    eprintln!(
                        "interrupted at t = {} s: the files hold the run up to then",
                        Readable(s.t_end)
                    );
                    ExitCode::from(EXIT_INTERRUPTED)
                }
                Ending::Failed => {
                    eprintln!(
                        "the run failed at t = {} s ({}): {}\nthe files hold the run up to then",
                        Readable(s.t_end),
                        stop_word(s.stop_reason),
                        s.stop_detail
                    );
                    ExitCode::from(EXIT_FAILED)
                }
            }
        }
        Err(err) => {
            eprintln!("error: {err}");
            ExitCode::from(EXIT_FAILED)
        }
    }
}

/// A run's stop as its word (`-` for a run without one).
fn stop_word(kind: Option<StopKind>) -> &'static str {
    kind.map_or("-", StopKind::name)
}
