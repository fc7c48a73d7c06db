//! `eulerdisk`: see `eulerdisk --help`. With no arguments it runs the paper's scene.

use std::io::IsTerminal;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use clap::Parser;
use eulerdisk::cli::{backend, Cli, Command, EvalArgs, ModelCommand, RunArgs};
use eulerdisk::eval::{evaluate, parse_params, parse_state};
use eulerdisk::run::{run_scene, Ending, ProgressStyle, RunOptions};
use eulerdisk::scene::{self, BUILTIN};

/// Exit code of a rejected input (bad scene, bad JSON, singular state).
const EXIT_INPUT: u8 = 2;
/// Exit code of a failed run (simulation error, output not writable).
const EXIT_FAILED: u8 = 1;
/// Exit code of an interrupted run (128 + SIGINT, as shells report it).
const EXIT_INTERRUPTED: u8 = 130;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        None => run(RunArgs {
            scene: scene::DEFAULT_SCENE.to_string(),
            out: "out".into(),
            ..RunArgs::default()
        }),
        Some(Command::Run(args)) => run(args),
        Some(Command::Eval(args)) => eval(&args),
        Some(Command::Sound(args)) => eulerdisk::sound::args::command(&args),
        Some(Command::Model(ModelCommand::Show { model, format })) => {
            match eulerdisk::model_show::show(model, format) {
                Ok(text) => {
                    print!("{text}");
                    ExitCode::SUCCESS
                }
                Err(err) => {
                    eprintln!("error: {err}");
                    ExitCode::from(EXIT_FAILED)
                }
            }
        }
        Some(Command::Scenes) => {
            for (name, text) in BUILTIN {
                let description = scene::parse(name, text, &[])
                    .ok()
                    .and_then(|s| s.file.description)
                    .unwrap_or_default();
                println!("{name:<20} {description}");
            }
            ExitCode::SUCCESS
        }
    }
}

fn eval(args: &EvalArgs) -> ExitCode {
    let mode = args.mode.into();
    let result = parse_params(args.params.as_deref()).and_then(|p| {
        let y = parse_state(mode, args.state.as_deref())?;
        evaluate(backend(args.reference), mode, &p, &y)
    });
    match result {
        Ok(e) => match serde_json::to_string_pretty(&e) {
            Ok(json) => {
                println!("{json}");
                ExitCode::SUCCESS
            }
            Err(err) => {
                eprintln!("error: cannot print the result: {err}");
                ExitCode::from(EXIT_FAILED)
            }
        },
        Err(err) => {
            eprintln!("error: {err}");
            ExitCode::from(EXIT_INPUT)
        }
    }
}

fn run(args: RunArgs) -> ExitCode {
    let scene = match args.overrides().and_then(|o| scene::load(&args.scene, &o)) {
        Ok(s) => s,
        Err(err) => {
            eprintln!("error: {err}");
            return ExitCode::from(EXIT_INPUT);
        }
    };
    let interrupt = Arc::new(AtomicBool::new(false));
    {
        let flag = interrupt.clone();
        let installed = ctrlc::set_handler(move || {
            if flag.swap(true, Ordering::SeqCst) {
                // Second Ctrl-C: leave at once; complete files are already in place and
                // partial ones only ever exist under temporary names.
                std::process::exit(i32::from(EXIT_INTERRUPTED));
            }
            eprintln!("\ninterrupted: writing what is complete (Ctrl-C again to quit now)");
        });
        if let Err(err) = installed {
            eprintln!("warning: Ctrl-C will not save partial results: {err}");
        }
    }
    let progress = if args.quiet {
        ProgressStyle::Quiet
    } else if std::io::stderr().is_terminal() {
        ProgressStyle::Bar
    } else {
        ProgressStyle::Lines
    };
    let opts = RunOptions {
        out_dir: args.out.clone(),
        progress,
        backend: backend(args.reference),
        figures: !args.no_figures,
    };
    if !args.quiet {
        eprintln!(
            "scene `{}`: t_end {} s, {} rtol {:e} atol {:e}, output in {}",
            scene.name,
            scene.file.run.t_end,
            scene.file.solver.integrator.as_str(),
            scene.file.solver.rtol,
            scene.file.solver.atol,
            args.out.display()
        );
        let choice = eulerdisk::run::model::choose(&scene, opts.backend, opts.figures);
        eprintln!("model: {}: {}", choice.model.label(), choice.reason);
    }
    match run_scene(&scene, &opts, &interrupt) {
        Ok(report) => {
            if !args.quiet {
                print!("{}", report.summary.table());
                println!(
                    "wrote {} files into {}",
                    report.files.len(),
                    args.out.display()
                );
            }
            match report.ending {
                Ending::Completed => ExitCode::SUCCESS,
                Ending::Interrupted => {
                    eprintln!(
                        "interrupted at t = {} s: the files hold the run up to then",
                        report.summary.t_end
                    );
                    ExitCode::from(EXIT_INTERRUPTED)
                }
                Ending::Failed => {
                    eprintln!(
                        "the run failed at t = {} s ({}); the files hold the run up to then",
                        report.summary.t_end, report.summary.stop_reason
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
