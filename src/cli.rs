//! The command line: `eulerdisk [run [SCENE]] | eval | scenes | sound | sweep`.
//!
//! Flags map onto scene keys (`--rtol` is `--set solver.rtol=...`) so every value from the
//! command line passes the same validation as the scene file.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::eval::Backend;
use crate::run::ProgressStyle;
use crate::scene::{Override, SceneError, DEFAULT_SCENE};
use equations::Mode;

/// Euler's disk rolling and sliding on a rough plane (Saje & Zupan's model).
#[derive(Debug, Parser)]
#[command(name = "eulerdisk", version, about)]
pub struct Cli {
    /// What to do (default: run the default scene).
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Simulate a scene and write trajectory, events, the paper's figures and a summary.
    Run(RunArgs),
    /// Evaluate the equations of one mode at one state and print JSON.
    Eval(EvalArgs),
    /// List the built-in scenes.
    Scenes,
    /// Simulate a scene and hear its rattle: a WAV of the normal-force peaks, their rate
    /// against the paper's, and a spectrogram.
    Sound(crate::sound::args::SoundArgs),
    /// Run many scenes at once: axes over any scene key, a table of their summaries, figures;
    /// resumable, and shardable over a cluster's job array (`sweep merge` joins the shards).
    Sweep(crate::sweep::args::SweepArgs),
    /// Print a model's equations as the compiler solved them (`model show rolling`).
    #[command(subcommand)]
    Model(ModelCommand),
}

/// `eulerdisk model ...`.
#[derive(Debug, Subcommand)]
pub enum ModelCommand {
    /// The solved explicit equations block by block, their pivots and the outputs (Markdown,
    /// or LaTeX with `--format latex`); for `rolling` also N/mg at the paper's start beside
    /// the paper's formula (13).
    Show {
        /// The model.
        #[arg(value_enum)]
        model: crate::model_show::ModelName,
        /// Markdown (DSL syntax) or LaTeX.
        #[arg(long, value_enum, default_value = "markdown")]
        format: crate::model_show::Format,
    },
}

/// Exit code of a rejected input (bad scene, bad sweep file, bad JSON, singular state).
pub const EXIT_INPUT: u8 = 2;
/// Exit code of a failed run (simulation error, output not writable, incomplete merge).
pub const EXIT_FAILED: u8 = 1;
/// Exit code of an interrupted run (128 + SIGINT, as shells report it).
pub const EXIT_INTERRUPTED: u8 = 130;

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
    /// Override `solver.integrator` (dopri5, dop853, rodas4).
    #[arg(long)]
    pub integrator: Option<String>,
    /// Output directory.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Print nothing but errors and why a run stopped early: no progress, no scene line, no
    /// summary table (summary.json is still written).
    #[arg(long)]
    pub quiet: bool,
    /// Override any scene key: `--set table.key=value` (repeatable).
    #[arg(long = "set", value_name = "TABLE.KEY=VALUE")]
    pub set: Vec<String>,
    /// Run the hand-written reference models instead of the generated ones.
    #[arg(long)]
    pub reference: bool,
    /// Skip the figures.
    #[arg(long)]
    pub no_figures: bool,
}

impl RunArgs {
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
        if let Some(v) = &self.integrator {
            out.push(Override::new("solver", "integrator", v.as_str()));
        }
        for spec in &self.set {
            out.push(Override::parse(spec)?);
        }
        Ok(out)
    }
}

/// A mode on the command line.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum ModeArg {
    /// The contact particle at rest.
    Rolling,
    /// The contact particle slipping (polar slip: v_C, alpha).
    Sliding,
}

impl From<ModeArg> for Mode {
    fn from(m: ModeArg) -> Mode {
        match m {
            ModeArg::Rolling => Mode::Rolling,
            ModeArg::Sliding => Mode::Sliding,
        }
    }
}

/// `eulerdisk eval`.
#[derive(Debug, Args)]
pub struct EvalArgs {
    /// The mode whose equations are evaluated.
    #[arg(long, value_enum)]
    pub mode: ModeArg,
    /// Use the hand-written reference instead of the generated models.
    #[arg(long)]
    pub reference: bool,
    /// The state as a JSON object by the paper's names (missing entries are 0).
    #[arg(long)]
    pub state: Option<String>,
    /// Parameters as a JSON object (m, a, g, mu_d, mu_st, mu_a, w_z; missing: the paper's).
    #[arg(long)]
    pub params: Option<String>,
}

/// How a command reports progress: nothing when `quiet`, a bar on a terminal, lines otherwise.
pub fn progress_style(quiet: bool) -> ProgressStyle {
    if quiet {
        ProgressStyle::Quiet
    } else if std::io::stderr().is_terminal() {
        ProgressStyle::Bar
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

/// The models the CLI runs unless `--reference` is given: the one line to switch.
pub const DEFAULT_BACKEND: Backend = Backend::Generated;

/// The backend a `--reference` flag selects.
pub fn backend(reference: bool) -> Backend {
    if reference {
        Backend::Reference
    } else {
        DEFAULT_BACKEND
    }
}
