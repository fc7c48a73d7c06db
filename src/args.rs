//! What every subcommand's arguments share: the exit codes, the arguments of a run, the
//! integrators, the tables' format, the progress style, the Ctrl-C handler, the choice of
//! models.
//!
//! One vocabulary for every subcommand: `--state NAME=VALUE` and `--set KEY=VALUE`
//! (repeatable), `--integrator`, `--rtol`, `--atol`, `--t-end`, `-o/--out`, `-q/--quiet`,
//! `-s` for `--set`, `-j/--jobs`, `-f/--format` (of what a command writes: its tables, or the
//! equations `model show` prints). The exit codes:
//!
//! | code | meaning |
//! |---|---|
//! | 0 | ran to the end |
//! | 1 | failed (a simulation error, an output that cannot be written, an incomplete merge) |
//! | 2 | bad input (a scene, sweep or model file, a flag's value); nothing was run |
//! | 3 | stopped early by the physics (contact lost, lying flat, a `:stop` event, ...) |
//! | 130 | interrupted (Ctrl-C) |
//!
//! Kept apart from the parser (`cli.rs`), which names every subcommand's arguments, so that a
//! subcommand's own argument module (`sound/args.rs`, `sweep/args.rs`) can use these without
//! depending on the parser that depends on it.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use clap::{Args, ValueEnum};

use eulerdisk::{
    Backend, EngineChoice, Override, ProgressStyle, SceneError, TableFormat, DEFAULT_BACKEND,
    DEFAULT_ENGINE, DEFAULT_SCENE,
};

use crate::terminal::TERMINAL_BARS;

/// Exit code of a rejected input (bad scene, bad sweep file, bad JSON, singular state).
pub const EXIT_INPUT: u8 = 2;
/// Exit code of a failed run (simulation error, output not writable, incomplete merge).
pub const EXIT_FAILED: u8 = 1;
/// Exit code of a run that stopped before its end time at a condition of the physics (contact
/// lost, the disk lying flat, a mode that is not allowed, chattering, a `:stop` event): the
/// files hold the run up to there.
pub const EXIT_STOPPED: u8 = 3;
/// Exit code of an interrupted run (128 + SIGINT, as shells report it).
pub const EXIT_INTERRUPTED: u8 = 130;

/// Writes `text` to standard output. A full or closed standard output is a failure said on
/// standard error, `Err` with exit code 1 for the command to return (`println!` would panic).
/// The one way commands print their answers.
pub fn print_out(text: &str) -> Result<(), std::process::ExitCode> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|err| {
            eprintln!("error: cannot write to standard output: {err}");
            std::process::ExitCode::from(EXIT_FAILED)
        })
}

/// Prints `value` as pretty JSON on standard output: success, or a failure naming why it could
/// not be printed. The one way `eval` and `model eval` answer.
pub fn print_json<T: serde::Serialize>(value: &T) -> std::process::ExitCode {
    match serde_json::to_string_pretty(value) {
        Ok(json) => match print_out(&format!("{json}\n")) {
            Ok(()) => std::process::ExitCode::SUCCESS,
            Err(code) => code,
        },
        Err(err) => {
            eprintln!("error: cannot print the result: {err}");
            std::process::ExitCode::from(EXIT_FAILED)
        }
    }
}

/// An integrator, by the name scenes give it in `solver.integrator` (the command line offers
/// the adaptive ones; fixed-step RK4 is for programs only).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum IntegratorName {
    /// Dormand–Prince 5(4).
    Dopri5,
    /// Dormand–Prince 8(5,3).
    Dop853,
    /// Rosenbrock 4(3), with the model's symbolic Jacobian (stiff models).
    Rodas4,
}

impl IntegratorName {
    /// The name as scenes write it.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorName::Dopri5 => "dopri5",
            IntegratorName::Dop853 => "dop853",
            IntegratorName::Rodas4 => "rodas4",
        }
    }
}

impl From<IntegratorName> for model_runtime::Method {
    fn from(method: IntegratorName) -> Self {
        match method {
            IntegratorName::Dopri5 => model_runtime::Method::Dopri5,
            IntegratorName::Dop853 => model_runtime::Method::Dop853,
            IntegratorName::Rodas4 => model_runtime::Method::Rodas4,
        }
    }
}

/// The format of the tables, as `-f/--format` takes it (the library's [`TableFormat`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FormatArg {
    /// Comma-separated text, numbers that parse back to the same bits.
    Csv,
    /// Apache Parquet: typed columns, Snappy-compressed.
    Parquet,
}

impl From<FormatArg> for TableFormat {
    fn from(format: FormatArg) -> TableFormat {
        match format {
            FormatArg::Csv => TableFormat::Csv,
            FormatArg::Parquet => TableFormat::Parquet,
        }
    }
}

/// The engine, as `--engine` takes it (the library's [`EngineChoice`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum EngineArg {
    /// The DSL's mode graph, where it models the scene (still air, `slip_sign = "physical"`,
    /// dop853 or dopri5, the full models); the hand-written system elsewhere.
    Graph,
    /// The hand-written hybrid system, the graph's reference.
    HandWritten,
}

