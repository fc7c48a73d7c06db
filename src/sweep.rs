//! The `sweep` subcommand: `eulerdisk sweep SWEEP [--out DIR] [--shard i/n|auto] [--jobs N]`
//! and `eulerdisk sweep merge DIR... [--out DIR]`.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Subcommand};

use crate::args::{
    interrupt_on_ctrl_c, print_out, progress_style, FormatArg, EXIT_FAILED, EXIT_INPUT,
    EXIT_INTERRUPTED,
};
use eulerdisk::{
    load_sweep, merge, parse_sweep, plan, run_arguments, run_sweep, sweep_dir, ExecOptions,
    PointId, Shard, TableFormat, BUILTIN_SWEEPS, SWEEP_FORMAT_KEY, TABLE_STEM,
};

/// `eulerdisk sweep`.
#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct SweepArgs {
    /// `merge`, or nothing to run a sweep.
    #[command(subcommand)]
    pub command: Option<SweepCommand>,
    /// A sweep file, or the name of a built-in sweep (`speed-accuracy`, `paper-friction`).
    #[arg(required = true)]
    pub sweep: Option<String>,
    /// Output folder (a shard writes into `shard-I-of-N` inside it).
    #[arg(short, long, default_value = "out/sweep")]
    pub out: PathBuf,
    /// Run only shard `i/n` of the points (0 ≤ i < n); `auto` takes it from a Slurm job array
    /// or, as `auto/n`, from a Kubernetes Indexed Job.
    #[arg(long, value_name = "i/n|auto|auto/n")]
    pub shard: Option<String>,
    /// Runs at once (default: the number of cores).
    #[arg(short, long)]
    pub jobs: Option<usize>,
    /// Override a scene key of every point before the axes: `--set table.key=value`.
    #[arg(short, long = "set", value_name = "TABLE.KEY=VALUE")]
    pub set: Vec<String>,
    /// The format of the table and of the runs' tables: overrides `output.format` of every
    /// point.
    #[arg(short, long, value_enum)]
    pub format: Option<FormatArg>,
    /// Validate every point and list them; run nothing.
    #[arg(long)]
    pub dry_run: bool,
    /// No progress output.
    #[arg(short, long)]
    pub quiet: bool,
}

/// The subcommands of `sweep`.
#[derive(Debug, Subcommand)]
pub enum SweepCommand {
    /// Join sweep folders (shards) into one; lists missing and duplicated runs.
    Merge(MergeArgs),
    /// List the built-in sweeps.
    List,
}

/// `eulerdisk sweep merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Sweep folders, or folders holding them (`out/sweep` for its `shard-*` folders).
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// The merged folder.
    #[arg(short, long, default_value = "out/sweep")]
    pub out: PathBuf,
}

/// Runs `eulerdisk sweep ...`; returns the exit code.
pub fn command(args: &SweepArgs) -> ExitCode {
    match &args.command {
        Some(SweepCommand::Merge(m)) => merge_command(m),
        Some(SweepCommand::List) => {
            for (name, text) in BUILTIN_SWEEPS {
                let description = parse_sweep(name, text)
                    .ok()
                    .and_then(|s| s.description)
                    .unwrap_or_default();
                if let Err(code) = print_out(&format!("{name:<20} {description}\n")) {
                    return code;
                }
            }
            ExitCode::SUCCESS
        }
        None => sweep_command(args),
    }
}

fn input_error(err: impl std::fmt::Display) -> ExitCode {
    eprintln!("error: {err}");
    ExitCode::from(EXIT_INPUT)
}

fn sweep_command(args: &SweepArgs) -> ExitCode {
    let name = args.sweep.as_deref().unwrap_or_default();
    let loaded = match load_sweep(name) {
        Ok(l) => l,
        Err(e) => return input_error(e),
    };
    let shard = match args
        .shard
        .as_deref()
        .map(|s| Shard::parse(s, |k| std::env::var(k).ok()))
    {
        Some(Err(e)) => return input_error(e),
        Some(Ok(s)) => Some(s),
        None => None,
    };
    if args.jobs == Some(0) {
        return input_error("--jobs must be at least 1");
    }
    let mut sets: Vec<String> = args
        .format
        .map(|f| format!("{SWEEP_FORMAT_KEY}={}", TableFormat::from(f)))
        .into_iter()
        .collect();
    sets.extend(args.set.iter().cloned());
    let plan = match plan(&loaded, &sets) {
        Ok(p) => p,
        Err(e) => return input_error(e),
    };
    let d = &plan.definition;
    if args.dry_run {
        for (i, values) in d.points.iter().enumerate() {
            if Shard::selects(shard, i) {
                let sets = run_arguments(d, values).join(" --set ");
                let line = format!("{} run {} --set {sets}\n", PointId(i).name(), d.scene_name);
                if let Err(code) = print_out(&line) {
                    return code;
                }
            }
        }
        return ExitCode::SUCCESS;
    }
    let jobs = args
        .jobs
        .or(d.file.jobs)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let progress = progress_style(args.quiet);
    let interrupt = interrupt_on_ctrl_c(
        "finished runs are kept; running the same command again resumes the sweep",
    );
    if !args.quiet {
        eprintln!(
            "sweep `{}`: {} points{}, {jobs} worker{}, base scene `{}`, output in {}",
            d.name,
            d.points.len(),
            shard.map_or(String::new(), |s| format!(
                " (shard {}/{})",
                s.index, s.count
            )),
            if jobs == 1 { "" } else { "s" },
            d.scene_name,
            sweep_dir(&args.out, shard).display()
        );
    }
    let opts = ExecOptions {
        jobs,
        progress,
        shard,
    };
    match run_sweep(&plan, &args.out, &opts, &interrupt) {
        Ok(report) => {
            let e = report.exec;
            if !args.quiet {
                let said = format!(
                    "{} of {} runs done now ({} failed or timed out), {} already done; table in {}\n",
                    e.ran,
                    e.points,
                    e.failed,
                    e.skipped,
                    report.dir.join(d.format.file(TABLE_STEM)).display()
                );
                if let Err(code) = print_out(&said) {
                    return code;
                }
            }
            if e.interrupted {
                eprintln!(
                    "interrupted: {} runs still to do; run the same command again to resume",
                    e.points - e.ran - e.skipped
                );
                ExitCode::from(EXIT_INTERRUPTED)
            } else {
                ExitCode::SUCCESS
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(EXIT_FAILED)
        }
    }
}

fn merge_command(args: &MergeArgs) -> ExitCode {
    let report = match merge(&args.dirs, &args.out) {
        Ok((_, _, report)) => report,
        Err(e) => return input_error(e),
    };
    let mut said = format!(
        "merged {} rows of {} points from {} folders into {}\n",
        report.rows,
        report.points,
        report.inputs.len(),
        args.out.display()
    );
    if !report.missing.is_empty() {
        let names: Vec<String> = report.missing.iter().map(|p| p.name()).collect();
        said += &format!("missing ({}): {}\n", names.len(), names.join(" "));
    }
    for d in &report.duplicates {
        let dirs: Vec<String> = d.dirs.iter().map(|p| p.display().to_string()).collect();
        said += &format!(
            "duplicated: {} in {} ({})\n",
            d.point.name(),
            dirs.join(", "),
            if d.agree {
                "same numbers"
            } else {
                "DIFFERENT numbers: the first is kept"
            }
        );
    }
    if let Err(code) = print_out(&said) {
        return code;
    }
    if report.complete() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    }
}
