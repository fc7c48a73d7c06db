//! `eulerdisk`: see `eulerdisk --help`. With no arguments it runs the paper's scene.

use std::process::ExitCode;

use clap::Parser;
use eulerdisk::{
    backend, evaluate, interrupt_on_ctrl_c, load_scene, parse_params, parse_scene, parse_state,
    print_json, print_out, progress_style, run_scene, Cli, Command, Ending, EvalArgs, Provenance,
    RunArgs, RunOptions, BUILTIN_SCENES, DEFAULT_SCENE, EXIT_FAILED, EXIT_INPUT, EXIT_INTERRUPTED,
};

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        None => run(RunArgs {
            scene: DEFAULT_SCENE.to_string(),
            out: "out".into(),
            ..RunArgs::default()
        }),
        Some(Command::Run(args)) => run(args),
        Some(Command::Eval(args)) => eval(&args),
        Some(Command::Sound(args)) => eulerdisk::sound_command(&args),
        Some(Command::Sweep(args)) => eulerdisk::sweep_command(&args),
        Some(Command::Model(command)) => eulerdisk::model_command(&command),
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
    let result = parse_params(args.params.as_deref()).and_then(|p| {
        let y = parse_state(mode, args.state.as_deref())?;
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
    let opts = RunOptions {
        out_dir: args.out.clone(),
        progress,
        backend: backend(args.reference),
        figures: !args.no_figures,
        trajectory: true,
        provenance: Provenance::new(&scene, &args.scene, &overrides),
    };
    if !args.quiet {
        eprintln!(
            "scene `{}`: t_end {} s, {} rtol {:e} atol {:e}, output in {}",
            scene.name,
            scene.file.settings.run.t_end,
            scene.config.integrator.name(),
            scene.file.settings.solver.rtol,
            scene.file.settings.solver.atol,
            args.out.display()
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
                    args.out.display()
                );
                if let Err(code) = print_out(&said) {
                    return code;
                }
            }
            let s = &report.summary;
            match report.ending {
                Ending::Completed => {
                    if s.stop_reason != "end_time" {
                        eprintln!(
                            "stopped early at t = {} s of {} s ({}): {}",
                            s.t_end, scene.file.settings.run.t_end, s.stop_reason, s.stop_detail
                        );
                    }
                    ExitCode::SUCCESS
                }
                Ending::Interrupted => {
                    eprintln!(
                        "interrupted at t = {} s: the files hold the run up to then",
                        s.t_end
                    );
                    ExitCode::from(EXIT_INTERRUPTED)
                }
                Ending::Failed => {
                    eprintln!(
                        "the run failed at t = {} s ({}): {}\nthe files hold the run up to then",
                        s.t_end, s.stop_reason, s.stop_detail
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