impl From<EngineArg> for EngineChoice {
    fn from(engine: EngineArg) -> EngineChoice {
        match engine {
            EngineArg::Graph => EngineChoice::ModeGraph,
            EngineArg::HandWritten => EngineChoice::HandWritten,
        }
    }
}

/// `eulerdisk run`.
#[derive(Debug, Args, Default)]
pub struct RunArgs {
    /// A scene file, or the name of a built-in scene.
    #[arg(default_value = DEFAULT_SCENE)]
    pub scene: String,
    /// Override `run.t_end` (s).
    #[arg(long, allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// Override `solver.rtol`.
    #[arg(long, allow_negative_numbers = true)]
    pub rtol: Option<f64>,
    /// Override `solver.atol`.
    #[arg(long, allow_negative_numbers = true)]
    pub atol: Option<f64>,
    /// Override `solver.integrator`.
    #[arg(long, value_enum)]
    pub integrator: Option<IntegratorName>,
    /// Output directory (default: `out` for `run`, `out/sound` for `sound`).
    #[arg(short, long)]
    pub out: Option<PathBuf>,
    /// Print nothing but errors and why a run stopped early: no progress, no scene line, no
    /// summary table (summary.json is still written).
    #[arg(short, long)]
    pub quiet: bool,
    /// Override any scene key: `--set table.key=value` (repeatable).
    #[arg(short, long = "set", value_name = "TABLE.KEY=VALUE")]
    pub set: Vec<String>,
    /// The format of the tables (trajectory, events, extrema, peaks): overrides
    /// `output.format`.
    #[arg(short, long, value_enum)]
    pub format: Option<FormatArg>,
    /// Run the hand-written reference models instead of the generated ones.
    #[arg(long)]
    pub reference: bool,
    /// The engine that runs the disk: the DSL's mode graph (the default, where it models the
    /// scene) or the hand-written hybrid system it is held to. `summary.json` names the
    /// engine that ran.
    #[arg(long, value_enum)]
    pub engine: Option<EngineArg>,
    /// Skip the figures.
    #[arg(long)]
    pub no_figures: bool,
}

impl RunArgs {
    /// The output directory: `--out`, else the command's own default.
    pub fn out_dir(&self, default: &str) -> PathBuf {
        self.out.clone().unwrap_or_else(|| PathBuf::from(default))
    }

    /// The scene overrides these arguments ask for, in order (`--set` last, so it wins).
    pub fn overrides(&self) -> Result<Vec<Override>, SceneError> {
        let mut out = Vec::new();
        if let Some(v) = self.t_end {
            out.push(Override::new("run", "t_end", v));
        }
        if let Some(v) = self.rtol {
            out.push(Override::new("solver", "rtol", v));
        }
        if let Some(v) = self.atol {
            out.push(Override::new("solver", "atol", v));
        }
        if let Some(v) = self.integrator {
            out.push(Override::new("solver", "integrator", v.name()));
        }
        if let Some(v) = self.format {
            out.push(Override::new(
                "output",
                "format",
                TableFormat::from(v).name(),
            ));
        }
        for spec in &self.set {
            out.push(Override::parse(spec)?);
        }
        Ok(out)
    }
}

/// How a command reports progress: nothing when `quiet`, a bar on a terminal, lines otherwise
/// (the library's lines; the bar is this program's, [`TERMINAL_BARS`]).
pub fn progress_style(quiet: bool) -> ProgressStyle {
    if quiet {
        ProgressStyle::Quiet
    } else if std::io::stderr().is_terminal() {
        ProgressStyle::Bar(&TERMINAL_BARS)
    } else {
        ProgressStyle::Lines
    }
}

/// Installs the Ctrl-C handler of a long command: the first Ctrl-C sets the returned flag and
/// prints `message` (what happens now); a second one exits at once with
/// [`EXIT_INTERRUPTED`] (complete files are already in place, partial ones only ever exist
/// under temporary names).
pub fn interrupt_on_ctrl_c(message: &'static str) -> Arc<AtomicBool> {
    let interrupt = Arc::new(AtomicBool::new(false));
    let flag = interrupt.clone();
    let installed = ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            std::process::exit(i32::from(EXIT_INTERRUPTED));
        }
        eprintln!("\ninterrupted: {message} (Ctrl-C again to quit now)");
    });
    if let Err(err) = installed {
        eprintln!("warning: Ctrl-C will not save partial results: {err}");
    }
    interrupt
}

/// The backend a `--reference` flag selects.
pub fn backend(reference: bool) -> Backend {
    if reference {
        Backend::Reference
    } else {
        DEFAULT_BACKEND
    }
}

/// The engine an `--engine` flag selects (the library's default without one).
pub fn engine(asked: Option<EngineArg>) -> EngineChoice {
    asked.map_or(DEFAULT_ENGINE, EngineChoice::from)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_format_flag_offers_every_format_of_the_library() {
        for format in TableFormat::ALL {
            let flag = FormatArg::from_str(format.name(), false).unwrap();
            assert_eq!(TableFormat::from(flag), format);
        }
        assert_eq!(FormatArg::value_variants().len(), TableFormat::ALL.len());
    }
}
